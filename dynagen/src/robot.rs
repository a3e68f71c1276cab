//! The numeric API: the generic solver on `f64` and nalgebra types, for any
//! robot at run time.
//!
//! A [`Robot`] owns its [`Model`] and the scratch the algorithms need, so
//! that after construction the `*_into` calls allocate nothing (for control
//! loops); the other calls allocate only their result. Every call checks its
//! inputs: a wrong length or a non-finite value is an [`InputError`] naming
//! the argument and the joint, never a panic or a NaN result.
//!
//! Units: rad, rad/s, rad/s² for revolute joints, m, m/s, m/s² for
//! prismatic ones; torques in N·m, forces in N. Joint order is
//! [`Robot::joint_names`]. Spatial vectors are (angular; linear).

use crate::algorithms::compensated::CompensatedSolver;
use crate::algorithms::integrators::IntegratorScratch;
use crate::algorithms::{aba, bias, crba, forward_dynamics, kinematics, rnea, Loads, TipWrench, Workspace};
use crate::model::{BuildOptions, Model, ModelError};
use crate::spatial::{Force, Vec3};
use nalgebra::{DMatrix, DVector, Matrix4, Matrix6xX, Vector3, Vector6};
use std::path::Path;

/// A bad argument to a numeric call.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// A vector or matrix of the wrong size.
    #[error("{what} has {got} entries, but the robot has {expected} joints")]
    WrongLength {
        /// The argument (`q`, `qd`, …).
        what: &'static str,
        /// Its length.
        got: usize,
        /// The robot's number of joints.
        expected: usize,
    },
    /// A NaN or infinite entry.
    #[error("{what}[{index}] (joint \"{joint}\") is {value}, not a finite number")]
    NonFinite {
        /// The argument.
        what: &'static str,
        /// The entry.
        index: usize,
        /// The joint it belongs to.
        joint: String,
        /// The value.
        value: f64,
    },
    /// A non-finite gravity or tip wrench.
    #[error("{0} is not finite")]
    NonFiniteLoad(&'static str),
    /// An unknown frame name.
    #[error("no frame named \"{0}\"")]
    UnknownFrame(String),
    /// A matrix of the wrong shape (a trajectory's, or a tip wrench history).
    #[error("{what} is {rows}×{cols}, but it must be {expected_rows}×{expected_cols}")]
    WrongShape {
        /// The argument.
        what: &'static str,
        /// Its number of rows.
        rows: usize,
        /// Its number of columns.
        cols: usize,
        /// The rows it must have.
        expected_rows: usize,
        /// The columns it must have.
        expected_cols: usize,
    },
    /// A bad entry in one row of a trajectory.
    #[error("row {row}: {error}")]
    Row {
        /// The row (time step), from 0.
        row: usize,
        /// What is wrong in it.
        error: Box<InputError>,
    },
    /// A bad integration parameter (time step, number of sub-steps).
    #[error("{what} is {value}, but it must be {must}")]
    BadParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        must: &'static str,
    },
}

/// Checks that a joint-space argument has one finite entry per joint.
pub(crate) fn check_joint_vector(model: &Model, what: &'static str, x: &[f64]) -> Result<(), InputError> {
    let n = model.dof();
    if x.len() != n {
        return Err(InputError::WrongLength { what, got: x.len(), expected: n });
    }
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => {
            Err(InputError::NonFinite { what, index, joint: model.bodies[index].joint.name.clone(), value: x[index] })
        }
        None => Ok(()),
    }
}

/// Checks that an output has the length `want`.
pub(crate) fn check_output_length(
    model: &Model,
    what: &'static str,
    len: usize,
    want: usize,
) -> Result<(), InputError> {
    if len != want {
        return Err(InputError::WrongLength { what, got: len, expected: model.dof() });
    }
    Ok(())
}

/// A robot with the generic `f64` solver, on nalgebra types: units, frames
/// and joint order as in the crate documentation.
#[derive(Clone, Debug)]
pub struct Robot {
    pub(crate) model: Model,
    pub(crate) ws: Workspace<f64>,
    pub(crate) tips: Vec<TipWrench<f64>>,
    jac: Vec<f64>,
    pub(crate) integ: IntegratorScratch<f64>,
    /// Scratch of [`Robot::forward_dynamics_compensated`].
    pub(crate) comp: CompensatedSolver,
}

impl Robot {
    /// Wraps a model.
    pub fn new(model: Model) -> Self {
        let ws = Workspace::new(&model);
        let jac = vec![0.0; 6 * model.dof()];
        let integ = IntegratorScratch::new(&model);
        let comp = CompensatedSolver::new(&model);
        Robot { model, ws, tips: Vec::new(), jac, integ, comp }
    }
    /// Reads a URDF file.
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Self, ModelError> {
        Ok(Self::new(Model::from_urdf_file(path)?))
    }
    /// Reads a URDF file, with options (strict inertia checks).
    pub fn from_urdf_file_with(path: impl AsRef<Path>, opts: &BuildOptions) -> Result<Self, ModelError> {
        Ok(Self::new(Model::from_urdf_file_with(path, opts)?))
    }
    /// Reads a URDF document from a string.
    pub fn from_urdf_str(xml: &str) -> Result<Self, ModelError> {
        Ok(Self::new(Model::from_urdf_str(xml)?))
    }
    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }
    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.model.dof()
    }
    /// The joint names, in the order of every vector and matrix index.
    pub fn joint_names(&self) -> Vec<&str> {
        self.model.joint_names()
    }
    /// Gravity in the base frame (m/s²).
    pub fn gravity(&self) -> Vector3<f64> {
        Vector3::from(self.model.gravity.0)
    }
    /// Sets gravity in the base frame (m/s²).
    pub fn set_gravity(&mut self, g: Vector3<f64>) -> Result<(), InputError> {
        if !g.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFiniteLoad("gravity"));
        }
        self.model.gravity = Vec3([g.x, g.y, g.z]);
        Ok(())
    }
    /// Sets the wrench (m; f) that frame `frame` applies to its environment,
    /// in that frame (the Modern Robotics `Ftip`). It enters
    /// [`inverse_dynamics`](Self::inverse_dynamics) and
    /// [`forward_dynamics`](Self::forward_dynamics) until cleared.
    pub fn set_tip_wrench(&mut self, frame: &str, wrench: Vector6<f64>) -> Result<(), InputError> {
        let idx = self.model.frame_index(frame).ok_or_else(|| InputError::UnknownFrame(frame.to_string()))?;
        if !wrench.iter().all(|x| x.is_finite()) {
            return Err(InputError::NonFiniteLoad("tip wrench"));
        }
        let w = Force::from_array([wrench[0], wrench[1], wrench[2], wrench[3], wrench[4], wrench[5]]);
        match self.tips.iter_mut().find(|t| t.frame == idx) {
            Some(t) => t.wrench = w,
            None => self.tips.push(TipWrench { frame: idx, wrench: w }),
        }
        Ok(())
    }
    /// Removes every tip wrench.
    pub fn clear_tip_wrenches(&mut self) {
        self.tips.clear();
    }

    pub(crate) fn check(&self, what: &'static str, x: &[f64]) -> Result<(), InputError> {
        check_joint_vector(&self.model, what, x)
    }
    pub(crate) fn check_out(&self, what: &'static str, len: usize, want: usize) -> Result<(), InputError> {
        check_output_length(&self.model, what, len, want)
    }
    pub(crate) fn frame(&self, frame: &str) -> Result<usize, InputError> {
        self.model.frame_index(frame).ok_or_else(|| InputError::UnknownFrame(frame.to_string()))
    }

    /// Inverse dynamics τ = M(q)q̈ + C(q, q̇)q̇ + g(q) + J(q)ᵀF_tip by the
    /// recursive Newton-Euler algorithm.
    pub fn inverse_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        let mut tau = DVector::zeros(self.dof());
        self.inverse_dynamics_into(q, qd, qdd, &mut tau)?;
        Ok(tau)
    }
    /// [`inverse_dynamics`](Self::inverse_dynamics) into `tau`, allocating nothing.
    pub fn inverse_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        tau: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check("q", q.as_slice())?;
        self.check("qd", qd.as_slice())?;
        self.check("qdd", qdd.as_slice())?;
        self.check_out("tau", tau.len(), self.dof())?;
        let g = self.model.gravity;
        rnea::rnea(
            &self.model,
            &mut self.ws,
            q.as_slice(),
            Some(qd.as_slice()),
            Some(qdd.as_slice()),
            Loads::gravity(&g).with_tips(&self.tips),
            tau.as_mut_slice(),
        );
        Ok(())
    }

    /// The mass matrix M(q) (symmetric positive definite) by the
    /// composite-rigid-body algorithm.
    pub fn mass_matrix(&mut self, q: &DVector<f64>) -> Result<DMatrix<f64>, InputError> {
        let n = self.dof();
        let mut m = DMatrix::zeros(n, n);
        self.mass_matrix_into(q, &mut m)?;
        Ok(m)
    }
    /// [`mass_matrix`](Self::mass_matrix) into `m` (n×n), allocating nothing.
    pub fn mass_matrix_into(&mut self, q: &DVector<f64>, m: &mut DMatrix<f64>) -> Result<(), InputError> {
        self.check("q", q.as_slice())?;
        let n = self.dof();
        if m.nrows() != n || m.ncols() != n {
            return Err(InputError::WrongLength { what: "M", got: m.len(), expected: n });
        }
        // M is symmetric, so row-major and nalgebra's column-major agree.
        crba::crba(&self.model, &mut self.ws, q.as_slice(), Loads::none(), m.as_mut_slice());
        Ok(())
    }

    /// The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q).
    pub fn bias_forces(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        let mut h = DVector::zeros(self.dof());
        self.bias_forces_into(q, qd, &mut h)?;
        Ok(h)
    }
    /// [`bias_forces`](Self::bias_forces) into `h`, allocating nothing.
    pub fn bias_forces_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        h: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check("q", q.as_slice())?;
        self.check("qd", qd.as_slice())?;
        self.check_out("h", h.len(), self.dof())?;
        let g = self.model.gravity;
        bias::bias_forces(&self.model, &mut self.ws, q.as_slice(), qd.as_slice(), Some(&g), h.as_mut_slice());
        Ok(())
    }

    /// The gravity torques g(q).
    pub fn gravity_torques(&mut self, q: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        let mut g = DVector::zeros(self.dof());
        self.gravity_torques_into(q, &mut g)?;
        Ok(g)
    }
    /// [`gravity_torques`](Self::gravity_torques) into `out`, allocating nothing.
    pub fn gravity_torques_into(&mut self, q: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), InputError> {
        self.check("q", q.as_slice())?;
        self.check_out("g", out.len(), self.dof())?;
        let g = self.model.gravity;
        bias::gravity_torques(&self.model, &mut self.ws, q.as_slice(), &g, out.as_mut_slice());
        Ok(())
    }

    /// The Coriolis and centripetal torques C(q, q̇)q̇ (Modern Robotics'
    /// `VelQuadraticForces`).
    pub fn coriolis_torques(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        self.check("q", q.as_slice())?;
        self.check("qd", qd.as_slice())?;
        let mut c = DVector::zeros(self.dof());
        bias::coriolis_torques(&self.model, &mut self.ws, q.as_slice(), qd.as_slice(), c.as_mut_slice());
        Ok(c)
    }

    /// The joint torques J(q)ᵀF_tip that the tip wrenches set with
    /// [`set_tip_wrench`](Self::set_tip_wrench) cost (Modern Robotics'
    /// `EndEffectorForces`).
    pub fn tip_wrench_torques(&mut self, q: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        self.check("q", q.as_slice())?;
        let mut t = DVector::zeros(self.dof());
        bias::tip_wrench_torques(&self.model, &mut self.ws, q.as_slice(), &self.tips, t.as_mut_slice());
        Ok(t)
    }

    /// Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip) by the
    /// articulated-body algorithm, the most accurate method here.
    pub fn forward_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        let mut qdd = DVector::zeros(self.dof());
        self.forward_dynamics_into(q, qd, tau, &mut qdd)?;
        Ok(qdd)
    }
    /// [`forward_dynamics`](Self::forward_dynamics) into `qdd`, allocating nothing.
    pub fn forward_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        qdd: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check("q", q.as_slice())?;
        self.check("qd", qd.as_slice())?;
        self.check("tau", tau.as_slice())?;
        self.check_out("qdd", qdd.len(), self.dof())?;
        let g = self.model.gravity;
        aba::aba(
            &self.model,
            &mut self.ws,
            q.as_slice(),
            qd.as_slice(),
            tau.as_slice(),
            Loads::gravity(&g).with_tips(&self.tips),
            qdd.as_mut_slice(),
        );
        Ok(())
    }
    /// Forward dynamics through the mass matrix: M by the composite-rigid-
    /// body algorithm and a sparse LᵀDL solve, as *Modern Robotics* writes it.
    pub fn forward_dynamics_ldlt(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        self.check("q", q.as_slice())?;
        self.check("qd", qd.as_slice())?;
        self.check("tau", tau.as_slice())?;
        let mut qdd = DVector::zeros(self.dof());
        let g = self.model.gravity;
        forward_dynamics::forward_dynamics_ldlt(
            &self.model,
            &mut self.ws,
            q.as_slice(),
            qd.as_slice(),
            tau.as_slice(),
            Loads::gravity(&g).with_tips(&self.tips),
            qdd.as_mut_slice(),
        );
        Ok(qdd)
    }

    /// The pose T_sb of a frame (a link name for URDF) in the base frame.
    pub fn frame_pose(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix4<f64>, InputError> {
        let f = self.frame(frame)?;
        self.check("q", q.as_slice())?;
        kinematics::forward_kinematics(&self.model, &mut self.ws, q.as_slice());
        let t = kinematics::frame_pose(&self.model, &self.ws, f).to_homogeneous();
        Ok(Matrix4::from_fn(|r, c| t[r][c]))
    }
    /// The space Jacobian J_s(q) of a frame (6×n, rows (ω; v)): see
    /// [`kinematics::space_jacobian`].
    pub fn space_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        let f = self.frame(frame)?;
        self.check("q", q.as_slice())?;
        kinematics::forward_kinematics(&self.model, &mut self.ws, q.as_slice());
        kinematics::space_jacobian(&self.model, &self.ws, f, &mut self.jac);
        Ok(Matrix6xX::from_row_slice(&self.jac))
    }
    /// The body Jacobian J_b(q) of a frame (6×n, rows (ω; v)), in the frame.
    pub fn body_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        let f = self.frame(frame)?;
        self.check("q", q.as_slice())?;
        kinematics::forward_kinematics(&self.model, &mut self.ws, q.as_slice());
        kinematics::body_jacobian(&self.model, &self.ws, f, &mut self.jac);
        Ok(Matrix6xX::from_row_slice(&self.jac))
    }
}
