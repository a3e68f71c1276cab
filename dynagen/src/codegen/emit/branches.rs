//! The branches of a function emitted as a loop (`trace/branches.rs`): for
//! each group, the body `NAME_branchG` of one branch, the table
//! `NAME_BRANCHG` of its constants (one row per branch), and the statements
//! in `NAME_sc` that run the body for each row.

use super::statements::{self, BodyStyle, Dim, Param, Shape, Signature, Sizes};
use super::syntax::ident;
use crate::codegen::trace::branches::{results_name, BranchBody, Branched, Kind, MOTION};
use crate::codegen::{CodegenError, CodegenOptions};
use crate::model::Model;
use quote::{format_ident, quote};
use syn::{Expr, Stmt};

/// The name of group `g`'s body.
fn body_name(name: &str, g: usize) -> String {
    format!("{name}_branch{g}")
}

/// The name of group `g`'s table.
fn table_name(name: &str, g: usize) -> String {
    format!("{}_BRANCH{g}", name.to_uppercase())
}

/// The parameters of a branch body: its constants, its parent's motion, then
/// its joints' sines, cosines, positions (where it reads them), velocities
/// and accelerations (τ).
fn params(x: &BranchBody) -> Vec<Param> {
    let nb = x.group.lanes[0].len();
    let mut list = vec![Param::fixed("k", x.table[0].len())];
    if x.motion() {
        list.push(Param::fixed("m", MOTION));
    }
    for name in ["s", "c", "q", "qd", "qdd"] {
        let read = x.body.function.input_names().iter().any(|n| n == name);
        if read && (name != "q" || x.body.function.uses_input("q")) {
            list.push(Param::fixed(name, nb));
        }
    }
    list
}

/// The items of `f`'s branches: each group's body (private, inlined into
/// the loop) and table.
pub(super) fn items(
    name: &str,
    b: &Branched,
    model: &Model,
    options: &CodegenOptions,
    sizes: Sizes,
) -> Result<Vec<syn::Item>, CodegenError> {
    let mut items = Vec::new();
    let style = BodyStyle { split_lets: None, ..BodyStyle::of(options) };
    for (g, x) in b.branches.iter().enumerate() {
        let nb = x.group.lanes[0].len();
        let first = |lane: &Vec<usize>| model.bodies[lane[0]].joint.name.clone();
        let starts: Vec<String> = x.group.lanes.iter().map(|l| format!("`{}`", first(l))).collect();
        let parent = match x.group.parent {
            Some(p) => format!("`{}`", model.bodies[p].name),
            None => "the base".to_string(),
        };
        let what = match x.kind {
            Kind::Rnea { .. } => {
                "its parent's motion `m` (ω, ω̇, the origin's acceleration and U = [ω̇×] + [ω×][ω×] row by row, \
                 in the parent's frame) and its joints' state; returns their τ, then the wrench it puts on its \
                 parent (moment, force; parent frame)"
            }
            Kind::Crba => {
                "its joints' sines and cosines; returns its own block of M (row after row), each joint's Iᶜ·S in \
                 its parent's frame (moment, force), and its composite inertia there (mass, m·c, Ī as xx, yy, zz, \
                 xy, xz, yz)"
            }
        };
        let doc = format!(
            " One branch of [`{name}_sc`] ({nb} joints), run for each of those that hang alike from {parent}, from \
             {} on. Takes its constants `k` (a row of [`{}`]) and {what}.",
            starts.join(", "),
            table_name(name, g)
        );
        let signature = Signature {
            name: body_name(name, g),
            params: params(x),
            output: Shape::Vector(Dim::Fixed(x.outputs())),
            calls: None,
        };
        let body =
            statements::emit_function(&x.body.function, &signature, options.scalar, options.trig, sizes, &doc, style)?;
        // Only the body the loop inlines: with the run-time dispatch its
        // generic `_on` (documented as the branch), else the function
        // itself, made private and inlined.
        let on = format!("{}_on", signature.name);
        let emitted = if style.dispatch { on.clone() } else { signature.name.clone() };
        for item in body {
            let syn::Item::Fn(mut func) = item else { continue };
            if func.sig.ident != emitted {
                continue;
            }
            func.vis = syn::Visibility::Inherited;
            func.attrs.retain(|a| !a.path().is_ident("doc") && !a.path().is_ident("inline"));
            let doc = doc.lines();
            func.attrs.splice(0..0, doc.map(|line| -> syn::Attribute { syn::parse_quote!(#[doc = #line]) }));
            func.attrs.push(syn::parse_quote!(#[inline(always)]));
            items.push(syn::Item::Fn(func));
        }
        let ty = statements::scalar_type(options.scalar);
        let p = proc_macro2::Literal::usize_unsuffixed(x.table[0].len());
        let l = proc_macro2::Literal::usize_unsuffixed(x.table.len());
        let rows = x.table.iter().map(|row| {
            let entries = row.iter().map(|&v| super::syntax::float(v, options.scalar).expect("finite constants"));
            quote!([#(#entries),*])
        });
        let table = format_ident!("{}", table_name(name, g));
        let doc = format!(" The constants of [`{emitted}`], one row per branch: {}.", starts.join(", "));
        items.push(
            syn::parse2(quote! {
                #[doc = #doc]
                #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]
                const #table: [[#ty; #p]; #l] = [#(#rows),*];
            })
            .map_err(|e| CodegenError::Internal(e.to_string()))?,
        );
    }
    Ok(items)
}

/// The statements of `NAME_sc` that run each group's body for each branch,
/// from the parents' motions (`args`, [`MOTION`] a group): the results go
/// to `r0`, `r1`, … (branch after branch), which the rest of the body reads.
pub(super) fn glue(
    name: &str,
    b: &Branched,
    floating: bool,
    dispatch: bool,
    args: &[Expr],
) -> Result<Vec<Stmt>, CodegenError> {
    let (q_off, v_off) = if floating { (7, 6) } else { (0, 0) };
    let mut stmts = Vec::new();
    let mut motions = args.chunks(MOTION);
    for (g, x) in b.branches.iter().enumerate() {
        let m = format_ident!("m_b{g}");
        let r = ident(&results_name(g));
        let call = match dispatch {
            true => {
                let f = format_ident!("{}_on", body_name(name, g));
                quote!(#f::<I>)
            }
            false => {
                let f = format_ident!("{}", body_name(name, g));
                quote!(#f)
            }
        };
        let table = format_ident!("{}", table_name(name, g));
        let mut locals = Vec::new();
        let mut call_args = vec![quote!(&#table[l])];
        if x.motion() {
            let motion = motions.next().expect("a motion per group that reads it");
            locals.push(quote!(let #m = [#(#motion),*];));
            call_args.push(quote!(&#m));
        }
        for p in params(x).iter().skip(call_args.len()) {
            let local = format_ident!("{}_b{g}", p.name);
            let source = ident(&p.name);
            let skip = match p.name.as_str() {
                "q" => q_off,
                "qd" | "qdd" => v_off,
                _ => 0,
            };
            let rows = x.group.lanes.iter().map(|lane| {
                let entries = lane.iter().map(|&j| proc_macro2::Literal::usize_unsuffixed(skip + j));
                quote!([#(#source[#entries]),*])
            });
            locals.push(quote!(let #local = [#(#rows),*];));
            call_args.push(quote!(&#local[l]));
        }
        let len = proc_macro2::Literal::usize_unsuffixed(x.outputs());
        let total = proc_macro2::Literal::usize_unsuffixed(x.group.lanes.len() * x.outputs());
        let block: syn::Block = syn::parse2(quote! {{
            #(#locals)*
            let mut #r = [0.0; #total];
            for (l, out) in #r.chunks_exact_mut(#len).enumerate() {
                out.copy_from_slice(&#call(#(#call_args),*));
            }
        }})
        .map_err(|e| CodegenError::Internal(e.to_string()))?;
        stmts.extend(block.stmts);
    }
    Ok(stmts)
}
