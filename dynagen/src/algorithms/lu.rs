//! A dense LU factorisation with partial pivoting, and its solve: the
//! Newton matrix of the implicit integrator
//! ([`implicit_euler_with`](super::integrators::implicit_euler_with)).
//! Pivots are chosen on the values' magnitudes: a numeric routine for
//! `f64`, `f32` or a precise scalar, never traced.

use crate::Scalar;

/// |x| of a numeric scalar as `f64` (∞ for one without a value).
pub(crate) fn magnitude<S: Scalar>(x: S) -> f64 {
    x.to_f64().map_or(f64::INFINITY, f64::abs)
}

/// LU factorisation with partial pivoting, in place (pivots chosen on the
/// values' magnitudes: a numeric routine, never traced).
pub(crate) fn factorise<S: Scalar>(a: &mut [S], perm: &mut [usize], n: usize) {
    for (i, p) in perm.iter_mut().enumerate() {
        *p = i;
    }
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| magnitude(a[i * n + k]).total_cmp(&magnitude(a[j * n + k]))).unwrap_or(k);
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
            perm.swap(k, p);
        }
        let inv = S::one() / a[k * n + k];
        for i in k + 1..n {
            let l = a[i * n + k] * inv;
            a[i * n + k] = l;
            for c in k + 1..n {
                let u = a[k * n + c];
                a[i * n + c] -= l * u;
            }
        }
    }
}

/// Solves LU·x = P·b in place of `b` (with `tmp` as scratch).
pub(crate) fn solve<S: Scalar>(a: &[S], perm: &[usize], n: usize, b: &mut [S], tmp: &mut [S]) {
    for i in 0..n {
        tmp[i] = b[perm[i]];
    }
    for i in 0..n {
        for k in 0..i {
            let l = a[i * n + k];
            tmp[i] -= l * tmp[k];
        }
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            let u = a[i * n + k];
            tmp[i] -= u * tmp[k];
        }
        tmp[i] = tmp[i] / a[i * n + i];
    }
    b.copy_from_slice(&tmp[..n]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_with_pivoting() {
        // A zero leading entry needs the row exchange.
        let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3).map(|i| a[i * 3] * x[0] + a[i * 3 + 1] * x[1] + a[i * 3 + 2] * x[2]).collect();
        let (mut perm, mut tmp) = (vec![0; 3], vec![0.0; 3]);
        factorise(&mut a, &mut perm, 3);
        solve(&a, &perm, 3, &mut b, &mut tmp);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-15, "{b:?}");
        }
    }
}
