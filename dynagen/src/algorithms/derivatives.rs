//! Derivatives of the dynamics: ∂τ/∂q and ∂τ/∂q̇ of the inverse dynamics
//! (∂τ/∂q̈ is the mass matrix), ∂q̈/∂q and ∂q̈/∂q̇ of the forward dynamics,
//! and M⁻¹ (= ∂q̈/∂τ).
//!
//! ∂τ/∂x is forward-mode differentiation of the inverse dynamics itself: the
//! same generic recursion run on [`Dual`] numbers, once for each joint's q
//! and once for its q̇, each run giving one column. There is no second
//! algorithm to keep in step with the first: every load, payload, armature
//! or friction term the inverse dynamics has is differentiated with it. On
//! the symbolic scalar the values are shared by all the runs (hash-consing)
//! and a derivative no path of the tree reaches (∂τᵢ/∂qⱼ with joints i and j
//! on different branches) folds to the constant 0; `docs/performance.md`
//! compares the operation counts with the values'.
//!
//! The forward dynamics' derivatives follow from the inverse's at q̈ =
//! FD(q, q̇, τ): τ(q, q̇, FD(q, q̇, τ)) = τ for all q, so ∂q̈/∂x = −M⁻¹ ∂τ/∂x
//! (Carpentier & Mansard, RSS 2018). M⁻¹ comes from the sparse LᵀDL factors
//! ([`ldlt`]), as L⁻¹ D⁻¹ L⁻ᵀ, its lower triangle only (it is symmetric),
//! with L⁻¹ non-zero only where L is: never a dense inversion.
//!
//! Matrices are row-major, `[i * n + j] = ∂yᵢ/∂xⱼ`.

use super::{ldlt, BodyInertia, Loads, TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Sym3, Vec3};
use crate::{Dual, Scalar};

/// Scratch for the derivatives of one model, allocated once.
#[derive(Clone, Debug)]
pub struct DerivativeWorkspace<S> {
    /// The dual runs' workspace.
    pub dual: Workspace<Dual<S>>,
    /// The mass matrix's workspace.
    pub ws: Workspace<S>,
    q: Vec<Dual<S>>,
    qd: Vec<Dual<S>>,
    qdd: Vec<Dual<S>>,
    tau: Vec<Dual<S>>,
    /// M, then its LᵀDL factor.
    factor: Vec<S>,
    /// L⁻¹ (row-major), then L⁻¹ D⁻¹.
    linv: Vec<S>,
    /// ∂τ/∂q and ∂τ/∂q̇ of the forward dynamics' derivatives.
    dtau_dq: Vec<S>,
    dtau_dqd: Vec<S>,
    /// τ − h(q, q̇).
    rhs: Vec<S>,
    /// q̈ = M⁻¹(τ − h).
    qdd_value: Vec<S>,
}

impl<S: Scalar> DerivativeWorkspace<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.dof();
        let d = vec![Dual::constant(S::zero()); n];
        DerivativeWorkspace {
            dual: Workspace::new(model),
            ws: Workspace::new(model),
            q: d.clone(),
            qd: d.clone(),
            qdd: d.clone(),
            tau: d,
            factor: vec![S::zero(); n * n],
            linv: vec![S::zero(); n * n],
            dtau_dq: vec![S::zero(); n * n],
            dtau_dqd: vec![S::zero(); n * n],
            rhs: vec![S::zero(); n],
            qdd_value: vec![S::zero(); n],
        }
    }
}

/// Run-time loads (gravity, tip wrenches, payloads) as dual constants: what
/// the dual runs of the inverse dynamics read, held constant.
#[derive(Clone, Debug)]
pub struct DualLoads<S> {
    gravity: Option<Vec3<Dual<S>>>,
    tips: Vec<TipWrench<Dual<S>>>,
    payloads: Vec<BodyInertia<Dual<S>>>,
    armature: Option<Vec<f64>>,
}

impl<S: Scalar> DualLoads<S> {
    /// Room for `capacity` tip wrenches and payloads (the model's number of
    /// frames is enough for a robot's), so that [`set`](Self::set) allocates
    /// nothing.
    pub fn with_capacity(capacity: usize, dof: usize) -> Self {
        DualLoads {
            gravity: None,
            tips: Vec::with_capacity(capacity),
            payloads: Vec::with_capacity(capacity),
            armature: Some(Vec::with_capacity(dof)),
        }
    }
    /// These loads become `loads`, as constants.
    pub fn set(&mut self, loads: &Loads<'_, S>) {
        let c = |v: &Vec3<S>| Vec3(v.0.map(Dual::constant));
        self.gravity = loads.gravity.map(c);
        self.tips.clear();
        self.tips.extend(
            loads
                .tips
                .iter()
                .map(|t| TipWrench { frame: t.frame, wrench: Force::new(c(&t.wrench.ang), c(&t.wrench.lin)) }),
        );
        self.payloads.clear();
        self.payloads.extend(loads.payloads.iter().map(|p| BodyInertia {
            body: p.body,
            inertia: Inertia {
                mass: Dual::constant(p.inertia.mass),
                h: c(&p.inertia.h),
                ibar: Sym3(p.inertia.ibar.0.map(Dual::constant)),
            },
        }));
        match (loads.armature, &mut self.armature) {
            (Some(a), Some(mine)) => {
                mine.clear();
                mine.extend_from_slice(a);
            }
            (Some(a), mine) => *mine = Some(a.to_vec()),
            (None, Some(mine)) => mine.clear(),
            (None, None) => {}
        }
    }
    /// The loads, to pass to the inverse dynamics run on dual numbers.
    pub fn loads(&self) -> Loads<'_, Dual<S>> {
        Loads {
            gravity: self.gravity.as_ref(),
            tips: &self.tips,
            payloads: &self.payloads,
            armature: self.armature.as_deref().filter(|a| !a.is_empty()),
        }
    }
}

/// ∂τ/∂q and ∂τ/∂q̇ (row-major n×n each) of the inverse dynamics `tau`
/// (`tau(ws, q, q̇, q̈, τ)`, any generic inverse dynamics run on dual numbers,
/// with its loads held constant) at `[q, q̇, q̈]`: one dual run per column.
pub fn inverse_dynamics_derivatives<S: Scalar>(
    dw: &mut DerivativeWorkspace<S>,
    [q, qd, qdd]: [&[S]; 3],
    mut tau: impl FnMut(&mut Workspace<Dual<S>>, &[Dual<S>], &[Dual<S>], &[Dual<S>], &mut [Dual<S>]),
    dtau_dq: &mut [S],
    dtau_dqd: &mut [S],
) {
    let n = dw.q.len();
    assert!(
        q.len() == n && qd.len() == n && qdd.len() == n && dtau_dq.len() == n * n && dtau_dqd.len() == n * n,
        "inverse_dynamics_derivatives: sizes must fit the model's {n} joints"
    );
    for i in 0..n {
        dw.q[i] = Dual::constant(q[i]);
        dw.qd[i] = Dual::constant(qd[i]);
        dw.qdd[i] = Dual::constant(qdd[i]);
    }
    for (wrt_qd, out) in [(false, dtau_dq), (true, dtau_dqd)] {
        for j in 0..n {
            let x = if wrt_qd { &mut dw.qd } else { &mut dw.q };
            x[j].eps = S::one();
            tau(&mut dw.dual, &dw.q, &dw.qd, &dw.qdd, &mut dw.tau);
            let x = if wrt_qd { &mut dw.qd } else { &mut dw.q };
            x[j].eps = S::zero();
            for i in 0..n {
                out[i * n + j] = dw.tau[i].eps;
            }
        }
    }
}

/// M⁻¹ (row-major, both triangles) from M (`factor`, overwritten by its
/// LᵀDL factor): L⁻¹ by rows, non-zero only at a joint's ancestors, then
/// (M⁻¹)ᵢⱼ = Σₖ (L⁻¹)ᵢₖ (L⁻¹)ⱼₖ / Dₖ over the common ancestors k of i and
/// j, for j ≤ i. `linv` is n×n scratch.
pub fn mass_matrix_inverse<S: Scalar>(model: &Model, factor: &mut [S], linv: &mut [S], minv: &mut [S]) {
    let n = model.dof();
    assert!(linv.len() == n * n && minv.len() == n * n, "mass_matrix_inverse: m must be {n}×{n}");
    ldlt::factorise(model, factor);
    // the tree of the factorisation (the kinematic tree, or with mimic
    // joints the elimination tree of M's pattern)
    let parent = |i: usize| ldlt::parent(model, i);
    // L⁻¹: row i = e_i − Σ_{m ancestor of i} L[i][m]·row m (rows of
    // ancestors first, as joints come after their parents).
    for i in 0..n {
        linv[i * n..(i + 1) * n].fill(S::zero());
        linv[i * n + i] = S::one();
        let mut m = parent(i);
        while let Some(mm) = m {
            let l = factor[i * n + mm];
            let mut k = Some(mm);
            while let Some(kk) = k {
                let v = l * linv[mm * n + kk];
                linv[i * n + kk] -= v;
                k = parent(kk);
            }
            m = parent(mm);
        }
    }
    // D⁻¹ on the factor's diagonal (D is read nowhere else).
    for k in 0..n {
        factor[k * n + k] = S::one() / factor[k * n + k];
    }
    for i in 0..n {
        for j in 0..=i {
            // Σ over the ancestors-or-self k of j ((L⁻¹)ᵢₖ is zero off i's);
            // (L⁻¹)ⱼₖ/Dₖ is the same product for every i (shared when traced).
            let mut acc: Option<S> = None;
            let mut k = Some(j);
            while let Some(kk) = k {
                let t = linv[i * n + kk] * (linv[j * n + kk] * factor[kk * n + kk]);
                acc = Some(acc.map_or(t, |a| a + t));
                k = parent(kk);
            }
            let v = acc.expect("j is its own ancestor-or-self");
            minv[i * n + j] = v;
            minv[j * n + i] = v;
        }
    }
}

/// ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ (row-major n×n each) of the forward dynamics at
/// `[q, q̇, τ]`: q̈ = M⁻¹(τ − h) with h = `tau`(q, q̇, 0) and M from `mass`
/// (`mass(ws, q, m)`, the mass matrix `tau` implies: armature and payloads
/// included), then −M⁻¹ ∂τ/∂x at that q̈. `tau` as in
/// [`inverse_dynamics_derivatives`]; the outputs `[∂q̈/∂q, ∂q̈/∂q̇, M⁻¹]`.
pub fn forward_dynamics_derivatives<S: Scalar>(
    model: &Model,
    dw: &mut DerivativeWorkspace<S>,
    [q, qd, tau_in]: [&[S]; 3],
    mut tau: impl FnMut(&mut Workspace<Dual<S>>, &[Dual<S>], &[Dual<S>], &[Dual<S>], &mut [Dual<S>]),
    mass: impl FnOnce(&mut Workspace<S>, &[S], &mut [S]),
    [dqdd_dq, dqdd_dqd, minv]: [&mut [S]; 3],
) {
    let n = model.dof();
    assert!(
        tau_in.len() == n && dqdd_dq.len() == n * n && dqdd_dqd.len() == n * n,
        "forward_dynamics_derivatives: sizes must fit the model's {n} joints"
    );
    // τ − h(q, q̇): the inverse dynamics at q̈ = 0, derivatives unseeded.
    for i in 0..n {
        dw.q[i] = Dual::constant(q[i]);
        dw.qd[i] = Dual::constant(qd[i]);
        dw.qdd[i] = Dual::constant(S::zero());
    }
    tau(&mut dw.dual, &dw.q, &dw.qd, &dw.qdd, &mut dw.tau);
    for ((r, t), h) in dw.rhs.iter_mut().zip(tau_in).zip(&dw.tau) {
        *r = *t - h.re;
    }
    mass(&mut dw.ws, q, &mut dw.factor);
    mass_matrix_inverse(model, &mut dw.factor, &mut dw.linv, minv);
    for i in 0..n {
        dw.qdd_value[i] = dot(&minv[i * n..(i + 1) * n], &dw.rhs, 1);
    }
    let (mut dq, mut dqd) = (std::mem::take(&mut dw.dtau_dq), std::mem::take(&mut dw.dtau_dqd));
    let qdd = std::mem::take(&mut dw.qdd_value);
    inverse_dynamics_derivatives(dw, [q, qd, &qdd], tau, &mut dq, &mut dqd);
    for (dtau, out) in [(&dq, &mut *dqdd_dq), (&dqd, &mut *dqdd_dqd)] {
        for i in 0..n {
            for j in 0..n {
                out[i * n + j] = -dot(&minv[i * n..(i + 1) * n], &dtau[j..], n);
            }
        }
    }
    (dw.dtau_dq, dw.dtau_dqd, dw.qdd_value) = (dq, dqd, qdd);
}

/// Σₖ a[k]·b[k·stride], k < a.len().
#[inline(always)]
fn dot<S: Scalar>(a: &[S], b: &[S], stride: usize) -> S {
    let mut acc = a[0] * b[0];
    for (k, x) in a.iter().enumerate().skip(1) {
        acc += *x * b[k * stride];
    }
    acc
}
