//! Operation counts.

use super::node::Node;
use core::fmt;
use core::ops::Add;

/// How many operations of each kind a function performs (each kept node
/// once; a sine and cosine of the same angle count as one `sin_cos`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct OpCount {
    /// Additions.
    pub add: usize,
    /// Subtractions.
    pub sub: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Sine-and-cosine evaluations (one per angle).
    pub sin_cos: usize,
}

impl OpCount {
    /// Counts the operation nodes of `nodes`.
    pub fn of(nodes: &[Node]) -> Self {
        let mut c = OpCount::default();
        for n in nodes {
            match n {
                Node::Add(..) => c.add += 1,
                Node::Sub(..) => c.sub += 1,
                Node::Mul(..) => c.mul += 1,
                Node::Div(..) => c.div += 1,
                Node::Neg(_) => c.neg += 1,
                Node::Sqrt(_) => c.sqrt += 1,
                Node::SinCos(_) => c.sin_cos += 1,
                Node::Const(_) | Node::Input { .. } | Node::Sin(_) | Node::Cos(_) => {}
            }
        }
        c
    }
    /// Every operation, negations included.
    pub fn total(&self) -> usize {
        self.arithmetic() + self.neg
    }
    /// Additions, subtractions, multiplications, divisions, square roots and
    /// sine-cosines (negations left out: they are free in a fused
    /// multiply-subtract or a sign flip).
    pub fn arithmetic(&self) -> usize {
        self.add + self.sub + self.mul + self.div + self.sqrt + self.sin_cos
    }
}

impl Add for OpCount {
    type Output = OpCount;
    fn add(self, o: OpCount) -> OpCount {
        OpCount {
            add: self.add + o.add,
            sub: self.sub + o.sub,
            mul: self.mul + o.mul,
            div: self.div + o.div,
            neg: self.neg + o.neg,
            sqrt: self.sqrt + o.sqrt,
            sin_cos: self.sin_cos + o.sin_cos,
        }
    }
}

impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ops: {} add, {} sub, {} mul, {} div, {} neg, {} sqrt, {} sin_cos",
            self.total(),
            self.add,
            self.sub,
            self.mul,
            self.div,
            self.neg,
            self.sqrt,
            self.sin_cos
        )
    }
}
