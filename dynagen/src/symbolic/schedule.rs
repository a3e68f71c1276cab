//! The order in which a body's statements are written: the traced order, or
//! one that keeps fewer values alive at once.
//!
//! The trace writes operations in the order the algorithm performs them.
//! For the recursive Newton-Euler algorithm that is every body's forward
//! pass, then every body's backward pass: each body's force is computed in
//! the forward pass and read only in the backward one, so all of them are
//! alive in between. On the humanoid32 that is 484 values at once, far more
//! than the 16 registers of x86-64, and the compiled body spends its time
//! spilling and reloading them.
//!
//! [`order`] is a greedy list schedule over the `let` statements of the
//! emitted body (fused sums with their products, no constants, inputs or
//! folded products): of the statements whose operands are all written, it
//! writes next the one that ends the most live ranges (that is the last
//! reader of the most values), the earliest traced one among equals. It
//! does not change any operation, only the order of the `let`s, so the
//! results are bit for bit the same.
//!
//! It is used only where it at least halves the largest number of values
//! alive at once ([`MIN_LIVE_RATIO`]): measured (`docs/performance.md`,
//! "Design choices decided by a measurement"), that is where it made the
//! compiled body faster (the inverse dynamics and bias forces), while on
//! bodies it shortens less (mass matrices, forward dynamics) it made them
//! up to 3 % slower.

use super::fuse::Fusion;
use super::node::{Node, NodeId};
use super::traced::Traced;
use std::collections::BTreeSet;

/// The greedy order is used only if the traced order's largest live set is
/// at least this many times the greedy one's.
const MIN_LIVE_RATIO: f64 = 2.0;

/// The order in which to write `f`'s nodes (every node once, operands
/// before users): the greedy schedule of the module documentation where it
/// at least halves the live set, else the traced order.
pub fn order(f: &Traced, fusion: &Fusion) -> Vec<NodeId> {
    let lets = Lets::of(f, fusion);
    let traced: Vec<NodeId> = (0..f.nodes().len() as NodeId).collect();
    let greedy = lets.greedy();
    let (before, after) = (lets.max_live(&traced), lets.max_live(&greedy));
    if before as f64 >= MIN_LIVE_RATIO * after as f64 {
        greedy
    } else {
        traced
    }
}

/// A body's nodes seen as its `let` statements.
struct Lets {
    /// Whether each node is written as a `let` (and so holds a value).
    is_let: Vec<bool>,
    /// Each node's operands as the emitter reads them (a fused sum's are
    /// the product's factors and the addend), distinct.
    operands: Vec<Vec<NodeId>>,
    /// Each node's readers (each once), by the operands above.
    users: Vec<Vec<NodeId>>,
    /// Output slots per node: a value that is an output lives to the end.
    outputs: Vec<u32>,
}

impl Lets {
    fn of(f: &Traced, fusion: &Fusion) -> Lets {
        let nodes = f.nodes();
        let n = nodes.len();
        let is_let: Vec<bool> = (0..n)
            .map(|id| match nodes[id] {
                Node::Const(_) | Node::Input { .. } | Node::Sin(_) | Node::Cos(_) => false,
                Node::Mul(..) => !fusion.is_folded(id as NodeId),
                _ => true,
            })
            .collect();
        let mut operands: Vec<Vec<NodeId>> = (0..n).map(|id| fusion.operands(f, id as NodeId)).collect();
        for ops in &mut operands {
            ops.sort_unstable();
            ops.dedup();
        }
        let mut users = vec![Vec::new(); n];
        for (id, ops) in operands.iter().enumerate() {
            for &a in ops {
                users[a as usize].push(id as NodeId);
            }
        }
        let mut outputs = vec![0u32; n];
        for &o in f.outputs() {
            outputs[o as usize] += 1;
        }
        Lets { is_let, operands, users, outputs }
    }

    /// How many reads of each node are still to come before any is written.
    fn reads(&self) -> Vec<u32> {
        (0..self.is_let.len()).map(|id| self.users[id].len() as u32 + self.outputs[id]).collect()
    }

    /// The largest number of `let` values alive at once when the nodes are
    /// written in `order`.
    fn max_live(&self, order: &[NodeId]) -> usize {
        let mut left = self.reads();
        let (mut live, mut most) = (0usize, 0usize);
        for &id in order {
            let id = id as usize;
            if self.is_let[id] && left[id] > 0 {
                live += 1;
            }
            for &a in &self.operands[id] {
                let a = a as usize;
                left[a] -= 1;
                if left[a] == 0 && self.is_let[a] {
                    live -= 1;
                }
            }
            most = most.max(live);
        }
        most
    }

    /// The greedy schedule: among the ready `let`s, the one that is the last
    /// reader of the most `let` values, then the earliest traced. A node
    /// that is not a `let` is written as soon as it is ready (it costs no
    /// register of its own).
    fn greedy(&self) -> Vec<NodeId> {
        let n = self.is_let.len();
        let mut left = self.reads();
        let mut waiting: Vec<u32> = self.operands.iter().map(|ops| ops.len() as u32).collect();
        let mut done = vec![false; n];
        // How many of each node's operands it would read last.
        let mut kills = vec![0u32; n];
        for a in 0..n {
            if self.is_let[a] && self.outputs[a] == 0 && self.users[a].len() == 1 {
                kills[self.users[a][0] as usize] += 1;
            }
        }
        // Ready lets, best first: (−kills, traced position).
        let mut ready: BTreeSet<(i64, NodeId)> = BTreeSet::new();
        let mut free: Vec<NodeId> = Vec::new();
        let mut order = Vec::with_capacity(n);
        for (id, &w) in waiting.iter().enumerate() {
            if w == 0 {
                if self.is_let[id] {
                    ready.insert((-(kills[id] as i64), id as NodeId));
                } else {
                    free.push(id as NodeId);
                }
            }
        }
        loop {
            // Free nodes first, in traced order of their becoming ready.
            let id = match free.pop() {
                Some(id) => id,
                None => match ready.pop_first() {
                    Some((_, id)) => id,
                    None => break,
                },
            };
            done[id as usize] = true;
            order.push(id);
            for &a in &self.operands[id as usize] {
                let a = a as usize;
                left[a] -= 1;
                // The one reader still to come now ends `a`'s range.
                if left[a] == 1 && self.outputs[a] == 0 && self.is_let[a] {
                    if let Some(&u) = self.users[a].iter().find(|&&u| !done[u as usize]) {
                        let u = u as usize;
                        let was = (-(kills[u] as i64), u as NodeId);
                        kills[u] += 1;
                        if ready.remove(&was) {
                            ready.insert((-(kills[u] as i64), u as NodeId));
                        }
                    }
                }
            }
            for &u in &self.users[id as usize] {
                let u = u as usize;
                waiting[u] -= 1;
                if waiting[u] == 0 {
                    if self.is_let[u] {
                        ready.insert((-(kills[u] as i64), u as NodeId));
                    } else {
                        free.push(u as NodeId);
                    }
                }
            }
        }
        debug_assert_eq!(order.len(), n, "every node is scheduled");
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::symbolic::{Graph, Latency};

    /// A forward pass then a backward pass: `k` values computed first and
    /// each read again only at the end, as the RNEA's forces are.
    fn passes(k: usize) -> Traced {
        let mut g = Graph::new();
        let x: Vec<_> = (0..k).map(|i| g.input("x", i)).collect();
        let forward: Vec<_> = x.iter().map(|&a| g.mul(a, a)).collect();
        let squared: Vec<_> = forward.iter().map(|&a| g.sqrt(a)).collect();
        let mut sum = squared[0];
        for &s in &squared[1..] {
            sum = g.add(sum, s);
        }
        Traced::from_ids("passes", &g, &[sum])
    }

    #[test]
    fn the_order_writes_every_node_once_after_its_operands() {
        let f = passes(40);
        let fusion = Fusion::of(&f, &Latency::default());
        let order = order(&f, &fusion);
        let mut position = vec![usize::MAX; f.nodes().len()];
        for (k, &id) in order.iter().enumerate() {
            assert_eq!(position[id as usize], usize::MAX, "node {id} written twice");
            position[id as usize] = k;
        }
        for (id, node) in f.nodes().iter().enumerate() {
            for a in node.operands() {
                assert!(position[a as usize] < position[id], "node {id} before its operand {a}");
            }
        }
    }

    #[test]
    fn a_forward_then_backward_body_is_reordered_to_a_short_live_set() {
        let f = passes(40);
        let fusion = Fusion::of(&f, &Latency::default());
        let lets = Lets::of(&f, &fusion);
        let traced: Vec<NodeId> = (0..f.nodes().len() as NodeId).collect();
        // Traced: all 40 products alive before the first square root.
        assert_eq!(lets.max_live(&traced), 40);
        let order = order(&f, &fusion);
        assert!(lets.max_live(&order) <= 3, "greedy live set {}", lets.max_live(&order));
    }

    #[test]
    fn a_body_the_greedy_order_does_not_halve_keeps_its_traced_order() {
        let mut g = Graph::new();
        let a = g.input("x", 0);
        let b = g.input("x", 1);
        let p = g.mul(a, b);
        let q = g.sqrt(p);
        let r = g.add(q, p);
        let f = Traced::from_ids("chain", &g, &[r]);
        let fusion = Fusion::of(&f, &Latency::default());
        assert_eq!(order(&f, &fusion), (0..f.nodes().len() as NodeId).collect::<Vec<_>>());
    }
}
