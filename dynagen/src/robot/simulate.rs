//! Simulation in the numeric API: one integration step, and the Modern
//! Robotics library's trajectory functions (`InverseDynamicsTrajectory`,
//! `ForwardDynamicsTrajectory`) on nalgebra matrices.
//!
//! A trajectory is a matrix with one row per time step and one column per
//! joint (in [`Robot::joint_names`] order), as in the library. Units: rad,
//! rad/s, rad/s² (revolute) or m, m/s, m/s² (prismatic); torques N·m, forces
//! N; time s. Gravity is the robot's ([`Robot::set_gravity`]); the tip
//! wrenches set with [`Robot::set_tip_wrench`] act at every step, and a
//! per-row tip wrench history, when given, acts in addition to them.
//!
//! ```
//! use dynagen::model::{Inertial, JointDescription};
//! use dynagen::{Integrator, Robot, RobotBuilder, Stepping};
//! use nalgebra::{dvector, DMatrix};
//!
//! // A 1 kg bob on a massless 1 m rod, swinging about y from 0.5 rad.
//! let model = RobotBuilder::new("pendulum")
//!     .link("base", None)
//!     .link("bob", Some(Inertial::point_mass(1.0, [0.0, 0.0, -1.0])))
//!     .joint(JointDescription::revolute("hinge", "base", "bob", [0.0, 1.0, 0.0]))
//!     .build()
//!     .unwrap();
//! let mut robot = Robot::new(model);
//! let tau = DMatrix::zeros(21, 1); // no torque, 20 intervals of 0.05 s
//! let (q, qd) = robot
//!     .forward_dynamics_trajectory(&dvector![0.5], &dvector![0.0], &tau, None, Stepping::new(0.05, 4, Integrator::Rk4))
//!     .unwrap();
//! // Energy ½q̇² − 9.81·cos q (J) is conserved, to the integrator's error.
//! let energy = |k: usize| 0.5 * qd[(k, 0)].powi(2) - 9.81 * q[(k, 0)].cos();
//! assert!((energy(20) - energy(0)).abs() < 1e-6);
//! assert!(q[(20, 0)] < 0.0); // it has swung past the bottom
//! ```

use super::check::{self, Check, InputError};
use super::Robot;
use crate::algorithms::integrators::{self, Integrator, StepInputs};
use crate::algorithms::{rnea, Loads, TipWrench};
use crate::spatial::Force;
use nalgebra::{DMatrix, DVector};

/// A wrench history: the frame it acts at, and an N×6 matrix whose row k is
/// the wrench (m; f) (N·m; N) that the frame applies to its environment at
/// time step k, in the frame's own coordinates (the Modern Robotics
/// library's `Ftipmat`, with the frame `"ee"` for a robot built by
/// [`Model::from_modern_robotics`](crate::Model::from_modern_robotics)).
#[derive(Clone, Copy, Debug)]
pub struct TipWrenchHistory<'a> {
    /// The frame's name (a link name for URDF).
    pub frame: &'a str,
    /// N×6, one wrench per row.
    pub wrenches: &'a DMatrix<f64>,
}

/// How [`Robot::forward_dynamics_trajectory`] integrates: each interval of
/// `dt` seconds in `int_res` equal sub-steps of `integrator` (the Modern
/// Robotics library's `dt` and `intRes`, with [`Integrator::Euler`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stepping {
    /// The interval between two rows of the trajectory (s): finite and
    /// positive.
    pub dt: f64,
    /// The number of sub-steps per interval: at least 1.
    pub int_res: usize,
    /// The scheme of each sub-step.
    pub integrator: Integrator,
}

impl Stepping {
    /// `int_res` sub-steps of `integrator` per interval of `dt` seconds.
    pub fn new(dt: f64, int_res: usize, integrator: Integrator) -> Self {
        Stepping { dt, int_res, integrator }
    }
}

/// A trajectory's rows as the algorithms read them: row `r` of a joint-space
/// matrix into a slice, and the tip wrench history's row into the last tip
/// wrench, each checked (an error names the row).
struct Rows<'a> {
    check: Check<'a>,
    tip: Option<&'a TipWrenchHistory<'a>>,
}

impl Rows<'_> {
    /// Copies row `r` of `m` into `out` and checks it as a joint-space argument.
    fn load(&self, what: &'static str, m: &DMatrix<f64>, r: usize, out: &mut [f64]) -> Result<(), InputError> {
        for (o, x) in out.iter_mut().zip(m.row(r).iter()) {
            *o = *x;
        }
        self.check.joint_slice(what, out).map(|_| ()).map_err(|e| InputError::Row { row: r, error: Box::new(e) })
    }
    /// Sets the last tip wrench to row `r` of the history, if there is one.
    fn load_tip(&self, r: usize, tips: &mut [TipWrench<f64>]) -> Result<(), InputError> {
        if let (Some(t), Some(last)) = (self.tip, tips.last_mut()) {
            let w = t.wrenches.row(r);
            let w = [w[0], w[1], w[2], w[3], w[4], w[5]];
            last.wrench = check::wrench(&w).map_err(|e| InputError::Row { row: r, error: Box::new(e) })?;
        }
        Ok(())
    }
}

impl Robot {
    /// The tip wrenches of the robot, plus a slot for the history's wrench
    /// (its index in `Model::frames`, zero for now) when there is one.
    fn tips_with(&self, tip: Option<&TipWrenchHistory<'_>>, rows: usize) -> Result<Vec<TipWrench<f64>>, InputError> {
        let mut tips = self.tips.clone();
        if let Some(t) = tip {
            let frame = self.check().frame(t.frame)?;
            check::shape("the tip wrench history", t.wrenches, rows, 6)?;
            tips.push(TipWrench { frame, wrench: Force::zero() });
        }
        Ok(tips)
    }

    /// Advances the state (`q`, `qd`) by one step of `dt` seconds of the
    /// forward dynamics (articulated-body algorithm) with the joint torques
    /// `tau` held constant, under the robot's gravity and tip wrenches, with
    /// the scheme `integrator` (see [`integrators`]). `dt` must be finite and
    /// positive. Allocates nothing.
    pub fn step(
        &mut self,
        integrator: Integrator,
        q: &mut DVector<f64>,
        qd: &mut DVector<f64>,
        tau: &DVector<f64>,
        dt: f64,
    ) -> Result<(), InputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("tau", tau)])?.forward_dynamics()?;
        check::dt(dt)?;
        let g = self.model.gravity;
        let inputs = StepInputs { dt, tau: tau.as_slice(), loads: Loads::gravity(&g).with_tips(&self.tips) };
        let (q, qd) = (q.as_mut_slice(), qd.as_mut_slice());
        integrators::step(integrator, &self.model, &mut self.ws, &mut self.integ, &inputs, q, qd);
        Ok(())
    }

    /// The joint torques along a trajectory (the Modern Robotics library's
    /// `InverseDynamicsTrajectory`): row k of the result (N×n, N·m or N) is
    /// the inverse dynamics τ = M(q)q̈ + C(q, q̇)q̇ + g(q) + J(q)ᵀF_tip at row
    /// k of `q`, `qd` and `qdd` (each N×n), under the robot's gravity and tip
    /// wrenches plus, when `tip` is given, its row k.
    pub fn inverse_dynamics_trajectory(
        &mut self,
        q: &DMatrix<f64>,
        qd: &DMatrix<f64>,
        qdd: &DMatrix<f64>,
        tip: Option<TipWrenchHistory<'_>>,
    ) -> Result<DMatrix<f64>, InputError> {
        let (rows, nq, n) = (q.nrows(), self.model.nq(), self.model.nv());
        for (what, m, cols) in [("q", q, nq), ("qd", qd, n), ("qdd", qdd, n)] {
            check::shape(what, m, rows, cols)?;
        }
        let mut tips = self.tips_with(tip.as_ref(), rows)?;
        let (mut qr, mut qdr, mut qddr, mut taur) = (vec![0.0; nq], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut out = DMatrix::zeros(rows, n);
        let g = self.model.gravity;
        for r in 0..rows {
            let load = Rows { check: self.check(), tip: tip.as_ref() };
            load.load("q", q, r, &mut qr)?;
            load.load("qd", qd, r, &mut qdr)?;
            load.load("qdd", qdd, r, &mut qddr)?;
            load.load_tip(r, &mut tips)?;
            let loads = Loads::gravity(&g).with_tips(&tips);
            rnea::rnea(&self.model, &mut self.ws, &qr, Some(&qdr), Some(&qddr), loads, &mut taur);
            out.row_mut(r).copy_from_slice(&taur);
        }
        Ok(out)
    }

    /// Simulates the robot under a history of joint torques (the Modern
    /// Robotics library's `ForwardDynamicsTrajectory`).
    ///
    /// `tau` is N×n: row k acts, constant, from time k·dt to (k+1)·dt (s),
    /// together with the robot's gravity and tip wrenches and, when `tip` is
    /// given, its row k. Each interval is integrated in `int_res` equal
    /// sub-steps of `integrator` (see [`Stepping`]; the library uses
    /// [`Integrator::Euler`]). Returns (q, q̇), each N×n: row 0 is the
    /// initial state (`q0`, `qd0`) and row k+1 the state at time (k+1)·dt,
    /// so the last row of `tau` (and of the tip wrench history) is not used,
    /// as in the library.
    pub fn forward_dynamics_trajectory(
        &mut self,
        q0: &DVector<f64>,
        qd0: &DVector<f64>,
        tau: &DMatrix<f64>,
        tip: Option<TipWrenchHistory<'_>>,
        stepping: Stepping,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>), InputError> {
        let Stepping { dt, int_res, integrator } = stepping;
        let (rows, nq, n) = (tau.nrows(), self.model.nq(), self.model.nv());
        self.check().joints(&[("q0", q0), ("qd0", qd0)])?.forward_dynamics()?;
        check::shape("tau", tau, rows, n)?;
        check::dt(dt)?;
        if int_res == 0 {
            return Err(InputError::BadParameter { what: "int_res", value: 0.0, must: "at least 1" });
        }
        let mut tips = self.tips_with(tip.as_ref(), rows)?;
        let (mut q, mut qd) = (q0.as_slice().to_vec(), qd0.as_slice().to_vec());
        let mut taur = vec![0.0; n];
        let mut qs = DMatrix::zeros(rows, nq);
        let mut qds = DMatrix::zeros(rows, n);
        let h = dt / int_res as f64;
        let g = self.model.gravity;
        for r in 0..rows {
            qs.row_mut(r).copy_from_slice(&q);
            qds.row_mut(r).copy_from_slice(&qd);
            if r + 1 == rows {
                break;
            }
            let load = Rows { check: self.check(), tip: tip.as_ref() };
            load.load("tau", tau, r, &mut taur)?;
            load.load_tip(r, &mut tips)?;
            let inputs = StepInputs { dt: h, tau: &taur, loads: Loads::gravity(&g).with_tips(&tips) };
            for _ in 0..int_res {
                integrators::step(integrator, &self.model, &mut self.ws, &mut self.integ, &inputs, &mut q, &mut qd);
            }
        }
        Ok((qs, qds))
    }
}
