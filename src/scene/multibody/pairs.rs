//! The `[[contact_pair]]` sections of a multibody scene validated into the solver's contact
//! pairs: the slave and master boundary parts (a body by name and `sides`, `where` or `group`;
//! the whole boundary by default), the foundation, single or two passes, the enforcement and the
//! friction. A two-pass section becomes two solver pairs with the roles exchanged; each solver
//! pair remembers the section it came from ([`PairOrigin`]).

use std::sync::Arc;

use serde::Serialize;

use crate::error::{require_finite, require_nonnegative, require_positive, Error, InputError};
use crate::mesh::gmsh::GmshMesh;
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::constraint::{Enforcement, PairLaw};
use crate::model::multibody::solver::{ContactPair, PairMaster};
use crate::model::multibody::surface::{ContactSurface, Foundation};
use crate::model::quasistatic::plane::BoundarySelector;
use crate::scene::boundary::{require_part_selected, selector, Selection};
use crate::scene::common::missing;
use crate::scene::multibody::format::{ContactPairSection, EnforcementName, PairSideSection, Pass};

/// Where a solver pair comes from: its `[[contact_pair]]` section and whether it is the second
/// pass of a two-pass section (the section's master as slave).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct PairOrigin {
    /// The index of the `[[contact_pair]]` section.
    pub section: usize,
    /// Whether the roles of the section are exchanged (the second pass).
    pub exchanged: bool,
}

/// The body of side `s` (named `{field}.body`) by its name.
fn body_index(field: &str, s: &PairSideSection, names: &[String]) -> Result<usize, InputError> {
    names.iter().position(|n| *n == s.body).ok_or_else(|| {
        InputError::new(
            format!("{field}.body"),
            format!("\"{}\"", s.body),
            format!(
                "the name of a [[body]]: {}",
                names
                    .iter()
                    .map(|n| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        )
    })
}

/// The boundary part of side `s` of body `b` (field `field`): its selector, checked to select
/// at least one edge; the whole boundary when the side selects nothing.
fn surface(
    field: &str,
    s: &PairSideSection,
    b: usize,
    bodies: &BodySet,
    gmsh: Option<&GmshMesh>,
) -> Result<ContactSurface, InputError> {
    let sel = if s.sides.is_empty() && s.where_.is_none() && s.group.is_none() {
        BoundarySelector::Predicate(Arc::new(|_| true))
    } else {
        selector(
            field,
            Selection {
                sides: &s.sides,
                where_: s.where_.as_ref(),
                group: s.group.as_ref(),
            },
            gmsh,
        )?
    };
    let body = bodies.body(b);
    require_part_selected(&body.data().mesh, field, &sel)?;
    ContactSurface::new(b, body, &sel, field)
}

/// The law of section `p` (named `contact_pair[p]`).
fn law(p: usize, c: &ContactPairSection) -> Result<PairLaw, InputError> {
    let field = format!("contact_pair[{p}]");
    require_nonnegative(&format!("{field}.friction"), c.friction)?;
    let enforcement = match (c.enforcement, c.stiffness) {
        (EnforcementName::Lagrange, None) => Enforcement::Lagrange,
        (EnforcementName::Lagrange, Some(s)) => {
            return Err(InputError::new(
                format!("{field}.stiffness"),
                s,
                "no stiffness with enforcement = \"lagrange\" (the multipliers need none; \
                 enforcement = \"penalty\" and \"compliant\" take one)",
            ))
        }
        (EnforcementName::Penalty, None) => {
            return Err(missing(
                format!("{field}.stiffness"),
                "the penalty stiffness ε > 0 of enforcement = \"penalty\"",
            ))
        }
        (EnforcementName::Penalty, Some(s)) => Enforcement::Penalty {
            stiffness: require_positive(&format!("{field}.stiffness"), s)?,
        },
        (EnforcementName::Compliant, None) => {
            return Err(missing(
                format!("{field}.stiffness"),
                "the stiffness ε > 0 of enforcement = \"compliant\"",
            ))
        }
        (EnforcementName::Compliant, Some(s)) => Enforcement::Compliant {
            stiffness: require_positive(&format!("{field}.stiffness"), s)?,
        },
    };
    if c.friction > 0.0 && matches!(enforcement, Enforcement::Penalty { .. }) {
        return Err(InputError::new(
            format!("{field}.friction"),
            c.friction,
            "0 with enforcement = \"penalty\" (friction needs a normal multiplier, enforcement = \
             \"lagrange\" or \"compliant\": its stick and slip conditions are written in it)",
        ));
    }
    Ok(PairLaw {
        enforcement,
        friction: c.friction,
    })
}

/// The contact pairs of the sections (a two-pass section gives two), each with its origin;
/// `gmsh[b]` is body b's Gmsh file, if it was read from one.
pub(super) fn pairs(
    sections: &[ContactPairSection],
    names: &[String],
    bodies: &BodySet,
    gmsh: &[Option<GmshMesh>],
) -> Result<(Vec<ContactPair>, Vec<PairOrigin>), Error> {
    let mut out = Vec::new();
    let mut origins = Vec::new();
    for (p, c) in sections.iter().enumerate() {
        let field = format!("contact_pair[{p}]");
        let law = law(p, c)?;
        let sb = body_index(&format!("{field}.slave"), &c.slave, names)?;
        let slave = surface(
            &format!("{field}.slave"),
            &c.slave,
            sb,
            bodies,
            gmsh[sb].as_ref(),
        )?;
        match (&c.master, &c.foundation) {
            (Some(_), Some(_)) => {
                return Err(InputError::new(
                    format!("{field}.foundation"),
                    "(given with master)",
                    "either master (another body) or foundation",
                )
                .into())
            }
            (None, None) => {
                return Err(missing(
                    format!("{field}.master"),
                    "master = { body = \"name\", … } or foundation = { level = y }",
                )
                .into())
            }
            (None, Some(f)) => {
                if c.pass == Pass::Two {
                    return Err(InputError::new(
                        format!("{field}.pass"),
                        "\"two\"",
                        "\"single\" against the foundation (the rigid foundation has no nodes \
                         to be a slave)",
                    )
                    .into());
                }
                let level = require_finite(&format!("{field}.foundation.level"), f.level)?;
                out.push(ContactPair {
                    slave,
                    master: PairMaster::Foundation(Foundation::horizontal(level)),
                    law,
                });
                origins.push(PairOrigin {
                    section: p,
                    exchanged: false,
                });
            }
            (Some(m), None) => {
                let mb = body_index(&format!("{field}.master"), m, names)?;
                if mb == sb {
                    return Err(InputError::new(
                        format!("{field}.master.body"),
                        format!("\"{}\"", m.body),
                        format!(
                            "a body other than the slave's (\"{}\": self-contact is not modelled)",
                            c.slave.body
                        ),
                    )
                    .into());
                }
                let master = surface(&format!("{field}.master"), m, mb, bodies, gmsh[mb].as_ref())?;
                if c.pass == Pass::Two {
                    out.push(ContactPair {
                        slave: slave.clone(),
                        master: PairMaster::Surface(master.clone()),
                        law,
                    });
                    origins.push(PairOrigin {
                        section: p,
                        exchanged: false,
                    });
                    out.push(ContactPair {
                        slave: master,
                        master: PairMaster::Surface(slave),
                        law,
                    });
                    origins.push(PairOrigin {
                        section: p,
                        exchanged: true,
                    });
                } else {
                    out.push(ContactPair {
                        slave,
                        master: PairMaster::Surface(master),
                        law,
                    });
                    origins.push(PairOrigin {
                        section: p,
                        exchanged: false,
                    });
                }
            }
        }
    }
    require_no_node_twice(&out, &origins)?;
    Ok((out, origins))
}

/// What a pair's master is, for comparing pairs: a body, or the foundation at a level.
fn master_key(m: &PairMaster) -> (Option<usize>, u64) {
    match m {
        PairMaster::Surface(s) => (Some(s.body), 0),
        PairMaster::Foundation(f) => (None, f.level.to_bits()),
    }
}

/// No slave node is constrained twice against the same master (two sections, or a two-pass
/// section and another, whose slave parts share a node): its two identical constraint rows would
/// make the step's matrix singular.
fn require_no_node_twice(pairs: &[ContactPair], origins: &[PairOrigin]) -> Result<(), InputError> {
    for (j, pj) in pairs.iter().enumerate() {
        for (i, pi) in pairs[..j].iter().enumerate() {
            if pi.slave.body != pj.slave.body || master_key(&pi.master) != master_key(&pj.master) {
                continue;
            }
            if let Some(node) = pj.slave.nodes.iter().find(|n| pi.slave.nodes.contains(n)) {
                let name = |o: PairOrigin| {
                    if o.exchanged {
                        format!("contact_pair[{}].pass", o.section)
                    } else {
                        format!("contact_pair[{}].slave", o.section)
                    }
                };
                return Err(InputError::new(
                    name(origins[j]),
                    format!(
                        "(shares node {node} of its slave body with {})",
                        name(origins[i])
                    ),
                    "slave parts that share no node against the same master (a node \
                     constrained twice makes the step's matrix singular)",
                ));
            }
        }
    }
    Ok(())
}
