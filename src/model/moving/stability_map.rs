//! Stability maps: the verdict at every point of a grid in two parameters (e.g. (v̄, p) or
//! (v̄, k̄_p)), parallel over points and deterministic.
//!
//! Each point assembles its system from the model's precomputed operators (O(n²)), solves the
//! quadratic eigenproblem with `Par::Seq` (O(n³), the cost), and classifies the eigenvalues
//! (`stability.rs`). When one axis is the friction (μh̄ or p) the friction matrix is rank one along
//! it, and every line of the map along that axis shares one Hessenberg reduction
//! (`solve::small_eigenvalues::RankOneLine`): a point then costs only the Francis QR iteration.
//! Rows (or lines) are handed to worker threads (`std::thread::scope`) from an atomic counter;
//! every point's result depends only on its own parameters (and its line's) and lands at its own
//! index, so the map is bit-identical for any thread count.

use std::sync::atomic::{AtomicUsize, Ordering};

use faer::{c64, Mat};
use serde::Serialize;

use crate::error::{Error, InputError, SolveError};
use crate::model::moving::linearized::{assess_point, LinearizedModel};
pub use crate::model::moving::linearized::{describe, AxisParameter};
use crate::model::moving::stability::{
    assess, assess_resolved, StabilityAssessment, Verdict, VerdictParams,
};
use crate::model::moving::string_data::{MovingStringData, StringParameter};
use crate::model::moving::string_model::MovingStringModel;
use crate::model::moving::system::MovingSystem;
use crate::solve::quadratic_eigen::{EigenKernel, QuadraticEigenParams, QuadraticEigenSolver};

/// The values of one parameter along one axis of a map or sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridAxis<P = StringParameter> {
    pub parameter: P,
    pub values: Vec<f64>,
}

impl<P: AxisParameter> GridAxis<P> {
    /// `points` equally spaced values from `from` to `to` (both included; `points` ≥ 2).
    pub fn linspace(parameter: P, from: f64, to: f64, points: usize) -> Result<Self, InputError> {
        let field = format!("axis.{}", parameter.key());
        if points < 2 {
            return Err(InputError::new(
                format!("{field}.points"),
                points,
                "at least 2 points",
            ));
        }
        if !(from.is_finite() && to.is_finite() && from != to) {
            return Err(InputError::new(
                format!("{field}.to"),
                to,
                format!("a finite number other than from = {from}"),
            ));
        }
        let values = (0..points)
            .map(|i| from + (to - from) * i as f64 / (points - 1) as f64)
            .collect();
        Ok(Self { parameter, values })
    }
}

/// Options of a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityMapParams {
    /// Worker threads (0: all available cores). The result does not depend on it.
    pub threads: usize,
    pub verdict: VerdictParams,
    /// The eigensolver; by default the eigenvalue-only kernel `EigenKernel::SmallDense`
    /// (verified point by point against faer in the case `moving_map`).
    pub eigen: QuadraticEigenParams,
}

impl StabilityMapParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), Error> {
        self.verdict.validate()?;
        self.eigen
            .validate()
            .map_err(|source| SolveError::Eigenproblem {
                at: "the map's parameters".into(),
                source,
            })?;
        if self.threads > 4096 {
            return Err(InputError::new("map.threads", self.threads, "0 to 4096").into());
        }
        Ok(())
    }
}

impl Default for StabilityMapParams {
    fn default() -> Self {
        Self {
            threads: 0,
            verdict: VerdictParams::default(),
            eigen: QuadraticEigenParams {
                kernel: EigenKernel::SmallDense,
                ..QuadraticEigenParams::default()
            },
        }
    }
}

/// The verdicts on a grid: each read from the eigenvalues below the model's resolution limit
/// (`resolution.rs`), with the unstable ones above it reported as the point's warning.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StabilityMap<P = StringParameter> {
    pub x: GridAxis<P>,
    pub y: GridAxis<P>,
    /// Row-major: point (ix, iy) at `iy * nx + ix`.
    pub points: Vec<StabilityAssessment>,
    /// The threads that ran (for the record; not part of the result).
    #[serde(skip)]
    pub threads_used: usize,
}

impl<P> StabilityMap<P> {
    /// The assessment at (ix, iy).
    pub fn at(&self, ix: usize, iy: usize) -> Option<&StabilityAssessment> {
        (ix < self.x.values.len())
            .then(|| self.points.get(iy * self.x.values.len() + ix))
            .flatten()
    }

    /// The number of points with `verdict`.
    pub fn count(&self, verdict: Verdict) -> usize {
        self.points.iter().filter(|p| p.verdict == verdict).count()
    }

    /// The number of points with a discretization warning (unstable eigenvalues above the
    /// resolution limit).
    pub fn count_unresolved(&self) -> usize {
        self.points
            .iter()
            .filter(|p| p.unresolved.is_present())
            .count()
    }
}

/// The number of threads for `threads` (0: all cores), at most `work` and at least 1.
pub fn resolve_threads(threads: usize, work: usize) -> usize {
    let t = if threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        threads
    };
    t.clamp(1, work.max(1))
}

/// Evaluates `row(iy, workspace)` for every row 0..rows on `threads` threads and returns the
/// rows in order (deterministic whatever the scheduling). Each thread owns a workspace made by
/// `workspace()`. The first error (in row order) wins.
pub fn parallel_rows<T, W, E, Fw, Fr>(
    rows: usize,
    threads: usize,
    workspace: Fw,
    row: Fr,
) -> Result<(Vec<T>, usize), E>
where
    T: Send,
    E: Send + From<crate::error::SolveError>,
    Fw: Fn() -> W + Sync,
    Fr: Fn(usize, &mut W) -> Result<T, E> + Sync,
{
    let threads = resolve_threads(threads, rows);
    let next = AtomicUsize::new(0);
    let mut done: Vec<(usize, Result<T, E>)> = Vec::with_capacity(rows);
    // the caller's own time limit holds in the workers too
    let deadline = crate::run_control::current_deadline();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    crate::run_control::with_deadline(deadline.clone(), || {
                        let mut ws = workspace();
                        let mut mine = Vec::new();
                        loop {
                            let iy = next.fetch_add(1, Ordering::Relaxed);
                            if iy >= rows {
                                break;
                            }
                            crate::run_control::report_progress(
                                "grid rows",
                                iy as u64,
                                rows as u64,
                            );
                            if let Err(e) = crate::run_control::check(|| {
                                format!("row {} of {rows} of the parameter grid", iy + 1)
                            }) {
                                mine.push((iy, Err(e.into())));
                                break;
                            }
                            let r = row(iy, &mut ws);
                            let failed = r.is_err();
                            mine.push((iy, r));
                            if failed {
                                break;
                            }
                        }
                        mine
                    })
                })
            })
            .collect();
        for h in handles {
            match h.join() {
                Ok(mine) => done.extend(mine),
                Err(payload) => std::panic::resume_unwind(payload),
            }
        }
    });
    done.sort_by_key(|(i, _)| *i);
    let mut out = Vec::with_capacity(rows);
    for (_, r) in done {
        out.push(r?);
    }
    Ok((out, threads))
}

/// A worker's buffers: the system, C and K, and the eigensolver with its factored mass matrix
/// (refactored only when the model's mass key changes).
pub struct EigenWorkspace {
    system: MovingSystem,
    c: Mat<f64>,
    k: Mat<f64>,
    solver: Option<(f64, QuadraticEigenSolver)>,
    eigenvalues: Vec<c64>,
}

impl EigenWorkspace {
    /// Buffers for `model` with data shaped like `data`.
    pub fn new<Mo: LinearizedModel>(model: &Mo, data: &Mo::Data) -> Self {
        let coords = model.coordinates(data);
        let n = coords.len();
        Self {
            system: MovingSystem::zeros(coords),
            c: Mat::zeros(n, n),
            k: Mat::zeros(n, n),
            solver: None,
            eigenvalues: Vec::with_capacity(2 * n),
        }
    }

    /// Assembles and solves the system for `data`; returns its eigenvalues.
    pub fn eigenvalues<Mo: LinearizedModel>(
        &mut self,
        model: &Mo,
        data: &Mo::Data,
        eigen: QuadraticEigenParams,
    ) -> Result<&[c64], Error> {
        model.assemble_into(data, &mut self.system)?;
        self.system.velocity_matrix_into(&mut self.c);
        self.system.stiffness_matrix_into(&mut self.k);
        let mass_key = model.mass_key(data);
        let at = || model.describe(data);
        let rebuild = !matches!(&self.solver, Some((m, _)) if *m == mass_key);
        if rebuild {
            let solver = QuadraticEigenSolver::new(self.system.mass.as_ref(), eigen)
                .map_err(|source| SolveError::Eigenproblem { at: at(), source })?;
            self.solver = Some((mass_key, solver));
        }
        let Some((_, solver)) = self.solver.as_mut() else {
            unreachable!("the solver was just built")
        };
        solver
            .eigenvalues_into(self.c.as_ref(), self.k.as_ref(), &mut self.eigenvalues)
            .map_err(|source| SolveError::Eigenproblem { at: at(), source })?;
        Ok(&self.eigenvalues)
    }
}

/// The stability map of the string model over the grid x × y, every other parameter from `base`.
pub fn string_stability_map(
    model: &MovingStringModel,
    base: &MovingStringData,
    x: &GridAxis,
    y: &GridAxis,
    params: &StabilityMapParams,
) -> Result<StabilityMap, Error> {
    stability_map(model, base, x, y, params)
}

/// The stability map of any linearized model over the grid x × y, every other parameter from
/// `base`: point by point, or line by line when one axis is a rank-one parameter ([`line_map`]).
pub fn stability_map<Mo: LinearizedModel>(
    model: &Mo,
    base: &Mo::Data,
    x: &GridAxis<Mo::Parameter>,
    y: &GridAxis<Mo::Parameter>,
    params: &StabilityMapParams,
) -> Result<StabilityMap<Mo::Parameter>, Error> {
    params.validate()?;
    model.validate_data(base)?;
    if x.parameter == y.parameter {
        return Err(InputError::new(
            "map.y.parameter",
            y.parameter.key(),
            format!("a parameter other than x = {}", x.parameter.key()),
        )
        .into());
    }
    if let Some(map) = line_map(model, base, x, y, params)? {
        return Ok(map);
    }
    let nx = x.values.len();
    let (rows, threads) = parallel_rows(
        y.values.len(),
        params.threads,
        || EigenWorkspace::new(model, base),
        |iy, ws: &mut EigenWorkspace| -> Result<Vec<StabilityAssessment>, Error> {
            let mut row = Vec::with_capacity(nx);
            for (ix, &xv) in x.values.iter().enumerate() {
                // a stop is honoured within one eigen solve, also inside a long row
                crate::run_control::check(|| {
                    format!(
                        "point {} of {nx} of row {} of the parameter grid",
                        ix + 1,
                        iy + 1
                    )
                })?;
                let mut d = *base;
                model.set(x.parameter, &mut d, xv)?;
                model.set(y.parameter, &mut d, y.values[iy])?;
                let ev = ws.eigenvalues(model, &d, params.eigen)?;
                row.push(assess_point(model, &d, ev, &params.verdict));
            }
            Ok(row)
        },
    )?;
    Ok(StabilityMap {
        x: x.clone(),
        y: y.clone(),
        points: rows.into_iter().flatten().collect(),
        threads_used: threads,
    })
}

/// The fast path of [`stability_map`] when one axis is a parameter along which the stiffness is
/// affine and rank one (`LinearizedModel::rank_one`: the string's friction, the plate's pad
/// friction and stiffness) and the kernel is `SmallDense`: every line of the map along that axis
/// shares one Hessenberg reduction (`solve::small_eigenvalues::RankOneLine`). `None` when it
/// does not apply.
fn line_map<Mo: LinearizedModel>(
    model: &Mo,
    base: &Mo::Data,
    x: &GridAxis<Mo::Parameter>,
    y: &GridAxis<Mo::Parameter>,
    params: &StabilityMapParams,
) -> Result<Option<StabilityMap<Mo::Parameter>>, Error> {
    use crate::solve::small_eigenvalues::RankOneLine;
    if params.eigen.kernel != EigenKernel::SmallDense || params.eigen.compute_eigenvectors {
        return Ok(None);
    }
    let (line_axis, other, control_is_y) = if model.rank_one(base, y.parameter).is_some() {
        (y, x, true)
    } else if model.rank_one(base, x.parameter).is_some() {
        (x, y, false)
    } else {
        return Ok(None);
    };
    let n_lines = other.values.len();
    let n_points = line_axis.values.len();
    // Every point's data must be valid (the same checks as the point-by-point path).
    for &o in &other.values {
        let mut d = *base;
        model.set(other.parameter, &mut d, o)?;
        for &t in &line_axis.values {
            let mut e = d;
            model.set(line_axis.parameter, &mut e, t)?;
        }
    }
    let (lines, threads) = parallel_rows(
        n_lines,
        params.threads,
        || (),
        |il, _ws: &mut ()| -> Result<Vec<StabilityAssessment>, Error> {
            let mut d = *base;
            model.set(other.parameter, &mut d, other.values[il])?;
            model.set(line_axis.parameter, &mut d, 0.0)?;
            let at = || model.describe(&d);
            let limit = model.resolution_limit(&d);
            // along the line only friction varies: the speed, and so the warning, is the line's
            let supercritical = model.supercritical_speed(&d);
            let system = model.system(&d)?;
            let mut solver = QuadraticEigenSolver::new(system.mass.as_ref(), params.eigen)
                .map_err(|source| SolveError::Eigenproblem { at: at(), source })?;
            let (a0, gamma) = solver
                .scaled_companion(
                    system.velocity_matrix().as_ref(),
                    system.stiffness_matrix().as_ref(),
                )
                .map_err(|source| SolveError::Eigenproblem { at: at(), source })?;
            let Some((mut r, s, coef)) = model.rank_one(&d, line_axis.parameter) else {
                return Err(InputError::new(
                    format!("map.{}", line_axis.parameter.key()),
                    at(),
                    "a point where the stiffness is rank one along the axis",
                )
                .into());
            };
            let n = r.len();
            solver.solve_mass(&mut r);
            let mut b = vec![0.0; 2 * n];
            let mut c = vec![0.0; 2 * n];
            for i in 0..n {
                b[n + i] = -coef / (gamma * gamma) * r[i];
                c[i] = s[i];
            }
            let mut line = RankOneLine::new(&a0, &b, &c);
            let (mut re, mut im) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
            let mut ev = Vec::with_capacity(2 * n);
            let mut out = Vec::with_capacity(n_points);
            for (it, &t) in line_axis.values.iter().enumerate() {
                // a stop is honoured within one eigen solve, also inside a long line
                crate::run_control::check(|| {
                    format!(
                        "point {} of {n_points} of line {} of {n_lines} of the parameter grid",
                        it + 1,
                        il + 1
                    )
                })?;
                if line.eigenvalues_at(t, &mut re, &mut im).is_ok() {
                    ev.clear();
                    ev.extend(
                        re.iter()
                            .zip(&im)
                            .map(|(a, b)| c64::new(gamma * a, gamma * b)),
                    );
                    let mut a = assess_resolved(&ev, &params.verdict, limit);
                    if let Some(v) = supercritical {
                        a.flag_supercritical(v, &ev, &params.verdict);
                    }
                    out.push(a);
                } else {
                    // The small kernel's QR iteration ran out of sweeps (a stiff spectrum of a
                    // large basis): the point is solved by the reference kernel instead.
                    let mut e = d;
                    model.set(line_axis.parameter, &mut e, t)?;
                    let full = model
                        .system(&e)?
                        .eigen(QuadraticEigenParams {
                            kernel: EigenKernel::Faer,
                            ..params.eigen
                        })
                        .map_err(|source| SolveError::Eigenproblem {
                            at: format!("{}, {} = {t}", at(), line_axis.parameter.key()),
                            source,
                        })?;
                    out.push(assess_point(model, &e, &full.eigenvalues, &params.verdict));
                }
            }
            Ok(out)
        },
    )?;
    let nx = x.values.len();
    let ny = y.values.len();
    let mut points = vec![assess(&[], &params.verdict); nx * ny];
    for (il, line) in lines.into_iter().enumerate() {
        for (ip, a) in line.into_iter().enumerate() {
            let (ix, iy) = if control_is_y { (il, ip) } else { (ip, il) };
            points[iy * nx + ix] = a;
        }
    }
    Ok(Some(StabilityMap {
        x: x.clone(),
        y: y.clone(),
        points,
        threads_used: threads,
    }))
}

#[cfg(test)]
mod tests {
    //! Setting: a small (v̄, p) map of the thick string. Goal: the same bits with 1 and 3 threads;
    //! the string alone is stable below v̄ = 1 with damping and unstable above.
    use super::*;
    use crate::model::moving::string_data::{ContactModel, OscillatorData};
    use crate::model::moving::string_model::{MovingStringParams, StringDiscretization};

    #[test]
    fn map_is_identical_for_any_thread_count() {
        let model = MovingStringModel::new(
            StringDiscretization::Sine { modes: 5 },
            MovingStringParams::default(),
        )
        .unwrap();
        let base = MovingStringData {
            speed: 0.3,
            damping: 0.05,
            oscillator: Some(OscillatorData {
                stiffness: 5.0,
                mass: 0.5,
                position: 0.3,
                contact: ContactModel::Ideal,
                friction: 0.0,
                patch_width: 0.0,
            }),
        };
        let x = GridAxis::linspace(StringParameter::Speed, 0.0, 1.2, 7).unwrap();
        let y = GridAxis::linspace(StringParameter::ControlParameter, 0.0, 4.0, 5).unwrap();
        let run = |threads| {
            string_stability_map(
                &model,
                &base,
                &x,
                &y,
                &StabilityMapParams {
                    threads,
                    ..Default::default()
                },
            )
            .unwrap()
        };
        let (a, b) = (run(1), run(3));
        assert_eq!(a.points, b.points);
        assert_eq!(a.at(0, 0).unwrap().verdict, Verdict::Stable);
        assert!(a.at(6, 0).unwrap().verdict.is_unstable());
    }

    #[test]
    fn rank_one_lines_agree_with_point_by_point_solves() {
        let model = MovingStringModel::new(
            StringDiscretization::Sine { modes: 8 },
            MovingStringParams::default(),
        )
        .unwrap();
        let base = MovingStringData {
            speed: 0.3,
            damping: 0.05,
            oscillator: Some(OscillatorData {
                stiffness: 2.0,
                mass: 0.5,
                position: 0.3,
                contact: ContactModel::Penalty { stiffness: 5.0 },
                friction: 0.0,
                patch_width: 0.0,
            }),
        };
        let x = GridAxis::linspace(StringParameter::Speed, 0.0, 0.9, 6).unwrap();
        let y = GridAxis::linspace(StringParameter::ControlParameter, 0.0, 1.0, 7).unwrap();
        let fast =
            string_stability_map(&model, &base, &x, &y, &StabilityMapParams::default()).unwrap();
        let faer = string_stability_map(
            &model,
            &base,
            &x,
            &y,
            &StabilityMapParams {
                eigen: QuadraticEigenParams::default(),
                ..Default::default()
            },
        )
        .unwrap();
        for (a, b) in fast.points.iter().zip(&faer.points) {
            assert_eq!(a.verdict, b.verdict);
            assert!((a.max_real_part - b.max_real_part).abs() < 1e-12 * b.spectral_scale);
        }
        // transposed axes give the transposed map
        let t =
            string_stability_map(&model, &base, &y, &x, &StabilityMapParams::default()).unwrap();
        for ix in 0..6 {
            for iy in 0..7 {
                assert_eq!(
                    t.at(iy, ix).unwrap().verdict,
                    fast.at(ix, iy).unwrap().verdict
                );
            }
        }
    }

    #[test]
    fn equal_axes_are_rejected() {
        let model = MovingStringModel::new(
            StringDiscretization::Sine { modes: 2 },
            MovingStringParams::default(),
        )
        .unwrap();
        let x = GridAxis::linspace(StringParameter::Speed, 0.0, 0.5, 2).unwrap();
        let e = string_stability_map(
            &model,
            &MovingStringData::string(0.1, 0.0),
            &x,
            &x,
            &Default::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("map.y.parameter"));
    }
}
