//! The classical acceleration bias of a frame, J̇q̇: the frame's
//! acceleration at q̈ = 0, in the frame's own axes, angular first, its
//! linear part the acceleration of the frame's origin (a point of its
//! body). With the body Jacobian J ([`kinematics::body_jacobian`](super::kinematics::body_jacobian),
//! [`floating::kinematics::body_jacobian`](super::floating::kinematics::body_jacobian))
//! the frame's classical acceleration is `J q̈ + J̇q̇`, so a contact that
//! holds the point still is `J_lin q̈ + (J̇q̇)_lin = 0` (Pinocchio's
//! `getFrameClassicalAcceleration` at q̈ = 0 with `LOCAL`).
//!
//! The recursion is the velocity part of the Newton-Euler forward pass,
//! along the path from the base to the frame's body only: each body's
//! twist and its spatial acceleration `X a_parent + v × S q̇` (with a
//! floating base's body twist at the root, and no gravity). The spatial
//! acceleration of the frame is `J̇ q̇` with J̇ the time derivative of J
//! along q̇; the classical one adds `(0; ω × v)`.

use super::floating::base_motion;
use super::joint::{add_motion, cross_motion, joint_transform, motion_to_child};
use super::Workspace;
use crate::model::Model;
use crate::spatial::Motion;
use crate::Scalar;

/// J̇q̇ of frame `frame` (an index into [`Model::frames`]) at (q, q̇): its
/// classical acceleration at q̈ = 0, (angular; linear) in the frame. `q`
/// and `qd` as every algorithm takes them (n entries, or NQ and NV with a
/// floating base).
///
/// # Panics
/// If a slice has the wrong length.
pub fn frame_acceleration_bias<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    frame: usize,
) -> Motion<S> {
    let (nq, nv) = (model.nq(), model.nv());
    assert!(q.len() == nq && qd.len() == nv, "frame_acceleration_bias: q must have {nq} entries and qd {nv}");
    // (with mimic joints, on the bodies' coordinates)
    super::mimic::on_tree(model, ws, q, Some(qd), |ws, q, qd| bias_on_tree(model, ws, q, qd.unwrap_or(&[]), frame))
}

/// [`frame_acceleration_bias`] of the bodies' coordinates, one per body.
fn bias_on_tree<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], qd: &[S], frame: usize) -> Motion<S> {
    // Where the joints start in q and q̇, and the base's twist.
    let (oq, ov, v0) = if model.is_floating() { (7, 6, base_motion(qd)) } else { (0, 0, Motion::zero()) };
    let f = &model.frames[frame];
    let (v, a) = match f.body {
        None => (v0, Motion::zero()),
        Some(fb) => {
            for (i, body) in model.bodies.iter().enumerate().take(fb + 1) {
                if !model.is_in_subtree(i, fb) {
                    continue; // not on the path to the frame
                }
                let joint = &body.joint;
                let x = joint_transform(joint, q[oq + i]);
                let (vp, ap) = match body.parent {
                    Some(p) => (ws.v[p], ws.a[p]),
                    None => (v0, Motion::zero()),
                };
                let mut v = motion_to_child(joint, &x, &vp);
                add_motion(joint, &mut v, qd[ov + i]);
                ws.a[i] = motion_to_child(joint, &x, &ap) + cross_motion(joint, &v, qd[ov + i]);
                ws.v[i] = v;
            }
            (ws.v[fb], ws.a[fb])
        }
    };
    let place = f.placement_in::<S>();
    let v = place.motion_to_child(&v);
    let mut a = place.motion_to_child(&a);
    a.lin += v.ang.cross(&v.lin);
    a
}
