//! Forward dynamics of a floating-base robot by the articulated-body
//! algorithm: the joints by the fixed-base algorithm's passes (body frames,
//! classic accelerations), the base as their moving root, and at the root
//! the articulated inertia of the whole robot, a 6×6 symmetric
//! positive-definite solve for the base's acceleration. O(n), without
//! forming M.

use super::{base_inertia, check_tree_sizes, quaternion_rotation, solve6};
use crate::algorithms::aba::{add_carried, inward, outward, velocities, ArticulatedInertia, Carried, RootArticulated};
use crate::algorithms::rnea::{gyroscopic, products, use_products_for_gyroscopic, velocity_product_matrix};
use crate::algorithms::{add_tip_wrenches, Loads, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Motion, Vec3};
use crate::Scalar;

/// q̈ = M(q)⁻¹(τ − h(q, q̇) − Jᵀ F_tip) of a floating-base model: `q` NQ
/// long, `qd`, `tau` and `qdd` NV long (`tau[0..6]` the wrench on the base,
/// base frame). `loads` as for [`rnea`](super::rnea::rnea) (gravity in the
/// world frame).
///
/// # Panics
/// If a slice's length is not NQ or NV, or the model's root is not floating.
pub fn aba<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    aba_impl(model, ws, q, Some(qd), tau, loads, &[], qdd);
}

/// M(q)⁻¹τ of a floating-base model: [`aba`] at rest (q̇ = 0) and of
/// `loads` only the inertias (payloads, armature), the solve of the
/// compensated forward dynamics.
///
/// # Panics
/// As [`aba`].
pub fn aba_at_rest<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    aba_impl(model, ws, q, None, tau, loads.inertias(), &[], qdd);
}

/// [`aba`], or at rest for `qd: None` (every velocity term left out): the
/// fixed-base passes of [`crate::algorithms::aba`] with the base as their
/// moving root. Accelerations are "classic" there (ω̇; the ordinary
/// acceleration of the frame's origin), so the base's is
/// `â₀ = (ω̇_b; v̇_b + ω_b × v_b − Rᵀg)`, gravity folded in as a fictitious
/// acceleration, and its equation `Iᴬ₀ â₀ = τ_b − pᴬ₀` (pᴬ₀ with the base's
/// own `(ω × Ī ω; ω × (ω × h))`) is a 6×6 symmetric positive-definite solve.
/// `carried`: what branches computed apart pass to their parents (see
/// [`Carried`]). Returns `â₀`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn aba_impl<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    tau: &[S],
    loads: Loads<'_, S>,
    carried: &[Carried<S>],
    qdd: &mut [S],
) -> Motion<S> {
    let n = model.bodies.len();
    let nv = model.tree_nv();
    check_tree_sizes(model, "floating aba", q.len(), &[qd.map_or(nv, <[S]>::len), tau.len(), qdd.len()]);
    loads.check(n, "floating aba");
    let vec3 = |x: &[S]| Vec3([x[0], x[1], x[2]]);
    let w0 = qd.map(vec3);
    velocities(model, ws, &q[7..], qd.map(|x| &x[6..]), w0.as_ref(), loads);
    // (a payload on the base is part of its inertia)
    let i0 = base_inertia(model, loads.payloads);
    let mut root = RootArticulated { inertia: ArticulatedInertia::from_rigid(&i0), bias: Force::zero() };
    if let Some(w) = &w0 {
        // (ω × Ī ω; ω × (ω × h))
        let p = products(w);
        let u = velocity_product_matrix(Some(&p), &Vec3::zero());
        let gyro = if use_products_for_gyroscopic(&model.base_inertia.ibar) {
            gyroscopic(&i0.ibar, &p)
        } else {
            w.cross(&i0.ibar.mul_vec(w))
        };
        root.bias = Force::new(gyro, u.mul_vec(&i0.h));
    }
    add_tip_wrenches(model, loads.tips, None, Some(&mut root.bias));
    add_carried(ws, Some(&mut root), carried);
    // The fixed-base passes' arm: distributed when traced (see aba.rs).
    let distributed = S::TRACED;
    inward(model, ws, (&tau[6..], qd.is_some()), loads.armature, Some(&mut root), distributed);
    let mut a0 = [S::zero(); 6];
    for (k, (t, p)) in tau[..6].iter().zip(root.bias.to_array()).enumerate() {
        a0[k] = *t - p;
    }
    solve6(root.inertia.to_matrix(), &mut a0);
    let a0 = Motion::from_array(a0);
    // q̈_b = (ω̇_b; â₀'s linear part − ω_b × v_b + Rᵀg)
    let mut base = a0;
    if let (Some(w), Some(qd)) = (&w0, qd) {
        base.lin -= w.cross(&vec3(&qd[3..]));
    }
    if let Some(g) = loads.gravity {
        base.lin += quaternion_rotation(&q[3..7]).tr_mul_vec(g);
    }
    qdd[..6].copy_from_slice(&base.to_array());
    outward(model, ws, &a0, &mut qdd[6..], distributed);
    a0
}
