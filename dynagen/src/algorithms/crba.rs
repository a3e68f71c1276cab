//! The mass matrix M(q) by the composite-rigid-body algorithm
//! (Featherstone, *Rigid Body Dynamics Algorithms*, §6.2), and by the
//! *Modern Robotics* construction — n inverse dynamics calls with unit
//! accelerations — kept as an independent check.

use super::joint::{force_to_parent, inertia_times_subspace, inertia_to_parent, project};
use super::rnea::{rnea, update_joint_transforms};
use super::{BodyInertia, Workspace};
use crate::model::Model;
use crate::spatial::Inertia;
use crate::Scalar;

/// M(q) by the composite-rigid-body algorithm, written row-major into `m`
/// (n×n). Both triangles are written, each entry computed once.
///
/// # Panics
/// If `q` does not have the model's number of joints or `m` is not n×n.
pub fn crba<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], m: &mut [S]) {
    composite_rigid_body(model, ws, q, &[], m);
}

/// [`crba`] with extra inertias carried by bodies (`payloads`, each in its
/// body's frame): each is added to its body's inertia before the composite
/// inertias are summed up the tree, exactly as if the body's own inertia
/// were the sum. Code generation uses it for payloads given at run time;
/// with `&[]` it is [`crba`].
///
/// # Panics
/// As [`crba`], and if a payload's body is not a body of the model.
pub fn crba_with_payloads<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    payloads: &[BodyInertia<S>],
    m: &mut [S],
) {
    composite_rigid_body(model, ws, q, payloads, m);
}

/// The algorithm of [`crba`] and [`crba_with_payloads`], inlined into both
/// so that `crba` is compiled without the payloads.
#[inline(always)]
fn composite_rigid_body<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    payloads: &[BodyInertia<S>],
    m: &mut [S],
) {
    let n = model.dof();
    assert!(q.len() == n && m.len() == n * n && ws.dof() == n, "crba: slices must fit the model's {n} joints");
    assert!(payloads.iter().all(|p| p.body < n), "crba: a payload's body is not one of the model's {n}");
    update_joint_transforms(model, ws, q);
    // Entries of joints on different branches stay zero.
    m.fill(S::zero());
    for (i, b) in model.bodies.iter().enumerate() {
        ws.inertia[i] = Inertia::from_f64(&b.inertia);
    }
    for p in payloads {
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
        rnea(model, ws, q, None, Some(&e), None, &[], &mut col);
        e[j] = S::zero();
        for i in 0..n {
            m[i * n + j] = col[i];
        }
    }
}
