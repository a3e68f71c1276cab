//! The error measures of the tests, in one file: dynagen's integration
//! tests take it through `support`, and `dynagen-tests` (the cross-crate
//! tests, the report) includes it by path.
//!
//! A bound on every entry, |gotᵢ − wantᵢ| ≤ tol · max(max |want|, floor),
//! is written with `approx`: `abs_diff_eq!(got, want, epsilon = tol *
//! scale(want, floor))`. Two things `approx` does not say, which stay here:
//! a bound relative to a vector's Euclidean norm, ‖got − want‖ ≤ tol ·
//! ‖want‖ ([`norm_rel_err`]; `approx` compares entry by entry, and an
//! entry-wise ε = tol · ‖want‖ would let the error's norm grow √n times
//! larger), and an error as a number, for tests that report or compare
//! errors ([`rel_err`]).

/// max(max |want|, `floor`): the scale an entry-wise error bound is
/// relative to (`floor` keeps it away from zero).
pub fn scale(want: &[f64], floor: f64) -> f64 {
    want.iter().fold(floor, |m, x| m.max(x.abs()))
}

/// max |got − want| / [`scale`]`(want, floor)`: the largest entry's error
/// relative to the reference's scale.
pub fn rel_err(got: &[f64], want: &[f64], floor: f64) -> f64 {
    assert_eq!(got.len(), want.len());
    got.iter().zip(want).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale(want, floor)
}

/// ‖got − want‖ / max(‖want‖, `floor`) in Euclidean norms: the error
/// relative to the reference's size (`floor` bounds the divisor away from
/// zero: a tiny floor compares an all-zero `want` absolutely).
pub fn norm_rel_err(got: &[f64], want: &[f64], floor: f64) -> f64 {
    assert_eq!(got.len(), want.len());
    let norm = want.iter().map(|x| x * x).sum::<f64>().sqrt();
    let diff = got.iter().zip(want).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
    diff / norm.max(floor)
}
