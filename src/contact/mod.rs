//! Contact laws. `normal_law`: the normal damped response laws p_ν of Fernández & Sofonea (2004),
//! (2.7)–(2.9), each with its value and a generalized derivative.

pub mod normal_law;
