//! The scalar trait every algorithm is generic over.
//!
//! The same algorithm source runs on `f64` and `f32` (the generic solver), on
//! a higher-precision type (the reference errors are measured against), and
//! on a symbolic expression type (a trace that code generation turns into
//! Rust). The trait therefore asks only for what all of them can provide:
//! the field operations, `sqrt`, `sin` and `cos`, and conversion from `f64`
//! constants. It deliberately has no comparison: an algorithm must not
//! branch on a value, or the symbolic trace would only be valid for one
//! branch. Algorithms may branch on the *model* (which is plain `f64`), never
//! on the state.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real number type the dynamics algorithms can run on.
pub trait Scalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + 'static
{
    /// Converts a model constant (always stored as `f64`) to this scalar.
    fn from_f64(x: f64) -> Self;
    /// The value as `f64`, when the scalar has one (a symbolic scalar has one
    /// only when it is a constant).
    fn to_f64(self) -> Option<f64>;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Sine and cosine of the same angle, in radians.
    fn sin_cos(self) -> (Self, Self);

    /// Zero.
    #[inline(always)]
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// One.
    #[inline(always)]
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// Sine, in radians.
    #[inline(always)]
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    /// Cosine, in radians.
    #[inline(always)]
    fn cos(self) -> Self {
        self.sin_cos().1
    }
}

impl Scalar for f64 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> Option<f64> {
        Some(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
}

impl Scalar for f32 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> Option<f64> {
        Some(self as f64)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f32::sin_cos(self)
    }
}

mod double_double;
pub use double_double::DoubleDouble;
