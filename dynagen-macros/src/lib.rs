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
//! time: not `dynagen`, not even `std` (with the default `trig = batched`;
//! `trig = std` calls `f64::sin_cos`). `dynagen` does not re-export these
//! macros, because this crate depends on it (a re-export would make a
//! dependency cycle).
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
//! | `functions` | `[inverse_dynamics, mass_matrix, bias_forces, gravity_torques, forward_dynamics]` (the five of the contract), and on request `coriolis`, `inverse_dynamics_derivatives`, `forward_dynamics_derivatives`, `mass_matrix_inverse` | all five |
//! | `scalar` | `f64`, `f32` | `f64` |
//! | `forward_dynamics` | `auto`, `aba`, `ldlt` | `auto` (the faster of the two unless it is less accurate; the header says which) |
//! | `snap_rounding` | `true`, `false` | `true` |
//! | `trig` | `batched` (the module's own `sin_cos_array`: no_std, no dependency, faster than std's), `std` (`f64::sin_cos`), `libm`, `inputs` (only the `NAME_sc` functions) | `batched` |
//! | `split_lets` | a number of `let`s, or `none` | 2500 (longer bodies become `#[inline(never)]` parts) |
//! | `fma` | `true`, `false`: `a*b + c` as `fma(a, b, c)`, one rounding where the target has a fused multiply-add | `true` |
//! | `allow_nonphysical_inertia` | `true`, `false`: accept links whose rotational inertia is not positive semi-definite, with a warning (the mass matrix may be indefinite) | `false` (refused) |
//! | `dispatch` | `true`, `false`: on x86-64 builds without the `avx2` and `fma` target features, also compile each function for AVX2 and FMA, and for AVX-512 (F, VL, DQ), and run the copy the processor has (results differ in the last bits between machines with and without FMA) | `true` |
//! | `branch_loops` | `true`, `false`: in τ, h, M and the ABA forward dynamics, sibling subtrees of one shape (legs, arms) as one body run on all of them (in vector lanes) over a table of their constants | `true` |
//! | `floating_base` | `true`, `false`: the robot's root link moves freely (`NQ = DOF + 7`, `NV = DOF + 6`; every scene key, frame function and derivative too) | `false` (a URDF `floating` root joint: `true`) |
//! | `mimic` | `follow`: a joint with a `<mimic>` (in `robot!`, a `mimic` field) follows its master, `q = multiplier·q_master + offset`, and is not in `DOF` and `JOINT_NAMES`; `independent`: it is a joint of its own | `follow` |
//!
//! # Scenes (both macros)
//!
//! A scene (see `dynagen::scene`) comes from a TOML file, `scene =
//! "scenes/controller.toml"` (relative to the crate's root), from inline
//! keys, or both: the keys then change the file's scene, in the order
//! given (an `armature` entry replaces the file's for that joint, a
//! `frame_pose` adds a function, …). The module is then that scene's
//! (`dynagen::codegen::generate_scene`; without them it is the default
//! scene's, the plain module): the functions asked for, the scene's
//! constants folded in, its run-time inputs as arguments (`gravity: &[f64;
//! 3]`, `f_tip: &[f64; 6]`, `payload_LINK: &[f64; 10]`). Names are
//! identifiers or strings; inside braces `=` and `:` both work.
//!
//! | key | value |
//! | --- | --- |
//! | `gravity` | `none`, `input`, `default` or `[x, y, z]` (in `robot!`, `gravity: [x, y, z]` is the robot's own gravity) |
//! | `tip_wrench` | `LINK`: the wrench at LINK is an argument |
//! | `subtree` | `{ root = LINK, tips = [LINK, …] }` |
//! | `lock` | `{ JOINT = position, … }` |
//! | `armature`, `viscous`, `coulomb` | `{ JOINT = value, … }` |
//! | `coulomb_velocity` | a number (rad/s or m/s) |
//! | `payload` | `{ link = LINK, mass = kg, com = [x, y, z], inertia = [ixx, iyy, izz, ixy, ixz, iyz] }` (repeat the key for several) |
//! | `payload_input` | `LINK`: its payload is an argument |
//! | `frame_pose`, `frame_jacobian`, `frame_world_jacobian`, `frame_acceleration_bias` | `[FRAME, …]`: `frame_pose_FRAME(q)`, `frame_jacobian_FRAME(q)` (body), `frame_world_jacobian_FRAME(q)`, `frame_acceleration_bias_FRAME(q, qd)` (J̇q̇) |
//! | `target` | `std` (std allowed: the trigonometry is the `trig` option's, `batched` by default), `no_std_libm`, `no_std_sincos` |
//!
//! ```ignore
//! mod ur5_tau {
//!     dynagen_macros::urdf!("robots/ur5.urdf", functions = [inverse_dynamics], gravity = none,
//!                           lock = { wrist_3_joint = 0.0 });
//! }
//! ```
//!
//! Every mistake is a compile error at the token it is about: an unknown
//! option or function, a number that is not one, a missing file (at the
//! path), a model error such as a massless subtree or a missing link (at
//! the joint's or link's name), a scene error such as an unknown or locked
//! joint or a tip not below the root (at the name the error is about; at
//! the scene file's path for an error in the file).

use dynagen::codegen::{Builder, ForwardDynamicsMethod, ScalarType, Trig};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{bracketed, Ident, LitBool, LitInt, LitStr, Token};

mod robot;
mod scene;

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
///   field optional (origin and rpy zero; axis required unless fixed);
///   `mimic: MASTER, multiplier: k, offset: o` makes the joint follow the
///   joint MASTER, `q = k·q_MASTER + o` (URDF's `<mimic>`; k 1 and o 0 by
///   default): it is not in `DOF` and `JOINT_NAMES` (option `mimic:
///   independent` makes it a joint of its own).
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
    trig: Option<Trig>,
    split_lets: Option<Option<usize>>,
    fma: Option<bool>,
    floating_base: Option<bool>,
    branch_loops: Option<bool>,
    dispatch: Option<bool>,
    allow_nonphysical_inertia: Option<bool>,
    mimic: Option<dynagen::model::MimicJoints>,
    scene: scene::SceneOptions,
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
                    if dynagen::codegen::Function::from_name(&f.to_string()).is_none() {
                        return Err(syn::Error::new(
                            f.span(),
                            format!(
                                "unknown function `{f}`; the functions are {}",
                                dynagen::codegen::Function::NAMES.join(", ")
                            ),
                        ));
                    }
                }
                self.functions = Some(list.into_iter().collect());
            }
            "scalar" => self.scalar = Some(parse_ident(input)?),
            "forward_dynamics" => self.forward_dynamics = Some(parse_ident(input)?),
            "snap_rounding" => self.snap_rounding = Some(input.parse::<LitBool>()?.value),
            "trig" => self.trig = Some(parse_ident(input)?),
            "split_lets" => {
                self.split_lets = Some(if input.peek(Ident) {
                    let v: Ident = input.parse()?;
                    if v != "none" {
                        return Err(syn::Error::new(v.span(), "expected a number of lets or `none`"));
                    }
                    None
                } else {
                    let n: LitInt = input.parse()?;
                    match n.base10_parse::<usize>()? {
                        0 => {
                            return Err(syn::Error::new(
                                n.span(),
                                "a part needs at least one `let`; `none` never splits",
                            ))
                        }
                        n => Some(n),
                    }
                });
            }
            "fma" => self.fma = Some(input.parse::<LitBool>()?.value),
            "floating_base" => self.floating_base = Some(input.parse::<LitBool>()?.value),
            "branch_loops" => self.branch_loops = Some(input.parse::<LitBool>()?.value),
            "dispatch" => self.dispatch = Some(input.parse::<LitBool>()?.value),
            "allow_nonphysical_inertia" => self.allow_nonphysical_inertia = Some(input.parse::<LitBool>()?.value),
            "mimic" => self.mimic = Some(parse_ident(input)?),
            _ => return self.scene.parse_value(key, input),
        }
        Ok(true)
    }

    /// The options as a builder's, with `source` for the header; the scene
    /// keys (a file, inline keys) give the scene.
    pub(crate) fn apply(&self, builder: Builder, source: String) -> syn::Result<Builder> {
        let mut b = self.scene.apply(builder.source(&source))?;
        if let Some(s) = self.scalar {
            b = b.scalar(s);
        }
        if let Some(m) = self.forward_dynamics {
            b = b.forward_dynamics(m);
        }
        if let Some(s) = self.snap_rounding {
            b = b.snap_rounding(s);
        }
        if let Some(t) = self.trig {
            b = b.trig(t);
        }
        if let Some(n) = self.split_lets {
            b = b.split_lets(n);
        }
        if let Some(f) = self.fma {
            b = b.fma(f);
        }
        if let Some(d) = self.dispatch {
            b = b.runtime_dispatch(d);
        }
        if let Some(f) = self.branch_loops {
            b = b.branch_loops(f);
        }
        if let Some(f) = self.floating_base {
            b = b.floating_base(f);
        }
        if let Some(a) = self.allow_nonphysical_inertia {
            b = b.allow_nonphysical_inertia(a);
        }
        if let Some(m) = self.mimic {
            b = b.mimic_joints(m);
        }
        if let Some(f) = &self.functions {
            b = b.functions(&f.iter().map(Ident::to_string).collect::<Vec<_>>());
        }
        Ok(b)
    }

    /// The span for an error of the builder.
    pub(crate) fn error_span(&self, error: &dynagen::codegen::BuildError, default: Span) -> Span {
        self.scene.error_span(error, default)
    }

    /// `const _: &[u8] = include_bytes!(…);` for the scene file, if any, so
    /// that the crate is rebuilt when it changes.
    pub(crate) fn rebuild_on_scene_change(&self) -> TokenStream {
        match self.scene.file_path() {
            Some(p) => quote!(
                const _: &[u8] = include_bytes!(#p);
            ),
            None => quote!(),
        }
    }
}

/// A value spelled as an identifier (`f32`, `ldlt`, `batched`), parsed by
/// the option's own `FromStr`: the spelling the command line uses too.
fn parse_ident<T: std::str::FromStr<Err = String>>(input: ParseStream) -> syn::Result<T> {
    let v: Ident = input.parse()?;
    v.to_string().parse().map_err(|e: String| syn::Error::new(v.span(), e))
}

/// The options every macro accepts, for error messages.
pub(crate) const OPTION_NAMES: &str = "functions, scalar, forward_dynamics, snap_rounding, trig, split_lets, fma, floating_base, branch_loops, \
                                       dispatch, allow_nonphysical_inertia, mimic, scene, gravity, tip_wrench, subtree, lock, armature, viscous, coulomb, \
                                       coulomb_velocity, payload, payload_input, frame_pose, frame_jacobian, frame_world_jacobian, \
                                       frame_acceleration_bias, target";

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
    let builder = input.options.apply(Builder::new().urdf(&path), given.clone())?;
    let module = builder
        .generate_module()
        .map_err(|e| syn::Error::new(input.options.error_span(&e, span), scene::SceneOptions::error_message(&e)))?;
    let body = items(&module.source, span)?;
    let abs = path.canonicalize().unwrap_or(path).display().to_string();
    let scene = input.options.rebuild_on_scene_change();
    Ok(quote! {
        // Rebuild when the robot file (or the scene file) changes.
        const _: &[u8] = include_bytes!(#abs);
        #scene
        #body
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A URDF and scene whose every name tries to break out of its place
    /// (`dynagen/tests/data/hostile_names.*`: newlines, CR, `*/`, quotes,
    /// U+2028, bidirectional controls): `urdf!` expands to the contract's
    /// items only, and `JOINT_NAMES` holds the names as they are.
    #[test]
    fn hostile_names_expand_to_no_item_of_their_own() {
        let input: UrdfInput = syn::parse_str(
            r#""../dynagen/tests/data/hostile_names.urdf", scene = "../dynagen/tests/data/hostile_names.toml""#,
        )
        .unwrap();
        let file: syn::File = syn::parse2(expand_urdf(input).unwrap()).unwrap();
        let mut public = Vec::new();
        let mut joint_names = Vec::new();
        for item in &file.items {
            let (name, is_pub) = match item {
                syn::Item::Fn(f) => (f.sig.ident.to_string(), matches!(f.vis, syn::Visibility::Public(_))),
                syn::Item::Const(c) => {
                    if c.ident == "JOINT_NAMES" {
                        let syn::Expr::Array(a) = &*c.expr else { panic!("JOINT_NAMES is not an array") };
                        for e in &a.elems {
                            let syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) = e else {
                                panic!("JOINT_NAMES holds a non-literal")
                            };
                            joint_names.push(s.value());
                        }
                    }
                    (c.ident.to_string(), matches!(c.vis, syn::Visibility::Public(_)))
                }
                _ => continue,
            };
            if is_pub {
                public.push(name);
            }
        }
        public.sort();
        let frame = "h_fn_injected"; // frame "h\n}\nfn injected() {\n", in snake case
        let mut expected: Vec<String> =
            ["DOF", "NQ", "NV", "JOINT_NAMES", "sin_cos_all", "sin_cos_array", "sin_cos_kernel"]
                .iter()
                .map(|s| s.to_string())
                .chain(
                    ["inverse_dynamics", "gravity_torques", "inverse_dynamics_sc", "gravity_torques_sc"]
                        .iter()
                        .map(|s| s.to_string()),
                )
                .chain([format!("frame_pose_{frame}"), format!("frame_pose_{frame}_sc")])
                .chain(["frame_jacobian_c_pub_fn_injected_u32_42_code_script".to_string()])
                .chain(["frame_jacobian_c_pub_fn_injected_u32_42_code_script_sc".to_string()])
                .collect();
        expected.sort();
        assert_eq!(public, expected);
        let inj = "pub fn injected() -> u32 { 42 }";
        assert_eq!(
            joint_names,
            [
                format!("J\n{inj}\n//"),
                format!("J\r\n{inj}\r//"),
                format!("J */ {inj} /* `</code><script>`"),
                format!("J\u{2028}{inj}\u{2029}//"),
                format!("J\"); {inj} //\\"),
                "J\u{85}\u{7f}\t\\u{a}".to_string(),
            ]
        );
    }
}
