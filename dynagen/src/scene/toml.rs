//! Scenes as TOML (the format is documented in the [scene docs](super)).

use super::{Function, Gravity, Payload, PayloadInertia, PayloadValue, ScalarType, Scene, SceneError, SubTree, Target};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    functions: Option<Vec<FunctionName>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_pose: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_jacobian: Vec<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scalar: Option<ScalarName>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    target: Option<TargetName>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tip_wrench: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    coulomb_velocity: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    gravity: Option<GravityFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    subtree: Option<SubTreeFile>,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    joints: BTreeMap<String, JointFile>,
    #[serde(default, rename = "payload", skip_serializing_if = "Vec::is_empty")]
    payloads: Vec<PayloadFile>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum FunctionName {
    InverseDynamics,
    MassMatrix,
    BiasForces,
    GravityTorques,
    Coriolis,
    ForwardDynamics,
}

#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum ScalarName {
    F64,
    F32,
}

#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum TargetName {
    Std,
    NoStdLibm,
    NoStdSincos,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum GravityMode {
    Default,
    Constant,
    None,
    Input,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct GravityFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mode: Option<GravityMode>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    vector: Option<[f64; 3]>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SubTreeFile {
    root: String,
    tips: Vec<String>,
}

#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JointFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    lock: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    armature: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    viscous: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    coulomb: Option<f64>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PayloadFile {
    link: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    input: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mass: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    com: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    inertia: Option<[f64; 6]>,
}

impl FunctionName {
    fn function(self) -> Function {
        match self {
            FunctionName::InverseDynamics => Function::InverseDynamics,
            FunctionName::MassMatrix => Function::MassMatrix,
            FunctionName::BiasForces => Function::BiasForces,
            FunctionName::GravityTorques => Function::GravityTorques,
            FunctionName::Coriolis => Function::Coriolis,
            FunctionName::ForwardDynamics => Function::ForwardDynamics,
        }
    }
}

fn scene_from_file(f: SceneFile) -> Result<Scene, SceneError> {
    let mut scene = Scene { name: f.name, tip_wrench: f.tip_wrench, ..Scene::default() };
    if let Some(list) = f.functions {
        scene.functions = Vec::new();
        for x in list {
            scene = scene.function(x.function());
        }
    }
    for frame in f.frame_pose {
        scene = scene.function(Function::FramePose(frame));
    }
    for frame in f.frame_jacobian {
        scene = scene.function(Function::FrameJacobian(frame));
    }
    scene.scalar = match f.scalar {
        Some(ScalarName::F32) => ScalarType::F32,
        _ => ScalarType::F64,
    };
    scene.target = match f.target {
        Some(TargetName::NoStdLibm) => Target::NoStdLibm,
        Some(TargetName::NoStdSincos) => Target::NoStdSinCos,
        _ => Target::Std,
    };
    if let Some(v) = f.coulomb_velocity {
        scene.coulomb_velocity = v;
    }
    if let Some(g) = f.gravity {
        scene.gravity = match (g.mode, g.vector) {
            (None | Some(GravityMode::Default), None) => Gravity::Default,
            (None | Some(GravityMode::Constant), Some(v)) => Gravity::Constant(v),
            (Some(GravityMode::Constant), None) => {
                return Err(SceneError::Gravity("mode \"constant\" needs a vector".to_string()))
            }
            (Some(GravityMode::None), None) => Gravity::None,
            (Some(GravityMode::Input), None) => Gravity::Input,
            (Some(mode), Some(v)) => {
                let name = match mode {
                    GravityMode::Default => "default",
                    GravityMode::None => "none",
                    _ => "input",
                };
                return Err(SceneError::Gravity(format!(
                    "mode \"{name}\" contradicts the constant vector {v:?} (a vector is only for mode \"constant\")"
                )));
            }
        };
    }
    scene.subtree = f.subtree.map(|s| SubTree { root: s.root, tips: s.tips });
    for (joint, j) in f.joints {
        if let Some(q) = j.lock {
            scene.locks.push((joint.clone(), q));
        }
        if let Some(a) = j.armature {
            scene.armature.push((joint.clone(), a));
        }
        if let Some(b) = j.viscous {
            scene.viscous_friction.push((joint.clone(), b));
        }
        if let Some(c) = j.coulomb {
            scene.coulomb_friction.push((joint, c));
        }
    }
    for p in f.payloads {
        let value = match (p.input, p.mass) {
            (Some(true), _) => {
                if p.mass.is_some() || p.com.is_some() || p.inertia.is_some() {
                    return Err(SceneError::PayloadSpec {
                        link: p.link,
                        why: "input = true contradicts the mass, com or inertia given",
                    });
                }
                PayloadValue::Input
            }
            (_, Some(mass)) => PayloadValue::Constant(PayloadInertia {
                mass,
                com: p.com.unwrap_or([0.0; 3]),
                inertia: p.inertia.unwrap_or([0.0; 6]),
            }),
            (_, None) => {
                return Err(SceneError::PayloadSpec { link: p.link, why: "needs a mass (or input = true)" });
            }
        };
        scene.payloads.push(Payload { link: p.link, value });
    }
    scene.check()?;
    Ok(scene)
}

fn file_from_scene(s: &Scene) -> SceneFile {
    let mut f = SceneFile { name: s.name.clone(), tip_wrench: s.tip_wrench.clone(), ..SceneFile::default() };
    let mut functions = Vec::new();
    for x in &s.functions {
        match x {
            Function::InverseDynamics => functions.push(FunctionName::InverseDynamics),
            Function::MassMatrix => functions.push(FunctionName::MassMatrix),
            Function::BiasForces => functions.push(FunctionName::BiasForces),
            Function::GravityTorques => functions.push(FunctionName::GravityTorques),
            Function::Coriolis => functions.push(FunctionName::Coriolis),
            Function::ForwardDynamics => functions.push(FunctionName::ForwardDynamics),
            Function::FramePose(frame) => f.frame_pose.push(frame.clone()),
            Function::FrameJacobian(frame) => f.frame_jacobian.push(frame.clone()),
        }
    }
    f.functions = Some(functions);
    f.scalar = Some(match s.scalar {
        ScalarType::F64 => ScalarName::F64,
        ScalarType::F32 => ScalarName::F32,
    });
    f.target = Some(match s.target {
        Target::Std => TargetName::Std,
        Target::NoStdLibm => TargetName::NoStdLibm,
        Target::NoStdSinCos => TargetName::NoStdSincos,
    });
    f.coulomb_velocity = Some(s.coulomb_velocity);
    f.gravity = Some(match s.gravity {
        Gravity::Default => GravityFile { mode: Some(GravityMode::Default), vector: None },
        Gravity::Constant(v) => GravityFile { mode: Some(GravityMode::Constant), vector: Some(v) },
        Gravity::None => GravityFile { mode: Some(GravityMode::None), vector: None },
        Gravity::Input => GravityFile { mode: Some(GravityMode::Input), vector: None },
    });
    f.subtree = s.subtree.as_ref().map(|t| SubTreeFile { root: t.root.clone(), tips: t.tips.clone() });
    for (j, q) in &s.locks {
        f.joints.entry(j.clone()).or_default().lock = Some(*q);
    }
    for (j, a) in &s.armature {
        f.joints.entry(j.clone()).or_default().armature = Some(*a);
    }
    for (j, b) in &s.viscous_friction {
        f.joints.entry(j.clone()).or_default().viscous = Some(*b);
    }
    for (j, c) in &s.coulomb_friction {
        f.joints.entry(j.clone()).or_default().coulomb = Some(*c);
    }
    f.payloads = s
        .payloads
        .iter()
        .map(|p| match &p.value {
            PayloadValue::Input => {
                PayloadFile { link: p.link.clone(), input: Some(true), mass: None, com: None, inertia: None }
            }
            PayloadValue::Constant(v) => PayloadFile {
                link: p.link.clone(),
                input: None,
                mass: Some(v.mass),
                com: Some(v.com),
                inertia: Some(v.inertia),
            },
        })
        .collect();
    f
}

impl Scene {
    /// Reads a scene from TOML (format in the [module docs](super)), and
    /// runs the checks that need no robot ([`Scene::check`]).
    pub fn from_toml_str(text: &str) -> Result<Scene, SceneError> {
        let file: SceneFile = ::toml::from_str(text).map_err(|e| SceneError::Toml(e.to_string()))?;
        scene_from_file(file)
    }
    /// Reads a scene from a TOML file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text =
            std::fs::read_to_string(path).map_err(|source| SceneError::Io { path: path.to_path_buf(), source })?;
        Self::from_toml_str(&text).map_err(|e| match e {
            SceneError::Toml(m) => SceneError::Toml(format!("{}: {m}", path.display())),
            e => e,
        })
    }
    /// The scene as TOML, every option written out: reading it back gives
    /// the same scene (with the per-joint options grouped by joint, in name
    /// order, and the frame functions after the others).
    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        ::toml::to_string(&file_from_scene(self)).map_err(|e| SceneError::Toml(e.to_string()))
    }
}
