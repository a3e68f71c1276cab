//! The nodes of an expression graph.

/// The index of a node in its graph. Operands always have smaller indices
/// than the node that uses them, so index order is a topological order.
pub type NodeId = u32;

/// One node: a constant, a named input, or an operation on earlier nodes.
///
/// A constant is stored as the bits of its `f64` ([`f64::to_bits`]) so that
/// nodes can be hashed; read it with [`Node::constant`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, as `f64` bits.
    Const(u64),
    /// Entry `index` of the named input vector `name` (an index into the
    /// graph's input names), e.g. `q[2]`.
    Input {
        /// The input vector (an index into the graph's input names).
        name: u32,
        /// The entry.
        index: u32,
    },
    /// `a + b`.
    Add(NodeId, NodeId),
    /// `a − b`.
    Sub(NodeId, NodeId),
    /// `a · b`.
    Mul(NodeId, NodeId),
    /// `a / b`.
    Div(NodeId, NodeId),
    /// `−a`.
    Neg(NodeId),
    /// `√a`.
    Sqrt(NodeId),
    /// Sine and cosine of one angle, computed together; read by [`Node::Sin`]
    /// and [`Node::Cos`].
    SinCos(NodeId),
    /// The sine part of a [`Node::SinCos`] node.
    Sin(NodeId),
    /// The cosine part of a [`Node::SinCos`] node.
    Cos(NodeId),
}

impl Node {
    /// A constant node.
    pub fn from_constant(x: f64) -> Node {
        Node::Const(x.to_bits())
    }
    /// The value of a constant node.
    pub fn constant(&self) -> Option<f64> {
        match *self {
            Node::Const(b) => Some(f64::from_bits(b)),
            _ => None,
        }
    }
    /// The operands of the node (none for constants and inputs).
    pub fn operands(&self) -> impl Iterator<Item = NodeId> {
        let (a, b) = match *self {
            Node::Const(_) | Node::Input { .. } => (None, None),
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => (Some(a), Some(b)),
            Node::Neg(a) | Node::Sqrt(a) | Node::SinCos(a) | Node::Sin(a) | Node::Cos(a) => (Some(a), None),
        };
        a.into_iter().chain(b)
    }
    /// The same node with its operands renamed by `f`.
    pub fn map_operands(&self, mut f: impl FnMut(NodeId) -> NodeId) -> Node {
        match *self {
            n @ (Node::Const(_) | Node::Input { .. }) => n,
            Node::Add(a, b) => Node::Add(f(a), f(b)),
            Node::Sub(a, b) => Node::Sub(f(a), f(b)),
            Node::Mul(a, b) => Node::Mul(f(a), f(b)),
            Node::Div(a, b) => Node::Div(f(a), f(b)),
            Node::Neg(a) => Node::Neg(f(a)),
            Node::Sqrt(a) => Node::Sqrt(f(a)),
            Node::SinCos(a) => Node::SinCos(f(a)),
            Node::Sin(a) => Node::Sin(f(a)),
            Node::Cos(a) => Node::Cos(f(a)),
        }
    }
}
