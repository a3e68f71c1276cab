//! Describing a robot in Rust.

use super::description::{Inertial, JointDescription, LinkDescription, RobotDescription};
use super::{BuildOptions, MimicJoints, Model, ModelError};

/// Builds a [`Model`] from links and joints written in Rust, with the same
/// checks as a URDF.
///
/// ```
/// use dynagen::model::{Inertial, JointDescription, RobotBuilder};
/// let model = RobotBuilder::new("pendulum")
///     .link("base", None)
///     .link("arm", Some(Inertial::point_mass(1.0, [0.0, 0.0, -1.0])))
///     .joint(JointDescription::revolute("hinge", "base", "arm", [0.0, 1.0, 0.0]))
///     .build()
///     .unwrap();
/// assert_eq!(model.dof(), 1);
/// ```
#[derive(Clone, Debug, Default)]
pub struct RobotBuilder {
    desc: RobotDescription,
    opts: BuildOptions,
    floating: bool,
}

impl RobotBuilder {
    /// An empty robot with this name.
    pub fn new(name: &str) -> Self {
        RobotBuilder {
            desc: RobotDescription { name: name.to_string(), ..Default::default() },
            opts: BuildOptions::default(),
            floating: false,
        }
    }
    /// Adds a link; `None` is massless.
    pub fn link(mut self, name: &str, inertial: Option<Inertial>) -> Self {
        self.desc.links.push(LinkDescription::new(name, inertial));
        self
    }
    /// Adds a joint (see [`JointDescription::revolute`] and its siblings).
    pub fn joint(mut self, joint: JointDescription) -> Self {
        self.desc.joints.push(joint);
        self
    }
    /// Sets gravity in the base frame (m/s²).
    pub fn gravity(mut self, g: [f64; 3]) -> Self {
        self.desc.gravity = Some(g);
        self
    }
    /// Refuse inertias that break the triangle inequality.
    pub fn strict(mut self, strict: bool) -> Self {
        self.opts.strict = strict;
        self
    }
    /// Accept links whose rotational inertia is not positive semi-definite,
    /// each with a warning ([`BuildOptions::allow_nonphysical_inertia`]).
    pub fn allow_nonphysical_inertia(mut self, allow: bool) -> Self {
        self.opts.allow_nonphysical_inertia = allow;
        self
    }
    /// Whether joints made with [`JointDescription::mimic`] follow their
    /// master (the default) or are independent joints
    /// ([`BuildOptions::mimic`]).
    ///
    /// ```
    /// use dynagen::model::{Inertial, JointDescription, MimicJoints, RobotBuilder};
    /// let finger = Some(Inertial::new(0.02, [0.0, 0.0, 0.03], [1e-6, 1e-6, 1e-6, 0.0, 0.0, 0.0]));
    /// let gripper = RobotBuilder::new("gripper")
    ///     .link("palm", None)
    ///     .link("left", finger)
    ///     .link("right", finger)
    ///     .joint(JointDescription::prismatic("left_joint", "palm", "left", [0.0, 1.0, 0.0]))
    ///     .joint(JointDescription::prismatic("right_joint", "palm", "right", [0.0, -1.0, 0.0]).mimic("left_joint", 1.0, 0.0));
    /// assert_eq!(gripper.build().unwrap().dof(), 1); // the fingers move together
    /// assert_eq!(gripper.mimic_joints(MimicJoints::Independent).build().unwrap().dof(), 2);
    /// ```
    pub fn mimic_joints(mut self, mimic: MimicJoints) -> Self {
        self.opts.mimic = mimic;
        self
    }
    /// The description built so far.
    pub fn description(&self) -> &RobotDescription {
        &self.desc
    }
    /// Validates and builds the model.
    pub fn build(&self) -> Result<Model, ModelError> {
        let model = Model::from_description_with(&self.desc, &self.opts)?;
        Ok(if self.floating { model.with_floating_base() } else { model })
    }
    /// Whether the root link floats (a quadruped's trunk): see
    /// [`Model::with_floating_base`].
    ///
    /// ```
    /// use dynagen::model::{Inertial, JointDescription, RobotBuilder};
    /// let body = Inertial::new(2.0, [0.0; 3], [0.1, 0.1, 0.1, 0.0, 0.0, 0.0]);
    /// let model = RobotBuilder::new("hopper")
    ///     .link("trunk", Some(body))
    ///     .link("leg", Some(Inertial::point_mass(0.5, [0.0, 0.0, -0.3])))
    ///     .joint(JointDescription::prismatic("knee", "trunk", "leg", [0.0, 0.0, 1.0]))
    ///     .floating_base(true)
    ///     .build()
    ///     .unwrap();
    /// assert_eq!((model.dof(), model.nq(), model.nv()), (1, 8, 7));
    /// ```
    pub fn floating_base(mut self, floating: bool) -> Self {
        self.floating = floating;
        self
    }
}
