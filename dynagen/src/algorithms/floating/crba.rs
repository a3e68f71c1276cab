//! The mass matrix of a floating-base robot by the composite-rigid-body
//! algorithm: NV × NV, its top-left 6×6 block the composite inertia of the
//! whole robot at the base (base frame), its base rows the momentum each
//! joint rate gives the whole robot, and its joint block the fixed-base
//! mass matrix of the same tree.

use super::{base_inertia, check_tree_sizes};
use crate::algorithms::joint::{force_to_parent, inertia_times_subspace, inertia_to_parent, joint_transform, project};
use crate::algorithms::{BodyInertia, Loads, Workspace, BASE_BODY};
use crate::model::Model;
use crate::spatial::{Force, Inertia};
use crate::Scalar;

/// Places the bodies (`ws.x`) and sums the composite inertias up the tree
/// (`ws.inertia[i]`: body i's subtree, in its frame, payloads included,
/// those on the base too);
/// returns the whole robot's composite inertia at the base, in the base
/// frame.
#[inline(always)]
pub fn composite_inertia<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    payloads: &[BodyInertia<S>],
) -> Inertia<S> {
    for (i, b) in model.bodies.iter().enumerate() {
        ws.x[i] = joint_transform(&b.joint, q[7 + i]);
        ws.inertia[i] = b.inertia_in();
    }
    for p in payloads.iter().filter(|p| p.body != BASE_BODY) {
        ws.inertia[p.body] = ws.inertia[p.body].add(&p.inertia);
    }
    let mut ic0 = base_inertia(model, payloads);
    for (i, b) in model.bodies.iter().enumerate().rev() {
        let moved = inertia_to_parent(&b.joint, &ws.x[i], &ws.inertia[i]);
        match b.parent {
            Some(p) => ws.inertia[p] = ws.inertia[p].add(&moved),
            None => ic0 = ic0.add(&moved),
        }
    }
    ic0
}

/// `Iᶜ_i S_i` carried up from body `i` to the base (base frame): the
/// momentum of the whole robot, about the base origin, per unit rate of
/// joint `i` (a column of the centroidal momentum matrix in the base
/// frame); `each` sees the projection on every ancestor joint on the way
/// `(ancestor, Sᵀ F)`. After [`composite_inertia`].
#[inline(always)]
pub(crate) fn carry_to_base<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    i: usize,
    mut each: impl FnMut(usize, S),
) -> Force<S> {
    let mut f = inertia_times_subspace(&model.bodies[i].joint, &ws.inertia[i]);
    each(i, project(&model.bodies[i].joint, &f));
    let mut j = i;
    loop {
        f = force_to_parent(&model.bodies[j].joint, &ws.x[j], &f);
        match model.bodies[j].parent {
            Some(p) => {
                j = p;
                each(j, project(&model.bodies[j].joint, &f));
            }
            None => return f,
        }
    }
}

/// M(q) of a floating-base model (NV × NV, row-major, both triangles) by
/// the composite-rigid-body algorithm. Of `loads` only the payloads and the
/// armature (on the joints) are read.
///
/// # Panics
/// If `q` is not NQ long, `m` not NV × NV, or the model's root not floating.
pub fn crba<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], loads: Loads<'_, S>, m: &mut [S]) {
    let (n, nv) = (model.bodies.len(), model.tree_nv());
    check_tree_sizes(model, "floating crba", q.len(), &[]);
    assert!(m.len() == nv * nv, "floating crba: m must be {nv}×{nv}");
    loads.check(n, "floating crba");
    let ic0 = composite_inertia(model, ws, q, loads.payloads);
    m.fill(S::zero());
    for (r, row) in ic0.to_matrix().iter().enumerate() {
        m[r * nv..r * nv + 6].copy_from_slice(row);
    }
    for i in (0..n).rev() {
        let f = carry_to_base(model, ws, i, |j, mij| {
            m[(6 + i) * nv + 6 + j] = mij;
            m[(6 + j) * nv + 6 + i] = mij;
        });
        for (k, x) in f.to_array().into_iter().enumerate() {
            m[(6 + i) * nv + k] = x;
            m[k * nv + 6 + i] = x;
        }
    }
    for (i, &a) in loads.armature.unwrap_or_default().iter().enumerate() {
        if a != 0.0 {
            m[(6 + i) * nv + 6 + i] += S::from_f64(a);
        }
    }
}
