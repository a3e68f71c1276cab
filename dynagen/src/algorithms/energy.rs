//! Kinetic and potential energy, for physical checks of the dynamics.

use super::joint::{joint_transform, motion};
use super::{floating, Workspace};
use crate::model::Model;
use crate::spatial::{Motion, Vec3};
use crate::Scalar;

/// Kinetic energy ½ Σ Vᵢᵀ Gᵢ Vᵢ = ½ q̇ᵀ M(q) q̇ (J). A floating model
/// takes NQ/NV-long `q`, `qd` and counts its base too.
pub fn kinetic_energy<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], qd: &[S]) -> S {
    if model.is_floating() {
        floating::check_sizes(model, "kinetic_energy", q.len(), &[qd.len()]);
    }
    super::mimic::on_tree(model, ws, q, Some(qd), |ws, q, qd| kinetic_energy_tree(model, ws, q, qd.unwrap_or(&[])))
}

/// [`kinetic_energy`] of the bodies' coordinates.
fn kinetic_energy_tree<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], qd: &[S]) -> S {
    let mut e = S::zero();
    // the base's twist and the offsets of the joints in q and q̇
    let (v0, oq, ov) = if model.is_floating() {
        let v0 = floating::base_motion(qd);
        e += v0.dot(&model.base_inertia_in::<S>().mul_motion(&v0));
        (v0, 7, 6)
    } else {
        (Motion::zero(), 0, 0)
    };
    for (i, b) in model.bodies.iter().enumerate() {
        let x = joint_transform(&b.joint, q[oq + i]);
        let s = motion(&b.joint, qd[ov + i]);
        let v = match b.parent {
            Some(p) => x.motion_to_child(&ws.v[p]) + s,
            None if model.is_floating() => x.motion_to_child(&v0) + s,
            None => s,
        };
        ws.v[i] = v;
        e += v.dot(&b.inertia_in::<S>().mul_motion(&v));
    }
    e * S::from_f64(0.5)
}

/// Potential energy −Σ mᵢ g·cᵢ of the moving bodies in the gravity field
/// `gravity` (base frame), zero at the base origin (J). A floating model:
/// of the whole robot, base included, with `q` NQ long and gravity in the
/// world frame, zero at the world origin.
pub fn potential_energy<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], gravity: &Vec3<S>) -> S {
    if model.is_floating() {
        let c = floating::centroidal::center_of_mass(model, ws, q);
        return -(gravity.dot(&c) * S::from_f64(floating::centroidal::total_mass(model)));
    }
    super::kinematics::forward_kinematics(model, ws, q);
    let mut e = S::zero();
    for (i, b) in model.bodies.iter().enumerate() {
        // m·c in the base frame = R h + m p
        let w = &ws.world[i];
        let inertia = b.inertia_in::<S>();
        let mc = w.rot.mul_vec(&inertia.h) + w.trans.scale(inertia.mass);
        e -= gravity.dot(&mc);
    }
    e
}
