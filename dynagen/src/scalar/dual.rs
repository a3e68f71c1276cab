//! Forward-mode dual numbers over any scalar: `a + b·ε` with `ε² = 0`. An
//! algorithm run on `Dual<S>` with one input's `eps` set to 1 returns, in
//! each output's `eps`, that output's derivative with respect to the input,
//! exact to `S`'s rounding (no step size). On `Dual<Expr>` the trace holds
//! the derivative's expression: hash-consing shares the values between the
//! directions, and a derivative that is structurally zero (an input no path
//! of the recursion reads) folds to the constant 0.

use super::Scalar;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A dual number `re + eps·ε` (ε² = 0): the value and its derivative along
/// one direction.
///
/// ```
/// use dynagen::{Dual, Scalar};
/// let x = Dual::variable(0.5_f64);
/// let y = x.sin() * x; // d(x sin x)/dx = sin x + x cos x
/// assert_eq!(y.re, 0.5_f64.sin() * 0.5);
/// assert!((y.eps - (0.5_f64.sin() + 0.5 * 0.5_f64.cos())).abs() < 1e-16);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dual<S> {
    /// The value.
    pub re: S,
    /// The derivative along the seeded direction.
    pub eps: S,
}

impl<S: Scalar> Dual<S> {
    /// A constant: derivative zero.
    #[inline(always)]
    pub fn constant(re: S) -> Self {
        Dual { re, eps: S::zero() }
    }
    /// The variable differentiated by: derivative one.
    #[inline(always)]
    pub fn variable(re: S) -> Self {
        Dual { re, eps: S::one() }
    }
}

impl<S: Scalar> Add for Dual<S> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Dual { re: self.re + o.re, eps: self.eps + o.eps }
    }
}
impl<S: Scalar> Sub for Dual<S> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Dual { re: self.re - o.re, eps: self.eps - o.eps }
    }
}
impl<S: Scalar> Mul for Dual<S> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Dual { re: self.re * o.re, eps: self.eps * o.re + self.re * o.eps }
    }
}
impl<S: Scalar> Div for Dual<S> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        // (a/b)' = (a' − (a/b)·b')/b
        let re = self.re / o.re;
        Dual { re, eps: (self.eps - re * o.eps) / o.re }
    }
}
impl<S: Scalar> Neg for Dual<S> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Dual { re: -self.re, eps: -self.eps }
    }
}
impl<S: Scalar> AddAssign for Dual<S> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<S: Scalar> SubAssign for Dual<S> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl<S: Scalar> MulAssign for Dual<S> {
    #[inline(always)]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

impl<S: Scalar> Scalar for Dual<S> {
    const TRACED: bool = S::TRACED;
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Dual::constant(S::from_f64(x))
    }
    /// The value, only when the derivative is known to be zero (a constant):
    /// an algorithm that skips work on a known value must not skip a
    /// derivative.
    #[inline(always)]
    fn to_f64(self) -> Option<f64> {
        if self.eps.to_f64() == Some(0.0) {
            self.re.to_f64()
        } else {
            None
        }
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let re = self.re.sqrt();
        Dual { re, eps: self.eps / (re + re) }
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.re.sin_cos();
        (Dual { re: s, eps: c * self.eps }, Dual { re: c, eps: -(s * self.eps) })
    }
    #[inline(always)]
    fn rotation_constant(r: &crate::spatial::Mat3<f64>) -> crate::spatial::Mat3<Self> {
        let m = S::rotation_constant(r);
        crate::spatial::Mat3(m.0.map(|row| row.map(Dual::constant)))
    }
    #[inline(always)]
    fn axis_norm_constant(axis: &crate::spatial::Vec3<f64>, norm: f64) -> Self {
        Dual::constant(S::axis_norm_constant(axis, norm))
    }
    const FILE_CONSTANTS: bool = S::FILE_CONSTANTS;
    #[inline(always)]
    fn from_double_double(x: crate::DoubleDouble) -> Self {
        Dual::constant(S::from_double_double(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DoubleDouble;

    /// Each rule against the derivative worked by hand, and the chain rule
    /// through a composition, against a central difference in double-double.
    #[test]
    fn rules_and_chain_rule() {
        let x = Dual::variable(0.7_f64);
        let c = Dual::constant(2.0);
        assert_eq!((x * c).eps, 2.0);
        assert_eq!((x + c).eps, 1.0);
        assert_eq!((c - x).eps, -1.0);
        assert!(((c / x).eps + 2.0 / 0.49).abs() < 1e-15);
        assert!((x.sqrt().eps - 0.5 / 0.7_f64.sqrt()).abs() < 1e-15);
        assert!((x.cos().eps + 0.7_f64.sin()).abs() < 1e-16);
        assert_eq!(c.to_f64(), Some(2.0));
        assert_eq!(x.to_f64(), None);
        // f(x) = sqrt(1 + sin(x)²)/x
        fn f<T: Scalar>(x: T) -> T {
            (T::one() + x.sin() * x.sin()).sqrt() / x
        }
        let h = 1e-8;
        let at = |x: f64| f(DoubleDouble::from(0.7) + DoubleDouble::from(x));
        let fd = ((at(h) - at(-h)) / DoubleDouble::from(2.0 * h)).to_f64();
        let d = f(x).eps;
        assert!((d - fd).abs() < 1e-14 * fd.abs(), "{d} vs {fd}");
    }
}
