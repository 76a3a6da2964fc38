//! Contact laws. `normal_law`: the normal damped response laws p_ν of Fernández & Sofonea (2004),
//! (2.7)–(2.9), each with its value and a generalized derivative. `compliance`: the normal
//! compliance forces of dynamic steps (penalty, energy-consistent (BDS (1.46), HLT (3.68)), the
//! HLT variant (3.69)). `friction`: Coulomb friction coefficients μ(u_ν) (BDS (1.13)).

pub mod compliance;
pub mod friction;
pub mod normal_law;
