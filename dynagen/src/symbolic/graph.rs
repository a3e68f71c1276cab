//! The expression graph: hash-consed nodes, simplified as they are built.

use super::node::{Node, NodeId};
use std::collections::HashMap;

/// Which value-changing rewrites the graph may make, beyond the exact ones
/// it always makes (see the [module documentation](super)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rewrites {
    /// `a·x ± b·x → (a ± b)·x`, `x + x → 2·x` and `x ± a·x → (1 ± a)·x` for
    /// constants `a`, `b`: one multiplication fewer, and a result that may
    /// differ from the unrewritten one in the last bit.
    pub like_terms: bool,
    /// `a·(b·x) → (a·b)·x` for constants `a`, `b`: one multiplication
    /// fewer, the same possible last-bit difference.
    pub constant_products: bool,
    /// `(x + a) + b → x + (a + b)` (and with subtractions) for constants
    /// `a`, `b`: one addition fewer, the same possible last-bit difference.
    pub constant_sums: bool,
    /// Sums reassociated for a shorter critical path after the trace
    /// ([`balance`](super::balance)): the same number of operations, a
    /// result that may differ in the last bits.
    pub reassociate: bool,
}

impl Default for Rewrites {
    /// Every rewrite on.
    fn default() -> Self {
        Rewrites { like_terms: true, constant_products: true, constant_sums: true, reassociate: true }
    }
}

impl Rewrites {
    /// Only the rewrites that never change a value.
    pub fn exact() -> Self {
        Rewrites { like_terms: false, constant_products: false, constant_sums: false, reassociate: false }
    }
}

/// An expression graph. Every node is built through the methods below, which
/// fold constants, apply the simplification rules and return the existing
/// node when an equal one was built before (hash-consing), so that equal
/// subexpressions are one node.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, NodeId>,
    input_names: Vec<String>,
    rewrites: Rewrites,
    /// In a lane trace ([`Graph::with_lane_constants`]): the values of the
    /// constants made inputs `k[i]`, in the order they were made.
    lanes: Option<Vec<f64>>,
}

/// The input vector that a lane trace's constants are read from.
pub const LANE_CONSTANTS: &str = "k";

impl Graph {
    /// An empty graph with the default rewrites.
    pub fn new() -> Self {
        Self::default()
    }
    /// An empty graph with the given rewrites.
    pub fn with_rewrites(rewrites: Rewrites) -> Self {
        Graph { rewrites, ..Self::default() }
    }
    /// An empty graph in which every constant, 0 and ±1 included, is an
    /// input `k[i]` of its own, in the order they are made
    /// ([`LANE_CONSTANTS`]; [`Graph::lane_constants`] has their values).
    /// Nothing folds: traced this way, two branches of a robot that take the
    /// same code paths give the same graph, whatever their numbers, and the
    /// constants all lanes share are folded afterwards.
    pub fn with_lane_constants(rewrites: Rewrites) -> Self {
        Graph { rewrites, lanes: Some(Vec::new()), ..Self::default() }
    }
    /// The values of a lane trace's `k[i]`, in order (`None` for another graph).
    pub fn lane_constants(&self) -> Option<&[f64]> {
        self.lanes.as_deref()
    }
    /// The rewrites this graph makes.
    pub fn rewrites(&self) -> Rewrites {
        self.rewrites
    }
    /// The number of nodes built (kept or not).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }
    /// Whether no node was built.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
    /// The node `id`.
    pub fn node(&self, id: NodeId) -> Node {
        self.nodes[id as usize]
    }
    /// All nodes, in index (topological) order.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }
    /// The names of the input vectors, indexed by [`Node::Input::name`].
    pub fn input_names(&self) -> &[String] {
        &self.input_names
    }
    /// The value of `id` if it is a constant.
    pub fn constant_value(&self, id: NodeId) -> Option<f64> {
        self.node(id).constant()
    }

    fn intern(&mut self, node: Node) -> NodeId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = NodeId::try_from(self.nodes.len()).expect("expression graph has more than 2^32 nodes");
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }
    fn negated(&self, id: NodeId) -> Option<NodeId> {
        match self.node(id) {
            Node::Neg(x) => Some(x),
            _ => None,
        }
    }
    /// `op(a, b)` (a product or a quotient) with the negations of `a` and
    /// `b` moved outwards: `op(x, y)` for `op(−x, −y)`, `−op(x, y)` for
    /// `op(−x, y)` and `op(x, −y)`; `None` when neither is a negation.
    fn signs_out(&mut self, a: NodeId, b: NodeId, op: fn(&mut Self, NodeId, NodeId) -> NodeId) -> Option<NodeId> {
        let (x, y) = (self.negated(a), self.negated(b));
        if x.is_none() && y.is_none() {
            return None;
        }
        let r = op(self, x.unwrap_or(a), y.unwrap_or(b));
        Some(if x.is_some() == y.is_some() { r } else { self.neg(r) })
    }
    /// `(c, x)` when `id` is `c·x` with `c` a constant.
    fn scaled(&self, id: NodeId) -> Option<(f64, NodeId)> {
        match self.node(id) {
            Node::Mul(a, b) => self.constant_value(a).map(|c| (c, b)),
            _ => None,
        }
    }
    /// `(c, x)` with `id = c·x` (`c` = 1 for anything but a constant product).
    fn as_scaled(&self, id: NodeId) -> (f64, NodeId) {
        self.scaled(id).unwrap_or((1.0, id))
    }

    /// `(c, x)` when `id` is `x + c` or `x − c` (then `c` is negated) with
    /// `c` a constant.
    fn offset(&self, id: NodeId) -> Option<(f64, NodeId)> {
        match self.node(id) {
            Node::Add(a, b) => match (self.constant_value(a), self.constant_value(b)) {
                (Some(c), None) => Some((c, b)),
                (None, Some(c)) => Some((c, a)),
                _ => None,
            },
            Node::Sub(a, b) => self.constant_value(b).map(|c| (-c, a)),
            _ => None,
        }
    }

    /// A constant. A negative zero becomes zero: the generated code does not
    /// promise signed zeros.
    pub fn constant(&mut self, x: f64) -> NodeId {
        let x = if x == 0.0 { 0.0 } else { x };
        if let Some(values) = self.lanes.as_mut() {
            values.push(x);
            let i = values.len() - 1;
            return self.input(LANE_CONSTANTS, i);
        }
        self.intern(Node::from_constant(x))
    }
    /// Entry `index` of the input vector `name`.
    pub fn input(&mut self, name: &str, index: usize) -> NodeId {
        let n = match self.input_names.iter().position(|s| s == name) {
            Some(n) => n,
            None => {
                self.input_names.push(name.to_string());
                self.input_names.len() - 1
            }
        };
        let index = u32::try_from(index).expect("input index exceeds u32");
        self.intern(Node::Input { name: n as u32, index })
    }

    /// An arithmetic node (`+ - * /`, negation, square root) of this
    /// graph's ids, built through the simplifying constructors; `None` for
    /// the other kinds, which a copying pass maps itself.
    pub fn arithmetic(&mut self, node: Node) -> Option<NodeId> {
        Some(match node {
            Node::Add(a, b) => self.add(a, b),
            Node::Sub(a, b) => self.sub(a, b),
            Node::Mul(a, b) => self.mul(a, b),
            Node::Div(a, b) => self.div(a, b),
            Node::Neg(a) => self.neg(a),
            Node::Sqrt(a) => self.sqrt(a),
            _ => return None,
        })
    }

    /// `a + b`.
    pub fn add(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x + y),
            (Some(0.0), _) => return b,
            (_, Some(0.0)) => return a,
            (Some(x), _) if x < 0.0 => {
                let c = self.constant(-x);
                return self.sub(b, c);
            }
            (_, Some(y)) if y < 0.0 => {
                let c = self.constant(-y);
                return self.sub(a, c);
            }
            _ => {}
        }
        if self.rewrites.constant_sums {
            let (ca, cb) = (self.constant_value(a), self.constant_value(b));
            let pair = match (ca, cb) {
                (Some(c), None) => self.offset(b).map(|(d, x)| (constant_sum(c, d), x)),
                (None, Some(c)) => self.offset(a).map(|(d, x)| (constant_sum(c, d), x)),
                _ => None,
            };
            if let Some((c, x)) = pair {
                let c = self.constant(c);
                return self.add(x, c);
            }
        }
        if let Some(y) = self.negated(b) {
            return self.sub(a, y);
        }
        if let Some(x) = self.negated(a) {
            return self.sub(b, x);
        }
        // a + (p − a) = p and (p − b) + b = p: the value of the algebra
        // (Rodrigues' c + (1 − c) on a joint's own axis is 1).
        if let Node::Sub(p, q) = self.node(b) {
            if q == a {
                return p;
            }
        }
        if let Node::Sub(p, q) = self.node(a) {
            if q == b {
                return p;
            }
        }
        if self.rewrites.like_terms {
            let ((ca, xa), (cb, xb)) = (self.as_scaled(a), self.as_scaled(b));
            if xa == xb && self.constant_value(xa).is_none() {
                let c = self.constant(ca + cb);
                return self.mul(c, xa);
            }
        }
        let (a, b) = (a.min(b), a.max(b));
        self.intern(Node::Add(a, b))
    }

    /// `a − b`.
    pub fn sub(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x - y),
            (Some(0.0), _) => return self.neg(b),
            (_, Some(0.0)) => return a,
            // −c − b = −(c + b)
            (Some(x), _) if x < 0.0 => {
                let c = self.constant(-x);
                let s = self.add(c, b);
                return self.neg(s);
            }
            (_, Some(y)) if y < 0.0 => {
                let c = self.constant(-y);
                return self.add(a, c);
            }
            _ => {}
        }
        if a == b {
            return self.constant(0.0);
        }
        if self.rewrites.constant_sums {
            if let (Some(c), Some((d, x))) = (self.constant_value(b), self.offset(a)) {
                let c = self.constant(constant_sum(d, -c));
                return self.add(x, c);
            }
        }
        if let Some(y) = self.negated(b) {
            return self.add(a, y);
        }
        // (x + y) − y = x, (x + y) − x = y, a − (a − y) = y, (x − y) − x = −y
        if let Node::Add(x, y) = self.node(a) {
            if y == b {
                return x;
            }
            if x == b {
                return y;
            }
        }
        if let Node::Sub(x, y) = self.node(b) {
            if x == a {
                return y;
            }
        }
        if let Node::Sub(x, y) = self.node(a) {
            if x == b {
                return self.neg(y);
            }
        }
        if self.rewrites.like_terms {
            let ((ca, xa), (cb, xb)) = (self.as_scaled(a), self.as_scaled(b));
            if xa == xb && self.constant_value(xa).is_none() {
                let c = self.constant(ca - cb);
                return self.mul(c, xa);
            }
        }
        self.intern(Node::Sub(a, b))
    }

    /// `a · b`.
    pub fn mul(&mut self, a: NodeId, b: NodeId) -> NodeId {
        // Constants first.
        let (a, b) = if self.constant_value(b).is_some() && self.constant_value(a).is_none() { (b, a) } else { (a, b) };
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(0.0), _) => return self.constant(0.0),
            (Some(1.0), _) => return b,
            (Some(-1.0), _) => return self.neg(b),
            (Some(x), _) if x < 0.0 => {
                let c = self.constant(-x);
                let p = self.mul(c, b);
                return self.neg(p);
            }
            _ => {}
        }
        // Negations move outwards, where an addition absorbs them.
        if let Some(p) = self.signs_out(a, b, Self::mul) {
            return p;
        }
        if let (Some(x), Some((y, z))) = (self.constant_value(a), self.scaled(b)) {
            if self.rewrites.constant_products {
                let c = self.constant(x * y);
                return self.mul(c, z);
            }
        }
        let (a, b) = if self.constant_value(a).is_some() { (a, b) } else { (a.min(b), a.max(b)) };
        self.intern(Node::Mul(a, b))
    }

    /// `a / b`.
    pub fn div(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x / y),
            (Some(0.0), _) => return self.constant(0.0),
            (_, Some(1.0)) => return a,
            (_, Some(-1.0)) => return self.neg(a),
            (_, Some(y)) if y < 0.0 => {
                let c = self.constant(-y);
                let q = self.div(a, c);
                return self.neg(q);
            }
            // Division by a power of two is an exact multiplication.
            (_, Some(y)) if y != 0.0 && y.is_finite() && (1.0 / y).is_finite() && is_power_of_two(y) => {
                let c = self.constant(1.0 / y);
                return self.mul(c, a);
            }
            _ => {}
        }
        if a == b {
            return self.constant(1.0);
        }
        if let Some(q) = self.signs_out(a, b, Self::div) {
            return q;
        }
        self.intern(Node::Div(a, b))
    }

    /// `−a`.
    pub fn neg(&mut self, a: NodeId) -> NodeId {
        if let Some(x) = self.constant_value(a) {
            return self.constant(-x);
        }
        match self.node(a) {
            Node::Neg(x) => x,
            Node::Sub(x, y) => self.sub(y, x),
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `√a`.
    pub fn sqrt(&mut self, a: NodeId) -> NodeId {
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.sqrt());
        }
        self.intern(Node::Sqrt(a))
    }

    /// The sine and cosine of `a`, sharing one [`Node::SinCos`].
    pub fn sin_cos(&mut self, a: NodeId) -> (NodeId, NodeId) {
        if let Some(x) = self.constant_value(a) {
            let (s, c) = x.sin_cos();
            return (self.constant(s), self.constant(c));
        }
        if let Some(x) = self.negated(a) {
            // sin(−x) = −sin x, cos(−x) = cos x: exact.
            let (s, c) = self.sin_cos(x);
            return (self.neg(s), c);
        }
        let sc = self.intern(Node::SinCos(a));
        (self.intern(Node::Sin(sc)), self.intern(Node::Cos(sc)))
    }
}

/// `c + d` for the `constant_sums` rewrite, with a sum that cancels to
/// within four ulps of its larger operand taken as 0: two constants of the
/// model that are equal up to their own rounding (e.g. two moments of
/// inertia of a symmetric body, each the result of sums) leave such a
/// residue, which would otherwise cost an addition.
fn constant_sum(c: f64, d: f64) -> f64 {
    let s = c + d;
    if s.abs() <= 4.0 * f64::EPSILON * c.abs().max(d.abs()) {
        0.0
    } else {
        s
    }
}

fn is_power_of_two(y: f64) -> bool {
    let bits = y.abs().to_bits();
    // A normal number whose mantissa bits are all zero.
    bits & ((1u64 << 52) - 1) == 0 && (bits >> 52) != 0
}
