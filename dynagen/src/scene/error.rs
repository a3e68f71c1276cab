//! Why a scene was refused, and what it accepted with a warning. Every
//! error and warning names the link, joint or option it is about.

use crate::model::ModelError;
use std::path::PathBuf;

/// Why a scene was refused.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The reason.
        #[source]
        source: std::io::Error,
    },
    /// The TOML is malformed, has an unknown key or a value of the wrong
    /// type (the message names the key and its place in the file).
    #[error("scene TOML: {0}")]
    Toml(String),
    /// A name that is not a link (or frame) of the robot.
    #[error("{what}: the robot has no link or frame named \"{name}\"")]
    UnknownLink {
        /// Which option names it (`sub-tree root`, `tip wrench`, …).
        what: &'static str,
        /// The name.
        name: String,
    },
    /// A name that is not a moving joint of the robot (fixed joints are
    /// merged away when the model is built, so they cannot be named).
    #[error("{what}: the robot has no moving joint named \"{name}\" (fixed joints cannot be named)")]
    UnknownJoint {
        /// Which option names it (`lock`, `armature`, …).
        what: &'static str,
        /// The name.
        name: String,
    },
    /// The same joint is named twice by one option.
    #[error("joint \"{joint}\": {what} is given twice")]
    JointListedTwice {
        /// The joint.
        joint: String,
        /// The option (`lock`, `armature`, …).
        what: &'static str,
    },
    /// A locked joint is also given armature or friction.
    #[error("joint \"{joint}\" is locked, so it cannot also have {what}")]
    LockedJointParameter {
        /// The joint.
        joint: String,
        /// The option (`armature`, `viscous friction`, `Coulomb friction`).
        what: &'static str,
    },
    /// A joint the sub-tree removes is given armature or friction.
    #[error("joint \"{joint}\" is not in the sub-tree (it is {why}), so it cannot have {what}")]
    RemovedJointParameter {
        /// The joint.
        joint: String,
        /// The option.
        what: &'static str,
        /// Why it is not kept.
        why: &'static str,
    },
    /// What a scene cannot do with a joint that follows another (`<mimic>`):
    /// lock it or give it armature or friction (those are its master's to
    /// have), keep it moving while its master is dropped, or merge it
    /// rigidly while its master moves.
    #[error("joint \"{joint}\" follows joint \"{master}\" (mimic): {why}")]
    MimicJoint {
        /// The mimic joint.
        joint: String,
        /// Its master.
        master: String,
        /// What the scene asks that cannot be, and what to do.
        why: String,
    },
    /// A negative or non-finite armature or friction coefficient.
    #[error("joint \"{joint}\": {what} is {value}; it must be finite and not negative")]
    BadCoefficient {
        /// The joint.
        joint: String,
        /// The option.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// A non-finite lock position.
    #[error("joint \"{joint}\": lock position {value} is not finite")]
    BadLockPosition {
        /// The joint.
        joint: String,
        /// The value.
        value: f64,
    },
    /// The Coulomb smoothing velocity is not a positive finite number.
    #[error("coulomb_velocity is {0}; it must be positive and finite")]
    BadCoulombVelocity(f64),
    /// Gravity options that contradict each other.
    #[error("gravity: {0}")]
    Gravity(String),
    /// A sub-tree without tips.
    #[error("sub-tree rooted at \"{root}\" has no tip links")]
    NoTips {
        /// The root.
        root: String,
    },
    /// A tip listed twice.
    #[error("sub-tree: tip \"{0}\" is listed twice")]
    TipListedTwice(String),
    /// A tip with no moving joint between it and the root.
    #[error("sub-tree: tip \"{tip}\" is not below the root \"{root}\" (no moving joint leads from the root to it)")]
    TipNotBelowRoot {
        /// The tip.
        tip: String,
        /// The root.
        root: String,
    },
    /// An option names a link or frame that the sub-tree removes.
    #[error("{what}: link \"{link}\" is not in the sub-tree (it is {why})")]
    LinkNotInScene {
        /// The option (`tip wrench`, `payload`, `frame_pose`, …).
        what: &'static str,
        /// The link.
        link: String,
        /// Why it is not kept.
        why: &'static str,
    },
    /// Two payloads on one link.
    #[error("link \"{0}\" has two payloads")]
    PayloadListedTwice(String),
    /// A payload with negative mass.
    #[error("payload on link \"{link}\": negative mass {mass} kg")]
    PayloadNegativeMass {
        /// The link.
        link: String,
        /// The mass.
        mass: f64,
    },
    /// A payload that no physical body has.
    #[error("payload on link \"{link}\": {why}")]
    PayloadNotPhysical {
        /// The link.
        link: String,
        /// What is wrong.
        why: String,
    },
    /// A payload table that is neither a constant nor an input, or both.
    #[error("payload on link \"{link}\": {why}")]
    PayloadSpec {
        /// The link.
        link: String,
        /// What is wrong.
        why: &'static str,
    },
    /// A scene that asks for no function at all.
    #[error("the scene generates no function: list at least one in `functions`, `frame_pose` or `frame_jacobian`")]
    NoFunctions,
    /// The reduced robot is not a valid model.
    #[error("the reduced robot: {0}")]
    Model(#[from] ModelError),
}

debug_as_display!(SceneError);

/// Something a scene does that is worth a look: the scene is applied all
/// the same.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SceneWarning {
    /// A branch that hangs off a kept body through a joint that is not on a
    /// path from the root to a tip is dropped: its mass no longer loads the
    /// kept joints.
    DroppedBranch {
        /// The joint that connected the branch.
        joint: String,
        /// The branch's links (the link of every moving body in it).
        links: Vec<String>,
    },
    /// A lock on a joint the sub-tree drops does nothing.
    LockOnDroppedJoint {
        /// The joint.
        joint: String,
    },
    /// A payload on a link fixed to the (new) base moves nothing.
    PayloadOnBase {
        /// The link.
        link: String,
    },
    /// A tip wrench at a link fixed to the (new) base loads no joint.
    TipWrenchOnBase {
        /// The link.
        link: String,
    },
    /// A sub-tree of a floating-base robot rooted at another link than the
    /// floating root: the reduced robot is fixed-base, its root link the
    /// fixed base.
    SubTreeOffFloatingBase {
        /// The sub-tree root.
        root: String,
        /// The floating base (the original root link).
        base: String,
    },
}

impl std::fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SceneWarning::DroppedBranch { joint, links } => write!(
                f,
                "sub-tree: the branch at joint \"{joint}\" (links {}) is not on a path from the root to a tip and is dropped; its mass no longer loads the kept joints",
                links.join(", ")
            ),
            SceneWarning::LockOnDroppedJoint { joint } => {
                write!(f, "joint \"{joint}\" is locked but the sub-tree drops it: the lock does nothing")
            }
            SceneWarning::PayloadOnBase { link } => {
                write!(f, "payload on link \"{link}\": the link is fixed to the base, so the payload moves nothing")
            }
            SceneWarning::TipWrenchOnBase { link } => {
                write!(f, "tip wrench at link \"{link}\": the link is fixed to the base, so the wrench loads no joint")
            }
            SceneWarning::SubTreeOffFloatingBase { root, base } => write!(
                f,
                "sub-tree: the root \"{root}\" is not the floating base \"{base}\", so the reduced robot is fixed-base: \
                 \"{root}\" is held still, the base's motion is left out, and gravity is seen with the base level (give \
                 gravity as an input to follow the base)"
            ),
        }
    }
}
