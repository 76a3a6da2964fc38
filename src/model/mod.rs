//! The problems. `quasistatic`: the Kelvin–Voigt body with normal damped response
//! (Fernández & Sofonea 2004). `dynamic`: elastodynamic contact with energy-consistent time
//! integration (Barboteu–Danan–Sofonea; Hauret–Le Tallec).
//! `moving`: moving continua with contacts and sliding friction, linearized models and their
//! stability (Hetzler 2009). `multibody`: bodies against bodies — node-to-segment contact with
//! Lagrange multipliers, friction and energy–momentum integration.

pub mod dynamic;
pub mod moving;
pub mod multibody;
pub mod quasistatic;
