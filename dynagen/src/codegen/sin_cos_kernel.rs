// The sine and cosine of one angle in straight-line f64 arithmetic: no
// branch, no table, no call, nothing from std or any crate, so that a loop
// over the joints of a robot vectorises.
//
// 1. Range reduction (Cody and Waite): x = k·π/2 + r with k the integer
//    nearest x·2/π (rounded by adding and subtracting 1.5·2⁵²) and π/2 split
//    into P1 + P2 + P3 (33 significant bits each) + P4 (53 bits), so that
//    k·P1, k·P2 and k·P3 are exact for |k| < 2²⁰ and x − k·P1 is exact. r is
//    kept as a double-double rh + rl through error-free sums: even when x is
//    the double nearest a multiple of π/2 and r cancels to ~1e-18, r keeps
//    about 70 correct bits. Valid for |x| ≤ 1.6e6 rad; beyond, the results
//    lose accuracy (they stay in [−1, 1]). NaN and ±∞ give NaN.
// 2. On |r| ≤ π/4: sin r = r + r³·S(r²), cos r = 1 − r²/2 + r⁴·C(r²) with
//    the Taylor coefficients 1/n! (to r¹⁷ and r¹⁸: truncation below 1e-19).
//    The leading terms (r, and 1 − r²/2 with r² as an exact double-double)
//    are added last, so the result carries one rounding plus a small part
//    of one: within 1 ulp of the exact value (the tests measure it).
// 3. The quadrant k mod 4 picks (±sin r, ±cos r) by bit masks, not branches.
/// The sine and cosine of `x` (one angle), accurate to 1 ulp for
/// |x| ≤ 1.6e6 rad; the scalar core of `sin_cos_all`.
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::unreadable_literal, clippy::approx_constant)]
pub fn sin_cos_kernel(x: f64) -> (f64, f64) {
    const FRAC_2_PI: f64 = 0.6366197723675814;
    const ROUND: f64 = 6755399441055744.0; // 1.5·2⁵²: x + ROUND − ROUND rounds x to an integer
    const P1: f64 = 1.5707963267341256;
    const P2: f64 = 6.077100506303966e-11;
    const P3: f64 = 2.0222662487111665e-21;
    const P4: f64 = 8.4784276603689e-32;
    const SPLIT: f64 = 134217729.0; // 2²⁷ + 1: Dekker's split of a double into two halves
    let t = x * FRAC_2_PI + ROUND;
    let quadrant = t.to_bits() & 3;
    let k = t - ROUND;
    // r = x − k·π/2 as the double-double rh + rl.
    let t0 = x - k * P1;
    let a2 = k * P2;
    let a3 = k * P3;
    let h1 = t0 - a2;
    let b1 = h1 - t0;
    let e1 = (t0 - (h1 - b1)) + (-a2 - b1);
    let h2 = h1 - a3;
    let b2 = h2 - h1;
    let e2 = (h1 - (h2 - b2)) + (-a3 - b2);
    let low = (e1 + e2) - k * P4;
    let rh = h2 + low;
    let rl = low - (rh - h2);
    // z = rh² exactly, as zh + zl.
    let p = rh * SPLIT;
    let hi = p - (p - rh);
    let lo = rh - hi;
    let zh = rh * rh;
    let zl = ((hi * hi - zh) + 2.0 * hi * lo) + lo * lo;
    let z = zh;
    // sin(rh + rl) = rh + rh·z·S(z) + rl·(1 − z/2) + …
    let ps = -0.16666666666666666
        + z * (0.008333333333333333
            + z * (-0.0001984126984126984
                + z * (2.7557319223985893e-06
                    + z * (-2.505210838544172e-08
                        + z * (1.6059043836821613e-10 + z * (-7.647163731819816e-13 + z * 2.8114572543455206e-15))))));
    let sin_r = rh + (rh * z * ps + rl * (1.0 - 0.5 * z));
    // cos(rh + rl) = (1 − z/2) + z²·C(z) − rh·rl + …, 1 − z/2 with its rounding error kept.
    let pc = 0.041666666666666664
        + z * (-0.001388888888888889
            + z * (2.48015873015873e-05
                + z * (-2.755731922398589e-07
                    + z * (2.08767569878681e-09
                        + z * (-1.1470745597729725e-11 + z * (4.779477332387385e-14 + z * -1.5619206968586225e-16))))));
    let hz = 0.5 * zh;
    let w = 1.0 - hz;
    let w_err = (1.0 - w) - hz;
    let cos_r = w + ((w_err - 0.5 * zl) + (z * z * pc - rh * rl));
    // Quadrant: odd swaps sine and cosine; the sign bits follow k mod 4.
    let swap = 0u64.wrapping_sub(quadrant & 1);
    let (sb, cb) = (sin_r.to_bits(), cos_r.to_bits());
    let sin_bits = (sb & !swap) | (cb & swap);
    let cos_bits = (cb & !swap) | (sb & swap);
    let sin_sign = ((quadrant >> 1) & 1) << 63;
    let cos_sign = (((quadrant + 1) >> 1) & 1) << 63;
    (f64::from_bits(sin_bits ^ sin_sign), f64::from_bits(cos_bits ^ cos_sign))
}
