//! Code generation: a model → a Rust module with its dynamics unrolled.
//!
//! [`generate`] traces each function of the generated-code contract
//! (DESIGN.md) by running the generic algorithm on the symbolic scalar
//! ([`crate::symbolic`]), keeps what the outputs reach, factors it
//! ([`crate::symbolic::factor`]), and prints one `let`
//! per kept operation with `quote`, formatted by `prettyplease`. The result
//! ([`GeneratedModule::source`]) is a file of items to `include!` in a
//! module: `DOF`, `JOINT_NAMES`, `inverse_dynamics`, `mass_matrix`,
//! `bias_forces`, `gravity_torques`, `forward_dynamics`, each also as
//! `NAME_sc`, which takes the sines and cosines of the joint angles instead
//! of computing them (the one body; `NAME` computes them and calls it), and
//! `sin_cos_all`, a batched sine and cosine without std ([`sin_cos_array`]).
//! Where `NAME` gets its sines and cosines is [`Trig`]: the module's
//! `sin_cos_array` (of only the angles the body reads; the default, see
//! [`Trig`] for why), std's `sin_cos`, the `libm` crate, or nobody (only the
//! `NAME_sc` functions). With the default, the module is `#![no_std]` and
//! has no dependency. The same model and options give a byte-identical
//! file.
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
//!
//! # Fused multiply-adds
//!
//! With [`CodegenOptions::fma`] (on by default) the bodies write the sums
//! that [`Fusion`](crate::symbolic::Fusion) picks as `fma(a, b, c)`
//! (`fmaf` in `f32` modules): `a·b + c`, `a·b − c` as `fma(a, b, -c)`,
//! `c − a·b` as `fma(-a, b, c)`, and a product that only such sums read is
//! not computed on its own. `fma` is a module-local `#[inline(always)]`
//! function: one fused multiply-add instruction (a single rounding) where
//! the target has one, i.e. x86-64 compiled with the `fma` target feature
//! (`-C target-cpu=native` on a machine that has it, or `-C
//! target-feature=+fma`) and aarch64, through `core::arch` (no std), and
//! `a * b + c` elsewhere, which rounds exactly as the unfused expression
//! did: a default x86-64 build gives the same bits as before (unless the
//! run-time dispatch below picks its AVX2 and FMA copy). The header
//! says so and counts the fused operations (the [`OpCount`] totals stay
//! those of the traced operations; [`OpCount::fp_ops`] counts each fused
//! one once).
//!
//! # Run-time dispatch
//!
//! A default x86-64 build (`cargo build` without `RUSTFLAGS`) targets SSE2:
//! no fused multiply-add, two angles to a vector register. With
//! [`CodegenOptions::runtime_dispatch`] (on by default) every public
//! function of the module — `NAME`, `NAME_sc`, `sin_cos_all`, the kernel's
//! `sin_cos_array`, `sin_cos_kernel` (and their `f32` versions), scene
//! functions — is written once, generic over the instructions it is compiled
//! for (`NAME_on<I: Isa>`, `#[inline(always)]`, its sums `I::fma(a, b, c)`),
//! and instantiated twice on x86-64 builds without the `avx2` and `fma`
//! target features: for `Baseline` (the build's own target, the code a
//! module without dispatch has) in `NAME`, and for `Avx2Fma` in
//! `NAME_avx2_fma`, an `unsafe fn` with `#[target_feature(enable =
//! "avx2,fma")]` that `NAME` calls when the processor has AVX2 and FMA and
//! the OS saves the 256-bit registers (`cpuid` leaves 1 and 7 and `xgetbv`,
//! asked once and kept in an atomic: `core::arch` only, so the module stays
//! `#![no_std]` and without dependencies). With batched trigonometry,
//! `NAME_avx2_fma` inlines the kernel and the body (`NAME_sc_on::<Avx2Fma>`),
//! so that the sines and cosines stay in registers as in a native build. A
//! body split into parts is dispatched part by part. Builds that have both features, and other
//! targets, compile `Baseline` alone: the same code as with the option off.
//! The AVX2 and FMA copy gives the bits of a build with those features
//! (`tests/tests/generated_fma.rs` checks it bit for bit), so a default
//! build's results differ in the last bits between processors with and
//! without FMA; off, they are the same on every x86-64 machine.
//!
//! # Constants that are 0 or ±1 up to rounding
//!
//! A robot file that turns a frame by `rpy="0 1.5707963267948966 0"` means
//! a quarter turn, but `cos(1.5707963267948966)` is `6.1e-17` in `f64`, not
//! 0, and every product with it would survive into the generated code as an
//! operation. With [`CodegenOptions::snap_rounding`] (on by default) the
//! generator first replaces, in a copy of the model, every constant within
//! [`ROUNDING_TOLERANCE`] (4 ulps) *times the scale of the quantity it
//! belongs to* of 0, or (rotation entries and unit axes) of ±1, by that
//! value:
//!
//! - rotation entries and unit-axis components: scale 1 (both are entries
//!   of unit vectors);
//! - translations, first moments of mass `m·c`, axes as given, gravity:
//!   the vector's norm;
//! - rotational inertias: the sum of the diagonal's magnitudes.
//!
//! Why this tolerance: each of these constants was itself computed in `f64`
//! (from rpy angles, a normalisation, an inertia rotation and shift), which
//! already put rounding errors of a few ulps of the quantity's scale in it.
//! A change of that size is below what the file's own numbers determine
//! after parsing, and it changes the generated results by no more than the
//! generic solver's own rounding (the tests compare at 1e-12). A larger
//! tolerance would need the precision the file printed, which the model no
//! longer knows, and a file's number is taken at its word: `1.570796325`
//! (the ur_description UR5's quarter turn) is 1.8e-9 rad away from π/2,
//! more than its nine printed decimals allow for, so its `cos` of `1.8e-9`
//! stays. Masses are never changed. What was replaced is listed in
//! [`GeneratedModule::snapped`] and counted in the header.

mod builder;
mod emit;
pub mod fd_choice;
mod generic_count;
mod grouping;
mod hash;
mod leaves;
mod literal;
mod mass_matrix;
mod rounding;
mod scene;
mod sin_cos;
mod split;
mod trace;

pub use builder::{module_name, BuildError, Builder, GeneratedFile};
pub use generic_count::generic_op_count;
pub use grouping::{center_prismatic_leaves, regroup_inertia, slide_origins_along_axes};
pub use hash::{canonical_text, fnv1a64, model_hash};
pub use literal::float_literal_text;
pub use rounding::{snap_rounding, SnappedConstant, ROUNDING_TOLERANCE};
pub use scene::{generate_scene, payload_argument, scene_function_name, trace_scene, SceneFunction};
#[doc(hidden)]
pub use sin_cos::kernel_internals;
pub use sin_cos::{sin_cos_array, sin_cos_array_f32, sin_cos_batch, sin_cos_kernel, sin_cos_kernel_f32};
pub use trace::{sin_cos_from_q, sin_cos_inputs, trace, trace_sin_cos_inputs, FunctionKind, SinCosTrace};

use crate::model::Model;
use crate::symbolic::{Function, OpCount, Rewrites};
use quote::quote;
use std::fmt::Write;

/// The names of the functions a module can have, in the order it lists them.
pub const FUNCTION_NAMES: [&str; 5] =
    ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"];

/// The generator's version, written into every header.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The float type of the generated code (one type with the scene's).
pub use crate::scene::ScalarType;

/// How the generated `forward_dynamics` computes q̈.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ForwardDynamicsMethod {
    /// Whichever of the two is faster without being less accurate, measured
    /// on the model when the module is generated (see [`fd_choice`]); a
    /// scene's module keeps the articulated-body algorithm.
    #[default]
    Auto,
    /// The articulated-body algorithm: the accurate one on long chains.
    Aba,
    /// M by CRBA, h by RNEA, then a sparse LᵀDL solve.
    Ldlt,
}

/// Where the generated code gets the sines and cosines of the joint
/// angles from.
///
/// Every function has one body, `NAME_sc(s, c, [q,] …)`, which reads the
/// sine `s[i]` and cosine `c[i]` of each joint's angle θᵢ = `q[i]` (times
/// `|axis|` when a revolute joint's axis is not a unit vector; the entries
/// of prismatic joints are not read) and takes `q` only when the model has
/// a prismatic joint. Except with [`Trig::Inputs`], the module also has the
/// contract's `NAME(q, …)`, which computes the sines and cosines and calls
/// `NAME_sc`. Every module has `sin_cos_all(q)`, the batched sine and
/// cosine of [`sin_cos_array`] (no std, no dependency, within 1 ulp).
///
/// Why `Batched` is the default:
///
/// - **Speed.** Whole generated functions, sines and cosines included, run
///   1.1x–1.8x faster than with std's `sin_cos` on the two machines
///   measured (`cargo run --release -p dynagen-bench --example interleaved
///   300`): on an AMD EPYC (Zen 5), the UR5's inverse dynamics in 32.2 ns
///   against 52.7 ns, the Panda's in 59.8 ns against 96.3 ns; on an Intel
///   Xeon, 1.1x–1.5x (`benches/README.md`, run 11, whose slower batched M
///   was the benchmark copying the returned matrix).
/// - **Accuracy.** Within 1 ulp for every finite angle: at most 0.73 ulp
///   measured on the tests' angles, std's `sin_cos` 0.56 ulp (the bodies'
///   own rounding is far larger; the tests hold both to 1e-12 of the
///   generic solver).
/// - **No std, no dependency.** The default module is then `#![no_std]`
///   and depends on nothing (a scene's square roots too: the module's own,
///   correctly rounded `sqrt`), which is what a module vendored into a
///   real-time controller needs.
///
/// [`Trig::Std`] remains an option (`--trig std`, the macros' `trig =
/// std`), for code that wants the platform's `sin_cos`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Trig {
    /// `NAME(q, …)` calls `f64::sin_cos` (or `f32::sin_cos`) per joint, and
    /// a scene's square roots are `f64::sqrt`: needs std.
    Std,
    /// `NAME(q, …)` calls the module's `sin_cos_array` on the angles its
    /// body reads, and a scene's square roots are the module's `sqrt`
    /// (`sqrtf`): `#![no_std]`, no dependency, faster than `Std` in the
    /// benchmarks. The default.
    #[default]
    Batched,
    /// `NAME(q, …)` calls `libm::sincos` (`libm::sincosf` for `f32`), and a
    /// scene's square roots are `libm::sqrt` (`sqrtf`): `#![no_std]`, needs
    /// the `libm` crate.
    Libm,
    /// Only the `NAME_sc` functions (and `sin_cos_all`), a scene's square
    /// roots the module's `sqrt`: `#![no_std]`, no dependency; the caller
    /// brings the sines and cosines.
    Inputs,
}

impl Trig {
    /// The trigonometry of a scene's module whose target is `target`, with
    /// the options' `trig`: `Std` allows std without asking for it, so it
    /// takes `trig` ([`Trig::Batched`] by default); `NoStdLibm` is
    /// [`Trig::Libm`] and `NoStdSinCos` [`Trig::Inputs`], whatever `trig` is.
    pub fn for_target(target: crate::scene::Target, trig: Trig) -> Trig {
        match target {
            crate::scene::Target::Std => trig,
            crate::scene::Target::NoStdLibm => Trig::Libm,
            crate::scene::Target::NoStdSinCos => Trig::Inputs,
        }
    }
    /// Whether the module needs std (only [`Trig::Std`] does).
    pub fn needs_std(self) -> bool {
        self == Trig::Std
    }
}

/// Which functions to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Functions {
    /// `inverse_dynamics(q, qd, qdd)`.
    pub inverse_dynamics: bool,
    /// `mass_matrix(q)`.
    pub mass_matrix: bool,
    /// `bias_forces(q, qd)`.
    pub bias_forces: bool,
    /// `gravity_torques(q)`.
    pub gravity_torques: bool,
    /// `forward_dynamics(q, qd, tau)`.
    pub forward_dynamics: bool,
}

impl Default for Functions {
    /// All five.
    fn default() -> Self {
        Functions {
            inverse_dynamics: true,
            mass_matrix: true,
            bias_forces: true,
            gravity_torques: true,
            forward_dynamics: true,
        }
    }
}

/// What to generate and how. Every field has a chained setter, so a
/// build-script builder or a macro can fill it in one expression.
#[derive(Clone, Debug, PartialEq)]
pub struct CodegenOptions {
    /// The float type of the output (`f64`).
    pub scalar: ScalarType,
    /// Which functions (all five).
    pub functions: Functions,
    /// The forward-dynamics algorithm emitted (the faster one that is as
    /// accurate, [`ForwardDynamicsMethod::Auto`]); both are traced and
    /// counted in the header.
    pub forward_dynamics: ForwardDynamicsMethod,
    /// Replace constants that are 0 or ±1 up to rounding (on); see the
    /// [module documentation](self).
    pub snap_rounding: bool,
    /// Move the inertia a joint cannot move to its parent (on); see
    /// [`regroup_inertia`] (with the body frames moved first:
    /// [`center_prismatic_leaves`], [`slide_origins_along_axes`]).
    pub regroup_inertia: bool,
    /// The value-changing graph rewrites (on); see [`Rewrites`].
    pub rewrites: Rewrites,
    /// Where the model came from (a file name), for the header.
    pub source: Option<String>,
    /// Where the sines and cosines come from ([`Trig::Batched`]: the
    /// module's own, no std).
    pub trig: Trig,
    /// A function body of more than this many `let`s is emitted as private
    /// parts of at most this many, called in order by the public function
    /// ([`DEFAULT_SPLIT_LETS`]; `None`: never split). Splitting keeps rustc
    /// from overflowing its stack on long bodies in debug builds and bounds
    /// LLVM's super-linear passes in release builds; the results are bit
    /// for bit those of the unsplit body.
    pub split_lets: Option<usize>,
    /// Write `a·b ± c` as `fma(a, b, ±c)` (on): one fused multiply-add
    /// with a single rounding where the target has one (x86-64 built with
    /// the `fma` target feature, aarch64), else `a * b + c`, bit for bit
    /// the unfused code; see [`crate::symbolic::Fusion`] for which sums.
    /// On by default: it costs nothing where the target has no fused
    /// multiply-add (the same bits, the same instructions), and where it
    /// has, the bodies, bound by the floating-point ports, run fewer
    /// operations (`benches/README.md`, "Run 7"); with
    /// [`runtime_dispatch`](Self::runtime_dispatch) a default x86-64 build
    /// has a copy with FMA too. Off, the bodies give the
    /// same bits on every target. (The module's `sin_cos_array` fuses its
    /// polynomials wherever the target has FMA, either way: within 1 ulp
    /// both ways.)
    pub fma: bool,
    /// On x86-64 builds without the `avx2` and `fma` target features (a
    /// default `cargo build`), compile every public function twice, once
    /// for the build's target and once for AVX2 and FMA, and pick the copy
    /// at run time by what the processor has (on): see the [module
    /// documentation](self). Builds that have both features, and other
    /// targets, get one copy, as without it. On by default, because most
    /// x86-64 processors in use have both and the bodies are bound by the
    /// floating-point ports: a default build then runs as fast as a native
    /// one. The price: a default build's results differ in the last bits
    /// between machines with and without FMA (on both they are within the
    /// accuracy the tests check, 1e-12 of the generic solver), and the
    /// bodies are compiled twice. Off, a build gives the same bits on every
    /// x86-64 machine. [`generate`] leaves it out of modules of more than
    /// [`DISPATCH_MAX_OPS`] operations (slow to compile), and says so in
    /// the header.
    pub runtime_dispatch: bool,
}

/// [`generate`] leaves the run-time dispatch out of a module whose emitted
/// functions take more operations than this (their sum, as the header
/// counts them), and says so in the header: rustc compiles the AVX2 and FMA
/// copies of long bodies very slowly. The fused multiply-adds are written
/// with `core::arch`'s `_mm_fmadd_sd` (`f64::mul_add` is not in `core`), and
/// LLVM's time on thousands of them grows far faster than the body: an
/// 8-joint chain's module (8,149 operations) took 20.5 s of `rustc -O`
/// with the dispatch and 1.6 s without, a 30-joint chain's 231 s against
/// 13 s, the Panda's (3,638) 3.8 s against 1.3 s. The same module built
/// with `-C target-cpu=native` pays the same (the fused copy is then the
/// only one), and with `mul_add` in place of the intrinsic the 8-joint
/// chain's took 1.1 s. The bundled robots are under the limit.
pub const DISPATCH_MAX_OPS: usize = 5_000;

/// The default [`CodegenOptions::split_lets`]: 2,500 `let`s. rustc with
/// debug information overflows its stack at about 2,900 `let`s in one
/// function; the largest body of a bundled robot (the torso's forward
/// dynamics, 2,104) stays whole. Measured in `benches/README.md`.
pub const DEFAULT_SPLIT_LETS: usize = 2500;

impl Default for CodegenOptions {
    fn default() -> Self {
        CodegenOptions {
            scalar: ScalarType::F64,
            functions: Functions::default(),
            forward_dynamics: ForwardDynamicsMethod::Auto,
            snap_rounding: true,
            regroup_inertia: true,
            rewrites: Rewrites::default(),
            source: None,
            trig: Trig::default(),
            split_lets: Some(DEFAULT_SPLIT_LETS),
            fma: true,
            runtime_dispatch: true,
        }
    }
}

impl CodegenOptions {
    /// Sets the float type.
    pub fn scalar(mut self, scalar: ScalarType) -> Self {
        self.scalar = scalar;
        self
    }
    /// Sets which functions to generate.
    pub fn functions(mut self, functions: Functions) -> Self {
        self.functions = functions;
        self
    }
    /// Sets the forward-dynamics algorithm.
    pub fn forward_dynamics(mut self, method: ForwardDynamicsMethod) -> Self {
        self.forward_dynamics = method;
        self
    }
    /// Turns the rounding snap on or off.
    pub fn snap_rounding(mut self, on: bool) -> Self {
        self.snap_rounding = on;
        self
    }
    /// Turns the regrouping of inertial parameters on or off.
    pub fn regroup_inertia(mut self, on: bool) -> Self {
        self.regroup_inertia = on;
        self
    }
    /// Sets the value-changing rewrites.
    pub fn rewrites(mut self, rewrites: Rewrites) -> Self {
        self.rewrites = rewrites;
        self
    }
    /// Sets where the sines and cosines come from.
    pub fn trig(mut self, trig: Trig) -> Self {
        self.trig = trig;
        self
    }
    /// Sets the longest body emitted as one function (`None`: no limit).
    pub fn split_lets(mut self, lets: Option<usize>) -> Self {
        self.split_lets = lets;
        self
    }
    /// Turns fused multiply-adds on or off.
    pub fn fma(mut self, on: bool) -> Self {
        self.fma = on;
        self
    }
    /// Turns the run-time choice of AVX2 and FMA copies on or off.
    pub fn runtime_dispatch(mut self, on: bool) -> Self {
        self.runtime_dispatch = on;
        self
    }
    /// Names the model's source for the header.
    pub fn source(mut self, source: impl Into<String>) -> Self {
        self.source = Some(source.into());
        self
    }
}

/// Why a module could not be generated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
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
    /// Two functions of a scene get the same Rust name (two frames whose
    /// names differ only in characters a Rust name cannot hold).
    #[error("two functions would be named `{0}` (frame names that differ only in characters Rust names cannot hold)")]
    DuplicateName(String),
    /// The generated tokens did not parse as a Rust file (a bug of dynagen).
    #[error("internal error: generated code does not parse: {0}")]
    Internal(String),
}

/// One traced function of a module.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedFunction {
    /// Which function.
    pub kind: FunctionKind,
    /// Whether it is in the source (the LᵀDL or ABA forward dynamics that
    /// was not chosen is traced and counted only).
    pub emitted: bool,
    /// The traced, dead-code-eliminated function of `q` (evaluate it with
    /// [`Function::eval`]).
    pub function: Function,
    /// The same function with the sines and cosines as inputs: the body of
    /// `NAME_sc`.
    pub sin_cos_inputs: SinCosTrace,
    /// Its operation count.
    pub op_count: OpCount,
}

/// A generated module.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedModule {
    /// The formatted Rust source, header included.
    pub source: String,
    /// Every traced function (of a module of [`generate`]; empty for a
    /// scene's).
    pub functions: Vec<GeneratedFunction>,
    /// The functions of a scene's module ([`generate_scene`]; empty for
    /// [`generate`]'s).
    pub scene_functions: Vec<SceneFunction>,
    /// The model constants replaced by 0 or ±1.
    pub snapped: Vec<SnappedConstant>,
    /// FNV-1a of the model's [`canonical_text`].
    pub model_hash: u64,
}

impl GeneratedModule {
    /// The operation counts, as `(label, count)`.
    pub fn op_counts(&self) -> Vec<(&'static str, OpCount)> {
        self.functions.iter().map(|f| (f.kind.label(), f.op_count)).collect()
    }
    /// The function of a scene's module named `name` (`inverse_dynamics`,
    /// `frame_pose_ee_link`, …).
    pub fn scene_function(&self, name: &str) -> Option<&SceneFunction> {
        self.scene_functions.iter().find(|f| f.name == name)
    }
    /// Every function's name and operation count, for either kind of
    /// module (the forward dynamics not emitted are labelled so).
    pub fn named_op_counts(&self) -> Vec<(String, OpCount)> {
        let plain = self
            .functions
            .iter()
            .map(|f| (format!("{}{}", f.kind.label(), if f.emitted { "" } else { " [not emitted]" }), f.op_count));
        plain.chain(self.scene_functions.iter().map(|f| (f.name.clone(), f.op_count))).collect()
    }
    /// The traced function of `kind`, if it was traced.
    pub fn function(&self, kind: FunctionKind) -> Option<&Function> {
        self.functions.iter().find(|f| f.kind == kind).map(|f| &f.function)
    }
}

fn doc_of(kind: FunctionKind, model: &Model, count: &OpCount) -> String {
    let what = match kind {
        FunctionKind::InverseDynamics => {
            "Inverse dynamics τ = M(q)q̈ + C(q, q̇)q̇ + g(q) by the recursive Newton-Euler algorithm."
        }
        FunctionKind::MassMatrix => {
            "The mass matrix M(q) by the composite-rigid-body algorithm (symmetric, `[row][col]`)."
        }
        FunctionKind::BiasForces => "The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q).",
        FunctionKind::GravityTorques => "The gravity torques g(q).",
        FunctionKind::ForwardDynamicsAba => {
            "Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇)) by the articulated-body algorithm."
        }
        FunctionKind::ForwardDynamicsLdlt => {
            "Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇)) by CRBA, RNEA and a sparse LᵀDL solve."
        }
    };
    format!(
        " {what}\n\n Joint order: [`JOINT_NAMES`]; rad, m, s, N·m, N; gravity {:?} m/s² in the base frame.\n {count}.",
        model.gravity.0
    )
}

/// The model code is generated from: `model` with the rounding snap and the
/// inertia regrouping the options ask for (both exact within the file's
/// precision, see [`snap_rounding`] and [`regroup_inertia`]; with the
/// regrouping, body frames first move where they cost less, see
/// [`center_prismatic_leaves`] and [`slide_origins_along_axes`]), and the
/// constants the snap changed. Plain and scene modules both start here.
pub(crate) fn prepare_model(model: &Model, options: &CodegenOptions) -> (Model, Vec<SnappedConstant>) {
    let (snapped_model, snapped) =
        if options.snap_rounding { snap_rounding(model) } else { (model.clone(), Vec::new()) };
    let prepared = if options.regroup_inertia {
        regroup_inertia(&slide_origins_along_axes(&center_prismatic_leaves(&snapped_model)))
    } else {
        snapped_model
    };
    (prepared, snapped)
}

/// Generates the module for `model`; see the [module documentation](self).
pub fn generate(model: &Model, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
    let (prepared, snapped) = prepare_model(model, options);
    let m = &prepared;
    let n = model.dof();
    let f = &options.functions;
    let wanted = [
        (FunctionKind::InverseDynamics, f.inverse_dynamics),
        (FunctionKind::MassMatrix, f.mass_matrix),
        (FunctionKind::BiasForces, f.bias_forces),
        (FunctionKind::GravityTorques, f.gravity_torques),
        (FunctionKind::ForwardDynamicsAba, f.forward_dynamics),
        (FunctionKind::ForwardDynamicsLdlt, f.forward_dynamics),
    ];
    let mut functions = Vec::new();
    let mut items: Vec<syn::Item> = Vec::new();
    let names = model.joint_names();
    let n_lit = proc_macro2::Literal::usize_unsuffixed(n);
    let consts = quote! {
        #[doc = " The number of degrees of freedom (joints)."]
        pub const DOF: usize = #n_lit;
        #[doc = " The joint names, in the order of every index of the functions below."]
        pub const JOINT_NAMES: [&str; DOF] = [#(#names),*];
    };
    let consts: syn::File = syn::parse2(consts).map_err(|e| CodegenError::Internal(e.to_string()))?;
    items.extend(consts.items);
    items.push(parse_item(sin_cos::sin_cos_all_item(options.scalar))?);
    let has_prismatic = m.bodies.iter().any(|b| b.joint.kind == crate::model::JointKind::Prismatic);
    let mut split_functions = Vec::new();
    for (kind, on) in wanted {
        if !on {
            continue;
        }
        let sc = trace_sin_cos_inputs(m, kind, options.rewrites).map_err(CodegenError::Internal)?;
        let function = sin_cos_from_q(&sc, options.rewrites);
        let op_count = counted(&function, options.fma);
        functions.push(GeneratedFunction { kind, emitted: true, function, sin_cos_inputs: sc, op_count });
    }
    let fd_method = match options.forward_dynamics {
        ForwardDynamicsMethod::Auto => {
            let find = |k: FunctionKind| functions.iter().find(|f| f.kind == k);
            match (find(FunctionKind::ForwardDynamicsAba), find(FunctionKind::ForwardDynamicsLdlt)) {
                (Some(aba), Some(ldlt)) => fd_choice::choose(aba, ldlt, n),
                _ => fd_choice::FdChoice { method: ForwardDynamicsMethod::Aba, why: String::new() },
            }
        }
        method => fd_choice::FdChoice { method, why: String::new() },
    };
    for f in &mut functions {
        f.emitted = match f.kind {
            FunctionKind::ForwardDynamicsAba => fd_method.method == ForwardDynamicsMethod::Aba,
            FunctionKind::ForwardDynamicsLdlt => fd_method.method == ForwardDynamicsMethod::Ldlt,
            _ => true,
        };
    }
    let emitted_ops = functions.iter().filter(|f| f.emitted).map(|f| f.op_count.total()).sum();
    let (effective, dropped_note) = within_dispatch_limit(options, emitted_ops);
    let options = &effective;
    for f in &functions {
        if !f.emitted {
            continue;
        }
        let (kind, sc, op_count) = (f.kind, &f.sin_cos_inputs, f.op_count);
        let mut params = vec!["s", "c"];
        if has_prismatic {
            params.push("q");
        }
        params.extend(&kind.inputs()[1..]);
        let sc_name = format!("{}_sc", kind.fn_name());
        let params = params.into_iter().map(emit::Param::dof).collect();
        let signature = emit::Signature { name: sc_name.clone(), params, output: emit::Shape::of(kind) };
        let doc = format!("{}\n\n{}", doc_of(kind, model, &counted(&sc.function, options.fma)), sc_doc(has_prismatic));
        let style = emit::BodyStyle::of(options);
        let emitted = emit::emit_function(&sc.function, &signature, options.scalar, options.trig, n, &doc, style)?;
        let sc_split = split::parts_of(&emitted);
        if let Some(parts) = sc_split {
            split_functions.push((sc_name.clone(), parts));
        }
        items.extend(emitted);
        if options.trig != Trig::Inputs {
            let doc = format!(
                "{}\n\n The sines and cosines of the joint angles by {}, then [`{sc_name}`].",
                doc_of(kind, model, &op_count),
                trig_source(options.trig, options.scalar)
            );
            let params: Vec<emit::Param> = kind.inputs().iter().map(|p| emit::Param::dof(p)).collect();
            let ret = emit::return_type(kind, options.scalar);
            let body = ScBody { trace: sc, has_prismatic, split: sc_split.is_some() };
            items.extend(parse_items(wrapper(kind.fn_name(), &params, ret, body, options, &doc))?);
        }
    }
    let file = syn::File { shebang: None, frontmatter: None, attrs: vec![], items };
    let body = emit::tidy_dispatch(&prettyplease::unparse(&file));
    let model_hash = model_hash(model);
    let mut header = header(model, options, &fd_method, &functions, &snapped, model_hash)
        + &split::header_note(options.split_lets, &split_functions);
    header.push_str(&dropped_note);
    let kernel = sin_cos::kernel_source(options.scalar, options.runtime_dispatch);
    Ok(GeneratedModule {
        source: format!("{header}\n{body}\n{kernel}"),
        functions,
        scene_functions: Vec::new(),
        snapped,
        model_hash,
    })
}

/// `options` with the run-time dispatch left out if the module's functions
/// take `ops` operations, over [`DISPATCH_MAX_OPS`], and the header's line
/// that says so (empty when nothing was left out).
pub(crate) fn within_dispatch_limit(options: &CodegenOptions, ops: usize) -> (CodegenOptions, String) {
    if !options.runtime_dispatch || ops <= DISPATCH_MAX_OPS {
        return (options.clone(), String::new());
    }
    let note = format!(
        "// Run-time dispatch was asked for but left out: the functions take {ops} operations, over\n\
         //   the {DISPATCH_MAX_OPS} up to which it is emitted (rustc compiles the fused copies of long bodies slowly).\n"
    );
    (CodegenOptions { runtime_dispatch: false, ..options.clone() }, note)
}

/// The operation count of `f`, with its fused multiply-adds if `fma`.
pub(crate) fn counted(f: &Function, fma: bool) -> OpCount {
    if fma {
        f.fusion().op_count(f)
    } else {
        f.op_count()
    }
}

/// The header's lines on fused multiply-adds and the run-time dispatch.
pub(crate) fn fma_note(options: &CodegenOptions) -> String {
    let fma = if options.fma {
        "// Fused multiply-adds: fma(a, b, c) (fmaf in f32) is a*b + c with one rounding where the target has an FMA\n\
         //   instruction (x86_64 built with target feature fma, e.g. -C target-cpu=native on a machine that has it;\n\
         //   aarch64), and plain a * b + c elsewhere: a default x86_64 build gives the same bits as unfused code.\n"
    } else {
        "// Fused multiply-adds: off (every a*b + c rounded twice, on every target).\n"
    };
    let dispatch = if options.runtime_dispatch {
        "// Run-time dispatch: on. On x86_64 builds without target features avx2 and fma (a default build), every\n\
         //   public function also has a copy compiled for AVX2 and FMA (NAME_avx2_fma, from the one generic body\n\
         //   NAME_on) and runs it where the processor has both (cpuid, asked once): as fast as a native build, and\n\
         //   with its bits, so results differ in the last bits between machines with and without FMA (within the\n\
         //   accuracy the tests check). Off: runtime_dispatch(false), the same bits on every x86_64 machine.\n"
    } else {
        "// Run-time dispatch: off (the build's target features only: the same bits on every x86_64 machine).\n"
    };
    format!("{fma}{dispatch}")
}

fn parse_item(tokens: proc_macro2::TokenStream) -> Result<syn::Item, CodegenError> {
    syn::parse2(tokens).map_err(|e| CodegenError::Internal(e.to_string()))
}

fn sc_doc(has_prismatic: bool) -> String {
    let q = if has_prismatic { " `q` is read for the prismatic joints only." } else { "" };
    format!(
        " Takes `s[i]` = sin θᵢ and `c[i]` = cos θᵢ of each revolute joint's angle θᵢ = `q[i]` (times `|axis|` for a \
         non-unit axis, see the caller); the entries of prismatic joints are not read.{q}"
    )
}

fn trig_source(trig: Trig, scalar: ScalarType) -> &'static str {
    match (trig, scalar) {
        (Trig::Std, ScalarType::F64) => "`f64::sin_cos`",
        (Trig::Std, ScalarType::F32) => "`f32::sin_cos`",
        (Trig::Batched, ScalarType::F64) => "`sin_cos_array` (only the angles the body reads)",
        (Trig::Batched, ScalarType::F32) => "`sin_cos_array_f32` (only the angles the body reads)",
        (Trig::Libm, ScalarType::F64) => "`libm::sincos`",
        (Trig::Libm, ScalarType::F32) => "`libm::sincosf`",
        (Trig::Inputs, _) => "the caller",
    }
}

/// What [`wrapper`] calls: the body `NAME_sc`, the angles it reads, whether
/// it takes `q` too (for its prismatic joints) and whether it is split into
/// parts.
struct ScBody<'a> {
    trace: &'a SinCosTrace,
    has_prismatic: bool,
    split: bool,
}

/// `NAME(q, …)`: the sines and cosines, then `NAME_sc`. `params` start
/// with `q`.
fn wrapper(
    fn_name: &str,
    params: &[emit::Param],
    ret: proc_macro2::TokenStream,
    body: ScBody<'_>,
    options: &CodegenOptions,
    doc: &str,
) -> proc_macro2::TokenStream {
    let ScBody { trace: sc, has_prismatic, split: sc_split } = body;
    let name = quote::format_ident!("{}", fn_name);
    let sc_name = quote::format_ident!("{}_sc", fn_name);
    let typed: Vec<proc_macro2::TokenStream> = params.iter().map(|p| p.tokens(options.scalar)).collect();
    let rest: Vec<proc_macro2::Ident> = params[1..].iter().map(|p| quote::format_ident!("{}", p.name)).collect();
    let q_arg = if has_prismatic { quote!(q,) } else { quote!() };
    let angle = |i: usize, k: f64| {
        let i = proc_macro2::Literal::usize_unsuffixed(i);
        if k == 1.0 {
            quote!(q[#i])
        } else {
            let k = literal::float_literal_text(k, options.scalar).unwrap_or_else(|| "1.0".into());
            let k: proc_macro2::TokenStream = k.parse().expect("a float literal");
            quote!(q[#i] * #k)
        }
    };
    // The batched trigonometry, then `NAME_sc`: `all` computes every sine and cosine, `some` those
    // of the angles it is given, `sc` calls the body.
    let batched = |all: proc_macro2::TokenStream,
                   some: &dyn Fn(usize) -> proc_macro2::TokenStream,
                   sc_call: &dyn Fn(proc_macro2::TokenStream) -> proc_macro2::TokenStream| {
        // Only the angles NAME_sc reads (the UR5's g reads 3 of 6, the Panda's functions 7 of 9).
        let read: Vec<(usize, f64)> =
            sc.angle_scale.iter().enumerate().filter_map(|(i, k)| k.map(|k| (i, k))).collect();
        if read.len() == sc.angle_scale.len() && read.iter().all(|&(_, k)| k == 1.0) {
            let call = sc_call(quote!(&s, &c, #q_arg #(#rest),*));
            quote! {
                let (s, c) = #all;
                #call
            }
        } else {
            let batch = some(read.len());
            let angles = read.iter().map(|&(i, k)| angle(i, k));
            let mut s_entries = Vec::new();
            let mut c_entries = Vec::new();
            let mut j = 0;
            for k in &sc.angle_scale {
                if k.is_some() {
                    let lit = proc_macro2::Literal::usize_unsuffixed(j);
                    s_entries.push(quote!(s[#lit]));
                    c_entries.push(quote!(c[#lit]));
                    j += 1;
                } else {
                    s_entries.push(quote!(0.0));
                    c_entries.push(quote!(1.0));
                }
            }
            let call = if read.is_empty() { quote!() } else { quote!(let (s, c) = #batch(&[#(#angles),*]);) };
            let sc_call = sc_call(quote!(&[#(#s_entries),*], &[#(#c_entries),*], #q_arg #(#rest),*));
            quote! {
                #call
                #sc_call
            }
        }
    };
    let body = if options.trig == Trig::Batched {
        let batch = sin_cos::batch_function(options.scalar);
        batched(quote!(sin_cos_all(q)), &|_| batch.clone(), &|args| quote!(#sc_name(#args)))
    } else {
        let mut stmts = Vec::new();
        let mut s_entries = Vec::new();
        let mut c_entries = Vec::new();
        for (i, k) in sc.angle_scale.iter().enumerate() {
            match k {
                Some(k) => {
                    let (si, ci) = (quote::format_ident!("s{i}"), quote::format_ident!("c{i}"));
                    let a = angle(i, *k);
                    let call = match (options.trig, options.scalar) {
                        (Trig::Libm, ScalarType::F64) => quote!(libm::sincos(#a)),
                        (Trig::Libm, ScalarType::F32) => quote!(libm::sincosf(#a)),
                        _ if *k == 1.0 => quote!(#a.sin_cos()),
                        _ => quote!((#a).sin_cos()),
                    };
                    stmts.push(quote!(let (#si, #ci) = #call;));
                    s_entries.push(quote!(#si));
                    c_entries.push(quote!(#ci));
                }
                None => {
                    s_entries.push(quote!(0.0));
                    c_entries.push(quote!(1.0));
                }
            }
        }
        quote! {
            #(#stmts)*
            #sc_name(&[#(#s_entries),*], &[#(#c_entries),*], #q_arg #(#rest),*)
        }
    };
    let doc = doc.lines();
    if !(options.runtime_dispatch && options.trig == Trig::Batched) {
        return quote! {
            #(#[doc = #doc])*
            #[inline]
            pub fn #name(#(#typed),*) -> #ret {
                #body
            }
        };
    }
    // With run-time dispatch, the batched sines and cosines and the body are inlined into an AVX2
    // and FMA copy of `NAME`, as in a native build: no second check, no call of the kernel or of
    // `NAME_sc_avx2_fma` with the sines and cosines through memory. (The body is compiled a second
    // time for it; inlined, the UR5's τ took 70 ns instead of 78.) A body split into parts is
    // called as `NAME_sc_avx2_fma`, the chain of its parts.
    let fast = quote::format_ident!("{}_avx2_fma", fn_name);
    let sc_fast = quote::format_ident!("{}_sc_avx2_fma", fn_name);
    let sc_on = quote::format_ident!("{}_sc_on", fn_name);
    let on = match options.scalar {
        ScalarType::F64 => quote!(sin_cos_array_on),
        ScalarType::F32 => quote!(sin_cos_array_f32_on),
    };
    let fast_body = batched(
        quote!(#on::<Avx2Fma, DOF>(q)),
        &|n| {
            let n = proc_macro2::Literal::usize_unsuffixed(n);
            quote!(#on::<Avx2Fma, #n>)
        },
        &|args| if sc_split { quote!(unsafe { #sc_fast(#args) }) } else { quote!(#sc_on::<Avx2Fma>(#args)) },
    );
    let args = params.iter().map(|p| quote::format_ident!("{}", p.name));
    let fast_doc = format!(" [`{fn_name}`] compiled for processors with AVX2 and FMA.");
    quote! {
        #(#[doc = #doc])*
        #[inline]
        pub fn #name(#(#typed),*) -> #ret {
            #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
            if has_avx2_and_fma() {
                return unsafe { #fast(#(#args),*) };
            }
            #body
        }
        #[doc = #fast_doc]
        #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
        #[target_feature(enable = "avx2,fma")]
        unsafe fn #fast(#(#typed),*) -> #ret {
            #fast_body
        }
    }
}

/// The items of `tokens`.
fn parse_items(tokens: proc_macro2::TokenStream) -> Result<Vec<syn::Item>, CodegenError> {
    syn::parse2::<syn::File>(tokens).map(|f| f.items).map_err(|e| CodegenError::Internal(e.to_string()))
}

fn header(
    model: &Model,
    options: &CodegenOptions,
    fd: &fd_choice::FdChoice,
    functions: &[GeneratedFunction],
    snapped: &[SnappedConstant],
    hash: u64,
) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "// Dynamics of the robot \"{}\" ({} joints), generated by dynagen {GENERATOR_VERSION}.",
        model.name,
        model.dof()
    );
    let _ = writeln!(h, "// Do not edit: regenerate from the model instead.");
    let _ = writeln!(h, "//");
    let source = options.source.as_deref().unwrap_or("(not given)");
    let _ = writeln!(h, "// Model source: {source}");
    let _ = writeln!(h, "// Model content hash (FNV-1a 64 of its canonical text): {hash:016x}");
    let _ = writeln!(h, "// Gravity: {:?} m/s^2 in the base frame, folded in.", model.gravity.0);
    let scalar = match options.scalar {
        ScalarType::F64 => "f64",
        ScalarType::F32 => "f32",
    };
    let fd_name = match fd.method {
        ForwardDynamicsMethod::Aba | ForwardDynamicsMethod::Auto => "articulated-body algorithm",
        ForwardDynamicsMethod::Ldlt => "CRBA + RNEA + sparse LTDL",
    };
    let fd_how = if options.forward_dynamics == ForwardDynamicsMethod::Auto { " (chosen)" } else { "" };
    let r = options.rewrites;
    let _ = writeln!(
        h,
        "// Options: scalar {scalar}; forward dynamics by the {fd_name}{fd_how}; rounding snap {} ({} constants); inertia regrouping {}; like terms {}, constant products {}, constant sums {}, reassociation {}.",
        if options.snap_rounding { "on" } else { "off" },
        snapped.len(),
        if options.regroup_inertia { "on" } else { "off" },
        if r.like_terms { "on" } else { "off" },
        if r.constant_products { "on" } else { "off" },
        if r.constant_sums { "on" } else { "off" },
        if r.reassociate { "on" } else { "off" },
    );
    let trig = match options.trig {
        Trig::Std => "NAME(q, ...) computes the sines and cosines by std's sin_cos (needs std)",
        Trig::Batched => {
            "NAME(q, ...) computes the sines and cosines it reads by sin_cos_array, two at a time, four where the target (or, with run-time dispatch, the processor) has AVX2 (no_std, no dependency)"
        }
        Trig::Libm => "NAME(q, ...) computes the sines and cosines by libm::sincos (no_std; needs the `libm` crate)",
        Trig::Inputs => "only NAME_sc(s, c, ...): the caller passes the sines and cosines (no_std, no dependency)",
    };
    let _ = writeln!(h, "// Trigonometry: {trig}.");
    h.push_str(&fma_note(options));
    let why = match fd.method {
        _ if !fd.why.is_empty() => fd.why.as_str(),
        ForwardDynamicsMethod::Aba | ForwardDynamicsMethod::Auto => {
            "the articulated-body algorithm, as asked: the accurate one on long chains (64-joint chain against \
             double-double: 1e-12 against 7e-10)"
        }
        ForwardDynamicsMethod::Ldlt => "CRBA + LTDL, as asked: fewer operations, less accurate on long chains",
    };
    let _ = writeln!(h, "// Forward dynamics: {why}.");
    let _ = writeln!(
        h,
        "// Every NAME_sc(s, c, ...) takes s[i] = sin(theta_i), c[i] = cos(theta_i) of joint i's angle theta_i = q[i]\n\
         //   (times |axis| for a non-unit axis; prismatic entries unused), and q only if a joint is prismatic.\n\
         // sin_cos_all(q): the batched sine and cosine, within 1 ulp for every finite angle, no std{}.",
        if options.scalar == ScalarType::F32 { " (computed in f64, rounded to f32)" } else { "" }
    );
    let left_out: Vec<&str> = FunctionKind::ALL
        .iter()
        .filter(|k| !functions.iter().any(|f| f.kind == **k))
        .map(|k| k.fn_name())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if !left_out.is_empty() {
        let _ = writeln!(h, "// Left out: {}.", left_out.join(", "));
    }
    let _ = writeln!(
        h,
        "// Operation counts; critical path = the longest chain of dependent operations, weighted by latency\n\
         //   (add, sub, mul, fma 4 cycles, div 14, sqrt 18, neg 1), of the body with the sines and cosines given:"
    );
    for f in functions {
        let note = if f.emitted { "" } else { " [not emitted]" };
        let body = &f.sin_cos_inputs.function;
        let path = if options.fma { body.fusion().critical_path() } else { body.critical_path() };
        let _ = writeln!(h, "//   {}{note}: {}; body NAME_sc {path}", f.kind.label(), f.op_count);
    }
    h
}
