// The sine and cosine of joint angles in plain f64 arithmetic: nothing from
// std or any crate. Within 1 ulp of the exact values for every finite
// angle; NaN and ±∞ give NaN.
//
// 1. Fast path, |x| ≤ 1.5e6 rad (Cody and Waite): x = k·π/2 + r with k the
//    integer nearest x·2/π (rounded by adding and subtracting 1.5·2⁵²) and
//    π/2 ≈ P1 + P2 + P3, P1 and P2 of 33 significant bits (so k·P1, k·P2
//    and x − k·P1 are exact for |k| < 2²⁰) and P3 the next 53 bits. r is
//    kept as rh + rl, |r − (rh + rl)| ≤ 3e-37·|x|, and |rl| ≤ ulp(rh)/2.
// 2. Slow path, taken only when the fast path's r could have lost digits
//    (|rh| < 2⁻⁵⁸·|x|: the doubles nearest to multiples of π/2, fewer than
//    one angle in 10¹¹), |x| > 1.5e6 rad, NaN or ±∞ (Payne and Hanek): the
//    bits of x·2/π near the binary point from x's 53-bit integer times a
//    192-bit window of 2/π (1280 bits of it in the table), so r carries
//    ~125 bits for every finite x.
// 3. On |r| ≤ π/4: sin r = r + r³·S(r²), cos r = 1 − r²/2 + r⁴·C(r²), S and
//    C of degree 5, minimax for the error relative to sin and cos
//    (coefficients by scripts/sin_cos_minimax.py, Remez in 50 digits: max
//    relative error 1.1e-17 and 1.1e-18 after rounding to f64), evaluated
//    by Estrin's scheme (short dependency chains). The leading terms r and
//    1 − r²/2 (with its rounding error kept) are added last.
//    Where the target has fused multiply-adds (`fma` below), each `a·b + c`
//    of the polynomials and of the final sums is one, rounded once instead
//    of twice: every rounding error of the fused evaluation is one of the
//    unfused evaluation's (a fused product adds none), so the error bound
//    and the 1-ulp result hold for both (the tests measure both: max 0.73
//    ulp unfused, see `tests/tests/generated_fma.rs` for the fused build).
//    x − k·P1 is written fused too (exact either way); the other steps of
//    the reduction are left as they are, so k and the fast-path test are
//    the same on every target.
// 4. The quadrant k mod 4 picks (±sin r, ±cos r) by bit masks.
// `sin_cos_array` runs the fast path on LANES angles at a time, up to three
// such vectors interleaved step by step (independent chains the processor
// overlaps): on x86-64 in SSE2 instructions, two angles a vector, or AVX2,
// four, where the target has it (`sin_cos_lanes`: the same operations as
// the scalar code, so the same bits), elsewhere as the scalar code on pairs,
// which the compiler may vectorise.

// `fma(a, b, c)`: a·b + c. Where the target has a fused multiply-add
// (x86-64 compiled with the `fma` target feature, e.g. by
// `-C target-cpu=native` on a processor that has it; aarch64 with NEON, which
// every aarch64 Linux, macOS and Windows target has) it is one instruction
// with a single rounding; elsewhere it is `a * b + c`, two roundings, bit for
// bit the unfused expression (plain x86-64 builds give the same results as
// code without `fma`).

/// `a·b + c` with one rounding (x86-64 with the `fma` feature).
#[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    use core::arch::x86_64::{_mm_cvtsd_f64, _mm_fmadd_sd, _mm_set_sd};
    // SAFETY: the cfg above compiles this only where the `fma` target
    // feature is enabled, so the instruction exists.
    unsafe { _mm_cvtsd_f64(_mm_fmadd_sd(_mm_set_sd(a), _mm_set_sd(b), _mm_set_sd(c))) }
}

/// `a·b + c` with one rounding (aarch64).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    use core::arch::aarch64::{vdup_n_f64, vfma_f64, vget_lane_f64};
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { vget_lane_f64::<0>(vfma_f64(vdup_n_f64(c), vdup_n_f64(a), vdup_n_f64(b))) }
}

/// `a·b + c`, rounded twice (targets without a fused multiply-add).
#[cfg(not(any(
    all(target_arch = "x86_64", target_feature = "fma"),
    all(target_arch = "aarch64", target_feature = "neon")
)))]
#[inline(always)]
#[allow(dead_code)]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    a * b + c
}

/// The sines and cosines of `x`, entry by entry: within 1 ulp of the exact
/// values for every finite angle (NaN and ±∞ give NaN); `LANES` angles at
/// a time in vector instructions.
#[inline]
pub fn sin_cos_array<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut s = [0.0; N];
    let mut c = [0.0; N];
    let mut fast = true;
    let mut i = 0;
    while i < N {
        // Up to three vectors of LANES angles a pass, interleaved for the
        // processor to overlap (the last vector takes the last angle again
        // where N runs out).
        let at = |j: usize| x[if i + j < N { i + j } else { N - 1 }];
        let ok = match N - i {
            k if k <= LANES => sin_cos_pass::<1, N>(i, core::array::from_fn(|v| core::array::from_fn(|l| at(v * LANES + l))), &mut s, &mut c),
            k if k <= 2 * LANES => sin_cos_pass::<2, N>(i, core::array::from_fn(|v| core::array::from_fn(|l| at(v * LANES + l))), &mut s, &mut c),
            _ => sin_cos_pass::<3, N>(i, core::array::from_fn(|v| core::array::from_fn(|l| at(v * LANES + l))), &mut s, &mut c),
        };
        fast &= ok;
        i += 3 * LANES;
    }
    if !fast {
        sin_cos_again(x, &mut s, &mut c);
    }
    (s, c)
}

/// How many angles one vector of `sin_cos_lanes` holds: 4 with AVX2 (256
/// bits), else 2 (SSE2 on x86-64, 128 bits; elsewhere pairs of scalars).
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
const LANES: usize = 4;
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx2")))]
const LANES: usize = 2;

/// `sin_cos_lanes` on `x`, the results into `s[i..]` and `c[i..]` (what
/// fits), and whether they are all within 1 ulp.
#[inline(always)]
fn sin_cos_pass<const P: usize, const N: usize>(
    i: usize,
    x: [[f64; LANES]; P],
    s: &mut [f64; N],
    c: &mut [f64; N],
) -> bool {
    let (ps, pc, ok) = sin_cos_lanes(x);
    for j in 0..LANES * P {
        if i + j < N {
            (s[i + j], c[i + j]) = (ps[j / LANES][j % LANES], pc[j / LANES][j % LANES]);
        }
    }
    ok
}

/// `sin_cos_fast` on `P` vectors of `LANES` angles, the vectors interleaved
/// step by step: on x86-64 spelled out in SSE2 (part of every x86-64
/// target; the compiler's own vectoriser takes the scalar code for some
/// lengths only), or AVX2 where the target has it, with FMA where it has
/// that: the same operations in the same order as `sin_cos_fast`, so the
/// same bits.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(unused_unsafe, clippy::excessive_precision, clippy::approx_constant)]
fn sin_cos_lanes<const P: usize>(x: [[f64; LANES]; P]) -> ([[f64; LANES]; P], [[f64; LANES]; P], bool) {
    // The vector instructions of `sin_cos_lanes`, by one name for both widths.
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    use core::arch::x86_64::{
        __m256d as F64s, _mm256_add_pd as add_pd, _mm256_and_si256 as and_si, _mm256_andnot_pd as andnot_pd,
        _mm256_castpd_si256 as castpd_si, _mm256_castsi256_pd as castsi_pd, _mm256_loadu_pd as loadu_pd,
        _mm256_min_pd as min_pd, _mm256_movemask_pd as movemask_pd, _mm256_mul_pd as mul_pd, _mm256_or_si256 as or_si,
        _mm256_set1_epi64x as set1_epi64x, _mm256_set1_pd as set1_pd, _mm256_setzero_si256 as setzero_si,
        _mm256_slli_epi64 as slli_epi64, _mm256_storeu_pd as storeu_pd, _mm256_sub_epi64 as sub_epi64,
        _mm256_sub_pd as sub_pd, _mm256_xor_pd as xor_pd, _mm256_xor_si256 as xor_si,
    };
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    use core::arch::x86_64::{
        __m128d as F64s, _mm_add_pd as add_pd, _mm_and_si128 as and_si, _mm_andnot_pd as andnot_pd,
        _mm_castpd_si128 as castpd_si, _mm_castsi128_pd as castsi_pd, _mm_loadu_pd as loadu_pd, _mm_min_pd as min_pd,
        _mm_movemask_pd as movemask_pd, _mm_mul_pd as mul_pd, _mm_or_si128 as or_si, _mm_set1_epi64x as set1_epi64x,
        _mm_set1_pd as set1_pd, _mm_setzero_si128 as setzero_si, _mm_slli_epi64 as slli_epi64, _mm_storeu_pd as storeu_pd,
        _mm_sub_epi64 as sub_epi64, _mm_sub_pd as sub_pd, _mm_xor_pd as xor_pd, _mm_xor_si128 as xor_si,
    };
    // SAFETY: SSE2 is enabled on every x86-64 target, and the AVX2 and FMA
    // instructions are used only where their target features are (the
    // cfgs); the loads and stores read and write LANES f64 of arrays of
    // LANES f64.
    unsafe {
        let v = |a: f64| set1_pd(a);
        fn each<const P: usize>(f: impl FnMut(usize) -> F64s) -> [F64s; P] {
            core::array::from_fn(f)
        }
        let add = |a: &[F64s; P], b: &[F64s; P]| each(|i| add_pd(a[i], b[i]));
        let sub = |a: &[F64s; P], b: &[F64s; P]| each(|i| sub_pd(a[i], b[i]));
        let mul = |a: &[F64s; P], b: &[F64s; P]| each(|i| mul_pd(a[i], b[i]));
        // a·b + c: fused where the scalar `fma` is.
        #[cfg(all(target_feature = "fma", target_feature = "avx2"))]
        let fma = |a: &[F64s; P], b: &[F64s; P], c: &[F64s; P]| {
            each(|i| core::arch::x86_64::_mm256_fmadd_pd(a[i], b[i], c[i]))
        };
        #[cfg(all(target_feature = "fma", not(target_feature = "avx2")))]
        let fma = |a: &[F64s; P], b: &[F64s; P], c: &[F64s; P]| {
            each(|i| core::arch::x86_64::_mm_fmadd_pd(a[i], b[i], c[i]))
        };
        #[cfg(not(target_feature = "fma"))]
        let fma = |a: &[F64s; P], b: &[F64s; P], c: &[F64s; P]| add(&mul(a, b), c);
        // a ≥ b (false if either is NaN)
        #[cfg(target_feature = "avx2")]
        let ge = |a: F64s, b: F64s| core::arch::x86_64::_mm256_cmp_pd::<{ core::arch::x86_64::_CMP_GE_OQ }>(a, b);
        #[cfg(not(target_feature = "avx2"))]
        let ge = |a: F64s, b: F64s| core::arch::x86_64::_mm_cmpge_pd(a, b);
        let neg = |a: &[F64s; P]| each(|i| xor_pd(a[i], v(-0.0)));
        let all = |a: f64| [v(a); P];
        let x: [F64s; P] = each(|i| loadu_pd(x[i].as_ptr()));
        let t = add(&mul(&x, &all(0.6366197723675814)), &all(6755399441055744.0));
        let k = sub(&t, &all(6755399441055744.0));
        let t0 = fma(&neg(&k), &all(1.5707963267341256), &x);
        let w = mul(&k, &all(6.077100506303966e-11));
        let a = sub(&t0, &w);
        let b = sub(&sub(&sub(&t0, &a), &w), &mul(&k, &all(2.0222662487959506e-21)));
        let rh = add(&a, &b);
        let rl = sub(&b, &sub(&rh, &a));
        let m: [F64s; P] = each(|i| mul_pd(andnot_pd(v(-0.0), rh[i]), v(2.8823037615171174e17)));
        let ok: [F64s; P] = each(|i| ge(min_pd(m[i], v(1.5e6)), andnot_pd(v(-0.0), x[i])));
        // sin_cos_reduced
        let z = mul(&rh, &rh);
        let z2 = mul(&z, &z);
        let poly = |c: [f64; 6]| {
            let lo = fma(&z, &all(c[1]), &all(c[0]));
            let mid = fma(&z, &all(c[3]), &all(c[2]));
            let hi = fma(&z, &all(c[5]), &all(c[4]));
            fma(&z2, &fma(&z2, &hi, &mid), &lo)
        };
        let ps = poly([
            -1.666666666666663e-1,
            8.333333333322118e-3,
            -1.9841269829589533e-4,
            2.7557313621384545e-6,
            -2.5050747762700404e-8,
            1.5896230149614662e-10,
        ]);
        let pc = poly([
            4.1666666666666595e-2,
            -1.3888888888873056e-3,
            2.4801587288851704e-5,
            -2.755731417929683e-7,
            2.08757008419834e-9,
            -1.1358536521605753e-11,
        ]);
        let hz = mul(&all(0.5), &z);
        let sin_r = add(&rh, &fma(&mul(&rh, &z), &ps, &mul(&rl, &sub(&all(1.0), &hz))));
        let w = sub(&all(1.0), &hz);
        let cos_r = add(&w, &add(&sub(&sub(&all(1.0), &w), &hz), &fma(&z2, &pc, &neg(&mul(&rh, &rl)))));
        // sin_cos_quadrant, lane by lane
        let sign = castpd_si(v(-0.0));
        let out = |i: usize| {
            let sb = or_si(castpd_si(sin_r[i]), and_si(castpd_si(a[i]), sign));
            let cb = castpd_si(cos_r[i]);
            let q = castpd_si(t[i]);
            let odd = sub_epi64(setzero_si(), and_si(q, set1_epi64x(1)));
            let d = and_si(xor_si(sb, cb), odd);
            let sin_sign = and_si(slli_epi64::<62>(q), sign);
            let cos_sign = xor_si(sin_sign, slli_epi64::<63>(q));
            let (mut s, mut c) = ([0.0; LANES], [0.0; LANES]);
            storeu_pd(s.as_mut_ptr(), castsi_pd(xor_si(xor_si(sb, d), sin_sign)));
            storeu_pd(c.as_mut_ptr(), castsi_pd(xor_si(xor_si(cb, d), cos_sign)));
            (s, c)
        };
        let sc: [([f64; LANES], [f64; LANES]); P] = core::array::from_fn(out);
        let fast = ok.iter().all(|&ok| movemask_pd(ok) == (1 << LANES) - 1);
        (core::array::from_fn(|i| sc[i].0), core::array::from_fn(|i| sc[i].1), fast)
    }
}

/// `sin_cos_fast` on `P` vectors of `LANES` angles (other targets: the
/// compiler's vectoriser may turn the calls into vector instructions).
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn sin_cos_lanes<const P: usize>(x: [[f64; LANES]; P]) -> ([[f64; LANES]; P], [[f64; LANES]; P], bool) {
    let r = x.map(|x| x.map(sin_cos_fast));
    (r.map(|r| r.map(|r| r.0)), r.map(|r| r.map(|r| r.1)), r.iter().flatten().all(|r| r.2))
}

/// The rare case of `sin_cos_array`: every angle again, one at a time.
#[cold]
#[inline(never)]
fn sin_cos_again(x: &[f64], s: &mut [f64], c: &mut [f64]) {
    for ((x, s), c) in x.iter().zip(s).zip(c) {
        (*s, *c) = sin_cos_kernel(*x);
    }
}

/// The sine and cosine of one angle `x`: within 1 ulp of the exact values
/// for every finite `x` (NaN and ±∞ give NaN).
#[inline]
pub fn sin_cos_kernel(x: f64) -> (f64, f64) {
    match sin_cos_fast(x) {
        (s, c, true) => (s, c),
        _ => sin_cos_slow(x),
    }
}

/// Step 1 and 3: the sine and cosine, and whether they are within 1 ulp
/// (false: take `sin_cos_slow`).
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
fn sin_cos_fast(x: f64) -> (f64, f64, bool) {
    const FRAC_2_PI: f64 = 0.6366197723675814;
    const ROUND: f64 = 6755399441055744.0; // 1.5·2⁵²: x + ROUND − ROUND rounds x to an integer
    const P1: f64 = 1.5707963267341256;
    const P2: f64 = 6.077100506303966e-11;
    const P3: f64 = 2.0222662487959506e-21;
    let t = x * FRAC_2_PI + ROUND;
    let k = t - ROUND;
    let t0 = fma(-k, P1, x); // exact, fused or not
    let w = k * P2; // exact
    let a = t0 - w;
    // The rounding error of t0 − w, exact (|t0| ≥ |w|, or else t0 − w is exact), then − k·P3.
    let b = ((t0 - a) - w) - k * P3;
    // Renormalised: |rl| ≤ ulp(rh)/2 (the polynomials need that; |b| ≤ |a| where `ok` below holds).
    let rh = a + b;
    let rl = b - (rh - a);
    // Within 1 ulp if |x| ≤ 1.5e6 and |rh| ≥ 2⁻⁵⁸·|x| (as |r − (rh + rl)| ≤ 3e-37·|x|), which also
    // holds for k = 0 (rh = x) and fails for NaN and ±∞ (then rh is NaN). One comparison:
    // min(2⁵⁸·|rh|, 1.5e6) ≥ |x|, the `if` a `min` instruction (a NaN picks 1.5e6).
    let m = rh.abs() * 2.8823037615171174e17;
    let ok = (if m < 1.5e6 { m } else { 1.5e6 }) >= x.abs();
    let (s, c) = sin_cos_reduced(rh, rl, a.to_bits() & (1 << 63), t.to_bits());
    (s, c, ok)
}

/// Step 3 and 4: sin and cos of k·π/2 + rh + rl for |rh + rl| ≤ π/4 and
/// k ≡ `quadrant` (mod 4); `sign` is the sign bit of rh (in place), also
/// when rh = −0 (which the reduction may turn into +0).
#[inline(always)]
#[allow(clippy::excessive_precision)]
fn sin_cos_reduced(rh: f64, rl: f64, sign: u64, quadrant: u64) -> (f64, f64) {
    const S0: f64 = -1.666666666666663e-1;
    const S1: f64 = 8.333333333322118e-3;
    const S2: f64 = -1.9841269829589533e-4;
    const S3: f64 = 2.7557313621384545e-6;
    const S4: f64 = -2.5050747762700404e-8;
    const S5: f64 = 1.5896230149614662e-10;
    const C0: f64 = 4.1666666666666595e-2;
    const C1: f64 = -1.3888888888873056e-3;
    const C2: f64 = 2.4801587288851704e-5;
    const C3: f64 = -2.755731417929683e-7;
    const C4: f64 = 2.08757008419834e-9;
    const C5: f64 = -1.1358536521605753e-11;
    let z = rh * rh;
    let z2 = z * z;
    // (S0 + z·S1) + z²·((S2 + z·S3) + z²·(S4 + z·S5)), likewise C.
    let ps = fma(z2, fma(z2, fma(z, S5, S4), fma(z, S3, S2)), fma(z, S1, S0));
    let pc = fma(z2, fma(z2, fma(z, C5, C4), fma(z, C3, C2)), fma(z, C1, C0));
    let hz = 0.5 * z;
    // sin(rh + rl) = rh + rh·z·S(z) + rl·(1 − z/2) + …; rh's sign or-ed in keeps sin(−0) = −0.
    let sin_r = rh + fma(rh * z, ps, rl * (1.0 - hz));
    let sb = sin_r.to_bits() | sign;
    // cos(rh + rl) = (1 − z/2) + z²·C(z) − rh·rl + …, with the rounding error of 1 − z/2.
    let w = 1.0 - hz;
    let cos_r = w + (((1.0 - w) - hz) + fma(z2, pc, -(rh * rl)));
    sin_cos_quadrant(sb, cos_r.to_bits(), quadrant)
}

/// Step 4: (sin, cos) of k·π/2 + r from the bits `sb`, `cb` of sin r and
/// cos r and k ≡ `quadrant` (mod 4).
#[inline(always)]
fn sin_cos_quadrant(sb: u64, cb: u64, quadrant: u64) -> (f64, f64) {
    // Odd quadrants swap sine and cosine (d: the bits that differ, or 0);
    // sin changes sign in quadrants 2 and 3, cos in 1 and 2.
    let d = (sb ^ cb) & 0u64.wrapping_sub(quadrant & 1);
    let sin_sign = (quadrant << 62) & (1 << 63);
    let cos_sign = sin_sign ^ (quadrant << 63);
    (f64::from_bits(sb ^ d ^ sin_sign), f64::from_bits(cb ^ d ^ cos_sign))
}

/// Step 2: Payne and Hanek's reduction of any finite `x`, then step 3.
#[inline(never)]
#[cold]
#[allow(clippy::unreadable_literal, clippy::approx_constant)]
fn sin_cos_slow(x: f64) -> (f64, f64) {
    // 2/π = Σ FRAC_2_PI_BITS[i]·2^(−64(i+1)) + less than 2⁻¹²⁸⁰.
    const FRAC_2_PI_BITS: [u64; 20] = [
        0xa2f9836e4e441529, 0xfc2757d1f534ddc0, 0xdb6295993c439041, 0xfe5163abdebbc561,
        0xb7246e3a424dd2e0, 0x06492eea09d1921c, 0xfe1deb1cb129a73e, 0xe88235f52ebb4484,
        0xe99c7026b45f7e41, 0x3991d639835339f4, 0x9c845f8bbdf9283b, 0x1ff897ffde05980f,
        0xef2f118b5a0a6d1f, 0x6d367ecf27cb09b7, 0x4f463f669e5fea2d, 0x7527bac7ebe5f17b,
        0x3d0739f78a5292ea, 0x6bfb5fb11f8d5d08, 0x56033046fc7b6bab, 0xf0cfbc209af4361d,
    ];
    const PIO2_HI: f64 = 1.5707963267948966;
    const PIO2_LO: f64 = 6.123233995736766e-17;
    const SPLIT: f64 = 134217729.0; // 2²⁷ + 1: Dekker's split of a double into two halves
    if !x.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let ax = x.abs();
    if ax < 0.78 {
        let (s, c) = sin_cos_reduced(ax, 0.0, 0, 0);
        return (if x < 0.0 { -s } else { s }, c);
    }
    // |x| = m·2^e with m < 2⁵³ an integer.
    let bits = ax.to_bits();
    let m = (bits & ((1 << 52) - 1)) | (1 << 52);
    let e = (bits >> 52) as i64 - 1075;
    // Bits j < j0 of 2/π (weight 2^−j) add multiples of 4 to x·2/π: skip
    // them. w = the 192 bits from j0 on (the rest adds < 2⁻¹³⁷).
    let j0 = (e - 1).max(1);
    let (limb, shift) = (((j0 - 1) / 64) as usize, ((j0 - 1) % 64) as u32);
    let window = |i: usize| {
        let two = ((FRAC_2_PI_BITS[limb + i] as u128) << 64) | FRAC_2_PI_BITS[limb + i + 1] as u128;
        (two >> (64 - shift)) as u64
    };
    let (w0, w1, w2) = (window(0), window(1), window(2));
    // p = m·w (256 bits, p3 on top); x·2/π ≡ p·2^(e − j0 − 191) (mod 4).
    let m = m as u128;
    let a2 = m * w2 as u128;
    let a1 = m * w1 as u128 + (a2 >> 64);
    let a0 = m * w0 as u128 + (a1 >> 64);
    let (p1, p2, p3) = (a1 as u64 as u128, a0 as u64 as u128, a0 >> 64);
    // y = x·2/π mod 4 in units of 2⁻¹²⁶ (the top 2 bits are the integer part).
    let s = (65 - (e - j0)) as u32 - 64;
    let y = (((p2 << 64) | p1) >> s) | p3.checked_shl(128 - s).unwrap_or(0);
    let k = (y.wrapping_add(1 << 125) >> 126) as u64;
    let f = y.wrapping_sub((k as u128) << 126) as i128; // |f| ≤ 2¹²⁵: r = f·2⁻¹²⁶·π/2
    let fh = f as f64;
    let fl = (f - fh as i128) as f64;
    let scale = f64::from_bits((1023 - 126) << 52);
    let (fh, fl) = (fh * scale, fl * scale);
    // r = (fh + fl)·(PIO2_HI + PIO2_LO), fh·PIO2_HI exactly (Dekker).
    let split = |a: f64| {
        let p = a * SPLIT;
        let hi = p - (p - a);
        (hi, a - hi)
    };
    let ((ah, al), (bh, bl)) = (split(fh), split(PIO2_HI));
    let ph = fh * PIO2_HI;
    let pl = ((ah * bh - ph) + ah * bl + al * bh) + al * bl;
    let low = pl + (fh * PIO2_LO + fl * PIO2_HI);
    let rh = ph + low;
    let rl = low - (rh - ph);
    let (s, c) = sin_cos_reduced(rh, rl, rh.to_bits() & (1 << 63), k);
    (if x < 0.0 { -s } else { s }, c)
}
