//! Forward dynamics through the mass matrix for a floating-base robot (h
//! and g are [`bias`](crate::algorithms::bias)'s functions, whose inverse
//! dynamics goes to [`super::rnea::rnea`] for a floating model): q̈
//! solves M q̈ = τ − h by the sparse LᵀDL factorisation, the base's six
//! coordinates a chain ahead of the joints (a dense 6×6 block at the top,
//! no fill-in between branches).

use super::crba::crba;
use super::rnea::rnea;
use super::{check_sizes, velocity_parent};
use crate::algorithms::{ldlt, Loads, Workspace};
use crate::model::Model;
use crate::Scalar;

/// q̈ = M⁻¹(τ − h − Jᵀ F_tip) with M from [`crba`] and its sparse LᵀDL
/// factorisation; arguments as [`aba`](super::aba::aba), which computes the
/// same in O(n).
pub fn forward_dynamics_ldlt<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    if model.has_mimic() {
        // the recursions below take one coordinate per body: the dispatching form expands them
        return crate::algorithms::forward_dynamics::forward_dynamics_ldlt(model, ws, q, qd, tau, loads, qdd);
    }
    let nv = model.nv();
    check_sizes(model, "floating forward_dynamics_ldlt", q.len(), &[qd.len(), tau.len(), qdd.len()]);
    rnea(model, ws, q, Some(qd), None, loads, qdd);
    for (x, t) in qdd.iter_mut().zip(tau) {
        *x = *t - *x;
    }
    let mut m = std::mem::take(&mut ws.mat);
    crba(model, ws, q, loads, &mut m);
    ldlt::factorise_tree(nv, |k| velocity_parent(model, k), &mut m);
    ldlt::solve_tree(nv, |k| velocity_parent(model, k), &m, qdd);
    ws.mat = m;
}
