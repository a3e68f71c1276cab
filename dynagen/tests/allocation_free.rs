//! The `_into` forms of [`Robot`]'s derivatives allocate nothing: a
//! counting global allocator (this test binary's own) sees no allocation
//! during the calls, after the robot and the outputs were made. One test
//! function, so no other test of this binary allocates meanwhile.

mod support;

use nalgebra::{DMatrix, DVector};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting allocations and reallocations.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded to the system allocator unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: the caller's contract is the system allocator's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made while `f` runs.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    f();
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

#[test]
fn derivative_into_forms_allocate_nothing() {
    for name in ["panda", "torso_two_arms"] {
        let mut robot = support::robot(name);
        let n = robot.dof();
        // a tip wrench set, as the dual-number loads copy them
        let frame = robot.model().frames.iter().rposition(|f| f.body.is_some()).unwrap();
        let frame_name = robot.model().frames[frame].name.clone();
        robot.set_tip_wrench(&frame_name, nalgebra::Vector6::new(0.1, 0.2, -0.3, 4.0, 5.0, -6.0)).unwrap();
        let mut rng = support::Rng::new(7);
        let (q, qd, x) = (
            DVector::from_vec(rng.vec(n, 1.0)),
            DVector::from_vec(rng.vec(n, 1.0)),
            DVector::from_vec(rng.vec(n, 1.0)),
        );
        let (mut a, mut b, mut c) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        for round in 0..2 {
            let count = allocations(|| {
                robot.inverse_dynamics_derivatives_into(&q, &qd, &x, &mut a, &mut b).unwrap();
                robot.forward_dynamics_derivatives_into(&q, &qd, &x, &mut a, &mut b, &mut c).unwrap();
                robot.mass_matrix_inverse_into(&q, &mut c).unwrap();
            });
            assert_eq!(count, 0, "{name}, round {round}: {count} allocations");
        }
        // the counter counts: an allocating call is seen
        assert!(allocations(|| drop(robot.mass_matrix_inverse(&q).unwrap())) > 0);
        assert!(c.iter().all(|v| v.is_finite()) && a.iter().all(|v| v.is_finite()));
    }
}
