// The sine and cosine of joint angles in plain f64 arithmetic: nothing from
// std or any crate. Within 1 ulp of the exact values for every finite
// angle; NaN and ±∞ give NaN.
//
// 1. Fast path, |x| ≤ 1.5e6 rad (Cody and Waite): x = k·π/2 + r with k the
//    integer nearest x·2/π (rounded by adding and subtracting 1.5·2⁵²) and
//    π/2 ≈ P1 + P2 + P3, P1 and P2 of 33 significant bits (so k·P1, k·P2
//    and x − k·P1 are exact for |k| < 2²⁰) and P3 the next 53 bits. r is
//    kept as a + b, |r − (a + b)| ≤ 3e-37·|x|: a = (x − k·P1) − k·P2
//    rounded, b its rounding error (exact) − k·P3, so |b| ≤ ulp(a)/2 + 2e-15.
//    The pair is not renormalised: step 3 starts from a at once, and b
//    catches up (it is needed only in the last terms).
// 2. Slow path, taken only when the fast path's r could have lost digits
//    (|a| < 2⁻⁵⁸·|x|: the doubles nearest to multiples of π/2, fewer than
//    one angle in 10¹¹), |x| > 1.5e6 rad, NaN or ±∞ (Payne and Hanek): the
//    bits of x·2/π near the binary point from x's 53-bit integer times a
//    192-bit window of 2/π (1280 bits of it in the table), so r carries
//    ~125 bits for every finite x.
// 3. On |r| ≤ π/4: sin r = r + r³·S(r²), cos r = 1 − r²/2 + r⁴·C(r²), S and
//    C of degree 5, minimax for the error relative to sin and cos
//    (coefficients by scripts/sin_cos_minimax.py, Remez in 50 digits: max
//    relative error 1.1e-17 and 1.1e-18 after rounding to f64), evaluated
//    by Estrin's scheme (short dependency chains), at r's high part rh (a);
//    its low part rl (b) enters as rl·cos rh and −rl·sin rh, each to
//    O(rl·rh⁶) (1 − rh²/2 + rh⁴/24, rh − rh³/6 + rh⁵/120), which keeps
//    |rl| up to 2e-15 far below an ulp. The leading terms rh and 1 − rh²/2
//    (with its rounding error kept) are added last.
//    Where the target has fused multiply-adds (`fma` below), each `a·b + c`
//    of the polynomials and of the final sums is one, rounded once instead
//    of twice: every rounding error of the fused evaluation is one of the
//    unfused evaluation's (a fused product adds none), so the error bound
//    and the 1-ulp result hold for both (the tests measure both: max 0.73
//    ulp unfused, see `tests/tests/generated_fma.rs` for the fused build).
//    x − k·P1 is written fused too (exact either way), and so is x·2/π +
//    1.5·2⁵²: fused, k is the integer nearest the exact x·2/π, which can
//    differ from the unfused k next to a half-integer; |r| then exceeds π/4
//    by an ulp or so, where the polynomials are as accurate.
// 4. The quadrant k mod 4 picks (±sin r, ±cos r) by bit masks.
// `sin_cos_array` runs the fast path on several angles at once, in vector
// registers on x86-64: four to a register where the target has AVX2
// (`-C target-cpu=native` or `x86-64-v3`), else two (SSE2, part of every
// x86-64 target), up to two or three registers interleaved step by step
// (independent chains the processor overlaps). Steps 1, 3 and 4 are written
// once (`sin_cos_lanes`) over the operations of `Lanes`, which `f64`, two-
// and four-lane registers implement lane by lane: the same operations in
// the same order, so every width gives the bits of the one-angle code.

// `fma(a, b, c)`: a·b + c. Where the target has a fused multiply-add
// (x86-64 compiled with the `fma` target feature, e.g. by
// `-C target-cpu=native` on a processor that has it; aarch64 with NEON, which
// every aarch64 Linux, macOS and Windows target has) it is one instruction
// with a single rounding; elsewhere it is `a * b + c`, two roundings, bit for
// bit the unfused expression (plain x86-64 builds give the same results as
// code without `fma`).

// The instructions are written in `fma_x86` and `fma_neon` (`fmaf_x86`,
// `fmaf_neon`): `unsafe` functions compiled with the feature that has them,
// so that rustc inlines `core::arch`'s vector helpers into them before LLVM
// sees the code. Called from a function without the feature, the helpers
// pass their 128-bit vectors through the stack (Rust's ABI for vectors),
// and a body of a few thousand fused multiply-adds gave LLVM's SROA pass
// tens of thousands of stack slots to take apart: its compile time grew
// superlinearly (the 30-joint chain's module: minutes). Written this way
// the machine code is the same and the compile time grows linearly
// (`docs/performance.md`, "Fused multiply-adds and run-time dispatch").

/// `a·b + c` with one rounding (x86-64 with the `fma` feature).
#[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
#[inline(always)]
#[allow(dead_code)]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    // SAFETY: the cfg above compiles this only where the `fma` target
    // feature is enabled, so the instruction exists.
    unsafe { fma_x86(a, b, c) }
}

/// The fused multiply-add instruction (`vfmadd…sd`). Only called where
/// the `fma` feature is known: see `fma` and `Avx2Fma`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
#[inline]
#[allow(dead_code, unused_unsafe)]
unsafe fn fma_x86(a: f64, b: f64, c: f64) -> f64 {
    use core::arch::x86_64::{_mm_cvtsd_f64, _mm_fmadd_sd, _mm_set_sd};
    // SAFETY: compiled with the `fma` feature, called only where it is present.
    unsafe { _mm_cvtsd_f64(_mm_fmadd_sd(_mm_set_sd(a), _mm_set_sd(b), _mm_set_sd(c))) }
}

/// `a·b + c` with one rounding (aarch64).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code)]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { fma_neon(a, b, c) }
}

/// NEON's fused multiply-add (`fmadd`), for `fma`.
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[target_feature(enable = "neon")]
#[inline]
#[allow(dead_code, unused_unsafe)]
unsafe fn fma_neon(a: f64, b: f64, c: f64) -> f64 {
    use core::arch::aarch64::{vdup_n_f64, vfma_f64, vget_lane_f64};
    // SAFETY: compiled only where NEON is enabled.
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

/// `a·b + c` in `f32` with one rounding (x86-64 with the `fma` feature);
/// see `fma`.
#[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
#[inline(always)]
#[allow(dead_code)]
fn fmaf(a: f32, b: f32, c: f32) -> f32 {
    // SAFETY: the cfg above compiles this only where the `fma` target
    // feature is enabled, so the instruction exists.
    unsafe { fmaf_x86(a, b, c) }
}

/// `fma_x86` in `f32` (`vfmadd…ss`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
#[inline]
#[allow(dead_code, unused_unsafe)]
unsafe fn fmaf_x86(a: f32, b: f32, c: f32) -> f32 {
    use core::arch::x86_64::{_mm_cvtss_f32, _mm_fmadd_ss, _mm_set_ss};
    // SAFETY: compiled with the `fma` feature, called only where it is present.
    unsafe { _mm_cvtss_f32(_mm_fmadd_ss(_mm_set_ss(a), _mm_set_ss(b), _mm_set_ss(c))) }
}

/// `a·b + c` in `f32` with one rounding (aarch64).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code)]
fn fmaf(a: f32, b: f32, c: f32) -> f32 {
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { fmaf_neon(a, b, c) }
}

/// `fma_neon` in `f32`.
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[target_feature(enable = "neon")]
#[inline]
#[allow(dead_code, unused_unsafe)]
unsafe fn fmaf_neon(a: f32, b: f32, c: f32) -> f32 {
    use core::arch::aarch64::{vdup_n_f32, vfma_f32, vget_lane_f32};
    // SAFETY: compiled only where NEON is enabled.
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

// `sqrt(x)`: the square root, correctly rounded as IEEE 754 requires, so
// bit for bit std's `f64::sqrt`, which `core` does not have. Generated code
// that may not use std calls it (scene functions with Coulomb friction, whose
// smoothing is v/sqrt(v² + v_ε²)). It is the square-root instruction where
// every build of the target has one: x86-64 (SSE2, part of every x86-64
// target) and aarch64 (NEON); elsewhere `sqrt_portable`, in exact integer
// arithmetic. `sqrtf` (in `f32` modules) is the same in `f32`.

/// The square root of `x`, correctly rounded (x86-64: SSE2's `sqrtsd`).
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn sqrt(x: f64) -> f64 {
    use core::arch::x86_64::{_mm_cvtsd_f64, _mm_set_sd, _mm_sqrt_sd};
    // SAFETY: the cfg above compiles this only where SSE2 is enabled.
    unsafe {
        let v = _mm_set_sd(x);
        _mm_cvtsd_f64(_mm_sqrt_sd(v, v))
    }
}

/// The square root of `x`, correctly rounded (aarch64: NEON's `fsqrt`).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
#[allow(dead_code, unused_unsafe)]
fn sqrt(x: f64) -> f64 {
    use core::arch::aarch64::{vdup_n_f64, vget_lane_f64, vsqrt_f64};
    // SAFETY: the cfg above compiles this only where NEON is enabled.
    unsafe { vget_lane_f64::<0>(vsqrt_f64(vdup_n_f64(x))) }
}

/// The square root of `x`, correctly rounded (targets without a
/// square-root instruction in every build: `sqrt_portable`).
#[cfg(not(any(
    all(target_arch = "x86_64", target_feature = "sse2"),
    all(target_arch = "aarch64", target_feature = "neon")
)))]
#[inline]
#[allow(dead_code)]
fn sqrt(x: f64) -> f64 {
    sqrt_portable(x)
}

/// The square root of `x`, correctly rounded, in integer arithmetic: what
/// `sqrt` is on targets without the instruction, compiled on every target
/// (the tests compare it with `f64::sqrt` bit for bit). ±0 and +∞ give
/// themselves, NaN gives NaN (the operand's, quieted), a negative number
/// NaN. Otherwise x = m·2^e with the integer m ∈ [2⁵², 2⁵³) (a subnormal's
/// significand shifted up), and with s = 54 or 55, whichever makes e − s
/// even, M = m·2^s ∈ [2¹⁰⁶, 2¹⁰⁸) and √x = √M·2^((e − s)/2). The integer
/// root R = ⌊√M⌋ ∈ [2⁵³, 2⁵⁴) is found one bit at a time (exact: the
/// remainder M − R² is kept), and its top 53 bits, plus its last bit, are
/// the significand rounded to nearest: √M/2 lies above the halfway point
/// R/2 when R is odd (it cannot equal it: M = R² would be odd, but M is
/// even) and below it when R is even.
#[allow(dead_code)]
fn sqrt_portable(x: f64) -> f64 {
    if x.is_nan() || x == 0.0 || x == f64::INFINITY {
        return x + x;
    }
    if x < 0.0 {
        return f64::NAN;
    }
    let bits = x.to_bits();
    let (mut m, mut biased) = (bits & ((1 << 52) - 1), (bits >> 52) as i32);
    if biased == 0 {
        // Subnormal: move the leading 1 of m to bit 52.
        let shift = m.leading_zeros() as i32 - 11;
        m <<= shift;
        biased = 1 - shift;
    } else {
        m |= 1 << 52;
    }
    // x = m·2^e.
    let e = biased - 1075;
    let s = if (e - 54) & 1 == 0 { 54 } else { 55 };
    // R = ⌊√M⌋ digit by digit: `bit` runs over the powers of 4 from 4⁵³ down,
    // `rest` is M minus the square of the root found so far.
    let (mut rest, mut root, mut bit) = ((m as u128) << s, 0u128, 1u128 << 106);
    while bit != 0 {
        if rest >= root + bit {
            rest -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    // √x = q·2^((e − s)/2 − 51) with the significand q ∈ [2⁵², 2⁵³]: its
    // leading bit adds 1 to the exponent field below (and q = 2⁵³ carries
    // one more, as it should).
    let q = (root >> 1) as u64 + (root & 1) as u64;
    let below = ((e - s) / 2 + 1075) as u64;
    f64::from_bits((below << 52) + q)
}

// Run-time dispatch (`CodegenOptions::runtime_dispatch`, on unless the
// module says `RUNTIME_DISPATCH = false`). A default x86-64 build has SSE2
// only: no fused multiply-add, two angles to a register. Most x86-64
// processors in use have AVX2 and FMA, so on such builds every public
// function is compiled twice from one generic body: for `Baseline` (the
// build's own target features, the code a build without dispatch has) and
// for `Avx2Fma`, inside a `#[target_feature(enable = "avx2,fma")]` function
// that the public one calls when `has_avx2_and_fma()` says the processor
// has both. The results are then those of a build with `-C
// target-feature=+avx2,+fma`: bit for bit those of a native build on such
// a processor, and different in the last bits from the baseline's on
// processors without FMA. Builds that already have both features, and other
// targets, compile no such copy: `Baseline` is all there is.
//
// Processors with AVX-512 (F, VL and DQ) get a third copy on x86-64 builds
// without those features (also `x86-64-v3` ones): the body for `Avx2Fma`
// again (the same operations in the same order, four angles or branches to
// a register, so the same bits), compiled with 32 vector registers instead
// of 16, which long bodies need (fewer values spilled to the stack).
// `has_avx512()` checks the processor and that the OS saves the 512-bit
// state. (Eight angles to a register were measured and left out:
// `docs/performance.md`, "An AVX-512 copy of every function".)

/// The instructions a copy of a generic body is compiled for.
#[allow(dead_code)]
trait Isa {
    /// Whether `Lanes::mul_add` rounds once.
    const FUSED: bool;
    /// Whether four angles go to a register (else two), and four branches.
    const QUADS: bool;
    /// `a·b + c` in `f64`.
    fn fma(a: f64, b: f64, c: f64) -> f64;
    /// `a·b + c` in `f32`.
    fn fmaf(a: f32, b: f32, c: f32) -> f32;
}

/// What the build's target features give: fused multiply-adds where the
/// target has them (`fma`, `fmaf`), four angles to a register where it has
/// AVX2.
#[allow(dead_code)]
enum Baseline {}

impl Isa for Baseline {
    const FUSED: bool = cfg!(any(
        all(target_arch = "x86_64", target_feature = "fma"),
        all(target_arch = "aarch64", target_feature = "neon")
    ));
    const QUADS: bool = cfg!(all(target_arch = "x86_64", target_feature = "avx2"));
    #[inline(always)]
    fn fma(a: f64, b: f64, c: f64) -> f64 {
        fma(a, b, c)
    }
    #[inline(always)]
    fn fmaf(a: f32, b: f32, c: f32) -> f32 {
        fmaf(a, b, c)
    }
}

/// AVX2 and FMA: named only in the bodies of `#[target_feature(enable =
/// "avx2,fma")]` functions, which are called only where
/// `has_avx2_and_fma()` holds, and of the AVX-512 copies
/// (`#[target_feature(enable = "avx2,fma,avx512f,avx512vl,avx512dq")]`,
/// called only where `has_avx512()` holds): their operations are the same,
/// their target features (and so their registers) not.
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[allow(dead_code)]
enum Avx2Fma {}

#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
impl Isa for Avx2Fma {
    const FUSED: bool = true;
    const QUADS: bool = true;
    #[inline(always)]
    fn fma(a: f64, b: f64, c: f64) -> f64 {
        // SAFETY: `Avx2Fma` code runs only on processors with FMA (see above).
        unsafe { fma_x86(a, b, c) }
    }
    #[inline(always)]
    fn fmaf(a: f32, b: f32, c: f32) -> f32 {
        // SAFETY: `Avx2Fma` code runs only on processors with FMA (see above).
        unsafe { fmaf_x86(a, b, c) }
    }
}

/// `ask()`'s answer, asked once and then kept in `answer` (0: not asked
/// yet, 1: no, 2: yes; racing first calls store the same answer).
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[inline]
#[allow(dead_code)]
fn remembered(answer: &core::sync::atomic::AtomicU8, ask: fn() -> bool) -> bool {
    use core::sync::atomic::Ordering;
    match answer.load(Ordering::Relaxed) {
        0 => {
            let yes = ask();
            answer.store(if yes { 2 } else { 1 }, Ordering::Relaxed);
            yes
        }
        answer => answer == 2,
    }
}

/// Whether this processor has AVX2 and FMA and the operating system saves
/// the 256-bit registers: asked once (`cpuid`, `xgetbv`), then remembered.
#[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
#[inline]
#[allow(dead_code)]
fn has_avx2_and_fma() -> bool {
    static ANSWER: core::sync::atomic::AtomicU8 = core::sync::atomic::AtomicU8::new(0);
    remembered(&ANSWER, ask_cpu_for_avx2_and_fma)
}

/// `cpuid` leaf 1: FMA (ECX bit 12), OSXSAVE (27), AVX (28); `xgetbv`: the
/// OS saves the SSE and AVX state (XCR0 bits 1 and 2); leaf 7: AVX2 (EBX
/// bit 5).
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[cold]
#[inline(never)]
#[allow(dead_code, unused_unsafe)]
fn ask_cpu_for_avx2_and_fma() -> bool {
    use core::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};
    let bit = |word: u32, b: u32| word >> b & 1 == 1;
    // SAFETY: every x86-64 processor has `cpuid`; `xgetbv` is run only where
    // leaf 1 says the OS has enabled it (OSXSAVE).
    unsafe {
        if __cpuid(0).eax < 7 {
            return false;
        }
        let ecx = __cpuid(1).ecx;
        if !(bit(ecx, 12) && bit(ecx, 27) && bit(ecx, 28)) || _xgetbv(0) & 0b110 != 0b110 {
            return false;
        }
        bit(__cpuid_count(7, 0).ebx, 5)
    }
}

/// Whether this processor has AVX-512 F, VL and DQ (and AVX2 and FMA) and
/// the operating system saves the 512-bit registers: asked once, then
/// remembered.
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[inline]
#[allow(dead_code)]
fn has_avx512() -> bool {
    static ANSWER: core::sync::atomic::AtomicU8 = core::sync::atomic::AtomicU8::new(0);
    remembered(&ANSWER, ask_cpu_for_avx512)
}

/// AVX2 and FMA (`ask_cpu_for_avx2_and_fma`), then `xgetbv`: the OS saves
/// the AVX-512 state too (XCR0 bits 5 to 7); `cpuid` leaf 7: AVX-512 F
/// (EBX bit 16), DQ (17) and VL (31).
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[cold]
#[inline(never)]
#[allow(dead_code, unused_unsafe)]
fn ask_cpu_for_avx512() -> bool {
    use core::arch::x86_64::{__cpuid_count, _xgetbv};
    if !ask_cpu_for_avx2_and_fma() {
        return false;
    }
    let bit = |word: u32, b: u32| word >> b & 1 == 1;
    // SAFETY: the processor has `cpuid` leaf 7 and the OS has enabled
    // `xgetbv` (OSXSAVE), as `ask_cpu_for_avx2_and_fma` found.
    unsafe {
        let ebx = __cpuid_count(7, 0).ebx;
        _xgetbv(0) & 0b1110_0000 == 0b1110_0000 && bit(ebx, 16) && bit(ebx, 17) && bit(ebx, 31)
    }
}

/// The sines and cosines of `x`, entry by entry: within 1 ulp of the exact
/// values for every finite angle (NaN and ±∞ give NaN); two or four angles
/// at a time in vector instructions.
#[inline]
#[allow(dead_code)]
pub fn sin_cos_array<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    #[cfg(all(
        target_arch = "x86_64",
        not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
    ))]
    if RUNTIME_DISPATCH && has_avx512() {
        // SAFETY: this processor has AVX-512 (checked just above).
        return unsafe { sin_cos_array_avx512(x) };
    }
    #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
    if RUNTIME_DISPATCH && has_avx2_and_fma() {
        // SAFETY: this processor has AVX2 and FMA (checked just above).
        return unsafe { sin_cos_array_avx2_fma(x) };
    }
    sin_cos_array_on::<Baseline, N>(x)
}

/// `sin_cos_array` compiled for AVX2 and FMA.
#[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
#[target_feature(enable = "avx2,fma")]
#[allow(dead_code)]
unsafe fn sin_cos_array_avx2_fma<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    sin_cos_array_on::<Avx2Fma, N>(x)
}

/// `sin_cos_array` compiled for AVX-512.
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
))]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl,avx512dq")]
#[allow(dead_code)]
unsafe fn sin_cos_array_avx512<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    sin_cos_array_on::<Avx2Fma, N>(x)
}

/// `sin_cos_array` in the instructions of `I`.
#[inline(always)]
fn sin_cos_array_on<I: Isa, const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut s = [0.0; N];
    let mut c = [0.0; N];
    if !sin_cos_batches::<I, Precise, N>(x, &mut s, &mut c) {
        sin_cos_again::<I>(x, &mut s, &mut c);
    }
    (s, c)
}

/// `[e(0), …, e(P − 1)]` for `each!(i => e(i))`: one step on each of the
/// `P ≥ 1` registers of the function it is used in. A macro, not a function
/// taking a closure: LLVM leaves closures (and `core::array::from_fn`) that
/// return vector registers out of line when their caller is a
/// `#[target_feature]` function (`Avx2Fma` code), and out of line they are
/// compiled without its features; so the fast path calls nothing that is
/// not `#[inline(always)]` (checked in the release assembly).
macro_rules! each {
    ($i:ident => $e:expr) => {{
        let mut out = [{
            let $i = 0;
            $e
        }; P];
        let mut $i = 1;
        while $i < P {
            out[$i] = $e;
            $i += 1;
        }
        out
    }};
}

/// A fast path over registers of angles: (sin, cos, within 1 ulp) per
/// register.
trait FastPath {
    /// The fast path on `P` registers, step by step across them.
    fn lanes<I: Isa, V: Lanes, const P: usize>(x: [V; P]) -> [(V, V, bool); P];
}

/// `sin_cos_lanes`: within 1 ulp of `f64`.
struct Precise;

impl FastPath for Precise {
    #[inline(always)]
    fn lanes<I: Isa, V: Lanes, const P: usize>(x: [V; P]) -> [(V, V, bool); P] {
        sin_cos_lanes::<I, V, P>(x)
    }
}

/// `K`'s fast path on every angle of `x`, the results into `s` and `c`, and
/// whether they are all within 1 ulp (false: redo them on the slow path).
#[inline(always)]
fn sin_cos_batches<I: Isa, K: FastPath, const N: usize>(x: &[f64; N], s: &mut [f64; N], c: &mut [f64; N]) -> bool {
    let mut fast = true;
    let mut i = 0;
    while i < N {
        if I::QUADS {
            fast &= match N - i {
                1..=4 => sin_cos_pass::<I, K, 4, 1, N>(i, [angles(x, i)], s, c),
                _ => sin_cos_pass::<I, K, 4, 2, N>(i, [angles(x, i), angles(x, i + 4)], s, c),
            };
            i += 8;
        } else {
            fast &= match N - i {
                1 | 2 => sin_cos_pass::<I, K, 2, 1, N>(i, [angles(x, i)], s, c),
                3 | 4 => sin_cos_pass::<I, K, 2, 2, N>(i, [angles(x, i), angles(x, i + 2)], s, c),
                _ => sin_cos_pass::<I, K, 2, 3, N>(i, [angles(x, i), angles(x, i + 2), angles(x, i + 4)], s, c),
            };
            i += 6;
        }
    }
    fast
}

/// The `W` angles of `x` from `from` on; past the end, the first ones again
/// (a register of copies of one angle makes the compiler fall back to scalar
/// code).
#[inline(always)]
fn angles<const W: usize, const N: usize>(x: &[f64; N], from: usize) -> [f64; W] {
    let mut out = [0.0; W];
    let mut l = 0;
    while l < W {
        out[l] = x[(from + l) % N];
        l += 1;
    }
    out
}

/// `K`'s fast path on `P` registers of `W` angles, interleaved, the results
/// into `s[i..]` and `c[i..]` (what fits), and whether they are all within 1
/// ulp.
#[inline(always)]
fn sin_cos_pass<I: Isa, K: FastPath, const W: usize, const P: usize, const N: usize>(
    i: usize,
    x: [[f64; W]; P],
    s: &mut [f64; N],
    c: &mut [f64; N],
) -> bool
where
    [f64; W]: ToLanes,
{
    let r = K::lanes::<I, _, P>(each!(p => x[p].to_lanes()));
    let (mut j, mut fast) = (0, true);
    while j < W * P {
        if i + j < N {
            (s[i + j], c[i + j]) = (r[j / W].0.lane(j % W), r[j / W].1.lane(j % W));
        }
        fast &= r[j / W].2;
        j += 1;
    }
    fast
}

/// `W` angles as a register: `[f64; 1]` as `f64`, `[f64; 2]` and `[f64; 4]`
/// on x86-64 as SSE2 and AVX2 registers, elsewhere lane by lane.
trait ToLanes {
    /// The register.
    type V: Lanes;
    /// The angles loaded.
    fn to_lanes(self) -> Self::V;
}

/// What steps 1, 3 and 4 do to angles, lane by lane.
trait Lanes: Copy {
    /// `a` in every lane.
    fn splat(a: f64) -> Self;
    /// Lane `l`.
    fn lane(self, l: usize) -> f64;
    /// The lanes to `out[0]`, `out[1]`, … (as many as there are lanes;
    /// `out` has at least that many).
    fn store(self, out: &mut [f64]);
    /// `self + b`.
    fn add(self, b: Self) -> Self;
    /// `self − b`.
    fn sub(self, b: Self) -> Self;
    /// `self · b`.
    fn mul(self, b: Self) -> Self;
    /// `self / b` (the branch bodies' divisions; the sines and cosines have none).
    #[allow(dead_code)]
    fn div(self, b: Self) -> Self;
    /// `√self`, correctly rounded (the branch bodies' square roots, of
    /// Coulomb friction's smoothing; the sines and cosines have none).
    #[allow(dead_code)]
    fn sqrt(self) -> Self;
    /// `self · b + c`, rounded once if `I::FUSED`.
    fn mul_add<I: Isa>(self, b: Self, c: Self) -> Self;
    /// `−self`.
    fn neg(self) -> Self;
    /// `|self|`.
    fn abs(self) -> Self;
    /// Whether min(`self`, 1.5e6) ≥ `b` in every lane: a NaN `self` takes
    /// 1.5e6, a NaN `b` fails.
    fn capped_ge(self, b: Self) -> bool;
    /// Step 4: (sin, cos) of k·π/2 + r from sin r without its sign bit,
    /// the sign bit of `signed` or-ed in, cos r, and k ≡ the low bits of
    /// `quadrant` (mod 4).
    fn quadrant(sin_r: Self, signed: Self, cos_r: Self, quadrant: Self) -> (Self, Self);
}

impl ToLanes for [f64; 1] {
    type V = f64;
    #[inline(always)]
    fn to_lanes(self) -> f64 {
        self[0]
    }
}

impl Lanes for f64 {
    #[inline(always)]
    fn splat(a: f64) -> f64 {
        a
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn store(self, out: &mut [f64]) {
        out[0] = self;
    }
    #[inline(always)]
    fn add(self, b: f64) -> f64 {
        self + b
    }
    #[inline(always)]
    fn sub(self, b: f64) -> f64 {
        self - b
    }
    #[inline(always)]
    fn mul(self, b: f64) -> f64 {
        self * b
    }
    #[inline(always)]
    fn div(self, b: f64) -> f64 {
        self / b
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        sqrt(self)
    }
    #[inline(always)]
    fn mul_add<I: Isa>(self, b: f64, c: f64) -> f64 {
        I::fma(self, b, c)
    }
    #[inline(always)]
    fn neg(self) -> f64 {
        -self
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::from_bits(self.to_bits() & !(1 << 63))
    }
    #[inline(always)]
    fn capped_ge(self, b: f64) -> bool {
        // The `if` a `min` instruction.
        (if self < 1.5e6 { self } else { 1.5e6 }) >= b
    }
    #[inline(always)]
    fn quadrant(sin_r: f64, signed: f64, cos_r: f64, quadrant: f64) -> (f64, f64) {
        let sb = sin_r.to_bits() | (signed.to_bits() & (1 << 63));
        let (cb, k) = (cos_r.to_bits(), quadrant.to_bits());
        // Odd quadrants swap sine and cosine (d: the bits that differ, or 0);
        // sin changes sign in quadrants 2 and 3, cos in 1 and 2.
        let d = (sb ^ cb) & 0u64.wrapping_sub(k & 1);
        let sin_sign = (k << 62) & (1 << 63);
        let cos_sign = sin_sign ^ (k << 63);
        (f64::from_bits(sb ^ d ^ sin_sign), f64::from_bits(cb ^ d ^ cos_sign))
    }
}

/// `Lanes` in SSE2 (two angles) and AVX2 (four) instructions: the
/// operations of `impl Lanes for f64`, lane by lane.
#[cfg(target_arch = "x86_64")]
macro_rules! vector_lanes {
    ($w:literal, $v:ident, $all:literal, $add:ident, $sub:ident, $mul:ident, $div:ident, $sqrt:ident, $fmadd:ident, $xor_pd:ident,
     $set1:ident, $loadu:ident, $storeu:ident, $andnot:ident, $min:ident, $cmp_ge:expr, $movemask:ident,
     $to_int:ident, $to_float:ident, $and:ident, $or:ident, $xor:ident, $sub64:ident, $zero:ident, $set1_64:ident,
     $shl:ident) => {
        impl ToLanes for [f64; $w] {
            type V = core::arch::x86_64::$v;
            #[inline(always)]
            #[allow(unused_unsafe)]
            fn to_lanes(self) -> Self::V {
                // SAFETY (this and every block below): the processor has the
                // instructions: SSE2 is part of every x86-64 target, and the
                // AVX2 registers and `_fmadd_` are used only where the target
                // has them (`Baseline::QUADS` and `FUSED` are their `cfg`) or
                // in `Avx2Fma` code; loads and stores are of `$w` f64 from and
                // to arrays of `$w` f64.
                unsafe { core::arch::x86_64::$loadu(self.as_ptr()) }
            }
        }
        #[allow(unused_unsafe)]
        impl Lanes for core::arch::x86_64::$v {
            #[inline(always)]
            fn splat(a: f64) -> Self {
                unsafe { core::arch::x86_64::$set1(a) }
            }
            #[inline(always)]
            fn lane(self, l: usize) -> f64 {
                let mut a = [0.0; $w];
                unsafe { core::arch::x86_64::$storeu(a.as_mut_ptr(), self) };
                a[l]
            }
            #[inline(always)]
            fn store(self, out: &mut [f64]) {
                let out = &mut out[..$w];
                unsafe { core::arch::x86_64::$storeu(out.as_mut_ptr(), self) };
            }
            #[inline(always)]
            fn add(self, b: Self) -> Self {
                unsafe { core::arch::x86_64::$add(self, b) }
            }
            #[inline(always)]
            fn sub(self, b: Self) -> Self {
                unsafe { core::arch::x86_64::$sub(self, b) }
            }
            #[inline(always)]
            fn mul(self, b: Self) -> Self {
                unsafe { core::arch::x86_64::$mul(self, b) }
            }
            #[inline(always)]
            fn div(self, b: Self) -> Self {
                unsafe { core::arch::x86_64::$div(self, b) }
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                unsafe { core::arch::x86_64::$sqrt(self) }
            }
            #[inline(always)]
            fn mul_add<I: Isa>(self, b: Self, c: Self) -> Self {
                if I::FUSED {
                    unsafe { core::arch::x86_64::$fmadd(self, b, c) }
                } else {
                    self.mul(b).add(c)
                }
            }
            #[inline(always)]
            fn neg(self) -> Self {
                unsafe { core::arch::x86_64::$xor_pd(self, Self::splat(-0.0)) }
            }
            #[inline(always)]
            fn abs(self) -> Self {
                unsafe { core::arch::x86_64::$andnot(Self::splat(-0.0), self) }
            }
            #[inline(always)]
            fn capped_ge(self, b: Self) -> bool {
                use core::arch::x86_64::*;
                unsafe { $movemask($cmp_ge($min(self, Self::splat(1.5e6)), b)) == $all }
            }
            #[inline(always)]
            fn quadrant(sin_r: Self, signed: Self, cos_r: Self, quadrant: Self) -> (Self, Self) {
                use core::arch::x86_64::*;
                unsafe {
                    let sign = $to_int(Self::splat(-0.0));
                    let sb = $or($to_int(sin_r), $and($to_int(signed), sign));
                    let (cb, k) = ($to_int(cos_r), $to_int(quadrant));
                    let d = $and($xor(sb, cb), $sub64($zero(), $and(k, $set1_64(1))));
                    let sin_sign = $and($shl::<62>(k), sign);
                    let cos_sign = $xor(sin_sign, $shl::<63>(k));
                    ($to_float($xor($xor(sb, d), sin_sign)), $to_float($xor($xor(cb, d), cos_sign)))
                }
            }
        }
    };
}

#[cfg(target_arch = "x86_64")]
vector_lanes!(2, __m128d, 3, _mm_add_pd, _mm_sub_pd, _mm_mul_pd, _mm_div_pd, _mm_sqrt_pd, _mm_fmadd_pd, _mm_xor_pd, _mm_set1_pd, _mm_loadu_pd,
    _mm_storeu_pd, _mm_andnot_pd, _mm_min_pd, _mm_cmpge_pd, _mm_movemask_pd, _mm_castpd_si128, _mm_castsi128_pd,
    _mm_and_si128, _mm_or_si128, _mm_xor_si128, _mm_sub_epi64, _mm_setzero_si128, _mm_set1_epi64x, _mm_slli_epi64);
#[cfg(target_arch = "x86_64")]
vector_lanes!(4, __m256d, 15, _mm256_add_pd, _mm256_sub_pd, _mm256_mul_pd, _mm256_div_pd, _mm256_sqrt_pd, _mm256_fmadd_pd, _mm256_xor_pd, _mm256_set1_pd,
    _mm256_loadu_pd, _mm256_storeu_pd, _mm256_andnot_pd, _mm256_min_pd, _mm256_cmp_pd::<_CMP_GE_OQ>,
    _mm256_movemask_pd, _mm256_castpd_si256, _mm256_castsi256_pd, _mm256_and_si256, _mm256_or_si256,
    _mm256_xor_si256, _mm256_sub_epi64, _mm256_setzero_si256, _mm256_set1_epi64x, _mm256_slli_epi64);

/// Other targets: two angles lane by lane (the compiler may vectorise);
/// four only to compile `sin_cos_batches` (`Baseline::QUADS` is false).
#[cfg(not(target_arch = "x86_64"))]
impl ToLanes for [f64; 2] {
    type V = [f64; 2];
    #[inline(always)]
    fn to_lanes(self) -> [f64; 2] {
        self
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl ToLanes for [f64; 4] {
    type V = [f64; 4];
    #[inline(always)]
    fn to_lanes(self) -> [f64; 4] {
        self
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl<const W: usize> Lanes for [f64; W] {
    #[inline(always)]
    fn splat(a: f64) -> Self {
        [a; W]
    }
    #[inline(always)]
    fn lane(self, l: usize) -> f64 {
        self[l]
    }
    #[inline(always)]
    fn store(self, out: &mut [f64]) {
        out[..W].copy_from_slice(&self);
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        core::array::from_fn(|l| self[l] + b[l])
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        core::array::from_fn(|l| self[l] - b[l])
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        core::array::from_fn(|l| self[l] * b[l])
    }
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        core::array::from_fn(|l| self[l] / b[l])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(sqrt)
    }
    #[inline(always)]
    fn mul_add<I: Isa>(self, b: Self, c: Self) -> Self {
        core::array::from_fn(|l| I::fma(self[l], b[l], c[l]))
    }
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f64::abs)
    }
    #[inline(always)]
    fn capped_ge(self, b: Self) -> bool {
        (0..W).all(|l| self[l].capped_ge(b[l]))
    }
    #[inline(always)]
    fn quadrant(sin_r: Self, signed: Self, cos_r: Self, quadrant: Self) -> (Self, Self) {
        let r: [(f64, f64); W] = core::array::from_fn(|l| f64::quadrant(sin_r[l], signed[l], cos_r[l], quadrant[l]));
        (r.map(|r| r.0), r.map(|r| r.1))
    }
}

// Branch loops in vector lanes (`--branch-loops`): a module's branch body
// `NAME_branchG::<I, V>` runs `W` alike branches at once, lane l of each
// register one branch, over the operations of `Lanes` (the bits of the
// scalar code in every lane). `branch_lanes` loads `W` rows of the
// branches' constants or inputs as registers, `branch_splat` a row shared
// by all, `branch_rows` writes each lane's results to the branch's entries.

/// Rows `from..from + W` of `rows`, entry by entry, as registers of `W`
/// lanes; past the last row, the first ones again (as in `angles`).
#[inline(always)]
#[allow(dead_code)]
fn branch_lanes<const W: usize, const A: usize, const L: usize>(
    rows: &[[f64; A]; L],
    from: usize,
) -> [<[f64; W] as ToLanes>::V; A]
where
    [f64; W]: ToLanes,
{
    let mut entries = [[0.0; W]; A];
    let mut l = 0;
    while l < W {
        let row = &rows[(from + l) % L];
        let mut i = 0;
        while i < A {
            entries[i][l] = row[i];
            i += 1;
        }
        l += 1;
    }
    let mut out = [<<[f64; W] as ToLanes>::V as Lanes>::splat(0.0); A];
    let mut i = 0;
    while i < A {
        out[i] = entries[i].to_lanes();
        i += 1;
    }
    out
}

/// Entries `offset..offset + A` of the results `r` of `L` branches (entry i
/// of branch b at `r[i·L + b]`, as `branch_rows` writes them) for branches
/// `from..from + W` (past the last, the first ones again), as registers:
/// what a branch's second part reads of its first part's results.
#[inline(always)]
#[allow(dead_code)]
fn branch_entries<const W: usize, const A: usize, const L: usize, const N: usize>(
    r: &[f64; N],
    offset: usize,
    from: usize,
) -> [<[f64; W] as ToLanes>::V; A]
where
    [f64; W]: ToLanes,
{
    let mut out = [<<[f64; W] as ToLanes>::V as Lanes>::splat(0.0); A];
    let mut i = 0;
    while i < A {
        let mut lanes = [0.0; W];
        let mut l = 0;
        while l < W {
            lanes[l] = r[(offset + i) * L + (from + l) % L];
            l += 1;
        }
        out[i] = lanes.to_lanes();
        i += 1;
    }
    out
}

/// `x` in every lane, entry by entry.
#[inline(always)]
#[allow(dead_code)]
fn branch_splat<V: Lanes, const A: usize>(x: &[f64; A]) -> [V; A] {
    let mut out = [V::splat(0.0); A];
    let mut i = 0;
    while i < A {
        out[i] = V::splat(x[i]);
        i += 1;
    }
    out
}

/// Lane l of `v` to the results of branch `from + l` in `out`, where
/// entry i of branch b is `out[i·L + b]` (L = N / R branches): one store a
/// register where all `W` branches exist, else lane by lane.
#[inline(always)]
#[allow(dead_code)]
fn branch_rows<V: Lanes, const W: usize, const R: usize, const N: usize>(v: &[V; R], out: &mut [f64; N], from: usize) {
    let branches = N / R;
    let mut i = 0;
    while i < R {
        if from + W <= branches {
            v[i].store(&mut out[i * branches + from..]);
        } else {
            let mut l = 0;
            while from + l < branches {
                out[i * branches + from + l] = v[i].lane(l);
                l += 1;
            }
        }
        i += 1;
    }
}

/// The rare case of `sin_cos_array`: every angle again, one at a time.
#[cold]
#[inline(never)]
fn sin_cos_again<I: Isa>(x: &[f64], s: &mut [f64], c: &mut [f64]) {
    for ((x, s), c) in x.iter().zip(s).zip(c) {
        (*s, *c) = sin_cos_kernel_on::<I>(*x);
    }
}

/// The sine and cosine of one angle `x`: within 1 ulp of the exact values
/// for every finite `x` (NaN and ±∞ give NaN).
#[inline]
#[allow(dead_code)]
pub fn sin_cos_kernel(x: f64) -> (f64, f64) {
    #[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
    if RUNTIME_DISPATCH && has_avx2_and_fma() {
        // SAFETY: this processor has AVX2 and FMA (checked just above).
        return unsafe { sin_cos_kernel_avx2_fma(x) };
    }
    sin_cos_kernel_on::<Baseline>(x)
}

/// `sin_cos_kernel` compiled for AVX2 and FMA.
#[cfg(all(target_arch = "x86_64", not(all(target_feature = "avx2", target_feature = "fma"))))]
#[target_feature(enable = "avx2,fma")]
#[allow(dead_code)]
unsafe fn sin_cos_kernel_avx2_fma(x: f64) -> (f64, f64) {
    sin_cos_kernel_on::<Avx2Fma>(x)
}

/// `sin_cos_kernel` in the instructions of `I`.
#[inline(always)]
fn sin_cos_kernel_on<I: Isa>(x: f64) -> (f64, f64) {
    match sin_cos_lanes::<I, f64, 1>([x]) {
        [(s, c, true)] => (s, c),
        _ => sin_cos_slow::<I>(x),
    }
}

/// Step 1 and 3 on `P` registers of angles, step by step across them: the
/// sines and cosines, and whether they are within 1 ulp (false: take
/// `sin_cos_slow`).
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
fn sin_cos_lanes<I: Isa, V: Lanes, const P: usize>(x: [V; P]) -> [(V, V, bool); P] {
    const FRAC_2_PI: f64 = 0.6366197723675814;
    const ROUND: f64 = 6755399441055744.0; // 1.5·2⁵²: x + ROUND − ROUND rounds x to an integer
    const P1: f64 = 1.5707963267341256;
    const P2: f64 = 6.077100506303966e-11;
    const P3: f64 = 2.0222662487959506e-21;
    let v = V::splat;
    let t: [V; P] = each!(i => x[i].mul_add::<I>(v(FRAC_2_PI), v(ROUND)));
    let k: [V; P] = each!(i => t[i].sub(v(ROUND)));
    let t0: [V; P] = each!(i => k[i].neg().mul_add::<I>(v(P1), x[i])); // exact, fused or not
    let w: [V; P] = each!(i => k[i].mul(v(P2))); // exact
    let a: [V; P] = each!(i => t0[i].sub(w[i]));
    // r ≈ a + b: the rounding error of t0 − w, exact (|t0| ≥ |w|, or else t0 − w is exact), then − k·P3.
    // Not renormalised, so that the polynomials start from a without waiting for b: |b| ≤ ulp(a)/2 +
    // |k|·P3 ≤ 2e-15, which step 3 allows for.
    let b: [V; P] = each!(i => t0[i].sub(a[i]).sub(w[i]).sub(k[i].mul(v(P3))));
    // Within 1 ulp if |x| ≤ 1.5e6 and |a| ≥ 2⁻⁵⁸·|x| (as |r − (a + b)| ≤ 3e-37·|x|), which also
    // holds for k = 0 (a = x) and fails for NaN and ±∞ (then a is NaN): min(2⁵⁸·|a|, 1.5e6) ≥ |x|.
    let ok: [bool; P] = each!(i => a[i].abs().mul(v(2.8823037615171174e17)).capped_ge(x[i].abs()));
    // a's sign is r's, also when a = −0 (x = −0).
    let r = sin_cos_reduced::<I, V, P>(a, b, a, t);
    each!(i => (r[i].0, r[i].1, ok[i]))
}

/// Step 3 and 4: sin and cos of k·π/2 + rh + rl for |rh + rl| ≤ π/4 and
/// k ≡ the low bits of `quadrant` (mod 4); the sign bit of `signed` is or-ed
/// into sin (rh's sign, also when rh = −0).
#[inline(always)]
#[allow(clippy::excessive_precision)]
fn sin_cos_reduced<I: Isa, V: Lanes, const P: usize>(rh: [V; P], rl: [V; P], signed: [V; P], quadrant: [V; P]) -> [(V, V); P] {
    const S: [f64; 6] = [
        -1.666666666666663e-1,
        8.333333333322118e-3,
        -1.9841269829589533e-4,
        2.7557313621384545e-6,
        -2.5050747762700404e-8,
        1.5896230149614662e-10,
    ];
    const C: [f64; 6] = [
        4.1666666666666595e-2,
        -1.3888888888873056e-3,
        2.4801587288851704e-5,
        -2.755731417929683e-7,
        2.08757008419834e-9,
        -1.1358536521605753e-11,
    ];
    let v = V::splat;
    let z: [V; P] = each!(i => rh[i].mul(rh[i]));
    let z2: [V; P] = each!(i => z[i].mul(z[i]));
    // Estrin: (c0 + z·c1) + z²·((c2 + z·c3) + z²·(c4 + z·c5)). (A function, not a closure: called
    // four times, a closure would stay out of line, outside a `#[target_feature]` caller's features.)
    #[inline(always)]
    fn poly<I: Isa, V: Lanes>(c: [f64; 6], z: V, z2: V) -> V {
        let v = V::splat;
        let lo = z.mul_add::<I>(v(c[1]), v(c[0]));
        let (mid, hi) = (z.mul_add::<I>(v(c[3]), v(c[2])), z.mul_add::<I>(v(c[5]), v(c[4])));
        z2.mul_add::<I>(z2.mul_add::<I>(hi, mid), lo)
    }
    let ps: [V; P] = each!(i => poly::<I, V>(S, z[i], z2[i]));
    let pc: [V; P] = each!(i => poly::<I, V>(C, z[i], z2[i]));
    let hz: [V; P] = each!(i => v(0.5).mul(z[i]));
    let w: [V; P] = each!(i => v(1.0).sub(hz[i]));
    // rl·cos rh and rl·sin rh to O(rl·rh⁶): 1 − z/2 + z²/24 and rh·(1 − z/6 + z²/120), so that rl
    // may be up to 2e-15 (the fast path's b) without costing digits.
    let cos_rh: [V; P] = each!(i => z2[i].mul_add::<I>(v(1.0 / 24.0), w[i]));
    let sin_rh: [V; P] =
        each!(i => rh[i].mul(z2[i].mul_add::<I>(v(1.0 / 120.0), z[i].mul_add::<I>(v(-1.0 / 6.0), v(1.0)))));
    // sin(rh + rl) = rh + rh·z·S(z) + rl·cos rh + …; the sign or-ed in keeps sin(−0) = −0.
    let sin_r: [V; P] = each!(i => rh[i].add(rh[i].mul(z[i]).mul_add::<I>(ps[i], rl[i].mul(cos_rh[i]))));
    // cos(rh + rl) = (1 − z/2) + z²·C(z) − rl·sin rh + …, with the rounding error of 1 − z/2.
    let cos_r: [V; P] =
        each!(i => w[i].add(z2[i].mul_add::<I>(pc[i], v(1.0).sub(w[i]).sub(hz[i])).sub(rl[i].mul(sin_rh[i]))));
    each!(i => V::quadrant(sin_r[i], signed[i], cos_r[i], quadrant[i]))
}

/// Step 2: Payne and Hanek's reduction of any finite `x`, then step 3.
#[inline(never)]
#[cold]
#[allow(clippy::unreadable_literal, clippy::approx_constant)]
fn sin_cos_slow<I: Isa>(x: f64) -> (f64, f64) {
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
        let [(s, c)] = sin_cos_reduced::<I, f64, 1>([ax], [0.0], [0.0], [0.0]);
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
    let [(s, c)] = sin_cos_reduced::<I, f64, 1>([rh], [rl], [rh], [f64::from_bits(k)]);
    (if x < 0.0 { -s } else { s }, c)
}
