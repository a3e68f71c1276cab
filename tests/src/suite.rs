//! The measurements of the stiff and extreme suite, shared by
//! `tests/stiff_extreme.rs` (which asserts the bounds) and the report (which
//! shows them): every output of the generic solver at a state, in any scalar,
//! the condition number of M, and the suite's error bounds.

use super::{Rng, StiffCase};
use dynagen::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::{Model, Scalar};
use nalgebra::DMatrix;

const EPS: f64 = f64::EPSILON;

/// Every output of the solver at one state, as f64.
#[derive(Debug)]
pub struct Outputs {
    /// τ(q, q̇, q̈).
    pub tau: Vec<f64>,
    /// M(q), row-major.
    pub m: Vec<f64>,
    /// h(q, q̇).
    pub h: Vec<f64>,
    /// g(q).
    pub g: Vec<f64>,
    /// q̈ by the articulated-body algorithm at τ.
    pub qdd_aba: Vec<f64>,
    /// q̈ by CRBA + LTDL at τ.
    pub qdd_ldlt: Vec<f64>,
}

/// Every output of the generic algorithms at one state, in the scalar `S`
/// (model's gravity, no tip wrenches).
pub fn eval<S: Scalar>(model: &Model, q: &[f64], qd: &[f64], qdd: &[f64], tau: &[f64]) -> Outputs {
    let n = model.dof();
    let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
    let back = |x: &[S]| x.iter().map(|v| v.to_f64().unwrap()).collect::<Vec<f64>>();
    let (q, qd, qdd, tau) = (c(q), c(qd), c(qdd), c(tau));
    let grav = Vec3::<S>::from_f64(&model.gravity);
    let mut ws = Workspace::<S>::new(model);
    let mut out = vec![S::zero(); n];
    rnea::rnea(model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&grav), &mut out);
    let tau_out = back(&out);
    let mut m = vec![S::zero(); n * n];
    crba::crba(model, &mut ws, &q, Loads::none(), &mut m);
    bias::bias_forces(model, &mut ws, &q, &qd, Some(&grav), &mut out);
    let h = back(&out);
    bias::gravity_torques(model, &mut ws, &q, &grav, &mut out);
    let g = back(&out);
    aba::aba(model, &mut ws, &q, &qd, &tau, Loads::gravity(&grav), &mut out);
    let qdd_aba = back(&out);
    forward_dynamics::forward_dynamics_ldlt(model, &mut ws, &q, &qd, &tau, Loads::gravity(&grav), &mut out);
    let qdd_ldlt = back(&out);
    Outputs { tau: tau_out, m: back(&m), h, g, qdd_aba, qdd_ldlt }
}

/// The 2-norm condition number of a symmetric matrix and whether it is
/// positive definite (eigenvalues from nalgebra, in f64: enough to print an
/// order of magnitude and to see the sign).
pub fn spd_condition(n: usize, m: &[f64]) -> (f64, bool) {
    let mat = DMatrix::from_row_slice(n, n, m);
    let symmetric = (0..n).all(|i| (0..n).all(|j| m[i * n + j] == m[j * n + i]));
    let ev = mat.symmetric_eigenvalues();
    let (lo, hi) = (ev.min(), ev.max());
    (hi / lo, symmetric && lo > 0.0)
}

/// A state of the suite: (q, q̇, q̈, τ).
pub type State = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// The suite's `count` states of a case: q and q̇ at the case's scales, q̈
/// and τ in ±10 (deterministic).
pub fn states(case: &StiffCase, count: usize) -> Vec<State> {
    let n = case.model.dof();
    let mut rng = Rng::new(0x5eed ^ n as u64);
    (0..count)
        .map(|_| (rng.vec(n, case.q_scale), rng.vec(n, case.qd_scale), rng.vec(n, 10.0), rng.vec(n, 10.0)))
        .collect()
}

/// The suite's bound on a forward dynamics error (max-norm, relative to the
/// reference's largest entry) at one state: `r` the reference outputs, `cond`
/// the condition number of M.
pub fn fd_bound(n: usize, cond: f64, r: &Outputs, tau: &[f64]) -> f64 {
    // Forward dynamics solves M q̈ = τ − h. A backward-stable method's
    // error is bounded by cond(M)·ε relative to the solution the
    // right-hand side's size stands for: ‖τ‖ + ‖h‖ can be far larger
    // than ‖M q̈‖ when they cancel. Factor 10 for the O(1) constants.
    let rhs_scale: f64 = r.h.iter().chain(tau).fold(0.0, |m, x| m.max(x.abs()));
    let m_norm = DMatrix::from_row_slice(n, n, &r.m).norm();
    let qdd_scale = r.qdd_aba.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let implied = rhs_scale / m_norm;
    10.0 * cond * EPS * (1.0 + implied / qdd_scale.max(f64::MIN_POSITIVE))
}

/// τ, M, h and g: each entry is a sum of O(n) products along the tree, so
/// its rounding error is O(n)·ε relative to the largest term; bounded by
/// 100·n·ε relative to the output's largest entry.
pub fn id_bound(n: usize) -> f64 {
    100.0 * n as f64 * EPS
}
