//! The dynamics of a scene, generic over the scalar like every algorithm:
//! the reduced model's rigid-body terms plus armature and friction (see the
//! [scene docs](super) for the equations). [`SceneRobot`](super::SceneRobot)
//! runs these on `f64`; code generation traces the same functions.
//!
//! The coefficients are model constants (`f64`): a joint without armature or
//! friction costs nothing, and the code branches only on them, never on the
//! state.

use super::SceneModel;
use crate::algorithms::derivatives::JointTorques;
use crate::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads, Workspace};
use crate::spatial::Vec3;
use crate::Scalar;

/// σ(v) = v / √(v² + v_ε²): the smooth stand-in for sign(v) in Coulomb
/// friction.
#[inline(always)]
pub fn smooth_sign<S: Scalar>(v: S, v_eps: f64) -> S {
    v / (v * v + S::from_f64(v_eps * v_eps)).sqrt()
}

/// Where the joints' entries start in a velocity-side vector: 0, or 6
/// after a floating base's twist (friction and armature act on the joints
/// only).
fn joints_at(scene: &SceneModel) -> usize {
    scene.model.nv() - scene.dof()
}

/// Adds the friction torques b∘q̇ + f∘σ(q̇) to `tau` (joints' entries).
pub fn add_friction<S: Scalar>(scene: &SceneModel, qd: &[S], tau: &mut [S]) {
    let o = joints_at(scene);
    for (i, t) in tau[o..].iter_mut().enumerate() {
        let (b, f) = (scene.viscous_friction[i], scene.coulomb_friction[i]);
        if b != 0.0 {
            *t += S::from_f64(b) * qd[o + i];
        }
        if f != 0.0 {
            *t += S::from_f64(f) * smooth_sign(qd[o + i], scene.coulomb_velocity);
        }
    }
}

/// Subtracts the friction torques from `tau` (joints' entries).
pub fn sub_friction<S: Scalar>(scene: &SceneModel, qd: &[S], tau: &mut [S]) {
    let o = joints_at(scene);
    for (i, t) in tau[o..].iter_mut().enumerate() {
        let (b, f) = (scene.viscous_friction[i], scene.coulomb_friction[i]);
        sub_joint_friction(t, qd[o + i], b, f, scene.coulomb_velocity);
    }
}

/// Subtracts one joint's friction torque b·q̇ + f·σ(q̇) from `t` (each term
/// only where its coefficient is not zero), as [`sub_friction`] does for
/// every joint.
pub(crate) fn sub_joint_friction<S: Scalar>(t: &mut S, qd: S, b: f64, f: f64, v_eps: f64) {
    if b != 0.0 {
        *t -= S::from_f64(b) * qd;
    }
    if f != 0.0 {
        *t -= S::from_f64(f) * smooth_sign(qd, v_eps);
    }
}

/// The scene's friction, for the derivatives of its dynamics (velocity-side
/// vectors: n long, or NV on a floating base).
impl JointTorques for SceneModel {
    fn add_to<S: Scalar>(&self, qd: &[S], tau: &mut [S]) {
        add_friction(self, qd, tau);
    }
}

/// Adds the armature to the joints' diagonal of the row-major `m` (n×n, or
/// NV×NV on a floating base).
pub fn add_armature_diagonal<S: Scalar>(scene: &SceneModel, m: &mut [S]) {
    let (o, nv) = (joints_at(scene), scene.model.nv());
    for (i, &a) in scene.armature.iter().enumerate() {
        if a != 0.0 {
            m[(o + i) * nv + o + i] += S::from_f64(a);
        }
    }
}

/// The scene's armature (`None` when it has none) added to `loads`.
pub(crate) fn with_armature<'a, S>(scene: &'a SceneModel, loads: Loads<'a, S>) -> Loads<'a, S> {
    loads.with_armature(scene.has_armature().then_some(scene.armature.as_slice()))
}

/// τ = M(q)q̈ + h(q, q̇) + J(q)ᵀF_tip + armature∘q̈ + friction, under `loads`
/// (gravity, tip wrenches, payloads given at run time; the scene's armature
/// is added to them).
pub fn inverse_dynamics<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    qdd: &[S],
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    rnea::rnea(&scene.model, ws, q, Some(qd), Some(qdd), with_armature(scene, loads), tau);
    add_friction(scene, qd, tau);
}

/// M(q) + diag(armature), row-major n×n.
pub fn mass_matrix<S: Scalar>(scene: &SceneModel, ws: &mut Workspace<S>, q: &[S], m: &mut [S]) {
    crba::crba(&scene.model, ws, q, with_armature(scene, Loads::none()), m);
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
/// joint inertias ([`aba::aba`]): exact, O(n), and the most accurate method
/// (`docs/performance.md`). `loads` as [`inverse_dynamics`].
pub fn forward_dynamics<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    let rhs = tau_minus_friction(scene, ws, qd, tau);
    aba::aba(&scene.model, ws, q, qd, &rhs, with_armature(scene, loads), qdd);
    ws.rhs = rhs;
}

/// The same q̈ as [`forward_dynamics`](fn@forward_dynamics) through the mass matrix: M by the
/// composite-rigid-body algorithm with the armature on its diagonal, h and
/// J(q)ᵀF_tip by the recursive Newton-Euler algorithm, and the sparse LᵀDL
/// solve of [`ldlt`](crate::algorithms::ldlt)
/// ([`forward_dynamics_ldlt`](forward_dynamics::forward_dynamics_ldlt)).
/// Fewer operations on short chains, fewer digits on long ones.
pub fn forward_dynamics_ldlt<S: Scalar>(
    scene: &SceneModel,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    let rhs = tau_minus_friction(scene, ws, qd, tau);
    forward_dynamics::forward_dynamics_ldlt(&scene.model, ws, q, qd, &rhs, with_armature(scene, loads), qdd);
    ws.rhs = rhs;
}

/// τ − friction, in the workspace's right-hand side (taken out of it; the
/// caller puts it back).
fn tau_minus_friction<S: Scalar>(scene: &SceneModel, ws: &mut Workspace<S>, qd: &[S], tau: &[S]) -> Vec<S> {
    let (n, nv) = (scene.model.bodies.len(), scene.model.nv());
    assert!(tau.len() == nv && ws.dof() == n, "forward_dynamics: tau must have the model's {nv} entries");
    let mut rhs = std::mem::take(&mut ws.rhs);
    rhs.copy_from_slice(tau);
    sub_friction(scene, qd, &mut rhs);
    rhs
}
