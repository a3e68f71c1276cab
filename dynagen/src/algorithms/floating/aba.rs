//! Forward dynamics of a floating-base robot by the articulated-body
//! algorithm: the joints as in the fixed-base algorithm (Featherstone's
//! spatial form, in body frames), and at the root the articulated inertia
//! of the whole robot at the base, a 6×6 symmetric positive-definite solve
//! for the base's acceleration. O(n), without forming M.

use super::{base_inertia, base_motion, check_tree_sizes, quaternion_rotation, solve6};
use crate::algorithms::aba::ArticulatedInertia;
use crate::algorithms::joint::{
    add_motion, cross_motion, force_to_parent, joint_transform, motion_to_child, project, with_rotation,
};
use crate::algorithms::{Loads, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Motion, Transform};
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
    aba_impl(model, ws, q, Some(qd), tau, loads, qdd)
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
    aba_impl(model, ws, q, None, tau, loads.inertias(), qdd)
}

/// [`aba`], or at rest for `qd: None` (every velocity term left out).
#[inline(always)]
fn aba_impl<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    let n = model.bodies.len();
    let nv = model.tree_nv();
    check_tree_sizes(model, "floating aba", q.len(), &[qd.map_or(nv, <[S]>::len), tau.len(), qdd.len()]);
    loads.check(n, "floating aba");
    let Loads { gravity, tips, payloads, armature } = loads;
    // Forward: spatial velocities v, velocity-product accelerations c (in
    // ws.a), bias forces pᴬ = v ×* I v (in ws.f).
    let v0 = qd.map_or(Motion::zero(), base_motion);
    let i0 = base_inertia(model, payloads);
    let mut art0 = ArticulatedInertia::from_rigid(&i0);
    let mut p0 = match qd {
        Some(_) => v0.cross_force(&i0.mul_motion(&v0)),
        None => Force::zero(),
    };
    for (i, body) in model.bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[7 + i]);
        ws.x[i] = x;
        let mut inertia = Inertia::<S>::from_f64(&body.inertia);
        for p in payloads.iter().filter(|p| p.body == i) {
            inertia = inertia.add(&p.inertia);
        }
        ws.art[i] = ArticulatedInertia::from_rigid(&inertia);
        let Some(qd) = qd else {
            // at rest: no velocity, no velocity-product acceleration, no bias force
            ws.a[i] = Motion::zero();
            ws.f[i] = Force::zero();
            continue;
        };
        let vp = body.parent.map_or(v0, |p| ws.v[p]);
        let mut v = motion_to_child(joint, &x, &vp);
        add_motion(joint, &mut v, qd[6 + i]);
        ws.a[i] = cross_motion(joint, &v, qd[6 + i]);
        ws.f[i] = v.cross_force(&inertia.mul_motion(&v));
        ws.v[i] = v;
    }
    for tip in tips {
        let frame = &model.frames[tip.frame];
        let w = Transform::<S>::from_f64(&frame.placement).force_to_parent(&tip.wrench);
        match frame.body {
            Some(b) => ws.f[b] += w,
            None => p0 += w,
        }
    }
    // Backward: articulated inertias and bias forces, down to the base.
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let joint = &body.joint;
        let u = ws.art[i].mul_subspace(joint);
        let arm = armature.map_or(0.0, |a| a[i]);
        let d = project(joint, &u);
        let d = if arm == 0.0 { d } else { d + S::from_f64(arm) };
        let d_inv = S::one() / d;
        let ui = tau[6 + i] - project(joint, &ws.f[i]);
        ws.u6[i] = u;
        ws.s1[i] = d_inv;
        ws.s2[i] = ui;
        let ia = ws.art[i].sub_outer(&u, d_inv);
        let pa = ws.f[i] + ia.mul_motion(&ws.a[i]) + u.scale(ui * d_inv);
        let x = ws.x[i];
        let ia_p = with_rotation!(joint, x, |r| ia.expressed_in_parent(&r, &x.trans));
        let pa_p = force_to_parent(joint, &x, &pa);
        match body.parent {
            Some(p) => {
                ws.art[p] = ws.art[p].add(&ia_p);
                ws.f[p] += pa_p;
            }
            None => {
                art0 = art0.add(&ia_p);
                p0 += pa_p;
            }
        }
    }
    // The root: Iᴬ₀ â₀ = τ_b − pᴬ₀ for the acceleration â₀ = q̈_b − (0; Rᵀg)
    // that gravity as a fictitious acceleration gives.
    let mut a0 = [S::zero(); 6];
    for (k, (t, p)) in tau[..6].iter().zip(p0.to_array()).enumerate() {
        a0[k] = *t - p;
    }
    solve6(art0.to_matrix(), &mut a0);
    let a0 = Motion::from_array(a0);
    let mut base = a0;
    if let Some(g) = gravity {
        base.lin += quaternion_rotation(&q[3..7]).tr_mul_vec(g);
    }
    qdd[..6].copy_from_slice(&base.to_array());
    // Outward: the accelerations (gravity still a fictitious one).
    for (i, body) in model.bodies.iter().enumerate() {
        let joint = &body.joint;
        let ap = body.parent.map_or(a0, |p| ws.a[p]);
        let a = motion_to_child(joint, &ws.x[i], &ap) + ws.a[i];
        let qddi = (ws.s2[i] - a.dot(&ws.u6[i])) * ws.s1[i];
        qdd[6 + i] = qddi;
        let mut a = a;
        add_motion(joint, &mut a, qddi);
        ws.a[i] = a;
    }
}
