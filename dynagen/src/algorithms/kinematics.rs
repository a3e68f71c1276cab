//! Forward kinematics and the space and body Jacobians of any frame.

use super::joint::{joint_transform, motion};
use super::Workspace;
use crate::model::Model;
use crate::spatial::{Motion, Transform};
use crate::Scalar;

/// The pose of every body in the base frame, into the workspace (read them
/// with [`body_pose`]). `q` has one entry per joint with a coordinate of
/// its own (a mimic joint is placed by its master's).
pub fn forward_kinematics<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    let n = model.dof();
    assert!(q.len() == n, "forward_kinematics: q must have the model's {n} joints");
    if model.has_mimic() {
        return super::mimic::forward_kinematics(model, ws, q);
    }
    forward_kinematics_tree(model, ws, q)
}

/// [`forward_kinematics`] from the bodies' coordinates, one per body.
pub(crate) fn forward_kinematics_tree<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    let n = model.bodies.len();
    assert!(q.len() == n && ws.dof() == n, "forward_kinematics: q must have the model's {n} bodies");
    for (i, b) in model.bodies.iter().enumerate() {
        let x = joint_transform(&b.joint, q[i]);
        ws.x[i] = x;
        ws.world[i] = match b.parent {
            Some(p) => ws.world[p].compose(&x),
            None => x,
        };
    }
}

/// The pose of body `i` in the base frame, after [`forward_kinematics`].
pub fn body_pose<S: Scalar>(ws: &Workspace<S>, i: usize) -> Transform<S> {
    ws.world[i]
}

/// The pose T_sb of frame `frame` (an index into [`Model::frames`]) in the
/// base frame, after [`forward_kinematics`].
pub fn frame_pose<S: Scalar>(model: &Model, ws: &Workspace<S>, frame: usize) -> Transform<S> {
    let f = &model.frames[frame];
    let place = f.placement_in::<S>();
    match f.body {
        Some(b) => ws.world[b].compose(&place),
        None => place,
    }
}

/// The space Jacobian J_s(q) of a frame, as in *Modern Robotics*: column i is
/// the screw axis of joint i in the base frame at the current configuration
/// (zero for joints that do not move the frame), so that the frame's space
/// twist is `V_s = J_s q̇` (angular; linear, the linear part being the
/// velocity of the point at the base origin). Written row-major, 6×n.
/// Call [`forward_kinematics`] first. A mimic joint's column is added to
/// its master's, times its multiplier (`J = J_tree G`).
pub fn space_jacobian<S: Scalar>(model: &Model, ws: &Workspace<S>, frame: usize, j: &mut [S]) {
    jacobian_columns(model, ws, frame, |s| s, j);
}

/// The columns of a Jacobian of `frame`, each joint's screw axis in the
/// base frame mapped by `map`, a mimic joint's added to its master's.
fn jacobian_columns<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    frame: usize,
    map: impl Fn(Motion<S>) -> Motion<S>,
    j: &mut [S],
) {
    let n = model.dof();
    assert!(j.len() == 6 * n, "jacobian: j must be 6×{n}");
    j.fill(S::zero());
    let mut b = model.frames[frame].body;
    while let Some(i) = b {
        let s_world: Motion<S> = ws.world[i].motion_to_parent(&motion(&model.bodies[i].joint, S::one()));
        let (c, k) = super::mimic::body_column(model, i);
        for (r, x) in map(s_world).to_array().into_iter().enumerate() {
            let e = &mut j[r * n + c];
            *e = if model.has_mimic() { *e + super::mimic::times(k, x) } else { x };
        }
        b = model.bodies[i].parent;
    }
}

/// The body Jacobian J_b(q) of a frame: the same columns expressed in the
/// frame itself, so that the frame's body twist is `V_b = J_b q̇`.
/// Row-major, 6×n. Call [`forward_kinematics`] first.
pub fn body_jacobian<S: Scalar>(model: &Model, ws: &Workspace<S>, frame: usize, j: &mut [S]) {
    let t_sf = frame_pose(model, ws, frame);
    jacobian_columns(model, ws, frame, |s| t_sf.motion_to_child(&s), j);
}
