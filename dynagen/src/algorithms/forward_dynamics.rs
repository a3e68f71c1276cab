//! Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip), as *Modern
//! Robotics* §8.5 writes it: M by the composite-rigid-body algorithm, the
//! right-hand side by one inverse dynamics call with q̈ = 0, and a sparse
//! LᵀDL solve. The articulated-body algorithm ([`aba`](super::aba::aba))
//! computes the same thing and is the default elsewhere, being more accurate
//! on long chains; this path is kept as its check and for comparison.

use super::crba::crba;
use super::ldlt;
use super::rnea::rnea;
use super::{Loads, Workspace};
use crate::model::Model;
use crate::Scalar;

/// Forward dynamics through the factorised mass matrix; see the module
/// documentation. Arguments as [`aba`](super::aba::aba): the payloads
/// enter M and h, the armature M's diagonal.
pub fn forward_dynamics_ldlt<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    if model.is_floating() && !model.has_mimic() {
        return super::floating::forward_dynamics::forward_dynamics_ldlt(model, ws, q, qd, tau, loads, qdd);
    }
    let n = model.nv();
    assert!(tau.len() == n && qdd.len() == n, "forward_dynamics_ldlt: slices must have the model's {n} joints");
    // h + JᵀF_tip into qdd, then the right-hand side τ − that.
    rnea(model, ws, q, Some(qd), None, loads, qdd);
    for i in 0..n {
        qdd[i] = tau[i] - qdd[i];
    }
    solve_with_mass_matrix(model, ws, q, loads, qdd);
}

/// Solves M(q) x = b in place (`b` becomes x): M by [`crba`] (with the
/// inertias of `loads`), then its sparse LᵀDL factorisation.
pub(crate) fn solve_with_mass_matrix<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    loads: Loads<'_, S>,
    b: &mut [S],
) {
    let mut m = std::mem::take(&mut ws.mat);
    crba(model, ws, q, loads, &mut m);
    ldlt::factorise(model, &mut m);
    ldlt::solve(model, &m, b);
    ws.mat = m;
}
