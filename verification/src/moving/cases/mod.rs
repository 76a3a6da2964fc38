//! The moving family's case kinds, one file each: the case body's format (unknown keys are
//! errors), its checks, and its runner (which writes its detailed numbers to
//! `<out>/<case id>/data.json`).

pub mod disc;
pub mod envelope;
pub mod extremes;
pub mod flutter;
pub mod map;
pub mod map_lines;
pub mod oscillator;
pub mod penalty;
pub mod plate;
pub mod string;
pub mod symmetry;
pub mod time_check;
