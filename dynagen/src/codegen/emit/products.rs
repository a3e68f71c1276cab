//! The forward dynamics' derivatives as their factors and a loop.
//!
//! ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ). Traced whole, the two products
//! are unrolled into up to 2n³ scalar multiply-adds; where M⁻¹ is dense (a
//! floating base, a long chain) that is most of the body: 11,664 of the
//! floating quadruped12's. Emitted instead as `NAME_factors` (∂τ/∂q and
//! ∂τ/∂q̇ at the forward dynamics' q̈, and M⁻¹: one traced body) and a
//! loop over the rows of M⁻¹, the products run as vector instructions
//! (`derivative_products`, four lanes with AVX2). [`loop_ops`] is what the
//! choice counts for the loop: one operation per vector multiply-add, so
//! the factors and the loop are emitted where they count fewer operations
//! than the whole trace.
//!
//! The loop sums over k in order, one rounding per term where the target
//! fuses; the traced products sum in the trace's order. The two differ in
//! the last bits, both within the generic solver's 1e-12.

use super::statements::{checks, scalar_type, Param, TIERS};
use crate::codegen::{CodegenOptions, ScalarType, Trig};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Operations counted for the products of an `nv`×`nv` M⁻¹ with two
/// `nv`×`nv` matrices in the loop: a multiply-add for each four entries
/// of a row (rounded up) of each product, and [`LOOP_OVERHEAD`].
pub(crate) fn loop_ops(nv: usize) -> usize {
    2 * nv * nv * nv.div_ceil(4) + LOOP_OVERHEAD
}

/// What the loop costs beyond its multiply-adds (the matrices returned and
/// zeroed, the second dispatch), in operations of a body: measured about
/// 50 ns on the UR5, whose factors (1158 FP ops) and loop (144) made it 3–8 %
/// slower than its whole trace (1598), where the Panda's (3886 + 486 against
/// 5470) made it 11–14 % faster (docs/performance.md, "Derivatives of the
/// dynamics").
const LOOP_OVERHEAD: usize = 400;

/// The module's `derivative_products`: −M⁻¹A and −M⁻¹B, with its AVX2 and
/// FMA copy under run-time dispatch.
pub(crate) fn helper(options: &CodegenOptions) -> TokenStream {
    let ty = scalar_type(options.scalar);
    let m = quote!([[#ty; NV]; NV]);
    let fma = match options.scalar {
        ScalarType::F64 => quote!(fma),
        ScalarType::F32 => quote!(fmaf),
    };
    let step = |acc: TokenStream, a: TokenStream| match options.fma {
        true => quote!(#acc = I::#fma(m, #a, #acc);),
        false => quote!(#acc = m * #a + #acc;),
    };
    let (x, y) = (step(quote!(x[i][j]), quote!(a[k][j])), step(quote!(y[i][j]), quote!(b[k][j])));
    let doc = " −M⁻¹A and −M⁻¹B: the derivatives of q̈ from those of τ (`forward_dynamics_derivatives`), row by row.";
    let on = quote! {
        #[doc = " The body of [`derivative_products`], in the instructions of `I`."]
        #[inline(always)]
        fn derivative_products_on<I: Isa>(minv: &#m, a: &#m, b: &#m) -> (#m, #m) {
            let mut x = [[0.0; NV]; NV];
            let mut y = [[0.0; NV]; NV];
            for i in 0..NV {
                for k in 0..NV {
                    let m = -minv[i][k];
                    for j in 0..NV {
                        #x
                        #y
                    }
                }
            }
            (x, y)
        }
    };
    if !options.runtime_dispatch {
        return quote! {
            #[doc = #doc]
            #[inline]
            fn derivative_products(minv: &#m, a: &#m, b: &#m) -> (#m, #m) {
                derivative_products_on::<Baseline>(minv, a, b)
            }
            #on
        };
    }
    let checks = checks("derivative_products", &[quote!(minv), quote!(a), quote!(b)]);
    let copies = TIERS.iter().map(|t| {
        let isa = t.isa();
        let signature = quote!((minv: &#m, a: &#m, b: &#m) -> (#m, #m));
        t.copy("derivative_products", signature, quote!(derivative_products_on::<#isa>(minv, a, b)))
    });
    quote! {
        #[doc = #doc]
        #[inline]
        fn derivative_products(minv: &#m, a: &#m, b: &#m) -> (#m, #m) {
            #checks
            derivative_products_on::<Baseline>(minv, a, b)
        }
        #(#copies)*
        #on
    }
}

/// `name` (and `name_sc`) as its factors `factors` (`factors_sc`) and the
/// products: `params` are `name`'s, `sc_params` `name_sc`'s.
pub(crate) fn wrappers(
    name: &str,
    factors: &str,
    params: &[Param],
    sc_params: &[Param],
    ret: TokenStream,
    options: &CodegenOptions,
    [doc, sc_doc]: [&str; 2],
) -> TokenStream {
    let one = |fn_name: String, factors: String, params: &[Param], doc: &str| {
        let (f, factors) = (format_ident!("{fn_name}"), format_ident!("{factors}"));
        let typed = params.iter().map(|p| p.tokens(options.scalar));
        let args = params.iter().map(|p| format_ident!("{}", p.name));
        let doc = doc.lines();
        quote! {
            #(#[doc = #doc])*
            #[inline]
            pub fn #f(#(#typed),*) -> #ret {
                let (a, b, minv) = #factors(#(#args),*);
                let (x, y) = derivative_products(&minv, &a, &b);
                (x, y, minv)
            }
        }
    };
    let sc = one(format!("{name}_sc"), format!("{factors}_sc"), sc_params, sc_doc);
    match options.trig {
        Trig::Inputs => sc,
        _ => {
            let full = one(name.to_string(), factors.to_string(), params, doc);
            quote!(#sc #full)
        }
    }
}
