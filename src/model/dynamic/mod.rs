//! Dynamic contact of elastic bodies with a rigid foundation, with energy-consistent time
//! integration (Barboteu–Danan–Sofonea 2015, "BDS"; Hauret–Le Tallec 2006, "HLT").
//!
//!   ρ ü − Div Π(F) = f0,  u = 0 on Γ1,  Π ν = f2 on Γ2,  contact and friction on Γ3
//!   (BDS (1.14)–(1.20)),
//!
//! discretized by P1 elements ([`bar`] in 1D, [`plane_body`] in plane strain, with regions of
//! their own material: [`plane_material`]), integrated by Newmark, the midpoint rule or
//! Gonzalez's energy-conserving scheme ([`scheme`]), with the contact treatments of
//! [`contact_model`] solved by one semismooth Newton method ([`newton`]) on a full or a condensed
//! step operator ([`step_operator`]). Every run carries its energy audit ([`audit`]): the
//! residuals of BDS Propositions 1.1 and 1.3 and of HLT Proposition 3.7 per step; [`record`]
//! observes a run step by step (what a run that stops partway computed) and says which
//! identities a problem satisfies to round-off.

pub mod audit;
pub mod bar;
pub mod body;
pub mod contact_model;
pub mod newton;
pub mod plane_body;
pub mod plane_material;
pub mod record;
pub mod scheme;
pub mod solver;
pub mod step_operator;
