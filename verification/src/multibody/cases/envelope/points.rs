//! The runs of a `multibody_envelope` case: one per (sweep, speed, mesh) and one per overlapping
//! start, in parallel (each is independent and deterministic; the results keep the order).

use rayon::prelude::*;

use contactlab::error::Error;
use contactlab::model::multibody::audit::scheme_energy_warning;
use contactlab::model::multibody::bodies::BodySet;
use contactlab::model::multibody::solver::{MultibodySolution, MultibodySolver};
use contactlab::scene::Scene;

use crate::exact::bar_impact::{HeadOnBars, TwoBarImpact};
use crate::multibody::cases::bars::setup::{build, Geometry, Level, Treatment};
use crate::multibody::cases::envelope::energy::{state_sums, StateSums};
use crate::multibody::cases::envelope::format::{EnvelopeCase, OverlapSpec};
use crate::multibody::study::{LawName, MaterialSpec};

/// Where a run came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// Sweep `sweep` at v/c = `speed` on `elements` along and `rows` across.
    Sweep {
        sweep: usize,
        speed: f64,
        elements: usize,
        rows: usize,
    },
    /// The overlapping start `overlap`.
    Overlap { overlap: usize },
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Ending {
    Completed,
    /// A typed error: its variant's name (`EnergyGain`, `ActiveSetCycle`, …; `overlap_error` for a
    /// scene refused at t = 0) and its message.
    Failed {
        kind: String,
        message: String,
    },
}

/// One run's outcome; the sums are recomputed from the initial and final states
/// ([`super::energy`]).
#[derive(Debug, Clone)]
pub struct PointRun {
    pub source: Source,
    pub label: String,
    /// v (the bars' speed) and N.
    pub speed: f64,
    pub steps: usize,
    pub ending: Ending,
    /// The run summary's warning (Newmark with multipliers whose energy rose).
    pub warning: Option<String>,
    /// Steps whose positive set-change work the audit flagged, and its sum over E_0.
    pub flagged_steps: usize,
    pub flagged_work: f64,
    /// The solver's own E_N/E_0 (reported beside the recomputed one, never gated).
    pub solver_ratio: Option<f64>,
    /// The exact centre velocities of the bars at T (the head-on sweep points:
    /// [`HeadOnBars`], the swap ±v → ∓v after the release).
    pub exact_final: Option<[f64; 2]>,
    pub start: Option<StateSums>,
    pub end: Option<StateSums>,
}

impl PointRun {
    /// The outcome's names: the error's kind, or `completed` with `newmark_warning` and
    /// `audit_flag` when the summary carries them.
    pub fn outcomes(&self) -> Vec<String> {
        match &self.ending {
            Ending::Failed { kind, .. } => vec![kind.clone()],
            Ending::Completed => {
                let mut v = vec!["completed".to_string()];
                if self.warning.is_some() {
                    v.push("newmark_warning".into());
                }
                if self.flagged_steps > 0 {
                    v.push("audit_flag".into());
                }
                v
            }
        }
    }

    /// The rebound's error max_b |v_b(T) − v_b,exact(T)|/v from the recomputed momenta against
    /// the exact centre velocities (equal bars swap their velocities, ±v → ∓v).
    pub fn rebound_error(&self) -> Option<f64> {
        let (s, exact) = (self.end.as_ref()?, self.exact_final?);
        let vl = s.body_momentum[0][0] / s.body_mass[0];
        let vr = s.body_momentum[1][0] / s.body_mass[1];
        Some((vl - exact[0]).abs().max((vr - exact[1]).abs()) / self.speed)
    }

    /// E_T/E_0 recomputed.
    pub fn energy_ratio(&self) -> Option<f64> {
        Some(self.end.as_ref()?.energy / self.start.as_ref()?.energy)
    }
}

/// The name of a typed error's variant (`EnergyGain` of `Error::Solve(SolveError::EnergyGain {..})`).
pub fn error_kind(e: &Error) -> String {
    let debug = match e {
        Error::Solve(s) => format!("{s:?}"),
        other => format!("{other:?}"),
    };
    debug
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// Every sweep point of the case (sweep order, then speed, then mesh).
pub fn sources(file: &EnvelopeCase) -> Vec<Source> {
    let mut out = Vec::new();
    for (s, sweep) in file.sweeps.iter().enumerate() {
        for &speed in &sweep.speeds {
            for &elements in &sweep.elements {
                out.push(Source::Sweep {
                    sweep: s,
                    speed,
                    elements,
                    rows: sweep.cells.rows(&file.bars, elements),
                });
            }
        }
    }
    out.extend((0..file.overlaps.len()).map(|overlap| Source::Overlap { overlap }));
    out
}

/// Runs every point (in parallel; the order of [`sources`]).
pub fn run_all(file: &EnvelopeCase) -> Result<Vec<PointRun>, String> {
    sources(file)
        .par_iter()
        .map(|s| match *s {
            Source::Sweep { .. } => run_sweep_point(file, *s),
            Source::Overlap { overlap } => run_overlap(file, overlap, &file.overlaps[overlap]),
        })
        .collect()
}

/// The outcome of a solve of `solver` (which starts from its problem's initial state).
fn finish(
    file: &EnvelopeCase,
    source: Source,
    label: String,
    speed: f64,
    solver: &MultibodySolver,
    result: Result<MultibodySolution, Error>,
) -> PointRun {
    let p = solver.problem();
    let (young, poisson) = (file.bars.young, file.bars.poisson);
    let start = state_sums(
        &p.bodies,
        young,
        poisson,
        &p.initial_displacement,
        &p.initial_velocity,
    );
    let mut run = PointRun {
        source,
        label,
        speed,
        steps: p.steps,
        ending: Ending::Completed,
        warning: None,
        flagged_steps: 0,
        flagged_work: 0.0,
        solver_ratio: None,
        exact_final: None,
        start: Some(start),
        end: None,
    };
    match result {
        Ok(sol) => {
            let s = sol.summary();
            let multipliers = p.pairs.iter().any(|q| q.law.has_normal_multiplier());
            run.warning = scheme_energy_warning(p.scheme, multipliers, &s);
            run.flagged_steps = s.positive_set_work_steps;
            run.flagged_work = s.positive_set_work_relative;
            run.solver_ratio = Some(s.final_energy_ratio);
            run.end = Some(final_sums(&p.bodies, young, poisson, &sol));
        }
        Err(e) => {
            run.ending = Ending::Failed {
                kind: error_kind(&e),
                message: e.to_string(),
            }
        }
    }
    run
}

fn final_sums(bodies: &BodySet, young: f64, poisson: f64, sol: &MultibodySolution) -> StateSums {
    state_sums(
        bodies,
        young,
        poisson,
        &sol.final_displacement,
        &sol.final_velocity,
    )
}

/// The head-on bars of a sweep point.
fn run_sweep_point(file: &EnvelopeCase, source: Source) -> Result<PointRun, String> {
    let Source::Sweep {
        sweep,
        speed,
        elements,
        rows,
    } = source
    else {
        return Err("not a sweep point".into());
    };
    let (b, spec) = (&file.bars, &file.sweeps[sweep]);
    let v = speed * b.wave_speed();
    let geometry = Geometry {
        left_length: b.length,
        right_length: b.length,
        height: b.height,
        density: b.density,
        gap: spec.gap.unwrap_or_else(|| b.gap(v, elements)),
        left_velocity: v,
        right_velocity: -v,
    };
    let level = Level {
        elements,
        rows,
        step: b.step(elements),
        steps: b.steps(elements, geometry.gap, v),
    };
    let material = MaterialSpec {
        law: LawName::Linear,
        young: b.young,
        poisson: b.poisson,
    };
    let treatment = Treatment {
        scheme: spec.scheme,
        two_pass: spec.two_pass,
    };
    let label = format!("{}: v/c = {speed}, M = {elements} × {rows}", spec.name);
    let solver =
        build(&geometry, &material, &level, treatment).map_err(|e| format!("{label}: {e}"))?;
    let result = solver.solve();
    let mut run = finish(file, source, label, v, &solver, result);
    let exact = HeadOnBars {
        length: b.length,
        density: b.density,
        young: b.young,
        area: b.height,
        speed: v,
        gap: geometry.gap,
    };
    run.exact_final = Some(exact.centre_velocities(level.final_time()));
    Ok(run)
}

/// The scene text of the bars started `depth` into each other (a negative depth: apart), at ±v.
pub fn overlap_scene(file: &EnvelopeCase, o: &OverlapSpec) -> String {
    let b = &file.bars;
    let v = o.speed * b.wave_speed();
    let extra = if o.resolve {
        "initial_overlap = \"resolve\""
    } else {
        ""
    };
    let body = |name: &str, x: f64, vx: f64| {
        format!(
            "[[body]]\nname = \"{name}\"\nshape = \"rectangle\"\norigin = [{x:?}, 0.0]\n\
             size = [{:?}, {:?}]\ndivisions = [{}, 1]\ndensity = {:?}\n\
             material = {{ law = \"linear\", young = {:?}, poisson = {:?} }}\n\
             velocity = [{vx:?}, 0.0]\n",
            b.length, b.height, o.elements, b.density, b.young, b.poisson
        )
    };
    let k = b.step(o.elements);
    let steps = b.steps(o.elements, 0.0, v);
    format!(
        "title = \"{}\"\nmodel = \"dynamic\"\n{}{}[[contact_pair]]\n\
         slave = {{ body = \"left\", sides = [\"right\"] }}\n\
         master = {{ body = \"right\", sides = [\"left\"] }}\n{extra}\n\
         [time]\nfinal_time = {:?}\nsteps = {steps}\n",
        o.name,
        body("left", -b.length + 0.5 * o.depth, v),
        body("right", -0.5 * o.depth, -v),
        k * steps as f64,
    )
}

/// An overlapping start: refused (typed error) or resolved and run.
fn run_overlap(file: &EnvelopeCase, index: usize, o: &OverlapSpec) -> Result<PointRun, String> {
    let source = Source::Overlap { overlap: index };
    let label = format!("overlap: {}", o.name);
    let v = o.speed * file.bars.wave_speed();
    let scene = match Scene::from_toml_str(&overlap_scene(file, o), "envelope_overlap.toml") {
        Ok(Scene::Multibody(s)) => s,
        Ok(other) => return Err(format!("{label}: a {} scene", other.model())),
        Err(e) => {
            let kind = match &e {
                Error::Input(_) => "overlap_error".to_string(),
                other => error_kind(other),
            };
            return Ok(PointRun {
                source,
                label,
                speed: v,
                steps: 0,
                ending: Ending::Failed {
                    kind,
                    message: e.to_string(),
                },
                warning: None,
                flagged_steps: 0,
                flagged_work: 0.0,
                solver_ratio: None,
                exact_final: None,
                start: None,
                end: None,
            });
        }
    };
    let solver = scene.solver().map_err(|e| format!("{label}: {e}"))?;
    let result = solver.solve();
    Ok(finish(file, source, label, v, &solver, result))
}
