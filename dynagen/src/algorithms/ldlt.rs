//! The sparse LᵀDL factorisation of a mass matrix (Featherstone, *Rigid Body
//! Dynamics Algorithms*, §6.5): M = LᵀDL with L unit lower triangular and
//! non-zero only where M is (a joint and its ancestors), so a tree's
//! branches cause no fill-in. No square roots, so it traces well.

use crate::model::Model;
use crate::Scalar;

/// Factorises the n×n row-major `m` in place: on return the diagonal holds
/// D and the strictly lower triangle holds L (entries of joints on other
/// branches are left untouched). Only the lower triangle is read.
pub fn factorise<S: Scalar>(model: &Model, m: &mut [S]) {
    let n = model.dof();
    assert!(m.len() == n * n, "ldlt: m must be {n}×{n}");
    for k in (0..n).rev() {
        let inv = S::one() / m[k * n + k];
        let mut i = model.bodies[k].parent;
        while let Some(ii) = i {
            let a = m[k * n + ii] * inv;
            let mut j = Some(ii);
            while let Some(jj) = j {
                m[ii * n + jj] -= a * m[k * n + jj];
                j = model.bodies[jj].parent;
            }
            m[k * n + ii] = a;
            i = model.bodies[ii].parent;
        }
    }
}

/// Solves M x = b in place (`b` becomes x) with a factor from [`factorise`].
pub fn solve<S: Scalar>(model: &Model, factor: &[S], b: &mut [S]) {
    let n = model.dof();
    assert!(factor.len() == n * n && b.len() == n, "ldlt: sizes must fit the model's {n} joints");
    // Lᵀ z = b, from the tips up.
    for i in (0..n).rev() {
        let bi = b[i];
        let mut j = model.bodies[i].parent;
        while let Some(jj) = j {
            b[jj] -= factor[i * n + jj] * bi;
            j = model.bodies[jj].parent;
        }
    }
    // D w = z
    for i in 0..n {
        b[i] = b[i] / factor[i * n + i];
    }
    // L x = w, from the base down.
    for i in 0..n {
        let mut acc = b[i];
        let mut j = model.bodies[i].parent;
        while let Some(jj) = j {
            acc -= factor[i * n + jj] * b[jj];
            j = model.bodies[jj].parent;
        }
        b[i] = acc;
    }
}
