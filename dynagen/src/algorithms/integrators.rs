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
//!
//! Units: `dt` in s; q in rad (revolute) or m (prismatic), q̇ per s; τ in
//! N·m or N; gravity (m/s²) in the base frame; tip wrenches in their frames.

use super::aba::aba;
use super::{TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::Vec3;
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
}

/// What acts on the robot during a step, held constant over it.
#[derive(Clone, Copy, Debug)]
pub struct StepInputs<'a, S> {
    /// Joint torques (N·m) or forces (N), in joint order.
    pub tau: &'a [S],
    /// Gravity in the base frame (m/s²); `None` for none.
    pub gravity: Option<&'a Vec3<S>>,
    /// Wrenches the robot applies to its environment, each in its frame.
    pub tips: &'a [TipWrench<S>],
}

/// Scratch for the integrators: the accelerations and the intermediate
/// stages of [`rk4`]. Create it once per model, outside a control loop.
#[derive(Clone, Debug)]
pub struct IntegratorScratch<S> {
    /// The last accelerations computed (for Euler and semi-implicit Euler:
    /// q̈ at the start of the step).
    qdd: Vec<S>,
    /// Runge-Kutta stage position and velocity.
    q_stage: Vec<S>,
    qd_stage: Vec<S>,
    /// Runge-Kutta weighted sums of the stage slopes.
    q_sum: Vec<S>,
    qd_sum: Vec<S>,
}

impl<S: Scalar> IntegratorScratch<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.dof();
        IntegratorScratch {
            qdd: vec![S::zero(); n],
            q_stage: vec![S::zero(); n],
            qd_stage: vec![S::zero(); n],
            q_sum: vec![S::zero(); n],
            qd_sum: vec![S::zero(); n],
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

fn check<S: Scalar>(model: &Model, ws: &Workspace<S>, scratch: &IntegratorScratch<S>, q: &[S], qd: &[S], tau: &[S]) {
    let n = model.dof();
    assert!(
        q.len() == n && qd.len() == n && tau.len() == n && ws.dof() == n && scratch.dof() == n,
        "integrators: slices and scratch must have the model's {n} joints"
    );
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
    dt: S,
    q: &mut [S],
    qd: &mut [S],
) {
    check(model, ws, scratch, q, qd, inputs.tau);
    aba(model, ws, q, qd, inputs.tau, inputs.gravity, inputs.tips, &mut scratch.qdd);
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
    dt: S,
    q: &mut [S],
    qd: &mut [S],
) {
    check(model, ws, scratch, q, qd, inputs.tau);
    aba(model, ws, q, qd, inputs.tau, inputs.gravity, inputs.tips, &mut scratch.qdd);
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
    dt: S,
    q: &mut [S],
    qd: &mut [S],
) {
    check(model, ws, scratch, q, qd, inputs.tau);
    let n = q.len();
    let half = dt * S::from_f64(0.5);
    let IntegratorScratch { qdd, q_stage, qd_stage, q_sum, qd_sum } = scratch;
    q_stage.copy_from_slice(q);
    qd_stage.copy_from_slice(qd);
    // (weight of the stage's slope in the sum, offset of the next stage)
    let stages =
        [(S::one(), Some(half)), (S::from_f64(2.0), Some(half)), (S::from_f64(2.0), Some(dt)), (S::one(), None)];
    q_sum.fill(S::zero());
    qd_sum.fill(S::zero());
    for (weight, next) in stages {
        aba(model, ws, q_stage, qd_stage, inputs.tau, inputs.gravity, inputs.tips, qdd);
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

/// One step with the scheme `integrator`: [`euler`], [`semi_implicit_euler`]
/// or [`rk4`].
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints.
#[allow(clippy::too_many_arguments)]
pub fn step<S: Scalar>(
    integrator: Integrator,
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    dt: S,
    q: &mut [S],
    qd: &mut [S],
) {
    match integrator {
        Integrator::Euler => euler(model, ws, scratch, inputs, dt, q, qd),
        Integrator::SemiImplicitEuler => semi_implicit_euler(model, ws, scratch, inputs, dt, q, qd),
        Integrator::Rk4 => rk4(model, ws, scratch, inputs, dt, q, qd),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Inertial, JointDescription, RobotBuilder};

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
        let inputs = StepInputs { tau: &tau, gravity: None, tips: &[] };
        let (mut q, mut qd) = ([0.25], [-0.5]);
        step(integrator, &model, &mut ws, &mut scratch, &inputs, dt, &mut q, &mut qd);
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
            let inputs = StepInputs { tau: &tau, gravity: Some(&g), tips: &[] };
            let (mut q, mut qd) = ([S::from_f64(0.7)], [S::from_f64(-0.2)]);
            for _ in 0..20 {
                rk4(model, &mut ws, &mut scratch, &inputs, S::from_f64(0.01), &mut q, &mut qd);
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
}
