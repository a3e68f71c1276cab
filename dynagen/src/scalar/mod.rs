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

use crate::spatial::{Mat3, Vec3};
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
    /// Whether the scalar traces the algorithm for code generation (the
    /// symbolic [`Expr`](crate::symbolic::Expr)): each operation is then
    /// emitted once, with products by the model's zeros and ones folded
    /// away, so a formulation with fewer operations pays even where, run as
    /// a generic loop over numbers, it would only add code. An algorithm may
    /// choose such a formulation on this constant; both give the same
    /// results up to rounding (tested on `f64` directly). `false` by default.
    const TRACED: bool = false;

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

    /// A rotation matrix of the model (computed in `f64`, so orthonormal only
    /// to `f64` precision). A scalar more precise than `f64` re-establishes
    /// orthonormality at its own precision, so that the model it computes
    /// with is a rigid one and identities such as `RᵀR = 1` hold to its
    /// precision; the default converts entry by entry.
    #[inline(always)]
    fn rotation_constant(r: &Mat3<f64>) -> Mat3<Self> {
        Mat3::from_f64(r)
    }
    /// The rotation by the angle of sine `s` and cosine `c` about a joint
    /// axis: `axis` as given, `unit` its `f64` normalisation. The default
    /// uses `unit`, with the products of its components folded in `f64`; a
    /// more precise scalar normalises `axis` itself, so that the rotation is
    /// exactly about the joint's motion axis.
    #[inline(always)]
    fn axis_rotation(axis: &Vec3<f64>, unit: &Vec3<f64>, s: Self, c: Self) -> Mat3<Self> {
        let _ = axis;
        crate::spatial::linalg_rodrigues(unit, s, c)
    }
    /// `|axis|`, the factor between a revolute joint's position and its
    /// angle (1 for a unit axis), computed in `f64` as `norm`.
    #[inline(always)]
    fn axis_norm_constant(axis: &Vec3<f64>, norm: f64) -> Self {
        let _ = axis;
        Self::from_f64(norm)
    }

    /// Whether the scalar computes with the robot file's own constants
    /// where the model has them ([`FileValue`](crate::model::FileValue):
    /// placements with their rotations from rpy, unit axes, inertias moved
    /// to body frames and merged through fixed joints, all computed in
    /// double-double from the file's decimals) rather than with their `f64`
    /// rounding. `false` by default: `f64`, `f32` and the symbolic scalar
    /// (hence generated code) compute with the `f64` model. The precise
    /// scalars set it, so that a double-double reference is the file's
    /// robot, not one an ε away, which cancelling states would amplify.
    /// Where the model has no file value (a robot built in Rust, whose
    /// `f64` numbers are exact), the hooks above apply.
    const FILE_CONSTANTS: bool = false;
    /// A model constant from the robot file, in double-double (called only
    /// when [`FILE_CONSTANTS`](Self::FILE_CONSTANTS) is set); the default
    /// rounds it to `f64`.
    #[inline(always)]
    fn from_double_double(x: DoubleDouble) -> Self {
        Self::from_f64(x.to_f64())
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

mod compensated;
mod counting;
mod decimal;
mod double_double;
mod dual;
mod error_free;
pub use compensated::{Compensated, CompensatedFma, CompensatedWith, Dekker, ExactProduct, Fused};
pub use counting::Counting;
pub use double_double::DoubleDouble;
pub use dual::Dual;
