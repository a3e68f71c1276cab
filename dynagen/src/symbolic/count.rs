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
    /// Of the additions and subtractions, those emitted as a fused
    /// multiply-add with one of their products ([`Fusion`](super::Fusion));
    /// 0 for a function counted without fusion. The counts above stay those
    /// of the traced operations (a fused operation counts as its
    /// multiplication and its addition), comparable to other tools'.
    pub fused: usize,
    /// Of the multiplications, those that only fed fused multiply-adds and
    /// so are not computed on their own.
    pub mul_folded: usize,
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
    /// The floating-point operations the emitted code performs when a fused
    /// multiply-add is one operation: [`OpCount::arithmetic`] less the
    /// multiplications folded into fused multiply-adds (each fused sum
    /// stays one operation).
    pub fn fp_ops(&self) -> usize {
        self.arithmetic() - self.mul_folded
    }
    /// The multiplications the emitted code performs: the products computed
    /// on their own and the fused multiply-adds (a product fused into two
    /// sums is two). Processors with two multiply-capable floating-point
    /// pipes and separate adders (AMD Zen 4 and 5) start at most two of
    /// these a cycle, so a throughput-bound body takes at least half this
    /// many cycles, however few its additions are (`docs/performance.md`,
    /// "What bounds the bodies"); on Intel cores, whose adders are the same two pipes, the
    /// bound is half of [`OpCount::fp_ops`].
    pub fn multiplies(&self) -> usize {
        self.mul - self.mul_folded + self.fused
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
            fused: self.fused + o.fused,
            mul_folded: self.mul_folded + o.mul_folded,
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
        )?;
        if self.fused > 0 {
            write!(f, "; {} fused multiply-adds, {} FP ops with each fused = 1", self.fused, self.fp_ops())?;
        }
        Ok(())
    }
}

/// Latencies, in cycles, of each kind of operation, for
/// [`Traced::critical_path`](super::Traced::critical_path): how long a result takes to be ready once its
/// operands are, on the machine the generated code runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Latency {
    /// Addition or subtraction.
    pub add: u32,
    /// Multiplication.
    pub mul: u32,
    /// Division.
    pub div: u32,
    /// Negation (a sign flip).
    pub neg: u32,
    /// Square root.
    pub sqrt: u32,
    /// A sine and cosine of one angle.
    pub sin_cos: u32,
    /// A fused multiply-add.
    pub fma: u32,
}

impl Default for Latency {
    /// Typical of a current x86-64 core with SSE2 doubles: add, multiply
    /// and fused multiply-add 4 cycles, divide 14, square root 18, a sign
    /// flip 1, a library `sin_cos` about 40.
    fn default() -> Self {
        Latency { add: 4, mul: 4, div: 14, neg: 1, sqrt: 18, sin_cos: 40, fma: 4 }
    }
}

impl Latency {
    /// The latency of `node` (0 for constants, inputs and the reads of a
    /// sine-cosine's parts).
    pub fn of(&self, node: &Node) -> u32 {
        match node {
            Node::Add(..) | Node::Sub(..) => self.add,
            Node::Mul(..) => self.mul,
            Node::Div(..) => self.div,
            Node::Neg(_) => self.neg,
            Node::Sqrt(_) => self.sqrt,
            Node::SinCos(_) => self.sin_cos,
            Node::Const(_) | Node::Input { .. } | Node::Sin(_) | Node::Cos(_) => 0,
        }
    }
}

/// The latency-weighted depth of a function's graph: the longest chain of
/// dependent operations from the inputs to any output, in cycles of
/// [`Latency`], and the number of operations on it. A body whose run time
/// is close to `cycles` is latency-bound (more parallel hardware would not
/// help; a shallower graph would); one whose time is close to its operation
/// count over the machine's throughput is throughput-bound.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct CriticalPath {
    /// The longest chain, in cycles.
    pub cycles: u32,
    /// The number of operations on that chain.
    pub ops: u32,
}

impl CriticalPath {
    /// The critical path of `nodes` (operands before users) to `outputs`.
    pub fn of(nodes: &[Node], outputs: &[super::node::NodeId], latency: &Latency) -> Self {
        // (cycles, ops) at which each node's value is ready.
        let mut ready: Vec<(u32, u32)> = Vec::with_capacity(nodes.len());
        for n in nodes {
            ready.push(Self::ready_after(&ready, n.operands(), latency.of(n)));
        }
        Self::to_outputs(&ready, outputs)
    }
    /// When an operation of latency `latency` (none if 0) on `operands` is
    /// ready, as (cycles, operations on the longest chain), given when
    /// each earlier node is `ready`.
    pub(crate) fn ready_after(
        ready: &[(u32, u32)],
        operands: impl Iterator<Item = super::node::NodeId>,
        latency: u32,
    ) -> (u32, u32) {
        let (c, o) = operands.map(|a| ready[a as usize]).max().unwrap_or((0, 0));
        (c + latency, o + u32::from(latency > 0))
    }
    /// The longest of the `ready` times of `outputs`.
    pub(crate) fn to_outputs(ready: &[(u32, u32)], outputs: &[super::node::NodeId]) -> Self {
        let (cycles, ops) = outputs.iter().map(|&o| ready[o as usize]).max().unwrap_or((0, 0));
        CriticalPath { cycles, ops }
    }
}

impl fmt::Display for CriticalPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "critical path {} cycles ({} ops)", self.cycles, self.ops)
    }
}
