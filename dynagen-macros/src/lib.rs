//! The proc-macros of dynagen: [`urdf!`] and [`robot!`]. They hold no
//! dynamics: they parse their input with `syn`, build the model with
//! dynagen, and call dynagen's code generator
//! ([`dynagen::codegen::Builder`]); what they expand to is the module a
//! build script would write with the same options.
//!
//! # Which crate to depend on
//!
//! Depend on `dynagen-macros` directly and call `dynagen_macros::urdf!`
//! (as with `serde_derive`). The generated code needs nothing else at run
//! time: not `dynagen`, not even `std` beyond `f64::sin_cos`. `dynagen`
//! does not re-export these macros, because this crate depends on it (a
//! re-export would make a dependency cycle).
//!
//! ```toml
//! [dependencies]
//! dynagen-macros = "0.1"
//! ```
//!
//! ```ignore
//! mod ur5 {
//!     dynagen_macros::urdf!("robots/ur5.urdf", functions = [inverse_dynamics, mass_matrix]);
//! }
//! let tau = ur5::inverse_dynamics(&q, &qd, &qdd);
//! ```
//!
//! The model is traced at compile time, in the proc-macro, which cargo
//! builds without optimisation by default; for large robots add
//!
//! ```toml
//! [profile.dev.build-override]
//! opt-level = 3
//! ```
//!
//! # Options (both macros)
//!
//! | option | values | default |
//! | --- | --- | --- |
//! | `functions` | `[inverse_dynamics, mass_matrix, bias_forces, gravity_torques, forward_dynamics]` | all five |
//! | `scalar` | `f64`, `f32` | `f64` |
//! | `forward_dynamics` | `aba`, `ldlt` | `aba` |
//! | `snap_rounding` | `true`, `false` | `true` |
//!
//! Every mistake is a compile error at the token it is about: an unknown
//! option or function, a number that is not one, a missing file (at the
//! path), a model error such as a massless subtree or a missing link (at
//! the joint's or link's name).

use dynagen::codegen::{Builder, CodegenOptions, ForwardDynamicsMethod, Functions, ScalarType};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{bracketed, Ident, LitBool, LitStr, Token};

mod robot;

/// Generates the dynamics module of a URDF robot, in place: write it inside
/// a module.
///
/// ```ignore
/// mod ur5 {
///     dynagen_macros::urdf!("robots/ur5.urdf", functions = [inverse_dynamics, mass_matrix], scalar = f32);
/// }
/// ```
///
/// The path is relative to the crate's root (`CARGO_MANIFEST_DIR`); the
/// crate is rebuilt when the file changes. See the [crate docs](crate) for
/// the options.
#[proc_macro]
pub fn urdf(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    match syn::parse::<UrdfInput>(input).and_then(expand_urdf) {
        Ok(t) => t.into(),
        Err(e) => e.to_compile_error().into(),
    }
}

/// Generates the dynamics module of a robot written inline, in place: write
/// it inside a module.
///
/// ```ignore
/// mod pendulum {
///     dynagen_macros::robot! {
///         name: pendulum,
///         link base {},
///         link arm { mass: 1.0, com: [0, 0, -0.5], inertia: [0.1, 0.1, 0.01, 0, 0, 0] },
///         joint hinge: revolute(base -> arm) { origin: [0, 0, 0], rpy: [0, 0, 0], axis: [0, 1, 0] },
///     }
/// }
/// ```
///
/// - `name: ident` (required first), then optionally `gravity: [x, y, z]`
///   and the code-generation options of the [crate docs](crate) as
///   `option: value`;
/// - `link NAME { mass: m, com: [x, y, z], inertia: [ixx, iyy, izz, ixy, ixz, iyz] }`
///   (inertia about the centre of mass, kg·m²; `{}` is a massless link);
/// - `joint NAME: TYPE(PARENT -> CHILD) { origin: [x, y, z], rpy: [r, p, y], axis: [x, y, z], limits: [lower, upper, velocity, effort] }`
///   with TYPE `revolute`, `continuous`, `prismatic` or `fixed`; every
///   field optional (origin and rpy zero; axis required unless fixed).
///
/// Conventions are URDF's: the joint frame is the child link's frame, rpy is
/// fixed-axis X, Y, Z. Items are separated by commas.
#[proc_macro]
pub fn robot(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    match syn::parse::<robot::RobotInput>(input).and_then(robot::expand) {
        Ok(t) => t.into(),
        Err(e) => e.to_compile_error().into(),
    }
}

/// The code-generation options a macro was given.
#[derive(Default)]
pub(crate) struct MacroOptions {
    functions: Option<Vec<Ident>>,
    scalar: Option<ScalarType>,
    forward_dynamics: Option<ForwardDynamicsMethod>,
    snap_rounding: Option<bool>,
}

impl MacroOptions {
    /// Parses the value of option `key` (the separator is already read), or
    /// returns `Ok(false)` when `key` is not a code-generation option.
    pub(crate) fn parse_value(&mut self, key: &Ident, input: ParseStream) -> syn::Result<bool> {
        let name = key.to_string();
        match name.as_str() {
            "functions" => {
                let content;
                bracketed!(content in input);
                let list: Punctuated<Ident, Token![,]> = content.parse_terminated(Ident::parse, Token![,])?;
                for f in &list {
                    if !dynagen::codegen::FUNCTION_NAMES.contains(&f.to_string().as_str()) {
                        return Err(syn::Error::new(
                            f.span(),
                            format!(
                                "unknown function `{f}`; the functions are {}",
                                dynagen::codegen::FUNCTION_NAMES.join(", ")
                            ),
                        ));
                    }
                }
                self.functions = Some(list.into_iter().collect());
            }
            "scalar" => {
                let v: Ident = input.parse()?;
                self.scalar = Some(match v.to_string().as_str() {
                    "f64" => ScalarType::F64,
                    "f32" => ScalarType::F32,
                    _ => return Err(syn::Error::new(v.span(), "expected `f64` or `f32`")),
                });
            }
            "forward_dynamics" => {
                let v: Ident = input.parse()?;
                self.forward_dynamics = Some(match v.to_string().as_str() {
                    "aba" => ForwardDynamicsMethod::Aba,
                    "ldlt" => ForwardDynamicsMethod::Ldlt,
                    _ => return Err(syn::Error::new(v.span(), "expected `aba` or `ldlt`")),
                });
            }
            "snap_rounding" => self.snap_rounding = Some(input.parse::<LitBool>()?.value),
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The options as a builder's, with `source` for the header.
    pub(crate) fn apply(&self, builder: Builder, source: String) -> Builder {
        let mut o = CodegenOptions::default().source(source);
        if let Some(s) = self.scalar {
            o = o.scalar(s);
        }
        if let Some(m) = self.forward_dynamics {
            o = o.forward_dynamics(m);
        }
        if let Some(s) = self.snap_rounding {
            o = o.snap_rounding(s);
        }
        if let Some(f) = &self.functions {
            let names: Vec<String> = f.iter().map(Ident::to_string).collect();
            // Checked when parsed.
            o = o.functions(Functions::from_names(&names).unwrap_or_default());
        }
        builder.options(o)
    }
}

/// The options every macro accepts, for error messages.
pub(crate) const OPTION_NAMES: &str = "functions, scalar, forward_dynamics, snap_rounding";

struct UrdfInput {
    path: LitStr,
    options: MacroOptions,
}

impl Parse for UrdfInput {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let path: LitStr = input.parse()?;
        let mut options = MacroOptions::default();
        while !input.is_empty() {
            input.parse::<Token![,]>()?;
            if input.is_empty() {
                break;
            }
            let key: Ident = input.parse()?;
            input.parse::<Token![=]>()?;
            if !options.parse_value(&key, input)? {
                return Err(syn::Error::new(
                    key.span(),
                    format!("unknown option `{key}`; the options are {OPTION_NAMES}"),
                ));
            }
        }
        Ok(UrdfInput { path, options })
    }
}

/// The module's items from the generated source.
pub(crate) fn items(source: &str, span: Span) -> syn::Result<TokenStream> {
    source
        .parse::<TokenStream>()
        .map_err(|e| syn::Error::new(span, format!("dynagen produced code that does not parse (a bug): {e}")))
}

fn expand_urdf(input: UrdfInput) -> syn::Result<TokenStream> {
    let span = input.path.span();
    let given = input.path.value();
    let root = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let path = std::path::Path::new(&root).join(&given);
    if !path.is_file() {
        return Err(syn::Error::new(
            span,
            format!("no such file: {given:?} (paths are relative to the crate's root, the folder of its Cargo.toml)"),
        ));
    }
    let builder = input.options.apply(Builder::new().urdf(&path), given.clone());
    let module = builder.generate_module().map_err(|e| {
        let text = e.to_string();
        syn::Error::new(span, text.strip_prefix("dynagen: ").unwrap_or(&text).to_string())
    })?;
    let body = items(&module.source, span)?;
    let abs = path.canonicalize().unwrap_or(path).display().to_string();
    Ok(quote! {
        // Rebuild when the robot file changes.
        const _: &[u8] = include_bytes!(#abs);
        #body
    })
}
