//! The symbolic scalar: a handle to a node of the active trace's graph.

use super::node::NodeId;
use super::tracer::{active_trace, with_graph};
use crate::Scalar;
use core::fmt;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A symbolic real number: a node of the graph of the active
/// [`Tracer`](super::Tracer). It is `Copy` (a trace id and a node index), so
/// the generic algorithms run on it unchanged; every operation adds a node
/// (or finds an equal one) in the thread's graph.
///
/// # Panics
/// Operations panic when no trace is active on the thread or when the
/// expression comes from another trace.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Expr {
    trace: u32,
    id: NodeId,
}

impl Expr {
    pub(crate) fn new(trace: u32, id: NodeId) -> Self {
        Expr { trace, id }
    }
    /// The node's index in the trace's graph.
    pub fn id(self) -> NodeId {
        self.id
    }
    fn binary(self, o: Expr, f: impl FnOnce(&mut super::Graph, NodeId, NodeId) -> NodeId) -> Expr {
        assert_eq!(self.trace, o.trace, "symbolic scalars from two different traces");
        Expr::new(self.trace, with_graph(self.trace, |g| f(g, self.id, o.id)))
    }
    fn unary(self, f: impl FnOnce(&mut super::Graph, NodeId) -> NodeId) -> Expr {
        Expr::new(self.trace, with_graph(self.trace, |g| f(g, self.id)))
    }
}

impl fmt::Debug for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Expr(#{})", self.id)
    }
}

impl Add for Expr {
    type Output = Expr;
    fn add(self, o: Expr) -> Expr {
        self.binary(o, |g, a, b| g.add(a, b))
    }
}
impl Sub for Expr {
    type Output = Expr;
    fn sub(self, o: Expr) -> Expr {
        self.binary(o, |g, a, b| g.sub(a, b))
    }
}
impl Mul for Expr {
    type Output = Expr;
    fn mul(self, o: Expr) -> Expr {
        self.binary(o, |g, a, b| g.mul(a, b))
    }
}
impl Div for Expr {
    type Output = Expr;
    fn div(self, o: Expr) -> Expr {
        self.binary(o, |g, a, b| g.div(a, b))
    }
}
impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        self.unary(|g, a| g.neg(a))
    }
}
impl AddAssign for Expr {
    fn add_assign(&mut self, o: Expr) {
        *self = *self + o;
    }
}
impl SubAssign for Expr {
    fn sub_assign(&mut self, o: Expr) {
        *self = *self - o;
    }
}
impl MulAssign for Expr {
    fn mul_assign(&mut self, o: Expr) {
        *self = *self * o;
    }
}

impl Scalar for Expr {
    const TRACED: bool = true;

    /// A constant of the trace active on this thread.
    fn from_f64(x: f64) -> Self {
        let trace = active_trace();
        Expr::new(trace, with_graph(trace, |g| g.constant(x)))
    }
    fn to_f64(self) -> Option<f64> {
        with_graph(self.trace, |g| g.constant_value(self.id))
    }
    fn sqrt(self) -> Self {
        self.unary(|g, a| g.sqrt(a))
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = with_graph(self.trace, |g| g.sin_cos(self.id));
        (Expr::new(self.trace, s), Expr::new(self.trace, c))
    }
}
