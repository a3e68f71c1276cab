//! Frame poses and Jacobians of a floating-base robot, in the world frame
//! and in the base frame. The joints' part is the fixed-base kinematics of
//! the same tree relative to the base
//! ([`kinematics`](crate::algorithms::kinematics)); the base adds its pose
//! and six Jacobian columns (the base's body twist).

use super::{base_pose, check_sizes};
use crate::algorithms::joint::motion;
use crate::algorithms::kinematics as fixed;
use crate::algorithms::Workspace;
use crate::model::Model;
use crate::spatial::{Motion, Transform};
use crate::Scalar;

/// Places every body relative to the base (read them with
/// [`fixed::body_pose`] and [`fixed::frame_pose`], base frame).
pub fn forward_kinematics<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    check_sizes(model, "floating forward_kinematics", q.len(), &[]);
    fixed::forward_kinematics(model, ws, &q[7..]);
}

/// The pose of frame `frame` in the world, after [`forward_kinematics`].
pub fn frame_pose_world<S: Scalar>(model: &Model, ws: &Workspace<S>, q: &[S], frame: usize) -> Transform<S> {
    base_pose(q).compose(&fixed::frame_pose(model, ws, frame))
}

/// Writes the 6×NV row-major Jacobian whose column k is the twist that unit
/// velocity coordinate k gives the frame, each column mapped by `map` from
/// its twist in the base frame (about the base origin).
fn jacobian<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    frame: usize,
    map: impl Fn(&Motion<S>) -> Motion<S>,
    j: &mut [S],
) {
    let nv = model.nv();
    assert!(j.len() == 6 * nv, "floating jacobian: j must be 6×{nv}");
    j.fill(S::zero());
    let mut put = |k: usize, col: &Motion<S>| {
        for (r, x) in map(col).to_array().into_iter().enumerate() {
            j[r * nv + k] = x;
        }
    };
    for k in 0..6 {
        let mut e = [S::zero(); 6];
        e[k] = S::one();
        put(k, &Motion::from_array(e));
    }
    // the joints that move the frame: their screw axes in the base frame (a
    // mimic joint's added to its master's column, times its multiplier)
    let mut b = model.frames[frame].body;
    while let Some(i) = b {
        let axis = ws.world[i].motion_to_parent(&motion(&model.bodies[i].joint, S::one()));
        let (c, k) = crate::algorithms::mimic::body_column(model, i);
        for (r, x) in map(&axis).to_array().into_iter().enumerate() {
            let e = &mut j[r * nv + 6 + c];
            *e = if model.has_mimic() { *e + crate::algorithms::mimic::times(k, x) } else { x };
        }
        b = model.bodies[i].parent;
    }
}

/// The space Jacobian in the world frame (*Modern Robotics*' J_s): the
/// frame's twist `V_s = J_s q̇` at the world origin, world axes. 6×NV
/// row-major; after [`forward_kinematics`].
pub fn space_jacobian_world<S: Scalar>(model: &Model, ws: &Workspace<S>, q: &[S], frame: usize, j: &mut [S]) {
    let t = base_pose(q);
    jacobian(model, ws, frame, |m| t.motion_to_parent(m), j);
}

/// The space Jacobian in the base frame: the frame's twist at the base
/// origin, base axes, per unit velocity coordinate (the base's own columns
/// the identity). 6×NV row-major; after [`forward_kinematics`].
pub fn space_jacobian_base<S: Scalar>(model: &Model, ws: &Workspace<S>, frame: usize, j: &mut [S]) {
    jacobian(model, ws, frame, |m| *m, j);
}

/// The body Jacobian: the frame's body twist `V = J_b q̇` in its own axes.
/// 6×NV row-major; after [`forward_kinematics`].
pub fn body_jacobian<S: Scalar>(model: &Model, ws: &Workspace<S>, frame: usize, j: &mut [S]) {
    let t = fixed::frame_pose(model, ws, frame);
    jacobian(model, ws, frame, |m| t.motion_to_child(m), j);
}
