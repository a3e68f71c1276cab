//! URDF import, through urdf-rs, then dynagen's own checks.

use super::description::{Inertial, JointDescription, JointLimits, JointType, LinkDescription, RobotDescription};
use super::{BuildOptions, Model, ModelError, ModelWarning};
use crate::spatial::{Mat3, Sym3, Transform, Vec3};
use std::path::Path;

fn pose(p: &urdf_rs::Pose) -> Transform<f64> {
    Transform::new(Mat3::from_rpy(p.rpy[0], p.rpy[1], p.rpy[2]), Vec3(*p.xyz))
}

/// Converts a parsed URDF to a description. Axes are normalised (as the URDF
/// specification requires and Pinocchio does); each normalisation is
/// returned as a warning.
pub(super) fn description_from_urdf(
    robot: &urdf_rs::Robot,
) -> Result<(RobotDescription, Vec<ModelWarning>), ModelError> {
    let mut warnings = Vec::new();
    let links = robot
        .links
        .iter()
        .map(|l| {
            let i = &l.inertial;
            let rpy = &i.origin.rpy;
            if !rpy.iter().all(|x| x.is_finite()) {
                return Err(ModelError::NonFinite {
                    item: format!("link \"{}\"", l.name),
                    what: "inertial origin rpy",
                });
            }
            let inertia =
                Sym3([i.inertia.ixx, i.inertia.iyy, i.inertia.izz, i.inertia.ixy, i.inertia.ixz, i.inertia.iyz]);
            let massless = i.mass.value == 0.0 && inertia.0.iter().all(|&x| x == 0.0);
            Ok(LinkDescription {
                name: l.name.clone(),
                inertial: (!massless).then(|| Inertial { mass: i.mass.value, origin: pose(&i.origin), inertia }),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let joints = robot
        .joints
        .iter()
        .map(|j| {
            if !j.origin.rpy.iter().all(|x| x.is_finite()) {
                return Err(ModelError::NonFinite { item: format!("joint \"{}\"", j.name), what: "origin rpy" });
            }
            let joint_type = match j.joint_type {
                urdf_rs::JointType::Revolute => JointType::Revolute,
                urdf_rs::JointType::Continuous => JointType::Continuous,
                urdf_rs::JointType::Prismatic => JointType::Prismatic,
                urdf_rs::JointType::Fixed => JointType::Fixed,
                urdf_rs::JointType::Floating => JointType::Floating,
                urdf_rs::JointType::Planar => JointType::Planar,
                urdf_rs::JointType::Spherical => JointType::Spherical,
            };
            let mut axis = Vec3(*j.axis.xyz);
            let norm = axis.norm();
            if joint_type != JointType::Fixed && norm.is_finite() && norm > 0.0 && (norm - 1.0).abs() > 1e-9 {
                warnings.push(ModelWarning::AxisNormalised { joint: j.name.clone(), norm });
                axis = axis.scale(1.0 / norm);
            }
            let limits = matches!(joint_type, JointType::Revolute | JointType::Prismatic).then_some(JointLimits {
                lower: j.limit.lower,
                upper: j.limit.upper,
                velocity: j.limit.velocity,
                effort: j.limit.effort,
            });
            Ok(JointDescription {
                name: j.name.clone(),
                joint_type,
                parent: j.parent.link.clone(),
                child: j.child.link.clone(),
                origin: pose(&j.origin),
                axis,
                limits,
                mimic: j.mimic.is_some(),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((RobotDescription { name: robot.name.clone(), links, joints, gravity: None }, warnings))
}

impl Model {
    /// Reads a URDF document from a string.
    pub fn from_urdf_str(xml: &str) -> Result<Model, ModelError> {
        Self::from_urdf_str_with(xml, &BuildOptions::default())
    }

    /// Reads a URDF document from a string, with options.
    pub fn from_urdf_str_with(xml: &str, opts: &BuildOptions) -> Result<Model, ModelError> {
        let robot = urdf_rs::read_from_string(xml).map_err(|e| ModelError::Urdf(e.to_string()))?;
        let (desc, warnings) = description_from_urdf(&robot)?;
        let mut model = Model::from_description_with(&desc, opts)?;
        model.warnings.splice(0..0, warnings);
        Ok(model)
    }

    /// Reads a URDF file.
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Model, ModelError> {
        Self::from_urdf_file_with(path, &BuildOptions::default())
    }

    /// Reads a URDF file, with options.
    pub fn from_urdf_file_with(path: impl AsRef<Path>, opts: &BuildOptions) -> Result<Model, ModelError> {
        let path = path.as_ref();
        let xml =
            std::fs::read_to_string(path).map_err(|source| ModelError::Io { path: path.to_path_buf(), source })?;
        Self::from_urdf_str_with(&xml, opts)
    }
}
