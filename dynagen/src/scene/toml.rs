//! Scenes as TOML (the format is documented in the [scene docs](super)).

use super::{Gravity, Payload, PayloadInertia, PayloadValue, Scene, SceneError, SubTree};
use crate::codegen::{CodegenOptions, Function, ScalarType, Trig};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileText {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    functions: Option<Vec<String>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_pose: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_jacobian: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_world_jacobian: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    frame_acceleration_bias: Vec<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scalar: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    target: Option<TargetName>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    trig: Option<String>,
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

/// The code-generation keys a scene file may carry; each sets the
/// [`CodegenOptions`] field of its name unless that was set otherwise.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CodeKeys {
    /// `name`.
    pub name: Option<String>,
    /// `functions` and the frame keys (`frame_pose`, `frame_jacobian`,
    /// `frame_world_jacobian`, `frame_acceleration_bias`; `None` if the
    /// file has none of them).
    pub functions: Option<Vec<Function>>,
    /// `scalar`.
    pub scalar: Option<ScalarType>,
    /// `trig` (`batched`, `std`, `libm`, `inputs`), or `target`:
    /// `no_std_libm` is [`Trig::Libm`], `no_std_sincos` [`Trig::Inputs`],
    /// `std` leaves the trigonometry to the options. Both keys at once are
    /// an error.
    pub trig: Option<Trig>,
}

impl CodeKeys {
    /// `options` with the file's keys applied.
    pub fn apply(&self, mut options: CodegenOptions) -> CodegenOptions {
        if let Some(n) = &self.name {
            options.name = Some(n.clone());
        }
        if let Some(f) = &self.functions {
            options = options.functions(f.iter().cloned());
        }
        if let Some(s) = self.scalar {
            options.scalar = s;
        }
        if let Some(t) = self.trig {
            options.trig = t;
        }
        options
    }
}

/// A scene file: the physics, and the code-generation keys beside it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneFile {
    /// The physics.
    pub scene: Scene,
    /// The code-generation keys.
    pub code: CodeKeys,
}

fn scene_from_file(f: FileText) -> Result<SceneFile, SceneError> {
    let mut scene = Scene { tip_wrench: f.tip_wrench, ..Scene::default() };
    let mut code = CodeKeys { name: f.name, ..CodeKeys::default() };
    let frames = [
        (Function::FRAME_KINDS[0], f.frame_pose),
        (Function::FRAME_KINDS[1], f.frame_jacobian),
        (Function::FRAME_KINDS[2], f.frame_world_jacobian),
        (Function::FRAME_KINDS[3], f.frame_acceleration_bias),
    ];
    if f.functions.is_some() || frames.iter().any(|(_, list)| !list.is_empty()) {
        let mut list: Vec<Function> = match f.functions {
            // The spelling the command line and the macros read too.
            Some(names) => names
                .iter()
                .map(|n| {
                    Function::from_name(n).ok_or_else(|| {
                        SceneError::Toml(format!(
                            "functions: unknown function \"{n}\" (expected one of {})",
                            Function::NAMES.join(", ")
                        ))
                    })
                })
                .collect::<Result<_, _>>()?,
            None => Function::DEFAULT.to_vec(),
        };
        for (kind, names) in frames {
            list.extend(names.iter().filter_map(|frame| Function::frame_function(kind, frame)));
        }
        let mut functions = Vec::new();
        for x in list {
            if !functions.contains(&x) {
                functions.push(x);
            }
        }
        if functions.is_empty() {
            return Err(SceneError::NoFunctions);
        }
        code.functions = Some(functions);
    }
    // The spelling the command line and the macros read too.
    code.scalar = match f.scalar {
        Some(s) => Some(s.parse::<ScalarType>().map_err(SceneError::Toml)?),
        None => None,
    };
    code.trig = match (f.target, f.trig) {
        (Some(_), Some(_)) => {
            return Err(SceneError::Toml(
                "`target` and `trig` both say where the sines and cosines come from: give one".into(),
            ))
        }
        (None, Some(t)) => Some(t.parse::<Trig>().map_err(SceneError::Toml)?),
        (Some(TargetName::NoStdLibm), None) => Some(Trig::Libm),
        (Some(TargetName::NoStdSincos), None) => Some(Trig::Inputs),
        (Some(TargetName::Std) | None, None) => None,
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
    Ok(SceneFile { scene, code })
}

fn file_from_scene(s: &Scene) -> FileText {
    let mut f = FileText { tip_wrench: s.tip_wrench.clone(), ..FileText::default() };
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

impl SceneFile {
    /// Reads a scene file from TOML (format in the [module docs](super)),
    /// and runs the checks that need no robot ([`Scene::check`]).
    pub fn from_toml_str(text: &str) -> Result<SceneFile, SceneError> {
        let file: FileText = ::toml::from_str(text).map_err(|e| SceneError::Toml(e.to_string()))?;
        scene_from_file(file)
    }
    /// Reads a scene file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<SceneFile, SceneError> {
        let path = path.as_ref();
        let text =
            std::fs::read_to_string(path).map_err(|source| SceneError::Io { path: path.to_path_buf(), source })?;
        Self::from_toml_str(&text).map_err(|e| match e {
            SceneError::Toml(m) => SceneError::Toml(format!("{}: {m}", path.display())),
            e => e,
        })
    }
}

impl SceneFile {
    /// The scene file as TOML: reading it back gives the same [`SceneFile`]
    /// (the per-joint options grouped by joint, in name order; functions,
    /// then each frame key's frames; the trigonometry as `trig`).
    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        let mut f = file_from_scene(&self.scene);
        let c = &self.code;
        f.name = c.name.clone();
        if let Some(list) = &c.functions {
            let mut names = Vec::new();
            for x in list {
                match x {
                    Function::FramePose(frame) => f.frame_pose.push(frame.clone()),
                    Function::FrameJacobian(frame) => f.frame_jacobian.push(frame.clone()),
                    Function::FrameWorldJacobian(frame) => f.frame_world_jacobian.push(frame.clone()),
                    Function::FrameAccelerationBias(frame) => f.frame_acceleration_bias.push(frame.clone()),
                    other => names.push(other.name().to_string()),
                }
            }
            f.functions = Some(names);
        }
        f.scalar = c.scalar.map(|s| s.name().to_string());
        f.trig = c.trig.map(|t| t.name().to_string());
        ::toml::to_string(&f).map_err(|e| SceneError::Toml(e.to_string()))
    }
}

impl Scene {
    /// The physics of a scene file read from TOML (its code-generation keys
    /// are checked, then left to [`SceneFile`]).
    pub fn from_toml_str(text: &str) -> Result<Scene, SceneError> {
        SceneFile::from_toml_str(text).map(|f| f.scene)
    }
    /// The physics of a scene file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        SceneFile::from_toml_file(path).map(|f| f.scene)
    }
    /// The scene as TOML, every option written out: reading it back gives
    /// the same scene (with the per-joint options grouped by joint, in name
    /// order).
    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        ::toml::to_string(&file_from_scene(self)).map_err(|e| SceneError::Toml(e.to_string()))
    }
}
