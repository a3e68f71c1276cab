//! Inverse dynamics of a floating-base robot by the recursive Newton-Euler
//! algorithm in body coordinates: the base is the root that the fixed-base
//! recursion (`rnea::rnea_tree`) hangs the bodies from, moving with its body
//! twist and accelerating with gravity folded in (`v̇_b + ω_b × v_b − Rᵀg`,
//! the ordinary acceleration of its origin, so gravity costs nothing per
//! body), and the wrench left at the base after the backward pass is
//! `τ[0..6]`, the wrench that must act on the base (base frame, moment about
//! its origin first).

use super::{base_inertia, check_tree_sizes, quaternion_rotation, write_force};
use crate::algorithms::rnea::{add_armature, body_wrench, rnea_tree, use_products_for_gyroscopic, Root, RootMotion};
use crate::algorithms::{add_tip_wrenches, Loads, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Mat3, Motion, Vec3};
use crate::Scalar;

/// τ = M(q)q̈ + h(q, q̇) (+ Jᵀ F_tip) of a floating-base model.
///
/// - `q`: NQ entries (base position, quaternion (x, y, z, w), joints);
///   `qd`, `qdd`: NV entries (`None`: zero); `tau`: NV entries written.
/// - `loads`: gravity in the world frame; tip wrenches at frames (those on
///   the base too); payloads on bodies and on the base
///   ([`BASE_BODY`](crate::algorithms::BASE_BODY)); armature on the joints
///   (not the base).
///
/// # Panics
/// If a slice's length is not NQ or NV, or the model's root is not floating.
#[inline(always)]
pub fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    let n = model.bodies.len();
    let nv = model.tree_nv();
    check_tree_sizes(
        model,
        "floating rnea",
        q.len(),
        &[tau.len(), qd.map_or(nv, <[S]>::len), qdd.map_or(nv, <[S]>::len)],
    );
    loads.check(n, "floating rnea");
    let (own, root) = base_motion(model, q, qd, qdd, loads);
    let (qd_joints, qdd_joints) = (qd.map(|x| &x[6..]), qdd.map(|x| &x[6..]));
    let children = rnea_tree(model, ws, &q[7..], (qd_joints, qdd_joints), Root::Moving(&root), loads, &mut tau[6..]);
    let mut f0 = own + children;
    add_tip_wrenches(model, loads.tips, None, Some(&mut f0));
    write_force(&f0, tau);
    add_armature(loads.armature, qdd_joints, &mut tau[6..]);
}

/// The base's own wrench and the motion it hands its children in
/// [`rnea`]: ω, ω̇, the ordinary acceleration of its origin `v̇ + ω × v`
/// with gravity as the fictitious acceleration `−Rᵀg`, and its `U`.
#[inline(always)]
pub(crate) fn base_motion<S: Scalar>(
    model: &Model,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    loads: Loads<'_, S>,
) -> (Force<S>, RootMotion<S>) {
    let vec3 = |x: &[S]| Vec3([x[0], x[1], x[2]]);
    let zero = Vec3::zero();
    // The base's ω, ω̇ and the ordinary acceleration of its origin
    // v̇ + ω × v, with gravity as a fictitious acceleration −Rᵀg.
    let w = qd.map_or(zero, vec3);
    let wd = qdd.map_or(zero, vec3);
    let mut a = qdd.map_or(zero, |x| vec3(&x[3..]));
    if let Some(qd) = qd {
        a += w.cross(&vec3(&qd[3..]));
    }
    if let Some(g) = loads.gravity {
        a -= quaternion_rotation(&q[3..7]).tr_mul_vec(g);
    }
    // The base's own wrench, and its U for the bodies it carries.
    let moving = qd.is_some() || qdd.is_some();
    // (a payload on the base is part of its inertia; the form of ω × (Ī·ω)
    // is chosen by the model's own base inertia)
    let gyro = use_products_for_gyroscopic(&model.base_inertia.ibar);
    let (own, u) = body_wrench(&base_inertia(model, loads.payloads), [&w, &wd, &a], (qd.is_some(), moving), gyro);
    (own, RootMotion { w, wd, a, u: u.unwrap_or(Mat3::zero()) })
}

/// The wrench of the robot's weight on its base (base frame, moment about
/// the base origin first): `(c × m Rᵀg; m Rᵀg)` for the whole robot's mass
/// m and centre of mass c (base frame), `Iᶜ·(0; Rᵀg)` with the composite
/// inertia `Iᶜ` of the whole robot at the base (`composite`, see
/// [`crba`](super::crba::crba)).
pub fn weight_wrench<S: Scalar>(composite: &Inertia<S>, q: &[S], gravity: &Vec3<S>) -> Force<S> {
    let g_base = quaternion_rotation(&q[3..7]).tr_mul_vec(gravity);
    composite.mul_motion(&Motion::new(Vec3::zero(), g_base))
}
