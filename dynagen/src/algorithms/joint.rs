//! Joint kinematics: the pose of a body in its parent's frame as a function
//! of the joint position, and the joint's motion subspace.

use crate::model::{Joint, JointKind};
use crate::spatial::{Force, Motion, Transform, Vec3};
use crate::Scalar;

/// The pose of the joint's body in its parent's frame at position `q`:
/// the fixed placement, then the joint's own motion (a rotation by
/// `|axis|·q` about the axis, or a translation by `axis·q`).
#[inline(always)]
pub fn joint_transform<S: Scalar>(joint: &Joint, q: S) -> Transform<S> {
    let place = Transform::<S>::from_f64(&joint.placement);
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => {
            let angle =
                if joint.axis_norm == 1.0 { q } else { q * S::axis_norm_constant(&joint.axis, joint.axis_norm) };
            let (s, c) = angle.sin_cos();
            let r = S::axis_rotation(&joint.axis, &joint.unit_axis, s, c);
            Transform { rot: place.rot.mul_mat(&r), trans: place.trans }
        }
        JointKind::Prismatic => {
            let d = Vec3::<S>::from_f64(&joint.axis).scale(q);
            Transform { rot: place.rot, trans: place.trans + place.rot.mul_vec(&d) }
        }
    }
}

/// `S·x`: the twist of a joint moving at rate `x`, in the joint's frame.
#[inline(always)]
pub fn motion<S: Scalar>(joint: &Joint, x: S) -> Motion<S> {
    let a = Vec3::<S>::from_f64(&joint.axis).scale(x);
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => Motion::new(a, Vec3::zero()),
        JointKind::Prismatic => Motion::new(Vec3::zero(), a),
    }
}

/// `Sᵀ·f`: the generalised force of a wrench on the joint.
#[inline(always)]
pub fn project<S: Scalar>(joint: &Joint, f: &Force<S>) -> S {
    let a = Vec3::<S>::from_f64(&joint.axis);
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => a.dot(&f.ang),
        JointKind::Prismatic => a.dot(&f.lin),
    }
}

/// `Sᵀ·m` for a motion vector (used where a motion is projected, e.g. the
/// body Jacobian's transpose).
#[inline(always)]
pub fn motion_dot<S: Scalar>(joint: &Joint, m: &Motion<S>) -> S {
    let a = Vec3::<S>::from_f64(&joint.axis);
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => a.dot(&m.ang),
        JointKind::Prismatic => a.dot(&m.lin),
    }
}
