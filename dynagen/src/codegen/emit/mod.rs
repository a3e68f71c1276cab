//! Emitting: traced functions → the module's Rust source. Each emitted
//! function becomes its body `NAME_sc` (`statements.rs`, long bodies split
//! into parts by `split.rs`) and, unless the caller brings the sines and
//! cosines, its public `NAME` (`wrapper.rs`); `header.rs` writes what the
//! module was made from; the sine and cosine kernel's text is appended.

mod branches;
mod header;
mod literal;
mod products;
mod split;
mod statements;
mod syntax;
mod text;
mod wrapper;

pub use literal::float_literal_text;
pub(crate) use products::loop_ops;
pub(crate) use statements::{tidy_dispatch, BodyStyle, Dim, Param, Shape, Signature, Sizes};
pub(crate) use text::{doc_code, identifier};

use super::trace::fd_choice::FdChoice;
use super::{sin_cos, CodegenError, CodegenOptions, GeneratedFunction, SnappedConstant, Trig};
use crate::model::JointKind;
use crate::scene::SceneModel;
use quote::quote;

/// The name of a run-time payload's argument: `payload_` and the link's
/// name in snake case (ASCII letters and digits, other characters `_`).
pub fn payload_argument(link: &str) -> String {
    identifier_name("payload", link)
}

/// `{prefix}_{name}`, the name made an identifier's part ([`text::identifier_part`]).
pub(crate) fn identifier_name(prefix: &str, name: &str) -> String {
    match text::identifier_part(name) {
        part if part.is_empty() => prefix.to_string(),
        part => format!("{prefix}_{part}"),
    }
}

/// Marks every item `#[allow(dead_code)]`: a crate that includes the module
/// and calls one of its functions must compile without a warning about the
/// others (an `include!`d file cannot carry the inner attribute that would
/// say it once). Items reached from an allowed item count as used, so the
/// private helpers need nothing.
fn allow_unused(items: &mut [syn::Item]) {
    let allow: syn::Attribute = syn::parse_quote!(#[allow(dead_code)]);
    for item in items {
        let attrs = match item {
            syn::Item::Fn(f) => &mut f.attrs,
            syn::Item::Const(c) => &mut c.attrs,
            syn::Item::Static(s) => &mut s.attrs,
            syn::Item::Trait(t) => &mut t.attrs,
            syn::Item::Struct(s) => &mut s.attrs,
            _ => continue,
        };
        attrs.push(allow.clone());
    }
}

/// What the emitted module is made of.
pub(crate) struct ModuleParts<'a> {
    /// The scene (its original reduced model: the header's hash and names).
    pub scene: &'a SceneModel,
    /// The prepared scene the functions were traced on.
    pub prepared: &'a SceneModel,
    pub options: &'a CodegenOptions,
    pub functions: &'a [GeneratedFunction],
    pub fd: &'a FdChoice,
    pub snapped: &'a [SnappedConstant],
    pub hash: u64,
}

/// The module's source: header, constants, the emitted functions, kernel.
pub(crate) fn module_source(parts: &ModuleParts) -> Result<String, CodegenError> {
    let ModuleParts { scene, prepared, options, functions, .. } = *parts;
    let model = &prepared.model;
    let n = model.dof();
    let joint_names = model.joint_names();
    let n_lit = proc_macro2::Literal::usize_unsuffixed(n);
    let sizes = Sizes::of(model);
    let floating = sizes.floating();
    let lengths = if floating {
        let (nq, nv) = (sizes.nq, sizes.nv);
        let (nq, nv) = (proc_macro2::Literal::usize_unsuffixed(nq), proc_macro2::Literal::usize_unsuffixed(nv));
        quote! {
            #[doc = " The length of `q`: the base's position (3, world frame) and quaternion (x, y, z, w; world ← base), then the joints."]
            pub const NQ: usize = #nq;
            #[doc = " The length of the velocity-side vectors (`qd`, `qdd`, `tau`, the outputs): the base's body twist (ω, v; base frame), then the joints."]
            pub const NV: usize = #nv;
        }
    } else {
        quote! {
            #[doc = " The length of `q` (a fixed base: `DOF`)."]
            pub const NQ: usize = DOF;
            #[doc = " The length of the velocity-side vectors (a fixed base: `DOF`)."]
            pub const NV: usize = DOF;
        }
    };
    let joints_doc = if floating {
        " The joint names, in the order of `q[7..]`, of the velocity-side vectors' `[6..]` and of `s` and `c`."
    } else {
        " The joint names, in the order of every index of the functions below."
    };
    let consts = quote! {
        #[doc = " The number of degrees of freedom (joints)."]
        pub const DOF: usize = #n_lit;
        #lengths
        #[doc = #joints_doc]
        pub const JOINT_NAMES: [&str; DOF] = [#(#joint_names),*];
    };
    let mut items = wrapper::parse_items(consts)?;
    if functions.iter().any(|f| f.emitted && matches!(f.function.shape(floating), Shape::Matrices(..))) {
        let ty = statements::scalar_type(options.scalar);
        items.extend(wrapper::parse_items(match floating {
            false => quote! {
                #[doc = " A DOF × DOF matrix `[row][col]`, as the derivatives return them (`[output][input]`)."]
                pub type DofMatrix = [[#ty; DOF]; DOF];
            },
            true => quote! {
                #[doc = " An NV × NV matrix `[row][col]`, as the derivatives return them (`[output][input]`)."]
                pub type NvMatrix = [[#ty; NV]; NV];
            },
        })?);
    }
    items.push(wrapper::parse_item(sin_cos::sin_cos_all_item(options.scalar))?);
    // NAME_sc reads q for its prismatic joints, and a floating base's position and quaternion.
    let has_prismatic = floating || model.bodies.iter().any(|b| b.joint.kind == JointKind::Prismatic);
    let q_param = Param::sized("q", if floating { Dim::Nq } else { Dim::Dof });
    let mut split_functions = Vec::new();
    let mut products = false;
    for f in functions.iter().filter(|f| f.emitted) {
        // The forward dynamics' derivatives as their factors and a loop
        // (products.rs): the factors' body is emitted as `NAME_factors`.
        let factors_name = format!("{}_factors", f.name);
        let (sc, name) = match (&f.factors, &f.branched) {
            (Some((factors, _)), _) => (factors, &factors_name),
            (None, Some(b)) => (&b.body, &f.name),
            (None, None) => (&f.sin_cos_inputs, &f.name),
        };
        let first_item = items.len();
        let ldlt = f.method == Some(super::ForwardDynamicsMethod::Ldlt);
        let ps = f.function.params(prepared);
        // one sine and cosine per joint, then the mimic joints' own angles
        let angles = |name| match sc.extra_angles.len() {
            0 => Param::dof(name),
            _ => Param::fixed(name, sc.angles()),
        };
        if options.trig == Trig::Inputs && !sc.extra_angles.is_empty() {
            return Err(CodegenError::Unsupported(format!(
                "{name}: a mimic joint turns by an angle of its own (a multiplier other than ±1 or an offset), \
                 which sines and cosines given by the caller (trig inputs) have no entry for: use another trig \
                 option, or mimic joints as independent joints"
            )));
        }
        let mut sc_params = vec![angles("s"), angles("c")];
        if has_prismatic {
            sc_params.push(q_param.clone());
        }
        sc_params.extend(ps[1..].iter().cloned());
        let sc_name = format!("{name}_sc");
        let signature = Signature {
            name: sc_name.clone(),
            params: sc_params.clone(),
            output: f.function.shape(floating),
            calls: None,
        };
        let sc_count = super::counted(&sc.function, options.fma);
        let doc = match f.factors {
            Some(_) => format!(
                " The factors of [`{}_sc`]: ∂τ/∂q and ∂τ/∂q̇ at its q̈ = FD(q, q̇, τ), and M⁻¹ ({} FP ops).",
                f.name,
                sc_count.fp_ops()
            ),
            None => {
                format!("{}\n\n{}", f.function.doc(prepared, ldlt, &sc_count), wrapper::sc_doc(has_prismatic, floating))
            }
        };
        let style = BodyStyle::of(options);
        let mut lanes = Vec::new();
        if let Some(b) = &f.branched {
            let (branch_items, in_lanes) = branches::items(name, b, model, options, sizes)?;
            items.extend(branch_items);
            lanes = in_lanes;
        }
        let glue = |phase: usize, args: &[syn::Expr]| match &f.branched {
            Some(b) => branches::glue(name, b, floating, style.dispatch, &lanes, phase, args),
            None => Ok(Vec::new()),
        };
        let signature = Signature {
            calls: f.branched.as_ref().map(|b| statements::Calls {
                outputs: b.outputs,
                phases: (0..b.phases()).map(|p| b.args_before(p + 1) - b.args_before(p)).collect(),
                glue: &glue,
            }),
            ..signature
        };
        let emitted =
            statements::emit_function(&sc.function, &signature, options.scalar, options.trig, sizes, &doc, style)?;
        let sc_split = split::parts_of(&emitted);
        if let Some(parts) = sc_split {
            split_functions.push((sc_name.clone(), parts));
        }
        items.extend(emitted);
        let ret = f.function.shape(floating).tokens(options.scalar);
        if options.trig != Trig::Inputs {
            let doc = match f.factors {
                Some(_) => format!(" The factors of [`{}`]: the sines and cosines, then [`{sc_name}`].", f.name),
                None => format!(
                    "{}\n\n The sines and cosines of the joint angles by {}, then [`{sc_name}`].",
                    f.function.doc(prepared, ldlt, &f.op_count),
                    wrapper::trig_source(options.trig, options.scalar)
                ),
            };
            let body = wrapper::ScBody { trace: sc, has_prismatic, split: sc_split.is_some() };
            items.extend(wrapper::parse_items(wrapper::wrapper(name, &ps, ret.clone(), body, options, &doc))?);
        }
        if let Some((_, count)) = &f.factors {
            // The factors stay private; `NAME` and `NAME_sc` multiply them.
            for item in &mut items[first_item..] {
                if let syn::Item::Fn(func) = item {
                    func.vis = syn::Visibility::Inherited;
                }
            }
            let how = format!(
                "\n\n Emitted as `{factors_name}` ({} FP ops) and the products −M⁻¹∂τ in a loop \
                 (`derivative_products`), which counts fewer operations than the whole trace.",
                count.fp_ops()
            );
            let doc = format!("{}{how}", f.function.doc(prepared, ldlt, &f.op_count));
            let sc_doc = format!(
                "{}{how}\n\n{}",
                f.function.doc(prepared, ldlt, &f.sin_cos_inputs.function.op_count()),
                wrapper::sc_doc(has_prismatic, floating)
            );
            let tokens = products::wrappers(&f.name, &factors_name, &ps, &sc_params, ret, options, [&doc, &sc_doc]);
            items.extend(wrapper::parse_items(tokens)?);
            products = true;
        }
    }
    if products {
        items.extend(wrapper::parse_items(products::helper(options))?);
    }
    allow_unused(&mut items);
    let file = syn::File { shebang: None, frontmatter: None, attrs: vec![], items };
    let body = tidy_dispatch(&prettyplease::unparse(&file));
    let facts =
        header::HeaderFacts { scene, options, fd: parts.fd, functions, snapped: parts.snapped, hash: parts.hash };
    let header = header::header(&facts) + &split::header_note(options.split_lets, &split_functions);
    let kernel = sin_cos::kernel_source(options.scalar, options.runtime_dispatch);
    let source = format!("{header}\n{body}\n{kernel}");
    text::check_source(&header, &source)?;
    Ok(source)
}
