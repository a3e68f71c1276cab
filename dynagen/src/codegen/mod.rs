//! Code generation: a robot → a Rust module with its dynamics unrolled.
//!
//! One pipeline, a folder a stage (`docs/architecture.md` has the map and
//! where to add a function):
//!
//! 1. `prepare/`: the model's constants snapped ([`snap_rounding`]) and its
//!    inertias regrouped ([`regroup_inertia`]), exact within the file's
//!    precision;
//! 2. `trace/`: each asked [`Function`] run on the symbolic scalar through
//!    the generic algorithms ([`trace()`]), the forward dynamics both ways
//!    and one kept ([`fd_choice`]), the sines and cosines made inputs
//!    ([`sin_cos_inputs`]);
//! 3. `emit/`: one `NAME_sc` body and one `NAME` wrapper a function, the
//!    header, the sine and cosine kernel ([`sin_cos_array`]);
//! 4. the front doors: [`generate`] and [`generate_scene`], the build
//!    script's [`Builder`], the macros and the command line on top of it.
//!
//! A plain module is the default scene's: [`generate`] applies
//! `Scene::default()` and runs [`generate_scene`]. What to model (the
//! physics) is a `Scene`'s; what code to write, [`CodegenOptions`]'. The
//! same model and options give a byte-identical file.
//!
//! ```
//! use dynagen::codegen::{generate, CodegenOptions};
//! use dynagen::model::{Inertial, JointDescription, RobotBuilder};
//! let model = RobotBuilder::new("pendulum")
//!     .link("base", None)
//!     .link("arm", Some(Inertial::point_mass(1.0, [0.0, 0.0, -1.0])))
//!     .joint(JointDescription::revolute("hinge", "base", "arm", [0.0, 1.0, 0.0]))
//!     .build()
//!     .unwrap();
//! let module = generate(&model, &CodegenOptions::default()).unwrap();
//! assert!(module.source.contains("pub fn gravity_torques(q: &[f64; DOF]) -> [f64; DOF]"));
//! ```

mod builder;
mod emit;
mod function;
mod module;
mod options;
mod prepare;
mod sin_cos;
mod trace;

pub use builder::{module_name, BuildError, Builder, GeneratedFile};
pub use emit::{float_literal_text, payload_argument};
pub use function::Function;
pub use module::{GeneratedFunction, GeneratedModule};
pub use options::{CodegenOptions, ForwardDynamicsMethod, ScalarType, Trig, DEFAULT_SPLIT_LETS};
pub use prepare::{
    canonical_text, center_prismatic_leaves, fnv1a64, model_hash, regroup_inertia, slide_origins_along_axes,
    snap_rounding, SnappedConstant, ROUNDING_TOLERANCE,
};
#[doc(hidden)]
pub use sin_cos::kernel_internals;
pub use sin_cos::{sin_cos_array, sin_cos_array_f32, sin_cos_batch, sin_cos_kernel, sin_cos_kernel_f32};
pub use trace::{fd_choice, generic_op_count, sin_cos_from_q, sin_cos_inputs, trace, SinCosTrace};

use crate::model::Model;
use crate::scene::{Scene, SceneError, SceneModel};
use crate::symbolic::{OpCount, Traced};

/// The generator's version, written into every header.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Why a module could not be generated.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum CodegenError {
    /// A constant folded to NaN or an infinity, which has no literal.
    #[error("function {function}: a constant folded to {value}, which Rust cannot write as a literal")]
    NonFiniteConstant {
        /// The function.
        function: String,
        /// The value.
        value: f64,
    },
    /// A symbolic trace was already running on this thread.
    #[error(transparent)]
    TraceActive(#[from] crate::symbolic::TraceActive),
    /// Two functions (or two payload arguments) get the same Rust name (two
    /// frames or links whose names differ only in characters a Rust name
    /// cannot hold).
    #[error("two functions or arguments would be named `{0}` (frame or link names that differ only in characters Rust names cannot hold)")]
    DuplicateName(String),
    /// A name that becomes part of an identifier (a frame function's, a
    /// payload argument's) did not give a Rust identifier.
    #[error("{item} gives the Rust name `{name}`, which is not an identifier (or is a keyword): rename it")]
    BadIdentifier {
        /// The identifier made.
        name: String,
        /// What it was made from, as `frame "name"` or `link "name"`.
        item: String,
    },
    /// No function was asked for.
    #[error("no function to generate: ask for at least one")]
    NoFunctions,
    /// The scene does not fit the model, or a frame function names a frame
    /// the (reduced) model does not have.
    #[error(transparent)]
    Scene(Box<SceneError>),
    /// A function or scene that code generation does not support for this
    /// model yet (it names them).
    #[error("{0}")]
    Unsupported(String),
    /// Forward dynamics asked for a model whose joints are dependent.
    #[error(
        "forward_dynamics cannot be generated: joints {} are dependent (together they move without moving any mass, so the mass matrix is singular at every configuration); leave forward_dynamics out of the functions, or make the joints independent",
        crate::model::quoted_names(.0)
    )]
    DependentJoints(Vec<String>),
    /// The generated tokens did not parse as a Rust file (a bug of dynagen).
    #[error("internal error: generated code does not parse: {0}")]
    Internal(String),
}

debug_as_display!(CodegenError);

/// The operation count of `f`, with its fused multiply-adds if `fma`.
pub(crate) fn counted(f: &Traced, fma: bool) -> OpCount {
    if fma {
        f.fusion().op_count(f)
    } else {
        f.op_count()
    }
}

/// Generates the module of `model`: the default scene's
/// ([`generate_scene`]).
pub fn generate(model: &Model, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
    let scene = Scene::default().apply(model).map_err(|e| CodegenError::Scene(Box::new(e)))?;
    generate_scene(&scene, options)
}

/// Generates the module of an applied scene: the functions `options` ask
/// for, everything the scene fixes folded in, its run-time inputs (gravity,
/// tip wrench, payloads; see [`Function`]'s arguments) after the state
/// vectors.
///
/// ```
/// use dynagen::codegen::{generate_scene, CodegenOptions, Function};
/// use dynagen::scene::{Gravity, Scene};
/// let ur5 = dynagen::Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap();
/// let scene = Scene::new().gravity(Gravity::None).tip_wrench("ee_link");
/// let options = CodegenOptions::default().functions([Function::InverseDynamics]);
/// let module = generate_scene(&scene.apply(&ur5).unwrap(), &options).unwrap();
/// assert!(module.source.contains("f_tip: &[f64; 6]"));
/// assert!(!module.source.contains("fn mass_matrix"));
/// assert!(module.source.contains("//   functions not generated: mass_matrix, bias_forces"));
/// ```
pub fn generate_scene(scene: &SceneModel, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
    if options.functions.is_empty() {
        return Err(CodegenError::NoFunctions);
    }
    let mut names = std::collections::HashSet::new();
    for f in &options.functions {
        if let Some(frame) = f.frame() {
            scene.frame(f.name(), frame).map_err(|e| CodegenError::Scene(Box::new(e)))?;
            emit::identifier(&f.rust_name(), &format!("frame \"{frame}\""))?;
        }
        if !names.insert(f.rust_name()) {
            return Err(CodegenError::DuplicateName(f.rust_name()));
        }
    }
    let mut arguments = std::collections::HashSet::new();
    for p in &scene.input_payloads {
        let argument = payload_argument(&p.link);
        emit::identifier(&argument, &format!("link \"{}\" (its payload input)", p.link))?;
        if !arguments.insert(argument.clone()) {
            return Err(CodegenError::DuplicateName(argument));
        }
    }
    if options.functions.contains(&Function::ForwardDynamics) {
        if let Some(joints) = scene.model.dependent_joints().first() {
            return Err(CodegenError::DependentJoints(joints.to_vec()));
        }
    }
    let (prepared, snapped) = prepare::prepare(scene, options);
    let (functions, fd) = trace::trace_module(&prepared, options)?;
    let hash = model_hash(&scene.model);
    let parts = emit::ModuleParts {
        scene,
        prepared: &prepared,
        options,
        functions: &functions,
        fd: &fd,
        snapped: &snapped,
        hash,
    };
    let source = emit::module_source(&parts)?;
    Ok(GeneratedModule { source, functions, snapped, model_hash: hash })
}
