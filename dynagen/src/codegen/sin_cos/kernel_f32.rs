
// For f32 modules: the same steps in f64 arithmetic with less precision
// kept, as 24 bits are asked for: π/2 ≈ P1 + P2 in two parts (P2 of 53
// bits: |r − exact| ≤ 2e-26·|x|, so the fast path takes |r| ≥ 2⁻⁴⁵·|x|,
// every f32 angle up to 1e5 rad), no low part rl, and S of degree 3 and C
// of degree 2 (scripts/sin_cos_minimax.py 3 2: relative errors 5e-12 and
// 1.2e-10), so the result is within 2⁻³³ relative of the exact value before
// its one rounding to f32 (fused multiply-adds, where the target has them,
// round once where the unfused code rounds twice: the bound holds for
// both). The slow path is the f64 kernel's.

/// The sines and cosines of `x` (`f32`), entry by entry: within 1 ulp of
/// `f32` for every finite angle (NaN and ±∞ give NaN); two or four angles
/// at a time in vector instructions, like `sin_cos_array`.
#[inline]
#[allow(dead_code)]
pub fn sin_cos_array_f32<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    #[cfg(all(
        target_arch = "x86_64",
        not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
    ))]
    if RUNTIME_DISPATCH && has_avx512() {
        // SAFETY: this processor has AVX-512 (checked just above).
        return unsafe { sin_cos_array_f32_avx512(x) };
    }
    #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
    if RUNTIME_DISPATCH && has_avx2_and_fma() {
        // SAFETY: this processor has AVX2 and FMA (checked just above).
        return unsafe { sin_cos_array_f32_avx2_fma(x) };
    }
    sin_cos_array_f32_on::<Baseline, N>(x)
}

/// `sin_cos_array_f32` compiled for AVX2 and FMA.
#[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
#[target_feature(enable = "avx2,fma")]
#[allow(dead_code)]
unsafe fn sin_cos_array_f32_avx2_fma<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    sin_cos_array_f32_on::<Avx2Fma, N>(x)
}

/// `sin_cos_array_f32` compiled for AVX-512.
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl,avx512dq")]
#[allow(dead_code)]
unsafe fn sin_cos_array_f32_avx512<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    sin_cos_array_f32_on::<Avx2Fma, N>(x)
}

/// `sin_cos_array_f32` in the instructions of `I`.
#[inline(always)]
fn sin_cos_array_f32_on<I: Isa, const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    let mut s = [0.0; N];
    let mut c = [0.0; N];
    if sin_cos_batches::<I, Single, N>(&each_of(x, f64::from), &mut s, &mut c) {
        (each_of(&s, |s| s as f32), each_of(&c, |c| c as f32))
    } else {
        let (mut s, mut c) = ([0.0; N], [0.0; N]);
        let mut i = 0;
        while i < N {
            (s[i], c[i]) = sin_cos_kernel_f32_on::<I>(x[i]);
            i += 1;
        }
        (s, c)
    }
}

/// `[f(x[0]), …, f(x[N − 1])]` for scalars `T` and `U` (see `each!`).
#[inline(always)]
fn each_of<T: Copy, U: Copy + Default, const N: usize>(x: &[T; N], f: impl Fn(T) -> U) -> [U; N] {
    let mut out = [U::default(); N];
    let mut i = 0;
    while i < N {
        out[i] = f(x[i]);
        i += 1;
    }
    out
}

/// The sine and cosine of one `f32` angle: within 1 ulp of `f32` for every
/// finite angle (NaN and ±∞ give NaN).
#[inline]
#[allow(dead_code)]
pub fn sin_cos_kernel_f32(x: f32) -> (f32, f32) {
    #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
    if RUNTIME_DISPATCH && has_avx2_and_fma() {
        // SAFETY: this processor has AVX2 and FMA (checked just above).
        return unsafe { sin_cos_kernel_f32_avx2_fma(x) };
    }
    sin_cos_kernel_f32_on::<Baseline>(x)
}

/// `sin_cos_kernel_f32` compiled for AVX2 and FMA.
#[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
#[target_feature(enable = "avx2,fma")]
#[allow(dead_code)]
unsafe fn sin_cos_kernel_f32_avx2_fma(x: f32) -> (f32, f32) {
    sin_cos_kernel_f32_on::<Avx2Fma>(x)
}

/// `sin_cos_kernel_f32` in the instructions of `I`.
#[inline(always)]
fn sin_cos_kernel_f32_on<I: Isa>(x: f32) -> (f32, f32) {
    match sin_cos_lanes_f32::<I, f64, 1>([f64::from(x)]) {
        [(s, c, true)] => (s as f32, c as f32),
        _ => {
            let (s, c) = sin_cos_kernel_on::<I>(f64::from(x));
            (s as f32, c as f32)
        }
    }
}

/// `sin_cos_lanes_f32`: within 1 ulp of `f32` once rounded to it.
struct Single;

impl FastPath for Single {
    #[inline(always)]
    fn lanes<I: Isa, V: Lanes, const P: usize>(x: [V; P]) -> [(V, V, bool); P] {
        sin_cos_lanes_f32::<I, V, P>(x)
    }
}

/// The fast path for `f32` angles (in `f64`) on `P` registers: the sines
/// and cosines before their rounding to `f32`, and whether they are within
/// 1 ulp of `f32` once rounded (false: take `sin_cos_kernel`).
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
fn sin_cos_lanes_f32<I: Isa, V: Lanes, const P: usize>(x: [V; P]) -> [(V, V, bool); P] {
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
    let v = V::splat;
    let t: [V; P] = each!(i => x[i].mul(v(FRAC_2_PI)).add(v(ROUND)));
    let k: [V; P] = each!(i => t[i].sub(v(ROUND)));
    let r: [V; P] = each!(i => k[i].neg().mul_add::<I>(v(P2), k[i].neg().mul_add::<I>(v(P1), x[i])));
    // Within 1 ulp of f32 if |x| ≤ 1.5e6 and |r| ≥ 2⁻⁴⁵·|x|: min(2⁴⁵·|r|, 1.5e6) ≥ |x|.
    let ok: [bool; P] = each!(i => r[i].abs().mul(v(3.5184372088832e13)).capped_ge(x[i].abs()));
    let z: [V; P] = each!(i => r[i].mul(r[i]));
    let z2: [V; P] = each!(i => z[i].mul(z[i]));
    // r·(1 + z·S(z)) keeps sin(−0) = −0.
    let sin_r: [V; P] = each!(i => {
        r[i].mul(z[i].mul_add::<I>(z2[i].mul_add::<I>(z[i].mul_add::<I>(v(S3), v(S2)), z[i].mul_add::<I>(v(S1), v(S0))), v(1.0)))
    });
    let cos_r: [V; P] = each!(i => {
        z2[i].mul_add::<I>(z[i].mul_add::<I>(z[i].mul_add::<I>(v(C2), v(C1)), v(C0)), v(-0.5).mul_add::<I>(z[i], v(1.0)))
    });
    each!(i => {
        let (s, c) = V::quadrant(sin_r[i], sin_r[i], cos_r[i], t[i]);
        (s, c, ok[i])
    })
}

/// The square root of `x` in `f32`, correctly rounded (x86-64: SSE's
/// `sqrtss`); see `sqrt`.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn sqrtf(x: f32) -> f32 {
    use core::arch::x86_64::{_mm_cvtss_f32, _mm_set_ss, _mm_sqrt_ss};
    // SAFETY: the cfg above compiles this only where SSE2 (and so SSE) is
    // enabled.
    unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))) }
}

/// The square root of `x` in `f32`, correctly rounded (aarch64: NEON's
/// `fsqrt`).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn sqrtf(x: f32) -> f32 {
    use core::arch::aarch64::{vdup_n_f32, vget_lane_f32, vsqrt_f32};
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { vget_lane_f32::<0>(vsqrt_f32(vdup_n_f32(x))) }
}

/// The square root of `x` in `f32`, correctly rounded (targets without a
/// square-root instruction in every build: `sqrtf_portable`).
#[cfg(not(any(
    all(target_arch = "x86_64", target_feature = "sse2"),
    all(target_arch = "aarch64", target_feature = "neon")
)))]
#[inline]
#[allow(dead_code)]
fn sqrtf(x: f32) -> f32 {
    sqrtf_portable(x)
}

/// The square root of `x` in `f32`, correctly rounded, without a
/// square-root instruction: `sqrt_portable` of `x` in `f64`, rounded to
/// `f32`. Rounding twice is exact here: the square root of a number of
/// p = 24 bits rounded to 2p + 2 = 50 ≤ 53 bits and then to p bits is the
/// square root rounded once to p bits (Figueroa, 1995).
#[allow(dead_code)]
fn sqrtf_portable(x: f32) -> f32 {
    sqrt_portable(f64::from(x)) as f32
}
