//! Errors and warnings of model construction. Every one names the link or
//! joint it is about.

use std::path::PathBuf;

/// Why a robot description was refused.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The reason.
        #[source]
        source: std::io::Error,
    },
    /// The URDF is not well-formed XML or not a URDF document.
    #[error("malformed URDF: {0}")]
    Urdf(String),
    /// The URDF names something a number cannot be read from.
    #[error("{item}: cannot read {what} from {text:?}")]
    BadNumber {
        /// The link or joint, as `link "name"` or `joint "name"`.
        item: String,
        /// The attribute.
        what: String,
        /// The text found.
        text: String,
    },
    /// The robot has no links.
    #[error("the robot has no links")]
    NoLinks,
    /// Two links share a name.
    #[error("link \"{0}\" is defined twice")]
    DuplicateLink(String),
    /// Two joints share a name.
    #[error("joint \"{0}\" is defined twice")]
    DuplicateJoint(String),
    /// A joint names a link that does not exist.
    #[error("joint \"{joint}\": its {role} link \"{link}\" does not exist")]
    MissingLink {
        /// The joint.
        joint: String,
        /// "parent" or "child".
        role: &'static str,
        /// The missing link.
        link: String,
    },
    /// A link is the child of two joints.
    #[error("link \"{link}\" is the child of two joints, \"{first}\" and \"{second}\": the robot is not a tree")]
    MultipleParents {
        /// The link.
        link: String,
        /// The first joint.
        first: String,
        /// The second joint.
        second: String,
    },
    /// More than one link has no parent.
    #[error("the robot has several root links ({}): a robot must be one tree", .0.join(", "))]
    MultipleRoots(Vec<String>),
    /// A `floating` joint where dynagen cannot take it: anywhere but
    /// between the root link (the world) and the floating body.
    #[error("joint \"{joint}\": {why}")]
    Floating {
        /// The floating joint.
        joint: String,
        /// What is wrong with it.
        why: String,
    },
    /// The joints form a cycle.
    #[error("the joints form a cycle through link(s) {}", .0.join(", "))]
    Cycle(Vec<String>),
    /// A number that must be finite is not.
    #[error("{item}: {what} is not finite")]
    NonFinite {
        /// The link or joint, as `link "name"` or `joint "name"`.
        item: String,
        /// What is not finite.
        what: &'static str,
    },
    /// A joint axis is zero.
    #[error("joint \"{0}\": the axis is zero")]
    ZeroAxis(String),
    /// A screw axis (whose length scales the joint's motion) too long or
    /// too short for the dynamics to be computed in `f64`.
    #[error(
        "joint \"{joint}\": the axis has length {norm:e}, which scales the joint's motion (a screw axis): lengths outside 1e-100..1e100 overflow the dynamics; give a unit axis, or mark it a direction (URDF axes are)"
    )]
    AxisOutOfRange {
        /// The joint.
        joint: String,
        /// The axis' length.
        norm: f64,
    },
    /// A rotation matrix is not a rotation.
    #[error("{item}: the {what} rotation is not orthonormal with determinant 1")]
    NotARotation {
        /// The link or joint, as `link "name"` or `joint "name"`.
        item: String,
        /// Which rotation.
        what: &'static str,
    },
    /// A link has negative mass.
    #[error("link \"{link}\": negative mass {mass} kg")]
    NegativeMass {
        /// The link.
        link: String,
        /// The mass.
        mass: f64,
    },
    /// A link's rotational inertia is not positive semi-definite.
    #[error(
        "link \"{link}\": the inertia is not positive semi-definite (principal moments {moments:?} kg·m²): no body has it; to load the file all the same, as Pinocchio does, use the option allow_nonphysical_inertia (--allow-nonphysical-inertia, Builder::allow_nonphysical_inertia, the macro key allow_nonphysical_inertia = true, BuildOptions::allow_nonphysical_inertia)"
    )]
    InertiaNotPositive {
        /// The link.
        link: String,
        /// The principal moments.
        moments: [f64; 3],
    },
    /// In strict mode: principal moments that no physical body has.
    #[error("link \"{link}\": the principal moments {moments:?} kg·m² break the triangle inequality (strict mode)")]
    TriangleInequality {
        /// The link.
        link: String,
        /// The principal moments.
        moments: [f64; 3],
    },
    /// A joint moves nothing with mass or inertia along its motion (at
    /// q = 0), so M(q) would be singular.
    #[error(
        "joint \"{joint}\" moves no mass or inertia along its motion (at q = 0), so the mass matrix would be singular: {fix}"
    )]
    MasslessSubtree {
        /// The joint.
        joint: String,
        /// Its child link.
        link: String,
        /// What to change, naming the link.
        fix: String,
    },
    /// A joint's lower position limit is above its upper one.
    #[error("joint \"{joint}\": the lower limit {lower} is above the upper limit {upper}")]
    LimitsReversed {
        /// The joint.
        joint: String,
        /// The lower limit.
        lower: f64,
        /// The upper limit.
        upper: f64,
    },
    /// A joint that follows another (`<mimic>`) in a way dynagen cannot
    /// model: an unknown, fixed or mimicking master, or a joint that does
    /// not move.
    #[error("joint \"{joint}\" (mimic): {why}")]
    Mimic {
        /// The mimic joint.
        joint: String,
        /// What is wrong.
        why: String,
    },
    /// A feature the model does not handle yet.
    #[error("joint \"{joint}\": {what} not supported yet")]
    Unsupported {
        /// The joint.
        joint: String,
        /// The feature.
        what: String,
    },
    /// The Modern Robotics lists do not fit together.
    #[error("Modern Robotics lists: {0}")]
    ModernRobotics(String),
    /// A named frame, link or joint was not found.
    #[error("no link, joint or frame named \"{0}\"")]
    UnknownName(String),
}

debug_as_display!(ModelError);

/// Something accepted, but worth a look: the model is built all the same.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ModelWarning {
    /// Positive semi-definite inertia whose principal moments break the
    /// triangle inequality (seen in published URDFs of hands and fingers;
    /// Pinocchio accepts them too).
    TriangleInequality {
        /// The link.
        link: String,
        /// The principal moments.
        moments: [f64; 3],
    },
    /// A link without mass has a non-zero rotational inertia.
    InertiaWithoutMass {
        /// The link.
        link: String,
    },
    /// Accepted by [`BuildOptions::allow_nonphysical_inertia`](super::BuildOptions::allow_nonphysical_inertia):
    /// a rotational inertia that is not positive semi-definite.
    NonPhysicalInertia {
        /// The link.
        link: String,
        /// The principal moments (the smallest negative).
        moments: [f64; 3],
    },
    /// Joints that together can move without moving any mass: the mass
    /// matrix is singular at every configuration tried (coincident joints
    /// with one axis, say). Inverse dynamics, M, h and g are computed;
    /// forward dynamics is refused.
    DependentJoints {
        /// The joints of one dependent motion, in joint order.
        joints: Vec<String>,
    },
    /// A URDF joint axis that was not of unit length was normalised.
    AxisNormalised {
        /// The joint.
        joint: String,
        /// The axis' length in the file.
        norm: f64,
    },
    /// A revolute joint moves mass at q = 0, but only through point masses
    /// and rods that later joints can carry onto its axis: its diagonal
    /// entry of M(q) could vanish in some configuration (no body moved by
    /// it has a moment of inertia about every axis, and its own body none
    /// about its axis).
    MassMatrixMayBeSingular {
        /// The joint.
        joint: String,
    },
    /// A floating base whose whole robot, at q = 0, has no mass or no
    /// moment of inertia about some axis through its centre of mass: the
    /// base block of M(q) is singular there, and forward dynamics fails.
    FloatingBaseSingular {
        /// The floating root link.
        root: String,
    },
}

impl ModelWarning {
    /// Whether the warning says the dynamics themselves may fail (a
    /// non-physical inertia accepted, dependent joints), rather than that a
    /// file's numbers look odd: a build script shows these.
    pub fn is_about_the_dynamics(&self) -> bool {
        matches!(self, ModelWarning::NonPhysicalInertia { .. } | ModelWarning::DependentJoints { .. })
    }
    /// The message on one line, control characters and line separators in
    /// names escaped (`\u{a}`), for a `cargo:warning=` line or a log.
    pub fn one_line(&self) -> String {
        self.to_string()
            .chars()
            .map(|c| match c {
                c if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') => c.escape_unicode().to_string(),
                c => c.to_string(),
            })
            .collect()
    }
}

impl std::fmt::Display for ModelWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ModelWarning::TriangleInequality { link, moments } => write!(
                f,
                "link \"{link}\": principal moments {moments:?} kg·m² break the triangle inequality (no physical body has them; accepted, refused in strict mode)"
            ),
            ModelWarning::NonPhysicalInertia { link, moments } => write!(
                f,
                "link \"{link}\": the inertia is not positive semi-definite (principal moments {moments:?} kg·m²), accepted as asked (allow_nonphysical_inertia): no body has it, so the mass matrix M(q) may be indefinite or singular, its kinetic energy negative, and forward dynamics may fail or give accelerations no robot has; inverse dynamics computes what the numbers say"
            ),
            ModelWarning::DependentJoints { joints } => write!(
                f,
                "joints {} are dependent: together they can move without moving any mass, so the mass matrix M(q) is singular at every configuration; inverse dynamics, M, h and g are computed, but forward dynamics is undefined and refused (make the joints independent: remove or fix one, or give them different axes or places)",
                quoted(joints)
            ),
            ModelWarning::InertiaWithoutMass { link } => {
                write!(f, "link \"{link}\": zero mass but a non-zero rotational inertia")
            }
            ModelWarning::AxisNormalised { joint, norm } => {
                write!(f, "joint \"{joint}\": axis of length {norm} normalised to unit length")
            }
            ModelWarning::MassMatrixMayBeSingular { joint } => write!(
                f,
                "joint \"{joint}\": it moves only point masses and rods held by later joints (nothing with a moment of inertia about every axis, and its own body nothing about its axis), so its diagonal entry of M(q), positive at q = 0, may vanish in another configuration, where forward dynamics fails"
            ),
            ModelWarning::FloatingBaseSingular { root } => write!(
                f,
                "link \"{root}\" floats, but the whole robot at q = 0 has no mass or no moment of inertia about some axis through its centre of mass: the base block of M(q) is singular, and forward dynamics fails"
            ),
        }
    }
}

/// `"a", "b" and "c"`.
pub(crate) fn quoted(names: &[String]) -> String {
    let q: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    match q.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}
