//! The case body of `plane_paper_test_2d` and its checks (unknown keys are errors; every error
//! names its field).

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::core::case::Case;
use crate::core::format::{at_least, invalid, positive, CaseError};

/// The case body.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperTestCase {
    /// The paper's Test 2D as a plane scene (each run sets its reading, mesh and β).
    pub scene: toml::Table,
    pub paper_test: PaperTestSpec,
}

/// `[paper_test]`: Test 2D (Fernández & Sofonea 2004, §4.2) under both readings of Γ1 on a
/// sequence of meshes, the mesh-converged quantities with their GCI, set beside Figs 14–15.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperTestSpec {
    /// Squares per side, ascending with a constant ratio (at least three: the GCI).
    pub meshes: Vec<usize>,
    /// The mesh of the deformed-mesh and von Mises pictures (one of `meshes`; pictures only).
    pub figure_mesh: usize,
    pub betas: Vec<f64>,
    /// The β of the paper's Fig 14 (one of `betas`).
    pub von_mises_beta: f64,
    /// The paper's von Mises range at T (Fig 14), set beside ours, not gated.
    pub paper_von_mises: [f64; 2],
    /// The paper's lowest contact-line value at T (Fig 15), set beside ours, not gated.
    pub paper_contact_lowest: f64,
    /// The rigid sinking of the rollers reading against its closed form, to this multiple of
    /// ε · (the number of steps) (round-off of the accumulated sum).
    pub sinking_round_off_factor: f64,
    #[serde(default)]
    pub gci: Vec<GciGateSpec>,
}

/// A reading of "the horizontal displacements on the lateral surfaces vanish".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reading {
    /// u = 0 on the sides.
    Clamped,
    /// u_x = 0 on the sides.
    Rollers,
}

impl Reading {
    pub const ALL: [Reading; 2] = [Reading::Clamped, Reading::Rollers];

    pub fn name(self) -> &'static str {
        match self {
            Reading::Clamped => "clamped",
            Reading::Rollers => "rollers",
        }
    }
}

/// A quantity of one run at T.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// min over triangles of the plane-stress von Mises norm of σ.
    VonMisesMin,
    VonMisesMax,
    /// min over the Γ3 nodes of u_y (the lowest point of the contact line).
    ContactLineMin,
    ContactLineMax,
}

impl Quantity {
    pub const ALL: [Quantity; 4] = [
        Quantity::VonMisesMin,
        Quantity::VonMisesMax,
        Quantity::ContactLineMin,
        Quantity::ContactLineMax,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Quantity::VonMisesMin => "von Mises min",
            Quantity::VonMisesMax => "von Mises max",
            Quantity::ContactLineMin => "contact line min",
            Quantity::ContactLineMax => "contact line max",
        }
    }
}

/// What a `[[paper_test.gci]]` expects of its quantity under mesh refinement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Expect {
    /// A mesh limit: the observed order verified, GCI_fine and the asymptotic ratio gated.
    Converges,
    /// A mesh limit whose observed order is not verified (the extreme moves between elements):
    /// only the GCI with Roache's fallback (formal order, F_s = 3) is gated.
    ConvergesUnverified,
    /// No mesh limit (a singularity): the differences of the finest three levels grow.
    Diverges,
}

/// `[[paper_test.gci]]`: one quantity of one reading at one β.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GciGateSpec {
    pub reading: Reading,
    pub quantity: Quantity,
    /// One of `betas`.
    pub beta: f64,
    pub expect: Expect,
    /// The order the quantity should show (and the fallback order of the GCI).
    pub formal_order: f64,
    /// GCI of the finest level in per cent (`converges`, `converges_unverified`).
    pub max_percent: Option<f64>,
    /// |A − 1| for the asymptotic ratio A (`converges`; four levels or more).
    pub asymptotic_tolerance: Option<f64>,
    #[serde(default)]
    pub note: String,
}

impl PaperTestCase {
    /// Parses and checks the case body.
    pub fn parse(case: &Case) -> Result<Self, CaseError> {
        let c: Self = case.body()?;
        c.paper_test.check(case.path())?;
        Ok(c)
    }
}

impl PaperTestSpec {
    /// The refinement ratio of the meshes.
    pub fn ratio(&self) -> f64 {
        self.meshes[1] as f64 / self.meshes[0] as f64
    }

    fn check(&self, path: &Path) -> Result<(), CaseError> {
        at_least(path, "paper_test.meshes", &self.meshes, 3)?;
        if self.meshes[0] == 0 {
            return Err(invalid(
                path,
                "paper_test.meshes",
                0,
                "squares per side ≥ 1",
            ));
        }
        let r = self.ratio();
        if !(r > 1.0
            && self
                .meshes
                .windows(2)
                .all(|w| (w[1] as f64 / w[0] as f64 - r).abs() < 1e-12))
        {
            return Err(invalid(
                path,
                "paper_test.meshes",
                format!("{:?}", self.meshes),
                "ascending with a constant ratio > 1",
            ));
        }
        if !self.meshes.contains(&self.figure_mesh) {
            return Err(invalid(
                path,
                "paper_test.figure_mesh",
                self.figure_mesh,
                "one of paper_test.meshes",
            ));
        }
        at_least(path, "paper_test.betas", &self.betas, 1)?;
        for (i, b) in self.betas.iter().enumerate() {
            positive(path, &format!("paper_test.betas[{i}]"), *b)?;
        }
        if !self.betas.contains(&self.von_mises_beta) {
            return Err(invalid(
                path,
                "paper_test.von_mises_beta",
                self.von_mises_beta,
                "one of paper_test.betas",
            ));
        }
        positive(
            path,
            "paper_test.sinking_round_off_factor",
            self.sinking_round_off_factor,
        )?;
        for (i, g) in self.gci.iter().enumerate() {
            let field = format!("paper_test.gci[{i}]");
            if !self.betas.contains(&g.beta) {
                return Err(invalid(
                    path,
                    &format!("{field}.beta"),
                    g.beta,
                    "one of paper_test.betas",
                ));
            }
            positive(path, &format!("{field}.formal_order"), g.formal_order)?;
            match g.expect {
                Expect::Converges | Expect::ConvergesUnverified => {
                    let p = g.max_percent.ok_or_else(|| {
                        invalid(
                            path,
                            &format!("{field}.max_percent"),
                            "(missing)",
                            "a GCI bound in per cent for a converging quantity",
                        )
                    })?;
                    positive(path, &format!("{field}.max_percent"), p)?;
                }
                Expect::Diverges => {
                    if g.max_percent.is_some() || g.asymptotic_tolerance.is_some() {
                        return Err(invalid(
                            path,
                            &format!("{field}.expect"),
                            "diverges",
                            "no max_percent or asymptotic_tolerance for a diverging quantity",
                        ));
                    }
                }
            }
            if let Some(t) = g.asymptotic_tolerance {
                positive(path, &format!("{field}.asymptotic_tolerance"), t)?;
                if g.expect != Expect::Converges || self.meshes.len() < 4 {
                    return Err(invalid(
                        path,
                        &format!("{field}.asymptotic_tolerance"),
                        t,
                        "only for expect = \"converges\" with four meshes or more",
                    ));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The format: a valid body parses; a mesh sequence without a constant ratio, a gate on a β
    //! that is not run, and a GCI bound on a diverging quantity are typed errors naming the field.
    use super::*;

    fn spec(extra: &str) -> Result<PaperTestSpec, CaseError> {
        let text = format!(
            "meshes = [12, 24, 48, 96]\nfigure_mesh = 24\nbetas = [10.0, 1000.0]\n\
             von_mises_beta = 1000.0\npaper_von_mises = [6.56, 49.22]\n\
             paper_contact_lowest = -0.35\nsinking_round_off_factor = 4.0\n{extra}"
        );
        let s: PaperTestSpec = toml::from_str(&text).map_err(|e| CaseError::Read {
            path: "t".into(),
            message: e.to_string(),
        })?;
        s.check(Path::new("t"))?;
        Ok(s)
    }

    #[test]
    fn a_valid_body_parses() {
        let s = spec(
            "[[gci]]\nreading = \"rollers\"\nquantity = \"von_mises_max\"\nbeta = 1000.0\n\
             expect = \"converges\"\nformal_order = 1.0\nmax_percent = 1.0\n\
             asymptotic_tolerance = 0.1\n",
        )
        .expect("valid");
        assert_eq!(s.ratio(), 2.0);
    }

    #[test]
    fn bad_bodies_name_the_field() {
        let e = spec("").map(|_| ()).and_then(|_| {
            let mut s = spec("")?;
            s.meshes = vec![12, 24, 36];
            s.check(Path::new("t"))
        });
        assert!(e.unwrap_err().to_string().contains("paper_test.meshes"));
        let e = spec(
            "[[gci]]\nreading = \"rollers\"\nquantity = \"von_mises_max\"\nbeta = 50.0\n\
             expect = \"converges\"\nformal_order = 1.0\nmax_percent = 1.0\n",
        )
        .unwrap_err();
        assert!(e.to_string().contains("paper_test.gci[0].beta"), "{e}");
        let e = spec(
            "[[gci]]\nreading = \"clamped\"\nquantity = \"von_mises_max\"\nbeta = 1000.0\n\
             expect = \"diverges\"\nformal_order = 1.0\nmax_percent = 1.0\n",
        )
        .unwrap_err();
        assert!(e.to_string().contains("paper_test.gci[0].expect"), "{e}");
        let e = spec("stray = 1\n").unwrap_err();
        assert!(e.to_string().contains("stray"), "{e}");
    }
}
