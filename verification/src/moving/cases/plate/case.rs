//! `moving_plate`: the rotating annular Kirchhoff plate of Hetzler (2009) §4.1 without pad —
//! frequencies against the exact characteristic equation (`frequencies.rs`), the spatial-frame
//! spectrum i(±ω_{n,m} − nΩ) and the Campbell diagram (`rotating.rs`), and the symmetry of the
//! transport operators (`symmetry.rs`).

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::context::RunContext;
use crate::core::format::{invalid, CaseError};
use crate::core::gate::RateGate;
use crate::core::report::case_report::CaseReport;
use crate::moving::cases::plate::common::PlateSection;
use crate::moving::cases::plate::frequencies::{self, FrequenciesSection, FrequencyLevel};
use crate::moving::cases::plate::rotating::{self, CampbellSection, RotatingSection};
use crate::moving::cases::plate::symmetry::{self, FamilyRow, SymmetrySection};
use crate::moving::study::SeriesSelect;

/// The case format of `moving_plate`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlateCase {
    pub plate: PlateSection,
    pub frequencies: FrequenciesSection,
    /// Rate gates on the frequency series (`series` = an outer edge, or `centre n ≥ 2`, …).
    #[serde(default, skip_serializing)]
    pub gate: Vec<RateGate<SeriesSelect>>,
    pub rotating: RotatingSection,
    pub campbell: CampbellSection,
    pub symmetry: SymmetrySection,
}

impl PlateCase {
    /// Checks the numbers of the case.
    pub fn check(&self, p: &Path) -> Result<(), CaseError> {
        self.plate.check(p)?;
        self.frequencies.check(p)?;
        for (i, g) in self.gate.iter().enumerate() {
            g.criteria.check(p, &format!("gate[{i}]"))?;
        }
        if self.rotating.speeds.is_empty() {
            return Err(invalid(p, "rotating.speeds", "[]", "at least one speed"));
        }
        if self.campbell.points < 3 {
            return Err(invalid(
                p,
                "campbell.points",
                self.campbell.points,
                "at least 3",
            ));
        }
        if !(self.symmetry.sector_angle > 0.0 && self.symmetry.sector_angle < std::f64::consts::TAU)
        {
            return Err(invalid(
                p,
                "symmetry.sector_angle",
                self.symmetry.sector_angle,
                "an angle in (0, 2π)",
            ));
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Serialize)]
struct Data {
    frequencies: Vec<FrequencyLevel>,
    sectors: Vec<FamilyRow>,
}

/// Runs the case.
pub fn run(case: &PlateCase, ctx: &RunContext, report: &mut CaseReport) -> Result<(), String> {
    let plate = case.plate.properties();
    let (levels, fig) = frequencies::run(plate, &case.frequencies, &case.gate, report)?;
    ctx.plot(report, "frequencies", &fig)?;
    rotating::run(plate, &case.rotating, &case.campbell, ctx, report)?;
    let sectors = symmetry::run(plate, &case.symmetry, report)?;
    ctx.write_data(
        report,
        &Data {
            frequencies: levels,
            sectors,
        },
    )
}
