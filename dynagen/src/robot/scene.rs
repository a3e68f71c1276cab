//! The numeric API of a scene, [`SceneRobot`]: the generic solver on `f64`
//! and nalgebra types, with the scene's armature, friction, gravity and
//! run-time inputs ([`SceneInputs`]). Its arguments are checked as a
//! [`Robot`](crate::Robot)'s are, in `robot/check.rs`.

mod derivatives;

use super::check::{self, Check};
use super::{frame_acceleration_bias, frame_jacobian, frame_pose, matrix, vector, InputError, Jacobian};
use crate::algorithms::{Loads, TipWrench, Workspace};
use crate::scene::dynamics;
use crate::scene::{PayloadInertia, ResolvedGravity, SceneError, SceneModel};
use crate::spatial::{Inertia, Vec3};
use nalgebra::{DMatrix, DVector, Matrix4, Matrix6xX, Vector3, Vector6};

/// The run-time inputs of a scene, for the `*_with` calls of [`SceneRobot`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SceneInputs<'a> {
    /// Gravity in the reduced model's base frame (m/s²), when the scene's
    /// gravity is [`Gravity::Input`](crate::scene::Gravity::Input).
    pub gravity: Option<Vector3<f64>>,
    /// The wrench (m; f) the tip frame applies to its environment, in that
    /// frame, when the scene has a tip wrench.
    pub tip_wrench: Option<Vector6<f64>>,
    /// One value per input payload, in the order of
    /// [`SceneModel::input_payloads`].
    pub payloads: &'a [PayloadInertia],
}

/// A bad argument to a [`SceneRobot`] call.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneInputError {
    /// A wrong length or a non-finite entry.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The scene makes this an input, and the call uses it, but it was not
    /// given.
    #[error("the scene makes {0} a run-time input: pass it in SceneInputs to the `_with` call")]
    MissingInput(&'static str),
    /// An input the scene does not declare.
    #[error("{0} was given, but the scene does not make it a run-time input")]
    UnexpectedInput(&'static str),
    /// A payload value that no body has, or the wrong number of them.
    #[error(transparent)]
    Payload(#[from] SceneError),
}

/// A scene with the generic `f64` solver.
///
/// The run-time inputs (gravity, tip wrench, payloads) go in a
/// [`SceneInputs`] to the `*_with` calls, and only when the scene makes them
/// inputs: an input the scene does not declare is an error, and so is a
/// declared input missing from a call that uses it. The plain calls are the
/// `*_with` calls with no inputs, for scenes that have none. Units, joint
/// order and input checks are those of [`Robot`](crate::Robot); calls
/// allocate only their result.
///
/// ```
/// use dynagen::scene::{Gravity, Scene, SceneInputs, SceneRobot};
/// use nalgebra::{DVector, Vector3};
/// let model = dynagen::Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap();
/// let scene = Scene::new().gravity(Gravity::Input).armature("elbow_joint", 0.2).apply(&model).unwrap();
/// let mut robot = SceneRobot::new(scene);
/// let q = DVector::from_element(6, 0.3);
/// let inputs = SceneInputs { gravity: Some(Vector3::new(0.0, 0.0, -9.81)), ..Default::default() };
/// let g = robot.gravity_torques_with(&q, &inputs).unwrap();
/// assert!(robot.gravity_torques(&q).is_err()); // gravity is an input
/// let m = robot.mass_matrix(&q).unwrap(); // M needs no gravity
/// assert!(m[(2, 2)] > 0.2 && g.len() == 6);
/// ```
#[derive(Clone, Debug)]
pub struct SceneRobot {
    scene: SceneModel,
    /// Body inertias without the input payloads.
    base_inertia: Vec<Inertia<f64>>,
    /// The floating base's inertia without the input payloads.
    root_inertia: Inertia<f64>,
    ws: Workspace<f64>,
    tips: Vec<TipWrench<f64>>,
    jac: Vec<f64>,
    /// Scratch of the derivatives.
    deriv: super::derivatives::DerivativeScratch,
}

/// What a call reads.
#[derive(Clone, Copy)]
struct Uses {
    gravity: bool,
    tip: bool,
}

impl SceneRobot {
    /// Wraps an applied scene.
    pub fn new(scene: SceneModel) -> Self {
        let nv = scene.model.nv();
        let ws = Workspace::new(&scene.model);
        let base_inertia = scene.model.bodies.iter().map(|b| b.inertia).collect();
        let root_inertia = scene.model.base_inertia;
        let deriv = super::derivatives::DerivativeScratch::new(&scene.model);
        SceneRobot { scene, base_inertia, root_inertia, ws, tips: Vec::with_capacity(1), jac: vec![0.0; 6 * nv], deriv }
    }
    /// The applied scene (its model's inertias include the input payloads of
    /// the last call).
    pub fn scene(&self) -> &SceneModel {
        &self.scene
    }
    /// The number of joints (n, without a floating base's six).
    pub fn dof(&self) -> usize {
        self.scene.dof()
    }
    /// The length of a configuration q: n, or n + 7 with a floating base.
    pub fn nq(&self) -> usize {
        self.scene.model.nq()
    }
    /// The length of q̇, q̈, τ and the side of M: n, or n + 6 with a
    /// floating base.
    pub fn nv(&self) -> usize {
        self.scene.model.nv()
    }
    /// The joint names, in the order of every vector and matrix index.
    pub fn joint_names(&self) -> Vec<&str> {
        self.scene.joint_names()
    }

    /// The checks of this robot's arguments.
    fn check(&self) -> Check<'_> {
        Check(&self.scene.model)
    }

    /// Checks the inputs against the scene, sets the tip wrench and the
    /// payloads, and returns gravity.
    fn prepare(&mut self, inputs: &SceneInputs<'_>, uses: Uses) -> Result<Option<Vec3<f64>>, SceneInputError> {
        let gravity_input = self.scene.gravity == ResolvedGravity::Input;
        if inputs.gravity.is_some() && !gravity_input {
            return Err(SceneInputError::UnexpectedInput("gravity"));
        }
        if inputs.tip_wrench.is_some() && self.scene.tip_wrench_frame.is_none() {
            return Err(SceneInputError::UnexpectedInput("a tip wrench"));
        }
        if !inputs.payloads.is_empty() && self.scene.input_payloads.is_empty() {
            return Err(SceneInputError::UnexpectedInput("a payload"));
        }
        let gravity = match (&self.scene.gravity, inputs.gravity) {
            (ResolvedGravity::Input, Some(g)) => Some(check::gravity(&g)?),
            (ResolvedGravity::Input, None) if uses.gravity => return Err(SceneInputError::MissingInput("gravity")),
            (g, _) => match g {
                ResolvedGravity::Constant(v) => Some(Vec3(*v)),
                _ => None,
            },
        };
        self.tips.clear();
        if let (Some(frame), true) = (self.scene.tip_wrench_frame, uses.tip) {
            let w = inputs.tip_wrench.ok_or(SceneInputError::MissingInput("a tip wrench"))?;
            self.tips.push(TipWrench { frame, wrench: check::wrench(w.as_slice())? });
        }
        if !self.scene.input_payloads.is_empty() {
            if inputs.payloads.is_empty() {
                return Err(SceneInputError::MissingInput("the payloads"));
            }
            if inputs.payloads.len() != self.scene.input_payloads.len() {
                return Err(SceneError::PayloadSpec {
                    link: self.scene.input_payloads.iter().map(|p| p.link.as_str()).collect::<Vec<_>>().join(", "),
                    why: "the number of payload values differs from the number of input payloads",
                }
                .into());
            }
            for (p, v) in self.scene.input_payloads.iter().zip(inputs.payloads) {
                v.check(&p.link)?;
            }
            // On a fixed base a payload on the base moves nothing; a
            // floating base carries it.
            let model = &mut self.scene.model;
            let floating = model.is_floating();
            model.base_inertia = self.root_inertia;
            for p in &self.scene.input_payloads {
                if let Some(b) = p.body {
                    model.bodies[b].inertia = self.base_inertia[b];
                }
            }
            for (p, v) in self.scene.input_payloads.iter().zip(inputs.payloads) {
                match p.body {
                    Some(b) => model.bodies[b].inertia = model.bodies[b].inertia.add(&p.inertia_in_body(v)),
                    None if floating => model.base_inertia = model.base_inertia.add(&p.inertia_in_body(v)),
                    None => {}
                }
            }
        }
        Ok(gravity)
    }

    /// Inverse dynamics τ = M(q)q̈ + h(q, q̇) + J(q)ᵀF_tip with armature and
    /// friction, for a scene without inputs.
    pub fn inverse_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> Result<DVector<f64>, SceneInputError> {
        self.inverse_dynamics_with(q, qd, qdd, &SceneInputs::default())
    }
    /// [`inverse_dynamics`](Self::inverse_dynamics) with the scene's inputs
    /// (gravity, tip wrench, payloads).
    pub fn inverse_dynamics_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DVector<f64>, SceneInputError> {
        vector(self.nv(), |tau| self.inverse_dynamics_into(q, qd, qdd, inputs, tau))
    }
    /// [`inverse_dynamics_with`](Self::inverse_dynamics_with) into `tau`,
    /// allocating nothing.
    pub fn inverse_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        tau: &mut DVector<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("qdd", qdd)])?.output("tau", tau)?;
        let g = self.prepare(inputs, Uses { gravity: true, tip: true })?;
        let loads = Loads::new(g.as_ref(), &self.tips, &[]);
        let (q, qd, qdd) = (q.as_slice(), qd.as_slice(), qdd.as_slice());
        dynamics::inverse_dynamics(&self.scene, &mut self.ws, q, qd, qdd, loads, tau.as_mut_slice());
        Ok(())
    }

    /// The mass matrix M(q) + diag(armature), for a scene without input
    /// payloads.
    pub fn mass_matrix(&mut self, q: &DVector<f64>) -> Result<DMatrix<f64>, SceneInputError> {
        self.mass_matrix_with(q, &SceneInputs::default())
    }
    /// [`mass_matrix`](Self::mass_matrix) with the scene's inputs (only the
    /// payloads matter).
    pub fn mass_matrix_with(
        &mut self,
        q: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DMatrix<f64>, SceneInputError> {
        matrix(self.nv(), |m| self.mass_matrix_into(q, inputs, m))
    }
    /// [`mass_matrix_with`](Self::mass_matrix_with) into `m` (n×n),
    /// allocating nothing.
    pub fn mass_matrix_into(
        &mut self,
        q: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        m: &mut DMatrix<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q)])?.square("M", m)?;
        self.prepare(inputs, Uses { gravity: false, tip: false })?;
        // M is symmetric, so row-major and nalgebra's column-major agree.
        dynamics::mass_matrix(&self.scene, &mut self.ws, q.as_slice(), m.as_mut_slice());
        Ok(())
    }

    /// The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q) + friction (no tip
    /// wrench), for a scene without inputs.
    pub fn bias_forces(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, SceneInputError> {
        self.bias_forces_with(q, qd, &SceneInputs::default())
    }
    /// [`bias_forces`](Self::bias_forces) with the scene's inputs (gravity,
    /// payloads; a tip wrench is not part of h and is ignored).
    pub fn bias_forces_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DVector<f64>, SceneInputError> {
        vector(self.nv(), |h| self.bias_forces_into(q, qd, inputs, h))
    }
    /// [`bias_forces_with`](Self::bias_forces_with) into `h`, allocating
    /// nothing.
    pub fn bias_forces_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        h: &mut DVector<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q), ("qd", qd)])?.output("h", h)?;
        let g = self.prepare(inputs, Uses { gravity: true, tip: false })?;
        dynamics::bias_forces(&self.scene, &mut self.ws, q.as_slice(), qd.as_slice(), g.as_ref(), h.as_mut_slice());
        Ok(())
    }

    /// The gravity torques g(q) (zero when the scene has no gravity), for a
    /// scene without inputs.
    pub fn gravity_torques(&mut self, q: &DVector<f64>) -> Result<DVector<f64>, SceneInputError> {
        self.gravity_torques_with(q, &SceneInputs::default())
    }
    /// [`gravity_torques`](Self::gravity_torques) with the scene's inputs
    /// (gravity, payloads).
    pub fn gravity_torques_with(
        &mut self,
        q: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DVector<f64>, SceneInputError> {
        vector(self.nv(), |g| self.gravity_torques_into(q, inputs, g))
    }
    /// [`gravity_torques_with`](Self::gravity_torques_with) into `out`,
    /// allocating nothing.
    pub fn gravity_torques_into(
        &mut self,
        q: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        out: &mut DVector<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q)])?.output("g", out)?;
        let g = self.prepare(inputs, Uses { gravity: true, tip: false })?;
        dynamics::gravity_torques(&self.scene, &mut self.ws, q.as_slice(), g.as_ref(), out.as_mut_slice());
        Ok(())
    }

    /// The Coriolis and centripetal torques C(q, q̇)q̇, for a scene without
    /// input payloads.
    pub fn coriolis(&mut self, q: &DVector<f64>, qd: &DVector<f64>) -> Result<DVector<f64>, SceneInputError> {
        self.coriolis_with(q, qd, &SceneInputs::default())
    }
    /// [`coriolis`](Self::coriolis) with the scene's inputs (only the
    /// payloads matter).
    pub fn coriolis_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DVector<f64>, SceneInputError> {
        vector(self.nv(), |c| self.coriolis_into(q, qd, inputs, c))
    }
    /// [`coriolis_with`](Self::coriolis_with) into `c`, allocating nothing.
    pub fn coriolis_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        c: &mut DVector<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q), ("qd", qd)])?.output("C qd", c)?;
        self.prepare(inputs, Uses { gravity: false, tip: false })?;
        dynamics::coriolis(&self.scene, &mut self.ws, q.as_slice(), qd.as_slice(), c.as_mut_slice());
        Ok(())
    }

    /// Forward dynamics q̈ = M_s(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip), for a scene
    /// without inputs: by the articulated-body algorithm, with the armature
    /// in its joint inertias (see [`dynamics::forward_dynamics`]).
    pub fn forward_dynamics(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, SceneInputError> {
        self.forward_dynamics_with(q, qd, tau, &SceneInputs::default())
    }
    /// [`forward_dynamics`](Self::forward_dynamics) with the scene's inputs.
    pub fn forward_dynamics_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DVector<f64>, SceneInputError> {
        vector(self.nv(), |qdd| self.forward_dynamics_into(q, qd, tau, inputs, qdd))
    }
    /// [`forward_dynamics_with`](Self::forward_dynamics_with) into `qdd`,
    /// allocating nothing.
    pub fn forward_dynamics_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        inputs: &SceneInputs<'_>,
        qdd: &mut DVector<f64>,
    ) -> Result<(), SceneInputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("tau", tau)])?.forward_dynamics()?.output("qdd", qdd)?;
        let g = self.prepare(inputs, Uses { gravity: true, tip: true })?;
        let loads = Loads::new(g.as_ref(), &self.tips, &[]);
        let (q, qd, tau) = (q.as_slice(), qd.as_slice(), tau.as_slice());
        dynamics::forward_dynamics(&self.scene, &mut self.ws, q, qd, tau, loads, qdd.as_mut_slice());
        Ok(())
    }

    /// The pose of a frame in the reduced model's base frame (the sub-tree
    /// root; a floating base: the world frame), 4×4 homogeneous: what
    /// `frame_pose_FRAME` computes.
    pub fn frame_pose(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix4<f64>, SceneInputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_pose(&self.scene.model, &mut self.ws, (f, false), q))
    }
    /// The body Jacobian of a frame (6×n or 6×NV, rows (ω; v), in the
    /// frame): `J_bᵀF` is the torque of a wrench `F` given in the frame;
    /// `frame_jacobian_FRAME`.
    pub fn frame_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, SceneInputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_jacobian(&self.scene.model, &mut self.ws, (f, Jacobian::Body), q, &mut self.jac))
    }
    /// The Jacobian of a frame in the world frame (the base frame of a
    /// fixed base): its twist at the world origin, world axes (the space
    /// Jacobian); `frame_world_jacobian_FRAME`.
    pub fn frame_world_jacobian(&mut self, frame: &str, q: &DVector<f64>) -> Result<Matrix6xX<f64>, SceneInputError> {
        let f = self.check().frame(frame)?;
        self.check().joints(&[("q", q)])?;
        Ok(frame_jacobian(&self.scene.model, &mut self.ws, (f, Jacobian::Space), q, &mut self.jac))
    }
    /// The classical acceleration bias J̇q̇ of a frame ((angular; linear)
    /// in the frame, as [`Robot::frame_acceleration_bias`](crate::Robot::frame_acceleration_bias));
    /// `frame_acceleration_bias_FRAME`.
    pub fn frame_acceleration_bias(
        &mut self,
        frame: &str,
        q: &DVector<f64>,
        qd: &DVector<f64>,
    ) -> Result<Vector6<f64>, SceneInputError> {
        Ok(frame_acceleration_bias(&self.scene.model, &mut self.ws, frame, q, qd)?)
    }
}
