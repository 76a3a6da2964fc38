//! The memory a multibody run holds, estimated from the counts alone and refused above the limit
//! before anything is allocated ([`crate::scene::memory`]).
//!
//! Per dof of the system (2 per node, all bodies) the operators and the work vectors, as for a
//! dynamic body, and the step's sparse LU factor. The factor is the supernodal LU, whose structure
//! is that of the Cholesky factor of AᵀA under the column ordering: its columns hold up to the
//! front of the eliminated part of the mesh. For a planar mesh under a profile-type ordering the
//! front grows as √n (a mesh of n unknowns is crossed by fronts of ~√n unknowns), so the factor
//! holds ~ c n √n numbers. c = 22: the thin ring (one cell across, 10³ and 10⁴ cells around: a
//! step matrix of 4 540 and 44 980 unknowns) peaked at 21.3 √dofs doubles per dof (dofs: 2 per node; the rest of the step matrix, its multipliers, rides on them), the slenderest
//! shape measured; squares and the examples' rings stay far below (fill ~ n log n). The estimate
//! is held against measured peaks by `measured_peaks_stay_below_the_memory_estimate` (in
//! verification/tests/robustness_regressions.rs), the thin ring among them.
//! per output time and per step
//! what is recorded and its text ([`require_run_memory`]); the files against the disk limit.

use crate::error::InputError;
use crate::scene::memory::{distinct_times, RunSize, TEXT_BYTES};
use crate::scene::multibody::format::MultibodySceneFile;

/// c of the LU factor's c n √n numbers (the module's comment: measured 21.3 on the thin ring).
const LU_FRONT: f64 = 22.0;

/// The estimate for `nodes[b]` nodes of body b, against the memory and disk limits: the mesh
/// key named is the one that sets the largest body's size (`fields[b]` = (key, value as
/// written)). Per mesh the operators and the step's LU factor, 8 B × dofs (70 + 22 √dofs); per distinct output time
/// two copies (the solver's and the recorder's) of u, v and a contact state (12 values) per node
/// and the text of u and v in solution.json (VTK: 6 vectors more); per step the record and the
/// history row (40 + 2 bodies values) and their text (60 + 4 bodies numbers measured in
/// solution.json, history.csv and the plots).
pub(super) fn require_run_memory(
    file: &MultibodySceneFile,
    nodes: &[f64],
    fields: &[(String, String)],
) -> Result<(), InputError> {
    let total_nodes: f64 = nodes.iter().sum();
    let dofs = 2.0 * total_nodes;
    let bodies = nodes.len() as f64;
    let vtk = if file.output.vtk { 1.0 } else { 0.0 };
    let largest = nodes
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(b, _)| b);
    let run = RunSize {
        mesh_key: fields.get(largest).cloned().unwrap_or_default(),
        outputs: distinct_times(&file.output.times) as f64,
        steps: file.time.steps as f64,
        memory: [
            8.0 * dofs * (70.0 + LU_FRONT * dofs.sqrt()),
            8.0 * 2.0 * (2.0 * dofs + 12.0 * total_nodes)
                + 2.0 * dofs * TEXT_BYTES
                + vtk * 6.0 * dofs * (8.0 + TEXT_BYTES),
            8.0 * (40.0 + 2.0 * bodies) + (60.0 + 4.0 * bodies) * TEXT_BYTES,
        ],
        disk: [
            3.0 * dofs * TEXT_BYTES,
            dofs * TEXT_BYTES * (2.0 + 6.0 * vtk),
            (60.0 + 4.0 * bodies) * TEXT_BYTES,
        ],
        memory_how:
            "16 MiB + 8 B × dofs (70 + 22 √dofs: the step's LU) + output times × [2 × 8 B × \
                     (2 dofs + 12 nodes) + 2 dofs × 40 B of text; VTK: 6 dofs × 48 B] + (N + 1) \
                     × [8 B × (40 + 2 bodies) + 40 B × (60 + 4 bodies)]",
        disk_how: "40 B a number: output times × dofs (2, VTK 8) + (N + 1) × (60 + 4 bodies)",
    };
    run.require()
}
