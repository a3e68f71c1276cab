//! The sparse LᵀDL factorisation of a mass matrix (Featherstone, *Rigid Body
//! Dynamics Algorithms*, §6.5): M = LᵀDL with L unit lower triangular and
//! non-zero only where M is (a joint and its ancestors), so a tree's
//! branches cause no fill-in. No square roots, so it traces well.

use crate::model::Model;
use crate::Scalar;

/// Factorises the NV×NV row-major mass matrix `m` of `model` in place: on
/// return the diagonal holds D and the strictly lower triangle holds L
/// (entries of joints on other branches are left untouched). Only the
/// lower triangle is read.
pub fn factorise<S: Scalar>(model: &Model, m: &mut [S]) {
    factorise_tree(model.nv(), |k| parent(model, k), m)
}

/// The parent of velocity coordinate `k` in the tree the factorisation of
/// `model`'s mass matrix follows: the kinematic tree; a floating base's six
/// coordinates as a chain ahead of the joints (its 6×6 block is dense, and
/// a joint on the base has the base's last coordinate as its parent); with
/// mimic joints, the elimination tree of M's pattern (see
/// [`mimic`](super::mimic)).
#[inline(always)]
pub fn parent(model: &Model, k: usize) -> Option<usize> {
    let base = model.nv() - model.dof();
    match k.checked_sub(base) {
        None => k.checked_sub(1),
        Some(j) => match model.coupling.parent[j] {
            Some(p) => Some(p + base),
            None => base.checked_sub(1),
        },
    }
}

/// [`factorise`] for any tree of `n` coordinates given by the parent of
/// each (`parent(k) < k`): a floating base's six coordinates as a chain
/// ahead of the joints ([`velocity_parent`](super::floating::velocity_parent)).
pub fn factorise_tree<S: Scalar>(n: usize, parent: impl Fn(usize) -> Option<usize>, m: &mut [S]) {
    assert!(m.len() == n * n, "ldlt: m must be {n}×{n}");
    for k in (0..n).rev() {
        let inv = S::one() / m[k * n + k];
        eliminate(n, &parent, m, k, |x| x * inv);
    }
}

/// Pivot `k`'s step of the elimination from the tips up: for each ancestor
/// i of k, L's entry a = `ratio(m[k][i])` (the entry over the pivot), then
/// m[i][j] −= a·m[k][j] for the ancestors-or-self j of i, and m[k][i] = a.
/// [`factorise_tree`] multiplies by the pivot's inverse; the dependent-joint
/// check of `model/dependent.rs` divides by it, after testing it.
pub(crate) fn eliminate<S: Scalar>(
    n: usize,
    parent: &impl Fn(usize) -> Option<usize>,
    m: &mut [S],
    k: usize,
    ratio: impl Fn(S) -> S,
) {
    let mut i = parent(k);
    while let Some(ii) = i {
        let a = ratio(m[k * n + ii]);
        let mut j = Some(ii);
        while let Some(jj) = j {
            m[ii * n + jj] -= a * m[k * n + jj];
            j = parent(jj);
        }
        m[k * n + ii] = a;
        i = parent(ii);
    }
}

/// Solves M x = b in place (`b` becomes x) with a factor from [`factorise`].
pub fn solve<S: Scalar>(model: &Model, factor: &[S], b: &mut [S]) {
    solve_tree(model.nv(), |k| parent(model, k), factor, b)
}

/// [`solve`] for a factor from [`factorise_tree`] with the same `parent`.
pub fn solve_tree<S: Scalar>(n: usize, parent: impl Fn(usize) -> Option<usize>, factor: &[S], b: &mut [S]) {
    assert!(factor.len() == n * n && b.len() == n, "ldlt: sizes must fit the model's {n} joints");
    // Lᵀ z = b, from the tips up.
    for i in (0..n).rev() {
        let bi = b[i];
        let mut j = parent(i);
        while let Some(jj) = j {
            b[jj] -= factor[i * n + jj] * bi;
            j = parent(jj);
        }
    }
    // D w = z
    for i in 0..n {
        b[i] = b[i] / factor[i * n + i];
    }
    // L x = w, from the base down.
    for i in 0..n {
        let mut acc = b[i];
        let mut j = parent(i);
        while let Some(jj) = j {
            acc -= factor[i * n + jj] * b[jj];
            j = parent(jj);
        }
        b[i] = acc;
    }
}
