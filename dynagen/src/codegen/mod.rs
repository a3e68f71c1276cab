//! Code generation: a model → a Rust module with its dynamics unrolled.
//!
//! [`generate`] traces each function of the generated-code contract
//! (DESIGN.md) by running the generic algorithm on the symbolic scalar
//! ([`crate::symbolic`]), keeps what the outputs reach, factors it
//! ([`crate::symbolic::factor`]), and prints one `let`
//! per kept operation with `quote`, formatted by `prettyplease`. The result
//! ([`GeneratedModule::source`]) is a file of items to `include!` in a
//! module: `DOF`, `JOINT_NAMES`, `inverse_dynamics`, `mass_matrix`,
//! `bias_forces`, `gravity_torques`, `forward_dynamics`. It depends on
//! nothing but `sin_cos` and `sqrt` of the float type. The same model and
//! options give a byte-identical file.
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
mod generic_count;
mod hash;
mod literal;
mod rounding;
mod trace;

pub use builder::{module_name, BuildError, Builder, GeneratedFile};
pub use generic_count::generic_op_count;
pub use hash::{canonical_text, fnv1a64, model_hash};
pub use literal::float_literal_text;
pub use rounding::{snap_rounding, SnappedConstant, ROUNDING_TOLERANCE};
pub use trace::{trace, FunctionKind};

use crate::model::Model;
use crate::symbolic::{Function, OpCount, Rewrites};
use quote::quote;
use std::fmt::Write;

/// The names of the functions a module can have, in the order it lists them.
pub const FUNCTION_NAMES: [&str; 5] =
    ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"];

/// The generator's version, written into every header.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The float type of the generated code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ScalarType {
    /// `f64`.
    #[default]
    F64,
    /// `f32` (constants rounded to `f32`).
    F32,
}

/// How the generated `forward_dynamics` computes q̈.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ForwardDynamicsMethod {
    /// The articulated-body algorithm: the accurate one on long chains.
    #[default]
    Aba,
    /// M by CRBA, h by RNEA, then a sparse LᵀDL solve.
    Ldlt,
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
    /// The forward-dynamics algorithm emitted (ABA); both are traced and
    /// counted in the header.
    pub forward_dynamics: ForwardDynamicsMethod,
    /// Replace constants that are 0 or ±1 up to rounding (on); see the
    /// [module documentation](self).
    pub snap_rounding: bool,
    /// The value-changing graph rewrites (on); see [`Rewrites`].
    pub rewrites: Rewrites,
    /// Where the model came from (a file name), for the header.
    pub source: Option<String>,
}

impl Default for CodegenOptions {
    fn default() -> Self {
        CodegenOptions {
            scalar: ScalarType::F64,
            functions: Functions::default(),
            forward_dynamics: ForwardDynamicsMethod::Aba,
            snap_rounding: true,
            rewrites: Rewrites::default(),
            source: None,
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
    /// Sets the value-changing rewrites.
    pub fn rewrites(mut self, rewrites: Rewrites) -> Self {
        self.rewrites = rewrites;
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
    /// The traced, dead-code-eliminated function (evaluate it with
    /// [`Function::eval`]).
    pub function: Function,
    /// Its operation count.
    pub op_count: OpCount,
}

/// A generated module.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedModule {
    /// The formatted Rust source, header included.
    pub source: String,
    /// Every traced function.
    pub functions: Vec<GeneratedFunction>,
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

/// Generates the module for `model`; see the [module documentation](self).
pub fn generate(model: &Model, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
    let (snapped_model, snapped) =
        if options.snap_rounding { snap_rounding(model) } else { (model.clone(), Vec::new()) };
    let m = &snapped_model;
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
    for (kind, on) in wanted {
        if !on {
            continue;
        }
        let function = trace(m, kind, options.rewrites)?;
        let op_count = function.op_count();
        let emitted = match kind {
            FunctionKind::ForwardDynamicsAba => options.forward_dynamics == ForwardDynamicsMethod::Aba,
            FunctionKind::ForwardDynamicsLdlt => options.forward_dynamics == ForwardDynamicsMethod::Ldlt,
            _ => true,
        };
        if emitted {
            items.push(emit::emit_function(&function, kind, options.scalar, n, &doc_of(kind, model, &op_count))?);
        }
        functions.push(GeneratedFunction { kind, emitted, function, op_count });
    }
    let file = syn::File { shebang: None, frontmatter: None, attrs: vec![], items };
    let body = prettyplease::unparse(&file);
    let model_hash = model_hash(model);
    let header = header(model, options, &functions, &snapped, model_hash);
    Ok(GeneratedModule { source: format!("{header}\n{body}"), functions, snapped, model_hash })
}

fn header(
    model: &Model,
    options: &CodegenOptions,
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
    let fd = match options.forward_dynamics {
        ForwardDynamicsMethod::Aba => "articulated-body algorithm",
        ForwardDynamicsMethod::Ldlt => "CRBA + RNEA + sparse LTDL",
    };
    let r = options.rewrites;
    let _ = writeln!(
        h,
        "// Options: scalar {scalar}; forward dynamics by the {fd}; rounding snap {} ({} constants); like terms {}, constant products {}, constant sums {}.",
        if options.snap_rounding { "on" } else { "off" },
        snapped.len(),
        if r.like_terms { "on" } else { "off" },
        if r.constant_products { "on" } else { "off" },
        if r.constant_sums { "on" } else { "off" },
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
    let _ = writeln!(h, "// Operation counts:");
    for f in functions {
        let note = if f.emitted { "" } else { " [not emitted]" };
        let _ = writeln!(h, "//   {}{note}: {}", f.kind.label(), f.op_count);
    }
    h
}
