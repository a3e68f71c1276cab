//! Double-double arithmetic: a number as the unevaluated sum `hi + lo` of
//! two `f64` with `|lo| ≤ ulp(hi)/2`, about 106 bits (32 decimal digits) of
//! precision. It is the reference the report and the stiff tests measure
//! errors against: the generic algorithms run on it unchanged.
//!
//! The algorithms are the classical error-free transformations (Knuth's
//! two-sum, Dekker's product through a fused multiply-add) with the
//! renormalisations of Hida, Li and Bailey's "QD" library design. `sin` and
//! `cos` reduce the argument by π/2 held in three doubles (so that angles up
//! to about 1e6 rad keep full precision) and sum Taylor series to 1e-33.
//!
//! Not a performance type: a double-double operation costs 10–20 `f64`
//! operations, and sin/cos about 60 double-double operations.

use super::error_free::{quick_two_sum, two_prod_fma, two_sum, PI_2};
use super::Scalar;
use crate::spatial::{Mat3, Vec3};
use core::cmp::Ordering;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A double-double number `hi + lo`, about 106 bits (32 decimal digits) of
/// precision: the reference scalar errors are measured against.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DoubleDouble {
    /// The leading part: the `f64` nearest the value.
    pub hi: f64,
    /// The trailing part.
    pub lo: f64,
}

impl DoubleDouble {
    /// Zero.
    pub const ZERO: DoubleDouble = DoubleDouble { hi: 0.0, lo: 0.0 };
    /// One.
    pub const ONE: DoubleDouble = DoubleDouble { hi: 1.0, lo: 0.0 };

    /// From its two parts, renormalised.
    pub fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }
    /// The exact sum of two doubles.
    pub fn sum(a: f64, b: f64) -> Self {
        let (hi, lo) = two_sum(a, b);
        DoubleDouble { hi, lo }
    }
    /// The exact product of two doubles.
    pub fn product(a: f64, b: f64) -> Self {
        let (hi, lo) = two_prod_fma(a, b);
        DoubleDouble { hi, lo }
    }
    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
    /// Whether both parts are finite.
    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }
    /// The absolute value.
    pub fn abs(self) -> Self {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -self
        } else {
            self
        }
    }
    /// Multiplication by a double.
    pub fn mul_f64(self, b: f64) -> Self {
        let (p, e) = two_prod_fma(self.hi, b);
        let (hi, lo) = quick_two_sum(p, e + self.lo * b);
        DoubleDouble { hi, lo }
    }
    fn sqrt_dd(self) -> Self {
        if self.hi <= 0.0 {
            // sqrt(0) = 0; a negative argument gives NaN, as f64::sqrt does.
            return DoubleDouble { hi: self.hi.sqrt(), lo: 0.0 };
        }
        // One Newton step from the double square root doubles the digits.
        let y = self.hi.sqrt();
        let y2 = DoubleDouble::product(y, y);
        let r = (self - y2).hi / (2.0 * y);
        DoubleDouble::sum(y, r)
    }
    /// sin and cos of |r| ≤ π/4 by their Taylor series.
    fn sin_cos_reduced(r: Self) -> (Self, Self) {
        let r2 = r * r;
        let eps = 1e-34;
        // sin r = r − r³/3! + …
        let mut term = r;
        let mut sin = r;
        let mut k = 1.0;
        while term.hi.abs() > eps {
            term = -(term * r2) / DoubleDouble::product(k + 1.0, k + 2.0);
            sin += term;
            k += 2.0;
        }
        // cos r = 1 − r²/2! + …
        let mut term = DoubleDouble::ONE;
        let mut cos = DoubleDouble::ONE;
        let mut k = 0.0;
        while term.hi.abs() > eps {
            term = -(term * r2) / DoubleDouble::product(k + 1.0, k + 2.0);
            cos += term;
            k += 2.0;
        }
        (sin, cos)
    }
    fn sin_cos_dd(self) -> (Self, Self) {
        if !self.is_finite() {
            return (DoubleDouble { hi: f64::NAN, lo: 0.0 }, DoubleDouble { hi: f64::NAN, lo: 0.0 });
        }
        // x = k·π/2 + r with |r| ≲ π/4 (k need not be the nearest integer
        // exactly: the series converge fast on a slightly larger range); k·π/2
        // is subtracted part by part, each product exact.
        let kf = (self.hi / PI_2[0]).round();
        let mut r = self;
        for c in PI_2 {
            r -= DoubleDouble::product(kf, c);
        }
        let (s, c) = Self::sin_cos_reduced(r);
        match (kf.rem_euclid(4.0)) as u8 {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }
}

impl PartialOrd for DoubleDouble {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        match self.hi.partial_cmp(&o.hi) {
            Some(Ordering::Equal) => self.lo.partial_cmp(&o.lo),
            other => other,
        }
    }
}

impl From<f64> for DoubleDouble {
    fn from(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DoubleDouble { hi, lo }
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        DoubleDouble { hi: -self.hi, lo: -self.lo }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline]
    fn mul(self, b: Self) -> Self {
        let (p, e) = two_prod_fma(self.hi, b.hi);
        let e = e + (self.hi * b.lo + self.lo * b.hi);
        let (hi, lo) = quick_two_sum(p, e);
        DoubleDouble { hi, lo }
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    #[inline]
    fn div(self, b: Self) -> Self {
        // Three quotient digits, each from the remainder so far.
        let q1 = self.hi / b.hi;
        let r = self - b.mul_f64(q1);
        let q2 = r.hi / b.hi;
        let r = r - b.mul_f64(q2);
        let q3 = r.hi / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo } + DoubleDouble::from(q3)
    }
}

impl AddAssign for DoubleDouble {
    #[inline]
    fn add_assign(&mut self, b: Self) {
        *self = *self + b;
    }
}
impl SubAssign for DoubleDouble {
    #[inline]
    fn sub_assign(&mut self, b: Self) {
        *self = *self - b;
    }
}
impl MulAssign for DoubleDouble {
    #[inline]
    fn mul_assign(&mut self, b: Self) {
        *self = *self * b;
    }
}

impl Scalar for DoubleDouble {
    fn from_f64(x: f64) -> Self {
        DoubleDouble::from(x)
    }
    fn to_f64(self) -> Option<f64> {
        Some(DoubleDouble::to_f64(self))
    }
    fn sqrt(self) -> Self {
        self.sqrt_dd()
    }
    fn sin_cos(self) -> (Self, Self) {
        self.sin_cos_dd()
    }
    fn rotation_constant(r: &Mat3<f64>) -> Mat3<Self> {
        // One Newton-Schulz step X ← X(3·1 − XᵀX)/2 squares the distance
        // to orthonormality: from ~1e-16 to ~1e-32.
        let x = Mat3::<Self>::from_f64(r);
        let xtx = x.transpose().mul_mat(&x);
        let mut k = Mat3::<Self>::zero();
        for i in 0..3 {
            for j in 0..3 {
                let d = if i == j { 3.0 } else { 0.0 };
                k.0[i][j] = (Self::from(d) - xtx.0[i][j]).mul_f64(0.5);
            }
        }
        x.mul_mat(&k)
    }
    fn axis_rotation(axis: &Vec3<f64>, _unit: &Vec3<f64>, s: Self, c: Self) -> Mat3<Self> {
        let a = Vec3::<Self>::from_f64(axis);
        let unit = a.scale(Self::ONE / a.norm_squared().sqrt());
        crate::spatial::rodrigues_generic(&unit, s, c)
    }
    fn axis_norm_constant(axis: &Vec3<f64>, _norm: f64) -> Self {
        Vec3::<Self>::from_f64(axis).norm_squared().sqrt()
    }
    const FILE_CONSTANTS: bool = true;
    fn from_double_double(x: DoubleDouble) -> Self {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// |a − (hi + lo)| relative to |hi|, evaluated in double-double.
    fn rel(a: DoubleDouble, hi: f64, lo: f64) -> f64 {
        let want = DoubleDouble::new(hi, lo);
        let scale = hi.abs().max(1e-300);
        (a - want).to_f64().abs() / scale
    }

    #[test]
    fn arithmetic_to_double_double_precision() {
        // References from mpmath at 60 digits, split as hi + lo.
        let third = DoubleDouble::ONE / DoubleDouble::from(3.0);
        assert!(rel(third, 0.3333333333333333, 1.850371707708594e-17) < 1e-31);
        let two_sevenths = DoubleDouble::from(2.0) / DoubleDouble::from(7.0);
        assert!(rel(two_sevenths, 0.2857142857142857, 1.586032892321652e-17) < 1e-31);
        let s2 = DoubleDouble::from(2.0).sqrt();
        assert!(rel(s2, core::f64::consts::SQRT_2, -9.667293313452913e-17) < 1e-31);
        // (1 + 2⁻⁶⁰)² − 1 = 2⁻⁵⁹ + 2⁻¹²⁰: f64 gives 0; double-double keeps the
        // 2⁻⁵⁹ (the 2⁻¹²⁰ is below its precision relative to the square, ≈ 1).
        let x = DoubleDouble::new(1.0, 2f64.powi(-60));
        let y = x * x - DoubleDouble::ONE;
        assert_eq!(y.to_f64(), 2f64.powi(-59));
        assert_eq!((1.0 + 2f64.powi(-60)).powi(2) - 1.0, 0.0);
        assert!((third * DoubleDouble::from(3.0) - DoubleDouble::ONE).to_f64().abs() < 1e-31);
    }

    #[test]
    #[allow(clippy::approx_constant)] // the literals are data from mpmath, not constants
    fn sin_cos_to_double_double_precision() {
        // (x, sin hi, sin lo, cos hi, cos lo): mpmath, 60 digits, of the double x.
        let cases = [
            (1.0, 0.8414709848078965, 1.776845092935536e-18, 0.5403023058681398, -4.760954612604417e-17),
            (0.5, 0.479425538604203, -5.103969860556013e-18, 0.8775825618903728, -4.2623149864279997e-17),
            (10000.0, -0.30561438888825215, 1.1737169553511932e-17, -0.9521553682590148, -3.9690952362333257e-17),
            (-1234.5678, -0.07803344920002027, 2.762970751686303e-18, -0.9969507414140119, 3.7057717162849634e-17),
            (3.141592653589793, 1.2246467991473532e-16, -2.99476980971834e-33, -1.0, 7.498798913309288e-33),
            (1e-08, 1e-08, -1.6666666666666668e-25, 1.0, -5e-17),
            (100.0, -0.5063656411097588, -3.050947053792115e-18, 0.8623188722876839, 4.334809858136501e-17),
            (
                0.7853981633974483,
                0.7071067811865475,
                4.1036934489363755e-17,
                0.7071067811865476,
                -2.6687565161377232e-17,
            ),
            (0.0025, 0.002499997395834147, 1.46976089436814e-19, 0.9999968750016276, 9.590288877967533e-18),
            (7.0, 0.6569865987187891, 2.937261786543214e-17, 0.7539022543433046, 3.728245359710072e-17),
            (-3.0, -0.1411200080598672, -8.577269787017502e-18, -0.9899924966004454, -4.2060261566099734e-17),
        ];
        for (x, sh, sl, ch, cl) in cases {
            let (s, c) = DoubleDouble::from(x).sin_cos();
            // Absolute error against a magnitude-1 function, except near the
            // zero of sin π where the relative error is checked.
            let tol = 1e-31;
            assert!((s - DoubleDouble::new(sh, sl)).to_f64().abs() < tol * sh.abs().max(1e-16), "sin({x}) = {s:?}");
            assert!((c - DoubleDouble::new(ch, cl)).to_f64().abs() < tol, "cos({x}) = {c:?}");
        }
    }

    #[test]
    fn non_finite_stays_non_finite() {
        let (s, c) = DoubleDouble::from(f64::NAN).sin_cos();
        assert!(s.hi.is_nan() && c.hi.is_nan());
        assert!(!(DoubleDouble::from(f64::INFINITY) * DoubleDouble::from(2.0)).is_finite());
        assert_eq!(DoubleDouble::from(0.0).sqrt().to_f64(), 0.0);
    }
}
