//! The mass matrix M(q) by the composite-rigid-body algorithm
//! (Featherstone, *Rigid Body Dynamics Algorithms*, §6.2), and by the
//! *Modern Robotics* construction — n inverse dynamics calls with unit
//! accelerations — kept as an independent check.

use super::joint::{force_to_parent, inertia_times_subspace, inertia_to_parent, project};
use super::rnea::{rnea, update_joint_transforms};
use super::{Loads, Workspace};
use crate::model::Model;
use crate::Scalar;

/// M(q) by the composite-rigid-body algorithm, written row-major into `m`
/// (n×n; a floating model: NV×NV by
/// [`floating::crba`](super::floating::crba::crba)). Both triangles are written, each entry computed once. Of `loads`
/// only the inertias matter: each payload is added to its body's inertia
/// before the composite inertias are summed up the tree (exactly as if the
/// body's own inertia were the sum), and the armature to the diagonal.
///
/// A model with mimic joints: `Gᵀ M_tree G` ([`mimic`](super::mimic)).
///
/// # Panics
/// If `q` does not have the model's number of joints, `m` is not n×n, or a
/// payload's body is not a body of the model.
pub fn crba<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], loads: Loads<'_, S>, m: &mut [S]) {
    if model.has_mimic() {
        return super::mimic::crba(model, ws, q, loads, m);
    }
    crba_tree(model, ws, q, loads, m)
}

/// [`crba`] on the bodies' coordinates: M_tree, one row per body.
pub(crate) fn crba_tree<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], loads: Loads<'_, S>, m: &mut [S]) {
    if model.is_floating() {
        return super::floating::crba::crba(model, ws, q, loads, m);
    }
    let n = model.bodies.len();
    assert!(q.len() == n && m.len() == n * n && ws.dof() == n, "crba: slices must fit the model's {n} joints");
    loads.check(n, "crba");
    update_joint_transforms(model, ws, q);
    // Entries of joints on different branches stay zero.
    m.fill(S::zero());
    for (i, b) in model.bodies.iter().enumerate() {
        ws.inertia[i] = b.inertia_in();
    }
    // (a payload on the fixed base moves nothing)
    for p in loads.payloads.iter().filter(|p| p.body != super::BASE_BODY) {
        ws.inertia[p.body] = ws.inertia[p.body].add(&p.inertia);
    }
    for i in (0..n).rev() {
        let body = &model.bodies[i];
        // F = Iᶜ_i S_i, then carried up the chain of ancestors.
        let mut f = inertia_times_subspace(&body.joint, &ws.inertia[i]);
        m[i * n + i] = project(&body.joint, &f);
        let mut j = i;
        while let Some(p) = model.bodies[j].parent {
            f = force_to_parent(&model.bodies[j].joint, &ws.x[j], &f);
            j = p;
            let mij = project(&model.bodies[j].joint, &f);
            m[i * n + j] = mij;
            m[j * n + i] = mij;
        }
        if let Some(p) = body.parent {
            let ic = inertia_to_parent(&body.joint, &ws.x[i], &ws.inertia[i]);
            ws.inertia[p] = ws.inertia[p].add(&ic);
        }
    }
    for (i, &a) in loads.armature.unwrap_or_default().iter().enumerate() {
        if a != 0.0 {
            m[i * n + i] += S::from_f64(a);
        }
    }
}

/// M(q) column by column, as the Modern Robotics library computes it: column
/// j is the inverse dynamics with q̇ = 0, q̈ = e_j and no gravity. O(n²);
/// used as a check of [`crba`].
pub fn mass_matrix_by_unit_accelerations<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], m: &mut [S]) {
    let n = model.dof();
    assert!(m.len() == n * n, "mass_matrix_by_unit_accelerations: m must be {n}×{n}");
    let mut e = vec![S::zero(); n];
    let mut col = vec![S::zero(); n];
    for j in 0..n {
        e[j] = S::one();
        rnea(model, ws, q, None, Some(&e), Loads::none(), &mut col);
        e[j] = S::zero();
        for i in 0..n {
            m[i * n + j] = col[i];
        }
    }
}
