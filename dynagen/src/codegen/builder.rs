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
//! `#![...]`), so it can be `include!`d inside a `mod` block, and every item
//! is `#[allow(dead_code)]`, so a crate that calls one of its functions
//! compiles without a warning about the others. With the default options it
//! uses neither std nor any crate, so it also compiles in a `#![no_std]`
//! crate. [`Builder`] says how the file is named and how a renamed output
//! never leaves a stale file behind.

use super::{
    generate_scene, CodegenError, CodegenOptions, ForwardDynamicsMethod, Function, GeneratedModule, ScalarType, Trig,
};
use crate::model::{Model, ModelError};
use crate::scene::{Scene, SceneError, SceneFile};
use crate::symbolic::Rewrites;
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

/// One option set on the builder: applied over the [`options`](Builder::options)
/// and a scene file's code keys, in the order the setters were called.
#[derive(Clone, Debug)]
enum Setting {
    Name(String),
    Functions(Vec<String>),
    Scalar(ScalarType),
    ForwardDynamics(ForwardDynamicsMethod),
    SnapRounding(bool),
    RegroupInertia(bool),
    Rewrites(Rewrites),
    Trig(Trig),
    SplitLets(Option<usize>),
    Fma(bool),
    RuntimeDispatch(bool),
    BranchLoops(bool),
    Source(String),
}

impl Setting {
    fn apply(&self, mut o: CodegenOptions) -> Result<CodegenOptions, BuildError> {
        match self.clone() {
            Setting::Name(n) => o.name = Some(n),
            Setting::Functions(names) => {
                // The names replace the functions without a frame; frame
                // functions (a scene file's) stay unless named too.
                let mut list = Vec::new();
                for name in &names {
                    let f: Function = name.parse().map_err(|_| BuildError::UnknownFunction { name: name.clone() })?;
                    list.push(f);
                }
                let frames = o.functions.iter().filter(|f| f.frame().is_some());
                list.extend(frames.cloned().collect::<Vec<_>>());
                o = o.functions(list);
            }
            Setting::Scalar(x) => o.scalar = x,
            Setting::ForwardDynamics(x) => o.forward_dynamics = x,
            Setting::SnapRounding(x) => o.snap_rounding = x,
            Setting::RegroupInertia(x) => o.regroup_inertia = x,
            Setting::Rewrites(x) => o.rewrites = x,
            Setting::Trig(x) => o.trig = x,
            Setting::SplitLets(x) => o.split_lets = x,
            Setting::Fma(x) => o.fma = x,
            Setting::RuntimeDispatch(x) => o.runtime_dispatch = x,
            Setting::BranchLoops(x) => o.branch_loops = x,
            Setting::Source(x) => o.source = Some(x),
        }
        Ok(o)
    }
}

/// Generates a robot's dynamics module from a build script, in the manner
/// of `prost-build`: chained options, then one [`generate`](Builder::generate)
/// that writes `<name>.rs` into `OUT_DIR` and tells cargo to rerun the build
/// script when an input file changes.
///
/// # The output's name, and no stale file
///
/// The file is named, in this order, by [`Builder::file_name`] or
/// [`Builder::module_name`], by the module's name ([`Builder::name`] or a
/// scene file's `name`), by the URDF file's name (`robots/ur5.urdf` →
/// `ur5.rs`), or for a [model](Builder::model) by its name: never by the
/// `<robot name>` inside a file, which a new version of the file may change.
///
/// In cargo's `OUT_DIR`, the Builder records what it writes
/// (`OUT_DIR/dynagen-outputs.txt`) and moves what an earlier run of the
/// build script wrote out of the way (into `OUT_DIR/dynagen-previous/`; a
/// file written again with the same content comes back unchanged): after a
/// rename, an `include!` of the old name is a compile error ("couldn't read
/// …/ur5.rs"), never the old dynamics. In a folder given by
/// [`Builder::out_dir`] other than `OUT_DIR`, only the file written changes.
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
    options: CodegenOptions,
    settings: Vec<Setting>,
    floating_base: bool,
    file_name: Option<String>,
    out_dir: Option<PathBuf>,
    cargo_output: Option<bool>,
    model_options: crate::model::BuildOptions,
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
#[derive(thiserror::Error)]
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
    /// A function name that is not one of [`Function::NAMES`] (or
    /// `KIND:FRAME` with a kind of [`Function::FRAME_KINDS`]).
    #[error("dynagen: unknown function \"{name}\" (the functions are {})", Function::all_names())]
    UnknownFunction {
        /// The name given.
        name: String,
    },
    /// A file name that is not a plain `name.rs` (a folder, a control
    /// character).
    #[error("dynagen: bad output file name {0:?} (give a plain file name such as \"ur5.rs\"; use `.out_dir` for the folder)")]
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

debug_as_display!(BuildError);

/// The file, in the output folder, in which the Builders of a build script
/// record what they wrote (in cargo's `OUT_DIR` only).
pub(crate) const OUTPUTS_FILE: &str = "dynagen-outputs.txt";

/// This process's run: what tells the files one run of a build script wrote
/// from those of its earlier runs (each run is a new process).
fn this_run() -> &'static str {
    static RUN: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    RUN.get_or_init(|| {
        let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos());
        format!("{}-{nanos}", std::process::id())
    })
}

/// Where the files of earlier runs go (out of the way of `include!`): a
/// file this run writes with the same content comes back from there with
/// its modification time, so cargo sees it unchanged.
const PREVIOUS_DIR: &str = "dynagen-previous";

/// The plain `.rs` file names an earlier run recorded in `dir`, moved to
/// [`PREVIOUS_DIR`]; this run's records kept.
fn retire_earlier_runs(dir: &Path) -> Result<(), BuildError> {
    let manifest = dir.join(OUTPUTS_FILE);
    let Ok(old) = std::fs::read_to_string(&manifest) else { return Ok(()) };
    let run = this_run();
    let mut kept = String::new();
    for (r, f) in old.lines().filter_map(|l| l.split_once('\t')) {
        if r == run {
            kept.push_str(&format!("{r}\t{f}\n"));
            continue;
        }
        // Only plain `.rs` names, as `record_output` writes them.
        let path = dir.join(f);
        if f.contains(['/', '\\']) || !f.ends_with(".rs") || !path.is_file() {
            continue;
        }
        let previous = dir.join(PREVIOUS_DIR);
        std::fs::create_dir_all(&previous)
            .and_then(|()| std::fs::rename(&path, previous.join(f)))
            .map_err(|source| BuildError::Write { path, source })?;
    }
    if kept != old {
        std::fs::write(&manifest, kept).map_err(|source| BuildError::Write { path: manifest, source })?;
    }
    Ok(())
}

/// Records `file` as written in `dir` by this run.
fn record_output(dir: &Path, file: &str) -> Result<(), BuildError> {
    let manifest = dir.join(OUTPUTS_FILE);
    let mut text = std::fs::read_to_string(&manifest).unwrap_or_default();
    let line = format!("{}\t{file}\n", this_run());
    if !text.contains(&line) {
        text.push_str(&line);
        std::fs::write(&manifest, text).map_err(|source| BuildError::Write { path: manifest, source })?;
    }
    Ok(())
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
    /// Give the robot a floating root (`Model::with_floating_base`): its
    /// root link moves freely; the module then has `NQ = DOF + 7`,
    /// `NV = DOF + 6` and takes `q: &[f64; NQ]` (see the crate's
    /// conventions). A URDF whose root joint is `floating` has one anyway.
    pub fn floating_base(mut self, on: bool) -> Self {
        self.floating_base = on;
        self
    }
    /// A scene: the physics to model (see [`generate_scene`]); a plain
    /// module is the default scene's.
    pub fn scene(mut self, scene: Scene) -> Self {
        self.scene = Some(SceneInput::Scene(Box::new(scene)));
        self
    }
    /// A scene from a TOML file (see [`scene`](crate::scene)): its physics,
    /// and its code keys (`name`, `functions`, `frame_pose`,
    /// `frame_jacobian`, `scalar`, `target`) over [`options`](Builder::options),
    /// under every other setter. In a build script, cargo reruns it when
    /// the file changes.
    pub fn scene_file(mut self, path: impl AsRef<Path>) -> Self {
        self.scene = Some(SceneInput::File(path.as_ref().to_path_buf()));
        self
    }
    /// Every code-generation option at once, as the base that a scene
    /// file's keys and this builder's other setters (before or after this
    /// call) change.
    pub fn options(mut self, options: CodegenOptions) -> Self {
        self.options = options;
        self
    }
    fn set(mut self, setting: Setting) -> Self {
        self.settings.push(setting);
        self
    }
    /// The module's name ([`CodegenOptions::name`]): the header's, and the
    /// output file's `<name>.rs` unless [`file_name`](Builder::file_name)
    /// says otherwise.
    pub fn name(self, name: &str) -> Self {
        self.set(Setting::Name(name.to_string()))
    }
    /// Only these functions, by name (`inverse_dynamics`, `mass_matrix`,
    /// `bias_forces`, `gravity_torques`, `coriolis`, `forward_dynamics`,
    /// `inverse_dynamics_derivatives`, `forward_dynamics_derivatives`,
    /// `mass_matrix_inverse`, `frame_pose:FRAME`, `frame_jacobian:FRAME`,
    /// `frame_world_jacobian:FRAME`, `frame_acceleration_bias:FRAME`);
    /// default the five of the
    /// contract. A scene file's frame functions stay.
    pub fn functions<S: AsRef<str>>(self, names: &[S]) -> Self {
        self.set(Setting::Functions(names.iter().map(|s| s.as_ref().to_string()).collect()))
    }
    /// The float type ([`CodegenOptions::scalar`], `f64`).
    pub fn scalar(self, scalar: ScalarType) -> Self {
        self.set(Setting::Scalar(scalar))
    }
    /// The forward-dynamics algorithm ([`CodegenOptions::forward_dynamics`]).
    pub fn forward_dynamics(self, method: ForwardDynamicsMethod) -> Self {
        self.set(Setting::ForwardDynamics(method))
    }
    /// Where the sines and cosines come from ([`CodegenOptions::trig`]).
    pub fn trig(self, trig: Trig) -> Self {
        self.set(Setting::Trig(trig))
    }
    /// Accept URDF links whose rotational inertia is not positive
    /// semi-definite, each with a warning (off: they are refused; see
    /// [`BuildOptions::allow_nonphysical_inertia`](crate::model::BuildOptions::allow_nonphysical_inertia)).
    pub fn allow_nonphysical_inertia(mut self, allow: bool) -> Self {
        self.model_options.allow_nonphysical_inertia = allow;
        self
    }
    /// Whether URDF joints with a `<mimic>` element follow their master
    /// ([`MimicJoints::Follow`](crate::model::MimicJoints::Follow), the
    /// default: `DOF` and `JOINT_NAMES` are the other joints) or are
    /// independent joints ([`MimicJoints::Independent`](crate::model::MimicJoints::Independent)).
    pub fn mimic_joints(mut self, mimic: crate::model::MimicJoints) -> Self {
        self.model_options.mimic = mimic;
        self
    }
    /// Replace model constants that are 0 or ±1 up to rounding
    /// ([`CodegenOptions::snap_rounding`], on).
    pub fn snap_rounding(self, on: bool) -> Self {
        self.set(Setting::SnapRounding(on))
    }
    /// Move the inertia a joint cannot move to its parent
    /// ([`CodegenOptions::regroup_inertia`], on).
    pub fn regroup_inertia(self, on: bool) -> Self {
        self.set(Setting::RegroupInertia(on))
    }
    /// The value-changing graph rewrites ([`CodegenOptions::rewrites`]).
    pub fn rewrites(self, rewrites: Rewrites) -> Self {
        self.set(Setting::Rewrites(rewrites))
    }
    /// The longest body emitted as one function, in `let`s
    /// ([`CodegenOptions::split_lets`]).
    pub fn split_lets(self, lets: Option<usize>) -> Self {
        self.set(Setting::SplitLets(lets))
    }
    /// Write `a·b ± c` as fused multiply-adds ([`CodegenOptions::fma`], on).
    pub fn fma(self, on: bool) -> Self {
        self.set(Setting::Fma(on))
    }
    /// Compile the functions also for AVX-512 and for AVX2 and FMA, picked
    /// at run time ([`CodegenOptions::runtime_dispatch`], on).
    pub fn runtime_dispatch(self, on: bool) -> Self {
        self.set(Setting::RuntimeDispatch(on))
    }
    /// Emit branches of one shape as one body run on all of them
    /// ([`CodegenOptions::branch_loops`], on).
    pub fn branch_loops(self, on: bool) -> Self {
        self.set(Setting::BranchLoops(on))
    }
    /// The model's source for the header ([`CodegenOptions::source`];
    /// default: the URDF's path).
    pub fn source(self, source: &str) -> Self {
        self.set(Setting::Source(source.to_string()))
    }
    /// The output file's name, `<name>.rs` (default: the module's name, else
    /// the URDF file's, see [`Builder`]).
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

    /// The applied scene, the options and the input files, without writing
    /// anything.
    fn prepare(&self) -> Result<(crate::scene::SceneModel, CodegenOptions, Vec<PathBuf>), BuildError> {
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
                Model::from_urdf_file_with(path, &self.model_options)
                    .map_err(|source| BuildError::Robot { path: path.clone(), source })?
            }
        };
        let model = if self.floating_base { model.with_floating_base() } else { model };
        let (scene, label) = match &self.scene {
            None => (Scene::default(), "(default)".to_string()),
            Some(SceneInput::Scene(s)) => ((**s).clone(), "(given in Rust)".to_string()),
            Some(SceneInput::File(path)) => {
                inputs.push(path.clone());
                let file = SceneFile::from_toml_file(path)
                    .map_err(|source| BuildError::Scene { path: path.clone(), source })?;
                options = file.code.apply(options);
                (file.scene, path.display().to_string())
            }
        };
        for s in &self.settings {
            options = s.apply(options)?;
        }
        let applied = scene.apply(&model).map_err(|source| BuildError::SceneRobot {
            scene: label,
            robot: self.robot_label(),
            source: Box::new(source),
        })?;
        Ok((applied, options, inputs))
    }

    /// Generates the module without writing it or printing anything (what
    /// the proc-macros and the `dynagen` command use).
    pub fn generate_module(&self) -> Result<GeneratedModule, BuildError> {
        let (scene, options, _) = self.prepare()?;
        generate_scene(&scene, &options).map_err(|source| BuildError::Codegen { robot: self.robot_label(), source })
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
    /// content changes. In cargo's `OUT_DIR`, moves away the files earlier
    /// runs of the build script wrote (see [`Builder`]).
    pub fn generate(&self) -> Result<GeneratedFile, BuildError> {
        let (scene, options, inputs) = self.prepare()?;
        let out_env = std::env::var_os("OUT_DIR");
        if self.cargo_output.unwrap_or(out_env.is_some()) {
            for p in &inputs {
                println!("cargo:rerun-if-changed={}", p.display());
            }
            for w in scene.model.warnings.iter().filter(|w| w.is_about_the_dynamics()) {
                println!("cargo:warning={}", w.one_line());
            }
        }
        let cargo_out_dir = match (&self.out_dir, &out_env) {
            (Some(d), Some(o)) => d == Path::new(o),
            (None, Some(_)) => true,
            (_, None) => false,
        };
        let dir = match (&self.out_dir, out_env) {
            (Some(d), _) => d.clone(),
            (None, Some(d)) => PathBuf::from(d),
            (None, None) => return Err(BuildError::NoOutDir),
        };
        let file = match (&self.file_name, &options.name, &self.robot) {
            (Some(f), _, _) => f.clone(),
            (None, Some(n), _) => format!("{}.rs", module_name(n)),
            (None, None, Some(RobotInput::Urdf(p))) => {
                let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
                format!("{}.rs", module_name(&stem))
            }
            (None, None, _) => format!("{}.rs", module_name(&scene.model.name)),
        };
        if file.contains(['/', '\\']) || !file.ends_with(".rs") || file == ".rs" || file.contains(char::is_control) {
            return Err(BuildError::BadFileName(file));
        }
        let module = generate_scene(&scene, &options)
            .map_err(|source| BuildError::Codegen { robot: self.robot_label(), source })?;
        let path = dir.join(&file);
        if cargo_out_dir {
            retire_earlier_runs(&dir)?;
            let previous = dir.join(PREVIOUS_DIR).join(&file);
            if std::fs::read(&previous).is_ok_and(|old| old == module.source.as_bytes()) {
                std::fs::rename(&previous, &path).map_err(|source| BuildError::Write { path: path.clone(), source })?;
            }
        }
        let unchanged = std::fs::read(&path).is_ok_and(|old| old == module.source.as_bytes());
        if !unchanged {
            std::fs::create_dir_all(&dir)
                .and_then(|()| std::fs::write(&path, &module.source))
                .map_err(|source| BuildError::Write { path: path.clone(), source })?;
        }
        if cargo_out_dir {
            record_output(&dir, &file)?;
        }
        Ok(GeneratedFile { path, module, inputs })
    }
}

impl fmt::Display for GeneratedFile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())
    }
}
