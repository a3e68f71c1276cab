//! The branches of a function (`trace/branches.rs`): for each group, the
//! body `NAME_branchG` of one branch, written over vector registers of the
//! kernel's `Lanes` in `f64` (each lane a branch) and the function
//! `NAME_branchG_run` that runs it on the branches two or four at a time,
//! or in `f32` a scalar body and a loop; the table `NAME_BRANCHG` of its
//! constants (one row per branch); and the statements in `NAME_sc` that
//! run them.

use super::statements::{self, BodyStyle, Dim, Param, Shape, Signature, Sizes};
use super::syntax::ident;
use crate::codegen::trace::branches::{result_index, results_name, BranchBody, Branched, Kind, ABA_UP};
use crate::codegen::{CodegenError, CodegenOptions, ScalarType};
use crate::model::Model;
use quote::{format_ident, quote};
use syn::{Expr, Stmt};

/// The name of group `g`'s body.
fn body_name(name: &str, g: usize) -> String {
    format!("{name}_branch{g}")
}

/// The name of the function that runs group `g`'s body in lanes.
fn run_name(name: &str, g: usize) -> String {
    format!("{name}_branch{g}_run")
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
    if x.motion() > 0 {
        list.push(Param::fixed("m", x.motion()));
    }
    if x.carried() > 0 {
        list.push(Param::fixed("x", x.carried()));
    }
    // Only the rows the body reads (the second part of an articulated-body
    // branch reads neither q̇ nor τ).
    for name in ["s", "c", "q", "qd", "qdd", "tau"] {
        if x.body.function.uses_input(name) {
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
) -> Result<(Vec<syn::Item>, Vec<bool>), CodegenError> {
    let mut items = Vec::new();
    let mut in_lanes = Vec::new();
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
                "its parent's motion `m` (ω, ω̇, the origin's acceleration and `U = [ω̇×] + [ω×][ω×]` row by row, \
                 in the parent's frame) and its joints' state; returns their τ, then the wrench it puts on its \
                 parent (moment, force; parent frame)"
            }
            Kind::Crba => {
                "its joints' sines and cosines; returns its own block of M (row after row), each joint's Iᶜ·S in \
                 its parent's frame (moment, force), and its composite inertia there (mass, m·c, Ī as xx, yy, zz, \
                 xy, xz, yz)"
            }
            Kind::AbaUp => {
                "its parent's angular velocity `m` (parent frame) and its joints' state and τ; returns, for the \
                 articulated-body algorithm's first passes, its articulated inertia in its parent's frame (A as xx, \
                 yy, zz, xy, xz, yz, B row by row, C), its bias force there (moment, force), then what its second \
                 part reads (`x`)"
            }
            Kind::AbaDown => {
                "its parent's classic acceleration `m` (ω̇, the origin's acceleration with gravity folded in; parent \
                 frame) and what its first part computed (`x`); returns its joints' q̈"
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
        let mut lanes = false;
        for item in body {
            let syn::Item::Fn(mut func) = item else { continue };
            if func.sig.ident != emitted {
                continue;
            }
            func.vis = syn::Visibility::Inherited;
            func.attrs.retain(|a| !a.path().is_ident("doc") && !a.path().is_ident("inline"));
            // In f64, the body over registers of branches (see `in_lanes`),
            // and the function that runs it on every branch.
            let vector = match options.scalar {
                ScalarType::F64 => in_lanes_body(&func, &signature.name),
                ScalarType::F32 => None,
            };
            let doc = match vector {
                Some(_) => format!(
                    "{doc}\n\n Written over registers `V` of branches (lane l of each register one branch, the \
                     operations of `Lanes`, the bits of scalar code in every lane); run by [`{}`].",
                    run_name(name, g)
                ),
                None => doc.clone(),
            };
            if let Some(vector) = vector {
                func = vector;
                lanes = true;
            }
            func.attrs.splice(0..0, doc.lines().map(|line| -> syn::Attribute { syn::parse_quote!(#[doc = #line]) }));
            func.attrs.push(syn::parse_quote!(#[inline(always)]));
            items.push(syn::Item::Fn(func));
        }
        if lanes {
            let up = x.up.map(|u| b.branches[u].outputs());
            items.push(runner(name, g, x, up)?);
        }
        in_lanes.push(lanes);
        let ty = statements::scalar_type(options.scalar);
        let p = proc_macro2::Literal::usize_unsuffixed(x.table[0].len());
        let l = proc_macro2::Literal::usize_unsuffixed(x.table.len());
        let rows = x.table.iter().map(|row| {
            let entries = row.iter().map(|&v| super::syntax::float(v, options.scalar).expect("finite constants"));
            quote!([#(#entries),*])
        });
        let table = format_ident!("{}", table_name(name, g));
        let body = if lanes { signature.name.clone() } else { emitted.clone() };
        let doc = format!(" The constants of [`{body}`], one row per branch: {}.", starts.join(", "));
        items.push(
            syn::parse2(quote! {
                #[doc = #doc]
                #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]
                const #table: [[#ty; #p]; #l] = [#(#rows),*];
            })
            .map_err(|e| CodegenError::Internal(e.to_string()))?,
        );
    }
    Ok((items, in_lanes))
}

/// The statements of `NAME_sc` that run the bodies of phase `phase`
/// (`BranchBody::phase`) for each branch, from the parents' motions (`args`,
/// `BranchBody::motion` numbers a body, in order): the results go
/// to `r0`, `r1`, … (entry by entry, the branches' values of an entry
/// together, `trace::branches::result_index`), which the rest of the body reads.
pub(super) fn glue(
    name: &str,
    b: &Branched,
    floating: bool,
    dispatch: bool,
    lanes: &[bool],
    phase: usize,
    args: &[Expr],
) -> Result<Vec<Stmt>, CodegenError> {
    let (q_off, v_off) = if floating { (7, 6) } else { (0, 0) };
    let mut stmts = Vec::new();
    let mut args = args;
    for (g, x) in b.branches.iter().enumerate().filter(|(_, x)| x.phase() == phase) {
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
        // The scalar body's arguments for branch `l`, and the runner's (all branches).
        let mut call_args = vec![quote!(&#table[l])];
        let mut run_args = Vec::new();
        if x.motion() > 0 {
            let (motion, more) = args.split_at(x.motion());
            args = more;
            locals.push(quote!(let #m = [#(#motion),*];));
            call_args.push(quote!(&#m));
            run_args.push(quote!(&#m));
        }
        let branches = x.group.lanes.len();
        let in_lanes = lanes.get(g).copied().unwrap_or(false);
        for p in params(x).iter().skip(call_args.len()) {
            let local = format_ident!("{}_b{g}", p.name);
            call_args.push(quote!(&#local[l]));
            let rows: Vec<proc_macro2::TokenStream> = match (p.name.as_str(), x.up) {
                // In lanes, the second part of an articulated-body branch
                // reads its first part's results as they are.
                ("x", Some(up)) if in_lanes => {
                    let from = ident(&results_name(up));
                    run_args.push(quote!(&#from));
                    continue;
                }
                // Else it reads what its first part returned past ABA_UP,
                // entry by entry.
                ("x", Some(up)) => {
                    let from = ident(&results_name(up));
                    (0..branches)
                        .map(|l| {
                            let entries = (0..x.carried())
                                .map(|i| proc_macro2::Literal::usize_unsuffixed(result_index(branches, l, ABA_UP + i)));
                            quote!([#(#from[#entries]),*])
                        })
                        .collect()
                }
                _ => {
                    let source = ident(&p.name);
                    let skip = match p.name.as_str() {
                        "q" => q_off,
                        "qd" | "qdd" | "tau" => v_off,
                        _ => 0,
                    };
                    x.group
                        .lanes
                        .iter()
                        .map(|lane| {
                            let entries = lane.iter().map(|&j| proc_macro2::Literal::usize_unsuffixed(skip + j));
                            quote!([#(#source[#entries]),*])
                        })
                        .collect()
                }
            };
            locals.push(quote!(let #local = [#(#rows),*];));
            run_args.push(quote!(&#local));
        }
        let total = proc_macro2::Literal::usize_unsuffixed(x.group.lanes.len() * x.outputs());
        let block: syn::Block = if in_lanes {
            // Four branches to a register where there are more than two and
            // the instructions (`Isa::QUADS`: AVX2) have them, else two.
            let run = format_ident!("{}", run_name(name, g));
            let isa = if dispatch { quote!(I) } else { quote!(Baseline) };
            let run_all = |w: usize| {
                let w = proc_macro2::Literal::usize_unsuffixed(w);
                quote!(#run::<#isa, #w>(#(#run_args,)* &mut #r);)
            };
            let (four, two) = (run_all(4), run_all(2));
            let runs = match x.group.lanes.len() > 2 {
                true => quote!(if #isa::QUADS { #four } else { #two }),
                false => two,
            };
            syn::parse2(quote! {{
                #(#locals)*
                let mut #r = [0.0; #total];
                #runs
            }})
        } else {
            let branches = proc_macro2::Literal::usize_unsuffixed(x.group.lanes.len());
            syn::parse2(quote! {{
                #(#locals)*
                let mut #r = [0.0; #total];
                for l in 0..#branches {
                    for (i, v) in #call(#(#call_args),*).into_iter().enumerate() {
                        #r[i * #branches + l] = v;
                    }
                }
            }})
        }
        .map_err(|e| CodegenError::Internal(e.to_string()))?;
        stmts.extend(block.stmts);
    }
    Ok(stmts)
}

/// A branch body over `f64` (`func`, named `name`) over registers `V` of
/// `Lanes`: the same operations in the same order, each on every lane, so
/// each lane gets the scalar body's bits (square roots included: IEEE
/// rounds them correctly in every lane). `None` where the body has an
/// operation `Lanes` lacks: it then stays scalar.
fn in_lanes_body(func: &syn::ItemFn, name: &str) -> Option<syn::ItemFn> {
    let mut f = func.clone();
    f.sig.ident = format_ident!("{name}");
    f.sig.generics = syn::parse_quote!(<I: Isa, V: Lanes>);
    let registers = |ty: &mut syn::Type| match ty {
        syn::Type::Array(a) => {
            *a.elem = syn::parse_quote!(V);
            Some(())
        }
        _ => None,
    };
    for input in &mut f.sig.inputs {
        let syn::FnArg::Typed(arg) = input else { return None };
        let syn::Type::Reference(r) = &mut *arg.ty else { return None };
        registers(&mut r.elem)?;
    }
    let syn::ReturnType::Type(_, ty) = &mut f.sig.output else { return None };
    registers(ty)?;
    for stmt in &mut f.block.stmts {
        match stmt {
            syn::Stmt::Local(syn::Local { init: Some(init), .. }) if init.diverge.is_none() => {
                *init.expr = lanes_expr(&init.expr)?;
            }
            syn::Stmt::Expr(e, _) => *e = lanes_expr(e)?,
            _ => return None,
        }
    }
    Some(f)
}

/// `e` over registers: literals splat, `a + b` as `a.add(b)` (and `sub`,
/// `mul`, `div`, `neg`), `fma(a, b, c)` as `a.mul_add::<I>(b, c)`, a square
/// root as `a.sqrt()`.
fn lanes_expr(e: &Expr) -> Option<Expr> {
    use syn::{BinOp, UnOp};
    Some(match e {
        Expr::Lit(_) => syn::parse_quote!(V::splat(#e)),
        Expr::Path(_) | Expr::Index(_) => e.clone(),
        Expr::Paren(p) => lanes_expr(&p.expr)?,
        Expr::Array(a) => {
            let items = a.elems.iter().map(lanes_expr).collect::<Option<Vec<_>>>()?;
            syn::parse_quote!([#(#items),*])
        }
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
            Expr::Lit(_) => syn::parse_quote!(V::splat(#e)),
            inner => {
                let x = lanes_expr(inner)?;
                syn::parse_quote!(#x.neg())
            }
        },
        Expr::Binary(b) => {
            let (l, r) = (lanes_expr(&b.left)?, lanes_expr(&b.right)?);
            match b.op {
                BinOp::Add(_) => syn::parse_quote!(#l.add(#r)),
                BinOp::Sub(_) => syn::parse_quote!(#l.sub(#r)),
                BinOp::Mul(_) => syn::parse_quote!(#l.mul(#r)),
                BinOp::Div(_) => syn::parse_quote!(#l.div(#r)),
                _ => return None,
            }
        }
        Expr::Call(call) => {
            let Expr::Path(f) = &*call.func else { return None };
            let args = call.args.iter().map(lanes_expr).collect::<Option<Vec<_>>>()?;
            match f.path.segments.last()?.ident.to_string().as_str() {
                "fma" => {
                    let [a, b, c] = <[Expr; 3]>::try_from(args).ok()?;
                    syn::parse_quote!(#a.mul_add::<I>(#b, #c))
                }
                // the module's `sqrt(x)` or `libm::sqrt(x)`
                "sqrt" => {
                    let [a] = <[Expr; 1]>::try_from(args).ok()?;
                    syn::parse_quote!(#a.sqrt())
                }
                _ => return None,
            }
        }
        // `x.sqrt()` (std)
        Expr::MethodCall(m) if m.method == "sqrt" && m.args.is_empty() => {
            let a = lanes_expr(&m.receiver)?;
            syn::parse_quote!(#a.sqrt())
        }
        _ => return None,
    })
}

/// `NAME_branchG_run::<I, W>`: group `g`'s body in lanes on its branches,
/// `W` at a time, each lane's results to its branch's entries of `r`.
/// `up`: for the second part of an articulated-body branch, the number of
/// its first part's outputs, whose results (`x`) it reads as they are.
fn runner(name: &str, g: usize, x: &BranchBody, up: Option<usize>) -> Result<syn::Item, CodegenError> {
    let lit = proc_macro2::Literal::usize_unsuffixed;
    let (nb, l, r) = (x.group.lanes[0].len(), x.group.lanes.len(), x.outputs());
    let (nb_, l_, r_, p_, total) = (lit(nb), lit(l), lit(r), lit(x.table[0].len()), lit(l * r));
    let body = format_ident!("{}", body_name(name, g));
    let table = format_ident!("{}", table_name(name, g));
    let run = format_ident!("{}", run_name(name, g));
    let mut ps = Vec::new();
    let mut args = vec![quote!(&branch_lanes::<W, #p_, #l_>(&#table, l))];
    let mut splat = quote!();
    for p in params(x).iter().skip(1) {
        let id = ident(&p.name);
        if let ("x", Some(outputs)) = (p.name.as_str(), up) {
            let (n, carried, first) = (lit(l * outputs), lit(x.carried()), lit(ABA_UP));
            ps.push(quote!(#id: &[f64; #n]));
            args.push(quote!(&branch_entries::<W, #carried, #l_, #n>(#id, #first, l)));
        } else if p.name == "m" {
            let m = lit(x.motion());
            ps.push(quote!(#id: &[f64; #m]));
            splat = quote!(let #id = branch_splat::<<[f64; W] as ToLanes>::V, #m>(#id););
            args.push(quote!(&#id));
        } else {
            let len = match p.len {
                super::statements::Dim::Fixed(n) => lit(n),
                _ => nb_.clone(),
            };
            ps.push(quote!(#id: &[[f64; #len]; #l_]));
            args.push(quote!(&branch_lanes::<W, #len, #l_>(#id, l)));
        }
    }
    let doc = format!(
        " Runs [`{body}`] on the {l} branches of [`{}`], `W` to a register: each lane's results to its branch's \
         entries of `r` ({r} a branch, entry by entry). Takes the rows of each branch's inputs.",
        table_name(name, g)
    );
    syn::parse2(quote! {
        #[doc = #doc]
        #[inline(always)]
        fn #run<I: Isa, const W: usize>(#(#ps,)* r: &mut [f64; #total])
        where
            [f64; W]: ToLanes,
        {
            #splat
            let mut l = 0;
            while l < #l_ {
                let out = #body::<I, <[f64; W] as ToLanes>::V>(#(#args),*);
                branch_rows::<_, W, #r_, #total>(&out, r, l);
                l += W;
            }
        }
    })
    .map_err(|e| CodegenError::Internal(e.to_string()))
}
