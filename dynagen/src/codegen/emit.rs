//! One traced function → one Rust `fn`, as tokens.

use super::literal::float_literal;
use super::trace::FunctionKind;
use super::{CodegenError, ScalarType};
use crate::symbolic::{Function, Node};
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

/// The Rust type of the scalar.
pub(crate) fn scalar_type(scalar: ScalarType) -> TokenStream {
    match scalar {
        ScalarType::F64 => quote!(f64),
        ScalarType::F32 => quote!(f32),
    }
}

/// `pub fn name(inputs…) -> output { let …; [outputs] }`: one `let` per kept
/// operation, named `t{k}` in order (`s{k}`/`c{k}` for a sine and cosine),
/// constants written in place as literals, inputs read as `q[i]`.
pub(crate) fn emit_function(
    f: &Function,
    kind: FunctionKind,
    scalar: ScalarType,
    n: usize,
    doc: &str,
) -> Result<TokenStream, CodegenError> {
    let ty = scalar_type(scalar);
    let nodes = f.nodes();
    // How each node is referred to by its users.
    let mut refs: Vec<TokenStream> = Vec::with_capacity(nodes.len());
    let mut lets = Vec::new();
    // For each SinCos node: whether its sine and cosine are read.
    let mut sin_used = vec![false; nodes.len()];
    let mut cos_used = vec![false; nodes.len()];
    for node in nodes {
        match *node {
            Node::Sin(sc) => sin_used[sc as usize] = true,
            Node::Cos(sc) => cos_used[sc as usize] = true,
            _ => {}
        }
    }
    let mut k = 0usize;
    for (id, node) in nodes.iter().enumerate() {
        let r = |i: u32| &refs[i as usize];
        let (reference, stmt) = match *node {
            Node::Const(_) => {
                let x = node.constant().unwrap_or_default();
                let lit = float_literal(x, scalar)
                    .ok_or_else(|| CodegenError::NonFiniteConstant { function: f.name().to_string(), value: x })?;
                (lit, None)
            }
            Node::Input { name, index } => {
                let name = Ident::new(&f.input_names()[name as usize], Span::call_site());
                let index = proc_macro2::Literal::usize_unsuffixed(index as usize);
                (quote!(#name[#index]), None)
            }
            Node::SinCos(a) => {
                let (s, c) = (format_ident!("s{}", k), format_ident!("c{}", k));
                let a = r(a);
                let stmt = match (sin_used[id], cos_used[id]) {
                    (true, true) => quote!(let (#s, #c) = #a.sin_cos();),
                    (true, false) => quote!(let #s = #a.sin();),
                    _ => quote!(let #c = #a.cos();),
                };
                k += 1;
                // Users refer to the Sin / Cos nodes; keep the counter value.
                (quote!(#s #c), Some(stmt))
            }
            Node::Sin(sc) | Node::Cos(sc) => {
                let mut it = refs[sc as usize].clone().into_iter();
                let (s, c) = (it.next(), it.next());
                let pick = if matches!(node, Node::Sin(_)) { s } else { c };
                (pick.into_iter().collect(), None)
            }
            _ => {
                let t = format_ident!("t{}", k);
                k += 1;
                let e = match *node {
                    Node::Add(a, b) => {
                        let (a, b) = (r(a), r(b));
                        quote!(#a + #b)
                    }
                    Node::Sub(a, b) => {
                        let (a, b) = (r(a), r(b));
                        quote!(#a - #b)
                    }
                    Node::Mul(a, b) => {
                        let (a, b) = (r(a), r(b));
                        quote!(#a * #b)
                    }
                    Node::Div(a, b) => {
                        let (a, b) = (r(a), r(b));
                        quote!(#a / #b)
                    }
                    Node::Neg(a) => {
                        let a = r(a);
                        quote!(-#a)
                    }
                    Node::Sqrt(a) => {
                        let a = r(a);
                        quote!(#a.sqrt())
                    }
                    _ => unreachable!("handled above"),
                };
                (quote!(#t), Some(quote!(let #t = #e;)))
            }
        };
        refs.push(reference);
        if let Some(s) = stmt {
            lets.push(s);
        }
    }
    let out: Vec<&TokenStream> = f.outputs().iter().map(|&o| &refs[o as usize]).collect();
    let result = if kind.is_matrix() {
        let rows = out.chunks(n.max(1)).take(n).map(|row| quote!([#(#row),*]));
        quote!([#(#rows),*])
    } else {
        quote!([#(#out),*])
    };
    let params = kind.inputs().iter().map(|name| {
        let name = Ident::new(name, Span::call_site());
        quote!(#name: &[#ty; DOF])
    });
    let unused = kind.inputs().iter().filter(|name| !f.uses_input(name)).map(|name| {
        let name = Ident::new(name, Span::call_site());
        quote!(let _ = #name;)
    });
    let ret = if kind.is_matrix() { quote!([[#ty; DOF]; DOF]) } else { quote!([#ty; DOF]) };
    let name = Ident::new(kind.fn_name(), Span::call_site());
    let doc = doc.lines();
    Ok(quote! {
        #(#[doc = #doc])*
        #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal, clippy::too_many_lines)]
        pub fn #name(#(#params),*) -> #ret {
            #(#unused)*
            #(#lets)*
            #result
        }
    })
}
