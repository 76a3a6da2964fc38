//! The Newton matrix of a multibody step: the bodies' blocks and the contact candidates' rows and
//! columns on one structurally symmetric sparse pattern, factored by sparse LU.
//!
//! Unknowns: the increment of every body's free dofs (U), then λ_N and λ_T of the candidates. The
//! bodies' blocks (α M + the scheme's tangent, and the skew part of Gonzalez's discrete-gradient
//! tangent) are block diagonal; a candidate couples its slave node, its master segment's nodes and
//! its multipliers (an 8 × 8 local matrix, not symmetric: the force direction of the midpoint and
//! energy–momentum schemes is not the constraint's gradient at t_{n+1}). The matrix J = S + W is
//! stored as its symmetric and skew parts on the upper triangle of the pattern ([`SparseLu`]).
//! The pattern is laid out per candidate on a *patch*: its slave node and the nodes of its master
//! segment and of the two neighbouring segments, so that a node switching to the next segment
//! (which happens within a step as it slides) keeps the layout; the pattern is analyzed again only
//! when a candidate is added or dropped or leaves its patch.

use crate::error::SolveError;
use crate::fem::sparse::SymmetricPattern;
use crate::model::dynamic::body::ElasticBody;
use crate::model::multibody::bodies::BodySet;
use crate::model::multibody::constraint::{Candidate, Local88, PairLaw};
use crate::solve::sparse_lu::SparseLu;

const NONE: usize = usize::MAX;

/// The unknowns of a candidate's patch: 10 coordinates (the slave node and up to four master
/// nodes), λ_N and λ_T.
pub const PATCH: usize = 12;

/// The coordinates' dofs of a patch (the slave node first; `None`: held or absent).
pub type PatchDofs = [Option<usize>; 10];

/// The layout and the factorization of the step system.
pub struct StepSystem {
    n_u: usize,
    pattern: SymmetricPattern,
    /// Per body: the system slot of each slot of the body's pattern.
    body_slots: Vec<Vec<usize>>,
    /// Per candidate: its patch's unknowns (10 coordinates, λ_N, λ_T) and the slot of each entry
    /// (p, q) of the patch.
    unknowns: Vec<[Option<usize>; PATCH]>,
    /// The pair of each candidate (its law decides its multipliers).
    pairs: Vec<usize>,
    slots: Vec<[usize; PATCH * PATCH]>,
    lu: SparseLu,
    sym: Vec<f64>,
    skew: Vec<f64>,
    analyses: usize,
}

impl std::fmt::Debug for StepSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "StepSystem({} unknowns, {} candidates, {} entries)",
            self.order(),
            self.unknowns.len(),
            self.pattern.nnz()
        )
    }
}

impl StepSystem {
    /// Numbers the candidates' multipliers after the bodies' dofs and analyzes the pattern of
    /// their patches (`patches[i]`: candidate i's coordinates, which contain its current dofs).
    pub fn new(
        bodies: &BodySet,
        candidates: &mut [Candidate],
        patches: &[PatchDofs],
        laws: &[PairLaw],
    ) -> Result<Self, SolveError> {
        let n_u = bodies.dofs();
        let mut next = n_u;
        for c in candidates.iter_mut() {
            let law = &laws[c.pair];
            c.ln = law.has_normal_multiplier().then(|| {
                next += 1;
                next - 1
            });
            c.lt = law.has_friction().then(|| {
                next += 1;
                next - 1
            });
        }
        let n = next;
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for b in 0..bodies.len() {
            let p = bodies.body(b).pattern();
            let o = bodies.range(b).start;
            for j in 0..p.order() {
                for &i in &p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]] {
                    cols[o + j].push(o + i);
                }
            }
        }
        let unknowns: Vec<[Option<usize>; PATCH]> = candidates
            .iter()
            .zip(patches)
            .map(|(c, patch)| {
                let mut u = [None; PATCH];
                u[..10].copy_from_slice(patch);
                u[10] = c.ln;
                u[11] = c.lt;
                u
            })
            .collect();
        for u in &unknowns {
            for p in u.iter().flatten() {
                for q in u.iter().flatten() {
                    if p <= q {
                        cols[*q].push(*p);
                    }
                }
            }
        }
        let pattern = SymmetricPattern::from_columns(cols);
        let slot = |i: usize, j: usize| pattern.slot(i, j).unwrap_or(NONE);
        let body_slots = (0..bodies.len())
            .map(|b| {
                let p = bodies.body(b).pattern();
                let o = bodies.range(b).start;
                let mut map = Vec::with_capacity(p.nnz());
                for j in 0..p.order() {
                    for &i in &p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]] {
                        map.push(slot(o + i, o + j));
                    }
                }
                map
            })
            .collect();
        let slots = unknowns
            .iter()
            .map(|u| {
                let mut s = [NONE; PATCH * PATCH];
                for p in 0..PATCH {
                    for q in 0..PATCH {
                        if let (Some(gp), Some(gq)) = (u[p], u[q]) {
                            s[p * PATCH + q] = slot(gp, gq);
                        }
                    }
                }
                s
            })
            .collect();
        let lu =
            SparseLu::analyze_supernodal(&pattern, "multibody step matrix [αM + K, −G; C, ·]")?;
        let nnz = pattern.nnz();
        Ok(Self {
            n_u,
            pattern,
            body_slots,
            pairs: candidates.iter().map(|c| c.pair).collect(),
            unknowns,
            slots,
            lu,
            sym: vec![0.0; nnz],
            skew: vec![0.0; nnz],
            analyses: 1,
        })
    }

    /// Whether the layout serves these candidates: the same pairs in the same order, and every
    /// candidate's current coordinates within its patch (the multipliers are numbered by
    /// [`Self::number`]).
    pub fn serves(&self, candidates: &[Candidate]) -> bool {
        self.unknowns.len() == candidates.len()
            && self
                .unknowns
                .iter()
                .zip(&self.pairs)
                .zip(candidates)
                .all(|((u, p), c)| {
                    *p == c.pair && c.dofs.iter().flatten().all(|d| u[..10].contains(&Some(*d)))
                })
    }

    /// Gives `candidates` the multipliers' numbering of the layout (after [`Self::serves`]).
    pub fn number(&self, candidates: &mut [Candidate]) {
        for (u, c) in self.unknowns.iter().zip(candidates) {
            c.ln = u[10];
            c.lt = u[11];
        }
    }

    /// The number of unknowns.
    pub fn order(&self) -> usize {
        self.pattern.order()
    }

    /// The number of body dofs (the multipliers follow).
    pub fn body_dofs(&self) -> usize {
        self.n_u
    }

    /// The number of stored entries (upper triangle).
    pub fn nnz(&self) -> usize {
        self.pattern.nnz()
    }

    /// Zeroes the matrix.
    pub fn clear(&mut self) {
        self.sym.iter_mut().for_each(|v| *v = 0.0);
        self.skew.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Adds body b's symmetric block `sym` and skew block `skew` (values on its pattern; `skew`
    /// may be empty).
    pub fn add_body(&mut self, b: usize, sym: &[f64], skew: &[f64]) {
        for (s, &t) in self.body_slots[b].iter().enumerate() {
            self.sym[t] += sym[s];
        }
        if !skew.is_empty() {
            for (s, &t) in self.body_slots[b].iter().enumerate() {
                self.skew[t] += skew[s];
            }
        }
    }

    /// Adds candidate `c`'s local matrix (J_pq: row p, column q; p, q index its six coordinates
    /// `dofs`, λ_N and λ_T).
    pub fn add_candidate(&mut self, c: usize, dofs: &[Option<usize>; 6], jac: &Local88) {
        let u = &self.unknowns[c];
        // the patch position of each local unknown
        let mut at = [None; 8];
        for (p, d) in dofs.iter().enumerate() {
            if let Some(d) = d {
                at[p] = u[..10].iter().position(|x| *x == Some(*d));
            }
        }
        at[6] = u[10].map(|_| 10);
        at[7] = u[11].map(|_| 11);
        let slots = &self.slots[c];
        for p in 0..8 {
            let Some(ip) = at[p] else { continue };
            let Some(gp) = u[ip] else { continue };
            for q in 0..8 {
                let Some(iq) = at[q] else { continue };
                let Some(gq) = u[iq] else { continue };
                let v = jac[(p, q)];
                if v == 0.0 {
                    continue;
                }
                let s = slots[ip * PATCH + iq];
                if gp == gq {
                    self.sym[s] += v;
                } else if gp < gq {
                    self.sym[s] += 0.5 * v;
                    self.skew[s] += 0.5 * v;
                } else {
                    self.sym[s] += 0.5 * v;
                    self.skew[s] -= 0.5 * v;
                }
            }
        }
    }

    /// Adds v to the diagonal entry of unknown i (a multiplier's row).
    pub fn add_diagonal(&mut self, i: usize, v: f64) {
        if let Some(s) = self.pattern.diagonal_slot(i) {
            self.sym[s] += v;
        }
    }

    /// Factors the matrix and solves J x = b in place.
    pub fn solve(&mut self, x: &mut [f64]) -> Result<(), SolveError> {
        self.lu.factor_solve(&self.sym, &self.skew, x)
    }

    /// The number of symbolic analyses (1 per layout).
    pub fn analyses(&self) -> usize {
        self.analyses
    }
}
