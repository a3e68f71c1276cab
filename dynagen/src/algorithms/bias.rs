//! The terms of the equations of motion that do not depend on q̈, each one
//! call of [`rnea`](super::rnea::rnea()) with the other terms left out:
//! h(q, q̇) = C(q, q̇)q̇ + g(q), g(q), C(q, q̇)q̇ alone, and J(q)ᵀF_tip.
//! On a floating model (NQ/NV-long slices, gravity in the world frame) the
//! base's six rows come first: g's are the wrench that holds the robot's
//! weight, in the base frame.

use super::rnea::rnea;
use super::{Loads, TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::Vec3;
use crate::Scalar;

/// The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q) (without tip wrenches).
pub fn bias_forces<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    gravity: Option<&Vec3<S>>,
    h: &mut [S],
) {
    rnea(model, ws, q, Some(qd), None, Loads::new(gravity, &[], &[]), h);
}

/// The gravity torques g(q).
pub fn gravity_torques<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], gravity: &Vec3<S>, g: &mut [S]) {
    rnea(model, ws, q, None, None, Loads::gravity(gravity), g);
}

/// The Coriolis and centripetal torques C(q, q̇)q̇ (the Modern Robotics
/// library's `VelQuadraticForces`).
pub fn coriolis_torques<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], qd: &[S], c: &mut [S]) {
    rnea(model, ws, q, Some(qd), None, Loads::none(), c);
}

/// The joint torques J(q)ᵀF_tip that hold the tip wrenches at rest (the
/// Modern Robotics library's `EndEffectorForces`).
pub fn tip_wrench_torques<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    tips: &[TipWrench<S>],
    tau: &mut [S],
) {
    rnea(model, ws, q, None, None, Loads::none().with_tips(tips), tau);
}
