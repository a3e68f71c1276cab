//! `NAME(q, …)`: the public function that computes the sines and cosines
//! its body reads and calls `NAME_sc`, with the AVX-512 and the AVX2 and
//! FMA copies of the run-time dispatch.

use super::statements::{checks, TIERS};
use super::{literal, Param};
use crate::codegen::sin_cos;
use crate::codegen::trace::{Angle, SinCosTrace};
use crate::codegen::{CodegenError, CodegenOptions, ScalarType, Trig};
use quote::quote;

pub(super) fn parse_item(tokens: proc_macro2::TokenStream) -> Result<syn::Item, CodegenError> {
    syn::parse2(tokens).map_err(|e| CodegenError::Internal(e.to_string()))
}

pub(super) fn sc_doc(has_prismatic: bool, floating: bool) -> String {
    if floating {
        return " Takes `s[i]` = sin θᵢ and `c[i]` = cos θᵢ of each revolute joint's angle θᵢ = `q[7 + i]`; the \
                entries of prismatic joints are not read. `q` is read for the base's position and quaternion and \
                the prismatic joints."
            .to_string();
    }
    let q = if has_prismatic { " `q` is read for the prismatic joints only." } else { "" };
    format!(
        " Takes `s[i]` = sin θᵢ and `c[i]` = cos θᵢ of each revolute joint's angle θᵢ = `q[i]` (times `|axis|` for a \
         non-unit axis, see the caller); the entries of prismatic joints are not read.{q}"
    )
}

pub(super) fn trig_source(trig: Trig, scalar: ScalarType) -> &'static str {
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
pub(super) struct ScBody<'a> {
    pub trace: &'a SinCosTrace,
    pub has_prismatic: bool,
    pub split: bool,
}

/// `NAME(q, …)`: the sines and cosines, then `NAME_sc`. `params` start
/// with `q`.
pub(super) fn wrapper(
    fn_name: &str,
    params: &[Param],
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
    // Joint i's angle is q[i], or q[7 + i] after a floating base's position and quaternion; a mimic
    // joint's own angle k·q[i] + o (the generic solver's order of operations).
    let literal = |x: f64| -> proc_macro2::TokenStream {
        let x = literal::float_literal_text(x, options.scalar).unwrap_or_else(|| "1.0".into());
        x.parse().expect("a float literal")
    };
    let angle = |a: &Angle| {
        let i = proc_macro2::Literal::usize_unsuffixed(sc.q_offset + a.joint);
        let scaled = if a.scale == 1.0 {
            quote!(q[#i])
        } else {
            let k = literal(a.scale);
            quote!(q[#i] * #k)
        };
        if a.offset == 0.0 {
            scaled
        } else {
            let o = literal(a.offset);
            quote!(#scaled + #o)
        }
    };
    // Every entry of s and c with the angle it holds, if the body reads it.
    let slots: Vec<Option<Angle>> = sc
        .angle_scale
        .iter()
        .enumerate()
        .map(|(joint, k)| k.map(|scale| Angle { joint, scale, offset: 0.0 }))
        .chain(sc.extra_angles.iter().map(|a| Some(*a)))
        .collect();
    // The batched trigonometry, then `NAME_sc`: `all` computes every sine and cosine, `some` those
    // of the angles it is given, `sc` calls the body.
    let batched = |all: proc_macro2::TokenStream,
                   some: &dyn Fn(usize) -> proc_macro2::TokenStream,
                   sc_call: &dyn Fn(proc_macro2::TokenStream) -> proc_macro2::TokenStream| {
        // Only the angles NAME_sc reads (the UR5's g reads 3 of 6, the Panda's functions 7 of 9).
        let read: Vec<Angle> = slots.iter().flatten().copied().collect();
        let every_joint_once = read.len() == sc.angle_scale.len() && sc.extra_angles.is_empty();
        if sc.q_offset == 0 && every_joint_once && read.iter().all(|a| a.scale == 1.0) {
            let call = sc_call(quote!(&s, &c, #q_arg #(#rest),*));
            quote! {
                let (s, c) = #all;
                #call
            }
        } else {
            let batch = some(read.len());
            let angles = read.iter().map(angle);
            let mut s_entries = Vec::new();
            let mut c_entries = Vec::new();
            let mut j = 0;
            for k in &slots {
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
        for (i, slot) in slots.iter().enumerate() {
            match slot {
                Some(a) => {
                    let (si, ci) = (quote::format_ident!("s{i}"), quote::format_ident!("c{i}"));
                    let plain = a.scale == 1.0 && a.offset == 0.0;
                    let a = angle(a);
                    let call = match (options.trig, options.scalar) {
                        (Trig::Libm, ScalarType::F64) => quote!(libm::sincos(#a)),
                        (Trig::Libm, ScalarType::F32) => quote!(libm::sincosf(#a)),
                        _ if plain => quote!(#a.sin_cos()),
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
    // With run-time dispatch, the batched sines and cosines and the body are inlined into each
    // copy of `NAME` (AVX-512, AVX2 and FMA), as in a native build: no second check, no call of
    // the kernel or of `NAME_sc_avx2_fma` with the sines and cosines through memory. (The body is
    // compiled once more for each; inlined it is faster: docs/performance.md, "Compile time, a
    // body called instead of inlined".) A body split into parts is called as `NAME_sc_avx2_fma`
    // (`_avx512`), the chain of its parts.
    let sc_on = quote::format_ident!("{}_sc_on", fn_name);
    let on = match options.scalar {
        ScalarType::F64 => quote!(sin_cos_array_on),
        ScalarType::F32 => quote!(sin_cos_array_f32_on),
    };
    let args: Vec<proc_macro2::Ident> = params.iter().map(|p| quote::format_ident!("{}", p.name)).collect();
    let checks = checks(fn_name, &args);
    let copies = TIERS.iter().map(|t| {
        let (sc_fast, isa) = (t.name(&format!("{fn_name}_sc")), t.isa());
        let fast_body = batched(
            quote!(#on::<#isa, DOF>(q)),
            &|n| {
                let n = proc_macro2::Literal::usize_unsuffixed(n);
                quote!(#on::<#isa, #n>)
            },
            &|args| if sc_split { quote!(unsafe { #sc_fast(#args) }) } else { quote!(#sc_on::<#isa>(#args)) },
        );
        t.copy(fn_name, quote!((#(#typed),*) -> #ret), fast_body)
    });
    quote! {
        #(#[doc = #doc])*
        #[inline]
        pub fn #name(#(#typed),*) -> #ret {
            #checks
            #body
        }
        #(#copies)*
    }
}

/// The items of `tokens`.
pub(super) fn parse_items(tokens: proc_macro2::TokenStream) -> Result<Vec<syn::Item>, CodegenError> {
    syn::parse2::<syn::File>(tokens).map(|f| f.items).map_err(|e| CodegenError::Internal(e.to_string()))
}
