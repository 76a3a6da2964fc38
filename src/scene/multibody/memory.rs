//! The memory a multibody run holds, estimated from the counts alone and refused above the limit
//! before anything is allocated ([`crate::scene::memory`]).
//!
//! Per dof of the system (2 per node, all bodies) the operators, the step's sparse LU factor
//! (fill ~ n log₂ n) and the work vectors, as for a dynamic body; per output time the
//! displacement and velocity and at most one contact state (12 values) per node; per step the
//! audit's record (about 40 values) and, in `verify scene`, each body's centre-of-mass velocity.

use crate::error::InputError;
use crate::scene::memory::require_memory;
use crate::scene::multibody::format::MultibodySceneFile;

const HOW: &str = "8 B × [dofs (70 + 4 log₂ dofs) + output times (2 dofs + 12 nodes) + \
                   (40 + 2 bodies) (N + 1)]";

/// The estimate for `nodes[b]` nodes of body b, against the limit: the key named is the one that
/// sets the largest body's size (`fields[b]` = (key, value as written)), or `time.steps` when the
/// steps' records outweigh the meshes.
pub(super) fn require_run_memory(
    file: &MultibodySceneFile,
    nodes: &[f64],
    fields: &[(String, String)],
) -> Result<(), InputError> {
    let total_nodes: f64 = nodes.iter().sum();
    let dofs = 2.0 * total_nodes;
    let outputs = file.output.times.len() as f64;
    let per_mesh = 8.0 * dofs * (70.0 + 4.0 * dofs.max(2.0).log2())
        + 8.0 * outputs * (2.0 * dofs + 12.0 * total_nodes);
    let per_steps = 8.0 * (40.0 + 2.0 * nodes.len() as f64) * (file.time.steps as f64 + 1.0);
    let total = per_mesh + per_steps;
    let largest = nodes
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(b, _)| b);
    match largest {
        Some(b) if per_mesh >= per_steps => require_memory(&fields[b].0, &fields[b].1, total, HOW),
        _ => require_memory("time.steps", file.time.steps, total, HOW),
    }
}
