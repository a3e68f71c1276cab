//! The functions a module can have: one enum, and the one table of each
//! function's arguments, output shape and documentation.

use super::emit::{doc_code, identifier_name, payload_argument, Dim, Param, Shape, Sizes};
use crate::scene::{ResolvedGravity, SceneModel};
use crate::symbolic::OpCount;
use std::fmt::Write;
use std::str::FromStr;

/// A function code generation can emit. The Rust name of each is
/// [`Function::rust_name`]; the frame functions (`FramePose`,
/// `FrameJacobian`, `FrameWorldJacobian`, `FrameAccelerationBias`) name a
/// frame (link) of the robot.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Function {
    /// `inverse_dynamics(q, qd, qdd) -> τ` by the recursive Newton-Euler
    /// algorithm (with a scene's armature, friction and tip wrench).
    InverseDynamics,
    /// `mass_matrix(q) -> M` by the composite-rigid-body algorithm, armature
    /// included.
    MassMatrix,
    /// `bias_forces(q, qd) -> h = C(q, q̇)q̇ + g(q) + friction`.
    BiasForces,
    /// `gravity_torques(q) -> g(q)`.
    GravityTorques,
    /// `coriolis(q, qd) -> C(q, q̇)q̇`.
    Coriolis,
    /// `forward_dynamics(q, qd, tau) -> q̈`, by the articulated-body
    /// algorithm or CRBA + LᵀDL (see [`ForwardDynamicsMethod`](super::ForwardDynamicsMethod)).
    ForwardDynamics,
    /// `inverse_dynamics_derivatives(q, qd, qdd) -> (∂τ/∂q, ∂τ/∂q̇)`, each
    /// `[output][input]` (∂τ/∂q̈ is the mass matrix); generated only on
    /// request.
    InverseDynamicsDerivatives,
    /// `forward_dynamics_derivatives(q, qd, tau) -> (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹)`,
    /// each `[output][input]` (M⁻¹ = ∂q̈/∂τ); generated only on request.
    ForwardDynamicsDerivatives,
    /// `mass_matrix_inverse(q) -> M⁻¹`, from the sparse LᵀDL factors;
    /// generated only on request.
    MassMatrixInverse,
    /// `frame_pose_FRAME(q)`: the pose of a frame in the base frame (a
    /// floating base: in the world frame).
    FramePose(String),
    /// `frame_jacobian_FRAME(q)`: the body Jacobian of a frame (in the
    /// frame itself: JᵀF is the torque of a wrench given in that frame;
    /// Pinocchio's `LOCAL`), 6 × DOF (6 × NV on a floating base).
    FrameJacobian(String),
    /// `frame_world_jacobian_FRAME(q)`: the space Jacobian of a frame, its
    /// twist at the world origin in world axes (Pinocchio's `WORLD`; on a
    /// fixed base the world is the base frame).
    FrameWorldJacobian(String),
    /// `frame_acceleration_bias_FRAME(q, qd)`: the classical acceleration
    /// bias J̇q̇ of a frame, its acceleration at q̈ = 0 in its own axes
    /// (angular; linear), so that a contact holding the frame's origin
    /// still is `J q̈ + J̇q̇ = 0` in the linear rows of `frame_jacobian`.
    FrameAccelerationBias(String),
}

impl Function {
    /// What a module has unless told otherwise: the five functions of the
    /// generated-code contract.
    pub const DEFAULT: [Function; 5] = [
        Function::InverseDynamics,
        Function::MassMatrix,
        Function::BiasForces,
        Function::GravityTorques,
        Function::ForwardDynamics,
    ];
    /// The names of the functions without a frame, in the order a module
    /// lists them.
    pub const NAMES: [&'static str; 9] = [
        "inverse_dynamics",
        "mass_matrix",
        "bias_forces",
        "gravity_torques",
        "coriolis",
        "forward_dynamics",
        "inverse_dynamics_derivatives",
        "forward_dynamics_derivatives",
        "mass_matrix_inverse",
    ];

    /// The kinds of frame function, as TOML and the option lists spell
    /// them (`KIND:FRAME` in a list of functions).
    pub const FRAME_KINDS: [&'static str; 4] =
        ["frame_pose", "frame_jacobian", "frame_world_jacobian", "frame_acceleration_bias"];

    /// The frame function of kind `kind` (one of [`FRAME_KINDS`](Self::FRAME_KINDS))
    /// for `frame`, if `kind` is one.
    pub fn frame_function(kind: &str, frame: &str) -> Option<Function> {
        let frame = frame.to_string();
        Some(match kind {
            "frame_pose" => Function::FramePose(frame),
            "frame_jacobian" => Function::FrameJacobian(frame),
            "frame_world_jacobian" => Function::FrameWorldJacobian(frame),
            "frame_acceleration_bias" => Function::FrameAccelerationBias(frame),
            _ => return None,
        })
    }
    /// The frame a frame function names (`None` for the others).
    pub fn frame(&self) -> Option<&str> {
        match self {
            Function::FramePose(f)
            | Function::FrameJacobian(f)
            | Function::FrameWorldJacobian(f)
            | Function::FrameAccelerationBias(f) => Some(f),
            _ => None,
        }
    }

    /// The function without a frame named `name`, if it is one.
    pub fn from_name(name: &str) -> Option<Function> {
        Some(match name.trim() {
            "inverse_dynamics" => Function::InverseDynamics,
            "mass_matrix" => Function::MassMatrix,
            "bias_forces" => Function::BiasForces,
            "gravity_torques" => Function::GravityTorques,
            "coriolis" => Function::Coriolis,
            "forward_dynamics" => Function::ForwardDynamics,
            "inverse_dynamics_derivatives" => Function::InverseDynamicsDerivatives,
            "forward_dynamics_derivatives" => Function::ForwardDynamicsDerivatives,
            "mass_matrix_inverse" => Function::MassMatrixInverse,
            _ => return None,
        })
    }
    /// The function's kind as TOML and the option lists spell it (one of
    /// [`FRAME_KINDS`](Self::FRAME_KINDS) for the frame functions).
    pub fn name(&self) -> &'static str {
        match self {
            Function::InverseDynamics => "inverse_dynamics",
            Function::MassMatrix => "mass_matrix",
            Function::BiasForces => "bias_forces",
            Function::GravityTorques => "gravity_torques",
            Function::Coriolis => "coriolis",
            Function::ForwardDynamics => "forward_dynamics",
            Function::InverseDynamicsDerivatives => "inverse_dynamics_derivatives",
            Function::ForwardDynamicsDerivatives => "forward_dynamics_derivatives",
            Function::MassMatrixInverse => "mass_matrix_inverse",
            Function::FramePose(_) => "frame_pose",
            Function::FrameJacobian(_) => "frame_jacobian",
            Function::FrameWorldJacobian(_) => "frame_world_jacobian",
            Function::FrameAccelerationBias(_) => "frame_acceleration_bias",
        }
    }
    /// The function's name in generated code (`frame_pose_ee_link` for a
    /// frame function: the frame's name in snake case, ASCII letters and
    /// digits, every other run of characters one `_`).
    pub fn rust_name(&self) -> String {
        match self.frame() {
            Some(frame) => identifier_name(self.name(), frame),
            None => self.name().to_string(),
        }
    }
    /// The state vectors it takes, in argument order.
    pub fn vectors(&self) -> &'static [&'static str] {
        match self {
            Function::InverseDynamics | Function::InverseDynamicsDerivatives => &["q", "qd", "qdd"],
            Function::BiasForces | Function::Coriolis => &["q", "qd"],
            Function::ForwardDynamics | Function::ForwardDynamicsDerivatives => &["q", "qd", "tau"],
            Function::FrameAccelerationBias(_) => &["q", "qd"],
            _ => &["q"],
        }
    }
    /// Which run-time loads of a scene it reads: (gravity, tip wrench,
    /// payloads).
    pub(crate) fn loads(&self) -> (bool, bool, bool) {
        match self {
            Function::InverseDynamics
            | Function::ForwardDynamics
            | Function::InverseDynamicsDerivatives
            | Function::ForwardDynamicsDerivatives => (true, true, true),
            Function::BiasForces | Function::GravityTorques => (true, false, true),
            Function::MassMatrix | Function::Coriolis | Function::MassMatrixInverse => (false, false, true),
            Function::FramePose(_)
            | Function::FrameJacobian(_)
            | Function::FrameWorldJacobian(_)
            | Function::FrameAccelerationBias(_) => (false, false, false),
        }
    }
    /// Its arguments in `scene`: the state vectors, then the scene's
    /// run-time inputs it reads (gravity, tip wrench, payloads).
    pub(crate) fn params(&self, scene: &SceneModel) -> Vec<Param> {
        // With a floating base, q has NQ entries and the velocity-side vectors NV.
        let floating = scene.model.is_floating();
        let dim = |v: &str| match (floating, v) {
            (false, _) => Dim::Dof,
            (true, "q") => Dim::Nq,
            (true, _) => Dim::Nv,
        };
        let mut p: Vec<Param> = self.vectors().iter().map(|v| Param::sized(v, dim(v))).collect();
        let (gravity, tip, payloads) = self.loads();
        if gravity && scene.gravity == ResolvedGravity::Input {
            p.push(Param::fixed("gravity", 3));
        }
        if tip && scene.tip_wrench_frame.is_some() {
            p.push(Param::fixed("f_tip", 6));
        }
        if payloads {
            p.extend(scene.input_payloads.iter().map(|pl| Param::fixed(&payload_argument(&pl.link), 10)));
        }
        p
    }
    /// Whether it is a derivative of the dynamics (or M⁻¹): generated only
    /// on request, never listed as left out of a module.
    pub fn is_derivative(&self) -> bool {
        matches!(
            self,
            Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives | Function::MassMatrixInverse
        )
    }
    /// Its output's shape (velocity-side lengths NV with a floating base).
    pub(crate) fn shape(&self, floating: bool) -> Shape {
        let v = if floating { Dim::Nv } else { Dim::Dof };
        match self {
            Function::MassMatrix | Function::MassMatrixInverse => Shape::Matrix(v, v),
            Function::InverseDynamicsDerivatives => Shape::Matrices(2, v, v),
            Function::ForwardDynamicsDerivatives => Shape::Matrices(3, v, v),
            Function::FramePose(_) => Shape::Matrix(Dim::Fixed(4), Dim::Fixed(4)),
            Function::FrameJacobian(_) | Function::FrameWorldJacobian(_) => Shape::Matrix(Dim::Fixed(6), v),
            Function::FrameAccelerationBias(_) => Shape::Vector(Dim::Fixed(6)),
            _ => Shape::Vector(v),
        }
    }
    /// The number of outputs of a module of these sizes.
    pub(crate) fn output_len(&self, n: Sizes) -> usize {
        match self.shape(n.floating()) {
            Shape::Vector(d) => d.value(n),
            Shape::Matrix(r, c) => r.value(n) * c.value(n),
            Shape::Matrices(k, r, c) => k * r.value(n) * c.value(n),
        }
    }
    /// The doc comment of `NAME` in `scene`'s module (`count`: its
    /// operations). A scene without armature, friction or tip wrench says
    /// what a plain module says.
    pub(crate) fn doc(&self, scene: &SceneModel, ldlt: bool, count: &OpCount) -> String {
        let plain = scene.is_plain();
        let floating = scene.model.is_floating();
        let (world, cols, torque) =
            if floating { ("world", "NV", "generalised force") } else { ("base", "DOF", "joint torque") };
        let what = match self {
            Function::InverseDynamics if plain => {
                "Inverse dynamics τ = M(q)q̈ + C(q, q̇)q̇ + g(q) by the recursive Newton-Euler algorithm.".to_string()
            }
            Function::InverseDynamics => "Inverse dynamics τ = (M(q) + diag(armature))q̈ + C(q, q̇)q̇ + g(q) + friction + J(q)ᵀF_tip, by the recursive Newton-Euler algorithm.".to_string(),
            Function::MassMatrix if plain => {
                "The mass matrix M(q) by the composite-rigid-body algorithm (symmetric, `[row][col]`).".to_string()
            }
            Function::MassMatrix => "The mass matrix M(q) + diag(armature) by the composite-rigid-body algorithm (symmetric, `[row][col]`).".to_string(),
            Function::BiasForces if plain => "The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q).".to_string(),
            Function::BiasForces => "The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q) + friction.".to_string(),
            Function::GravityTorques => "The gravity torques g(q).".to_string(),
            Function::Coriolis => "The Coriolis and centripetal torques C(q, q̇)q̇.".to_string(),
            Function::ForwardDynamics if plain && ldlt => {
                "Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇)) by CRBA, RNEA and a sparse LᵀDL solve.".to_string()
            }
            Function::ForwardDynamics if plain => {
                "Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇)) by the articulated-body algorithm.".to_string()
            }
            Function::ForwardDynamics => {
                "Forward dynamics q̈ = (M(q) + diag(armature))⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip).".to_string()
            }
            Function::InverseDynamicsDerivatives => format!(
                "The derivatives (∂τ/∂q, ∂τ/∂q̇) of the inverse dynamics{}, each `[output][input]`: `[i][j] = ∂τᵢ/∂xⱼ`; ∂τ/∂q̈ is the mass matrix. Forward-mode (dual-number) derivatives of the recursive Newton-Euler algorithm{}.",
                if plain { "" } else { " (armature, friction and tip wrench included)" },
                if plain { "" } else { "; the run-time inputs are held constant" }
            ),
            Function::ForwardDynamicsDerivatives => format!(
                "The derivatives (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) of the forward dynamics{}, each `[output][input]`: `[i][j] = ∂q̈ᵢ/∂xⱼ`; M⁻¹ = ∂q̈/∂τ. −M⁻¹ ∂τ/∂x at q̈ = M⁻¹(τ − h), M⁻¹ from the sparse LᵀDL factors{}.",
                if plain { "" } else { " (armature, friction and tip wrench included)" },
                if plain { "" } else { "; the run-time inputs are held constant" }
            ),
            Function::MassMatrixInverse if plain => "The inverse of the mass matrix M(q)⁻¹ from its sparse LᵀDL factors (symmetric, `[row][col]`).".to_string(),
            Function::MassMatrixInverse => "The inverse (M(q) + diag(armature))⁻¹ from its sparse LᵀDL factors (symmetric, `[row][col]`).".to_string(),
            Function::FramePose(frame) => format!(
                "The pose of frame {} in the {} frame, as a homogeneous matrix `[row][col]`.",
                doc_code(frame),
                world
            ),
            Function::FrameJacobian(frame) => format!(
                "The body Jacobian of frame {} (6 × {cols}, rows (ω; v), in the frame): its twist is `J q̇`, and `Jᵀ F` is the {torque} of a wrench `F` given in the frame.",
                doc_code(frame)
            ),
            Function::FrameWorldJacobian(frame) => format!(
                "The space Jacobian of frame {} in the {world} frame (6 × {cols}, rows (ω; v)): `J q̇` is its twist at the {world} origin, in {world} axes.",
                doc_code(frame)
            ),
            Function::FrameAccelerationBias(frame) => format!(
                "The classical acceleration bias J̇q̇ of frame {}: its acceleration at q̈ = 0, (angular; linear) in the frame, the linear part that of the frame's origin. With `J` the body Jacobian its acceleration is `J q̈ + J̇q̇`: a contact holding the origin still is `J[3..6] q̈ + J̇q̇[3..6] = 0` (world axes: rotate both by the pose's rotation).",
                doc_code(frame)
            ),
        };
        // What the vectors hold: a floating base's conventions, or the joint order.
        let layout = if floating {
            "Floating base: `q` = [p (world), quaternion (x, y, z, w) world ← base, joints] (`NQ`), \
             the velocity-side vectors [ω_b, v_b (the base's body twist, base frame), joints] (`NV`), τ's first six \
             the wrench on the base (m; f) in the base frame; joints in [`JOINT_NAMES`] order; rad, m, s, N·m, N"
        } else {
            "Joint order: [`JOINT_NAMES`]; rad, m, s, N·m, N"
        };
        let quaternion = if floating { " The quaternion is used as given (the caller keeps it unit)." } else { "" };
        if plain {
            let g = scene.model.gravity.0;
            return format!(" {what}\n\n {layout}; gravity {g:?} m/s² in the {world} frame.{quaternion}\n {count}.");
        }
        let mut args = String::new();
        for p in self.params(scene) {
            let what = match p.name.as_str() {
                "gravity" => format!("`gravity`: m/s², in the {world} frame."),
                "f_tip" => {
                    let frame = scene.tip_wrench_frame.map(|i| scene.model.frames[i].name.as_str()).unwrap_or("");
                    format!(
                        "`f_tip`: the wrench (m; f) frame {} applies to its environment, in that frame (N·m; N).",
                        doc_code(frame)
                    )
                }
                name if name.starts_with("payload_") => format!(
                    "`{name}`: [mass, cx, cy, cz, ixx, iyy, izz, ixy, ixz, iyz], kg, m and kg·m² about the centre of mass, in the link's frame."
                ),
                _ => continue,
            };
            let _ = write!(args, "\n {what}");
        }
        format!(" {what}\n\n {layout}.{quaternion}{args}\n {count}.")
    }
}

impl FromStr for Function {
    type Err = String;
    /// A function without a frame by its name, or `KIND:FRAME` for a frame
    /// function (`frame_pose:FRAME`, …); the error says what the names are.
    fn from_str(s: &str) -> Result<Function, String> {
        let s = s.trim();
        if let Some(f) = Function::from_name(s) {
            return Ok(f);
        }
        match s.split_once(':') {
            Some((kind, frame)) if !frame.trim().is_empty() => Function::frame_function(kind.trim(), frame.trim()),
            _ => None,
        }
        .ok_or_else(|| format!("unknown function \"{s}\" (the functions are {})", Function::all_names()))
    }
}

impl Function {
    /// Every function's spelling, for messages: the names, then
    /// `KIND:FRAME` for each frame function.
    pub fn all_names() -> String {
        let frames = Function::FRAME_KINDS.iter().map(|k| format!("{k}:FRAME"));
        Function::NAMES.iter().map(|n| n.to_string()).chain(frames).collect::<Vec<_>>().join(", ")
    }
}
