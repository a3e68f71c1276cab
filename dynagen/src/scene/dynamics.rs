//! The dynamics of a scene, generic over the scalar like every algorithm:
//! the reduced model's rigid-body terms plus armature and friction (see the
//! [scene docs](super) for the equations). [`SceneRobot`](super::SceneRobot)
//! runs these on `f64`; code generation traces the same functions.
//!
//! The coefficients are model constants (`f64`): a joint without armature or
//! friction costs nothing, and the code branches only on them, never on the
//! state.

use super::SceneModel;
use crate::algorithms::{aba, bias, crba, ldlt, rnea, BodyInertia, TipWrench, Workspace};
use crate::spatial::Vec3;
use crate::Scalar;

/// σ(v) = v / √(v² + v_ε²): the smooth stand-in for sign(v) in Coulomb
/// friction.
#[inline(always)]
pub fn smooth_sign<S: Scalar>(v: S, v_eps: f64) -> S {
    v / (v * v + S::from_f64(v_eps * v_eps)).sqrt()
}

/// Adds the friction torques b∘q̇ + f∘σ(q̇) to `tau`.
pub fn add_friction<S: Scalar>(scene: &SceneModel, qd: &[S], tau: &mut [S]) {
    for (i, t) in tau.iter_mut().enumerate() {
        let (b, f) = (scene.viscous_friction[i], scene.coulomb_friction[i]);
        if b != 0.0 {
            *t += S::from_f64(b) * qd[i];
        }
        if f != 0.0 {
            *t += S::from_f64(f) * smooth_sign(qd[i], scene.coulomb_velocity);
        }
    }
}

/// Subtracts the friction torques from `tau`.
pub fn sub_friction<S: Scalar>(scene: &SceneModel, qd: &[S], tau: &mut [S]) {
    for (i, t) in tau.iter_mut().enumerate() {
        let (b, f) = (scene.viscous_friction[i], scene.coulomb_friction[i]);
        if b != 0.0 {
            *t -= S::from_f64(b) * qd[i];
        }
        if f != 0.0 {
            *t -= S::from_f64(f) * smooth_sign(qd[i], scene.coulomb_velocity);
        }
    }
}

/// Adds the armature to the diagonal of the n×n row-major `m`.
pub fn add_armature_diagonal<S: Scalar>(scene: &SceneModel, m: &mut [S]) {
    let n = scene.dof();
    for (i, &a) in scene.armature.iter().enumerate() {
        if a != 0.0 {
            m[i * n + i] += S::from_f64(a);
        }
    }
}

/// τ = M(q)q̈ + h(q, q̇) + J(q)ᵀF_tip + armature∘q̈ + friction.
#[allow(clippy::too_many_arguments)]
pub fn inverse_dynamics<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    qdd: &[S],
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    tau: &mut [S],
) {
    inverse_dynamics_with_payloads(scene, ws, q, qd, qdd, gravity, tips, &[], tau);
}

/// [`inverse_dynamics`] with extra body inertias (payloads given at run
/// time, see [`rnea::rnea_with_payloads`]).
#[allow(clippy::too_many_arguments)]
pub fn inverse_dynamics_with_payloads<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    qdd: &[S],
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    payloads: &[BodyInertia<S>],
    tau: &mut [S],
) {
    rnea::rnea_with_payloads(&scene.model, ws, q, Some(qd), Some(qdd), gravity, tips, payloads, tau);
    add_armature_times(scene, qdd, tau);
    add_friction(scene, qd, tau);
}

/// Adds armature∘q̈ to `tau`.
pub fn add_armature_times<S: Scalar>(scene: &SceneModel, qdd: &[S], tau: &mut [S]) {
    for (i, &a) in scene.armature.iter().enumerate() {
        if a != 0.0 {
            tau[i] += S::from_f64(a) * qdd[i];
        }
    }
}

/// M(q) + diag(armature), row-major n×n.
pub fn mass_matrix<S: Scalar>(scene: &SceneModel, ws: &mut Workspace<S>, q: &[S], m: &mut [S]) {
    crba::crba(&scene.model, ws, q, m);
    add_armature_diagonal(scene, m);
}

/// h(q, q̇) = C(q, q̇)q̇ + g(q) + friction.
pub fn bias_forces<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    gravity: Option<&Vec3<S>>,
    h: &mut [S],
) {
    bias::bias_forces(&scene.model, ws, q, qd, gravity, h);
    add_friction(scene, qd, h);
}

/// g(q) (zero without gravity).
pub fn gravity_torques<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    gravity: Option<&Vec3<S>>,
    g: &mut [S],
) {
    match gravity {
        Some(grav) => bias::gravity_torques(&scene.model, ws, q, grav, g),
        None => g.fill(S::zero()),
    }
}

/// C(q, q̇)q̇.
pub fn coriolis<S: Scalar>(scene: &SceneModel, ws: &mut Workspace<S>, q: &[S], qd: &[S], c: &mut [S]) {
    bias::coriolis_torques(&scene.model, ws, q, qd, c);
}

/// q̈ = (M(q) + diag(armature))⁻¹(τ − friction − h(q, q̇) − J(q)ᵀF_tip), by
/// the articulated-body algorithm on τ − friction with the armature in its
/// joint inertias ([`aba::aba_with_armature`]): exact, O(n), and the most
/// accurate method (`docs/performance.md`). `scratch` (n entries) holds τ − friction.
#[allow(clippy::too_many_arguments)]
pub fn forward_dynamics<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    scratch: &mut [S],
    qdd: &mut [S],
) {
    let n = scene.dof();
    assert!(scratch.len() == n && tau.len() == n, "forward_dynamics: slices must have the model's {n} joints");
    scratch.copy_from_slice(tau);
    sub_friction(scene, qd, scratch);
    let armature = if scene.has_armature() { Some(scene.armature.as_slice()) } else { None };
    aba::aba_with_armature(&scene.model, ws, q, qd, scratch, gravity, tips, armature, qdd);
}

/// The same q̈ as [`forward_dynamics`] through the mass matrix: M by the
/// composite-rigid-body algorithm with the armature on its diagonal, h and
/// J(q)ᵀF_tip by the recursive Newton-Euler algorithm, and the sparse LᵀDL
/// solve of [`ldlt`]. Fewer operations on short chains, fewer digits on
/// long ones. `scratch` (n entries) holds τ − friction.
#[allow(clippy::too_many_arguments)]
pub fn forward_dynamics_ldlt<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    scratch: &mut [S],
    qdd: &mut [S],
) {
    forward_dynamics_ldlt_with_payloads(scene, ws, q, qd, tau, gravity, tips, &[], scratch, qdd);
}

/// [`forward_dynamics_ldlt`] with extra body inertias (payloads given at run
/// time) in M and h ([`crba::crba_with_payloads`],
/// [`rnea::rnea_with_payloads`]).
#[allow(clippy::too_many_arguments)]
pub fn forward_dynamics_ldlt_with_payloads<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    payloads: &[BodyInertia<S>],
    scratch: &mut [S],
    qdd: &mut [S],
) {
    let n = scene.dof();
    assert!(scratch.len() == n && tau.len() == n, "forward_dynamics_ldlt: slices must have the model's {n} joints");
    scratch.copy_from_slice(tau);
    sub_friction(scene, qd, scratch);
    // h + JᵀF_tip into qdd, then the right-hand side.
    rnea::rnea_with_payloads(&scene.model, ws, q, Some(qd), None, gravity, tips, payloads, qdd);
    for i in 0..n {
        qdd[i] = scratch[i] - qdd[i];
    }
    let mut m = std::mem::take(&mut ws.mat);
    crba::crba_with_payloads(&scene.model, ws, q, payloads, &mut m);
    add_armature_diagonal(scene, &mut m);
    ldlt::factorise(&scene.model, &mut m);
    ldlt::solve(&scene.model, &m, qdd);
    ws.mat = m;
}
