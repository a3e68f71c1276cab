//! Factoring after the trace, where use counts are known.
//!
//! While a graph is built, nobody knows whether `a·x` will be used again,
//! so `a·x + b·x` cannot become `(a + b)·x` without risking a
//! multiplication more. Once a function is traced and its dead code is
//! gone, the uses are known: [`factor`] rebuilds the function through the
//! simplifying [`Graph`] and, where both products are used only by the sum,
//! shares their common factor:
//!
//! - `k·u ± k·v → k·(u ± v)` (one multiplication fewer);
//! - `(−x) − y → −(x + y)` when `−x` has no other use (the negation moves
//!   out, where the next addition absorbs it).
//!
//! Both may change the last bits of a value (as the graph's value-changing
//! [`Rewrites`](super::Rewrites) do), so [`factor`] runs only when
//! `like_terms` is on. It repeats until nothing changes.

use super::graph::{Graph, Rewrites};
use super::node::{Node, NodeId};
use super::traced::Traced;

/// One factoring pass.
fn pass(f: &Traced, rewrites: Rewrites) -> Traced {
    let nodes = f.nodes();
    let uses = f.use_counts();
    let mut g = Graph::with_rewrites(rewrites);
    let mut new: Vec<NodeId> = Vec::with_capacity(nodes.len());
    // The two factors of a product used once.
    let product = |id: NodeId| match nodes[id as usize] {
        Node::Mul(p, x) if uses[id as usize] == 1 => Some((p, x)),
        _ => None,
    };
    for node in nodes {
        let m = |id: NodeId| new[id as usize];
        let id = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => g.input(&f.input_names()[name as usize], index as usize),
            Node::Add(a, b) | Node::Sub(a, b) => {
                let is_add = matches!(node, Node::Add(..));
                let common = product(a).zip(product(b)).and_then(|((p, x), (q, y))| {
                    // k·u ± k·v with k the shared factor
                    if p == q {
                        Some((p, x, y))
                    } else if x == y {
                        Some((x, p, q))
                    } else if p == y {
                        Some((p, x, q))
                    } else if x == q {
                        Some((x, p, y))
                    } else {
                        None
                    }
                });
                match (common, nodes[a as usize]) {
                    (Some((k, u, v)), _) => {
                        let s = if is_add { g.add(m(u), m(v)) } else { g.sub(m(u), m(v)) };
                        g.mul(m(k), s)
                    }
                    (None, Node::Neg(x)) if !is_add && uses[a as usize] == 1 => {
                        let s = g.add(m(x), m(b));
                        g.neg(s)
                    }
                    _ if is_add => g.add(m(a), m(b)),
                    _ => g.sub(m(a), m(b)),
                }
            }
            Node::Mul(a, b) => g.mul(m(a), m(b)),
            Node::Div(a, b) => g.div(m(a), m(b)),
            Node::Neg(a) => g.neg(m(a)),
            Node::Sqrt(a) => g.sqrt(m(a)),
            Node::SinCos(a) => {
                // The pair is rebuilt by its Sin / Cos users; keep a slot.
                m(a)
            }
            Node::Sin(sc) => {
                g.sin_cos(m(match nodes[sc as usize] {
                    Node::SinCos(a) => a,
                    _ => unreachable!("Sin reads a SinCos"),
                }))
                .0
            }
            Node::Cos(sc) => {
                g.sin_cos(m(match nodes[sc as usize] {
                    Node::SinCos(a) => a,
                    _ => unreachable!("Cos reads a SinCos"),
                }))
                .1
            }
        };
        new.push(id);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut out = Traced::from_ids(f.name(), &g, &outputs);
    // Input vectors keep their names even if no longer read.
    out.set_input_names(f.input_names());
    out
}

/// Factors `f` until its operation count stops falling; see the [symbolic
/// module](super#after-the-trace). With `rewrites.like_terms` off, `f` is returned
/// unchanged.
pub fn factor(f: &Traced, rewrites: Rewrites) -> Traced {
    if !rewrites.like_terms {
        return f.clone();
    }
    let mut best = f.clone();
    for _ in 0..8 {
        let next = pass(&best, rewrites);
        if next.op_count().total() >= best.op_count().total() {
            break;
        }
        best = next;
    }
    best
}
