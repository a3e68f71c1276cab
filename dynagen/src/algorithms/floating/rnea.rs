//! Inverse dynamics of a floating-base robot by the recursive Newton-Euler
//! algorithm in body coordinates: the base's body twist and its derivative
//! start the forward pass (gravity as the base's fictitious acceleration
//! `−(0; Rᵀg)`), and the wrench left at the base after the backward pass is
//! `τ[0..6]`, the wrench that must act on the base (base frame, moment
//! about its origin first).

use super::{base_inertia, base_motion, check_tree_sizes, quaternion_rotation, write_force};
use crate::algorithms::joint::{add_motion, cross_motion, force_to_parent, joint_transform, motion_to_child, project};
use crate::algorithms::{Loads, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Motion, Transform, Vec3};
use crate::Scalar;

/// τ = M(q)q̈ + h(q, q̇) (+ Jᵀ F_tip) of a floating-base model.
///
/// - `q`: NQ entries (base position, quaternion (x, y, z, w), joints);
///   `qd`, `qdd`: NV entries (`None`: zero); `tau`: NV entries written.
/// - `loads`: gravity in the world frame; tip wrenches at frames (those on
///   the base too); payloads on bodies and on the base
///   ([`BASE_BODY`](crate::algorithms::BASE_BODY)); armature on the joints
///   (not the base).
///
/// # Panics
/// If a slice's length is not NQ or NV, or the model's root is not floating.
#[inline(always)]
pub fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    let n = model.bodies.len();
    let nv = model.tree_nv();
    check_tree_sizes(
        model,
        "floating rnea",
        q.len(),
        &[tau.len(), qd.map_or(nv, <[S]>::len), qdd.map_or(nv, <[S]>::len)],
    );
    loads.check(n, "floating rnea");
    let Loads { gravity, tips, payloads, armature } = loads;
    // The base: its twist, its acceleration with gravity as a fictitious
    // one, and the wrench that produces its motion.
    let v0 = qd.map_or(Motion::zero(), base_motion);
    let mut a0 = qdd.map_or(Motion::zero(), base_motion);
    if let Some(g) = gravity {
        a0.lin -= quaternion_rotation(&q[3..7]).tr_mul_vec(g);
    }
    let i0 = base_inertia(model, payloads);
    let mut f0 = i0.mul_motion(&a0);
    if qd.is_some() {
        f0 += v0.cross_force(&i0.mul_motion(&v0));
    }
    for (i, body) in model.bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[7 + i]);
        ws.x[i] = x;
        let (vp, ap) = match body.parent {
            Some(p) => (ws.v[p], ws.a[p]),
            None => (v0, a0),
        };
        let mut v = motion_to_child(joint, &x, &vp);
        let mut a = motion_to_child(joint, &x, &ap);
        if let Some(qd) = qd {
            add_motion(joint, &mut v, qd[6 + i]);
            a += cross_motion(joint, &v, qd[6 + i]);
        }
        if let Some(qdd) = qdd {
            add_motion(joint, &mut a, qdd[6 + i]);
        }
        let mut inertia = Inertia::<S>::from_f64(&body.inertia);
        for p in payloads.iter().filter(|p| p.body == i) {
            inertia = inertia.add(&p.inertia);
        }
        let mut f = inertia.mul_motion(&a);
        if qd.is_some() {
            f += v.cross_force(&inertia.mul_motion(&v));
        }
        ws.v[i] = v;
        ws.a[i] = a;
        ws.f[i] = f;
    }
    for tip in tips {
        let frame = &model.frames[tip.frame];
        let w = Transform::<S>::from_f64(&frame.placement).force_to_parent(&tip.wrench);
        match frame.body {
            Some(b) => ws.f[b] += w,
            None => f0 += w,
        }
    }
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let f = ws.f[i];
        tau[6 + i] = project(&body.joint, &f);
        let fp = force_to_parent(&body.joint, &ws.x[i], &f);
        match body.parent {
            Some(p) => ws.f[p] += fp,
            None => f0 += fp,
        }
    }
    write_force(&f0, tau);
    if let (Some(armature), Some(qdd)) = (armature, qdd) {
        for (i, &a) in armature.iter().enumerate() {
            if a != 0.0 {
                tau[6 + i] += S::from_f64(a) * qdd[6 + i];
            }
        }
    }
}

/// The wrench of the robot's weight on its base (base frame, moment about
/// the base origin first): `(c × m Rᵀg; m Rᵀg)` for the whole robot's mass
/// m and centre of mass c (base frame), `Iᶜ·(0; Rᵀg)` with the composite
/// inertia `Iᶜ` of the whole robot at the base (`composite`, see
/// [`crba`](super::crba::crba)).
pub fn weight_wrench<S: Scalar>(composite: &Inertia<S>, q: &[S], gravity: &Vec3<S>) -> Force<S> {
    let g_base = quaternion_rotation(&q[3..7]).tr_mul_vec(gravity);
    composite.mul_motion(&Motion::new(Vec3::zero(), g_base))
}
