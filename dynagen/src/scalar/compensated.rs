//! A light double-`f64` scalar for compensated computations: a number as the
//! unevaluated sum `hi + lo` of two `f64`, like [`DoubleDouble`](super::DoubleDouble),
//! but built for speed where about 20 correct digits are enough (compensated
//! forward dynamics, [`crate::algorithms::compensated`]).
//!
//! What it gives up against `DoubleDouble`:
//! - additions are the "sloppy" double-double sum (one two-sum on the
//!   leading parts, the trailing parts added in `f64`, one quick
//!   renormalisation): the error is about ε² times the *operands*, not the
//!   result — exactly what cancellation in a sum of terms needs;
//! - products form the exact product of the leading parts (through a fused
//!   multiply-add when the target has one, else by Dekker's splitting, which
//!   needs no library call) and add the cross terms in `f64`;
//! - sine and cosine reduce the angle by π/16 held in three doubles, take the
//!   sine and cosine of the multiple of π/16 from a double-double table, and
//!   sum a short series for the rest (|t| ≤ π/32) with only its first terms
//!   in double-double and the tail in `f64`: a few 1e-21 absolute error, for
//!   angles up to about 1e6 rad;
//! - division and square root take one correction step (about 1e-30).
//!
//! No operation branches on a value except the range reduction of sin/cos,
//! which runs numerically, never symbolically.

use super::error_free::{quick_two_sum, two_prod_fma, two_sum, PI_2};
use super::Scalar;
use crate::spatial::{Mat3, Vec3};
use core::marker::PhantomData;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A compensated `f64`: `hi + lo`, about 32 digits per operation but with
/// the light ("sloppy") double-double operations; see the module
/// documentation. Around 20 correct digits through a whole dynamics
/// recursion, at a few times the cost of `f64`. `E` says how exact products
/// are formed: [`Compensated`] (Dekker's splitting, or a fused multiply-add
/// when the build targets a CPU with one) is the type to use;
/// [`CompensatedFma`] always uses `f64::mul_add`, for code compiled with
/// FMA enabled (see [`crate::algorithms::compensated`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct CompensatedWith<E> {
    /// The leading part.
    pub hi: f64,
    /// The trailing part, |lo| ≲ ulp(hi).
    pub lo: f64,
    product: PhantomData<E>,
}

/// The compensated scalar with exact products by Dekker's splitting (no
/// library call), or by a fused multiply-add when the whole build targets a
/// CPU with one (`-C target-feature=+fma`, `-C target-cpu=native`).
#[cfg(not(target_feature = "fma"))]
pub type Compensated = CompensatedWith<Dekker>;
/// The compensated scalar with exact products by a fused multiply-add (the
/// build targets a CPU with one).
#[cfg(target_feature = "fma")]
pub type Compensated = CompensatedWith<Fused>;
/// The compensated scalar with exact products by `f64::mul_add`: fast only
/// where FMA instructions are enabled (else `mul_add` is a library call).
pub type CompensatedFma = CompensatedWith<Fused>;

/// How a [`CompensatedWith`] forms the exact product `a·b = p + e`.
pub trait ExactProduct: Copy + core::fmt::Debug + Default + PartialEq + 'static {
    /// `(p, e)` with `p = fl(a·b)` and `p + e = a·b` exactly.
    fn two_prod(a: f64, b: f64) -> (f64, f64);
    /// `a·b + c`, fused (one rounding) where products are formed by
    /// fused multiply-adds, else rounded twice: for the small cross terms
    /// of a product, whose own rounding is of order ε².
    fn mul_add(a: f64, b: f64, c: f64) -> f64;
}

/// Exact products by Dekker's splitting: 17 `f64` operations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dekker;
impl ExactProduct for Dekker {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        const SPLIT: f64 = 134_217_729.0; // 2²⁷ + 1
        let split = |x: f64| {
            let c = SPLIT * x;
            let h = c - (c - x);
            (h, x - h)
        };
        let p = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
}

/// Exact products by one fused multiply-add.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fused;
impl ExactProduct for Fused {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        two_prod_fma(a, b)
    }
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a.mul_add(b, c)
    }
}

/// π/16 as the sum of three doubles (π/2's three parts divided by 8, exactly).
const PI_16: [f64; 3] = [PI_2[0] / 8.0, PI_2[1] / 8.0, PI_2[2] / 8.0];

/// (sin hi, sin lo, cos hi, cos lo) of j·π/16, j = 0..7, from the
/// double-double reference.
#[allow(clippy::approx_constant)] // data, not a constant's approximation
const TABLE: [(f64, f64, f64, f64); 8] = [
    (0.0, 0.0, 1.0, 0.0),
    (0.19509032201612828, -7.991079068461733e-18, 0.9807852804032304, 1.854693999782501e-17),
    (0.3826834323650898, -1.0050772696461583e-17, 0.9238795325112867, 1.7645047084336686e-17),
    (0.5555702330196022, 4.709410940561676e-17, 0.8314696123025452, 1.407385698472807e-18),
    (0.7071067811865476, -4.833646656726456e-17, 0.7071067811865476, -4.833646656726456e-17),
    (0.8314696123025452, 1.407385698472807e-18, 0.5555702330196022, 4.709410940561676e-17),
    (0.9238795325112867, 1.7645047084336686e-17, 0.3826834323650898, -1.0050772696461583e-17),
    (0.9807852804032304, 1.854693999782501e-17, 0.19509032201612828, -7.991079068461733e-18),
];

impl<E: ExactProduct> CompensatedWith<E> {
    /// Zero.
    pub const ZERO: Self = Self { hi: 0.0, lo: 0.0, product: PhantomData };
    /// One.
    pub const ONE: Self = Self { hi: 1.0, lo: 0.0, product: PhantomData };

    /// From two parts as they are.
    #[inline(always)]
    const fn raw(hi: f64, lo: f64) -> Self {
        Self { hi, lo, product: PhantomData }
    }
    /// The same number with `|lo| ≤ ulp(hi)/2` (sums and products leave
    /// their parts unnormalised; division, square root and the sine's range
    /// reduction need the leading part to be the value).
    #[inline(always)]
    fn normalised(self) -> Self {
        let (hi, lo) = two_sum(self.hi, self.lo);
        Self::raw(hi, lo)
    }
    /// From its two parts, renormalised.
    pub fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        Self::raw(hi, lo)
    }
    /// The exact product of two doubles.
    #[inline(always)]
    pub fn product(a: f64, b: f64) -> Self {
        let (hi, lo) = E::two_prod(a, b);
        Self::raw(hi, lo)
    }
    /// The nearest `f64` (up to the last rounding).
    #[inline(always)]
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
    /// Multiplication by a double.
    #[inline(always)]
    pub fn mul_f64(self, b: f64) -> Self {
        let (p, e) = E::two_prod(self.hi, b);
        let (hi, lo) = quick_two_sum(p, E::mul_add(self.lo, b, e));
        Self::raw(hi, lo)
    }
    /// Division by a double.
    #[inline(always)]
    fn div_f64(self, b: f64) -> Self {
        let q1 = self.hi / b;
        let (p, e) = E::two_prod(q1, b);
        let q2 = ((self.hi - p) - e + self.lo) / b;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self::raw(hi, lo)
    }

    /// sin and cos of |t| ≲ π/32: double-double head, `f64` tail.
    #[inline(always)]
    fn sin_cos_small(t: Self) -> (Self, Self) {
        let t2 = t * t;
        let x = t2.hi;
        // sin t = t − t³/6 + t⁵(1/5! − t²/7! + t⁴/9! − t⁶/11!); the next term is below 2e-23.
        let t3 = t2 * t;
        let t5 = t3.hi * x;
        let tail = t5 * (1.0 / 120.0 - x * (1.0 / 5040.0 - x * (1.0 / 362880.0 - x * (1.0 / 39916800.0))));
        let sin = t - t3.div_f64(6.0) + Self::raw(tail, 0.0);
        // cos t = 1 − t²/2 + t⁴(1/4! − t²/6! + t⁴/8! − t⁶/10! + t⁸/12!).
        let t4 = x * x;
        let tail = t4
            * (1.0 / 24.0 - x * (1.0 / 720.0 - x * (1.0 / 40320.0 - x * (1.0 / 3628800.0 - x * (1.0 / 479001600.0)))));
        let half = Self::raw(0.5 * t2.hi, 0.5 * t2.lo);
        let cos = Self::raw(1.0, 0.0) - half + Self::raw(tail, 0.0);
        (sin, cos)
    }

    #[inline(always)]
    fn sin_cos_c(self) -> (Self, Self) {
        let x = self.normalised();
        // x = n·π/16 + t, |t| ≤ π/32 (plus rounding); n·π/16 subtracted part
        // by part, the first two products exact.
        let n = (x.hi * (16.0 / core::f64::consts::PI)).round();
        let t = x - Self::product(n, PI_16[0]) - Self::product(n, PI_16[1]) - Self::raw(n * PI_16[2], 0.0);
        let (st, ct) = Self::sin_cos_small(t.normalised());
        // n mod 32 = 8k + j: the angle is k quarter turns plus j·π/16. (A
        // non-finite n casts to 0; t is NaN then, and so are the results.)
        let m = n.rem_euclid(32.0) as usize % 32;
        let (sh, sl, ch, cl) = TABLE[m % 8];
        let (sa, ca) = (Self::raw(sh, sl), Self::raw(ch, cl));
        let s = sa * ct + ca * st;
        let c = ca * ct - sa * st;
        match m / 8 {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }

    fn sqrt_c(self) -> Self {
        let x = self.normalised();
        if x.hi <= 0.0 {
            return Self::raw(x.hi.sqrt(), 0.0);
        }
        let y = x.hi.sqrt();
        let r = (x - Self::product(y, y)).to_f64() / (2.0 * y);
        let (hi, lo) = quick_two_sum(y, r);
        Self::raw(hi, lo)
    }
}

impl<E: ExactProduct> From<f64> for CompensatedWith<E> {
    #[inline(always)]
    fn from(x: f64) -> Self {
        Self::raw(x, 0.0)
    }
}

impl<E: ExactProduct> Add for CompensatedWith<E> {
    type Output = Self;
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        // No renormalisation: hi is the f64 sum, lo gathers the errors.
        let (s, e) = two_sum(self.hi, b.hi);
        Self::raw(s, e + (self.lo + b.lo))
    }
}

impl<E: ExactProduct> Neg for CompensatedWith<E> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::raw(-self.hi, -self.lo)
    }
}

impl<E: ExactProduct> Sub for CompensatedWith<E> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl<E: ExactProduct> Mul for CompensatedWith<E> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        // No renormalisation: hi is the f64 product, lo gathers the errors.
        let (p, e) = E::two_prod(self.hi, b.hi);
        Self::raw(p, E::mul_add(self.hi, b.lo, E::mul_add(self.lo, b.hi, e)))
    }
}

impl<E: ExactProduct> Div for CompensatedWith<E> {
    type Output = Self;
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        let (a, b) = (self.normalised(), b.normalised());
        let q1 = a.hi / b.hi;
        let r = a - b.mul_f64(q1);
        let q2 = r.to_f64() / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self::raw(hi, lo)
    }
}

impl<E: ExactProduct> AddAssign for CompensatedWith<E> {
    #[inline(always)]
    fn add_assign(&mut self, b: Self) {
        *self = *self + b;
    }
}
impl<E: ExactProduct> SubAssign for CompensatedWith<E> {
    #[inline(always)]
    fn sub_assign(&mut self, b: Self) {
        *self = *self - b;
    }
}
impl<E: ExactProduct> MulAssign for CompensatedWith<E> {
    #[inline(always)]
    fn mul_assign(&mut self, b: Self) {
        *self = *self * b;
    }
}

impl<E: ExactProduct> Scalar for CompensatedWith<E> {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Self::from(x)
    }
    #[inline(always)]
    fn to_f64(self) -> Option<f64> {
        Some(Self::to_f64(self))
    }
    fn sqrt(self) -> Self {
        self.sqrt_c()
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        self.sin_cos_c()
    }
    /// One Newton-Schulz step, X(3·1 − XᵀX)/2 = X + X·E/2 with E = 1 − XᵀX:
    /// E (of order ε) is formed from exact products, the correction X·E/2 in
    /// `f64` (its own error is of order ε²), and kept as the trailing parts.
    #[inline(always)]
    fn rotation_constant(r: &Mat3<f64>) -> Mat3<Self> {
        let x = &r.0;
        let mut e = [[0.0f64; 3]; 3];
        for a in 0..3 {
            for b in a..3 {
                let mut s = Self::from(if a == b { 1.0 } else { 0.0 });
                for row in x {
                    s -= Self::product(row[a], row[b]);
                }
                e[a][b] = s.to_f64();
                e[b][a] = e[a][b];
            }
        }
        let mut out = [[Self::ZERO; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let corr = 0.5 * (x[i][0] * e[0][j] + x[i][1] * e[1][j] + x[i][2] * e[2][j]);
                let (hi, lo) = quick_two_sum(x[i][j], corr);
                out[i][j] = Self::raw(hi, lo);
            }
        }
        Mat3(out)
    }
    fn axis_rotation(axis: &Vec3<f64>, _unit: &Vec3<f64>, s: Self, c: Self) -> Mat3<Self> {
        let a = Vec3::<Self>::from_f64(axis);
        let unit = a.scale(inverse_norm(&a, axis.norm()));
        crate::spatial::rodrigues_generic(&unit, s, c)
    }
    fn axis_norm_constant(axis: &Vec3<f64>, norm: f64) -> Self {
        // |a| = |a|²/|a|
        let a = Vec3::<Self>::from_f64(axis);
        a.norm_squared() * inverse_norm(&a, norm)
    }
    const FILE_CONSTANTS: bool = true;
    #[inline(always)]
    fn from_double_double(x: crate::DoubleDouble) -> Self {
        Self::raw(x.hi, x.lo)
    }
}

/// 1/|a| to the scalar's precision, from the `f64` norm `approx`: one
/// Newton step for the inverse square root, y₁ = y₀(3/2 − |a|²y₀²/2), which
/// squares y₀'s relative error (≈ 1e-16 → 1e-32) without the division and
/// square root of the precise scalar (this runs for every general joint
/// axis in every call).
#[inline(always)]
fn inverse_norm<E: ExactProduct>(a: &Vec3<CompensatedWith<E>>, approx: f64) -> CompensatedWith<E> {
    let y0 = 1.0 / approx;
    let t = a.norm_squared().mul_f64(y0 * 0.5).mul_f64(y0);
    (CompensatedWith::<E>::from(1.5) - t).mul_f64(y0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DoubleDouble;

    fn dd(x: Compensated) -> DoubleDouble {
        DoubleDouble::new(x.hi, x.lo)
    }
    /// |a − b| in double-double.
    fn diff(a: Compensated, b: DoubleDouble) -> f64 {
        (dd(a) - b).to_f64().abs()
    }

    /// A small generator, so the test needs no dependency.
    struct Lcg(u64);
    impl Lcg {
        fn unit(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    #[test]
    fn sin_cos_agree_with_the_double_double_reference() {
        // Angles from 1e-8 to 1e4 rad, the multiples of π/16 and the range
        // reduction's edges among them: 5e-21 absolute (sin near its zeros:
        // relative to the angle's distance to them, through the reference).
        let mut rng = Lcg(7);
        let mut worst = 0.0f64;
        let mut angles: Vec<f64> =
            (0..2000).map(|k| rng.unit() * 10f64.powf(-8.0 + 12.0 * (k as f64 / 2000.0))).collect();
        angles.extend((-70..70).map(|j| j as f64 * core::f64::consts::PI / 32.0));
        angles.extend([0.0, -0.0, 1e4, -1e4, 12345.678, core::f64::consts::PI]);
        for x in angles {
            let (s, c) = Compensated::from(x).sin_cos();
            let (rs, rc) = DoubleDouble::from(x).sin_cos();
            let e = diff(s, rs).max(diff(c, rc));
            worst = worst.max(e);
            assert!(e < 5e-21, "sin_cos({x:e}): error {e:e}");
            // Small angles: sin is relatively accurate too.
            assert!(diff(s, rs) <= 1e-20 * rs.abs().to_f64(), "sin({x:e}) relative");
        }
        assert!(worst > 0.0, "the comparison saw rounding errors at all");
        // A double-double angle (not just a double) is reduced with its trailing part.
        let x = Compensated::new(2.5, 1e-17);
        let (rs, _) = DoubleDouble::new(2.5, 1e-17).sin_cos();
        assert!(diff(x.sin(), rs) < 5e-21);
    }

    #[test]
    fn arithmetic_keeps_about_thirty_digits() {
        let mut rng = Lcg(11);
        for _ in 0..1000 {
            let (a, b, c) = (rng.unit() * 1e3, rng.unit(), rng.unit() * 1e-3);
            let (x, y) = (Compensated::new(a, a * 1e-17), Compensated::new(b, c * 1e-20));
            let (rx, ry) = (DoubleDouble::new(a, a * 1e-17), DoubleDouble::new(b, c * 1e-20));
            let scale = rx.abs().to_f64() + ry.abs().to_f64();
            assert!(diff(x + y, rx + ry) <= 1e-30 * scale);
            assert!(diff(x - y, rx - ry) <= 1e-30 * scale);
            assert!(diff(x * y, rx * ry) <= 1e-30 * (rx * ry).abs().to_f64());
            assert!(diff(x / y, rx / ry) <= 1e-29 * (rx / ry).abs().to_f64());
            let ax = rx.abs();
            assert!(diff(Compensated::new(ax.hi, ax.lo).sqrt(), ax.sqrt()) <= 1e-30 * ax.sqrt().to_f64());
        }
        // Cancellation: (1 + 2⁻⁶⁰)² − 1 keeps the 2⁻⁵⁹ that f64 loses.
        let x = Compensated::new(1.0, 2f64.powi(-60));
        assert_eq!((x * x - Compensated::ONE).to_f64(), 2f64.powi(-59));
    }

    #[test]
    fn model_rotations_are_made_orthonormal() {
        // A rotation rounded to f64 (orthonormal to ~1e-16): after the hook,
        // RᵀR = 1 to ~1e-30, in double-double.
        let (s, c) = 0.3f64.sin_cos();
        let (s2, c2) = 1.1f64.sin_cos();
        let rz = Mat3([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]);
        let rx = Mat3([[1.0, 0.0, 0.0], [0.0, c2, -s2], [0.0, s2, c2]]);
        let r = rz.mul_mat(&rx);
        let m = Compensated::rotation_constant(&r);
        for i in 0..3 {
            for j in 0..3 {
                let mut sum = DoubleDouble::from(if i == j { -1.0 } else { 0.0 });
                for k in 0..3 {
                    sum += dd(m.0[k][i]) * dd(m.0[k][j]);
                }
                assert!(sum.to_f64().abs() < 1e-30, "(RᵀR − 1)[{i}][{j}] = {:e}", sum.to_f64());
                assert!((m.0[i][j].to_f64() - r.0[i][j]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn general_axes_agree_with_the_double_double_reference() {
        // The unit axis by one Newton step from the f64 norm, and |a|:
        // against DoubleDouble's square root and division, to ~1e-31.
        let mut rng = Lcg(11);
        let (s, c) = Compensated::from(0.7).sin_cos();
        let (sd, cd) = (dd(s), dd(c)); // the same sine and cosine: only the axis differs
        for _ in 0..200 {
            let scale = 10f64.powf(3.0 * rng.unit());
            let a = Vec3([rng.unit() * scale, rng.unit() * scale, rng.unit() * scale]);
            let (norm, unit) = (a.norm(), a.scale(1.0 / a.norm()));
            let n = Compensated::axis_norm_constant(&a, norm);
            let nd = DoubleDouble::axis_norm_constant(&a, norm);
            assert!(diff(n, nd) <= 1e-31 * norm, "{a:?}: |a| off by {:e}", diff(n, nd));
            let r = Compensated::axis_rotation(&a, &unit, s, c);
            let rd = DoubleDouble::axis_rotation(&a, &unit, sd, cd);
            for i in 0..3 {
                for j in 0..3 {
                    assert!(
                        diff(r.0[i][j], rd.0[i][j]) < 1e-30,
                        "{a:?}: R[{i}][{j}] off by {:e}",
                        diff(r.0[i][j], rd.0[i][j])
                    );
                }
            }
        }
    }
}
