//! Time integration of the forward dynamics: one step of the state
//! (q, q̇) over a time `dt` under q̈ = FD(q, q̇, τ), with the accelerations from
//! the articulated-body algorithm ([`aba`]) and τ, gravity and the tip
//! wrenches held constant over the step.
//!
//! Three schemes, all generic over the scalar and allocation-free (their
//! scratch is an [`IntegratorScratch`], created once per model):
//!
//! - [`euler`]: explicit Euler as the Modern Robotics library's `EulerStep`
//!   does it, q ← q + dt·q̇, q̇ ← q̇ + dt·q̈, the position update using the
//!   *old* velocity. First order; its energy grows.
//! - [`semi_implicit_euler`]: symplectic Euler, q̇ ← q̇ + dt·q̈, then
//!   q ← q + dt·q̇ with the *new* velocity. First order, but its energy error
//!   stays bounded over long runs of a conservative system.
//! - [`rk4`]: the classical fourth-order Runge-Kutta scheme on the first-order
//!   system d/dt (q, q̇) = (q̇, q̈); four calls of [`aba`] per step, error
//!   O(dt⁴) over a fixed time.
//! - [`implicit_euler`]: backward Euler, x₁ = x₀ + dt·f(x₁), solved by
//!   Newton's method with the Jacobian of the dynamics by finite
//!   differences. First order and strongly damping, but stable at any step
//!   on stiff scenes (stiff joint springs, a light link after a heavy one)
//!   where the explicit schemes blow up.
//!
//! Each scheme also has a `*_with` form that takes the accelerations as a
//! function q̈ = a(q, q̇), for dynamics with state-dependent torques (joint
//! springs and dampers, a controller).
//!
//! Units: `dt` in s; q in rad (revolute) or m (prismatic), q̇ per s; τ in
//! N·m or N; gravity (m/s²) in the base frame; tip wrenches in their frames.
//!
//! A floating-base model is stepped by [`floating::step`](super::floating::step)
//! (the base on SE(3), never q += dt·q̇; no implicit scheme there).

use super::aba::aba;
use super::lu::{self, magnitude};
use super::{Loads, Workspace};
use crate::model::Model;
use crate::Scalar;

/// Which scheme advances the state by one step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integrator {
    /// Explicit Euler, as the Modern Robotics library's `EulerStep`
    /// (see [`euler`]). The default, since it is what `ForwardDynamicsTrajectory` uses.
    #[default]
    Euler,
    /// Semi-implicit (symplectic) Euler (see [`semi_implicit_euler`]).
    SemiImplicitEuler,
    /// Classical fourth-order Runge-Kutta (see [`rk4`]).
    Rk4,
    /// Implicit (backward) Euler by Newton's method (see [`implicit_euler`]).
    ImplicitEuler,
}

/// A step: its length, and what acts on the robot during it, held
/// constant over it.
#[derive(Clone, Copy, Debug)]
pub struct StepInputs<'a, S> {
    /// The step's length (s).
    pub dt: S,
    /// Joint torques (N·m) or forces (N), in joint order.
    pub tau: &'a [S],
    /// Gravity, tip wrenches, payloads and armature (see [`Loads`]).
    pub loads: Loads<'a, S>,
}

/// Scratch for the integrators: the accelerations and the intermediate
/// stages of [`rk4`]. Create it once per model, outside a control loop.
#[derive(Clone, Debug)]
pub struct IntegratorScratch<S> {
    /// The last accelerations computed (for Euler and semi-implicit Euler:
    /// q̈ at the start of the step).
    pub(crate) qdd: Vec<S>,
    /// Runge-Kutta stage position and velocity.
    pub(crate) q_stage: Vec<S>,
    pub(crate) qd_stage: Vec<S>,
    /// Runge-Kutta weighted sums of the stage slopes.
    pub(crate) q_sum: Vec<S>,
    pub(crate) qd_sum: Vec<S>,
    /// A floating base's configuration step (velocity-side), see `floating::step`.
    pub(crate) delta: Vec<S>,
    /// The implicit scheme's Newton scratch.
    implicit: ImplicitScratch<S>,
}

impl<S: Scalar> IntegratorScratch<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        // NQ and NV entries (both n for a fixed base)
        let (nq, nv) = (model.nq(), model.nv());
        IntegratorScratch {
            qdd: vec![S::zero(); nv],
            q_stage: vec![S::zero(); nq],
            qd_stage: vec![S::zero(); nv],
            q_sum: vec![S::zero(); nv],
            qd_sum: vec![S::zero(); nv],
            delta: vec![S::zero(); if model.is_floating() { nv } else { 0 }],
            implicit: ImplicitScratch::new(nv, nq),
        }
    }
    /// The number of joints this scratch is for.
    pub fn dof(&self) -> usize {
        self.qdd.len()
    }
    /// The accelerations q̈ at the start of the last [`euler`] or
    /// [`semi_implicit_euler`] step (at the last stage for [`rk4`]).
    pub fn accelerations(&self) -> &[S] {
        &self.qdd
    }
}

/// The Modern Robotics library's `EulerStep` on given accelerations:
/// q ← q + dt·q̇ (with the velocity before the step), then q̇ ← q̇ + dt·q̈.
///
/// # Panics
/// If the slices differ in length.
pub fn euler_step<S: Scalar>(q: &mut [S], qd: &mut [S], qdd: &[S], dt: S) {
    assert!(q.len() == qd.len() && qd.len() == qdd.len(), "euler_step: q, qd and qdd must have the same length");
    for i in 0..q.len() {
        q[i] += dt * qd[i];
        qd[i] += dt * qdd[i];
    }
}

/// One step of `integrator` with the accelerations of the articulated-body
/// algorithm under `inputs`, after checking the lengths: what [`euler`],
/// [`semi_implicit_euler`], [`rk4`], [`implicit_euler`] and [`step`] do.
/// Returns the implicit scheme's Newton outcome, when it ran.
fn step_by_aba<S: Scalar>(
    integrator: Integrator,
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) -> Option<NewtonOutcome> {
    if model.is_floating() {
        super::floating::step::step(integrator, model, ws, scratch, inputs, q, qd);
        return None;
    }
    let n = model.dof();
    assert!(
        q.len() == n && qd.len() == n && inputs.tau.len() == n && ws.dof() == model.bodies.len() && scratch.dof() == n,
        "integrators: slices and scratch must have the model's {n} joints"
    );
    let accel = |q: &[S], qd: &[S], qdd: &mut [S]| aba(model, ws, q, qd, inputs.tau, inputs.loads, qdd);
    step_with_outcome(integrator, scratch, inputs.dt, q, qd, accel)
}

/// One explicit Euler step of the forward dynamics (the Modern Robotics
/// library's `ForwardDynamics` followed by `EulerStep`): q̈ = FD(q, q̇, τ),
/// q ← q + dt·q̇, q̇ ← q̇ + dt·q̈. `q` and `qd` are updated in place.
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
pub fn euler<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) {
    step_by_aba(Integrator::Euler, model, ws, scratch, inputs, q, qd);
}

/// [`euler`] with the accelerations from `accel(q, q̇, q̈_out)`.
///
/// # Panics
/// If `q`, `qd` or the scratch differ in length.
pub fn euler_with<S: Scalar>(
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    mut accel: impl FnMut(&[S], &[S], &mut [S]),
) {
    accel(q, qd, &mut scratch.qdd);
    euler_step(q, qd, &scratch.qdd, dt);
}

/// One semi-implicit (symplectic) Euler step: q̈ = FD(q, q̇, τ),
/// q̇ ← q̇ + dt·q̈, then q ← q + dt·q̇ with the new velocity. `q` and `qd`
/// are updated in place.
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
pub fn semi_implicit_euler<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) {
    step_by_aba(Integrator::SemiImplicitEuler, model, ws, scratch, inputs, q, qd);
}

/// [`semi_implicit_euler`] with the accelerations from `accel(q, q̇, q̈_out)`.
///
/// # Panics
/// If `q`, `qd` or the scratch differ in length.
pub fn semi_implicit_euler_with<S: Scalar>(
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    mut accel: impl FnMut(&[S], &[S], &mut [S]),
) {
    accel(q, qd, &mut scratch.qdd);
    for i in 0..q.len() {
        qd[i] += dt * scratch.qdd[i];
        q[i] += dt * qd[i];
    }
}

/// One classical Runge-Kutta step of d/dt (q, q̇) = (q̇, FD(q, q̇, τ)):
/// with x = (q, q̇) and f(x) = (q̇, q̈),
/// k₁ = f(x), k₂ = f(x + dt/2·k₁), k₃ = f(x + dt/2·k₂), k₄ = f(x + dt·k₃),
/// x ← x + dt/6·(k₁ + 2k₂ + 2k₃ + k₄). `q` and `qd` are updated in place.
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
pub fn rk4<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) {
    step_by_aba(Integrator::Rk4, model, ws, scratch, inputs, q, qd);
}

/// [`rk4`] with the accelerations from `accel(q, q̇, q̈_out)`.
///
/// # Panics
/// If `q`, `qd` or the scratch differ in length.
pub fn rk4_with<S: Scalar>(
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    mut accel: impl FnMut(&[S], &[S], &mut [S]),
) {
    let n = q.len();
    assert!(qd.len() == n && scratch.dof() == n, "rk4: q, qd and the scratch must have the same length");
    let half = dt * S::from_f64(0.5);
    let IntegratorScratch { qdd, q_stage, qd_stage, q_sum, qd_sum, .. } = scratch;
    q_stage.copy_from_slice(q);
    qd_stage.copy_from_slice(qd);
    // (weight of the stage's slope in the sum, offset of the next stage)
    let stages =
        [(S::one(), Some(half)), (S::from_f64(2.0), Some(half)), (S::from_f64(2.0), Some(dt)), (S::one(), None)];
    q_sum.fill(S::zero());
    qd_sum.fill(S::zero());
    for (weight, next) in stages {
        accel(q_stage, qd_stage, qdd);
        // The stage's slope is (qd_stage, qdd).
        for i in 0..n {
            q_sum[i] += weight * qd_stage[i];
            qd_sum[i] += weight * qdd[i];
            if let Some(c) = next {
                q_stage[i] = q[i] + c * qd_stage[i];
                qd_stage[i] = qd[i] + c * qdd[i];
            }
        }
    }
    let sixth = dt / S::from_f64(6.0);
    for i in 0..n {
        q[i] += sixth * q_sum[i];
        qd[i] += sixth * qd_sum[i];
    }
}

/// Scratch of [`implicit_euler`]: the Newton iteration's Jacobian, its LU
/// factors and vectors (part of [`IntegratorScratch`]).
#[derive(Clone, Debug)]
struct ImplicitScratch<S> {
    /// The Newton matrix J = 1 − dt·(dt·∂a/∂q + ∂a/∂q̇), n×n row-major, then its LU factors.
    jac: Vec<S>,
    /// Row permutation of the LU factorisation.
    perm: Vec<usize>,
    v: Vec<S>,
    q1: Vec<S>,
    a0: Vec<S>,
    a1: Vec<S>,
    r: Vec<S>,
    /// The scalar's machine epsilon (measured once), for the difference steps
    /// and the Newton tolerance.
    eps: f64,
}

/// The machine epsilon of `S` (2⁻⁵² for `f64`, 2⁻²³ for `f32`; a double-double
/// represents 1 + 2⁻ᵏ exactly for any k, and is given 1e-32), found by halving.
fn machine_epsilon<S: Scalar>() -> f64 {
    let mut e = 1.0f64;
    while e > 1e-40 {
        let h = e * 0.5;
        let d = (S::one() + S::from_f64(h)) - S::one();
        if d.to_f64().is_none_or(|d| d == 0.0) {
            break;
        }
        e = h;
    }
    e
}

impl<S: Scalar> ImplicitScratch<S> {
    fn new(n: usize, nq: usize) -> Self {
        ImplicitScratch {
            jac: vec![S::zero(); n * n],
            perm: (0..n).collect(),
            v: vec![S::zero(); n],
            q1: vec![S::zero(); nq],
            a0: vec![S::zero(); n],
            a1: vec![S::zero(); n],
            r: vec![S::zero(); n],
            eps: machine_epsilon::<S>().max(1e-32),
        }
    }
}

/// What a Newton solve of [`implicit_euler_with`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NewtonOutcome {
    /// Newton iterations done (each one evaluation of the dynamics, after the
    /// n + 1 evaluations that form the Jacobian).
    pub iterations: usize,
    /// Whether the last correction was below the tolerance (≈ ε^¾ relative).
    pub converged: bool,
}

/// Newton iterations of [`implicit_euler_with`] at most.
pub const IMPLICIT_MAX_ITERATIONS: usize = 12;

/// One implicit (backward) Euler step of d/dt (q, q̇) = (q̇, FD(q, q̇, τ)):
/// q₁ = q₀ + dt·q̇₁ and q̇₁ = q̇₀ + dt·FD(q₁, q̇₁, τ), solved for q̇₁ by
/// Newton's method (see [`implicit_euler_with`]). `q` and `qd` are updated
/// in place.
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
pub fn implicit_euler<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) -> NewtonOutcome {
    step_by_aba(Integrator::ImplicitEuler, model, ws, scratch, inputs, q, qd)
        .expect("the implicit scheme has an outcome")
}

/// One implicit Euler step with the accelerations from `accel(q, q̇, q̈_out)`.
///
/// With v = q̇₁ the unknown and q₁ = q₀ + dt·v, the step solves
/// r(v) = v − q̇₀ − dt·a(q₀ + dt·v, v) = 0 by Newton's method from v = q̇₀.
/// The Jacobian ∂r/∂v = 1 − dt·(dt·∂a/∂q + ∂a/∂q̇) is formed once per step
/// by forward differences (column j: v_j moved by √ε·max(1, |v_j|), which
/// moves q₁ by dt times that, so one evaluation of `a` per column), factorised
/// by LU with partial pivoting, and kept for the next iterations (a
/// simplified Newton method) as long as each correction is below a quarter
/// of the previous one; otherwise it is formed again at the current iterate.
/// Iterates until the correction is below ε^¾ relative to |v| (or 1), at
/// most [`IMPLICIT_MAX_ITERATIONS`] times.
///
/// The branches (pivots, convergence) look at values: this is a numeric
/// routine for `f64`, `f32` or a precise scalar, not one to trace.
///
/// # Panics
/// If `q`, `qd` or the scratch differ in length.
pub fn implicit_euler_with<S: Scalar>(
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    accel: impl FnMut(&[S], &[S], &mut [S]),
) -> NewtonOutcome {
    assert!(q.len() == qd.len(), "implicit_euler: q, qd and the scratch must have the same length");
    let add = |q: &[S], dt: S, v: &[S], q1: &mut [S]| {
        for i in 0..q.len() {
            q1[i] = q[i] + dt * v[i];
        }
    };
    implicit_euler_on(scratch, dt, q, qd, add, accel)
}

/// [`implicit_euler_with`] on a configuration space whose step
/// q₁ = q₀ ⊕ dt·v is `retract(q₀, dt, v, q₁)`: addition for joints, the
/// exponential map for a floating base (`floating::step`).
pub(crate) fn implicit_euler_on<S: Scalar>(
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    retract: impl Fn(&[S], S, &[S], &mut [S]),
    mut accel: impl FnMut(&[S], &[S], &mut [S]),
) -> NewtonOutcome {
    let n = qd.len();
    assert!(scratch.dof() == n, "implicit_euler: q, qd and the scratch must have the same length");
    let tmp = &mut scratch.qdd;
    let ImplicitScratch { jac, perm, v, q1, a0, a1, r, eps } = &mut scratch.implicit;
    let h_rel = eps.sqrt();
    let tol = eps.powf(0.75);
    v.copy_from_slice(qd);
    let mut outcome = NewtonOutcome { iterations: 0, converged: false };
    let (mut refresh, mut last) = (true, f64::INFINITY);
    for it in 0..IMPLICIT_MAX_ITERATIONS {
        retract(q, dt, v, q1);
        accel(q1, v, a0);
        if refresh {
            // Column j of ∂r/∂v by a forward difference.
            for j in 0..n {
                let vj = v[j];
                let step = S::from_f64(h_rel * magnitude(vj).max(1.0));
                v[j] = vj + step;
                retract(q, dt, v, q1);
                accel(q1, v, a1);
                // The step actually taken (v_j + step − v_j may round).
                let taken = v[j] - vj;
                for i in 0..n {
                    let d = (a1[i] - a0[i]) / taken;
                    jac[i * n + j] = if i == j { S::one() } else { S::zero() } - dt * d;
                }
                v[j] = vj;
                retract(q, dt, v, q1);
            }
            lu::factorise(jac, perm, n);
        }
        for i in 0..n {
            r[i] = v[i] - qd[i] - dt * a0[i];
        }
        lu::solve(jac, perm, n, r, tmp);
        let (mut dmax, mut vmax) = (0.0f64, 1.0f64);
        for i in 0..n {
            v[i] -= r[i];
            dmax = dmax.max(magnitude(r[i]));
            vmax = vmax.max(magnitude(v[i]));
        }
        outcome.iterations = it + 1;
        // A non-finite correction ends the iteration (not converged).
        if !dmax.is_finite() {
            break;
        }
        if dmax <= tol * vmax {
            outcome.converged = true;
            break;
        }
        // Slow convergence: the Jacobian of the first iterate is too far
        // from the current one; form it again at the next iterate.
        refresh = dmax > 0.25 * last;
        last = dmax;
    }
    retract(q, dt, v, q1);
    q.copy_from_slice(q1);
    qd.copy_from_slice(v);
    outcome
}

/// One step with the scheme `integrator`: [`euler`], [`semi_implicit_euler`],
/// [`rk4`] or [`implicit_euler`].
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
pub fn step<S: Scalar>(
    integrator: Integrator,
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) {
    step_by_aba(integrator, model, ws, scratch, inputs, q, qd);
}

/// [`step`] with the accelerations from `accel(q, q̇, q̈_out)` (for dynamics
/// with state-dependent torques, such as joint springs and dampers).
///
/// # Panics
/// If `q`, `qd` or the scratch differ in length.
pub fn step_with<S: Scalar>(
    integrator: Integrator,
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    accel: impl FnMut(&[S], &[S], &mut [S]),
) {
    step_with_outcome(integrator, scratch, dt, q, qd, accel);
}

/// [`step_with`], returning the implicit scheme's Newton outcome when it ran.
fn step_with_outcome<S: Scalar>(
    integrator: Integrator,
    scratch: &mut IntegratorScratch<S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
    accel: impl FnMut(&[S], &[S], &mut [S]),
) -> Option<NewtonOutcome> {
    match integrator {
        Integrator::Euler => euler_with(scratch, dt, q, qd, accel),
        Integrator::SemiImplicitEuler => semi_implicit_euler_with(scratch, dt, q, qd, accel),
        Integrator::Rk4 => rk4_with(scratch, dt, q, qd, accel),
        Integrator::ImplicitEuler => return Some(implicit_euler_with(scratch, dt, q, qd, accel)),
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Inertial, JointDescription, RobotBuilder};
    use crate::spatial::Vec3;

    // A point mass m on a massless prismatic joint along x with a constant
    // force f: q̈ = f/m exactly, so every scheme's error is known in closed form.
    fn slider(m: f64) -> Model {
        RobotBuilder::new("slider")
            .link("base", None)
            .link("cart", Some(Inertial::new(m, [0.0; 3], [0.1, 0.1, 0.1, 0.0, 0.0, 0.0])))
            .joint(JointDescription::prismatic("x", "base", "cart", [1.0, 0.0, 0.0]))
            .build()
            .unwrap()
    }

    fn run(integrator: Integrator, dt: f64) -> (f64, f64) {
        let model = slider(2.0);
        let mut ws = Workspace::new(&model);
        let mut scratch = IntegratorScratch::new(&model);
        let tau = [3.0]; // q̈ = 1.5
        let inputs = StepInputs { dt, tau: &tau, loads: Loads::none() };
        let (mut q, mut qd) = ([0.25], [-0.5]);
        step(integrator, &model, &mut ws, &mut scratch, &inputs, &mut q, &mut qd);
        (q[0], qd[0])
    }

    #[test]
    fn constant_acceleration() {
        // exact: q = q0 + qd0 dt + a dt²/2, qd = qd0 + a dt
        let (dt, a) = (0.1, 1.5);
        let (q, qd) = run(Integrator::Euler, dt);
        assert!((q - (0.25 - 0.5 * dt)).abs() < 1e-15 && (qd - (-0.5 + a * dt)).abs() < 1e-15);
        let (q, qd) = run(Integrator::SemiImplicitEuler, dt);
        assert!((q - (0.25 + (-0.5 + a * dt) * dt)).abs() < 1e-15 && (qd - (-0.5 + a * dt)).abs() < 1e-15);
        // RK4 is exact on a quadratic motion.
        let (q, qd) = run(Integrator::Rk4, dt);
        assert!((q - (0.25 - 0.5 * dt + 0.5 * a * dt * dt)).abs() < 1e-15 && (qd - (-0.5 + a * dt)).abs() < 1e-15);
    }

    #[test]
    fn generic_over_the_scalar() {
        // A pendulum under gravity, 20 RK4 steps in f32 and in f64: the same
        // code, agreeing to f32 precision.
        let model = RobotBuilder::new("pendulum")
            .link("base", None)
            .link("bob", Some(Inertial::new(1.5, [0.0, 0.0, -0.8], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("hinge", "base", "bob", [0.0, 1.0, 0.0]))
            .build()
            .unwrap();
        fn run<S: Scalar>(model: &Model) -> (f64, f64) {
            let mut ws = Workspace::<S>::new(model);
            let mut scratch = IntegratorScratch::<S>::new(model);
            let g = Vec3([S::zero(), S::zero(), S::from_f64(-9.81)]);
            let tau = [S::from_f64(0.5)];
            let inputs = StepInputs { dt: S::from_f64(0.01), tau: &tau, loads: Loads::gravity(&g) };
            let (mut q, mut qd) = ([S::from_f64(0.7)], [S::from_f64(-0.2)]);
            for _ in 0..20 {
                rk4(model, &mut ws, &mut scratch, &inputs, &mut q, &mut qd);
            }
            (q[0].to_f64().unwrap(), qd[0].to_f64().unwrap())
        }
        let (a, b) = (run::<f32>(&model), run::<f64>(&model));
        assert!((a.0 - b.0).abs() < 1e-5 && (a.1 - b.1).abs() < 1e-5, "{a:?} vs {b:?}");
        assert!((b.0 - 0.7).abs() > 1e-2, "the pendulum moved");
    }

    #[test]
    fn euler_step_is_modern_robotics() {
        // modern_robotics 1.1.1, EulerStep docstring example.
        let (mut q, mut qd) = ([0.1f64, 0.1, 0.1], [0.1f64, 0.2, 0.3]);
        euler_step(&mut q, &mut qd, &[2.0, 1.5, 1.0], 0.1);
        let (wq, wqd) = ([0.11, 0.12, 0.13], [0.3, 0.35, 0.4]);
        for i in 0..3 {
            assert!((q[i] - wq[i]).abs() < 1e-15 && (qd[i] - wqd[i]).abs() < 1e-15);
        }
    }

    /// A stiff joint spring-damper τ = −k·q − d·q̇ on the slider (mass 2 kg):
    /// ω = √(k/m) = 1000 rad/s, so dt = 0.01 s is 10 radians per step.
    fn spring_run(integrator: Integrator, dt: f64, steps: usize, k: f64, d: f64) -> (f64, f64) {
        let model = slider(2.0);
        let mut ws = Workspace::<f64>::new(&model);
        let mut scratch = IntegratorScratch::new(&model);
        let (mut q, mut qd) = ([0.1], [0.0]);
        for _ in 0..steps {
            step_with(integrator, &mut scratch, dt, &mut q, &mut qd, |q, qd, qdd| {
                let tau = [-k * q[0] - d * qd[0]];
                aba(&model, &mut ws, q, qd, &tau, Loads::none(), qdd);
            });
        }
        (q[0], qd[0])
    }

    #[test]
    fn implicit_euler_is_stable_where_explicit_schemes_blow_up() {
        let (k, d, dt) = (2e6, 10.0, 0.01);
        for explicit in [Integrator::Euler, Integrator::SemiImplicitEuler, Integrator::Rk4] {
            let (q, qd) = spring_run(explicit, dt, 100, k, d);
            assert!(!(q.abs() < 1e3 && qd.abs() < 1e3), "{explicit:?} should blow up, got q = {q:e}");
        }
        // Backward Euler damps every mode: the spring's energy decays.
        let (q, qd) = spring_run(Integrator::ImplicitEuler, dt, 100, k, d);
        assert!(q.abs() < 0.1 && (0.5 * 2.0 * qd * qd + 0.5 * k * q * q) < 0.5 * k * 0.01, "q = {q:e}, qd = {qd:e}");
        // At a step that resolves the oscillation, it agrees with RK4 to first order.
        let (qr, _) = spring_run(Integrator::Rk4, 1e-5, 1000, k, d);
        let (qi, _) = spring_run(Integrator::ImplicitEuler, 1e-6, 10000, k, d);
        assert!((qi - qr).abs() < 0.05 * 0.1, "implicit {qi:e} vs RK4 {qr:e}");
    }

    #[test]
    fn implicit_euler_converges_at_first_order() {
        // A double pendulum: the final state after 0.5 s against RK4 at a tiny
        // step; halving dt halves the error (ratio 2 ± 0.3).
        let model = RobotBuilder::new("double")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.0, 0.0, -0.5], [0.02, 0.02, 0.001, 0.0, 0.0, 0.0])))
            .link("b", Some(Inertial::new(0.7, [0.0, 0.0, -0.4], [0.01, 0.01, 0.001, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j1", "base", "a", [0.0, 1.0, 0.0]))
            .joint(JointDescription::revolute("j2", "a", "b", [0.0, 1.0, 0.0]).origin([0.0, 0.0, -1.0], [0.0; 3]))
            .build()
            .unwrap();
        let g = Vec3([0.0, 0.0, -9.81]);
        let tau = [0.3, -0.1];
        let run = |integrator: Integrator, steps: usize| {
            let mut ws = Workspace::<f64>::new(&model);
            let mut scratch = IntegratorScratch::new(&model);
            let dt = 0.5 / steps as f64;
            let inputs = StepInputs { dt, tau: &tau, loads: Loads::gravity(&g) };
            let (mut q, mut qd) = ([0.8, -0.4], [0.0, 0.5]);
            for _ in 0..steps {
                if integrator == Integrator::ImplicitEuler {
                    let out = implicit_euler(&model, &mut ws, &mut scratch, &inputs, &mut q, &mut qd);
                    assert!(out.converged, "Newton did not converge: {out:?}");
                } else {
                    step(integrator, &model, &mut ws, &mut scratch, &inputs, &mut q, &mut qd);
                }
            }
            [q[0], q[1], qd[0], qd[1]]
        };
        let reference = run(Integrator::Rk4, 4000);
        let err = |steps| {
            let x = run(Integrator::ImplicitEuler, steps);
            x.iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
        };
        let (e1, e2, e3) = (err(200), err(400), err(800));
        for (a, b) in [(e1, e2), (e2, e3)] {
            assert!((a / b - 2.0).abs() < 0.3, "errors {e1:e} {e2:e} {e3:e}: not first order");
        }
    }

    #[test]
    fn machine_epsilon_is_the_scalars() {
        assert_eq!(machine_epsilon::<f64>(), f64::EPSILON);
        assert_eq!(machine_epsilon::<f32>(), f32::EPSILON as f64);
    }
}
