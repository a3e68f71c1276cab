//! The numeric API: the generic solver on `f64` and nalgebra types, for any
//! robot at run time ([`Robot`]), and for a scene ([`SceneRobot`](crate::SceneRobot), with its
//! armature, friction and run-time inputs).
//!
//! A [`Robot`] owns its [`Model`] and the scratch the algorithms need, so
//! that after construction the `*_into` calls allocate nothing (for control
//! loops); the other calls allocate only their result. Every call checks its
//! inputs (in [`check`], for both kinds of robot): a wrong length or a
//! non-finite value is an [`InputError`] naming the argument and the joint,
//! never a panic or a NaN result.
//!
//! Units: rad, rad/s, rad/s² for revolute joints, m, m/s, m/s² for
//! prismatic ones; torques in N·m, forces in N. Joint order is
//! [`Robot::joint_names`]. Spatial vectors are (angular; linear).
//!
//! A floating-base robot ([`Model::with_floating_base`]) takes NQ = n + 7
//! long configurations `[p, quaternion (x, y, z, w), joints]` (the
//! quaternion of unit norm within 1e-6) and NV = n + 6 long velocities,
//! accelerations and forces `[ω_b, v_b, joints]` (the base's body twist or
//! wrench, base frame); M is NV×NV; gravity is in the world frame, and so
//! are frame poses and space Jacobians.

mod check;
mod compensated;
mod derivatives;
mod floating_base;
pub(crate) mod scene;
mod simulate;

pub use check::InputError;
pub use simulate::{Stepping, TipWrenchHistory};

use crate::algorithms::compensated::CompensatedSolver;
use crate::algorithms::integrators::IntegratorScratch;
use crate::algorithms::{
    aba, bias, crba, floating, forward_dynamics, frame_acceleration, kinematics, rnea, Loads, TipWrench, Workspace,
};
use crate::model::{BuildOptions, Model, ModelError};
use check::Check;
use nalgebra::{DMatrix, DVector, Matrix4, Matrix6xX, Vector3, Vector6};
use std::path::Path;

/// A vector of `n` zeros filled by `into`: the allocating form of an
/// `*_into` call.
fn vector<E>(n: usize, into: impl FnOnce(&mut DVector<f64>) -> Result<(), E>) -> Result<DVector<f64>, E> {
    let mut out = DVector::zeros(n);
    into(&mut out)?;
    Ok(out)
}

/// An n×n matrix of zeros filled by `into`.
fn matrix<E>(n: usize, into: impl FnOnce(&mut DMatrix<f64>) -> Result<(), E>) -> Result<DMatrix<f64>, E> {
    let mut out = DMatrix::zeros(n, n);
    into(&mut out)?;
    Ok(out)
}

/// The pose of frame `frame` of `model` at `q`, 4×4 homogeneous in the base
/// frame (in the world for a floating base, unless `in_base`).
fn frame_pose(
    model: &Model,
    ws: &mut Workspace<f64>,
    (frame, in_base): (usize, bool),
    q: &DVector<f64>,
) -> Matrix4<f64> {
    let q = q.as_slice();
    let t = if model.is_floating() {
        floating::kinematics::forward_kinematics(model, ws, q);
        match in_base {
            true => kinematics::frame_pose(model, ws, frame),
            false => floating::kinematics::frame_pose_world(model, ws, q, frame),
        }
    } else {
        kinematics::forward_kinematics(model, ws, q);
        kinematics::frame_pose(model, ws, frame)
    }
    .to_homogeneous();
    Matrix4::from_fn(|r, c| t[r][c])
}

/// Which Jacobian of a frame.
#[derive(Clone, Copy)]
enum Jacobian {
    /// In the world frame (J_s; on a fixed base, the base frame).
    Space,
    /// In the frame itself (J_b).
    Body,
    /// In the base frame, at the base origin (on a fixed base, J_s).
    Base,
}

/// A Jacobian of frame `frame` of `model` at `q` (6×n, rows (ω; v)), with
/// `jac` (6n entries) as scratch.
fn frame_jacobian(
    model: &Model,
    ws: &mut Workspace<f64>,
    (frame, which): (usize, Jacobian),
    q: &DVector<f64>,
    jac: &mut [f64],
) -> Matrix6xX<f64> {
    let q = q.as_slice();
    if model.is_floating() {
        floating::kinematics::forward_kinematics(model, ws, q);
        match which {
            Jacobian::Space => floating::kinematics::space_jacobian_world(model, ws, q, frame, jac),
            Jacobian::Body => floating::kinematics::body_jacobian(model, ws, frame, jac),
            Jacobian::Base => floating::kinematics::space_jacobian_base(model, ws, frame, jac),
        }
        return Matrix6xX::from_row_slice(jac);
    }
    kinematics::forward_kinematics(model, ws, q);
    match which {
        Jacobian::Space | Jacobian::Base => kinematics::space_jacobian(model, ws, frame, jac),
        Jacobian::Body => kinematics::body_jacobian(model, ws, frame, jac),
    }
    Matrix6xX::from_row_slice(jac)
}

/// J̇q̇ of the frame named `frame` of `model` at (q, q̇), (angular; linear)
/// in the frame, the arguments checked.
fn frame_acceleration_bias(
    model: &Model,
    ws: &mut Workspace<f64>,
    frame: &str,
    q: &DVector<f64>,
    qd: &DVector<f64>,
) -> Result<Vector6<f64>, InputError> {
    let f = Check(model).frame(frame)?;
    Check(model).joints(&[("q", q), ("qd", qd)])?;
    let a = frame_acceleration::frame_acceleration_bias(model, ws, q.as_slice(), qd.as_slice(), f);
    Ok(Vector6::from(a.to_array()))
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
    /// Scratch of the derivatives.
    pub(crate) deriv: derivatives::DerivativeScratch,
}

impl Robot {
    /// Wraps a model.
    pub fn new(model: Model) -> Self {
        let ws = Workspace::new(&model);
        let jac = vec![0.0; 6 * model.nv()];
        let integ = IntegratorScratch::new(&model);
        let comp = CompensatedSolver::new(&model);
        let deriv = derivatives::DerivativeScratch::new(&model);
        Robot { model, ws, tips: Vec::new(), jac, integ, comp, deriv }
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
    /// The number of joints (n, without a floating base's six).
    pub fn dof(&self) -> usize {
        self.model.dof()
    }
    /// The length of a configuration q: n, or n + 7 with a floating base.
    pub fn nq(&self) -> usize {
        self.model.nq()
    }
    /// The length of q̇, q̈, τ and the side of M: n, or n + 6 with a
    /// floating base.
    pub fn nv(&self) -> usize {
        self.model.nv()
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
        self.model.gravity = check::gravity(&g)?;
        Ok(())
    }
    /// Sets the wrench (m; f) that frame `frame` applies to its environment,
    /// in that frame (the Modern Robotics `Ftip`). It enters
    /// [`inverse_dynamics`](Self::inverse_dynamics) and
    /// [`forward_dynamics`](Self::forward_dynamics) until cleared.
    pub fn set_tip_wrench(&mut self, frame: &str, wrench: Vector6<f64>) -> Result<(), InputError> {
        let idx = self.check().frame(frame)?;
        let w = check::wrench(wrench.as_slice())?;
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

    /// The checks of this robot's arguments.
    fn check(&self) -> Check<'_> {
        Check(&self.model)
    }

    /// Inverse dynamics τ = M(q)q̈ + C(q, q̇)q̇ + g(q) + J(q)ᵀF_tip by the
    /// recursive Newton-Euler algorithm.
    pub fn inverse_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        vector(self.model.nv(), |tau| self.inverse_dynamics_into(q, qd, qdd, tau))
    }
    /// [`inverse_dynamics`](Self::inverse_dynamics) into `tau`, allocating nothing.
    pub fn inverse_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        tau: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("qdd", qdd)])?.output("tau", tau)?;
        let g = self.model.gravity;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let (q, qd, qdd) = (q.as_slice(), qd.as_slice(), qdd.as_slice());
        rnea::rnea(&self.model, &mut self.ws, q, Some(qd), Some(qdd), loads, tau.as_mut_slice());
        Ok(())
    }

    /// The mass matrix M(q) (symmetric positive definite) by the
    /// composite-rigid-body algorithm.
    pub fn mass_matrix(&mut self, q: &DVector<f64>) -> Result<DMatrix<f64>, InputError> {
        matrix(self.model.nv(), |m| self.mass_matrix_into(q, m))
    }
    /// [`mass_matrix`](Self::mass_matrix) into `m` (n×n), allocating nothing.
    pub fn mass_matrix_into(&mut self, q: &DVector<f64>, m: &mut DMatrix<f64>) -> Result<(), InputError> {
        self.check().joints(&[("q", q)])?.square("M", m)?;
        // M is symmetric, so row-major and nalgebra's column-major agree.
        crba::crba(&self.model, &mut self.ws, q.as_slice(), Loads::none(), m.as_mut_slice());
        Ok(())
    }

    /// The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q).
    pub fn bias_forces(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        vector(self.model.nv(), |h| self.bias_forces_into(q, qd, h))
    }
    /// [`bias_forces`](Self::bias_forces) into `h`, allocating nothing.
    pub fn bias_forces_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        h: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check().joints(&[("q", q), ("qd", qd)])?.output("h", h)?;
        let g = self.model.gravity;
        bias::bias_forces(&self.model, &mut self.ws, q.as_slice(), qd.as_slice(), Some(&g), h.as_mut_slice());
        Ok(())
    }

    /// The gravity torques g(q).
    pub fn gravity_torques(&mut self, q: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        vector(self.model.nv(), |g| self.gravity_torques_into(q, g))
    }
    /// [`gravity_torques`](Self::gravity_torques) into `out`, allocating nothing.
    pub fn gravity_torques_into(&mut self, q: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), InputError> {
        self.check().joints(&[("q", q)])?.output("g", out)?;
        let g = self.model.gravity;
        bias::gravity_torques(&self.model, &mut self.ws, q.as_slice(), &g, out.as_mut_slice());
        Ok(())
    }

    /// The Coriolis and centripetal torques C(q, q̇)q̇ (Modern Robotics'
    /// `VelQuadraticForces`).
    pub fn coriolis_torques(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        self.check().joints(&[("q", q), ("qd", qd)])?;
        vector(self.model.nv(), |c| {
            bias::coriolis_torques(&self.model, &mut self.ws, q.as_slice(), qd.as_slice(), c.as_mut_slice());
            Ok(())
        })
    }

    /// The joint torques J(q)ᵀF_tip that the tip wrenches set with
    /// [`set_tip_wrench`](Self::set_tip_wrench) cost (Modern Robotics'
    /// `EndEffectorForces`).
    pub fn tip_wrench_torques(&mut self, q: &DVector<f64>) -> Result<DVector<f64>, InputError> {
        self.check().joints(&[("q", q)])?;
        vector(self.model.nv(), |t| {
            bias::tip_wrench_torques(&self.model, &mut self.ws, q.as_slice(), &self.tips, t.as_mut_slice());
            Ok(())
        })
    }

    /// Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip) by the
    /// articulated-body algorithm, the most accurate method here.
    pub fn forward_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        vector(self.model.nv(), |qdd| self.forward_dynamics_into(q, qd, tau, qdd))
    }
    /// [`forward_dynamics`](Self::forward_dynamics) into `qdd`, allocating nothing.
    pub fn forward_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        qdd: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("tau", tau)])?.forward_dynamics()?.output("qdd", qdd)?;
        let g = self.model.gravity;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let (q, qd, tau) = (q.as_slice(), qd.as_slice(), tau.as_slice());
        aba::aba(&self.model, &mut self.ws, q, qd, tau, loads, qdd.as_mut_slice());
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
        self.check().joints(&[("q", q), ("qd", qd), ("tau", tau)])?.forward_dynamics()?;
        let g = self.model.gravity;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let (q, qd, tau) = (q.as_slice(), qd.as_slice(), tau.as_slice());
        vector(self.model.nv(), |qdd| {
            forward_dynamics::forward_dynamics_ldlt(&self.model, &mut self.ws, q, qd, tau, loads, qdd.as_mut_slice());
            Ok(())
        })
    }

    /// The pose T_sb of a frame (a link name for URDF) in the base frame
    /// (a floating base: in the world frame).
    pub fn frame_pose(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix4<f64>, InputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_pose(&self.model, &mut self.ws, (f, false), q))
    }
    /// The pose of a frame in the base frame (the same as
    /// [`frame_pose`](Self::frame_pose) on a fixed base).
    pub fn frame_pose_in_base(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix4<f64>, InputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_pose(&self.model, &mut self.ws, (f, true), q))
    }
    /// The space Jacobian J_s(q) of a frame (6×n, rows (ω; v); a floating
    /// base: 6×NV, in the world frame, Pinocchio's `WORLD`): see
    /// [`kinematics::space_jacobian`].
    pub fn space_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        self.jacobian(frame, Jacobian::Space, q)
    }
    /// The body Jacobian J_b(q) of a frame (6×n or 6×NV, rows (ω; v)), in
    /// the frame (Pinocchio's `LOCAL`).
    pub fn body_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        self.jacobian(frame, Jacobian::Body, q)
    }
    /// The Jacobian of a frame in the base frame: its twist at the base
    /// origin in base axes (a floating base's own six columns the
    /// identity); on a fixed base the space Jacobian.
    pub fn base_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        self.jacobian(frame, Jacobian::Base, q)
    }
    /// The classical acceleration bias J̇q̇ of a frame: its acceleration at
    /// q̈ = 0, (angular; linear) in the frame, the linear part the
    /// acceleration of the frame's origin, so that `body_jacobian · q̈ +
    /// J̇q̇` is the frame's classical acceleration (a contact holding the
    /// point: the linear rows = 0); see
    /// [`frame_acceleration`](crate::algorithms::frame_acceleration).
    pub fn frame_acceleration_bias(
        &mut self,
        frame: &str,
        q: &DVector<f64>,
        qd: &DVector<f64>,
    ) -> Result<Vector6<f64>, InputError> {
        frame_acceleration_bias(&self.model, &mut self.ws, frame, q, qd)
    }
    fn jacobian(&mut self, frame: &str, which: Jacobian, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_jacobian(&self.model, &mut self.ws, (f, which), q, &mut self.jac))
    }
}
