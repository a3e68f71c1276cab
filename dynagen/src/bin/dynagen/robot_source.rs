//! Where the robot comes from: a URDF file named on the command line, or the
//! bundled UR5, compiled into the binary so that it works from any directory.

use crate::error::CliError;
use dynagen::model::{BuildOptions, MimicJoints};
use dynagen::Model;
use std::fmt;
use std::path::{Path, PathBuf};

/// The bundled default robot.
const BUNDLED_UR5: &str = include_str!("../../../robots/ur5.urdf");
/// Its name in messages.
const BUNDLED_UR5_NAME: &str = "ur5.urdf (bundled)";

/// How a robot file is loaded: the options of every command that reads one.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct LoadArgs {
    /// Accept links whose rotational inertia is not positive semi-definite
    /// (as Pinocchio does), with a warning for each: M(q) may then be
    /// indefinite and forward dynamics may fail.
    #[arg(long)]
    pub allow_nonphysical_inertia: bool,
    /// Give the robot a floating root: its root link moves freely; q has
    /// NQ = DOF + 7 entries (base position, quaternion x, y, z, w, joints),
    /// the velocity-side vectors NV = DOF + 6 (the base's body twist, angular
    /// first, then the joints). A URDF whose root joint is `floating` has one
    /// anyway.
    #[arg(long)]
    pub floating_base: bool,
    /// What a joint with a <mimic> element is: `follow` (the default), it
    /// follows its master (q = multiplier·q_master + offset) and has no entry
    /// of its own in q, q̇, τ; `independent`, a joint of its own, as if the
    /// element were not there.
    #[arg(long, value_name = "follow|independent", default_value = "follow", value_parser = parse_mimic)]
    pub mimic: MimicJoints,
}

fn parse_mimic(s: &str) -> Result<MimicJoints, String> {
    s.parse()
}

impl LoadArgs {
    /// The model options these arguments ask for.
    pub fn options(&self) -> BuildOptions {
        BuildOptions::default().allow_nonphysical_inertia(self.allow_nonphysical_inertia).mimic_joints(self.mimic)
    }
}

/// A robot's source.
#[derive(Clone, Debug)]
pub enum RobotSource {
    /// The bundled UR5.
    BundledUr5,
    /// A URDF file.
    File(PathBuf),
}

impl RobotSource {
    /// The file given on the command line, or the bundled UR5.
    pub fn from_arg(arg: Option<&Path>) -> Self {
        match arg {
            Some(p) => RobotSource::File(p.to_path_buf()),
            None => RobotSource::BundledUr5,
        }
    }

    /// Reads and validates the robot. Errors name the file, then the link or
    /// joint (dynagen's model errors name it).
    pub fn load(&self, args: &LoadArgs) -> Result<Model, CliError> {
        let xml = match self {
            RobotSource::BundledUr5 => std::borrow::Cow::Borrowed(BUNDLED_UR5),
            RobotSource::File(p) => std::fs::read_to_string(p)
                .map(std::borrow::Cow::Owned)
                .map_err(|e| CliError::input(self, format!("cannot read the file: {e}")))?,
        };
        let model = Model::from_urdf_str_with(&xml, &args.options()).map_err(|e| CliError::input(self, e))?;
        Ok(if args.floating_base { model.with_floating_base() } else { model })
    }

    /// Each warning of the model, as `{file}: {warning}`.
    pub fn warnings(&self, model: &Model) -> Vec<String> {
        model.warnings.iter().map(|w| format!("{self}: {w}")).collect()
    }
}

impl fmt::Display for RobotSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RobotSource::BundledUr5 => f.write_str(BUNDLED_UR5_NAME),
            RobotSource::File(p) => write!(f, "{}", p.display()),
        }
    }
}
