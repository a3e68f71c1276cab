//! Small builders of `syn` syntax, shared by the statements and the
//! splitting of long bodies.

use super::literal::float_literal_text;
use crate::codegen::ScalarType;
use proc_macro2::{Ident, Span};
use syn::punctuated::Punctuated;
use syn::{BinOp, Expr, Pat, Stmt, UnOp};

pub(crate) fn ident(name: &str) -> Ident {
    Ident::new(name, Span::call_site())
}
pub(crate) fn path(id: Ident) -> Expr {
    Expr::Path(syn::ExprPath { attrs: vec![], qself: None, path: syn::Path::from(id) })
}
pub(crate) fn float(x: f64, scalar: ScalarType) -> Option<Expr> {
    let text = float_literal_text(x, scalar)?;
    let (neg, digits) = match text.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, text.as_str()),
    };
    let lit =
        Expr::Lit(syn::ExprLit { attrs: vec![], lit: syn::Lit::Float(syn::LitFloat::new(digits, Span::call_site())) });
    Some(if neg { unary(UnOp::Neg(Default::default()), lit) } else { lit })
}
pub(crate) fn index(array: &str, i: usize) -> Expr {
    subscript(path(ident(array)), i)
}
/// `base[i]`.
pub(crate) fn subscript(base: Expr, i: usize) -> Expr {
    Expr::Index(syn::ExprIndex {
        attrs: vec![],
        expr: Box::new(base),
        bracket_token: Default::default(),
        index: Box::new(Expr::Lit(syn::ExprLit {
            attrs: vec![],
            lit: syn::Lit::Int(syn::LitInt::new(&i.to_string(), Span::call_site())),
        })),
    })
}
/// The statement `left = right;`.
pub(crate) fn assign(left: Expr, right: Expr) -> Stmt {
    let assign =
        syn::ExprAssign { attrs: vec![], left: Box::new(left), eq_token: Default::default(), right: Box::new(right) };
    Stmt::Expr(Expr::Assign(assign), Some(Default::default()))
}
pub(crate) fn binary(a: &Expr, op: BinOp, b: &Expr) -> Expr {
    Expr::Binary(syn::ExprBinary { attrs: vec![], left: Box::new(a.clone()), op, right: Box::new(b.clone()) })
}
pub(crate) fn unary(op: UnOp, a: Expr) -> Expr {
    Expr::Unary(syn::ExprUnary { attrs: vec![], op, expr: Box::new(a) })
}
pub(crate) fn method(receiver: &Expr, name: &str) -> Expr {
    Expr::MethodCall(syn::ExprMethodCall {
        attrs: vec![],
        receiver: Box::new(receiver.clone()),
        dot_token: Default::default(),
        method: ident(name),
        turbofish: None,
        paren_token: Default::default(),
        args: Punctuated::new(),
    })
}
pub(crate) fn call(segments: &[&str], args: &[&Expr]) -> Expr {
    let path = syn::Path {
        leading_colon: None,
        segments: segments.iter().map(|s| syn::PathSegment::from(ident(s))).collect(),
    };
    Expr::Call(syn::ExprCall {
        attrs: vec![],
        func: Box::new(Expr::Path(syn::ExprPath { attrs: vec![], qself: None, path })),
        paren_token: Default::default(),
        args: args.iter().map(|&a| a.clone()).collect(),
    })
}
pub(crate) fn pat(id: Ident) -> Pat {
    Pat::Ident(syn::PatIdent { attrs: vec![], by_ref: None, mutability: None, ident: id, subpat: None })
}
pub(crate) fn let_stmt(pat: Pat, e: Expr) -> Stmt {
    Stmt::Local(syn::Local {
        attrs: vec![],
        let_token: Default::default(),
        modifiers: Default::default(),
        pat,
        init: Some(syn::LocalInit { eq_token: Default::default(), expr: Box::new(e), diverge: None }),
        semi_token: Default::default(),
    })
}
pub(crate) fn array(elems: impl IntoIterator<Item = Expr>) -> Expr {
    Expr::Array(syn::ExprArray { attrs: vec![], bracket_token: Default::default(), elems: elems.into_iter().collect() })
}
