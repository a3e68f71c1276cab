//! Long function bodies emitted as a chain of private parts.
//!
//! A generated body is one `let` per operation in a single basic block, and
//! two things in rustc grow worse than linearly with its length (measured in
//! `docs/performance.md`, "Long chains"):
//!
//! - with debug information (cargo's default `dev` profile), every `let`
//!   opens a lexical scope nested in the previous one, and LLVM's DWARF
//!   writer recurses once per scope: rustc overflows its stack on a few
//!   thousand `let`s in one function;
//! - in release builds, LLVM's SLP vectoriser and DAG combiner take time
//!   super-linear in the size of a basic block.
//!
//! So a body longer than [`CodegenOptions::split_lets`](super::CodegenOptions::split_lets)
//! `let`s becomes private functions `NAME_part1`, `NAME_part2`, … of at
//! most that many `let`s each, called in order by the public `NAME`. The
//! statements are the unsplit body's, cut where the budget runs out, with the same names: a value that a later part (or the
//! result) reads is stored into a fixed-size array `carry` at the end of the
//! part that computes it, and loaded back under its own name (`let t12 =
//! carry[3];`) at the start of each part that reads it; the loads count in
//! the budget. Slots are reused once their last reader has loaded them
//! (lowest free slot first), so the output is deterministic. Every value is
//! computed by the same operations in the same order as unsplit, so the
//! results are bit for bit the same.
//!
//! A body of up to [`INLINE_PARTS_MAX_LETS`] `let`s has its parts
//! `#[inline(always)]` (the AVX2 + FMA chain calls the parts' generic bodies
//! directly): a debug build still sees each part's scopes under its own
//! inlined subroutine (no overflow; the 30-joint chain's module inlined
//! whole compiled in 11.7 s against 11.2 s split), and an
//! optimised build gets the whole body back, which runs faster than the
//! chain of calls with its carried values in memory (the Panda's
//! `inverse_dynamics_derivatives`: 790 → 612 ns; `docs/performance.md`).
//! Longer bodies keep `#[inline(never)]` parts: optimised with debug
//! information, the inlined 30-joint chain took 40 s against 23 s.

use super::statements::{checks, TIERS};
use super::syntax::{assign, index, let_stmt, pat, path};
use crate::codegen::CodegenError;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use std::collections::BTreeSet;
use syn::{Expr, Stmt};

/// Bodies of up to this many `let`s, when split, have their parts inlined
/// (see the module documentation).
pub(crate) const INLINE_PARTS_MAX_LETS: usize = 10_000;

/// One statement of a body and the values it defines and reads.
pub(crate) struct Line {
    /// The `let` statement.
    pub stmt: Stmt,
    /// The values it binds (indexes into the body's value names).
    pub defs: Vec<u32>,
    /// The values it reads.
    pub uses: Vec<u32>,
    /// The input arrays it reads (indexes into the function's input names).
    pub inputs: Vec<u32>,
}

/// A parameter of the emitted function, as the parts see it.
pub(crate) struct PartParam {
    /// Its name.
    pub name: Ident,
    /// `name: &[T; len]`.
    pub typed: TokenStream,
    /// The index of its input name in the traced function, if it reads one.
    pub input: Option<u32>,
}

/// The body of one emitted function, before it is put into items.
pub(crate) struct Body {
    /// The statements, in order.
    pub lines: Vec<Line>,
    /// The name of each value.
    pub names: Vec<Ident>,
    /// The outputs in order: how to write each, and the value it is (none for
    /// a constant or an input entry).
    pub outputs: Vec<(Expr, Option<u32>)>,
}

/// The function `shell` (signature, documentation, attributes) with `body`:
/// one item when the body has at most `max_lets` `let`s (or `max_lets` is
/// `None`), else the public function and its parts. `result` arranges the
/// output expressions into the returned array.
///
/// With `dispatch` (the body's sums written `I::fma`), each part is a
/// generic `NAME_partK_on<I: Isa>` called by `NAME_partK` for `Baseline`,
/// and by `NAME_partK_avx512` and `NAME_partK_avx2_fma`
/// (`#[target_feature(enable = "avx2,fma")]`) for `Avx2Fma`, and the public
/// function calls `NAME_avx512` or `NAME_avx2_fma`, the chain of those
/// parts, where the processor has the instructions (see
/// [`emit_function`](super::emit::emit_function) and [`TIERS`]).
pub(crate) fn assemble(
    mut shell: syn::ItemFn,
    body: Body,
    params: &[PartParam],
    scalar: &TokenStream,
    max_lets: Option<usize>,
    result: impl Fn(Vec<Expr>) -> Expr,
    dispatch: bool,
) -> Result<Vec<syn::Item>, CodegenError> {
    let Some(max) = max_lets.filter(|&m| body.lines.len() > m) else {
        shell.block.stmts.extend(body.lines.into_iter().map(|l| l.stmt));
        shell.block.stmts.push(Stmt::Expr(result(body.outputs.into_iter().map(|(e, _)| e).collect()), None));
        return Ok(vec![syn::Item::Fn(shell)]);
    };
    let parse = |tokens: TokenStream| -> Result<syn::ItemFn, CodegenError> {
        syn::parse2(tokens).map_err(|e| CodegenError::Internal(e.to_string()))
    };
    let allow = quote!(#[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal, clippy::too_many_lines, clippy::too_many_arguments)]);
    // Below 3, a statement reading two carried values would not fit.
    let max = max.max(3);
    let plan = Plan::new(&body, max);
    let inline = body.lines.len() <= INLINE_PARTS_MAX_LETS;
    let part_inline = if inline { quote!(#[inline(always)]) } else { quote!(#[inline(never)]) };
    let name = shell.sig.ident.to_string();
    let k = proc_macro2::Literal::usize_unsuffixed(plan.slots.max(1));
    let n_parts = plan.parts.len();
    let mut items = Vec::with_capacity(3 * n_parts + 2);
    let mut lines = body.lines.into_iter();
    // The calls of the parts, in order: `NAME_partK(args, &mut carry);` (and
    // `NAME_partK_avx2_fma(…)`, … for each copy of `TIERS`).
    let mut chain: Vec<Stmt> = Vec::new();
    let mut fast_chains: Vec<Vec<Stmt>> = vec![Vec::new(); TIERS.len()];
    for (p, part) in plan.parts.iter().enumerate() {
        let part_name = format_ident!("{name}_part{}", p + 1);
        let own = lines.by_ref().take(part.len);
        let used = || params.iter().filter(|q| q.input.is_some_and(|i| part.inputs.contains(&i)));
        let typed: Vec<&TokenStream> = used().map(|q| &q.typed).collect();
        let args: Vec<&Ident> = used().map(|q| &q.name).collect();
        let doc = format!(
            " Part {} of {n_parts} of [`{name}`]: its statements {} to {}, with the values of earlier parts \
             loaded from `carry` and those later parts read stored into it.",
            p + 1,
            part.first + 1,
            part.first + part.len
        );
        let mut stmts: Vec<Stmt> = Vec::new();
        for &v in &part.loads {
            stmts.push(let_stmt(pat(body.names[v as usize].clone()), index("carry", plan.slot[v as usize])));
        }
        stmts.extend(own.map(|l| l.stmt));
        for &v in &part.stores {
            stmts.push(assign(index("carry", plan.slot[v as usize]), path(body.names[v as usize].clone())));
        }
        chain.push(syn::parse_quote!(#part_name(#(#args,)* &mut carry);));
        let mut f = if dispatch {
            let on = format_ident!("{part_name}_on");
            let on_doc = format!(" The body of [`{part_name}`], in the instructions of `I`.");
            items.push(syn::Item::Fn(parse(quote! {
                #[doc = #doc]
                #part_inline
                #[allow(clippy::too_many_arguments)]
                fn #part_name(#(#typed,)* carry: &mut [#scalar; #k]) {
                    #on::<Baseline>(#(#args,)* carry)
                }
            })?));
            for (t, fast_chain) in TIERS.iter().zip(&mut fast_chains) {
                let (fast, isa) = (t.name(&part_name.to_string()), t.isa());
                if inline {
                    // Inlined into `NAME_sc_avx2_fma` (`_avx512`), which has the features.
                    fast_chain.push(syn::parse_quote!(#on::<#isa>(#(#args,)* &mut carry);));
                } else {
                    let (cfg, features) = (t.cfg(), t.target_feature());
                    let fast_doc = format!(" [`{part_name}`] compiled for processors with {}.", t.what);
                    items.push(syn::Item::Fn(parse(quote! {
                        #[doc = #fast_doc]
                        #cfg
                        #features
                        #[inline(never)]
                        #[allow(clippy::too_many_arguments)]
                        unsafe fn #fast(#(#typed,)* carry: &mut [#scalar; #k]) {
                            #on::<#isa>(#(#args,)* carry)
                        }
                    })?));
                    fast_chain.push(syn::parse_quote!(#fast(#(#args,)* &mut carry);));
                }
            }
            parse(quote! {
                #[doc = #on_doc]
                #[inline(always)]
                #allow
                fn #on<I: Isa>(#(#typed,)* carry: &mut [#scalar; #k]) {}
            })?
        } else {
            parse(quote! {
                #[doc = #doc]
                #part_inline
                #allow
                fn #part_name(#(#typed,)* carry: &mut [#scalar; #k]) {}
            })?
        };
        f.block.stmts = stmts;
        items.push(syn::Item::Fn(f));
    }
    let outputs: Vec<Expr> = body
        .outputs
        .into_iter()
        .map(|(e, v)| match v {
            Some(v) => index("carry", plan.slot[v as usize]),
            None => e,
        })
        .collect();
    if dispatch {
        // `NAME_avx2_fma` (`_avx512`): the same chain of the parts' copies.
        let args: Vec<Box<syn::Pat>> = shell
            .sig
            .inputs
            .iter()
            .filter_map(|arg| match arg {
                syn::FnArg::Typed(t) => Some(t.pat.clone()),
                syn::FnArg::Receiver(_) => None,
            })
            .collect();
        for (t, fast_chain) in TIERS.iter().zip(&fast_chains).rev() {
            let (inputs, output, unused) = (&shell.sig.inputs, &shell.sig.output, &shell.block.stmts);
            let result = result(outputs.clone());
            // The parts' copies are unsafe to call; the inlined generic bodies are not.
            let chain = if inline { quote!(#(#fast_chain)*) } else { quote!(unsafe { #(#fast_chain)* }) };
            let body = quote! {
                #(#unused)*
                let mut carry = [0.0; #k];
                #chain
                #result
            };
            items.insert(0, syn::Item::Fn(parse(t.copy(&name, quote!((#inputs) #output), body))?));
        }
        let checks = checks(&name, &args);
        let checks: syn::Block = syn::parse2(quote!({ #checks })).map_err(|e| CodegenError::Internal(e.to_string()))?;
        shell.block.stmts.splice(0..0, checks.stmts);
    }
    shell.block.stmts.push(syn::parse_quote!(let mut carry = [0.0; #k];));
    shell.block.stmts.extend(chain);
    shell.block.stmts.push(Stmt::Expr(result(outputs), None));
    items.insert(0, syn::Item::Fn(shell));
    Ok(items)
}

/// One part: a run of statements.
struct Part {
    /// The index of its first statement.
    first: usize,
    /// How many statements.
    len: usize,
    /// The values of earlier parts it reads, by value index.
    loads: Vec<u32>,
    /// The values it defines that later parts or the outputs read.
    stores: Vec<u32>,
    /// The input arrays it reads.
    inputs: BTreeSet<u32>,
}

/// Where a body is cut and where each carried value lives.
struct Plan {
    parts: Vec<Part>,
    /// The slot of `carry` of each carried value (`usize::MAX` if none).
    slot: Vec<usize>,
    /// The number of slots.
    slots: usize,
}

impl Plan {
    fn new(body: &Body, max: usize) -> Plan {
        let n_values = body.names.len();
        let mut def_line = vec![usize::MAX; n_values];
        for (i, l) in body.lines.iter().enumerate() {
            for &v in &l.defs {
                def_line[v as usize] = i;
            }
        }
        // Cut greedily: a part takes statements while its statements plus
        // the loads they need stay within the budget.
        let mut parts = Vec::new();
        let mut first = 0;
        let mut loads = BTreeSet::new();
        let mut inputs = BTreeSet::new();
        for (i, l) in body.lines.iter().enumerate() {
            let new_loads = |first: usize, loads: &BTreeSet<u32>| {
                let mut new: Vec<u32> =
                    l.uses.iter().copied().filter(|&v| def_line[v as usize] < first && !loads.contains(&v)).collect();
                new.dedup();
                new.len()
            };
            if i > first && (i - first) + loads.len() + new_loads(first, &loads) + 1 > max {
                let loads = std::mem::take(&mut loads);
                let inputs = std::mem::take(&mut inputs);
                parts.push(Part { first, len: i - first, loads: loads.into_iter().collect(), stores: vec![], inputs });
                first = i;
            }
            loads.extend(l.uses.iter().copied().filter(|&v| def_line[v as usize] < first));
            inputs.extend(l.inputs.iter().copied());
        }
        let len = body.lines.len() - first;
        parts.push(Part { first, len, loads: loads.into_iter().collect(), stores: vec![], inputs });
        // The part of each statement, and the last part that reads each value
        // (`parts.len()` for the outputs, read by the public function).
        let part_of_line = |i: usize| parts.partition_point(|p| p.first <= i) - 1;
        let mut last_reader = vec![None::<usize>; n_values];
        for (p, part) in parts.iter().enumerate() {
            for &v in &part.loads {
                last_reader[v as usize] = Some(p);
            }
        }
        for v in body.outputs.iter().filter_map(|(_, v)| *v) {
            last_reader[v as usize] = Some(parts.len());
        }
        let mut stores: Vec<Vec<u32>> = vec![Vec::new(); parts.len()];
        for v in 0..n_values {
            let Some(reader) = last_reader[v] else { continue };
            let p = part_of_line(def_line[v]);
            if reader > p {
                stores[p].push(v as u32);
            }
        }
        // Slots: a slot is free again once its value's last reader has
        // loaded it (the part's stores come after its loads).
        let mut slot = vec![usize::MAX; n_values];
        let mut free = BTreeSet::new();
        let mut slots = 0;
        for (p, part) in parts.iter_mut().enumerate() {
            for &v in &part.loads {
                if last_reader[v as usize] == Some(p) {
                    free.insert(slot[v as usize]);
                }
            }
            for &v in &stores[p] {
                slot[v as usize] = free.pop_first().unwrap_or_else(|| {
                    slots += 1;
                    slots - 1
                });
            }
            part.stores = std::mem::take(&mut stores[p]);
        }
        Plan { parts, slot, slots }
    }
}

/// The header's line on split functions (`split`: each split function's
/// name and number of parts); empty when none was split, so that modules
/// without long bodies do not change.
pub(crate) fn header_note(max_lets: Option<usize>, split: &[(String, usize)]) -> String {
    match max_lets {
        Some(max) if !split.is_empty() => {
            let list: Vec<String> = split.iter().map(|(name, parts)| format!("{name} ({parts})")).collect();
            format!(
                "// Long bodies (over {max} lets) cut into private parts NAME_part1, NAME_part2, ... called in order \
                 (split_lets): {}.\n",
                list.join(", ")
            )
        }
        _ => String::new(),
    }
}

/// The number of parts of the items [`assemble`] made for one function, if
/// it was split.
pub(crate) fn parts_of(items: &[syn::Item]) -> Option<usize> {
    let name = |item: &syn::Item| match item {
        syn::Item::Fn(f) => f.sig.ident.to_string(),
        _ => String::new(),
    };
    let prefix = format!("{}_part", name(items.first()?));
    let parts = items.iter().filter(|item| name(item).starts_with(&prefix)).count();
    (parts > 0).then_some(parts)
}
