//! The problems. `quasistatic`: the Kelvin–Voigt body with normal damped response
//! (Fernández & Sofonea 2004).

pub mod quasistatic;
