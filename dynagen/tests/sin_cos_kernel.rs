//! The batched sine and cosine that every generated module carries
//! (`dynagen/src/codegen/sin_cos/kernel.rs` and `kernel_f32.rs`, compiled
//! into dynagen as [`sin_cos_array`], [`sin_cos_kernel`] and their `f32`
//! versions): within 1 ulp of the exact values (against [`DoubleDouble`] and
//! 60-digit references), the batches bit for bit the one-angle kernel at
//! every length and in every instruction set this machine has, and the
//! module's `sqrt` and `sqrtf` bit for bit std's.

mod support;

use dynagen::codegen::kernel_internals as internals;
use dynagen::codegen::{sin_cos_array, sin_cos_array_f32, sin_cos_batch, sin_cos_kernel, sin_cos_kernel_f32};
use dynagen::{DoubleDouble, Scalar};
use support::Rng;

/// |got − exact| in ulps of the exact value (a double-double).
fn ulps(got: f64, exact: DoubleDouble) -> f64 {
    let err = (DoubleDouble::from(got) - exact).to_f64().abs();
    let hi = exact.hi.abs();
    if hi == 0.0 {
        return if got == 0.0 { 0.0 } else { f64::INFINITY };
    }
    let mut ulp = f64::from_bits(hi.to_bits() & 0x7ff0_0000_0000_0000) * f64::EPSILON;
    // Just below a power of two the spacing is half as wide.
    if hi.to_bits() & 0x000f_ffff_ffff_ffff == 0 && exact.lo.signum() != exact.hi.signum() {
        ulp *= 0.5;
    }
    err / ulp.max(f64::from_bits(1))
}

/// The test angles: zeros, subnormals, tiny ones, the fast path's limits,
/// random ones on several scales, the doubles nearest (and next to)
/// k·π/2 for every k up to 2000 and random k up to 1e5 rad (the slow
/// path's cases: the reduced angle cancels to ~1e-18).
fn angles() -> Vec<f64> {
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let mut xs = vec![0.0, -0.0, 5e-324, -5e-324, 2.2e-308, 1e-300, 1e-20, 1e-9, 0.5, 1.0, 1e5, -1e5, 1.6e6];
    xs.extend([core::f64::consts::FRAC_PI_4, 0.78, 0.7853981633974484, 1.4999999e6, 1.5e6, 1.5000001e6]);
    for scale in [1.0, 4.0, 100.0, 1e4, 1e5, 1.6e6] {
        for _ in 0..3000 {
            xs.push(scale * (2.0 * rng.unit() - 1.0));
        }
    }
    let half_pi = DoubleDouble::new(core::f64::consts::FRAC_PI_2, 6.123233995736766e-17);
    let near = |k: f64, xs: &mut Vec<f64>| {
        let x = (half_pi.mul_f64(k)).to_f64();
        for d in -2i64..=2 {
            let y = f64::from_bits((x.to_bits() as i64 + d) as u64);
            xs.push(y);
            xs.push(-y);
        }
    };
    for k in 1..=2000 {
        near(k as f64, &mut xs);
    }
    for _ in 0..3000 {
        near((rng.unit() * 1e5 / core::f64::consts::FRAC_PI_2).round(), &mut xs);
    }
    xs
}

fn worst(f: impl Fn(f64) -> (f64, f64)) -> (f64, f64, f64) {
    let mut worst = (0.0f64, 0.0f64, 0.0);
    for x in angles() {
        let (s, c) = f(x);
        let (es, ec) = DoubleDouble::from(x).sin_cos();
        let (us, uc) = (ulps(s, es), ulps(c, ec));
        if us.max(uc) > worst.0.max(worst.1) {
            worst.2 = x;
        }
        worst.0 = worst.0.max(us);
        worst.1 = worst.1.max(uc);
    }
    worst
}

#[test]
fn kernel_within_one_ulp() {
    let (s, c, x) = worst(sin_cos_kernel);
    eprintln!("sin_cos_kernel: max error sin {s:.3} ulp, cos {c:.3} ulp (worst at x = {x:e})");
    assert!(s <= 1.0 && c <= 1.0, "sin {s} ulp, cos {c} ulp at x = {x:e}");
}

#[test]
fn the_pair_is_the_scalar_fast_path_bit_for_bit() {
    // Registers of two angles (SSE2 on x86-64) and, where the target has AVX2, four: the
    // same operations lane by lane as one angle at a time, so the same bits.
    type Registers<const W: usize> = fn([[f64; W]; 3]) -> [([f64; W], [f64; W], bool); 3];
    fn check<const W: usize>(xs: &[f64], registers: Registers<W>) {
        for w in xs.windows(3 * W).step_by(W) {
            let regs: [[f64; W]; 3] = core::array::from_fn(|r| core::array::from_fn(|l| w[r * W + l]));
            let got = registers(regs);
            for r in 0..3 {
                let want: Vec<(f64, f64, bool)> = (0..W).map(|l| internals::fast_path(regs[r][l])).collect();
                assert_eq!(got[r].2, want.iter().all(|r| r.2), "{w:?}");
                for (l, want) in want.iter().enumerate() {
                    assert_eq!(got[r].0[l].to_bits(), want.0.to_bits(), "{w:?}");
                    assert_eq!(got[r].1[l].to_bits(), want.1.to_bits(), "{w:?}");
                }
            }
        }
    }
    let xs = angles();
    check::<2>(&xs, internals::fast_path_pairs);
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    check::<4>(&xs, internals::fast_path_quads);
}

#[test]
fn std_sin_cos_within_one_ulp_on_the_same_angles() {
    // The same bound for the platform's libm: a check of the test itself.
    let (s, c, x) = worst(f64::sin_cos);
    eprintln!("f64::sin_cos: max error sin {s:.3} ulp, cos {c:.3} ulp (worst at x = {x:e})");
    assert!(s <= 1.0 && c <= 1.0, "sin {s} ulp, cos {c} ulp at x = {x:e}");
}

/// sin and cos of large angles as double-doubles (hi, lo): `python3
/// scripts/sin_cos_minimax.py --references` (mpmath, 60 digits). Among
/// them 6381956970095103·2⁷⁹⁷, the double nearest to a multiple of π/2
/// (its cosine is −4.7e-19).
#[allow(clippy::type_complexity)]
const LARGE: [(f64, (f64, f64), (f64, f64)); 13] = [
    (1600000.0, (-0.5414010921983009, -2.274244574012984e-17), (0.8407644482056118, -1.936105039722484e-17)),
    (1700000.0, (0.5711113510481804, 2.3243112427694177e-17), (-0.8208725995572772, 4.031711604056672e-18)),
    (30000000.0, (0.9641302978985832, 4.38901881977714e-18), (-0.2654294043130664, 2.6603162585193093e-17)),
    (1000000000.0, (0.5458434494486996, 6.1757333566640775e-18), (0.8378871813639024, -5.4718713289282437e-17)),
    (123456789.0, (0.9901147518020355, -8.980618906983069e-18), (0.14025968153390964, -5.935903437627408e-18)),
    (4503599627370496.0, (0.8742173026236351, 1.1559913144165328e-17), (-0.4855348677422206, -3.3821718984011717e-18)),
    (2500000000000000.0, (0.8462676043361337, 5.0791875276131056e-17), (-0.5327580518877035, 3.9826752396827006e-18)),
    (1e+22, (-0.8522008497671888, -6.7806825896773284e-18), (0.523214785395139, -4.7143201076575164e-17)),
    (1e+100, (-0.3806377310050287, 1.2782658365978341e-17), (0.9247242387519338, 1.669232482156043e-17)),
    (1e+300, (-0.8178819121159085, -4.78135837440326e-17), (-0.5753861119575491, 2.6770761918787068e-17)),
    (5.319372648326541e+255, (1.0, -1.098476220074687e-37), (-4.687165924254628e-19, 4.3720557429382733e-36)),
    (
        1.7976931348623157e+308,
        (0.004961954789184062, -2.5049377676494104e-19),
        (-0.9999876894265599, -2.6032890267216748e-17),
    ),
    (-8500000000000.0, (-0.6391363954162236, 4.613126468627203e-17), (0.7690934065861941, -4.590297231356081e-17)),
];

#[test]
fn kernel_within_one_ulp_on_large_angles() {
    let mut worst = 0.0f64;
    for (x, (sh, sl), (ch, cl)) in LARGE {
        let (gs, gc) = sin_cos_kernel(x);
        let (us, uc) = (ulps(gs, DoubleDouble::new(sh, sl)), ulps(gc, DoubleDouble::new(ch, cl)));
        assert!(us <= 1.0 && uc <= 1.0, "x = {x:e}: sin {gs:e} ({us} ulp), cos {gc:e} ({uc} ulp)");
        worst = worst.max(us).max(uc);
        let (ns, nc) = sin_cos_kernel(-x);
        assert_eq!((ns, nc), (-gs, gc), "odd sine, even cosine at x = {x:e}");
    }
    eprintln!("large angles (1.6e6 to 1.8e308 rad): max error {worst:.3} ulp");
}

#[test]
fn zeros_keep_their_sign_and_nan_and_infinities_give_nan() {
    assert_eq!(sin_cos_kernel(0.0), (0.0, 1.0));
    let (s, c) = sin_cos_kernel(-0.0);
    assert!(s == 0.0 && s.is_sign_negative() && c == 1.0);
    assert_eq!(sin_cos_kernel(-5e-324), (-5e-324, 1.0));
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (s, c) = sin_cos_kernel(x);
        assert!(s.is_nan() && c.is_nan(), "{x}");
    }
}

/// Bit patterns of `f64` and `f32`, to compare results exactly.
trait Bits: Copy + core::fmt::Debug {
    fn bits(self) -> u64;
    fn nan(self) -> bool;
}
impl Bits for f64 {
    fn bits(self) -> u64 {
        self.to_bits()
    }
    fn nan(self) -> bool {
        self.is_nan()
    }
}
impl Bits for f32 {
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
    fn nan(self) -> bool {
        self.is_nan()
    }
}

/// A batch function: the sines and cosines of `N` angles.
type Batch<T, const N: usize> = fn(&[T; N]) -> ([T; N], [T; N]);

/// `batch` on the first `N` angles of `q` gives `one`'s bits, angle by angle.
fn batch_is_one_angle_at_a_time<T: Bits, const N: usize>(q: &[T], batch: Batch<T, N>, one: fn(T) -> (T, T)) {
    let q: [T; N] = core::array::from_fn(|i| q[i]);
    let (s, c) = batch(&q);
    for i in 0..N {
        let (ks, kc) = one(q[i]);
        assert!(s[i].bits() == ks.bits() && c[i].bits() == kc.bits(), "N {N}, {q:?}");
    }
}

#[test]
fn batch_is_the_kernel_entry_by_entry_for_every_length() {
    // Fast angles, then slow ones (NaN, a near multiple of π/2, a huge one)
    // in every position: the slow path redoes the whole batch.
    let mut rng = Rng::new(7);
    let fast: Vec<f64> = (0..9).map(|_| 8.0 * rng.unit() - 4.0).collect();
    let near = (DoubleDouble::new(core::f64::consts::FRAC_PI_2, 6.123233995736766e-17).mul_f64(7.0)).to_f64();
    for slow in [None, Some(f64::NAN), Some(near), Some(1e300), Some(-f64::INFINITY)] {
        for at in 0..9 {
            let mut q = [0.0; 9];
            q.copy_from_slice(&fast);
            if let Some(x) = slow {
                q[at] = x;
            }
            let one = sin_cos_kernel;
            batch_is_one_angle_at_a_time::<f64, 1>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 2>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 3>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 4>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 5>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 6>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 7>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 8>(&q, sin_cos_array, one);
            batch_is_one_angle_at_a_time::<f64, 9>(&q, sin_cos_array, one);
        }
    }
    // The fast path takes every angle up to 1.5e6 rad but the few near multiples of π/2.
    let fast_taken = (0..20000).filter(|_| internals::fast_path(3e6 * rng.unit() - 1.5e6).2).count();
    assert_eq!(fast_taken, 20000);
    let (s, c) = sin_cos_batch(&[0.3, -2.0, 1e5]);
    assert!((s[1] - (-2.0f64).sin()).abs() < 1e-15 && (c[2] - 1e5f64.cos()).abs() < 1e-15);
}

/// |got − exact| in ulps of `f32` at the exact value.
fn ulps_f32(got: f32, exact: DoubleDouble) -> f64 {
    let err = (DoubleDouble::from(f64::from(got)) - exact).to_f64().abs();
    let e = exact.to_f64().abs() as f32;
    if e == 0.0 {
        return if got == 0.0 { 0.0 } else { f64::INFINITY };
    }
    // The spacing of f32 at |exact| (the smaller one just below a power of two).
    let below = f32::from_bits(e.to_bits() - 1);
    let ulp = if f64::from(e) > exact.to_f64().abs() {
        f64::from(e) - f64::from(below)
    } else {
        f64::from(f32::from_bits(e.to_bits() + 1)) - f64::from(e)
    };
    err / ulp
}

#[test]
fn f32_batch_within_one_ulp_of_f32() {
    // Random angles, and the f32 nearest to k·π/2 and its neighbours for k up to 1e5 rad.
    let mut rng = Rng::new(11);
    let mut xs: Vec<f32> = vec![0.0, -0.0, 1e-45, 1e-30, 0.5, 1.0];
    for scale in [1.0, 4.0, 100.0, 1e4, 1e5] {
        for _ in 0..2000 {
            xs.push((scale * (2.0 * rng.unit() - 1.0)) as f32);
        }
    }
    for _ in 0..3000 {
        let k = (rng.unit() * 1e5 / core::f64::consts::FRAC_PI_2).round();
        let x = (k * core::f64::consts::FRAC_PI_2) as f32;
        for d in -2i32..=2 {
            xs.push(f32::from_bits((x.to_bits() as i32 + d) as u32));
        }
    }
    let mut worst = (0.0f64, 0.0f64);
    for chunk in xs.chunks_exact(3) {
        let q = [chunk[0], chunk[1], chunk[2]];
        let (s, c) = sin_cos_array_f32(&q);
        for i in 0..3 {
            let (es, ec) = DoubleDouble::from(f64::from(q[i])).sin_cos();
            worst.0 = worst.0.max(ulps_f32(s[i], es));
            worst.1 = worst.1.max(ulps_f32(c[i], ec));
        }
    }
    eprintln!("sin_cos_array_f32: max error sin {:.3} ulp, cos {:.3} ulp (of f32)", worst.0, worst.1);
    assert!(worst.0 <= 1.0 && worst.1 <= 1.0, "{worst:?}");
    let (s, c) = sin_cos_array_f32(&[f32::NAN, f32::INFINITY]);
    assert!(s.iter().chain(&c).all(|v| v.is_nan()));
    let (s, c) = sin_cos_array_f32(&[-0.0, 0.0]);
    assert!(s[0] == 0.0 && s[0].is_sign_negative() && s[1].is_sign_positive() && c == [1.0, 1.0]);
    // Batches of every length give each angle's own result, also beside a slow angle.
    let near = (core::f64::consts::FRAC_PI_2 * 7.0) as f32;
    for slow in [None, Some(f32::NAN), Some(near), Some(3e7)] {
        for at in 0..9 {
            let mut q: [f32; 9] = core::array::from_fn(|i| xs[100 + 7 * i]);
            if let Some(x) = slow {
                q[at] = x;
            }
            let one = sin_cos_kernel_f32;
            batch_is_one_angle_at_a_time::<f32, 1>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 2>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 3>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 4>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 5>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 7>(&q, sin_cos_array_f32, one);
            batch_is_one_angle_at_a_time::<f32, 9>(&q, sin_cos_array_f32, one);
        }
    }
    // Beyond the fast path: the f64 kernel, rounded.
    for x in [2e6f32, -3.5e7, 1e20, f32::MAX] {
        let (s, c) = sin_cos_array_f32(&[x]);
        let (a, b) = sin_cos_kernel(f64::from(x));
        assert_eq!((s[0], c[0]), (a as f32, b as f32));
    }
    // The fast path takes the f32 nearest to every multiple of π/2 up to 1e5 rad.
    for k in 1..=63662 {
        let x = (k as f64 * core::f64::consts::FRAC_PI_2) as f32;
        for d in -1i32..=1 {
            let x = f32::from_bits((x.to_bits() as i32 + d) as u32);
            assert!(internals::fast_path_f32(f64::from(x)).2, "k = {k}");
        }
    }
}

/// `x` and its `k` neighbours on either side (bit patterns ± 1 … k).
fn with_neighbours(x: f64, k: i64, xs: &mut Vec<f64>) {
    xs.extend((-k..=k).map(|d| f64::from_bits((x.to_bits() as i64 + d) as u64)));
}

/// The arguments of the `f64` square-root tests: the special values,
/// every power of two (the subnormal ones too), perfect squares and the
/// products a·a⁺ of neighbours (√ lies next to the halfway point between
/// a and a⁺: the closest calls of the rounding) and their neighbours, at
/// every scale, random subnormals, and random bit patterns over the whole
/// range (negative numbers and NaNs among them).
fn sqrt_arguments() -> Vec<f64> {
    let mut rng = Rng::new(0x5eed_0f5a_ea2e_0007);
    let mut xs = vec![
        0.0,
        -0.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -f64::NAN,
        f64::from_bits(0x7ff0_0000_0000_0001),
        f64::MAX,
        -f64::MAX,
        f64::MIN_POSITIVE,
        -1.0,
        -5e-324,
    ];
    for k in 0..52 {
        xs.push(f64::from_bits(1 << k));
    }
    for field in 1..2047u64 {
        with_neighbours(f64::from_bits(field << 52), 2, &mut xs);
    }
    for n in 1..=3000u64 {
        with_neighbours((n * n) as f64, 3, &mut xs);
    }
    // A power of two 2^j, j in [−500, 500].
    let scale = |rng: &mut Rng| f64::from_bits((rng.bits() % 1001 + 523) << 52);
    for _ in 0..20_000 {
        let (n, p) = ((rng.bits() >> 38) as f64, scale(&mut rng));
        with_neighbours((n * p) * (n * p), 2, &mut xs);
        let a = (1.0 + rng.unit()) * p;
        with_neighbours(a * f64::from_bits(a.to_bits() + 1), 2, &mut xs);
    }
    for _ in 0..20_000 {
        xs.push(f64::from_bits(rng.bits() & ((1 << 52) - 1)));
    }
    for _ in 0..200_000 {
        xs.push(f64::from_bits(rng.bits()));
    }
    xs
}

/// The same bits, or both NaN (IEEE 754 does not fix a NaN's sign and
/// payload).
fn same<T: Bits>(a: T, b: T) -> bool {
    a.bits() == b.bits() || (a.nan() && b.nan())
}

#[test]
fn sqrt_is_std_sqrt_bit_for_bit() {
    let xs = sqrt_arguments();
    let mut rounded = [0usize; 2];
    for &x in &xs {
        let want = x.sqrt();
        let (portable, here) = (internals::sqrt_portable(x), internals::sqrt(x));
        assert!(same(portable, want), "sqrt_portable({x:e} = {:#x}): {portable:e}, std {want:e}", x.to_bits());
        assert!(same(here, want), "sqrt({x:e} = {:#x}): {here:e}, std {want:e}", x.to_bits());
        // Whether the root was rounded, and whether up (the sign of want² − x, exact).
        let residual = want.mul_add(want, -x);
        if want.is_finite() && residual != 0.0 {
            rounded[usize::from(residual > 0.0)] += 1;
        }
    }
    // Both directions of the rounding were taken, many times.
    assert!(rounded.iter().all(|&n| n > 10_000), "{rounded:?}");
    assert!(internals::sqrt_portable(-0.0).is_sign_negative() && internals::sqrt_portable(f64::NEG_INFINITY).is_nan());
    assert_eq!(internals::sqrt_portable(5e-324), 2f64.powi(-537));
    assert_eq!(internals::sqrt_portable(f64::MAX), 1.3407807929942596e154);
}

#[test]
fn sqrtf_is_std_sqrt_bit_for_bit() {
    let mut rng = Rng::new(0x5eed_0f5a_ea2e_0032);
    let mut xs: Vec<f32> = vec![0.0, -0.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, -f32::NAN, f32::MAX, -1.0];
    xs.push(f32::from_bits(0x7f80_0001));
    let neighbours = |x: f32, xs: &mut Vec<f32>| {
        xs.extend((-2i32..=2).map(|d| f32::from_bits((x.to_bits() as i32 + d) as u32)));
    };
    for k in 0..23 {
        xs.push(f32::from_bits(1 << k));
    }
    for field in 1..255u32 {
        neighbours(f32::from_bits(field << 23), &mut xs);
    }
    for n in 1..=4096u32 {
        neighbours((n * n) as f32, &mut xs);
    }
    for _ in 0..20_000 {
        // 2^j, j in [−60, 60]; a·a⁺ rounded to f32, next to the square of a halfway point.
        let p = f32::from_bits(((rng.bits() % 121) as u32 + 67) << 23);
        let a = (1.0 + rng.unit() as f32) * p;
        neighbours((f64::from(a) * f64::from(f32::from_bits(a.to_bits() + 1))) as f32, &mut xs);
        xs.push(f32::from_bits(rng.bits() as u32 & ((1 << 23) - 1)));
    }
    for _ in 0..200_000 {
        xs.push(f32::from_bits(rng.bits() as u32));
    }
    for x in xs {
        let want = x.sqrt();
        let (portable, here) = (internals::sqrtf_portable(x), internals::sqrtf(x));
        assert!(same(portable, want), "sqrtf_portable({x:e} = {:#x}): {portable:e}, std {want:e}", x.to_bits());
        assert!(same(here, want), "sqrtf({x:e} = {:#x}): {here:e}, std {want:e}", x.to_bits());
    }
}

#[test]
fn kernel_source_is_the_compiled_kernel() {
    assert!(internals::KERNEL_SOURCE.contains("pub fn sin_cos_kernel(x: f64) -> (f64, f64)"));
    assert!(internals::KERNEL_SOURCE.contains("pub fn sin_cos_array<const N: usize>"));
    assert!(internals::KERNEL_SOURCE_F32.starts_with(internals::KERNEL_SOURCE));
    assert!(internals::KERNEL_SOURCE_F32.contains("pub fn sin_cos_array_f32<const N: usize>"));
    assert!(!internals::KERNEL_SOURCE_F32.contains("//!"), "inner docs cannot be include!d into a module");
}

/// Defines the items and keeps their text, for a harness that must run the same code.
macro_rules! with_source {
    ($name:ident: $($item:tt)*) => {
        $($item)*
        const $name: &str = stringify!($($item)*);
    };
}

with_source! { HARNESS_ANGLES:
    /// The angles of `the_avx2_batch_is_the_scalar_kernel_bit_for_bit`, on both sides: random
    /// ones on several scales, near multiples of π/2, and the slow path's other cases.
    fn harness_angles() -> Vec<f64> {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            (x.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut xs = vec![0.0, -0.0, 5e-324, 1e-300, f64::NAN, f64::INFINITY, 1.5e6, 1.6e6, 1e300];
        for scale in [1.0, 4.0, 1e3, 1.5e6] {
            for _ in 0..4000 {
                xs.push(scale * (2.0 * next() - 1.0));
            }
        }
        for k in 1..2000 {
            let x = k as f64 * core::f64::consts::FRAC_PI_2;
            for d in -2i64..=2 {
                xs.push(f64::from_bits((x.to_bits() as i64 + d) as u64));
            }
        }
        xs
    }
}

/// Where the target has AVX2, `sin_cos_array` (and `sin_cos_array_f32`) takes four angles to a register, and where it
/// has FMA the polynomials are fused. CI builds for plain x86-64, so
/// this compiles the kernel's text with `rustc -O` and `-C target-feature=` `+avx2`, `+fma`,
/// `+avx2,+fma` and `+avx512f,+avx512vl,+avx512dq` (those this machine has; `RUNTIME_DISPATCH`
/// off) and checks, in each binary, that the batches, whole and cut at lengths 1 to 17, give
/// the bits of that binary's one-angle kernel; that the `+avx2` binary gives the bits of this
/// (SSE2, unfused) build; and that the AVX-512 binary gives the `+avx2,+fma` binary's. Then
/// once more without target features and with `RUNTIME_DISPATCH` on, where the machine has
/// AVX2 and FMA: the functions pick their AVX-512 copies at run time where it has AVX-512, else
/// their AVX2 and FMA copies, and must give the `+avx2,+fma` binary's bits (and, again,
/// batches the one-angle kernel's); and once more with the AVX-512 check answering no, so
/// that the AVX2 and FMA copies run on an AVX-512 machine too. (That the fused kernel stays
/// within 1 ulp is `tests/tests/generated_fma.rs`.)
#[test]
#[cfg(target_arch = "x86_64")]
fn the_avx2_and_fma_batches_are_the_scalar_kernel_bit_for_bit() {
    let harness = format!(
        "const RUNTIME_DISPATCH: bool = DISPATCH;\n{}\n{HARNESS_ANGLES}\n{}",
        internals::KERNEL_SOURCE_F32,
        r#"
fn main() {
    let xs = harness_angles();
    fn batch<const N: usize>(xs: &[f64]) {
        for w in xs.chunks_exact(N) {
            let (s, c) = sin_cos_array::<N>(w.try_into().unwrap());
            for i in 0..N {
                let (ks, kc) = sin_cos_kernel(w[i]);
                assert!(s[i].to_bits() == ks.to_bits() && c[i].to_bits() == kc.to_bits(), "N {N} at {}", w[i]);
            }
        }
    }
    batch::<1>(&xs);
    batch::<2>(&xs);
    batch::<3>(&xs);
    batch::<4>(&xs);
    batch::<5>(&xs);
    batch::<6>(&xs);
    batch::<7>(&xs);
    batch::<8>(&xs);
    batch::<9>(&xs);
    batch::<11>(&xs);
    batch::<16>(&xs);
    batch::<17>(&xs);
    fn batch_f32<const N: usize>(xs: &[f64]) {
        for w in xs.chunks_exact(N) {
            let w: [f32; N] = core::array::from_fn(|i| w[i] as f32);
            let (s, c) = sin_cos_array_f32::<N>(&w);
            for i in 0..N {
                let (ks, kc) = sin_cos_kernel_f32(w[i]);
                assert!(s[i].to_bits() == ks.to_bits() && c[i].to_bits() == kc.to_bits(), "f32 N {N} at {}", w[i]);
            }
        }
    }
    batch_f32::<1>(&xs);
    batch_f32::<3>(&xs);
    batch_f32::<5>(&xs);
    batch_f32::<8>(&xs);
    batch_f32::<9>(&xs);
    println!(
        "avx2 {} fma {} avx512 {}",
        cfg!(target_feature = "avx2"),
        cfg!(target_feature = "fma"),
        cfg!(all(target_feature = "avx512f", target_feature = "avx512vl", target_feature = "avx512dq"))
    );
    for x in xs {
        let (s, c) = sin_cos_kernel(x);
        let (s32, c32) = sin_cos_kernel_f32(x as f32);
        println!("{:016x} {:016x} {:08x} {:08x}", s.to_bits(), c.to_bits(), s32.to_bits(), c32.to_bits());
    }
}
"#
    );
    let dir = std::env::temp_dir().join(format!("dynagen-kernel-features-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let has = |f: &str| match f {
        "avx2" => std::is_x86_feature_detected!("avx2"),
        "avx512" => {
            std::is_x86_feature_detected!("avx512f")
                && std::is_x86_feature_detected!("avx512vl")
                && std::is_x86_feature_detected!("avx512dq")
        }
        _ => std::is_x86_feature_detected!("fma"),
    };
    let mut ran = 0;
    let mut native_bits: Option<String> = None;
    // (target features, run-time dispatch, whether the code runs with AVX2, with FMA and with
    // AVX-512 (where the build has them: else the copies pick what the machine has), whether
    // the AVX-512 check answers no)
    let builds = [
        ("+avx2", false, true, false, false, false),
        ("+fma", false, false, true, false, false),
        ("+avx2,+fma", false, true, true, false, false),
        ("+avx512f,+avx512vl,+avx512dq", false, true, true, true, false),
        ("", true, true, true, false, false),
        ("", true, true, true, false, true),
    ];
    for (features, dispatch, avx2, fma, avx512, no_avx512) in builds {
        if (avx2 && !has("avx2")) || (fma && !has("fma")) || (avx512 && !has("avx512")) {
            eprintln!("skipped {features:?} (run-time dispatch {dispatch}): this machine lacks its instructions");
            continue;
        }
        let name = match (dispatch, no_avx512) {
            (true, false) => "dispatch".to_string(),
            (true, true) => "dispatch_no_avx512".to_string(),
            _ => features.replace([',', '+'], "_"),
        };
        let src = dir.join(format!("{name}.rs"));
        let check = "fn ask_cpu_for_avx512() -> bool {\n";
        assert!(harness.contains(check));
        let text = match no_avx512 {
            true => harness.replace(check, &format!("{check}    if true {{\n        return false;\n    }}\n")),
            false => harness.clone(),
        };
        std::fs::write(&src, text.replace("DISPATCH;", &format!("{dispatch};"))).unwrap();
        let exe = dir.join(&name);
        let built = std::process::Command::new(&rustc)
            .args(["--edition", "2021", "-O", "-C", &format!("target-feature={features}"), "-o"])
            .arg(&exe)
            .arg(&src)
            .output()
            .expect("running rustc");
        assert!(built.status.success(), "{features}: {}", String::from_utf8_lossy(&built.stderr));
        let out = std::process::Command::new(&exe).output().unwrap();
        assert!(out.status.success(), "{name}: {}", String::from_utf8_lossy(&out.stderr));
        let out = String::from_utf8(out.stdout).unwrap();
        let (first, bits) = out.split_once('\n').unwrap();
        let built_for = format!("avx2 {} fma {} avx512 {}", avx2 && !dispatch, fma && !dispatch, avx512);
        assert_eq!(first, built_for, "{name}: not built as asked");
        if !fma {
            for (x, line) in harness_angles().into_iter().zip(bits.lines()) {
                let ((s, c), (s32, c32)) = (sin_cos_kernel(x), sin_cos_kernel_f32(x as f32));
                let want =
                    format!("{:016x} {:016x} {:08x} {:08x}", s.to_bits(), c.to_bits(), s32.to_bits(), c32.to_bits());
                assert_eq!(line, want, "{features} at x = {x:e}");
            }
        }
        if avx2 && fma && !dispatch && !avx512 {
            native_bits = Some(bits.to_string());
        }
        if avx512 {
            let native = native_bits.as_deref().expect("the +avx2,+fma binary ran");
            assert!(bits == native, "the AVX-512 build differs from the +avx2,+fma build");
        }
        if dispatch {
            let native = native_bits.as_deref().expect("the +avx2,+fma binary ran");
            assert!(bits == native, "the run-time copies ({name}) differ from the +avx2,+fma build");
            assert!(bits.lines().count() == harness_angles().len());
            let baseline = harness_angles().into_iter().map(|x| {
                let ((s, c), (s32, c32)) = (sin_cos_kernel(x), sin_cos_kernel_f32(x as f32));
                format!("{:016x} {:016x} {:08x} {:08x}", s.to_bits(), c.to_bits(), s32.to_bits(), c32.to_bits())
            });
            let differ = bits.lines().zip(baseline).filter(|(a, b)| a != b).count();
            assert!(differ > 0, "the run-time copies give this (unfused) build's bits: not fused");
            eprintln!("run-time copies ({name}): {differ} of {} angles differ from unfused", bits.lines().count());
        }
        ran += 1;
    }
    eprintln!("{ran} of {} builds checked", builds.len());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The branch loops' moves in and out of vector lanes: each row's entries
/// land at `i·L + l`, also for the last register of an odd number of rows,
/// half of whose lanes are copies.
#[test]
fn branch_rows_go_through_lanes_to_their_places() {
    let rows: [[f64; 5]; 3] = core::array::from_fn(|l| core::array::from_fn(|i| (10 * l + i) as f64 + 0.5));
    let out: [f64; 15] = internals::branch_rows_in_pairs(&rows);
    for (l, row) in rows.iter().enumerate() {
        for (i, &v) in row.iter().enumerate() {
            assert_eq!(out[i * 3 + l], v, "row {l}, entry {i}");
        }
    }
    let rows: [[f64; 2]; 4] = core::array::from_fn(|l| [l as f64, -(l as f64)]);
    let out: [f64; 8] = internals::branch_rows_in_pairs(&rows);
    assert_eq!(out, [0.0, 1.0, 2.0, 3.0, 0.0, -1.0, -2.0, -3.0]);
}

/// The branch bodies' square root in lanes gives `f64::sqrt`'s bits in
/// every lane: zeros, subnormals, ordinary and huge numbers, infinity, and
/// NaN for a negative number or a NaN.
#[test]
fn lanes_take_square_roots_bit_for_bit() {
    let mut values = vec![0.0, -0.0, f64::MIN_POSITIVE, 5e-324, 1.0, 2.0, 0.25, 1e300, f64::MAX, f64::INFINITY];
    let mut x = 0x1234_5678_9abc_def1u64;
    for _ in 0..2000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        // positive finite numbers of every exponent
        values.push(f64::from_bits(x >> 1).min(f64::MAX));
    }
    let same = |got: f64, v: f64| {
        let want = v.sqrt();
        assert!(
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
            "sqrt({v:e}) = {got:e}, not {want:e}"
        );
    };
    for pair in values.chunks(2).chain([[-1.0, f64::NAN].as_slice()]) {
        let p = [pair[0], pair[pair.len() - 1]];
        let got = internals::sqrt_pair(p);
        same(got[0], p[0]);
        same(got[1], p[1]);
    }
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    for quad in values.chunks_exact(4) {
        let q = [quad[0], quad[1], quad[2], quad[3]];
        for (got, v) in internals::sqrt_quad(q).into_iter().zip(q) {
            same(got, v);
        }
    }
}
