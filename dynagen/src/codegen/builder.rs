//! The build-script face of code generation: [`Builder`].
//!
//! ```no_run
//! // build.rs, in `fn main()`:
//! dynagen::Builder::new().urdf("robots/ur5.urdf").generate().expect("generating the UR5 dynamics");
//! ```
//!
//! ```ignore
//! // src/lib.rs
//! mod ur5 {
//!     include!(concat!(env!("OUT_DIR"), "/ur5.rs"));
//! }
//! ```
//!
//! The written file holds items only (no inner attributes such as
//! `#![...]`), so it can be `include!`d inside a `mod` block. With the
//! default options it uses neither std nor any crate, so it also compiles
//! in a `#![no_std]` crate.

use super::{
    generate, generate_scene, CodegenError, CodegenOptions, ForwardDynamicsMethod, Functions, GeneratedModule,
    ScalarType,
};
use crate::model::{Model, ModelError};
use crate::scene::{Function as SceneFunction, Scene, SceneError, SceneModel};
use std::fmt;
use std::path::{Path, PathBuf};

/// Where the robot comes from.
#[derive(Clone, Debug)]
enum RobotInput {
    Urdf(PathBuf),
    Model(Box<Model>),
}

/// Where the scene comes from.
#[derive(Clone, Debug)]
enum SceneInput {
    Scene(Box<Scene>),
    File(PathBuf),
}

/// Generates a robot's dynamics module from a build script, in the manner
/// of `prost-build`: chained options, then one [`generate`](Builder::generate)
/// that writes `<name>.rs` into `OUT_DIR` and tells cargo to rerun the build
/// script when an input file changes.
///
/// ```
/// # let dir = std::env::temp_dir().join("dynagen-builder-doc");
/// let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf");
/// let written = dynagen::Builder::new()
///     .urdf(urdf)
///     .functions(&["inverse_dynamics", "mass_matrix"])
///     .scalar(dynagen::codegen::ScalarType::F32)
///     .out_dir(&dir)
///     .generate()
///     .unwrap();
/// assert_eq!(written.path, dir.join("ur5.rs"));
/// assert!(written.module.source.contains("pub fn mass_matrix(q: &[f32; DOF]) -> [[f32; DOF]; DOF]"));
/// assert!(!written.module.source.contains("pub fn forward_dynamics"));
/// ```
#[derive(Clone, Debug, Default)]
#[must_use = "a Builder does nothing until `.generate()` is called"]
pub struct Builder {
    robot: Option<RobotInput>,
    scene: Option<SceneInput>,
    functions: Option<Vec<String>>,
    options: CodegenOptions,
    file_name: Option<String>,
    out_dir: Option<PathBuf>,
    cargo_output: Option<bool>,
}

/// What [`Builder::generate`] wrote.
#[derive(Clone, Debug)]
pub struct GeneratedFile {
    /// The file written.
    pub path: PathBuf,
    /// The module (source, op counts, …).
    pub module: GeneratedModule,
    /// The input files read (the URDF, the scene file), as given.
    pub inputs: Vec<PathBuf>,
}

/// Why [`Builder`] could not generate. The message names the file and the
/// item (link, joint, option) it is about, so `build.rs` can simply
/// `.unwrap()` or `.expect(..)`.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// Neither [`Builder::urdf`] nor [`Builder::model`] was called.
    #[error("dynagen::Builder: no robot given (call `.urdf(\"path/to/robot.urdf\")` or `.model(model)`)")]
    NoRobot,
    /// The robot file could not be read or is not a valid robot.
    #[error("dynagen: robot {}: {source}", .path.display())]
    Robot {
        /// The URDF file.
        path: PathBuf,
        /// What is wrong (names the link or joint).
        #[source]
        source: ModelError,
    },
    /// The scene file could not be read or is not a valid scene.
    #[error("dynagen: scene {}: {source}", .path.display())]
    Scene {
        /// The scene file.
        path: PathBuf,
        /// What is wrong (names the key, link or joint).
        #[source]
        source: SceneError,
    },
    /// The scene does not fit the robot (an unknown link or joint, a tip not
    /// below the root, …).
    #[error("dynagen: scene {scene} for {robot}: {source}")]
    SceneRobot {
        /// The scene file, or `(given in Rust)`.
        scene: String,
        /// The robot's source.
        robot: String,
        /// What is wrong (names the link, joint or option).
        #[source]
        source: Box<SceneError>,
    },
    /// A function name that is not one of the generated-code contract or
    /// `coriolis`.
    #[error("dynagen: unknown function \"{name}\" (the functions are {}, coriolis)", super::FUNCTION_NAMES.join(", "))]
    UnknownFunction {
        /// The name given.
        name: String,
    },
    /// A file name that is not a plain `name.rs`.
    #[error("dynagen: bad output file name \"{0}\" (give a plain file name such as \"ur5.rs\"; use `.out_dir` for the folder)")]
    BadFileName(String),
    /// `OUT_DIR` is not set and [`Builder::out_dir`] was not called.
    #[error("dynagen: OUT_DIR is not set (run from a build script, or call `.out_dir(..)`)")]
    NoOutDir,
    /// The generator failed.
    #[error("dynagen: generating the module for {robot}: {source}")]
    Codegen {
        /// The robot's source.
        robot: String,
        /// Why.
        #[source]
        source: CodegenError,
    },
    /// The output file could not be written.
    #[error("dynagen: cannot write {}: {source}", .path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
}

impl Functions {
    /// The functions named, from the names of the generated-code contract
    /// (`inverse_dynamics`, `mass_matrix`, `bias_forces`, `gravity_torques`,
    /// `forward_dynamics`); an unknown name is given back as the error.
    pub fn from_names<S: AsRef<str>>(names: impl IntoIterator<Item = S>) -> Result<Functions, String> {
        let mut f = Functions {
            inverse_dynamics: false,
            mass_matrix: false,
            bias_forces: false,
            gravity_torques: false,
            forward_dynamics: false,
        };
        for name in names {
            let slot = match name.as_ref().trim() {
                "inverse_dynamics" => &mut f.inverse_dynamics,
                "mass_matrix" => &mut f.mass_matrix,
                "bias_forces" => &mut f.bias_forces,
                "gravity_torques" => &mut f.gravity_torques,
                "forward_dynamics" => &mut f.forward_dynamics,
                other => return Err(other.to_string()),
            };
            *slot = true;
        }
        Ok(f)
    }
}

/// A module name from a robot name: lower case, `_` for anything that is
/// not a letter, digit or `_`, and a leading `_` before a digit.
pub fn module_name(robot: &str) -> String {
    let mut s: String =
        robot.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}

impl Builder {
    /// A builder with the default options ([`CodegenOptions::default`]):
    /// all five functions, `f64`, the module's own sines and cosines
    /// ([`Trig::Batched`](super::Trig::Batched): no std, no dependency), the
    /// forward dynamics chosen as [`ForwardDynamicsMethod::Auto`] says, the
    /// rounding snap on, output into `OUT_DIR`.
    pub fn new() -> Self {
        Self::default()
    }
    /// The robot, from a URDF file (relative paths are relative to the
    /// current directory, which in a build script is the package's root).
    pub fn urdf(mut self, path: impl AsRef<Path>) -> Self {
        self.robot = Some(RobotInput::Urdf(path.as_ref().to_path_buf()));
        self
    }
    /// The robot, as a model built in Rust (e.g. with
    /// [`RobotBuilder`](crate::RobotBuilder)).
    pub fn model(mut self, model: Model) -> Self {
        self.robot = Some(RobotInput::Model(Box::new(model)));
        self
    }
    /// A scene: the module then has only the scene's functions, with
    /// everything it fixes folded in and its run-time inputs as arguments
    /// (see [`generate_scene`](super::generate_scene)). The output file is
    /// named after the scene's name if it has one. [`functions`](Builder::functions)
    /// replaces the scene's functions other than the frame functions;
    /// [`scalar`](Builder::scalar)`(F32)` makes it `f32` whatever the scene
    /// says; the rounding snap, the forward-dynamics method and the
    /// trigonometry (for a std target) come from the builder.
    pub fn scene(mut self, scene: Scene) -> Self {
        self.scene = Some(SceneInput::Scene(Box::new(scene)));
        self
    }
    /// A scene from a TOML file (see [`scene`](crate::scene)); as
    /// [`scene`](Builder::scene). In a build script, cargo reruns it when the
    /// file changes.
    pub fn scene_file(mut self, path: impl AsRef<Path>) -> Self {
        self.scene = Some(SceneInput::File(path.as_ref().to_path_buf()));
        self
    }
    /// Only these functions, by name (`inverse_dynamics`, `mass_matrix`,
    /// `bias_forces`, `gravity_torques`, `forward_dynamics`, `coriolis`);
    /// default all five (or the scene's). `coriolis` is a scene function:
    /// without a scene it makes the module the default scene's.
    pub fn functions<S: AsRef<str>>(mut self, names: &[S]) -> Self {
        self.functions = Some(names.iter().map(|s| s.as_ref().to_string()).collect());
        self
    }
    /// The float type (`f64`).
    pub fn scalar(mut self, scalar: ScalarType) -> Self {
        self.options.scalar = scalar;
        self
    }
    /// The forward-dynamics algorithm emitted (the articulated-body algorithm).
    pub fn forward_dynamics(mut self, method: ForwardDynamicsMethod) -> Self {
        self.options.forward_dynamics = method;
        self
    }
    /// Replace model constants that are 0 or ±1 up to rounding (on); see
    /// [`codegen`](super).
    pub fn snap_rounding(mut self, on: bool) -> Self {
        self.options.snap_rounding = on;
        self
    }
    /// The longest body emitted as one function, in `let`s (`None`: no
    /// limit); longer ones become private parts (default
    /// [`DEFAULT_SPLIT_LETS`](super::DEFAULT_SPLIT_LETS); see
    /// [`CodegenOptions::split_lets`]).
    pub fn split_lets(mut self, lets: Option<usize>) -> Self {
        self.options.split_lets = lets;
        self
    }
    /// Write `a·b ± c` as fused multiply-adds (on); see
    /// [`CodegenOptions::fma`].
    pub fn fma(mut self, on: bool) -> Self {
        self.options.fma = on;
        self
    }
    /// Compile the functions also for AVX2 and FMA, picked at run time on
    /// x86-64 builds without those target features (on); see
    /// [`CodegenOptions::runtime_dispatch`].
    pub fn runtime_dispatch(mut self, on: bool) -> Self {
        self.options.runtime_dispatch = on;
        self
    }
    /// All code-generation options at once (replaces the scalar, forward
    /// dynamics, snap and function choices made so far).
    pub fn options(mut self, options: CodegenOptions) -> Self {
        self.options = options;
        self.functions = None;
        self
    }
    /// The output file's name, `<name>.rs` (default: from the robot's name,
    /// see [`module_name`]).
    pub fn module_name(mut self, name: &str) -> Self {
        self.file_name = Some(format!("{name}.rs"));
        self
    }
    /// The output file's name, e.g. `"ur5_f32.rs"`.
    pub fn file_name(mut self, name: &str) -> Self {
        self.file_name = Some(name.to_string());
        self
    }
    /// The folder to write into (default: the `OUT_DIR` cargo gives a build
    /// script).
    pub fn out_dir(mut self, dir: impl AsRef<Path>) -> Self {
        self.out_dir = Some(dir.as_ref().to_path_buf());
        self
    }
    /// Whether to print `cargo:rerun-if-changed=` for every input file
    /// (default: when `OUT_DIR` is set, i.e. in a build script).
    pub fn cargo_output(mut self, on: bool) -> Self {
        self.cargo_output = Some(on);
        self
    }

    /// What to generate, the options and the input files, without writing
    /// anything.
    fn prepare(&self) -> Result<(Target, CodegenOptions, Option<String>, Vec<PathBuf>), BuildError> {
        let mut inputs = Vec::new();
        let mut options = self.options.clone();
        let model = match &self.robot {
            None => return Err(BuildError::NoRobot),
            Some(RobotInput::Model(m)) => (**m).clone(),
            Some(RobotInput::Urdf(path)) => {
                inputs.push(path.clone());
                if options.source.is_none() {
                    options.source = Some(path.display().to_string());
                }
                Model::from_urdf_file(path).map_err(|source| BuildError::Robot { path: path.clone(), source })?
            }
        };
        // `coriolis` is a scene function: asking for it means the default scene.
        let coriolis = self.functions.as_ref().is_some_and(|f| f.iter().any(|n| n.trim() == "coriolis"));
        let default_scene = SceneInput::Scene(Box::default());
        let scene_input = match &self.scene {
            None if coriolis => Some(&default_scene),
            s => s.as_ref(),
        };
        let Some(input) = scene_input else {
            if let Some(names) = &self.functions {
                options.functions =
                    Functions::from_names(names).map_err(|name| BuildError::UnknownFunction { name })?;
            }
            return Ok((Target::Model(Box::new(model)), options, None, inputs));
        };
        let (mut scene, label) = match input {
            SceneInput::Scene(s) => ((**s).clone(), "(given in Rust)".to_string()),
            SceneInput::File(path) => {
                inputs.push(path.clone());
                let s =
                    Scene::from_toml_file(path).map_err(|source| BuildError::Scene { path: path.clone(), source })?;
                (s, path.display().to_string())
            }
        };
        if let Some(names) = &self.functions {
            let mut functions = Vec::new();
            for name in names {
                let f = SceneFunction::from_name(name.trim())
                    .ok_or_else(|| BuildError::UnknownFunction { name: name.clone() })?;
                functions.push(f);
            }
            functions.extend(
                scene
                    .functions
                    .iter()
                    .filter(|f| matches!(f, SceneFunction::FramePose(_) | SceneFunction::FrameJacobian(_)))
                    .cloned(),
            );
            scene.functions = functions;
        }
        let name = scene.name.clone();
        let applied = scene.apply(&model).map_err(|source| BuildError::SceneRobot {
            scene: label,
            robot: self.robot_label(),
            source: Box::new(source),
        })?;
        Ok((Target::Scene(Box::new(applied)), options, name, inputs))
    }

    /// Generates the module without writing it or printing anything (what
    /// the proc-macros and the `dynagen` command use).
    pub fn generate_module(&self) -> Result<GeneratedModule, BuildError> {
        let (target, options, _, _) = self.prepare()?;
        target.generate(&options).map_err(|source| BuildError::Codegen { robot: self.robot_label(), source })
    }

    fn robot_label(&self) -> String {
        match &self.robot {
            Some(RobotInput::Urdf(p)) => p.display().to_string(),
            Some(RobotInput::Model(m)) => format!("robot \"{}\"", m.name),
            None => "(no robot)".into(),
        }
    }

    /// Generates the module and writes it into the output folder as
    /// `<name>.rs`; in a build script, prints `cargo:rerun-if-changed=` for
    /// the URDF and the scene file. The file is rewritten only when its
    /// content changes.
    pub fn generate(&self) -> Result<GeneratedFile, BuildError> {
        let (target, options, scene_name, inputs) = self.prepare()?;
        let out_env = std::env::var_os("OUT_DIR");
        if self.cargo_output.unwrap_or(out_env.is_some()) {
            for p in &inputs {
                println!("cargo:rerun-if-changed={}", p.display());
            }
        }
        let dir = match (&self.out_dir, out_env) {
            (Some(d), _) => d.clone(),
            (None, Some(d)) => PathBuf::from(d),
            (None, None) => return Err(BuildError::NoOutDir),
        };
        let file = match (&self.file_name, scene_name) {
            (Some(f), _) => f.clone(),
            (None, Some(n)) => format!("{}.rs", module_name(&n)),
            (None, None) => format!("{}.rs", module_name(target.robot_name())),
        };
        if file.contains(['/', '\\']) || !file.ends_with(".rs") || file == ".rs" {
            return Err(BuildError::BadFileName(file));
        }
        let module =
            target.generate(&options).map_err(|source| BuildError::Codegen { robot: self.robot_label(), source })?;
        let path = dir.join(&file);
        let unchanged = std::fs::read(&path).is_ok_and(|old| old == module.source.as_bytes());
        if !unchanged {
            std::fs::create_dir_all(&dir)
                .and_then(|()| std::fs::write(&path, &module.source))
                .map_err(|source| BuildError::Write { path: path.clone(), source })?;
        }
        Ok(GeneratedFile { path, module, inputs })
    }
}

/// What a builder generates: a model's module, or a scene's.
enum Target {
    Model(Box<Model>),
    Scene(Box<SceneModel>),
}

impl Target {
    fn robot_name(&self) -> &str {
        match self {
            Target::Model(m) => &m.name,
            Target::Scene(s) => &s.model.name,
        }
    }
    fn generate(&self, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
        match self {
            Target::Model(m) => generate(m, options),
            Target::Scene(s) => generate_scene(s, options),
        }
    }
}

impl fmt::Display for GeneratedFile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())
    }
}
