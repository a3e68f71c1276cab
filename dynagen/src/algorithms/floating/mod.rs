//! The algorithms of a floating-base robot ([`RootJoint::Floating`]): the
//! root body moves freely, with six unactuated degrees of freedom ahead of
//! the joints.
//!
//! Conventions (`/shared/DESIGN.md`): `q = [p, (x, y, z, w), joints]` with
//! `p` the base origin in the world and the quaternion the base's
//! orientation (world ← base), NQ = n + 7; `q̇`, `q̈`, `τ` = `[ω_b, v_b,
//! joints]` with the base's body twist, its derivative and the wrench on
//! the base all in the base frame, angular first, NV = n + 6. Gravity is
//! in the world frame.
//!
//! The formulation is in body coordinates: every algorithm runs in the
//! base's frame, so the base's orientation enters only through gravity,
//! which the base feels as the fictitious acceleration `−(0; Rᵀg)`. The
//! rotation is a polynomial in the quaternion (no trigonometry, no branch
//! on the state): traced on the symbolic scalar, these functions unroll as
//! the fixed-base ones do. The quaternion is used as given (the checked
//! [`Robot`](crate::Robot) API refuses one far from unit norm).
//!
//! [`RootJoint::Floating`]: crate::model::RootJoint::Floating

pub mod aba;
pub mod centroidal;
pub mod crba;
pub mod forward_dynamics;
pub mod kinematics;
pub mod rnea;
pub mod step;

use crate::algorithms::{BodyInertia, BASE_BODY};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Mat3, Motion, Transform, Vec3};
use crate::Scalar;

/// The rotation (world ← base) of the quaternion `(x, y, z, w)`, as the
/// usual quadratic polynomial (a rotation when the quaternion has unit
/// norm).
#[inline(always)]
pub fn quaternion_rotation<S: Scalar>(quat: &[S]) -> Mat3<S> {
    let [x, y, z, w] = [quat[0], quat[1], quat[2], quat[3]];
    let two = S::from_f64(2.0);
    let (xx, yy, zz) = (x * x, y * y, z * z);
    let (xy, xz, yz) = (x * y, x * z, y * z);
    let (wx, wy, wz) = (w * x, w * y, w * z);
    let one = S::one();
    Mat3([
        [one - two * (yy + zz), two * (xy - wz), two * (xz + wy)],
        [two * (xy + wz), one - two * (xx + zz), two * (yz - wx)],
        [two * (xz - wy), two * (yz + wx), one - two * (xx + yy)],
    ])
}

/// The base's pose in the world (world ← base) from `q[0..7]`.
#[inline(always)]
pub fn base_pose<S: Scalar>(q: &[S]) -> Transform<S> {
    Transform::new(quaternion_rotation(&q[3..7]), Vec3([q[0], q[1], q[2]]))
}

/// The floating base's inertia (base frame): the model's, and every
/// payload carried by the base ([`BASE_BODY`]).
#[inline(always)]
pub(crate) fn base_inertia<S: Scalar>(model: &Model, payloads: &[BodyInertia<S>]) -> Inertia<S> {
    let mut i0 = model.base_inertia_in::<S>();
    for p in payloads.iter().filter(|p| p.body == BASE_BODY) {
        i0 = i0.add(&p.inertia);
    }
    i0
}

/// `x[0..6]` as a twist or acceleration (angular; linear).
#[inline(always)]
pub(crate) fn base_motion<S: Scalar>(x: &[S]) -> Motion<S> {
    Motion::new(Vec3([x[0], x[1], x[2]]), Vec3([x[3], x[4], x[5]]))
}

/// Writes a wrench into `out[0..6]` (moment; force).
#[inline(always)]
pub(crate) fn write_force<S: Scalar>(f: &Force<S>, out: &mut [S]) {
    out[..3].copy_from_slice(&f.ang.0);
    out[3..6].copy_from_slice(&f.lin.0);
}

/// The parent of velocity coordinate `k` in the floating system's tree, for
/// the sparse factorisation of M: the base's six coordinates form a chain
/// (so their 6×6 block is dense), and a joint hanging from the base has
/// the base's last coordinate as its parent.
#[inline(always)]
pub fn velocity_parent(model: &Model, k: usize) -> Option<usize> {
    crate::algorithms::ldlt::parent(model, k)
}

/// Panics unless `q` has NQ entries and each of `nv_slices` NV; `what`
/// names the algorithm.
pub(crate) fn check_sizes(model: &Model, what: &str, q: usize, nv_slices: &[usize]) {
    check_lengths(model, what, (model.nq(), model.nv()), q, nv_slices)
}

/// [`check_sizes`] for a recursion over the bodies, which takes one
/// coordinate per body ([`Model::tree_nq`]; NQ and NV without mimic joints).
pub(crate) fn check_tree_sizes(model: &Model, what: &str, q: usize, nv_slices: &[usize]) {
    check_lengths(model, what, (model.tree_nq(), model.tree_nv()), q, nv_slices)
}

fn check_lengths(model: &Model, what: &str, (nq, nv): (usize, usize), q: usize, nv_slices: &[usize]) {
    assert!(model.is_floating(), "{what}: the model's root is not floating");
    assert!(
        q == nq && nv_slices.iter().all(|&l| l == nv),
        "{what}: q must have NQ = {nq} entries and velocity-side slices NV = {nv}"
    );
}

/// Steps a floating configuration by the velocity-side increment `dv`
/// (`q̇·dt`): the base by the exponential map of the body twist
/// `(ω_b, v_b)·dt` (pose ← pose · exp(dv)), its quaternion renormalised, and
/// the joints by addition. Never `q += q̇·dt` for the base.
pub fn integrate<S: Scalar>(model: &Model, q: &[S], dv: &[S], out: &mut [S]) {
    integrate_scaled(model, q, dv, S::one(), out)
}

/// [`integrate`] by `dt·v`.
pub fn integrate_scaled<S: Scalar>(model: &Model, q: &[S], v: &[S], dt: S, out: &mut [S]) {
    check_sizes(model, "integrate", q.len(), &[v.len()]);
    assert!(out.len() == q.len(), "integrate: out must have NQ entries");
    let dv = |k: usize| dt * v[k];
    let (w, v6) = (Vec3([dv(0), dv(1), dv(2)]), Vec3([dv(3), dv(4), dv(5)]));
    // exp of the twist (ω, v): rotation by |ω| about ω, and the translation
    // V(ω)·v with V = I + (1 − cos θ)/θ² [ω] + (θ − sin θ)/θ³ [ω]²; near θ = 0
    // by the series (a branch on the step's size, which is not traced).
    let theta2 = w.norm_squared();
    let theta = theta2.sqrt();
    let small = theta2.to_f64().is_some_and(|t| t < 1e-8);
    let (b, c) = if small {
        // (1 − cos θ)/θ², (θ − sin θ)/θ³ to O(θ⁴)
        let t2 = theta2;
        (
            S::from_f64(0.5) - t2 / S::from_f64(24.0) + t2 * t2 / S::from_f64(720.0),
            S::one() / S::from_f64(6.0) - t2 / S::from_f64(120.0) + t2 * t2 / S::from_f64(5040.0),
        )
    } else {
        let (s, co) = theta.sin_cos();
        ((S::one() - co) / theta2, (theta - s) / (theta2 * theta))
    };
    let wv = w.cross(&v6);
    let step = v6 + wv.scale(b) + w.cross(&wv).scale(c);
    let pose = base_pose(q);
    let p = pose.trans + pose.rot.mul_vec(&step);
    // The quaternion of the step: (sin(θ/2)/θ · ω, cos(θ/2)).
    let (hs, hc) = (theta * S::from_f64(0.5)).sin_cos();
    let k = if small { S::from_f64(0.5) - theta2 / S::from_f64(48.0) } else { hs / theta };
    let dq = [w.0[0] * k, w.0[1] * k, w.0[2] * k, hc];
    let (x1, y1, z1, w1) = (q[3], q[4], q[5], q[6]);
    let [x2, y2, z2, w2] = dq;
    // quaternion product q ⊗ dq (the step is in the base frame)
    let mut nq = [
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
    ];
    let norm = (nq[0] * nq[0] + nq[1] * nq[1] + nq[2] * nq[2] + nq[3] * nq[3]).sqrt();
    for x in nq.iter_mut() {
        *x = *x / norm;
    }
    out[..3].copy_from_slice(&p.0);
    out[3..7].copy_from_slice(&nq);
    for i in 0..model.dof() {
        out[7 + i] = q[7 + i] + dv(6 + i);
    }
}

/// A symmetric positive-definite 6×6 system `m x = b` by LᵀDL without
/// pivoting or square roots (the floating root's articulated inertia):
/// `b` becomes x.
#[allow(clippy::needless_range_loop)] // the textbook indices
pub(crate) fn solve6<S: Scalar>(mut m: [[S; 6]; 6], b: &mut [S; 6]) {
    for k in (0..6).rev() {
        let inv = S::one() / m[k][k];
        // ancestors from the nearest: m[k][i] becomes L after its last use
        for i in (0..k).rev() {
            let a = m[k][i] * inv;
            for j in 0..=i {
                let t = a * m[k][j];
                m[i][j] -= t;
            }
            m[k][i] = a;
        }
    }
    for i in (0..6).rev() {
        for j in 0..i {
            let t = m[i][j] * b[i];
            b[j] -= t;
        }
    }
    for i in 0..6 {
        b[i] = b[i] / m[i][i];
    }
    for i in 0..6 {
        for j in 0..i {
            let t = m[i][j] * b[j];
            b[i] -= t;
        }
    }
}
