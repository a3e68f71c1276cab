//! A robot as links and joints, before validation: what importers produce
//! and [`Model::from_description`](super::Model::from_description) checks.

use super::file_values::{FileTransform, FileValue, FileVec3};
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};
use crate::DoubleDouble;

/// The type of a joint as a description (URDF) names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointType {
    /// Rotation about an axis, with limits.
    Revolute,
    /// Rotation about an axis, without limits.
    Continuous,
    /// Translation along an axis.
    Prismatic,
    /// No motion: the child is merged into the parent.
    Fixed,
    /// Six degrees of freedom (not supported yet).
    Floating,
    /// Motion in a plane (not supported yet).
    Planar,
    /// Rotation about a point (not supported yet).
    Spherical,
}

/// Joint limits, as in URDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower position limit (rad or m).
    pub lower: f64,
    /// Upper position limit (rad or m).
    pub upper: f64,
    /// Velocity limit (rad/s or m/s).
    pub velocity: f64,
    /// Effort limit (N·m or N).
    pub effort: f64,
}

/// Mass properties of a link: mass, and the rotational inertia about the
/// centre of mass, expressed in the frame `origin` (placed at the centre of
/// mass, in the link's frame), as URDF's `<inertial>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertial {
    /// Mass (kg).
    pub mass: f64,
    /// The inertial frame in the link frame; its origin is the centre of mass.
    pub origin: Transform<f64>,
    /// Rotational inertia about the centre of mass in the inertial frame,
    /// `[ixx, iyy, izz, ixy, ixz, iyz]` (kg·m²).
    pub inertia: Sym3<f64>,
}

impl Inertial {
    /// A mass at `com` (in the link frame) with the inertia
    /// `[ixx, iyy, izz, ixy, ixz, iyz]` about it, axes parallel to the link's.
    pub fn new(mass: f64, com: [f64; 3], inertia: [f64; 6]) -> Self {
        Inertial { mass, origin: Transform::translation(Vec3(com)), inertia: Sym3(inertia) }
    }
    /// A point mass at `com`.
    pub fn point_mass(mass: f64, com: [f64; 3]) -> Self {
        Self::new(mass, com, [0.0; 6])
    }
}

/// A link.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkDescription {
    /// The link's name.
    pub name: String,
    /// Mass properties; `None` is a massless link.
    pub inertial: Option<Inertial>,
    /// The link's spatial inertia in its own frame as the robot file defines
    /// it, beyond `f64` ([`FileValue`]), refining `inertial`; without it (a
    /// link described in Rust), `inertial`'s numbers are taken as exact.
    pub file_inertia: Option<FileInertial>,
}

/// A link's spatial inertia in its frame from the file's decimals, beside
/// the [`Inertial`] it refines.
pub type FileInertial = FileValue<Inertial, Inertia<DoubleDouble>>;

impl LinkDescription {
    /// A link with these mass properties (none: massless).
    pub fn new(name: &str, inertial: Option<Inertial>) -> Self {
        LinkDescription { name: name.to_string(), inertial, file_inertia: None }
    }
}

/// A joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointDescription {
    /// The joint's name.
    pub name: String,
    /// Its type.
    pub joint_type: JointType,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// The joint frame (= the child link's frame) in the parent link's frame.
    pub origin: Transform<f64>,
    /// The axis, in the joint frame (ignored for fixed joints).
    pub axis: Vec3<f64>,
    /// Whether `axis` is only a direction, as in URDF: the joint turns by
    /// exactly `q` radians about (or slides `q` metres along)
    /// `axis/|axis|`. Otherwise it is a screw axis, as in the Modern
    /// Robotics lists and the constructors below: the joint turns by
    /// `|axis|·q` (slides by `axis·q`). A direction written with all its
    /// decimals has `|axis| = 1 ± 1 ulp`, and only this flag keeps that
    /// ulp from scaling every angle.
    pub axis_is_direction: bool,
    /// Limits, when known.
    pub limits: Option<JointLimits>,
    /// The joint this one follows (URDF `<mimic>`), if any.
    pub mimic: Option<MimicDescription>,
    /// `origin` as the robot file defines it (the rotation from the file's
    /// rpy or quaternion), beyond `f64` ([`FileValue`]).
    pub file_origin: Option<FileTransform>,
    /// `axis` as the robot file writes it, beyond `f64` (without it, the
    /// `f64` axis is taken as exact).
    pub file_axis: Option<FileVec3>,
}

/// A joint that follows another (URDF `<mimic>`): its position is
/// `multiplier·q_master + offset` (rad or m), its rate and acceleration
/// `multiplier` times the master's. The master must be a moving joint that
/// follows no other.
#[derive(Clone, Debug, PartialEq)]
pub struct MimicDescription {
    /// The master joint's name.
    pub joint: String,
    /// The factor on the master's position (URDF default 1).
    pub multiplier: f64,
    /// The position at the master's zero (URDF default 0).
    pub offset: f64,
}

impl JointDescription {
    fn new(name: &str, joint_type: JointType, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        JointDescription {
            name: name.to_string(),
            joint_type,
            parent: parent.to_string(),
            child: child.to_string(),
            origin: Transform::identity(),
            axis: Vec3(axis),
            axis_is_direction: false,
            limits: None,
            mimic: None,
            file_origin: None,
            file_axis: None,
        }
    }
    /// A revolute joint about `axis` (in the joint frame).
    pub fn revolute(name: &str, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        Self::new(name, JointType::Revolute, parent, child, axis)
    }
    /// A continuous (unlimited revolute) joint about `axis`.
    pub fn continuous(name: &str, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        Self::new(name, JointType::Continuous, parent, child, axis)
    }
    /// A prismatic joint along `axis`.
    pub fn prismatic(name: &str, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        Self::new(name, JointType::Prismatic, parent, child, axis)
    }
    /// A fixed joint.
    pub fn fixed(name: &str, parent: &str, child: &str) -> Self {
        Self::new(name, JointType::Fixed, parent, child, [0.0, 0.0, 0.0])
    }
    /// Places the joint frame at `xyz` with URDF roll-pitch-yaw `rpy` in the
    /// parent link's frame. The numbers are exact: the precise scalars take
    /// the rotation computed from them in double-double (`file_origin`).
    pub fn origin(mut self, xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        self.origin = Transform::new(Mat3::from_rpy(rpy[0], rpy[1], rpy[2]), Vec3(xyz));
        let [r, p, y] = rpy.map(DoubleDouble::from);
        let exact = Transform::new(Mat3::rpy(r, p, y), Vec3(xyz.map(DoubleDouble::from)));
        self.file_origin = Some(FileValue::new(self.origin, exact));
        self
    }
    /// Makes the axis a direction (as URDF's): the joint turns by exactly
    /// `q` about `axis/|axis|` (see [`axis_is_direction`](Self::axis_is_direction)).
    pub fn unit_axis(mut self) -> Self {
        self.axis_is_direction = true;
        self
    }
    /// Makes the joint follow `master`: its position is
    /// `multiplier·q_master + offset` (see [`MimicDescription`]).
    pub fn mimic(mut self, master: &str, multiplier: f64, offset: f64) -> Self {
        self.mimic = Some(MimicDescription { joint: master.to_string(), multiplier, offset });
        self
    }
    /// Sets the limits.
    pub fn limits(mut self, lower: f64, upper: f64, velocity: f64, effort: f64) -> Self {
        self.limits = Some(JointLimits { lower, upper, velocity, effort });
        self
    }
}

/// A robot as links and joints.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RobotDescription {
    /// The robot's name.
    pub name: String,
    /// The links, in file order.
    pub links: Vec<LinkDescription>,
    /// The joints, in file order (this order decides the order of siblings).
    pub joints: Vec<JointDescription>,
    /// Gravity in the base frame, when the source says (Modern Robotics
    /// lists carry it); the default otherwise.
    pub gravity: Option<[f64; 3]>,
}
