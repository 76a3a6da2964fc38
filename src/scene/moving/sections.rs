//! The sections both moving-continuum scenes share: `[stability]` (the verdict tolerances,
//! threads, eigenvectors, the map's kernel) and the axes of `[[sweep]]` and `[map]`.

use serde::{Deserialize, Serialize};

use crate::error::{Error, InputError};
use crate::model::moving::linearized::AxisParameter;
use crate::model::moving::stability::VerdictParams;
use crate::model::moving::stability_map::GridAxis;
use crate::solve::quadratic_eigen::EigenKernel;

/// `[stability]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySection {
    /// τ_rel: the verdicts' round-off tolerance relative to the spectral scale max |λ| (default
    /// 1e-7).
    pub relative_tolerance: Option<f64>,
    /// τ_abs: the tolerance's floor when the spectral scale is tiny (default 1e-12).
    pub absolute_tolerance: Option<f64>,
    /// Verdicts from the resolved eigenvalues only (default true; `model::moving::resolution`).
    pub resolved_only: Option<bool>,
    /// Worker threads of sweeps and maps, 0 to 1024 (default 0: all cores; results do not depend on
    /// it).
    #[serde(default)]
    pub threads: usize,
    /// Also compute and write the eigenvectors at the analysed point (default false; string and
    /// plate).
    #[serde(default)]
    pub eigenvectors: bool,
    /// The eigensolver of the `[map]` points (default `"small_dense"`; string and plate).
    pub map_kernel: Option<EigenKernel>,
}

/// `[[sweep]]` and the axes of `[map]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisSection {
    /// The parameter varied: string `speed`, `damping`, `oscillator_stiffness`, `oscillator_mass`,
    /// `position`, `penalty_stiffness`, `friction`, `control_parameter`; disc `angular_speed`,
    /// `normal_force`, `friction_coefficient`, `radius`; plate `angular_speed`, `damping`,
    /// `pad_stiffness`, `friction` (the last two need a `[pad]`).
    pub parameter: String,
    /// The first value, finite.
    pub from: f64,
    /// The last value, finite and other than `from`.
    pub to: f64,
    /// The number of values from `from` to `to`, 2 to 100000.
    pub points: usize,
    /// `"linear"` (equal spacing) or `"log"` (geometric spacing; `from`, `to` > 0) (default
    /// `"linear"`).
    #[serde(default = "linear")]
    pub scale: String,
}

fn linear() -> String {
    "linear".into()
}

/// `[map]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapSection {
    /// The horizontal axis: `parameter`, `from`, `to`, `points`, `scale` as for `[[sweep]]`.
    pub x: AxisSection,
    /// The vertical axis, a parameter other than `x`'s.
    pub y: AxisSection,
}

/// Every `[[sweep]]` and the `[map]` checked into axes by `check_axis` (which names the field
/// it is given: `sweep[i]`, `map.x`, `map.y`); the map's two parameters must differ.
#[allow(clippy::type_complexity)]
pub fn sweeps_and_map<P: AxisParameter>(
    sweep: &[AxisSection],
    map: Option<&MapSection>,
    check_axis: impl Fn(&str, &AxisSection) -> Result<GridAxis<P>, Error>,
) -> Result<(Vec<GridAxis<P>>, Option<(GridAxis<P>, GridAxis<P>)>), Error> {
    let mut sweeps = Vec::new();
    for (i, s) in sweep.iter().enumerate() {
        sweeps.push(check_axis(&format!("sweep[{i}]"), s)?);
    }
    let map = match map {
        None => None,
        Some(m) => {
            let x = check_axis("map.x", &m.x)?;
            let y = check_axis("map.y", &m.y)?;
            if x.parameter == y.parameter {
                return Err(InputError::new(
                    "map.y.parameter",
                    &m.y.parameter,
                    format!("a parameter other than map.x.parameter = {}", m.x.parameter),
                )
                .into());
            }
            Some((x, y))
        }
    };
    Ok((sweeps, map))
}

/// The values of an axis: `points` values from `from` to `to`, equally or geometrically spaced.
pub fn axis_values(field: &str, a: &AxisSection) -> Result<Vec<f64>, InputError> {
    if !(2..=100_000).contains(&a.points) {
        return Err(InputError::new(
            format!("{field}.points"),
            a.points,
            "2 to 100000 points",
        ));
    }
    for (k, v) in [("from", a.from), ("to", a.to)] {
        if !v.is_finite() {
            return Err(InputError::new(
                format!("{field}.{k}"),
                v,
                "a finite number",
            ));
        }
    }
    if a.from == a.to {
        return Err(InputError::new(
            format!("{field}.to"),
            a.to,
            format!("a number other than from = {}", a.from),
        ));
    }
    let n = a.points - 1;
    match a.scale.as_str() {
        "linear" => Ok((0..=n)
            .map(|i| a.from + (a.to - a.from) * i as f64 / n as f64)
            .collect()),
        "log" => {
            if !(a.from > 0.0 && a.to > 0.0) {
                return Err(InputError::new(
                    format!("{field}.from"),
                    a.from,
                    "positive from and to for scale = \"log\"",
                ));
            }
            let (l0, l1) = (a.from.ln(), a.to.ln());
            Ok((0..=n)
                .map(|i| (l0 + (l1 - l0) * i as f64 / n as f64).exp())
                .collect())
        }
        other => Err(InputError::new(
            format!("{field}.scale"),
            other,
            "\"linear\" or \"log\"",
        )),
    }
}

/// The verdict parameters of `[stability]` (defaults where absent), with its thread count checked.
pub(super) fn verdict_params(s: &StabilitySection) -> Result<VerdictParams, InputError> {
    let d = VerdictParams::default();
    let p = VerdictParams {
        relative_tolerance: s.relative_tolerance.unwrap_or(d.relative_tolerance),
        absolute_tolerance: s.absolute_tolerance.unwrap_or(d.absolute_tolerance),
        resolved_only: s.resolved_only.unwrap_or(d.resolved_only),
    };
    p.validate()?;
    if s.threads > 1024 {
        return Err(InputError::new("stability.threads", s.threads, "0 to 1024"));
    }
    Ok(p)
}
