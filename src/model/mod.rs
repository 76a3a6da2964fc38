//! The problems. `quasistatic`: the Kelvin–Voigt body with normal damped response
//! (Fernández & Sofonea 2004). `dynamic`: elastodynamic contact with energy-consistent time
//! integration (Barboteu–Danan–Sofonea; Hauret–Le Tallec).
//! `moving`: moving continua with contacts and sliding friction, linearized models and their
//! stability (Hetzler 2009).

pub mod dynamic;
pub mod moving;
pub mod quasistatic;
