//! The expression graph that code generation traces the algorithms into.
//!
//! [`Expr`] is a [`Scalar`](crate::Scalar): a `Copy` handle (trace id, node
//! index) into a graph that lives in thread-local storage while a
//! [`Tracer`] session is open. Running an existing generic algorithm (RNEA,
//! CRBA, ABA, …) on `Expr` inputs records every operation it performs on
//! the state; everything that depends only on the model folds into
//! constants on the way. [`Tracer::finish`] hands the [`Graph`] over;
//! [`Traced::new`] keeps what chosen outputs reach; code generation
//! ([`crate::codegen`]) prints the kept nodes as Rust, and
//! [`Traced::eval`] interprets them (the check that simplification kept
//! the algorithm's values).
//!
//! # Simplification as the graph is built
//!
//! Each operation first looks for an equal node (hash-consing: equal
//! subexpressions are one node), after these rewrites. Exact ones (the
//! result is the same number, for finite values):
//!
//! - constants fold: `2·3 → 6`, `sin_cos(c)`, `√c`;
//! - `0·x → 0`, `1·x → x`, `−1·x → −x`, `x + 0 → x`, `0 + x → x`,
//!   `x − 0 → x`, `0 − x → −x`, `x − x → 0`, `x / 1 → x`, `x / −1 → −x`,
//!   `0 / x → 0`, `x / x → 1`, `x / 2ᵏ → 2⁻ᵏ·x`;
//! - negation: `−(−x) → x`, `−(a − b) → b − a`, `a + (−b) → a − b`,
//!   `a − (−b) → a + b`, `(−a)·b → −(a·b)`, `(−a)·(−b) → a·b`, `c·x` with
//!   `c < 0` becomes `−(|c|·x)` (so `2x` and `−2x` share `2x`),
//!   `x + (−c) → x − c`, likewise for division and for
//!   `sin_cos(−x) = (−sin x, cos x)`;
//! - `(x + y) − y → x`, `a + (p − a) → p`, `a − (a − y) → y`,
//!   `(x − y) − x → −y` (no rounding: the exact value of the algebra, which
//!   the unsimplified code would only approximate);
//! - commutative operations order their operands (constants first, then by
//!   node index), so `a·b` and `b·a` meet;
//! - the sine and the cosine of one angle are one [`Node::SinCos`].
//!
//! Rewrites that may change the last bit of a value, on by default and off
//! with [`Rewrites::exact`]: like terms with constant coefficients
//! (`a·x + b·x → (a+b)·x`), products of constants (`a·(b·x) → (ab)·x`) and
//! sums of constants (`(x + a) + b → x + (a + b)`, where an `a + b` that
//! cancels to within four ulps of the larger of `a`, `b` is taken as 0: the
//! residue of two model constants equal up to their own rounding).
//! General like terms with symbolic coefficients are not combined: whether
//! `a·x + b·x → (a+b)·x` saves anything depends on whether `a·x` is used
//! elsewhere, which is not known while the graph is being built.
//!
//! Signed zeros are not kept (`−0.0` becomes `0.0`), and `0·x → 0` assumes a
//! finite `x`: the generated code promises the generic solver's values for
//! finite inputs, not its NaN and infinity propagation.
//!
//! # After the trace
//!
//! [`Traced::new`] keeps only what the outputs reach (dead code
//! elimination) and renumbers the nodes densely; [`factor`] then uses the
//! now-known use counts to share common factors (`k·u ± k·v → k·(u ± v)`
//! when both products have no other use) and to move negations out;
//! [`balance`] (with [`Rewrites::reassociate`]) rebuilds the sums
//! whose inner nodes have no other use as the trees that are
//! ready earliest, which shortens the body's chain of dependent operations
//! without adding any. [`Fusion`] picks the sums that code generation emits
//! as fused multiply-adds (the graph is left as it is). The [`OpCount`] of
//! a function counts each kept operation once; its [`CriticalPath`] is that longest chain, weighted by
//! [`Latency`].
//!
//! Constants that are zero or ±1 up to the rounding of the robot file's
//! numbers (a `cos(π/2)` of `6e-17`) are decided before tracing, on the
//! model: see [`crate::codegen`].

mod balance;
mod count;
mod eval;
mod expr;
mod factor;
mod fuse;
mod graph;
mod node;
mod schedule;
mod traced;
mod tracer;

pub use balance::balance;
pub use count::{CriticalPath, Latency, OpCount};
pub use eval::MissingInput;
pub use expr::Expr;
pub use factor::factor;
pub use fuse::{Fused, Fusion};
pub use graph::{Graph, Rewrites, LANE_CONSTANTS};
pub use node::{Node, NodeId};
pub(crate) use schedule::order as statement_order;
pub use traced::Traced;
pub use tracer::{TraceActive, Tracer};
