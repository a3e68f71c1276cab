//! The batched sine and cosine emitted into every generated module.
//!
//! `core` has no `sin` or `cos` on stable Rust, so a `#![no_std]` module
//! either needs the `libm` crate, takes the sines and cosines as inputs, or
//! brings its own: [`sin_cos_kernel`] is that one, written once in
//! `sin_cos_kernel.rs` and copied verbatim into each module (it is compiled
//! here too, for the tests and the benchmarks). Each module wraps it as
//!
//! ```text
//! pub fn sin_cos_all(q: &[f64; DOF]) -> ([f64; DOF], [f64; DOF])
//! ```
//!
//! a loop over the joints with a branch-free body, which the compiler
//! vectorises. Accuracy: within 1 ulp of the exact sine and cosine for
//! |q| ≤ 1.6e6 rad (measured by the tests against [`crate::DoubleDouble`],
//! including the doubles nearest to multiples of π/2, where the reduced
//! angle cancels). For `f32` modules, `sin_cos_all` converts each angle to
//! `f64`, calls the kernel and rounds the results to `f32` (within 1 ulp of
//! `f32` too).

use super::ScalarType;
use proc_macro2::TokenStream;
use quote::quote;

include!("sin_cos_kernel.rs");

/// The kernel's source text, as copied into generated modules.
pub(crate) const KERNEL_SOURCE: &str = include_str!("sin_cos_kernel.rs");

/// The sines and cosines of `q`, entry by entry, by [`sin_cos_kernel`]:
/// what a generated module's `sin_cos_all` computes, for any length.
#[inline]
pub fn sin_cos_batch<const N: usize>(q: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut s = [0.0; N];
    let mut c = [0.0; N];
    for ((x, s), c) in q.iter().zip(&mut s).zip(&mut c) {
        (*s, *c) = sin_cos_kernel(*x);
    }
    (s, c)
}

/// The `sin_cos_all` function of a module of scalar `scalar` (the kernel
/// itself is appended to the file as text, see [`KERNEL_SOURCE`]).
pub(crate) fn sin_cos_all_item(scalar: ScalarType) -> TokenStream {
    let (ty, call) = match scalar {
        ScalarType::F64 => (quote!(f64), quote!((*s, *c) = sin_cos_kernel(*x);)),
        ScalarType::F32 => (
            quote!(f32),
            quote! {
                let (a, b) = sin_cos_kernel(f64::from(*x));
                (*s, *c) = (a as f32, b as f32);
            },
        ),
    };
    let doc = match scalar {
        ScalarType::F64 => {
            " The sines and cosines of `q`, joint by joint: within 1 ulp for |q| ≤ 1.6e6 rad, no std, vectorised."
        }
        ScalarType::F32 => {
            " The sines and cosines of `q`, joint by joint, computed in `f64` by `sin_cos_kernel` and rounded to `f32`."
        }
    };
    quote! {
        #[doc = #doc]
        #[inline]
        pub fn sin_cos_all(q: &[#ty; DOF]) -> ([#ty; DOF], [#ty; DOF]) {
            let mut s = [0.0; DOF];
            let mut c = [0.0; DOF];
            for ((x, s), c) in q.iter().zip(&mut s).zip(&mut c) {
                #call
            }
            (s, c)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DoubleDouble, Scalar};

    /// xorshift64*, uniform in [0, 1).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

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

    /// The test angles: random ones on several scales, the doubles nearest
    /// (and next to) k·π/2 for every k up to 2000 and random k up to 1e5 rad.
    fn angles() -> Vec<f64> {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut xs = vec![0.0, 1e-300, 1e-20, 1e-9, 0.5, 1.0, core::f64::consts::FRAC_PI_4, 1e5, -1e5, 1.6e6];
        for scale in [1.0, 4.0, 100.0, 1e4, 1e5, 1.6e6] {
            for _ in 0..3000 {
                xs.push(scale * (2.0 * rng.next() - 1.0));
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
            near((rng.next() * 1e5 / core::f64::consts::FRAC_PI_2).round(), &mut xs);
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
    fn std_sin_cos_within_one_ulp_on_the_same_angles() {
        // The same bound for the platform's libm: a check of the test itself.
        let (s, c, x) = worst(f64::sin_cos);
        eprintln!("f64::sin_cos: max error sin {s:.3} ulp, cos {c:.3} ulp (worst at x = {x:e})");
        assert!(s <= 1.0 && c <= 1.0, "sin {s} ulp, cos {c} ulp at x = {x:e}");
    }

    #[test]
    fn batch_is_the_kernel_entry_by_entry_and_nan_stays_nan() {
        let q = [0.3, -2.0, 1e5, f64::NAN, f64::INFINITY, 0.0];
        let (s, c) = sin_cos_batch(&q);
        for i in 0..3 {
            assert_eq!((s[i], c[i]), sin_cos_kernel(q[i]));
            assert!((s[i] - q[i].sin()).abs() < 1e-15 && (c[i] - q[i].cos()).abs() < 1e-15);
        }
        assert!(s[3].is_nan() && c[3].is_nan() && s[4].is_nan() && c[4].is_nan());
        assert_eq!((s[5], c[5]), (0.0, 1.0));
    }

    #[test]
    fn kernel_source_is_the_compiled_kernel() {
        assert!(KERNEL_SOURCE.contains("pub fn sin_cos_kernel(x: f64) -> (f64, f64)"));
        assert!(!KERNEL_SOURCE.contains("//!"), "inner docs cannot be include!d into a module");
    }
}
