//! The gravity torques as code generation traces them when the model has
//! point masses on prismatic joints without children (a gripper's fingers,
//! as [`center_prismatic_leaves`](crate::codegen::center_prismatic_leaves) and
//! [`regroup_inertia`](crate::codegen::regroup_inertia) leave them).
//!
//! Under gravity alone nothing moves, and the weight of a point mass `m` at
//! `p(q) = p₀ + d q` in its parent's frame (`d` the joint's axis there) is
//! the force `m a` and the moment `p(q) × m a` on the parent (`a` the
//! parent's acceleration, `−g` in its frame), and `m d·a` on its own joint.
//! Split at `q = 0`, that is the weight of the same mass fixed to the parent
//! at `p₀`, which the regrouping then carries down the chain like any other
//! constant inertia (the parent's weight often vanishes from the recursion),
//! plus a mass-free first moment `m d q` on the parent, whose weight is the
//! moment `m q d × a` alone. [`fold_for_gravity`] makes that model and
//! [`gravity_torques`] runs the generic recursion on it with the first
//! moments as payloads ([`rnea`]), then sets each folded
//! joint's torque to `m d·a`. (The leaves are point masses at their origins
//! only in a model prepared with the regrouping, or in a model written so;
//! the fold regroups what it moved, also in the latter.) The other
//! functions move the masses, and
//! there the fold does not pay (their finger terms are near the minimum
//! already); they keep the model as it is.

use crate::algorithms::rnea::rnea;
use crate::algorithms::{BodyInertia, Loads, Workspace};
use crate::codegen::regroup_inertia;
use crate::model::{JointKind, Model};
use crate::spatial::{Inertia, Sym3, Vec3};
use crate::Scalar;

/// A point mass on a prismatic joint without children, folded into its
/// parent for the gravity torques.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FoldedLeaf {
    /// The body (and joint) index.
    leaf: usize,
    /// Its parent.
    parent: usize,
    /// `m d`: its mass times its joint's axis, in the parent's frame.
    moment_per_q: Vec3<f64>,
}

/// Whether body `i` is a point mass at its origin on a prismatic joint,
/// with a parent and without children.
fn is_point_mass_leaf(model: &Model, i: usize) -> bool {
    let b = &model.bodies[i];
    b.joint.kind == JointKind::Prismatic
        && b.parent.is_some()
        && b.inertia.mass > 0.0
        && b.inertia.h.0 == [0.0; 3]
        && b.inertia.ibar.0 == [0.0; 6]
        && !model.bodies.iter().any(|c| c.parent == Some(i))
}

/// `model` (prepared for code generation) with every point-mass prismatic
/// leaf's mass moved to its parent at the leaf's place at `q = 0`, then
/// regrouped again (what was regrouped already moves nothing more), and
/// the leaves folded; `None` if there are none.
pub(crate) fn fold_for_gravity(model: &Model) -> Option<(Model, Vec<FoldedLeaf>)> {
    // A leaf's torque is its own joint's: with mimic joints it would belong
    // in its master's column. Folded and projected, the mimic Panda's g took
    // 184 operations against 169 unfolded (the recursion projects it).
    if model.has_mimic() {
        return None;
    }
    let leaves: Vec<FoldedLeaf> = (0..model.dof())
        .filter(|&i| is_point_mass_leaf(model, i))
        .map(|i| {
            let b = &model.bodies[i];
            let d = b.joint.placement.rot.mul_vec(&b.joint.axis);
            FoldedLeaf {
                leaf: i,
                parent: b.parent.expect("a leaf has a parent"),
                moment_per_q: d.scale(b.inertia.mass),
            }
        })
        .collect();
    if leaves.is_empty() {
        return None;
    }
    let mut m = model.clone();
    for l in &leaves {
        let b = &m.bodies[l.leaf];
        let fixed = b.joint.placement.inertia_to_parent(&b.inertia);
        m.bodies[l.parent].inertia = m.bodies[l.parent].inertia.add(&fixed);
        m.bodies[l.leaf].inertia = Inertia::zero();
    }
    Some((regroup_inertia(&m), leaves))
}

/// The gravity torques g(q) of the model [`fold_for_gravity`] was given,
/// from the folded `model` and its `leaves` (see the module documentation).
pub(crate) fn gravity_torques<S: Scalar>(
    model: &Model,
    leaves: &[FoldedLeaf],
    ws: &mut Workspace<S>,
    q: &[S],
    gravity: &Vec3<S>,
    g: &mut [S],
) {
    // One first moment per parent: Σ m d q over its leaves.
    let mut payloads: Vec<BodyInertia<S>> = Vec::new();
    for l in leaves {
        let h = Vec3::from_f64(&l.moment_per_q).scale(q[l.leaf]);
        match payloads.iter_mut().find(|p| p.body == l.parent) {
            Some(p) => p.inertia.h += h,
            None => payloads
                .push(BodyInertia { body: l.parent, inertia: Inertia { mass: S::zero(), h, ibar: Sym3::zero() } }),
        }
    }
    rnea(model, ws, q, None, None, Loads::new(Some(gravity), &[], &payloads), g);
    for l in leaves {
        g[l.leaf] = ws.a[l.parent].lin.dot(&Vec3::from_f64(&l.moment_per_q));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::bias;
    use crate::codegen::{prepare::prepare_model, CodegenOptions};

    /// The folded gravity torques of the prepared Panda equal the generic
    /// solver's on the original model, and the fold found both fingers.
    #[test]
    fn folded_gravity_torques_equal_the_generic_ones() {
        let path = format!("{}/robots/panda.urdf", env!("CARGO_MANIFEST_DIR"));
        let original = Model::from_urdf_file(path).unwrap();
        let (prepared, _) = prepare_model(&original, &CodegenOptions::default());
        let (folded, leaves) = fold_for_gravity(&prepared).unwrap();
        assert_eq!(leaves.iter().map(|l| (l.leaf, l.parent)).collect::<Vec<_>>(), [(7, 6), (8, 6)]);
        assert!(folded.bodies[7].inertia.mass == 0.0 && folded.bodies[6].inertia.mass == 0.0);
        let n = original.dof();
        let gravity = original.gravity;
        for k in 0..5 {
            let q: Vec<f64> = (0..n).map(|i| 0.37 * (i + k) as f64 - 1.2 + 0.013 * (k * i) as f64).collect();
            let mut want = vec![0.0; n];
            bias::gravity_torques(&original, &mut Workspace::new(&original), &q, &gravity, &mut want);
            let mut got = vec![0.0; n];
            gravity_torques(&folded, &leaves, &mut Workspace::new(&folded), &q, &gravity, &mut got);
            let norm = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            for (i, (x, y)) in got.iter().zip(&want).enumerate() {
                assert!((x - y).abs() <= 1e-13 * norm, "g[{i}] at state {k}: {x} vs {y}");
            }
        }
        // no prismatic leaves, nothing to fold
        let ur5 = Model::from_urdf_file(format!("{}/robots/ur5.urdf", env!("CARGO_MANIFEST_DIR"))).unwrap();
        assert!(fold_for_gravity(&prepare_model(&ur5, &CodegenOptions::default()).0).is_none());
    }
}
