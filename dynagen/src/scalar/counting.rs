//! A scalar that counts the operations performed on it.

use super::Scalar;
use crate::symbolic::OpCount;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use std::cell::Cell;

thread_local! {
    static COUNTS: Cell<OpCount> = Cell::new(OpCount::default());
}

/// Adds one to the counter `field` picks.
fn tally(field: impl FnOnce(&mut OpCount) -> &mut usize) {
    COUNTS.with(|c| {
        let mut n = c.get();
        *field(&mut n) += 1;
        c.set(n);
    });
}

/// An `f64` that counts every `+`, `−`, `×`, `÷`, negation, `sqrt` and
/// `sin_cos` done with it (on this thread), constants included. Running a
/// generic algorithm on it gives the operation count of the generic
/// recursion, the honest baseline for the generated code's count.
///
/// ```
/// use dynagen::{Counting, Scalar};
/// let (y, ops) = Counting::count(|| {
///     let x = Counting::from_f64(2.0);
///     let (s, c) = x.sin_cos();
///     s * x + c
/// });
/// assert_eq!(y.value(), 2f64.sin() * 2.0 + 2f64.cos());
/// assert_eq!((ops.mul, ops.add, ops.sin_cos, ops.total()), (1, 1, 1, 3));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct Counting(pub f64);

impl Counting {
    /// The value.
    pub fn value(self) -> f64 {
        self.0
    }
    /// Runs `f` and returns its result with the operations it did on
    /// `Counting` values (the count of this thread, restored afterwards, so
    /// calls may nest).
    pub fn count<R>(f: impl FnOnce() -> R) -> (R, OpCount) {
        let before = COUNTS.with(|c| c.replace(OpCount::default()));
        let r = f();
        let ops = COUNTS.with(|c| c.replace(before));
        (r, ops)
    }
}

macro_rules! binary {
    ($tr:ident, $m:ident, $atr:ident, $am:ident, $field:ident, $op:tt) => {
        impl $tr for Counting {
            type Output = Counting;
            #[inline]
            fn $m(self, o: Counting) -> Counting {
                tally(|n| &mut n.$field);
                Counting(self.0 $op o.0)
            }
        }
        impl $atr for Counting {
            #[inline]
            fn $am(&mut self, o: Counting) {
                *self = *self $op o;
            }
        }
    };
}
binary!(Add, add, AddAssign, add_assign, add, +);
binary!(Sub, sub, SubAssign, sub_assign, sub, -);
binary!(Mul, mul, MulAssign, mul_assign, mul, *);

impl Div for Counting {
    type Output = Counting;
    #[inline]
    fn div(self, o: Counting) -> Counting {
        tally(|n| &mut n.div);
        Counting(self.0 / o.0)
    }
}

impl Neg for Counting {
    type Output = Counting;
    #[inline]
    fn neg(self) -> Counting {
        tally(|n| &mut n.neg);
        Counting(-self.0)
    }
}

impl Scalar for Counting {
    fn from_f64(x: f64) -> Self {
        Counting(x)
    }
    fn to_f64(self) -> Option<f64> {
        Some(self.0)
    }
    fn sqrt(self) -> Self {
        tally(|n| &mut n.sqrt);
        Counting(self.0.sqrt())
    }
    fn sin_cos(self) -> (Self, Self) {
        tally(|n| &mut n.sin_cos);
        let (s, c) = self.0.sin_cos();
        (Counting(s), Counting(c))
    }
}
