//! Fused multiply-adds: which sums of a function absorb one of their
//! products.
//!
//! The generated bodies are bound by the processor's floating-point ports
//! (about two operations per cycle), and Rust never contracts `a * b + c`
//! into one fused multiply-add by itself. [`Fusion::of`] picks, for every
//! addition or subtraction that has a product among its operands, at most
//! one such product to fuse with (rules below): `a·b + c`, `a·b − c` and
//! `c − a·b` become one
//! operation `(±a)·b + (±c)` with a single rounding where the target has
//! one (code generation emits `fma(a, b, c)`, see [`crate::codegen`]).
//!
//! - A product that feeds several sums is fused into each of them, and its
//!   multiplication is then not computed on its own any more ("folded"):
//!   each folded multiplication is one floating-point operation less
//!   ([`OpCount::fp_ops`]).
//! - Only products that can be folded are fused: every use of them is a
//!   sum's operand. A product with another use (an output, a factor of
//!   another product) is computed anyway, so fusing it saves nothing; it
//!   would only shorten chains, and fusing such products too measured
//!   slower on the mass matrices (`docs/performance.md`, "Design choices
//!   decided by a measurement").
//! - When both operands of a sum can be folded, the one ready later (by
//!   the latency-weighted depth of [`Latency`]) is fused, so that its
//!   multiplication leaves the critical path; the other is then computed
//!   anyway, and its other sums stay unfused too.
//!
//! The graph itself is not changed: [`Fusion`] is a plan beside the
//! [`Traced`], read by the emitter, by the operation count
//! ([`Fusion::op_count`]) and by [`Traced::eval_fused`] (the interpreter
//! with a fused multiply-add, [`f64::mul_add`], for every fused sum).
//!
//! On a target without fused multiply-adds the emitted `fma(a, b, c)` is
//! `a * b + c`, bit for bit the unfused sum: `c − a·b` is written with the
//! product's first factor negated, and `x + (−y)`, `(−a)·b + c` round
//! exactly as `x − y`, `c − a·b` do (negation is exact).

use super::count::{CriticalPath, Latency, OpCount};
use super::node::{Node, NodeId};
use super::traced::Traced;

/// One sum computed as a fused multiply-add: `(±a)·b + (±c)`, rounded once.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Fused {
    /// The product's first factor.
    pub a: NodeId,
    /// The product's second factor.
    pub b: NodeId,
    /// Whether the product is subtracted (`c − a·b`).
    pub negate_product: bool,
    /// The other operand of the sum.
    pub c: NodeId,
    /// Whether the other operand is subtracted (`a·b − c`).
    pub negate_addend: bool,
}

/// Which sums of a function are fused multiply-adds, and which products
/// are then not computed on their own (the module documentation says how
/// they are chosen).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Fusion {
    /// For each node: how it is fused, if it is a fused sum.
    sums: Vec<Option<Fused>>,
    /// For each node: whether it is a product that only fused sums read.
    folded: Vec<bool>,
    /// The critical path of the function so computed.
    path: CriticalPath,
}

impl Fusion {
    /// The fused multiply-adds of `f`, chosen with the latencies `latency`.
    pub fn of(f: &Traced, latency: &Latency) -> Fusion {
        let nodes = f.nodes();
        let uses = f.use_counts();
        // How many uses of each node are as an operand of a sum (of two
        // different operands: `p + p` is left alone).
        let mut sum_uses = vec![0u32; nodes.len()];
        for n in nodes {
            if let Node::Add(x, y) | Node::Sub(x, y) = *n {
                if x != y {
                    sum_uses[x as usize] += 1;
                    sum_uses[y as usize] += 1;
                }
            }
        }
        let factors = |p: NodeId| match nodes[p as usize] {
            Node::Mul(a, b) => Some((a, b)),
            _ => None,
        };
        // A product can be folded if every use of it is a sum's operand.
        let foldable = |p: NodeId| factors(p).is_some() && sum_uses[p as usize] == uses[p as usize];
        let mut sums = vec![None; nodes.len()];
        // The product each fused sum took.
        let mut product = vec![NodeId::MAX; nodes.len()];
        let mut ready: Vec<(u32, u32)> = Vec::with_capacity(nodes.len());
        for (id, n) in nodes.iter().enumerate() {
            let pick = match *n {
                Node::Add(x, y) | Node::Sub(x, y) if x != y => match (foldable(x), foldable(y)) {
                    // The later one (the second on a tie).
                    (true, true) if ready[x as usize] > ready[y as usize] => Some((x, y)),
                    (true, true) | (false, true) => Some((y, x)),
                    (true, false) => Some((x, y)),
                    (false, false) => None,
                },
                _ => None,
            };
            let Some((p, c)) = pick else {
                ready.push(CriticalPath::ready_after(&ready, n.operands(), latency.of(n)));
                continue;
            };
            let (a, b) = factors(p).expect("a product");
            let subtract = matches!(n, Node::Sub(..));
            let first = matches!(*n, Node::Add(x, _) | Node::Sub(x, _) if x == p);
            sums[id] = Some(Fused { a, b, negate_product: subtract && !first, c, negate_addend: subtract && first });
            product[id] = p;
            ready.push(CriticalPath::ready_after(&ready, [a, b, c].into_iter(), latency.fma));
        }
        // A product that a sum with two products did not take is computed
        // anyway: its other sums then gain nothing from fusing it (the same
        // number of operations; measured slower on the mass matrices), so
        // they are left unfused, until every fused product is folded.
        let folded = loop {
            let mut fused_uses = vec![0u32; nodes.len()];
            for &p in product.iter().filter(|&&p| p != NodeId::MAX) {
                fused_uses[p as usize] += 1;
            }
            let folded: Vec<bool> = (0..nodes.len()).map(|p| fused_uses[p] > 0 && fused_uses[p] == uses[p]).collect();
            let mut changed = false;
            for (s, p) in sums.iter_mut().zip(product.iter_mut()) {
                if *p != NodeId::MAX && !folded[*p as usize] {
                    (*s, *p, changed) = (None, NodeId::MAX, true);
                }
            }
            if !changed {
                break folded;
            }
        };
        let mut ready: Vec<(u32, u32)> = Vec::with_capacity(nodes.len());
        for (n, s) in nodes.iter().zip(&sums) {
            ready.push(match s {
                Some(fu) => CriticalPath::ready_after(&ready, [fu.a, fu.b, fu.c].into_iter(), latency.fma),
                None => CriticalPath::ready_after(&ready, n.operands(), latency.of(n)),
            });
        }
        let path = CriticalPath::to_outputs(&ready, f.outputs());
        Fusion { sums, folded, path }
    }
    /// No fusion at all in `f`.
    pub fn none(f: &Traced) -> Fusion {
        let len = f.nodes().len();
        Fusion { sums: vec![None; len], folded: vec![false; len], path: f.critical_path() }
    }
    /// How node `id` is fused, if it is a fused sum.
    pub fn sum(&self, id: NodeId) -> Option<Fused> {
        self.sums.get(id as usize).copied().flatten()
    }
    /// The nodes the code computing node `id` (of `f`) reads: a fused
    /// sum's product factors and addend, any other node's operands.
    pub fn operands(&self, f: &Traced, id: NodeId) -> Vec<NodeId> {
        match self.sum(id) {
            Some(fu) => vec![fu.a, fu.b, fu.c],
            None => f.nodes()[id as usize].operands().collect(),
        }
    }
    /// Whether node `id` is a product that is not computed on its own
    /// (every use of it is fused).
    pub fn is_folded(&self, id: NodeId) -> bool {
        self.folded.get(id as usize).copied().unwrap_or(false)
    }
    /// `f`'s operation count ([`Traced::op_count`]) with the fused sums
    /// and folded products counted ([`OpCount::fused`],
    /// [`OpCount::mul_folded`]).
    pub fn op_count(&self, f: &Traced) -> OpCount {
        OpCount {
            fused: self.sums.iter().flatten().count(),
            mul_folded: self.folded.iter().filter(|&&x| x).count(),
            ..f.op_count()
        }
    }
    /// The critical path with the fused sums as one operation each, of
    /// latency [`Latency::fma`].
    pub fn critical_path(&self) -> CriticalPath {
        self.path
    }
}

impl Traced {
    /// Its fused multiply-adds with the default [`Latency`].
    pub fn fusion(&self) -> Fusion {
        Fusion::of(self, &Latency::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::symbolic::Graph;

    /// x0·x1 + x2, x2 − x0·x1 (the product shared, so fused into both and
    /// folded), x3·x4 − x5 with x3·x4 also an output (not fused: it is
    /// computed anyway), and (x0·x1 + x2)·x2 + x3·x4: both products, the
    /// one that can be folded is fused.
    fn example() -> Traced {
        let mut g = Graph::new();
        let x: Vec<NodeId> = (0..6).map(|i| g.input("x", i)).collect();
        let p = g.mul(x[0], x[1]);
        let s1 = g.add(p, x[2]);
        let s2 = g.sub(x[2], p);
        let r = g.mul(x[3], x[4]);
        let s3 = g.sub(r, x[5]);
        let late = g.mul(s1, x[2]);
        let s4 = g.add(late, r);
        Traced::from_ids("example", &g, &[s1, s2, s3, r, s4])
    }

    #[test]
    fn sums_absorb_their_products_and_shared_products_are_folded() {
        let f = example();
        let fusion = f.fusion();
        let count = fusion.op_count(&f);
        // 3 of the 4 sums fused; x0·x1 folded (both its uses fused), and the
        // late product (its one use fused); x3·x4 kept (an output), and
        // x3·x4 − x5 not fused.
        assert_eq!((count.add + count.sub, count.mul), (4, 3));
        assert_eq!((count.fused, count.mul_folded), (3, 2));
        assert_eq!(count.fp_ops(), count.arithmetic() - 2);
        // Multiplications executed: the fused x0·x1 twice, x3·x4 on its
        // own, the late product once, fused.
        assert_eq!(count.multiplies(), 4);
        let nodes = f.nodes();
        let id = |want: Node| nodes.iter().position(|n| *n == want).unwrap() as NodeId;
        let p = nodes.iter().position(|n| matches!(n, Node::Mul(..))).unwrap() as NodeId;
        assert!(fusion.is_folded(p));
        let Node::Mul(a, b) = nodes[p as usize] else { unreachable!() };
        // x2 − x0·x1: the product negated
        let Node::Input { .. } = nodes[a as usize] else { panic!("x0") };
        let s2 = nodes.iter().position(|n| matches!(n, Node::Sub(_, q) if *q == p)).unwrap() as NodeId;
        assert_eq!(fusion.sum(s2).unwrap(), Fused { a, b, negate_product: true, c: 2, negate_addend: false });
        // x3·x4 + (x0·x1 + x2)·x2: the later product, the one that can be
        // folded, is fused; x3·x4 is the addend
        let late = id(Node::Mul(2, f.outputs()[0]));
        let s4 = f.outputs()[4];
        assert_eq!(fusion.sum(s4).map(|u| (u.a, u.b)), Some((2, f.outputs()[0])));
        assert!(fusion.is_folded(late) && !fusion.is_folded(f.outputs()[3]));
        assert_eq!(fusion.sum(f.outputs()[2]), None, "x3·x4 − x5");
        // The chain x0·x1 → + → · → + is two fused operations.
        assert_eq!(f.critical_path().cycles, 4 * 4);
        assert_eq!(fusion.critical_path().cycles, 2 * 4);
    }

    #[test]
    fn the_fused_interpreter_rounds_once() {
        let f = example();
        let fusion = f.fusion();
        // x0·x1 + x2 with x0·x1 = (1 + ε)(1 + 2ε) = 1 + 3ε + 2ε² (not a
        // double) and x2 = −1: unfused the product rounds to 1 + 3ε, fused
        // the sum keeps the 2ε².
        let e = f64::EPSILON;
        let x = [1.0 + e, 1.0 + 2.0 * e, -1.0, 3.0, 5.0, 7.0];
        let plain = f.eval(&[("x", &x)]).unwrap();
        let fused = f.eval_fused(&fusion, &[("x", &x)]).unwrap();
        assert_eq!(plain[0], 3.0 * e);
        assert_eq!(fused[0], 3.0 * e + 2.0 * e * e);
        assert_eq!(fused[1], (-x[0]).mul_add(x[1], x[2]));
        assert_eq!((fused[2], fused[3]), (8.0, 15.0));
        // With no fusion, the same bits as the plain interpreter.
        assert_eq!(f.eval_fused(&Fusion::none(&f), &[("x", &x)]).unwrap(), plain);
    }
}
