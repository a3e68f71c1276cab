//! Reassociation of sums for a shorter critical path.
//!
//! The trace writes a sum the way the algorithm adds: left to right, e.g.
//! a child's force turned into the parent's frame and added to the
//! parent's own, term after term. Where the last term to be added is the
//! first to be ready, such a chain makes every addition wait for the one
//! before it, and the generated body waits on its longest chain of
//! dependent operations (its [`CriticalPath`](super::CriticalPath)) rather
//! than on the number of operations.
//!
//! [`balance`] rebuilds every *sum tree* — additions, subtractions and
//! negations whose inner nodes have no other use — where that makes it
//! ready earlier, from its leaves
//! (operands with signs), always adding the two leaves that are ready
//! first (by the latency-weighted depth of [`Latency`]), like a Huffman
//! code. The result is ready as early as any order of the same additions
//! allows; the number of operations does not grow (`n` leaves take `n − 1`
//! additions or subtractions, and a final negation only where every leaf
//! is negative, which the original had to pay for too).
//!
//! Products are left as traced: rebalancing chains of multiplications the
//! same way shortened the critical path a little more but made the compiled
//! bodies slower, measured (`docs/performance.md`, "Design choices decided
//! by a measurement"): the critical path is not the only limit (register
//! pressure and the overlap of consecutive calls are others).
//!
//! Reassociation changes rounding: `(a + b) + c` and `a + (b + c)` may
//! differ in the last bits, by at most about `n·ε·Σ|leaf|` for `n` leaves,
//! the same bound as the left-to-right sum has. It is a value-changing
//! rewrite, applied only when [`Rewrites::reassociate`](super::Rewrites) is
//! on (the default); the generated code stays within the 1e-12 contract of
//! the generic solver (the tests in `dynagen/tests/codegen_*.rs` and
//! `tests/tests/generated_*.rs` check it with reassociation on).

use super::count::Latency;
use super::graph::{Graph, Rewrites};
use super::node::{Node, NodeId};
use super::traced::Traced;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A sum is rebuilt only if that makes it ready earlier (by at least this
/// many cycles); otherwise it stays as traced. A tree keeps more partial
/// sums alive at once than the traced chain, which costs register spills:
/// rebuilding every sum, gain or not, measured slower than rebuilding only
/// where it helps, and a larger threshold kept only part of the gain
/// (`docs/performance.md`, "Design choices decided by a measurement").
const MIN_GAIN: u32 = 1;

/// The ready time of every node of a graph, extended as the graph grows.
struct Ready {
    cycles: Vec<u32>,
    latency: Latency,
}

impl Ready {
    fn of(&mut self, g: &Graph, id: NodeId) -> u32 {
        let nodes = g.nodes();
        while self.cycles.len() < nodes.len() {
            let n = &nodes[self.cycles.len()];
            let start = n.operands().map(|a| self.cycles[a as usize]).max().unwrap_or(0);
            self.cycles.push(start + self.latency.of(n));
        }
        self.cycles[id as usize]
    }
}

/// `f` with every sum tree rebuilt as the earliest-ready tree of the same
/// leaves (the comments of `symbolic/balance.rs` say how). The rebuilt graph makes
/// the given `rewrites`.
pub fn balance(f: &Traced, latency: &Latency, rewrites: Rewrites) -> Traced {
    let nodes = f.nodes();
    let uses = f.use_counts();
    let is_sum = |id: NodeId| matches!(nodes[id as usize], Node::Add(..) | Node::Sub(..) | Node::Neg(_));
    // An inner node of a sum tree: a sum node whose only use is a sum node.
    let mut inner = vec![false; nodes.len()];
    for n in nodes {
        if matches!(n, Node::Add(..) | Node::Sub(..) | Node::Neg(_)) {
            for op in n.operands() {
                if uses[op as usize] == 1 && is_sum(op) {
                    inner[op as usize] = true;
                }
            }
        }
    }
    let mut g = Graph::with_rewrites(rewrites);
    let mut ready = Ready { cycles: Vec::new(), latency: *latency };
    let mut new: Vec<NodeId> = Vec::with_capacity(nodes.len());
    for (id, node) in nodes.iter().enumerate() {
        let m = |x: NodeId| new[x as usize];
        let mapped = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => g.input(&f.input_names()[name as usize], index as usize),
            // Inner nodes are rebuilt by their tree's root (a copy made here
            // for operand numbering is dead code, dropped below).
            Node::Add(a, b) if inner[id] => g.add(m(a), m(b)),
            Node::Sub(a, b) if inner[id] => g.sub(m(a), m(b)),
            Node::Neg(a) if inner[id] => g.neg(m(a)),
            Node::Add(..) | Node::Sub(..) | Node::Neg(_) => {
                let traced = match *node {
                    Node::Add(a, b) => g.add(m(a), m(b)),
                    Node::Sub(a, b) => g.sub(m(a), m(b)),
                    Node::Neg(a) => g.neg(m(a)),
                    _ => unreachable!("a sum node"),
                };
                let mut leaves = Vec::new();
                collect(nodes, &inner, id as NodeId, true, &mut leaves);
                let mut heap = BinaryHeap::new();
                for (seq, (leaf, positive)) in leaves.into_iter().enumerate() {
                    let x = m(leaf);
                    heap.push(Reverse((ready.of(&g, x), seq, x, positive)));
                }
                let mut seq = heap.len();
                let balanced = loop {
                    let Reverse((_, _, x, px)) = heap.pop().expect("a sum has leaves");
                    let Some(Reverse((_, _, y, py))) = heap.pop() else {
                        break if px { x } else { g.neg(x) };
                    };
                    let (z, pz) = match (px, py) {
                        (true, true) => (g.add(x, y), true),
                        (true, false) => (g.sub(x, y), true),
                        (false, true) => (g.sub(y, x), true),
                        (false, false) => (g.add(x, y), false),
                    };
                    heap.push(Reverse((ready.of(&g, z), seq, z, pz)));
                    seq += 1;
                };
                // The copy not taken is dead code, dropped below.
                if ready.of(&g, balanced) + MIN_GAIN <= ready.of(&g, traced) {
                    balanced
                } else {
                    traced
                }
            }
            Node::Mul(a, b) => g.mul(m(a), m(b)),
            Node::Div(a, b) => g.div(m(a), m(b)),
            Node::Sqrt(a) => g.sqrt(m(a)),
            // The pair is rebuilt by its Sin / Cos users; keep a slot.
            Node::SinCos(a) => m(a),
            Node::Sin(sc) | Node::Cos(sc) => {
                let Node::SinCos(a) = nodes[sc as usize] else { unreachable!("Sin and Cos read a SinCos") };
                let (s, c) = g.sin_cos(m(a));
                if matches!(node, Node::Sin(_)) {
                    s
                } else {
                    c
                }
            }
        };
        new.push(mapped);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut out = Traced::from_ids(f.name(), &g, &outputs);
    out.set_input_names(f.input_names());
    out
}

/// The leaves of the sum tree under `id`, with their signs.
fn collect(nodes: &[Node], inner: &[bool], id: NodeId, positive: bool, out: &mut Vec<(NodeId, bool)>) {
    let visit = |x: NodeId, p: bool, out: &mut Vec<(NodeId, bool)>| {
        if inner[x as usize] {
            collect(nodes, inner, x, p, out);
        } else {
            out.push((x, p));
        }
    };
    match nodes[id as usize] {
        Node::Add(a, b) => {
            visit(a, positive, out);
            visit(b, positive, out);
        }
        Node::Sub(a, b) => {
            visit(a, positive, out);
            visit(b, !positive, out);
        }
        Node::Neg(a) => visit(a, !positive, out),
        _ => out.push((id, positive)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(f: &Traced, x: &[f64]) -> Vec<f64> {
        f.eval(&[("x", x)]).unwrap()
    }

    #[test]
    fn a_left_to_right_sum_becomes_a_tree_of_the_same_size() {
        let mut g = Graph::new();
        let xs: Vec<NodeId> = (0..8).map(|i| g.input("x", i)).collect();
        // x0 + x1 − x2 + x3 + x4 − x5 + x6 − x7, left to right, then negated
        let mut s = xs[0];
        for (i, &x) in xs.iter().enumerate().skip(1) {
            s = if i % 3 == 2 || i == 7 { g.sub(s, x) } else { g.add(s, x) };
        }
        let n = g.neg(s);
        let f = Traced::from_ids("sum", &g, &[n]);
        let b = balance(&f, &Latency::default(), Rewrites::default());
        assert_eq!(f.critical_path().cycles, 7 * 4);
        // three levels of additions (the negation is absorbed in both)
        assert_eq!(b.critical_path().cycles, 3 * 4);
        assert!(b.op_count().total() <= f.op_count().total());
        let x: Vec<f64> = (0..8).map(|i| (i * i + 1) as f64).collect();
        assert_eq!(eval(&f, &x), eval(&b, &x));
    }

    #[test]
    fn the_late_term_is_added_last_and_shared_terms_stay_shared() {
        let mut g = Graph::new();
        let x: Vec<NodeId> = (0..6).map(|i| g.input("x", i)).collect();
        // p = x0·x1·x2·x3 (left to right: ready at 12 cycles), then
        // ((p + x4) + x5): the sum waits on p twice unless x4 + x5 goes first.
        let p01 = g.mul(x[0], x[1]);
        let p012 = g.mul(p01, x[2]);
        let p = g.mul(p012, x[3]);
        let s = g.add(p, x[4]);
        let s = g.add(s, x[5]);
        // x4 + x5 on its own is a second output: a shared node is a leaf.
        let shared = g.add(x[4], x[5]);
        let f = Traced::from_ids("late", &g, &[s, shared]);
        let b = balance(&f, &Latency::default(), Rewrites::default());
        assert_eq!(f.critical_path().cycles, 3 * 4 + 2 * 4);
        // the product as traced, then one addition of the shared x4 + x5
        assert_eq!(b.critical_path().cycles, 3 * 4 + 4);
        assert_eq!(b.op_count().total(), f.op_count().total() - 1);
        let v = [1.5, -2.0, 3.0, 0.5, 7.0, -1.0];
        assert_eq!(eval(&f, &v), eval(&b, &v));
    }
}
