//! The rotating Kirchhoff plate's case kinds (Hetzler 2009, §4.1): `moving_plate` (frequencies
//! against the exact characteristic equation, the spatial-frame spectrum and Campbell diagram,
//! the symmetry of the transport operators) and `moving_plate_pad` (the stationary pad: spring,
//! friction, limits).

pub mod case;
pub mod common;
pub mod frequencies;
pub mod pad;
pub mod pad_format;
pub mod pad_limits;
pub mod rotating;
pub mod symmetry;
