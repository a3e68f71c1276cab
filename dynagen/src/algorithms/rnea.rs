//! The recursive Newton-Euler algorithm: inverse dynamics
//! τ = M(q)q̈ + C(q, q̇)q̇ + g(q) + J(q)ᵀF_tip.
//!
//! As in *Modern Robotics* §8.3: twists and accelerations go forward from the
//! base, with the base accelerating at −g so that gravity appears as an
//! inertial force; wrenches go backward from the tips, and each joint's
//! torque is the projection of the wrench it transmits onto its axis. Every
//! quantity is kept in the body's own frame.

use super::joint::{add_motion, cross_motion, joint_transform, motion, project};
use super::{TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::{Inertia, Motion, Transform, Vec3};
use crate::Scalar;

/// Computes the pose of every body in its parent's frame into `ws.x`.
#[inline(always)]
pub(crate) fn update_joint_transforms<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    for (i, b) in model.bodies.iter().enumerate() {
        ws.x[i] = joint_transform(&b.joint, q[i]);
    }
}

/// Inverse dynamics by the recursive Newton-Euler algorithm.
///
/// - `q`, `qd`, `qdd`: joint positions, velocities and accelerations in joint
///   order (rad, m; per second; per second²). `None` for `qd` or `qdd` means
///   zero, and the terms that would multiply it are not computed.
/// - `gravity`: in the base frame (m/s²); `None` for no gravity.
/// - `tips`: wrenches the robot applies to its environment at named frames
///   (the Modern Robotics `Ftip`).
/// - `tau`: the joint torques (N·m) or forces (N) are written here.
///
/// # Panics
/// If a slice's length is not the model's number of joints.
#[allow(clippy::too_many_arguments)]
pub fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    tau: &mut [S],
) {
    let n = model.dof();
    assert!(q.len() == n && tau.len() == n && ws.dof() == n, "rnea: slices must have the model's {n} joints");
    assert!(
        qd.is_none_or(|x| x.len() == n) && qdd.is_none_or(|x| x.len() == n),
        "rnea: slices must have the model's {n} joints"
    );

    // Slices of the known length, so that indexing by body needs no checks.
    let (bodies, q, tau) = (&model.bodies[..n], &q[..n], &mut tau[..n]);
    let (qd, qdd) = (qd.map(|x| &x[..n]), qdd.map(|x| &x[..n]));
    let (xs, vs, accs, fs) = (&mut ws.x[..n], &mut ws.v[..n], &mut ws.a[..n], &mut ws.f[..n]);
    // The base's acceleration is −g.
    let a0 = Motion::new(Vec3::zero(), gravity.map_or(Vec3::zero(), |g| -*g));
    let has_a0 = gravity.is_some();
    for (i, body) in bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[i]);
        xs[i] = x;
        let inertia = Inertia::<S>::from_f64(&body.inertia);
        // acceleration of the parent (or of the base)
        let a_parent = match body.parent {
            Some(p) => Some(accs[p]),
            None => has_a0.then_some(a0),
        };
        let mut a = a_parent.map_or(Motion::zero(), |ap| x.motion_to_child(&ap));
        if let Some(qdd) = qdd {
            add_motion(joint, &mut a, qdd[i]);
        }
        let f = if let Some(qd) = qd {
            let qdi = qd[i];
            let v = match body.parent {
                Some(p) => {
                    let mut v = x.motion_to_child(&vs[p]);
                    add_motion(joint, &mut v, qdi);
                    a += cross_motion(joint, &v, qdi);
                    v
                }
                // v ×ₘ S q̇ = 0 for v = S q̇
                None => motion(joint, qdi),
            };
            vs[i] = v;
            inertia.mul_motion(&a) + v.cross_force(&inertia.mul_motion(&v))
        } else {
            inertia.mul_motion(&a)
        };
        accs[i] = a;
        fs[i] = f;
    }
    for tip in tips {
        let frame = &model.frames[tip.frame];
        if let Some(b) = frame.body {
            let place = Transform::<S>::from_f64(&frame.placement);
            fs[b] += place.force_to_parent(&tip.wrench);
        }
    }
    for (i, body) in bodies.iter().enumerate().rev() {
        tau[i] = project(&body.joint, &fs[i]);
        if let Some(p) = body.parent {
            let fp = xs[i].force_to_parent(&fs[i]);
            fs[p] += fp;
        }
    }
}
