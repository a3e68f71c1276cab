//! The batched sine and cosine emitted into every generated module.
//!
//! `core` has no `sin` or `cos` on stable Rust, so a `#![no_std]` module
//! either needs the `libm` crate, takes the sines and cosines as inputs, or
//! brings its own: [`sin_cos_array`] is that one, written once in
//! `kernel.rs` (and, for `f32` modules, `kernel_f32.rs`) and
//! copied verbatim into each module (it is compiled here too, for the tests,
//! `dynagen/tests/sin_cos_kernel.rs`, and the benchmarks). Each module has
//!
//! ```text
//! pub fn sin_cos_all(q: &[f64; DOF]) -> ([f64; DOF], [f64; DOF])
//! ```
//!
//! and its `NAME(q, …)` of [`Trig::Batched`](super::Trig::Batched) call
//! `sin_cos_array` on the angles that `NAME_sc` reads, no others. Two or four
//! angles at a time go through the same branch-free code: on x86-64 written
//! out in SSE2 intrinsics (part of the default target; LLVM's own
//! vectoriser took the scalar code for some lengths only), four at a time
//! in AVX2 where the target has it, elsewhere the scalar code; the
//! polynomials use fused multiply-adds where the target has them (see
//! [`CodegenOptions::fma`](super::CodegenOptions::fma)). With run-time
//! dispatch ([`CodegenOptions::runtime_dispatch`](super::CodegenOptions::runtime_dispatch)),
//! an x86-64 build without AVX2 and FMA also has a copy of each public
//! function compiled for them, run where the processor has both: four
//! angles at a time, fused, the bits of a build with those features; and
//! one for AVX-512, the same bits with more registers. A rare slow path (angles within ~1e-17·|q| of a multiple of
//! π/2, |q| > 1.5e6 rad, NaN, ±∞) redoes the batch one angle at a time with
//! an exact (Payne–Hanek) reduction. Accuracy: within
//! 1 ulp of the exact sine and cosine for every finite angle (measured by
//! the tests against [`crate::DoubleDouble`] and against 60-digit values,
//! including the doubles nearest to multiples of π/2, where the reduced
//! angle cancels). `f32` modules run [`sin_cos_array_f32`]: the same steps in
//! `f64` with shorter polynomials and a two-part π/2, rounded to `f32`
//! (within 1 ulp of `f32`).
//!
//! The same text gives each module a private `sqrt` (`sqrtf` in `f32`
//! modules), which `core` lacks too: correctly rounded, so bit for bit std's
//! `f64::sqrt`. It is the square-root instruction on x86-64 (SSE2) and
//! aarch64 (NEON), and elsewhere `sqrt_portable`, exact integer arithmetic
//! (compiled on every target, and tested here against `f64::sqrt` bit for
//! bit). The bodies of [`Trig::Batched`](super::Trig::Batched) and
//! [`Trig::Inputs`](super::Trig::Inputs) modules call it where a scene needs
//! a square root (smoothed Coulomb friction).

use super::ScalarType;
use proc_macro2::TokenStream;
use quote::quote;

/// dynagen's own copy of the kernel is the baseline on every machine (a
/// module's `CodegenOptions::runtime_dispatch`, off): what the tests compare
/// the modules' run-time AVX2 and FMA copies against. (Unread in builds
/// that have AVX2 and FMA already, which compile no dispatch.)
#[allow(dead_code)]
const RUNTIME_DISPATCH: bool = false;

include!("kernel.rs");
include!("kernel_f32.rs");

/// The kernel's source text, as copied into generated `f64` modules.
pub(crate) const KERNEL_SOURCE: &str = include_str!("kernel.rs");

/// The kernel's source text for generated `f32` modules.
pub(crate) const KERNEL_SOURCE_F32: &str = concat!(include_str!("kernel.rs"), include_str!("kernel_f32.rs"));

/// The kernel text a module of scalar `scalar` carries, after the constant
/// `RUNTIME_DISPATCH` ([`CodegenOptions::runtime_dispatch`](super::CodegenOptions::runtime_dispatch)).
pub(crate) fn kernel_source(scalar: ScalarType, runtime_dispatch: bool) -> String {
    let kernel = match scalar {
        ScalarType::F64 => KERNEL_SOURCE,
        ScalarType::F32 => KERNEL_SOURCE_F32,
    };
    format!(
        "/// Whether `sin_cos_array` and the other public functions of the kernel below pick, on x86-64\n\
         /// builds without the `avx2` and `fma` target features, their copies compiled for AVX-512 or\n\
         /// for AVX2 and FMA where the processor has them (`CodegenOptions::runtime_dispatch`).\n\
         #[allow(dead_code)]\n\
         const RUNTIME_DISPATCH: bool = {runtime_dispatch};\n\n{kernel}"
    )
}

/// The name of the batch function of a module of scalar `scalar`.
pub(crate) fn batch_function(scalar: ScalarType) -> TokenStream {
    match scalar {
        ScalarType::F64 => quote!(sin_cos_array),
        ScalarType::F32 => quote!(sin_cos_array_f32),
    }
}

/// The sines and cosines of `q`, entry by entry: what a generated module's
/// `sin_cos_all` computes, for any length (the same as [`sin_cos_array`]).
#[inline]
pub fn sin_cos_batch<const N: usize>(q: &[f64; N]) -> ([f64; N], [f64; N]) {
    sin_cos_array(q)
}

/// The `sin_cos_all` function of a module of scalar `scalar` (the kernel
/// itself is appended to the file as text, see [`kernel_source`]).
pub(crate) fn sin_cos_all_item(scalar: ScalarType) -> TokenStream {
    let ty = match scalar {
        ScalarType::F64 => quote!(f64),
        ScalarType::F32 => quote!(f32),
    };
    let batch = batch_function(scalar);
    let doc = match scalar {
        ScalarType::F64 => {
            " The sines and cosines of `q`, joint by joint: within 1 ulp for every finite angle, no std, two at a time (four where the target, or with run-time dispatch the processor, has AVX2)."
        }
        ScalarType::F32 => {
            " The sines and cosines of `q`, joint by joint: within 1 ulp of `f32` for every finite angle (computed in `f64`), no std, two at a time."
        }
    };
    quote! {
        #[doc = #doc]
        #[inline]
        pub fn sin_cos_all(q: &[#ty; DOF]) -> ([#ty; DOF], [#ty; DOF]) {
            #batch(q)
        }
    }
}

/// The kernel's private parts, for its tests (`dynagen/tests/sin_cos_kernel.rs`):
/// not part of dynagen's API. The kernel text itself keeps them private, as
/// it is copied verbatim into every generated module.
#[doc(hidden)]
pub mod kernel_internals {
    use super::{Baseline, Lanes, ToLanes};

    /// The kernel's source text, as copied into generated `f64` modules.
    pub const KERNEL_SOURCE: &str = super::KERNEL_SOURCE;
    /// The kernel's source text for generated `f32` modules.
    pub const KERNEL_SOURCE_F32: &str = super::KERNEL_SOURCE_F32;

    /// The module's `sqrt`: the instruction where the target has one, else [`sqrt_portable`].
    pub fn sqrt(x: f64) -> f64 {
        super::sqrt(x)
    }
    /// The module's square root in integer arithmetic, for targets without the instruction.
    pub fn sqrt_portable(x: f64) -> f64 {
        super::sqrt_portable(x)
    }
    /// The `f32` modules' `sqrtf`.
    pub fn sqrtf(x: f32) -> f32 {
        super::sqrtf(x)
    }
    /// The `f32` modules' square root in integer arithmetic.
    pub fn sqrtf_portable(x: f32) -> f32 {
        super::sqrtf_portable(x)
    }

    /// The fast path on one angle: its sine, cosine, and whether the fast
    /// path holds (false: the batch is redone on the slow path).
    pub fn fast_path(x: f64) -> (f64, f64, bool) {
        super::sin_cos_lanes::<Baseline, f64, 1>([x])[0]
    }
    /// The `f32` modules' fast path on one angle (computed in `f64`).
    pub fn fast_path_f32(x: f64) -> (f64, f64, bool) {
        super::sin_cos_lanes_f32::<Baseline, f64, 1>([x])[0]
    }

    /// The fast path on three registers of two angles, as the batches run
    /// it: each lane's sine and cosine, and whether the register's angles all
    /// hold.
    pub fn fast_path_pairs(x: [[f64; 2]; 3]) -> [([f64; 2], [f64; 2], bool); 3] {
        registers(x.map(ToLanes::to_lanes))
    }
    /// [`fast_path_pairs`] with four angles to a register (AVX2).
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    pub fn fast_path_quads(x: [[f64; 4]; 3]) -> [([f64; 4], [f64; 4], bool); 3] {
        registers(x.map(ToLanes::to_lanes))
    }

    /// `L` branches' rows of `A` inputs into registers of two lanes
    /// (`branch_lanes`) and out again to their results (`branch_rows`), two
    /// branches at a time as a branch loop moves them: entry i of row l at
    /// `i·L + l` of the `N = A·L` results.
    pub fn branch_rows_in_pairs<const A: usize, const L: usize, const N: usize>(rows: &[[f64; A]; L]) -> [f64; N] {
        let mut out = [0.0; N];
        let mut l = 0;
        while l < L {
            let v = super::branch_lanes::<2, A, L>(rows, l);
            super::branch_rows::<_, 2, A, N>(&v, &mut out, l);
            l += 2;
        }
        out
    }

    /// `Lanes::sqrt` on a register of two lanes (SSE2 on x86-64, an array
    /// elsewhere), as a branch body with Coulomb friction runs it.
    pub fn sqrt_pair(x: [f64; 2]) -> [f64; 2] {
        let v = Lanes::sqrt(x.to_lanes());
        [v.lane(0), v.lane(1)]
    }
    /// [`sqrt_pair`] with four lanes to a register (AVX2).
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    pub fn sqrt_quad(x: [f64; 4]) -> [f64; 4] {
        let v = Lanes::sqrt(x.to_lanes());
        core::array::from_fn(|l| v.lane(l))
    }

    fn registers<V: Lanes, const W: usize>(x: [V; 3]) -> [([f64; W], [f64; W], bool); 3] {
        super::sin_cos_lanes::<Baseline, V, 3>(x)
            .map(|(s, c, holds)| (core::array::from_fn(|l| s.lane(l)), core::array::from_fn(|l| c.lane(l)), holds))
    }
}
