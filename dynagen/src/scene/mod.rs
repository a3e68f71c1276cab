//! Scenes: what a controller needs from the robot, and nothing more.
//!
//! A [`Scene`] says the physics: where gravity comes from, whether a tip
//! wrench is a run-time input, which part of the robot to keep (a
//! sub-tree), which joints to lock, which payloads to carry, and the
//! armature and friction of each joint. What code to write (the functions,
//! the scalar, the trigonometry, …) is
//! [`CodegenOptions`](crate::codegen::CodegenOptions)'. [`Scene::apply`]
//! turns a [`Model`] and a scene into a [`SceneModel`]: the reduced model
//! with every constant folded in, plus the per-joint vectors and run-time
//! inputs. The generic solver runs it through [`SceneRobot`]; code
//! generation ([`generate_scene`](crate::codegen::generate_scene), the
//! `Builder`'s `.scene(..)`, `dynagen generate --scene`, the macros' scene
//! keys) consumes the same [`SceneModel`] and traces the same functions,
//! [`dynamics`]. A plain module is the default scene's.
//!
//! # The equations of a scene
//!
//! With `a` the armature (reflected rotor inertia), `b` the viscous and `f`
//! the Coulomb friction coefficients of each joint, and `F_tip` the tip
//! wrench (zero unless the scene makes it an input):
//!
//! ```text
//! M_s(q)      = M(q) + diag(a)
//! friction    = b∘q̇ + f∘σ(q̇),     σ(v) = v / sqrt(v² + v_ε²)
//! h_s(q, q̇)   = C(q, q̇)q̇ + g(q) + friction
//! g_s(q)      = g(q)                               (friction is not in g)
//! τ           = M_s(q)q̈ + h_s(q, q̇) + J(q)ᵀF_tip
//! q̈           = M_s(q)⁻¹(τ − h_s(q, q̇) − J(q)ᵀF_tip)
//! ```
//!
//! where M, C, g and J are those of the reduced model. `coriolis` is
//! C(q, q̇)q̇ alone.
//!
//! **Coulomb friction** is smoothed: sign(q̇) has no derivative at 0, and the
//! algorithms cannot branch on the state (the same code is traced
//! symbolically; [`Scalar`](crate::Scalar) has no comparison and no tanh).
//! σ(v) = v/√(v² + v_ε²) needs one square root and one division, is odd,
//! smooth, strictly increasing and bounded by 1; σ(v_ε) = 0.707,
//! σ(10 v_ε) = 0.995, σ(100 v_ε) = 0.99995. The default smoothing velocity
//! v_ε is [`DEFAULT_COULOMB_VELOCITY`] = 0.01 rad/s (or m/s), set by
//! [`Scene::coulomb_velocity`]. A smaller v_ε is closer to sign(q̇) but
//! makes forward dynamics stiffer (the slope at rest is f/v_ε). Generated
//! code takes the square root from std (`f64::sqrt`, with
//! [`Trig::Std`](crate::codegen::Trig::Std)), from `libm` ([`Trig::Libm`](crate::codegen::Trig::Libm),
//! `no_std_libm`), or else from the module's own `sqrt`, which needs
//! neither and is correctly rounded like the other two: every target
//! generates Coulomb friction.
//!
//! # Reductions
//!
//! - **Locked joints** become fixed joints at their lock positions: the
//!   joint's transform at that position becomes part of the placement and
//!   the bodies merge (the reduced model has fewer bodies).
//! - **Sub-tree** (a root link and tip links): the moving joints on the
//!   paths from the root to the tips are kept. Everything below a tip is
//!   merged rigidly into the tip's body, each joint there at its lock
//!   position if the scene locks it and at zero otherwise. Bodies that hang
//!   off a kept body (or off the root's body) through a joint that is not on
//!   a path are **dropped**, with a [`SceneWarning::DroppedBranch`]: their
//!   mass no longer loads the kept joints. For a branch off the root this
//!   changes nothing (the fixed base carries it); for a branch off a moving
//!   body it is the model of a controller that ignores that branch (one arm
//!   of a two-armed robot, say), and keeps it independent of the branch's
//!   state. To keep a branch's mass instead, list a tip inside the branch and
//!   lock the branch's joints: locked joints on a path are merged, so the
//!   branch stays, rigid.
//!
//!   The root link becomes the fixed base, its frame the base frame. Its
//!   pose does not matter for a fixed base except for the direction of
//!   gravity: gravity (default or constant, both given in the original base
//!   frame) is re-expressed in the root's frame at the configuration where
//!   every joint above the root is at its lock position if the scene locks
//!   it, and at zero otherwise. A gravity *input* is given at run time
//!   directly in the root's frame, which is what a controller of a sub-tree
//!   on a moving platform knows.
//! - **Payloads**: a constant payload (mass, centre of mass and rotational
//!   inertia about it, both in the link's frame) is folded into the body
//!   the link belongs to, exactly as a URDF link fixed to it would be. An
//!   input payload is recorded in [`SceneModel::input_payloads`]; the generic
//!   solver adds the values given at each call to the body's inertia
//!   ([`SceneInputs::payloads`]); generated code takes it as an argument
//!   `payload_LINK: &[T; 10]`.
//!
//! # A floating base
//!
//! Every option works on a floating-base model ([`Model::with_floating_base`]);
//! q, q̇ and τ keep their floating layout (NQ = n + 7, NV = n + 6).
//!
//! - **Gravity** is in the world frame: the model's, a constant, or an
//!   input, all given in world axes (never re-expressed).
//! - **Armature and friction** act on the joints only, never on the base's
//!   six coordinates (a free body has no rotor and no bearing); the base
//!   rows of M get no armature and those of τ no friction.
//! - **Payloads and tip wrenches** may be on any link, the floating root
//!   and the links fixed to it included: there they load the base (on a
//!   fixed base they would move nothing, and warn).
//! - **Locks**: a locked joint's bodies merge into their parent, the base
//!   when the joint hangs from it; the base stays floating.
//! - **Sub-trees**: a sub-tree whose root is the floating root link keeps
//!   the floating base; one rooted at any other link (an arm's mount, even
//!   one fixed to the trunk) is a **fixed-base** robot, as any sub-tree
//!   is: the root link held still, the base's motion left out, gravity
//!   seen with the base level (or an input in the root's frame), with a
//!   [`SceneWarning::SubTreeOffFloatingBase`]. That is the model of a
//!   controller of the arm alone; to keep the body's motion, root the
//!   sub-tree at the floating root.
//!
//! # The TOML format
//!
//! Every key is optional; unknown keys are errors naming the key. Vectors
//! are in the original robot's base frame (a floating base's: the world
//! frame), payloads in their link's frame.
//! A scene file may also carry code-generation keys, which
//! [`SceneFile`] reads apart from the physics and which set
//! [`CodegenOptions`](crate::codegen::CodegenOptions) (options set in Rust
//! or on the command line win over them).
//!
//! ```toml
//! # Code-generation keys (CodegenOptions' name, functions, scalar, trig;
//! # SceneFile::to_toml_string writes them back):
//! name = "ur5_controller"      # the generated module's name
//! # Any of inverse_dynamics, mass_matrix, bias_forces, gravity_torques,
//! # coriolis, forward_dynamics (default: all but coriolis), plus the pose,
//! # the body and world Jacobians and the acceleration bias J̇q̇ of named
//! # frames (frame_pose_ee_link(q), frame_jacobian_ee_link(q), …).
//! functions = ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"]
//! frame_pose = ["ee_link"]
//! frame_jacobian = ["ee_link"]
//! frame_world_jacobian = ["ee_link"]
//! frame_acceleration_bias = ["ee_link"]
//! scalar = "f64"               # or "f32"
//! trig = "batched"            # or "std", "libm", "inputs"; or instead, as before,
//! # target = "std"             # std allowed (the trigonometry stays the options'), or
//!                              # "no_std_libm" (trig libm), "no_std_sincos" (trig inputs)
//!
//! # The physics:
//! # The wrench the robot applies to its environment at this link, in the
//! # link's frame, as a run-time input (no key: no tip wrench).
//! tip_wrench = "ee_link"
//!
//! # Smoothing velocity of Coulomb friction, rad/s or m/s (default 0.01).
//! coulomb_velocity = 0.01
//!
//! [gravity]
//! mode = "constant"            # "default" (the model's), "constant", "none" or "input"
//! vector = [0.0, 0.0, -9.81]   # m/s², only with "constant" (which it implies)
//!
//! [subtree]
//! root = "base_link"
//! tips = ["wrist_3_link"]
//!
//! [joints.shoulder_pan_joint]  # per moving joint
//! armature = 0.1               # kg·m² (kg for a prismatic joint)
//! viscous = 0.5                # N·m·s/rad (N·s/m)
//! coulomb = 2.0                # N·m (N)
//!
//! [joints.wrist_3_joint]
//! lock = 0.0                   # rad (m): the joint becomes fixed here
//!
//! [[payload]]
//! link = "ee_link"
//! mass = 0.8                   # kg
//! com = [0.0, 0.0, 0.05]       # m, in the link's frame
//! inertia = [1e-3, 1e-3, 5e-4, 0.0, 0.0, 0.0]  # ixx iyy izz ixy ixz iyz about the com, kg·m²
//!
//! [[payload]]
//! link = "wrist_2_link"
//! input = true                 # mass properties given at run time
//! ```
//!
//! `dynagen/scenes/ur5_controller.toml` is a complete example.
//!
//! # Errors
//!
//! Everything is checked: unknown names, locks on joints that do not exist,
//! tips not below the root, non-physical payloads, negative coefficients,
//! and contradictions (a locked joint with armature or friction, a tip
//! wrench or payload on a link the sub-tree drops, gravity `none` with a
//! vector, …). Each is a [`SceneError`] naming the item; nothing panics.

pub mod dynamics;
mod error;
mod reduce;
mod toml;

pub use crate::robot::scene::{SceneInputError, SceneInputs, SceneRobot};
pub use error::{SceneError, SceneWarning};
pub use reduce::{InputPayload, ResolvedGravity, SceneModel};
pub use toml::{CodeKeys, SceneFile};

use crate::model::Model;
use crate::spatial::Sym3;
use std::collections::HashSet;

/// The default smoothing velocity of Coulomb friction, v_ε (rad/s or m/s).
pub const DEFAULT_COULOMB_VELOCITY: f64 = 0.01;

/// Where gravity comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Gravity {
    /// The model's gravity (in the original base frame; a floating base's
    /// is in the world frame).
    #[default]
    Default,
    /// This vector (m/s², in the original base frame; a floating base: the
    /// world frame).
    Constant([f64; 3]),
    /// No gravity: g(q) = 0 and the gravity terms are left out.
    None,
    /// A run-time argument, in the reduced model's base frame (a floating
    /// base: the world frame).
    Input,
}

/// The part of the robot to keep: the moving joints on the paths from
/// `root` to each tip.
#[derive(Clone, Debug, PartialEq)]
pub struct SubTree {
    /// The link that becomes the fixed base.
    pub root: String,
    /// The links at the ends of the kept paths.
    pub tips: Vec<String>,
}

/// The mass properties of a payload, in the frame of the link it is
/// attached to.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PayloadInertia {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the link's frame (m).
    pub com: [f64; 3],
    /// Rotational inertia about the centre of mass, axes parallel to the
    /// link's, `[ixx, iyy, izz, ixy, ixz, iyz]` (kg·m²).
    pub inertia: [f64; 6],
}

impl PayloadInertia {
    /// A payload from its mass, centre of mass and inertia about it.
    pub fn new(mass: f64, com: [f64; 3], inertia: [f64; 6]) -> Self {
        PayloadInertia { mass, com, inertia }
    }
    /// Checks that a body could have these mass properties: finite, mass
    /// not negative, inertia positive semi-definite and obeying the triangle
    /// inequality, no inertia without mass.
    pub fn check(&self, link: &str) -> Result<(), SceneError> {
        let bad = |why: String| Err(SceneError::PayloadNotPhysical { link: link.to_string(), why });
        if !self.mass.is_finite() || !self.com.iter().chain(&self.inertia).all(|x| x.is_finite()) {
            return bad("mass, com and inertia must be finite".to_string());
        }
        if self.mass < 0.0 {
            return Err(SceneError::PayloadNegativeMass { link: link.to_string(), mass: self.mass });
        }
        let m = Sym3(self.inertia).eigenvalues();
        let tol = 1e-9 * m[2].abs();
        if m[0] < -tol {
            return bad(format!("the inertia is not positive semi-definite (principal moments {m:?} kg·m²)"));
        }
        if 0.5 * (m[0] + m[1] + m[2]) - m[2] < -tol {
            return bad(format!("the principal moments {m:?} kg·m² break the triangle inequality"));
        }
        if self.mass == 0.0 && m[2] > 0.0 {
            return bad("zero mass with a non-zero inertia".to_string());
        }
        Ok(())
    }
}

/// A payload: a constant, or a run-time input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PayloadValue {
    /// Folded into the link's body.
    Constant(PayloadInertia),
    /// Given at run time (see [`SceneInputs::payloads`]).
    Input,
}

/// A payload carried by a link.
#[derive(Clone, Debug, PartialEq)]
pub struct Payload {
    /// The link (or frame) it is fixed to.
    pub link: String,
    /// Its mass properties, or that they are an input.
    pub value: PayloadValue,
}

/// How to model a robot for a controller: the physics a module or
/// [`SceneRobot`] computes (code options are [`CodegenOptions`](crate::codegen::CodegenOptions)). See the
/// [module docs](self) for the equations, the reductions and the TOML form.
///
/// ```
/// use dynagen::scene::{Gravity, Scene};
/// let scene = Scene::new()
///     .gravity(Gravity::Input)
///     .lock("wrist_3_joint", 0.0)
///     .armature("shoulder_pan_joint", 0.1)
///     .coulomb("shoulder_pan_joint", 2.0);
/// let model = dynagen::Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap();
/// let reduced = scene.apply(&model).unwrap();
/// assert_eq!(reduced.dof(), 5);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Where gravity comes from.
    pub gravity: Gravity,
    /// The link or frame at which a tip wrench is a run-time input.
    pub tip_wrench: Option<String>,
    /// The part of the robot to keep (default: all of it).
    pub subtree: Option<SubTree>,
    /// Joints locked at a position (rad or m).
    pub locks: Vec<(String, f64)>,
    /// Payloads.
    pub payloads: Vec<Payload>,
    /// Armature per joint (kg·m² or kg).
    pub armature: Vec<(String, f64)>,
    /// Viscous friction per joint (N·m·s/rad or N·s/m).
    pub viscous_friction: Vec<(String, f64)>,
    /// Coulomb friction per joint (N·m or N).
    pub coulomb_friction: Vec<(String, f64)>,
    /// Smoothing velocity of Coulomb friction, v_ε.
    pub coulomb_velocity: f64,
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            gravity: Gravity::Default,
            tip_wrench: None,
            subtree: None,
            locks: Vec::new(),
            payloads: Vec::new(),
            armature: Vec::new(),
            viscous_friction: Vec::new(),
            coulomb_friction: Vec::new(),
            coulomb_velocity: DEFAULT_COULOMB_VELOCITY,
        }
    }
}

impl Scene {
    /// The default scene: the whole robot, the model's gravity, no tip
    /// wrench, payload, armature or friction (a plain module's).
    pub fn new() -> Self {
        Self::default()
    }
    /// Sets where gravity comes from.
    pub fn gravity(mut self, gravity: Gravity) -> Self {
        self.gravity = gravity;
        self
    }
    /// Makes the wrench applied at `frame` a run-time input.
    pub fn tip_wrench(mut self, frame: &str) -> Self {
        self.tip_wrench = Some(frame.to_string());
        self
    }
    /// Keeps only the joints on the paths from `root` to each of `tips`.
    pub fn subtree(mut self, root: &str, tips: &[&str]) -> Self {
        self.subtree = Some(SubTree { root: root.to_string(), tips: tips.iter().map(|t| t.to_string()).collect() });
        self
    }
    /// Locks a joint at `position`.
    pub fn lock(mut self, joint: &str, position: f64) -> Self {
        self.locks.push((joint.to_string(), position));
        self
    }
    /// Adds a constant payload on `link`.
    pub fn payload(mut self, link: &str, payload: PayloadInertia) -> Self {
        self.payloads.push(Payload { link: link.to_string(), value: PayloadValue::Constant(payload) });
        self
    }
    /// Adds a payload on `link` whose mass properties are a run-time input.
    pub fn payload_input(mut self, link: &str) -> Self {
        self.payloads.push(Payload { link: link.to_string(), value: PayloadValue::Input });
        self
    }
    /// Sets a joint's armature.
    pub fn armature(mut self, joint: &str, armature: f64) -> Self {
        self.armature.push((joint.to_string(), armature));
        self
    }
    /// Sets a joint's viscous friction coefficient.
    pub fn viscous(mut self, joint: &str, b: f64) -> Self {
        self.viscous_friction.push((joint.to_string(), b));
        self
    }
    /// Sets a joint's Coulomb friction.
    pub fn coulomb(mut self, joint: &str, f: f64) -> Self {
        self.coulomb_friction.push((joint.to_string(), f));
        self
    }
    /// Sets the smoothing velocity of Coulomb friction.
    pub fn coulomb_velocity(mut self, v: f64) -> Self {
        self.coulomb_velocity = v;
        self
    }
    /// Whether the tip wrench, gravity or a payload is a run-time input.
    pub fn has_inputs(&self) -> bool {
        self.gravity == Gravity::Input
            || self.tip_wrench.is_some()
            || self.payloads.iter().any(|p| p.value == PayloadValue::Input)
    }

    /// The checks that need no robot: numbers, duplicates and
    /// contradictions. [`apply`](Self::apply) runs them first.
    pub fn check(&self) -> Result<(), SceneError> {
        if !(self.coulomb_velocity.is_finite() && self.coulomb_velocity > 0.0) {
            return Err(SceneError::BadCoulombVelocity(self.coulomb_velocity));
        }
        if let Gravity::Constant(g) = self.gravity {
            if !g.iter().all(|x| x.is_finite()) {
                return Err(SceneError::Gravity(format!("the constant vector {g:?} is not finite")));
            }
        }
        let mut locked = HashSet::new();
        for (j, q) in &self.locks {
            if !locked.insert(j.as_str()) {
                return Err(SceneError::JointListedTwice { joint: j.clone(), what: "lock" });
            }
            if !q.is_finite() {
                return Err(SceneError::BadLockPosition { joint: j.clone(), value: *q });
            }
        }
        for (what, list) in self.coefficients() {
            let mut seen = HashSet::new();
            for (j, x) in list {
                if !seen.insert(j.as_str()) {
                    return Err(SceneError::JointListedTwice { joint: j.clone(), what });
                }
                if locked.contains(j.as_str()) {
                    return Err(SceneError::LockedJointParameter { joint: j.clone(), what });
                }
                if !(x.is_finite() && *x >= 0.0) {
                    return Err(SceneError::BadCoefficient { joint: j.clone(), what, value: *x });
                }
            }
        }
        if let Some(st) = &self.subtree {
            if st.tips.is_empty() {
                return Err(SceneError::NoTips { root: st.root.clone() });
            }
            let mut seen = HashSet::new();
            for t in &st.tips {
                if !seen.insert(t.as_str()) {
                    return Err(SceneError::TipListedTwice(t.clone()));
                }
            }
        }
        let mut seen = HashSet::new();
        for p in &self.payloads {
            if !seen.insert(p.link.as_str()) {
                return Err(SceneError::PayloadListedTwice(p.link.clone()));
            }
            if let PayloadValue::Constant(c) = &p.value {
                c.check(&p.link)?;
            }
        }
        Ok(())
    }

    /// The per-joint coefficient lists with their names.
    pub(crate) fn coefficients(&self) -> [(&'static str, &Vec<(String, f64)>); 3] {
        [
            ("armature", &self.armature),
            ("viscous friction", &self.viscous_friction),
            ("Coulomb friction", &self.coulomb_friction),
        ]
    }

    /// Checks the scene against `model` and builds the reduced model with
    /// everything the scene folds in; see [`SceneModel`].
    pub fn apply(&self, model: &Model) -> Result<SceneModel, SceneError> {
        reduce::apply(self, model)
    }
}
