//! Error-free transformations of `f64` sums and products, and π/2 in three
//! parts: the building blocks of the precise scalars ([`DoubleDouble`](super::DoubleDouble)
//! and [`Compensated`](super::Compensated)).

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (Knuth).
#[inline(always)]
pub(super) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// [`two_sum`] for |a| ≥ |b| (Dekker): three operations instead of six.
#[inline(always)]
pub(super) fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `(p, e)` with `p = fl(a·b)` and `p + e = a·b` exactly, by one fused
/// multiply-add.
#[inline(always)]
pub(super) fn two_prod_fma(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// π/2 as the sum of three doubles.
pub(super) const PI_2: [f64; 3] = [core::f64::consts::FRAC_PI_2, 6.123233995736766e-17, -1.4973849048591698e-33];
