//! The trace session: a thread-local graph that symbolic scalars point into.

use super::expr::Expr;
use super::graph::{Graph, Rewrites};
use std::cell::RefCell;
use std::marker::PhantomData;
use std::sync::atomic::{AtomicU32, Ordering};

thread_local! {
    static ACTIVE: RefCell<Option<(u32, Graph)>> = const { RefCell::new(None) };
}

static NEXT_TRACE: AtomicU32 = AtomicU32::new(1);

/// A second [`Tracer`] was started on a thread that already has one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("a symbolic trace is already active on this thread")]
pub struct TraceActive;

/// A trace session. While it lives, every [`Expr`] built on this thread is
/// a node of its graph; [`Tracer::finish`] hands the graph over, and
/// dropping the tracer discards it. One tracer at a time per thread; traces
/// on different threads are independent.
///
/// ```
/// use dynagen::symbolic::{Expr, Tracer};
/// use dynagen::Scalar;
/// let t = Tracer::start().unwrap();
/// let x = t.input("q", 0);
/// let y = x * Expr::one() + Expr::zero(); // simplified away as it is built
/// assert_eq!(y, x);
/// let graph = t.finish();
/// assert_eq!(graph.len(), 3); // q[0] and the constants 1 and 0
/// ```
#[derive(Debug)]
pub struct Tracer {
    trace: u32,
    // The graph lives in this thread's storage: the guard must stay here.
    _not_send: PhantomData<*const ()>,
}

impl Tracer {
    /// Starts a trace with the default [`Rewrites`].
    pub fn start() -> Result<Tracer, TraceActive> {
        Self::start_with(Rewrites::default())
    }
    /// Starts a trace with the given rewrites.
    pub fn start_with(rewrites: Rewrites) -> Result<Tracer, TraceActive> {
        Self::start_on(Graph::with_rewrites(rewrites))
    }
    /// Starts a trace whose constants are inputs ([`Graph::with_lane_constants`]).
    pub fn start_lanes(rewrites: Rewrites) -> Result<Tracer, TraceActive> {
        Self::start_on(Graph::with_lane_constants(rewrites))
    }
    fn start_on(graph: Graph) -> Result<Tracer, TraceActive> {
        ACTIVE.with(|a| {
            let mut a = a.borrow_mut();
            if a.is_some() {
                return Err(TraceActive);
            }
            let trace = NEXT_TRACE.fetch_add(1, Ordering::Relaxed);
            *a = Some((trace, graph));
            Ok(Tracer { trace, _not_send: PhantomData })
        })
    }
    /// Entry `index` of the input vector `name` (e.g. `q`, 2 for `q[2]`).
    pub fn input(&self, name: &str, index: usize) -> Expr {
        Expr::new(self.trace, with_graph(self.trace, |g| g.input(name, index)))
    }
    /// The input vector `name` with `n` entries.
    pub fn inputs(&self, name: &str, n: usize) -> Vec<Expr> {
        (0..n).map(|i| self.input(name, i)).collect()
    }
    /// A constant.
    pub fn constant(&self, x: f64) -> Expr {
        Expr::new(self.trace, with_graph(self.trace, |g| g.constant(x)))
    }
    /// Ends the trace and returns its graph. The expressions built in it
    /// index that graph (see [`Expr::id`]).
    pub fn finish(self) -> Graph {
        let graph = ACTIVE.with(|a| a.borrow_mut().take()).map(|(_, g)| g);
        std::mem::forget(self);
        graph.expect("the active trace disappeared")
    }
}

impl Drop for Tracer {
    fn drop(&mut self) {
        ACTIVE.with(|a| {
            let mut a = a.borrow_mut();
            if a.as_ref().is_some_and(|(t, _)| *t == self.trace) {
                *a = None;
            }
        });
    }
}

/// The id of the trace active on this thread.
///
/// # Panics
/// If no trace is active: symbolic scalars exist only inside a [`Tracer`].
pub(crate) fn active_trace() -> u32 {
    ACTIVE.with(|a| a.borrow().as_ref().map(|(t, _)| *t)).expect("symbolic scalar used outside a Tracer session")
}

/// Runs `f` on the graph of trace `trace`.
///
/// # Panics
/// If `trace` is not the trace active on this thread (an expression kept
/// from an earlier trace, or used on another thread).
pub(crate) fn with_graph<R>(trace: u32, f: impl FnOnce(&mut Graph) -> R) -> R {
    ACTIVE.with(|a| {
        let mut a = a.borrow_mut();
        match a.as_mut() {
            Some((t, g)) if *t == trace => f(g),
            _ => panic!("symbolic scalar used outside the Tracer session that made it"),
        }
    })
}
