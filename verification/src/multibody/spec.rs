//! What a multibody case states about its bodies and its audit: the material (law and constants)
//! and the claims its audit may make. A leaf: the study driver and the state-recomputed audit
//! both read it.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use contactlab::material::hyperelastic::{
    Hyperelastic2d, LinearElastic, NeoHooke, StVenantKirchhoff,
};
use contactlab::model::multibody::scheme::MultibodyScheme;

/// A plane-strain law of a case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LawName {
    Linear,
    StVenantKirchhoff,
    NeoHooke,
}

/// A case's material: the law and its constants (plane strain).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub law: LawName,
    pub young: f64,
    pub poisson: f64,
}

impl MaterialSpec {
    /// The law object.
    pub fn law(&self) -> Result<Arc<dyn Hyperelastic2d>, String> {
        let e = |x: contactlab::error::InputError| x.to_string();
        Ok(match self.law {
            LawName::Linear => {
                Arc::new(LinearElastic::from_young_poisson(self.young, self.poisson).map_err(e)?)
            }
            LawName::StVenantKirchhoff => Arc::new(
                StVenantKirchhoff::from_young_poisson(self.young, self.poisson).map_err(e)?,
            ),
            LawName::NeoHooke => {
                Arc::new(NeoHooke::from_young_poisson(self.young, self.poisson).map_err(e)?)
            }
        })
    }

    /// Whether the law is objective (its stress rotates with the body: angular momentum can be
    /// conserved).
    pub fn is_objective(&self) -> bool {
        !matches!(self.law, LawName::Linear)
    }

    /// The longitudinal (P-) wave speed at rest, √((λ + 2μ)/ρ) in plane strain.
    pub fn wave_speed(&self, density: f64) -> f64 {
        let (e, nu) = (self.young, self.poisson);
        (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / density).sqrt()
    }
}

/// What a run's audit may claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Claims {
    /// E_{n+1} − E_n = W_N + W_T + W_ext to round-off (the energy–momentum scheme).
    pub identity: bool,
    /// Energy conserved (up to the loads' and friction's work) in steps without a change of the
    /// active set.
    pub unchanged: bool,
    /// P_x, P_y conserved (no load and no foundation along the component).
    pub momentum: [bool; 2],
    /// J conserved (no load, no foundation, an objective law, a midpoint-type scheme).
    pub angular: bool,
    /// Friction's step work ≤ 0 (always).
    pub friction_sign: bool,
}

impl Claims {
    /// The claims of `scheme` for a system whose momentum components are free of external forces
    /// (`free`), with an objective law or not.
    pub fn of(scheme: MultibodyScheme, free: [bool; 2], objective: bool) -> Self {
        let em = scheme == MultibodyScheme::EnergyMomentum;
        let midpoint_type = scheme.is_midpoint_type();
        Self {
            identity: em,
            unchanged: em,
            momentum: free,
            angular: free[0] && free[1] && objective && midpoint_type,
            friction_sign: true,
        }
    }
}
