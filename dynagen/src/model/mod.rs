//! The robot: a kinematic tree of rigid bodies, one moving joint per body,
//! in topological order; a joint may follow another ([`Mimic`]).
//!
//! A [`Model`] is built from a [`RobotDescription`] (links and joints, as in a
//! URDF) by [`Model::from_description`], which validates everything and
//! merges bodies attached by fixed joints into their parent. The importers
//! ([`Model::from_urdf_file`], [`Model::from_urdf_str`],
//! [`Model::from_modern_robotics`]) and [`RobotBuilder`] all produce a
//! description first, so every path goes through the same checks.
//!
//! Conventions: body `i` carries joint `i`; `parent[i] < i`; joint order is
//! depth-first over the tree, children in the order the description lists
//! their joints (file order for URDF). A body's frame is its joint's frame.
//! The joint vectors (q, q̇, τ) have an entry per joint with a coordinate
//! of its own: body `i`'s is [`Model::column`]`(i)` (a mimic joint's is its
//! master's), the same as `i` when no joint follows another.

mod builder;
mod coupling;
mod dependent;
mod description;
mod error;
mod file_values;
mod modern_robotics;
mod tree;
mod urdf;
mod urdf_attributes;
mod urdf_decimals;
mod validate;

pub use builder::RobotBuilder;
pub(crate) use coupling::Coupling;
pub use description::{
    FileInertial, Inertial, JointDescription, JointLimits, JointType, LinkDescription, MimicDescription,
    RobotDescription,
};
pub(crate) use error::quoted as quoted_names;
pub use error::{ModelError, ModelWarning};
pub use file_values::{ExactAxis, FileAxis, FileInertia, FileTransform, FileValue, FileVec3, JointFileValues};
pub use modern_robotics::ModernRoboticsLists;

use crate::spatial::{Inertia, Mat3, Transform, Vec3};

/// How strictly to check a description.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BuildOptions {
    /// Refuse inertias that break the triangle inequality instead of
    /// warning about them.
    pub strict: bool,
    /// Accept links whose rotational inertia is not positive semi-definite
    /// (refused by default, as MuJoCo does), each with a warning
    /// ([`ModelWarning::NonPhysicalInertia`]): the dynamics are then those
    /// of a body no matter has, M(q) may be indefinite and forward
    /// dynamics may fail. Some published files (GRiD's Atlas) have such
    /// links, and Pinocchio loads them.
    pub allow_nonphysical_inertia: bool,
    /// What a joint with a `<mimic>` element is: coupled to its master
    /// (the default), or an independent joint as if it had none.
    pub mimic: MimicJoints,
}

/// How to model the joints a description marks as following another
/// (URDF `<mimic>`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MimicJoints {
    /// Each follows its master, `q = multiplier·q_master + offset`: it has
    /// no coordinate of its own, its motion counts in the master's column,
    /// and τ, M and h are those of the independent joints (as Pinocchio's
    /// URDF parser with its mimic option builds them).
    #[default]
    Follow,
    /// Each is an independent joint with its own coordinate (the
    /// `<mimic>` element is ignored): the robot as before dynagen knew
    /// mimic joints, for a controller that drives every joint itself.
    Independent,
}

impl std::str::FromStr for MimicJoints {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "follow" => Ok(MimicJoints::Follow),
            "independent" => Ok(MimicJoints::Independent),
            _ => Err(format!("unknown mimic mode \"{s}\": \"follow\" (the default) or \"independent\"")),
        }
    }
}

impl BuildOptions {
    /// These options with [`allow_nonphysical_inertia`](Self::allow_nonphysical_inertia) set.
    pub fn allow_nonphysical_inertia(mut self, allow: bool) -> Self {
        self.allow_nonphysical_inertia = allow;
        self
    }
    /// These options with [`mimic`](Self::mimic) set.
    pub fn mimic_joints(mut self, mimic: MimicJoints) -> Self {
        self.mimic = mimic;
        self
    }
}

/// A joint that follows another (URDF `<mimic>`, with
/// [`MimicJoints::Follow`]): its position is `multiplier·q_master + offset`,
/// its rate and acceleration `multiplier` times the master's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mimic {
    /// The body whose joint is the master (a joint that follows no other).
    pub master: usize,
    /// The factor on the master's position.
    pub multiplier: f64,
    /// The position at the master's zero (rad or m).
    pub offset: f64,
}

/// The kind of a moving joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the axis, with limits.
    Revolute,
    /// Rotation about the axis, without limits.
    Continuous,
    /// Translation along the axis.
    Prismatic,
}

/// A moving joint: it connects a body to its parent.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Revolute, continuous or prismatic.
    pub kind: JointKind,
    /// The joint's frame in the parent body's frame, at q = 0.
    pub placement: Transform<f64>,
    /// The axis in the joint's frame. A revolute joint rotates by
    /// `axis_norm·q` radians about `axis/|axis|`: a screw axis (Modern
    /// Robotics lists, the Rust constructors) is kept as given, with
    /// `axis_norm = |axis|`, as the Modern Robotics library does; a
    /// direction (every URDF axis, [`JointDescription::axis_is_direction`])
    /// is normalised, with `axis_norm` exactly 1, so that its angle is q.
    pub axis: Vec3<f64>,
    /// Position, velocity and effort limits, when known.
    pub limits: Option<JointLimits>,
    /// `axis / |axis|`.
    pub unit_axis: Vec3<f64>,
    /// The factor between the joint's position and its angle (or
    /// displacement): `|axis|` for a screw axis, exactly 1 for a direction.
    pub axis_norm: f64,
    /// Derived from `axis`: the coordinate axis it lies along, if any, so
    /// that the algorithms can skip the products with its zero components.
    pub alignment: AxisAlignment,
    /// Derived from `placement`: whether its rotation is exactly the
    /// identity, so that the algorithms can skip the product with it.
    pub placement_rotation_is_identity: bool,
    /// The placement and unit axis as the robot file defines them, beyond
    /// `f64`, for the precise scalars ([`FileValue`]); `None` for a joint
    /// built in Rust, whose `f64` numbers are exact.
    pub file_values: Option<Box<JointFileValues>>,
}

/// Which coordinate axis of its frame a joint's axis lies along (its other
/// two components exactly zero), or none. A model constant: algorithms may
/// branch on it, and for an aligned axis they compute only the non-zero
/// terms (the same numbers as the general formulas, up to rounding).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisAlignment {
    /// Along ±x.
    X,
    /// Along ±y.
    Y,
    /// Along ±z.
    Z,
    /// Any other direction.
    General,
}

impl AxisAlignment {
    /// The alignment of `axis` (a non-zero vector).
    pub fn of(axis: &Vec3<f64>) -> Self {
        match axis.0 {
            [_, 0.0, 0.0] => AxisAlignment::X,
            [0.0, _, 0.0] => AxisAlignment::Y,
            [0.0, 0.0, _] => AxisAlignment::Z,
            _ => AxisAlignment::General,
        }
    }
}

impl Joint {
    /// Recomputes the fields derived from `axis` and `placement`
    /// (`alignment`, `placement_rotation_is_identity`; `unit_axis` and
    /// `axis_norm` are left alone).
    pub fn refresh_derived(&mut self) {
        self.alignment = AxisAlignment::of(&self.axis);
        self.placement_rotation_is_identity = self.placement.rot == Mat3::identity();
    }
    /// The joint's motion subspace S in its own frame: the twist of the body
    /// relative to its parent per unit joint velocity, (angular; linear).
    pub fn motion_subspace(&self) -> [f64; 6] {
        let a = self.axis.0;
        match self.kind {
            JointKind::Revolute | JointKind::Continuous => [a[0], a[1], a[2], 0.0, 0.0, 0.0],
            JointKind::Prismatic => [0.0, 0.0, 0.0, a[0], a[1], a[2]],
        }
    }
    /// Whether the joint rotates.
    pub fn is_revolute(&self) -> bool {
        !matches!(self.kind, JointKind::Prismatic)
    }
}

/// How the root link is attached to the world.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RootJoint {
    /// The root link is the world: it never moves (a manipulator on a table).
    #[default]
    Fixed,
    /// The root link moves freely in space (a quadruped's or humanoid's
    /// trunk): six unactuated degrees of freedom ahead of the joints, with
    /// `q = [p, quaternion (x, y, z, w), joints]` (NQ = n + 7) and
    /// `q̇ = [ω_b, v_b, joint rates]` (NV = n + 6, the base's body twist).
    Floating,
}

/// A rigid body with the joint that connects it to its parent.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The name of the link this body is made of (the child link of its
    /// joint); links fixed to it are merged in.
    pub name: String,
    /// The parent body, or `None` for the fixed base.
    pub parent: Option<usize>,
    /// The joint between the parent and this body.
    pub joint: Joint,
    /// The spatial inertia of the body and every link fixed to it, in the
    /// body's (joint's) frame.
    pub inertia: Inertia<f64>,
    /// `inertia` as the robot file defines it, beyond `f64` ([`FileValue`]).
    pub file_inertia: Option<Box<FileInertia>>,
}

/// A named frame rigidly attached to a body (or to the fixed base): every
/// link of the description is one, and so is a Modern Robotics end-effector.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The frame's name (a link name for URDF).
    pub name: String,
    /// The body it is attached to, or `None` for the fixed base.
    pub body: Option<usize>,
    /// The frame's pose in the body's frame.
    pub placement: Transform<f64>,
    /// `placement` as the robot file defines it, beyond `f64` ([`FileValue`]).
    pub file_placement: Option<Box<FileTransform>>,
}

/// A robot: the constant data every algorithm reads.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The robot's name.
    pub name: String,
    /// The name of the root link (the fixed base frame).
    pub root: String,
    /// The moving bodies in topological order; body `i` carries joint `i`
    /// (whose entry in the joint vectors is [`Model::column`]`(i)`).
    pub bodies: Vec<Body>,
    /// Every named frame.
    pub frames: Vec<Frame>,
    /// Gravity in the base frame (m/s²), in the world frame for a floating
    /// base; (0, 0, −9.81) unless set otherwise.
    pub gravity: Vec3<f64>,
    /// What was accepted with a warning.
    pub warnings: Vec<ModelWarning>,
    /// Mass of everything fixed to the base (it never moves, and does not
    /// enter the dynamics).
    pub base_mass: f64,
    /// Fixed to the world, or floating.
    pub root_joint: RootJoint,
    /// The spatial inertia of the root link and every link fixed to it, in
    /// the root's frame: the floating base's own inertia (unused when the
    /// root is fixed).
    pub base_inertia: Inertia<f64>,
    /// Which bodies follow another's joint ([`Mimic`]), and where each
    /// body's motion is in the joint vectors: made when the model is built.
    pub(crate) coupling: Coupling,
    /// `base_inertia` as the robot file defines it, beyond `f64` ([`FileValue`]).
    pub file_base_inertia: Option<Box<FileInertia>>,
}

/// The default gravity: (0, 0, −9.81) m/s² in the base frame.
pub const DEFAULT_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

impl Model {
    /// The number of joints with a coordinate of their own: one per body,
    /// less the joints that follow another ([`Model::mimic`]); a floating
    /// base's six degrees of freedom are not counted (see [`Model::nv`]).
    pub fn dof(&self) -> usize {
        self.coupling.dof()
    }
    /// Whether some joint follows another ([`Mimic`]): then the joint
    /// vectors are shorter than the bodies, and body `i`'s motion is in
    /// column [`column(i)`](Self::column).
    pub fn has_mimic(&self) -> bool {
        self.coupling.any()
    }
    /// How body `i`'s joint follows another, if it does.
    pub fn mimic(&self, body: usize) -> Option<&Mimic> {
        self.coupling.mimic[body].as_ref()
    }
    /// The index in the joint vectors (q, q̇, τ, without a floating base's
    /// entries) of body `i`'s joint, or of its master's if it follows one.
    pub fn column(&self, body: usize) -> usize {
        self.coupling.column[body]
    }
    /// The body whose joint has column `k` of the joint vectors.
    pub fn joint_body(&self, column: usize) -> usize {
        self.coupling.body[column]
    }
    /// The length of a configuration the recursions over the bodies take:
    /// one coordinate per body, plus 7 with a floating base (`nq()` without
    /// mimic joints).
    pub fn tree_nq(&self) -> usize {
        self.bodies.len() + if self.is_floating() { 7 } else { 0 }
    }
    /// The length of a velocity the recursions over the bodies take (`nv()`
    /// without mimic joints).
    pub fn tree_nv(&self) -> usize {
        self.bodies.len() + if self.is_floating() { 6 } else { 0 }
    }
    /// Whether the root moves freely ([`RootJoint::Floating`]).
    pub fn is_floating(&self) -> bool {
        self.root_joint == RootJoint::Floating
    }
    /// The length of a configuration `q`: `dof()`, plus 7 (position and
    /// quaternion) with a floating base.
    pub fn nq(&self) -> usize {
        self.dof() + if self.is_floating() { 7 } else { 0 }
    }
    /// The length of a velocity, acceleration or force vector: `dof()`,
    /// plus 6 (the base's body twist or wrench) with a floating base.
    pub fn nv(&self) -> usize {
        self.dof() + if self.is_floating() { 6 } else { 0 }
    }
    /// This model with a floating root: the root link (with everything
    /// fixed to it) becomes a free body, and gravity is read in the world
    /// frame. A model that already floats is returned unchanged.
    /// A whole robot that cannot be accelerated in every direction at q = 0
    /// (no mass, or all of it on a line) gets a
    /// [`ModelWarning::FloatingBaseSingular`]; joints that can move with
    /// the base without moving any mass (a massless root link and its
    /// first joint, say) get a [`ModelWarning::DependentJoints`] that names
    /// the root link, and forward dynamics is refused.
    pub fn with_floating_base(mut self) -> Self {
        if self.root_joint == RootJoint::Floating {
            return self;
        }
        self.root_joint = RootJoint::Floating;
        // the whole robot's inertia at q = 0, about the base origin
        let mut composite: Vec<Inertia<f64>> = self.bodies.iter().map(|b| b.inertia).collect();
        let mut whole = self.base_inertia;
        for (i, b) in self.bodies.iter().enumerate().rev() {
            let moved = b.joint.placement.inertia_to_parent(&composite[i]);
            match b.parent {
                Some(p) => composite[p] = composite[p].add(&moved),
                None => whole = whole.add(&moved),
            }
        }
        let [lo, _, hi] = whole.inertia_at_com().eigenvalues();
        if !(whole.mass > 0.0 && hi > 0.0 && lo > 1e-12 * hi) {
            self.warnings.push(ModelWarning::FloatingBaseSingular { root: self.root.clone() });
        }
        // Joints dependent on the fixed base stay so; the base can add its
        // own (a massless root link moving against its first joint).
        self.warnings.retain(|w| !matches!(w, ModelWarning::DependentJoints { .. }));
        let dependent = dependent::dependent_joints(&self);
        self.warnings.extend(dependent.into_iter().map(|joints| ModelWarning::DependentJoints { joints }));
        self
    }
    /// The names of the joints with a coordinate of their own, in joint
    /// order (the order of every joint vector; joints that follow another
    /// are not among them).
    pub fn joint_names(&self) -> Vec<&str> {
        self.coupling.body.iter().map(|&b| self.bodies[b].joint.name.as_str()).collect()
    }
    /// The index in the joint vectors of the joint with this name; `None`
    /// for a joint that follows another (it has no entry) or no joint.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        let b = self.joint_body_index(name)?;
        self.mimic(b).is_none().then(|| self.column(b))
    }
    /// The body whose joint has this name (any moving joint).
    pub fn joint_body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.joint.name == name)
    }
    /// The index of the frame with this name (a link name for URDF).
    pub fn frame_index(&self, name: &str) -> Option<usize> {
        self.frames.iter().position(|f| f.name == name)
    }
    /// The frame with this name, or an error naming it.
    pub fn frame(&self, name: &str) -> Result<&Frame, ModelError> {
        self.frames.iter().find(|f| f.name == name).ok_or_else(|| ModelError::UnknownName(name.to_string()))
    }
    /// Whether body `j` is `i` or lies below it.
    pub fn is_in_subtree(&self, i: usize, mut j: usize) -> bool {
        loop {
            if j == i {
                return true;
            }
            match self.bodies[j].parent {
                Some(p) if p >= i => j = p,
                _ => return false,
            }
        }
    }
    /// The total mass of the moving bodies.
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.inertia.mass).sum()
    }
    /// Sets the gravity vector, in the base frame (m/s²).
    pub fn with_gravity(mut self, g: [f64; 3]) -> Self {
        self.gravity = Vec3(g);
        self
    }
}
