//! One traced function → one Rust `fn`.
//!
//! The signature and attributes are written with `quote` and parsed; the
//! body, which can hold tens of thousands of statements, is built directly
//! as `syn` syntax (parsing it back from tokens would dominate the
//! generator's run time).

use super::split::{self, Body, Line, PartParam};
use super::syntax::{array, assign, binary, call, float, ident, index, let_stmt, method, pat, path, subscript, unary};
use crate::codegen::{CodegenError, CodegenOptions, ScalarType, Trig};
use crate::symbolic::{statement_order, Fusion, Node, Traced};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::{BinOp, Expr, Pat, Stmt, UnOp};

/// The Rust type of the scalar.
pub(crate) fn scalar_type(scalar: ScalarType) -> TokenStream {
    match scalar {
        ScalarType::F64 => quote!(f64),
        ScalarType::F32 => quote!(f32),
    }
}

/// A length of a parameter or of the output: the number of joints (`DOF`)
/// or a fixed number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Dim {
    /// `DOF`.
    Dof,
    /// `NQ`: a floating-base module's configuration length (DOF + 7).
    Nq,
    /// `NV`: a floating-base module's velocity length (DOF + 6).
    Nv,
    /// A literal length.
    Fixed(usize),
}

impl Dim {
    fn tokens(self) -> TokenStream {
        match self {
            Dim::Dof => quote!(DOF),
            Dim::Nq => quote!(NQ),
            Dim::Nv => quote!(NV),
            Dim::Fixed(k) => {
                let k = proc_macro2::Literal::usize_unsuffixed(k);
                quote!(#k)
            }
        }
    }
    pub(crate) fn value(self, s: Sizes) -> usize {
        match self {
            Dim::Dof => s.dof,
            Dim::Nq => s.nq,
            Dim::Nv => s.nv,
            Dim::Fixed(k) => k,
        }
    }
}

/// The lengths a module's [`Dim`]s stand for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Sizes {
    /// Joints.
    pub dof: usize,
    /// Configuration entries (`dof`, or `dof + 7` with a floating base).
    pub nq: usize,
    /// Velocity entries (`dof`, or `dof + 6` with a floating base).
    pub nv: usize,
}

impl Sizes {
    /// The sizes of `model`.
    pub(crate) fn of(model: &crate::model::Model) -> Sizes {
        Sizes { dof: model.dof(), nq: model.nq(), nv: model.nv() }
    }
    /// Whether these are a floating-base module's.
    pub(crate) fn floating(self) -> bool {
        self.nq != self.dof
    }
}

/// The shape of a function's output: `[T; len]` or `[[T; cols]; rows]`
/// (the traced outputs row-major).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    /// A vector.
    Vector(Dim),
    /// A matrix, rows then columns.
    Matrix(Dim, Dim),
    /// A tuple of this many matrices of the same shape (the traced outputs
    /// one matrix after the other).
    Matrices(usize, Dim, Dim),
}

impl Shape {
    /// The shape of a function of the generated-code contract.
    pub(crate) fn tokens(self, scalar: ScalarType) -> TokenStream {
        let ty = scalar_type(scalar);
        match self {
            Shape::Vector(d) => {
                let d = d.tokens();
                quote!([#ty; #d])
            }
            Shape::Matrix(r, c) => {
                let (r, c) = (r.tokens(), c.tokens());
                quote!([[#ty; #c]; #r])
            }
            // The module's alias `DofMatrix` = `[[T; DOF]; DOF]`, or on a
            // floating base `NvMatrix` = `[[T; NV]; NV]` (a tuple of the full
            // types is too complex a type for clippy's taste).
            Shape::Matrices(k, d @ (Dim::Dof | Dim::Nv), c) if c == d => {
                let alias = if d == Dim::Dof { quote!(DofMatrix) } else { quote!(NvMatrix) };
                let each = (0..k).map(|_| alias.clone());
                quote!((#(#each),*))
            }
            Shape::Matrices(k, r, c) => {
                let (r, c) = (r.tokens(), c.tokens());
                let each = (0..k).map(|_| quote!([[#ty; #c]; #r]));
                quote!((#(#each),*))
            }
        }
    }
}

/// A parameter `name: &[T; len]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Param {
    /// Its name.
    pub name: String,
    /// Its length.
    pub len: Dim,
}

impl Param {
    /// `name: &[T; DOF]`.
    pub(crate) fn dof(name: &str) -> Param {
        Param { name: name.to_string(), len: Dim::Dof }
    }
    /// `name: &[T; len]`.
    pub(crate) fn sized(name: &str, len: Dim) -> Param {
        Param { name: name.to_string(), len }
    }
    /// `name: &[T; len]`.
    pub(crate) fn fixed(name: &str, len: usize) -> Param {
        Param { name: name.to_string(), len: Dim::Fixed(len) }
    }
    /// Its length.
    pub(crate) fn len_value(&self, s: Sizes) -> usize {
        self.len.value(s)
    }
    /// The tokens `name: &[T; len]`.
    pub(crate) fn tokens(&self, scalar: ScalarType) -> TokenStream {
        let ty = scalar_type(scalar);
        let name = ident(&self.name);
        let len = self.len.tokens();
        quote!(#name: &[#ty; #len])
    }
}

/// Calls made in the middle of a body: the traced function's outputs past
/// `outputs` are their arguments, computed first; `glue` writes the
/// statements that make the calls from those arguments' expressions, and
/// the rest of the body (which reads the calls' results as inputs) follows.
pub(crate) struct Calls<'a> {
    /// The function's own outputs.
    pub outputs: usize,
    /// How many of the other outputs (the calls' arguments) each phase of
    /// calls takes, in order: a phase's calls come after what its
    /// arguments need, and before what needs their results.
    pub phases: Vec<usize>,
    /// The statements of phase p's calls, from its arguments.
    pub glue: Glue<'a>,
}

/// What writes the statements of [`Calls`].
pub(crate) type Glue<'a> = &'a dyn Fn(usize, &[Expr]) -> Result<Vec<Stmt>, CodegenError>;

/// The name, parameters and output of an emitted function.
pub(crate) struct Signature<'a> {
    /// Its Rust name.
    pub name: String,
    /// Its parameters, in order.
    pub params: Vec<Param>,
    /// Its output.
    pub output: Shape,
    /// Calls its body makes in the middle, if any.
    pub calls: Option<Calls<'a>>,
}

/// How bodies are written: split into parts, fused multiply-adds, copies
/// for AVX2 and FMA chosen at run time.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyStyle {
    /// [`CodegenOptions::split_lets`](crate::codegen::CodegenOptions::split_lets).
    pub split_lets: Option<usize>,
    /// [`CodegenOptions::fma`](crate::codegen::CodegenOptions::fma).
    pub fma: bool,
    /// [`CodegenOptions::runtime_dispatch`](crate::codegen::CodegenOptions::runtime_dispatch).
    pub dispatch: bool,
}

impl BodyStyle {
    /// The style `options` ask for.
    pub(crate) fn of(options: &CodegenOptions) -> BodyStyle {
        BodyStyle { split_lets: options.split_lets, fma: options.fma, dispatch: options.runtime_dispatch }
    }
}

/// One copy of a body that the run-time dispatch picks where the processor
/// has its instructions: the AVX-512 copy (checked first), then the AVX2
/// and FMA one. Both are the generic body `NAME_on::<Avx2Fma>` compiled
/// inside a `#[target_feature]` function: the same operations, other
/// registers. The kernel text (`sin_cos/kernel.rs`) has `Avx2Fma` and the
/// checks.
pub(super) struct Tier {
    /// The copy's name is `NAME_{suffix}`.
    suffix: &'static str,
    /// Its `#[target_feature(enable = …)]`.
    features: &'static str,
    /// The kernel's function that says whether the processor has them.
    check: &'static str,
    /// The processors it is for, in its documentation.
    pub what: &'static str,
    /// The target features whose absence from the build the copy's `cfg`
    /// asks for (a build that has them all compiles no copy).
    cfg_features: &'static [&'static str],
}

/// The copies of the run-time dispatch, in the order they are checked.
pub(super) const TIERS: [Tier; 2] = [
    Tier {
        suffix: "avx512",
        features: "avx2,fma,avx512f,avx512vl,avx512dq",
        check: "has_avx512",
        what: "AVX-512 F, VL and DQ",
        cfg_features: &["avx512f", "avx512vl", "avx512dq"],
    },
    Tier {
        suffix: "avx2_fma",
        features: "avx2,fma",
        check: "has_avx2_and_fma",
        what: "AVX2 and FMA",
        cfg_features: &["avx2", "fma"],
    },
];

impl Tier {
    /// `NAME_{suffix}`.
    pub fn name(&self, base: &str) -> Ident {
        format_ident!("{base}_{}", self.suffix)
    }
    /// The `Isa` the copy's body is instantiated for: `Avx2Fma` for every
    /// copy (their operations are the same; only their target features
    /// differ).
    pub fn isa(&self) -> Ident {
        format_ident!("Avx2Fma")
    }
    /// `#[cfg(…)]`: x86-64 builds without the copy's features.
    pub fn cfg(&self) -> TokenStream {
        let features = self.cfg_features.iter().map(|f| quote!(target_feature = #f));
        quote!(#[cfg(all(target_arch = "x86_64", not(all(#(#features),*))))])
    }
    /// `#[target_feature(enable = …)]`.
    pub fn target_feature(&self) -> TokenStream {
        let features = self.features;
        quote!(#[target_feature(enable = #features)])
    }
    /// The copy `unsafe fn NAME_{suffix}signature { body }` of the function
    /// `of` (`signature`: its parameters and return type), documented.
    pub fn copy(&self, of: &str, signature: TokenStream, body: TokenStream) -> TokenStream {
        let (fast, cfg, features) = (self.name(of), self.cfg(), self.target_feature());
        let doc = format!(" [`{of}`] compiled for processors with {}.", self.what);
        quote! {
            #[doc = #doc]
            #cfg
            #features
            unsafe fn #fast #signature {
                #body
            }
        }
    }
    /// `cfg if check() { return unsafe { call }; }`, the dispatch to this copy.
    fn check(&self, call: TokenStream) -> TokenStream {
        let (cfg, check) = (self.cfg(), format_ident!("{}", self.check));
        quote! {
            #cfg
            if #check() {
                return unsafe { #call };
            }
        }
    }
}

/// The dispatch of `of` to its copies, in the order of [`TIERS`]: for each,
/// `cfg if check() { return unsafe { of_suffix(args) }; }`.
pub(super) fn checks<T: quote::ToTokens>(of: &str, args: &[T]) -> TokenStream {
    TIERS
        .iter()
        .map(|t| {
            let fast = t.name(of);
            t.check(quote!(#fast(#(#args),*)))
        })
        .collect()
}

/// The comment put above each call of a function's dispatched copy, `{}`
/// the instructions.
const SAFETY_COMMENT: &str = "// SAFETY: this processor has {} (checked just above).";

/// The comment above the calls of dispatched copies from another (a split
/// body's parts, `NAME_sc_avx2_fma` from `NAME_avx2_fma`).
const SAFETY_COMMENT_PARTS: &str = "// SAFETY: this processor has {} (the caller checked).";

/// `source` as a person would write the dispatch: [`SAFETY_COMMENT`] above
/// every `return unsafe {` and [`SAFETY_COMMENT_PARTS`] above every other
/// `unsafe {` (the calls of the copies; `syn` trees carry no comments),
/// naming the instructions of the copy called on that line or the next,
/// and each `#[cfg(…)]` on one line (prettyplease breaks them over six).
pub(crate) fn tidy_dispatch(source: &str) -> String {
    let mut out = String::with_capacity(source.len() + 1024);
    let mut lines = source.lines().peekable();
    while let Some(line) = lines.next() {
        let code = line.trim_start();
        let indent = &line[..line.len() - code.len()];
        if code == "#[cfg(" {
            out.push_str(indent);
            out.push_str("#[cfg(");
            for piece in lines.by_ref() {
                let piece = piece.trim();
                if piece == ")]" {
                    break;
                }
                out.push_str(piece);
                if piece.ends_with(',') {
                    out.push(' ');
                }
            }
            out.push_str(")]\n");
            continue;
        }
        let safety = match code {
            _ if code.starts_with("return unsafe {") => Some(SAFETY_COMMENT),
            _ if code.starts_with("unsafe {") => Some(SAFETY_COMMENT_PARTS),
            _ => None,
        };
        if let Some(comment) = safety {
            let next = lines.peek().copied().unwrap_or("");
            let tier = TIERS.iter().find(|t| {
                let called = format!("_{}(", t.suffix);
                line.contains(&called) || next.contains(&called)
            });
            out.push_str(indent);
            out.push_str(&comment.replace("{}", tier.unwrap_or(&TIERS[1]).what));
            out.push('\n');
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The `−x` of an emitted expression (`x` itself for a negated one).
fn negated(x: &Expr) -> Expr {
    match x {
        Expr::Unary(syn::ExprUnary { op: UnOp::Neg(_), expr, .. }) => (**expr).clone(),
        _ => unary(UnOp::Neg(Default::default()), x.clone()),
    }
}

/// `pub fn name(inputs…) -> output { let …; [outputs] }`: one `let` per kept
/// operation, named `t{k}` in order (`s{k}`/`c{k}` for a sine and cosine),
/// constants written in place as literals, inputs read as `q[i]`. With
/// `style.fma`, the sums of [`Fusion`] are `fma(a, b, c)` (`fmaf` in `f32`)
/// and the products only they read are not written. A square root is
/// `x.sqrt()` with [`Trig::Std`], `libm::sqrt(x)` with [`Trig::Libm`], and
/// otherwise the module's own `sqrt(x)` (`sqrtf`; no std, correctly
/// rounded, see [`super::sin_cos`]). A body of more than
/// `style.split_lets` `let`s is cut into private parts ([`split`]). A body
/// that is not cut and has at least [`EARLY_STORES_MIN_LETS`] statements
/// returning matrices stores each entry where it is computed
/// ([`store_early`]) and returns `out`.
///
/// With `style.dispatch`, a body that is not split is written once as a
/// generic `NAME_on<I: Isa>` (`#[inline(always)]`, its sums `I::fma(a, b,
/// c)`), instantiated in `NAME` for `Baseline` and in `NAME_avx2_fma`
/// (`#[target_feature(enable = "avx2,fma")]`) for `Avx2Fma`, which `NAME`
/// calls where the processor has both; on x86-64 builds that have both, and
/// on other targets, `NAME` is the `Baseline` body alone (see the kernel
/// text, `sin_cos_kernel.rs`). A split body is dispatched part by part
/// ([`split::assemble`]).
pub(crate) fn emit_function(
    f: &Traced,
    signature: &Signature<'_>,
    scalar: ScalarType,
    trig: Trig,
    n: Sizes,
    doc: &str,
    style: BodyStyle,
) -> Result<Vec<syn::Item>, CodegenError> {
    let fma = match scalar {
        ScalarType::F64 => "fma",
        ScalarType::F32 => "fmaf",
    };
    let fma_path: &[&str] = if style.dispatch { &["I", fma] } else { &[fma] };
    let mut body = body_of(f, scalar, trig, style, fma_path)?;
    // The statements before the calls' results can be read.
    let ready = match &signature.calls {
        Some(calls) => insert_calls(&mut body, calls)?,
        None => 0,
    };
    // (a body with calls is never split: its parts would have to carry the results)
    let whole = signature.calls.is_some() || style.split_lets.is_none_or(|max| body.lines.len() <= max);
    // Whether to cut is decided on the statements alone: the stores of an
    // early output do not make a whole body a split one.
    let max_lets = if whole { None } else { style.split_lets };
    // A long body returning a matrix stores each entry where it is computed.
    let early = (whole && body.lines.len() >= EARLY_STORES_MIN_LETS)
        .then(|| store_early(f, &mut body, signature.output, n, scalar, ready))
        .flatten();
    if style.dispatch && whole {
        return dispatched(f, signature, scalar, n, doc, body, early);
    }
    let shell = quote! {
        #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal, clippy::too_many_lines)]
        pub fn name() {}
    };
    let mut item: syn::ItemFn = syn::parse2(shell).map_err(|e| CodegenError::Internal(e.to_string()))?;
    let (attrs, sig) = signature_of(signature, scalar, doc)?;
    item.attrs.splice(0..0, attrs);
    item.sig = sig;
    item.block.stmts = unused_params(f, signature)?;
    let part_params: Vec<PartParam> = signature
        .params
        .iter()
        .map(|p| PartParam {
            name: ident(&p.name),
            typed: p.tokens(scalar),
            input: f.input_names().iter().position(|x| *x == p.name).map(|i| i as u32),
        })
        .collect();
    let literal = result_of(signature.output, n);
    let result = |outputs| early.clone().unwrap_or_else(|| literal(outputs));
    split::assemble(item, body, &part_params, &scalar_type(scalar), max_lets, result, style.dispatch)
}

/// Moves the statements the calls' arguments need first, then the calls,
/// then the rest, and drops the arguments from the outputs. Returns the
/// number of statements up to the calls' last.
fn insert_calls(body: &mut Body, calls: &Calls) -> Result<usize, CodegenError> {
    let mut lines = std::mem::take(&mut body.lines);
    let mut from = calls.outputs;
    for (phase, &count) in calls.phases.iter().enumerate() {
        // The statements this phase's arguments need, in order, first.
        let mut needed = vec![false; body.names.len()];
        for (_, v) in &body.outputs[from..from + count] {
            if let Some(v) = v {
                needed[*v as usize] = true;
            }
        }
        let mut first = vec![false; lines.len()];
        for (k, l) in lines.iter().enumerate().rev() {
            if l.defs.iter().any(|&d| needed[d as usize]) {
                first[k] = true;
                for &u in &l.uses {
                    needed[u as usize] = true;
                }
            }
        }
        let args: Vec<Expr> = body.outputs[from..from + count].iter().map(|(e, _)| e.clone()).collect();
        from += count;
        let glue = (calls.glue)(phase, &args)?.into_iter().map(|stmt| Line {
            stmt,
            defs: vec![],
            uses: vec![],
            inputs: vec![],
        });
        let (before, after): (Vec<_>, Vec<_>) =
            std::mem::take(&mut lines).into_iter().zip(first).partition(|(_, f)| *f);
        body.lines.extend(before.into_iter().map(|(l, _)| l));
        body.lines.extend(glue);
        lines = after.into_iter().map(|(l, _)| l).collect();
    }
    let ready = body.lines.len();
    body.lines.extend(lines);
    body.outputs.truncate(calls.outputs);
    Ok(ready)
}

/// From this many statements on, a body that returns matrices and is not
/// split stores each entry into the returned array right after the
/// statement that computes it, instead of returning one array literal at
/// the end. A body that long does not fit in the processor's micro-op cache
/// and runs at the rate its decoders take bytes, and the literal makes every
/// entry's value live to the end: spilled, reloaded and stored, three
/// instructions of eight or nine bytes where one store does. Shorter bodies
/// run from the micro-op cache, where the literal measured faster; split
/// bodies measured slower with their parts storing into the output
/// (`docs/performance.md`, "Long bodies: the front end").
pub(crate) const EARLY_STORES_MIN_LETS: usize = 2400;

/// Rewrites `body` to store its matrix outputs where they are computed:
/// first `let mut out = [[0.0; C]; R];` (a tuple of such for several
/// matrices) and the entries that are inputs or nonzero constants, then
/// after each statement `out[i][j] = t;` for every entry that is its value.
/// Returns the expression that ends the body (`out`), or `None` (and leaves
/// `body` as it was) for a vector output. The stores of inputs come after
/// the first `ready` statements (those that make the calls' results).
fn store_early(f: &Traced, body: &mut Body, output: Shape, n: Sizes, scalar: ScalarType, ready: usize) -> Option<Expr> {
    let (k, rows, cols) = match output {
        Shape::Vector(_) => return None,
        Shape::Matrix(r, c) => (None, r, c),
        Shape::Matrices(k, r, c) => (Some(k), r, c),
    };
    let (r, c) = (rows.value(n), cols.value(n));
    let zero = float(0.0, scalar).expect("0 is finite");
    let (rt, ct) = (rows.tokens(), cols.tokens());
    let one = quote!([[#zero; #ct]; #rt]);
    let init = match k {
        None => one,
        Some(k) => {
            let each = (0..k).map(|_| one.clone());
            quote!((#(#each),*))
        }
    };
    let out = format_ident!("out");
    // `out[i][j] = value;`, or `out.m[i][j] = value;` for the m-th matrix.
    let store = |o: usize, value: &Expr| -> Stmt {
        let (m, rc) = (o / (r * c), o % (r * c));
        let mut e = path(out.clone());
        if k.is_some() {
            e = Expr::Field(syn::ExprField {
                attrs: vec![],
                base: Box::new(e),
                dot_token: Default::default(),
                member: syn::Member::Unnamed(syn::Index::from(m)),
            });
        }
        assign(subscript(subscript(e, rc / c), rc % c), value.clone())
    };
    let line = |stmt: Stmt| Line { stmt, defs: vec![], uses: vec![], inputs: vec![] };
    let mut lines = vec![line(syn::parse_quote!(let mut #out = #init;))];
    // The entries each value is, by the value's index.
    let mut entries: Vec<Vec<usize>> = vec![Vec::new(); body.names.len()];
    let mut inputs = Vec::new();
    for (o, ((e, value), &node)) in body.outputs.iter().zip(f.outputs()).enumerate() {
        match value {
            Some(v) => entries[*v as usize].push(o),
            None if f.nodes()[node as usize].constant().is_some_and(|x| x.to_bits() == 0) => {}
            None => inputs.push(line(store(o, e))),
        }
    }
    let mut inputs = Some(inputs);
    for (k, l) in std::mem::take(&mut body.lines).into_iter().enumerate() {
        if k == ready {
            lines.extend(inputs.take().into_iter().flatten());
        }
        let mut stores = Vec::new();
        for &v in &l.defs {
            let value = path(body.names[v as usize].clone());
            stores.extend(entries[v as usize].iter().map(|&o| line(store(o, &value))));
        }
        lines.push(l);
        lines.extend(stores);
    }
    lines.extend(inputs.into_iter().flatten());
    body.lines = lines;
    Some(path(out))
}

/// How the outputs are arranged into the returned array.
fn result_of(output: Shape, n: Sizes) -> impl Fn(Vec<Expr>) -> Expr {
    let matrix =
        |out: &[Expr], r: usize, c: usize| array(out.chunks(c.max(1)).take(r).map(|row| array(row.iter().cloned())));
    move |out: Vec<Expr>| match output {
        Shape::Matrix(r, c) => matrix(&out, r.value(n), c.value(n)),
        Shape::Matrices(k, r, c) => {
            let (r, c) = (r.value(n), c.value(n));
            let elems = (0..k).map(|m| matrix(&out[m * r * c..(m + 1) * r * c], r, c)).collect();
            Expr::Tuple(syn::ExprTuple { attrs: vec![], paren_token: Default::default(), elems })
        }
        Shape::Vector(_) => array(out),
    }
}

/// The documentation attributes and the signature `fn name(params) -> ret`.
fn signature_of(
    signature: &Signature<'_>,
    scalar: ScalarType,
    doc: &str,
) -> Result<(Vec<syn::Attribute>, syn::Signature), CodegenError> {
    let params = signature.params.iter().map(|p| p.tokens(scalar));
    let ret = signature.output.tokens(scalar);
    let name = ident(&signature.name);
    let doc = doc.lines();
    let item: syn::ItemFn = syn::parse2(quote! {
        #(#[doc = #doc])*
        pub fn #name(#(#params),*) -> #ret {}
    })
    .map_err(|e| CodegenError::Internal(e.to_string()))?;
    Ok((item.attrs, item.sig))
}

/// `let _ = p;` for each parameter `f` does not read.
fn unused_params(f: &Traced, signature: &Signature) -> Result<Vec<Stmt>, CodegenError> {
    signature
        .params
        .iter()
        .filter(|p| !f.uses_input(&p.name))
        .map(|p| {
            let name = ident(&p.name);
            syn::parse2(quote!(let _ = #name;)).map_err(|e| CodegenError::Internal(e.to_string()))
        })
        .collect()
}

/// A body that is not split, written for run-time dispatch: the public
/// `NAME`, which calls `NAME_avx512` where the processor has AVX-512,
/// `NAME_avx2_fma` where it has AVX2 and FMA, and else runs
/// `NAME_on::<Baseline>`; those copies ([`TIERS`]); and the generic body
/// `NAME_on`.
fn dispatched(
    f: &Traced,
    signature: &Signature<'_>,
    scalar: ScalarType,
    n: Sizes,
    doc: &str,
    body: Body,
    early: Option<Expr>,
) -> Result<Vec<syn::Item>, CodegenError> {
    let name = ident(&signature.name);
    let on = format_ident!("{}_on", signature.name);
    let params: Vec<TokenStream> = signature.params.iter().map(|p| p.tokens(scalar)).collect();
    let args: Vec<Ident> = signature.params.iter().map(|p| ident(&p.name)).collect();
    let ret = signature.output.tokens(scalar);
    let doc = doc.lines();
    let on_doc = format!(" The body of [`{name}`], in the instructions of `I`.");
    let checks = checks(&signature.name, &args);
    let copies = TIERS.iter().map(|t| {
        let isa = t.isa();
        t.copy(&signature.name, quote!((#(#params),*) -> #ret), quote!(#on::<#isa>(#(#args),*)))
    });
    let items = quote! {
        #(#[doc = #doc])*
        pub fn #name(#(#params),*) -> #ret {
            #checks
            #on::<Baseline>(#(#args),*)
        }
        #(#copies)*
        #[doc = #on_doc]
        #[inline(always)]
        #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal, clippy::too_many_lines)]
        fn #on<I: Isa>(#(#params),*) -> #ret {}
    };
    let file: syn::File = syn::parse2(items).map_err(|e| CodegenError::Internal(e.to_string()))?;
    let mut items = file.items;
    let Some(syn::Item::Fn(body_fn)) = items.last_mut() else {
        return Err(CodegenError::Internal("no body function".into()));
    };
    body_fn.block.stmts = unused_params(f, signature)?;
    body_fn.block.stmts.extend(body.lines.into_iter().map(|l| l.stmt));
    let result =
        early.unwrap_or_else(|| result_of(signature.output, n)(body.outputs.into_iter().map(|(e, _)| e).collect()));
    body_fn.block.stmts.push(Stmt::Expr(result, None));
    Ok(items)
}

/// The statements of `f`'s body, its sums fused as `fma_path(a, b, c)`.
fn body_of(f: &Traced, scalar: ScalarType, trig: Trig, style: BodyStyle, fma: &[&str]) -> Result<Body, CodegenError> {
    // libm's and the module's own (the kernel text's) square root have the same names.
    let sqrt = match scalar {
        ScalarType::F64 => "sqrt",
        ScalarType::F32 => "sqrtf",
    };
    let fusion = if style.fma { f.fusion() } else { Fusion::none(f) };
    let nodes = f.nodes();
    // How each node is referred to by its users (for a SinCos node: its
    // sine; the cosine's name is kept in `cos_ref`).
    let mut refs: Vec<Option<Expr>> = vec![None; nodes.len()];
    let mut cos_ref: Vec<Option<Expr>> = vec![None; nodes.len()];
    // For the split: the value each node is (its sine for a SinCos node;
    // the cosine's in `cos_value`), or the input array it reads.
    let mut value: Vec<Option<u32>> = vec![None; nodes.len()];
    let mut cos_value: Vec<Option<u32>> = vec![None; nodes.len()];
    let mut input: Vec<Option<u32>> = vec![None; nodes.len()];
    let mut names: Vec<Ident> = Vec::new();
    let mut lines: Vec<Line> = Vec::new();
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
    // The statements in the order of `symbolic/schedule.rs`: operands
    // before users, traced or reordered for a shorter live set.
    for id in statement_order(f, &fusion) {
        let (id, node) = (id as usize, &nodes[id as usize]);
        let r = |i: u32| refs[i as usize].as_ref().expect("operands are written first");
        let fused = fusion.sum(id as u32);
        let operands = fusion.operands(f, id as u32);
        let mut uses: Vec<u32> = operands.iter().filter_map(|&a| value[a as usize]).collect();
        uses.sort_unstable();
        uses.dedup();
        let inputs: Vec<u32> = operands.iter().filter_map(|&a| input[a as usize]).collect();
        let (mut this_value, mut this_input) = (None, None);
        let reference = match *node {
            // Only fused sums read it, from its factors: not written.
            Node::Mul(a, b) if fusion.is_folded(id as u32) => binary(r(a), BinOp::Mul(Default::default()), r(b)),
            Node::Const(_) => {
                let x = node.constant().unwrap_or_default();
                float(x, scalar)
                    .ok_or_else(|| CodegenError::NonFiniteConstant { function: f.name().to_string(), value: x })?
            }
            Node::Input { name, index: i } => {
                this_input = Some(name);
                index(&f.input_names()[name as usize], i as usize)
            }
            Node::SinCos(a) => {
                let (s, c) = (format_ident!("s{}", k), format_ident!("c{}", k));
                k += 1;
                let a = r(a);
                let stmt = match (sin_used[id], cos_used[id]) {
                    (true, true) => {
                        let elems = [pat(s.clone()), pat(c.clone())].into_iter().collect();
                        let tuple = Pat::Tuple(syn::PatTuple { attrs: vec![], paren_token: Default::default(), elems });
                        let_stmt(tuple, method(a, "sin_cos"))
                    }
                    (true, false) => let_stmt(pat(s.clone()), method(a, "sin")),
                    _ => let_stmt(pat(c.clone()), method(a, "cos")),
                };
                let mut defs = Vec::new();
                if sin_used[id] {
                    this_value = Some(names.len() as u32);
                    defs.push(names.len() as u32);
                    names.push(s.clone());
                }
                if cos_used[id] || !sin_used[id] {
                    cos_value[id] = Some(names.len() as u32);
                    defs.push(names.len() as u32);
                    names.push(c.clone());
                }
                lines.push(Line { stmt, defs, uses, inputs });
                cos_ref[id] = Some(path(c));
                path(s)
            }
            Node::Sin(sc) => {
                this_value = value[sc as usize];
                r(sc).clone()
            }
            Node::Cos(sc) => {
                this_value = cos_value[sc as usize];
                cos_ref[sc as usize].clone().expect("a Cos reads a SinCos")
            }
            _ => {
                let t = format_ident!("t{}", k);
                k += 1;
                let e = match (*node, fused) {
                    (_, Some(fu)) => {
                        let a = if fu.negate_product { negated(r(fu.a)) } else { r(fu.a).clone() };
                        let c = if fu.negate_addend { negated(r(fu.c)) } else { r(fu.c).clone() };
                        call(fma, &[&a, r(fu.b), &c])
                    }
                    (Node::Add(a, b), _) => binary(r(a), BinOp::Add(Default::default()), r(b)),
                    (Node::Sub(a, b), _) => binary(r(a), BinOp::Sub(Default::default()), r(b)),
                    (Node::Mul(a, b), _) => binary(r(a), BinOp::Mul(Default::default()), r(b)),
                    (Node::Div(a, b), _) => binary(r(a), BinOp::Div(Default::default()), r(b)),
                    (Node::Neg(a), _) => unary(UnOp::Neg(Default::default()), r(a).clone()),
                    (Node::Sqrt(a), _) => match trig {
                        Trig::Std => method(r(a), "sqrt"),
                        Trig::Libm => call(&["libm", sqrt], &[r(a)]),
                        // No std, no dependency: the module's `sqrt` (`sqrtf`), correctly rounded.
                        Trig::Batched | Trig::Inputs => call(&[sqrt], &[r(a)]),
                    },
                    _ => unreachable!("handled above"),
                };
                this_value = Some(names.len() as u32);
                lines.push(Line { stmt: let_stmt(pat(t.clone()), e), defs: vec![names.len() as u32], uses, inputs });
                names.push(t.clone());
                path(t)
            }
        };
        refs[id] = Some(reference);
        value[id] = this_value;
        input[id] = this_input;
    }
    let outputs: Vec<(Expr, Option<u32>)> = f
        .outputs()
        .iter()
        .map(|&o| (refs[o as usize].clone().expect("every node is written"), value[o as usize]))
        .collect();
    Ok(Body { lines, names, outputs })
}
