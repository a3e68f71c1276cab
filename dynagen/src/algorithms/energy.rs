//! Kinetic and potential energy, for physical checks of the dynamics.

use super::joint::{joint_transform, motion};
use super::Workspace;
use crate::model::Model;
use crate::spatial::{Inertia, Vec3};
use crate::Scalar;

/// Kinetic energy ½ Σ Vᵢᵀ Gᵢ Vᵢ = ½ q̇ᵀ M(q) q̇ (J).
pub fn kinetic_energy<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], qd: &[S]) -> S {
    let mut e = S::zero();
    for (i, b) in model.bodies.iter().enumerate() {
        let x = joint_transform(&b.joint, q[i]);
        let s = motion(&b.joint, qd[i]);
        let v = match b.parent {
            Some(p) => x.motion_to_child(&ws.v[p]) + s,
            None => s,
        };
        ws.v[i] = v;
        e += v.dot(&Inertia::<S>::from_f64(&b.inertia).mul_motion(&v));
    }
    e * S::from_f64(0.5)
}

/// Potential energy −Σ mᵢ g·cᵢ of the moving bodies in the gravity field
/// `gravity` (base frame), zero at the base origin (J).
pub fn potential_energy<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], gravity: &Vec3<S>) -> S {
    super::kinematics::forward_kinematics(model, ws, q);
    let mut e = S::zero();
    for (i, b) in model.bodies.iter().enumerate() {
        // m·c in the base frame = R h + m p
        let w = &ws.world[i];
        let h = Vec3::<S>::from_f64(&b.inertia.h);
        let mc = w.rot.mul_vec(&h) + w.trans.scale(S::from_f64(b.inertia.mass));
        e -= gravity.dot(&mc);
    }
    e
}
