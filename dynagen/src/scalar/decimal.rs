//! Decimal text to double-double: a number as a robot file writes it, to
//! about 32 digits.
//!
//! A robot file's numbers are exact decimals; `0.1` in a URDF is one tenth,
//! and its `f64` rounding is a change of the robot by up to half an ulp.
//! The precise scalars compute with the file's values
//! ([`Scalar::FILE_CONSTANTS`](super::Scalar::FILE_CONSTANTS)), read here:
//! the significant digits (the first 40; the rest change the value by less
//! than 1e-39 of it) are gathered in double-double, 15 at a time (each
//! group exact in `f64`), and scaled by the power of ten, itself formed in
//! double-double. Each step rounds by at most about 2⁻¹⁰⁵ of its result, so
//! the value is within 1e-31 of the decimal's, relatively.

use super::DoubleDouble;

/// Significant digits kept: beyond these, a digit changes the value by less
/// than 1e-39 of it, far below double-double's precision.
const KEPT_DIGITS: usize = 40;

/// 10ᵏ for k = 0..=22, each exact in `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// 10ᵉ in double-double for 0 ≤ e ≤ 330 (by squaring from 10²², exact
/// below it).
fn pow10(e: u32) -> DoubleDouble {
    if e <= 22 {
        return DoubleDouble::from(POW10[e as usize]);
    }
    let mut result = DoubleDouble::from(POW10[(e % 22) as usize]);
    let mut base = DoubleDouble::from(1e22);
    let mut k = e / 22;
    while k > 0 {
        if k & 1 == 1 {
            result *= base;
        }
        k >>= 1;
        if k > 0 {
            base = base * base;
        }
    }
    result
}

impl DoubleDouble {
    /// The value of a decimal number written as text, to double-double
    /// precision (within 1e-31 of it, relatively): an optional sign, digits
    /// with an optional decimal point, an optional exponent (`e` or `E`,
    /// optionally signed). `None` for anything else (words such as `inf` or
    /// `nan` included), and for a value that is not zero but lies outside
    /// about 1e-290..1e308, where double-double no longer carries its
    /// digits or `f64` overflows.
    ///
    /// ```
    /// use dynagen::DoubleDouble;
    /// let tenth = DoubleDouble::from_decimal("0.1").unwrap();
    /// assert_eq!(tenth.hi, 0.1); // the f64 nearest one tenth
    /// assert!(tenth.lo != 0.0); // and what that f64 is off by
    /// assert!(((tenth * DoubleDouble::from(10.0)) - DoubleDouble::ONE).to_f64().abs() < 1e-31);
    /// ```
    pub fn from_decimal(text: &str) -> Option<DoubleDouble> {
        let bytes = text.as_bytes();
        let (negative, mut at) = match bytes.first() {
            Some(b'-') => (true, 1),
            Some(b'+') => (false, 1),
            _ => (false, 0),
        };
        // The significant digits (leading zeros skipped), and the exponent of
        // ten of the last one kept.
        let mut digits: Vec<u8> = Vec::with_capacity(KEPT_DIGITS);
        let mut exponent: i64 = 0;
        let (mut seen_digit, mut seen_point) = (false, false);
        while let Some(&b) = bytes.get(at) {
            match b {
                b'0'..=b'9' => {
                    seen_digit = true;
                    if digits.is_empty() && b == b'0' {
                        // a leading zero: after the point it moves the scale
                        if seen_point {
                            exponent -= 1;
                        }
                    } else if digits.len() < KEPT_DIGITS {
                        digits.push(b - b'0');
                        if seen_point {
                            exponent -= 1;
                        }
                    } else if !seen_point {
                        // a dropped digit before the point still scales
                        exponent += 1;
                    }
                }
                b'.' if !seen_point => seen_point = true,
                _ => break,
            }
            at += 1;
        }
        if !seen_digit {
            return None;
        }
        if let Some(b'e' | b'E') = bytes.get(at) {
            let rest = &text[at + 1..];
            let digits_only = rest.strip_prefix(['+', '-']).unwrap_or(rest);
            if digits_only.is_empty() || !digits_only.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            // An exponent beyond ±10⁶ makes any value of 40 digits 0 or infinite.
            let e: i64 = if digits_only.len() > 7 {
                if rest.starts_with('-') {
                    -10_000_000
                } else {
                    10_000_000
                }
            } else {
                rest.parse().ok()?
            };
            exponent += e;
        } else if at != bytes.len() {
            return None;
        }
        if digits.is_empty() {
            return Some(DoubleDouble::ZERO);
        }
        // The digits as an integer, 15 at a time.
        let mut value = DoubleDouble::ZERO;
        for group in digits.chunks(15) {
            let chunk = group.iter().fold(0u64, |a, &d| 10 * a + u64::from(d));
            value = value.mul_f64(POW10[group.len()]) + DoubleDouble::from(chunk as f64);
        }
        // The value's order of magnitude: 10^(magnitude - 1) ≤ |x| < 10^magnitude.
        let magnitude = exponent + digits.len() as i64;
        if !(-289..=309).contains(&magnitude) {
            return None;
        }
        if exponent >= 0 {
            value *= pow10(exponent as u32);
        } else {
            // Divided in two steps when 10^|e| alone would overflow.
            let mut e = -exponent;
            if e > 300 {
                value = value / pow10(300);
                e -= 300;
            }
            value = value / pow10(e as u32);
        }
        if !value.is_finite() {
            return None;
        }
        Some(if negative { -value } else { value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `from_decimal(text)` against (hi, lo), the double-double nearest the
    /// decimal (mpmath at 60 digits), to 1e-31 relative.
    fn check(text: &str, hi: f64, lo: f64) {
        let x = DoubleDouble::from_decimal(text).unwrap_or_else(|| panic!("{text} did not parse"));
        let want = DoubleDouble::new(hi, lo);
        let err = (x - want).to_f64().abs() / hi.abs().max(f64::MIN_POSITIVE);
        assert!(err < 1e-31, "{text}: {x:?} against {want:?}, relative error {err:e}");
        // and its leading part is the f64 that Rust's parser gives
        assert_eq!(x.hi, text.parse::<f64>().unwrap(), "{text}");
    }

    #[test]
    #[allow(clippy::approx_constant)] // the literals are data from mpmath, not constants
    fn decimals_to_double_double_precision() {
        // (text, hi, lo): mpmath, 60 digits, the decimal split as hi + lo.
        check("0.1", 0.1, -5.551115123125783e-18);
        check("-0.1", -0.1, 5.551115123125783e-18);
        check("1.5707963267948966", 1.5707963267948966, 4.2001018265727904e-17);
        check("0.089159", 0.089159, -2.1396218130576018e-18);
        check("3.875e-03", 0.003875, 2.7755575615628914e-20);
        check("-5.317e-02", -0.05317, 1.9828583219805297e-18);
        check("9.81", 9.81, -4.973799150320702e-16);
        check("123456789012345678901234567890", 1.2345678901234568e29, 1023514970834.0);
        check("1e-7", 1e-7, 4.525188817411374e-24);
        check("2.5e300", 2.5e300, -1.3126190063801106e284);
        check("6.02214076e23", 6.02214076e23, 12976128.0);
        check(".5", 0.5, 0.0);
        check("7.", 7.0, 0.0);
        check("+1E2", 100.0, 0.0);
        check("0.000001234", 1.234e-6, 4.10177534299061e-23);
        check("0.3333333333333333333333333333333333333333333333", 0.3333333333333333, 1.850371707708594e-17);
        check("1e-280", 1e-280, 4.263561183052483e-297);
        check("1.7976931348623157e308", 1.7976931348623157e308, -8.145274237317043e290);
    }

    #[test]
    fn zeros_and_refusals() {
        for zero in ["0", "-0.0", "0e5", "000.000", "0.0e-400"] {
            assert_eq!(DoubleDouble::from_decimal(zero).map(|x| x.to_f64()), Some(0.0), "{zero}");
        }
        for bad in ["", "-", ".", "e5", "1e", "1e+", "1.2.3", "1x", "nan", "inf", "1 2", " 1", "--1", "1e999", "1e-300"]
        {
            assert!(DoubleDouble::from_decimal(bad).is_none(), "{bad:?} parsed");
        }
    }
}
