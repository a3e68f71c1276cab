
// For f32 modules: the same steps in f64 arithmetic with less precision
// kept, as 24 bits are asked for: π/2 ≈ P1 + P2 in two parts (P2 of 53
// bits: |r − exact| ≤ 2e-26·|x|, so the fast path takes |r| ≥ 2⁻⁴⁵·|x|,
// every f32 angle up to 1e5 rad), no low part rl, and S of degree 3 and C
// of degree 2 (scripts/sin_cos_minimax.py 3 2: relative errors 5e-12 and
// 1.2e-10), so the result is within 2⁻³³ relative of the exact value before
// its one rounding to f32 (fused multiply-adds, where the target has them,
// round once where the unfused code rounds twice: the bound holds for
// both). The slow path is the f64 kernel's.

/// `a·b + c` in `f32` with one rounding (x86-64 with the `fma` feature);
/// see `fma`.
#[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn fmaf(a: f32, b: f32, c: f32) -> f32 {
    use core::arch::x86_64::{_mm_cvtss_f32, _mm_fmadd_ss, _mm_set_ss};
    // SAFETY: the cfg above compiles this only where the `fma` target
    // feature is enabled, so the instruction exists.
    unsafe { _mm_cvtss_f32(_mm_fmadd_ss(_mm_set_ss(a), _mm_set_ss(b), _mm_set_ss(c))) }
}

/// `a·b + c` in `f32` with one rounding (aarch64).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn fmaf(a: f32, b: f32, c: f32) -> f32 {
    use core::arch::aarch64::{vdup_n_f32, vfma_f32, vget_lane_f32};
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { vget_lane_f32::<0>(vfma_f32(vdup_n_f32(c), vdup_n_f32(a), vdup_n_f32(b))) }
}

/// `a·b + c` in `f32`, rounded twice (targets without a fused multiply-add).
#[cfg(not(any(
    all(target_arch = "x86_64", target_feature = "fma"),
    all(target_arch = "aarch64", target_feature = "neon")
)))]
#[inline(always)]
#[allow(dead_code)]
fn fmaf(a: f32, b: f32, c: f32) -> f32 {
    a * b + c
}

/// The sines and cosines of `x` (`f32`), entry by entry: within 1 ulp of
/// `f32` for every finite angle (NaN and ±∞ give NaN); two angles at a time
/// in vector instructions.
#[inline]
pub fn sin_cos_array_f32<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    let mut s = [0.0; N];
    let mut c = [0.0; N];
    let mut fast = true;
    let mut i = 0;
    while i + 2 <= N {
        let (s0, c0, ok0) = sin_cos_fast_f32(x[i]);
        let (s1, c1, ok1) = sin_cos_fast_f32(x[i + 1]);
        (s[i], s[i + 1], c[i], c[i + 1]) = (s0, s1, c0, c1);
        fast &= ok0 & ok1;
        i += 2;
    }
    if i < N {
        let ok;
        (s[i], c[i], ok) = sin_cos_fast_f32(x[i]);
        fast &= ok;
    }
    if !fast {
        sin_cos_again_f32(x, &mut s, &mut c);
    }
    (s, c)
}

/// The rare case of `sin_cos_array_f32`: every angle again by `sin_cos_kernel`.
#[cold]
#[inline(never)]
fn sin_cos_again_f32(x: &[f32], s: &mut [f32], c: &mut [f32]) {
    for ((x, s), c) in x.iter().zip(s).zip(c) {
        let (a, b) = sin_cos_kernel(f64::from(*x));
        (*s, *c) = (a as f32, b as f32);
    }
}

/// The sine and cosine of one `f32` angle, and whether they are within 1
/// ulp (false: take `sin_cos_kernel`).
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
fn sin_cos_fast_f32(x: f32) -> (f32, f32, bool) {
    const FRAC_2_PI: f64 = 0.6366197723675814;
    const ROUND: f64 = 6755399441055744.0;
    const P1: f64 = 1.5707963267341256;
    const P2: f64 = 6.077100506506192e-11;
    const S0: f64 = -1.666666664079704e-1;
    const S1: f64 = 8.333329304842202e-3;
    const S2: f64 = -1.9839312269384087e-4;
    const S3: f64 = 2.718121627070289e-6;
    const C0: f64 = 4.166664568297395e-2;
    const C1: f64 = -1.388731625430343e-3;
    const C2: f64 = 2.4433157053129838e-5;
    let x = f64::from(x);
    let t = x * FRAC_2_PI + ROUND;
    let k = t - ROUND;
    let r = fma(-k, P2, fma(-k, P1, x));
    let m = r.abs() * 3.5184372088832e13; // 2⁴⁵
    let ok = (if m < 1.5e6 { m } else { 1.5e6 }) >= x.abs();
    let z = r * r;
    // r·(1 + z·S(z)) keeps sin(−0) = −0.
    let sin_r = r * fma(z, fma(z * z, fma(z, S3, S2), fma(z, S1, S0)), 1.0);
    let cos_r = fma(z * z, fma(z, fma(z, C2, C1), C0), fma(-0.5, z, 1.0));
    let (s, c) = <f64 as Lanes>::quadrant(sin_r, sin_r, cos_r, t);
    (s as f32, c as f32, ok)
}
