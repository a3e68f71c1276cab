//! Derivatives of the dynamics: ∂τ/∂q and ∂τ/∂q̇ of the inverse dynamics
//! (∂τ/∂q̈ is the mass matrix), ∂q̈/∂q and ∂q̈/∂q̇ of the forward dynamics,
//! and M⁻¹ (= ∂q̈/∂τ).
//!
//! ∂τ/∂x has two formulations ([`Formulation`]), which give the same
//! matrices up to rounding:
//!
//! - **analytical**: the recursion of [`rnea_derivatives`] (O(n·d) work),
//!   the generic solver's, and what code generation emits where it traces
//!   to fewer operations;
//! - **dual numbers**: the inverse dynamics itself run on [`Dual`] numbers,
//!   once for each joint's q and once for its q̇, each run giving one
//!   column. Run on `f64` it redoes the whole recursion 2n times; traced on
//!   `Dual<Expr>`, the values are shared by all the runs (hash-consing) and
//!   a derivative no path of the tree reaches folds to the constant 0, so
//!   on short chains it traces to fewer operations than the analytical
//!   recursion (`docs/performance.md` compares them robot by robot).
//!
//! The forward dynamics' derivatives follow from the inverse's at q̈ =
//! FD(q, q̇, τ): τ(q, q̇, FD(q, q̇, τ)) = τ for all q, so ∂q̈/∂x = −M⁻¹ ∂τ/∂x
//! (Carpentier & Mansard, RSS 2018). M⁻¹ comes from the sparse LᵀDL factors
//! ([`ldlt`]), as L⁻¹ D⁻¹ L⁻ᵀ, its lower triangle only (it is symmetric),
//! with L⁻¹ non-zero only where L is: never a dense inversion.
//!
//! What is differentiated is a [`Dynamics`]: the model's inverse dynamics
//! under its loads (gravity, tip wrenches, payloads, all held constant, and
//! the armature), plus torques that depend on each joint's own velocity (a
//! scene's friction, [`JointTorques`]).
//!
//! Matrices are row-major, `[i * n + j] = ∂yᵢ/∂xⱼ`.

pub use super::rnea_derivatives::{rnea_derivatives, RneaDerivativeWorkspace};

use super::{crba, ldlt, rnea, BodyInertia, Loads, TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Sym3, Vec3};
use crate::{Dual, Scalar};

/// How ∂τ/∂(q, q̇) is computed (see the [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// The analytical recursion ([`rnea_derivatives`]).
    Analytical,
    /// Forward-mode dual numbers through the inverse dynamics, a run per
    /// column.
    DualNumbers,
}

impl Formulation {
    /// Both, the analytical first.
    pub const ALL: [Formulation; 2] = [Formulation::Analytical, Formulation::DualNumbers];
    /// Its name, for headers and tables: `analytical`, `dual numbers`.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Analytical => "analytical",
            Formulation::DualNumbers => "dual numbers",
        }
    }
}

/// Torques added to the rigid-body τ, each a function of its own joint's
/// velocity alone (a scene's friction): τᵢ += φᵢ(q̇ᵢ). Their derivatives
/// (a diagonal) are taken by one run on dual numbers with every q̇ᵢ seeded.
pub trait JointTorques {
    /// Adds φ(q̇) to `tau`, both velocity-side vectors (NV long: a floating
    /// base's six entries first, which φ leaves alone).
    fn add_to<S: Scalar>(&self, qd: &[S], tau: &mut [S]);
}

/// No torques beyond the rigid body's: a [`Robot`](crate::Robot)'s.
#[derive(Clone, Copy, Debug, Default)]
pub struct RigidBodyOnly;

impl JointTorques for RigidBodyOnly {
    fn add_to<S: Scalar>(&self, _: &[S], _: &mut [S]) {}
}

/// A mass matrix `mass(ws, q, m)` (row-major, the armature on its diagonal)
/// to use instead of the CRBA: code generation's planned one.
pub type MassMatrixFn<'a, S> = &'a dyn Fn(&mut Workspace<S>, &[S], &mut [S]);

/// The inverse dynamics differentiated: `model`'s RNEA under `loads` (with
/// its armature), plus `torques`.
pub struct Dynamics<'a, S, J> {
    /// The model (fixed base).
    pub model: &'a Model,
    /// Gravity, tip wrenches, payloads (held constant) and the armature.
    pub loads: Loads<'a, S>,
    /// Torques of each joint's velocity (friction).
    pub torques: &'a J,
    /// The mass matrix, if not the CRBA's (`None`).
    pub mass: Option<MassMatrixFn<'a, S>>,
}

impl<S: Scalar, J: JointTorques> Dynamics<'_, S, J> {
    /// τ(q, q̇, q̈) (`qdd: None`: h(q, q̇)).
    fn tau(&self, ws: &mut Workspace<S>, q: &[S], qd: &[S], qdd: Option<&[S]>, tau: &mut [S]) {
        rnea::rnea(self.model, ws, q, Some(qd), qdd, self.loads, tau);
        self.torques.add_to(qd, tau);
    }
    /// M(q) with the payloads and the armature.
    fn mass_matrix(&self, ws: &mut Workspace<S>, q: &[S], m: &mut [S]) {
        match self.mass {
            Some(f) => f(ws, q, m),
            None => crba::crba(self.model, ws, q, self.loads.inertias(), m),
        }
    }
}

/// Scratch for the derivatives of one model, allocated once.
#[derive(Clone, Debug)]
pub struct DerivativeWorkspace<S> {
    /// The values' workspace (M, h, q̈).
    pub ws: Workspace<S>,
    analytical: RneaDerivativeWorkspace<S>,
    dual: Workspace<Dual<S>>,
    dual_loads: DualLoads<S>,
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
    /// τ − h(q, q̇), or τ − φ(q̇).
    rhs: Vec<S>,
    /// q̈ = FD(q, q̇, τ).
    qdd_value: Vec<S>,
}

impl<S: Scalar> DerivativeWorkspace<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        let nv = model.nv();
        let d = vec![Dual::constant(S::zero()); nv];
        DerivativeWorkspace {
            ws: Workspace::new(model),
            analytical: RneaDerivativeWorkspace::new(model),
            dual: Workspace::new(model),
            dual_loads: DualLoads::with_capacity(model.frames.len()),
            q: vec![Dual::constant(S::zero()); model.nq()],
            qd: d.clone(),
            qdd: d.clone(),
            tau: d,
            factor: vec![S::zero(); nv * nv],
            linv: vec![S::zero(); nv * nv],
            dtau_dq: vec![S::zero(); nv * nv],
            dtau_dqd: vec![S::zero(); nv * nv],
            rhs: vec![S::zero(); nv],
            qdd_value: vec![S::zero(); nv],
        }
    }
}

/// Run-time loads (gravity, tip wrenches, payloads) as dual constants: what
/// the dual runs of the inverse dynamics read, held constant.
#[derive(Clone, Debug)]
struct DualLoads<S> {
    gravity: Option<Vec3<Dual<S>>>,
    tips: Vec<TipWrench<Dual<S>>>,
    payloads: Vec<BodyInertia<Dual<S>>>,
}

impl<S: Scalar> DualLoads<S> {
    /// Room for `capacity` tip wrenches and payloads (the model's number of
    /// frames is enough for a robot's), so that [`set`](Self::set) allocates
    /// nothing.
    fn with_capacity(capacity: usize) -> Self {
        DualLoads { gravity: None, tips: Vec::with_capacity(capacity), payloads: Vec::with_capacity(capacity) }
    }
    /// These loads become `loads`, as constants.
    fn set(&mut self, loads: &Loads<'_, S>) {
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
    }
    /// The loads, with `armature`, to pass to the inverse dynamics run on
    /// dual numbers.
    fn loads<'a>(&'a self, armature: Option<&'a [f64]>) -> Loads<'a, Dual<S>> {
        Loads { gravity: self.gravity.as_ref(), tips: &self.tips, payloads: &self.payloads, armature }
    }
}

/// Adds ∂φ/∂q̇ (a diagonal) of `torques` at `qd` to the row-major NV×NV
/// `dtau_dqd`, on the joints (after a floating base's six coordinates,
/// `off`): one run on dual numbers with every q̇ᵢ seeded (φᵢ reads q̇ᵢ
/// alone), in `dw`'s scratch.
fn add_joint_torque_derivatives<S: Scalar>(
    dw: &mut DerivativeWorkspace<S>,
    torques: &impl JointTorques,
    (qd, off): (&[S], usize),
    dtau_dqd: &mut [S],
) {
    let nv = qd.len();
    let (dqd, tau) = (&mut dw.qd, &mut dw.tau);
    for ((d, t), &v) in dqd.iter_mut().zip(tau.iter_mut()).zip(qd) {
        (*d, *t) = (Dual::variable(v), Dual::constant(S::zero()));
    }
    torques.add_to(dqd, tau);
    for (i, t) in tau.iter().enumerate().skip(off) {
        if t.eps.to_f64() != Some(0.0) {
            dtau_dqd[i * nv + i] += t.eps;
        }
    }
}

/// ∂τ/∂q and ∂τ/∂q̇ (row-major NV×NV each; n×n on a fixed base) of `d` at
/// `[q, q̇, q̈]` by `formulation`, and the mass matrix into `mass` if given
/// (the analytical recursion gives it on the way; the dual numbers call the
/// CRBA). On a floating base the configuration's tangent is the base's body
/// twist ([`rnea_derivatives`]).
pub fn inverse_dynamics_derivatives<S: Scalar, J: JointTorques>(
    d: &Dynamics<'_, S, J>,
    dw: &mut DerivativeWorkspace<S>,
    [q, qd, qdd]: [&[S]; 3],
    formulation: Formulation,
    [dtau_dq, dtau_dqd]: [&mut [S]; 2],
    mass: Option<&mut [S]>,
) {
    let (model, nv) = (d.model, d.model.nv());
    assert!(
        q.len() == model.nq() && qd.len() == nv && qdd.len() == nv,
        "inverse_dynamics_derivatives: q must have NQ entries, q̇ and q̈ NV"
    );
    // The analytical recursion runs over the bodies, one coordinate each; a
    // model with mimic joints takes the dual numbers, through the RNEA's
    // expansion and projection (`algorithms/mimic.rs`).
    let formulation = if model.has_mimic() { Formulation::DualNumbers } else { formulation };
    match formulation {
        Formulation::Analytical => {
            rnea_derivatives(model, &mut dw.analytical, [q, qd, qdd], d.loads, [dtau_dq, dtau_dqd], mass)
        }
        Formulation::DualNumbers => {
            dual_derivatives(d, dw, [q, qd, qdd], dtau_dq, dtau_dqd);
            if let Some(m) = mass {
                d.mass_matrix(&mut dw.ws, q, m);
            }
        }
    }
    add_joint_torque_derivatives(dw, d.torques, (qd, nv - model.dof()), dtau_dqd);
}

/// The rigid-body part of ∂τ/∂q and ∂τ/∂q̇ by dual numbers: one run of the
/// RNEA per column. A floating base's tangent columns: moving the base
/// changes nothing in its frame, turning it about eₖ turns gravity there, so
/// the world's gravity is seeded with its change g × R eₖ (R: world ← base).
fn dual_derivatives<S: Scalar, J>(
    d: &Dynamics<'_, S, J>,
    dw: &mut DerivativeWorkspace<S>,
    [q, qd, qdd]: [&[S]; 3],
    dtau_dq: &mut [S],
    dtau_dqd: &mut [S],
) {
    let (model, nv) = (d.model, d.model.nv());
    let (off, qoff) = if model.is_floating() { (6, 7) } else { (0, 0) };
    dw.dual_loads.set(&d.loads);
    for (x, &v) in dw.q.iter_mut().zip(q) {
        *x = Dual::constant(v);
    }
    for i in 0..nv {
        dw.qd[i] = Dual::constant(qd[i]);
        dw.qdd[i] = Dual::constant(qdd[i]);
    }
    let run = |dw: &mut DerivativeWorkspace<S>, out: &mut [S], column: usize| {
        let loads = dw.dual_loads.loads(d.loads.armature);
        rnea::rnea(model, &mut dw.dual, &dw.q, Some(&dw.qd), Some(&dw.qdd), loads, &mut dw.tau);
        for i in 0..nv {
            out[i * nv + column] = dw.tau[i].eps;
        }
    };
    for j in 0..nv - off {
        dw.q[qoff + j].eps = S::one();
        run(dw, dtau_dq, off + j);
        dw.q[qoff + j].eps = S::zero();
    }
    for j in 0..nv {
        dw.qd[j].eps = S::one();
        run(dw, dtau_dqd, j);
        dw.qd[j].eps = S::zero();
    }
    if off == 6 {
        let rot = super::floating::quaternion_rotation(&q[3..7]);
        for k in 0..6 {
            match (k < 3, d.loads.gravity) {
                (true, Some(g)) => {
                    let turned = g.cross(&rot.col(k));
                    let re = dw.dual_loads.gravity.expect("set with the loads").0.map(|x| x.re);
                    dw.dual_loads.gravity = Some(Vec3(std::array::from_fn(|c| Dual { re: re[c], eps: turned.0[c] })));
                    run(dw, dtau_dq, k);
                    dw.dual_loads.gravity = Some(Vec3(re.map(Dual::constant)));
                }
                _ => (0..nv).for_each(|i| dtau_dq[i * nv + k] = S::zero()),
            }
        }
    }
}

/// M⁻¹ (row-major, both triangles) from M (`factor`, overwritten by its
/// LᵀDL factor): L⁻¹ by rows, non-zero only at a joint's ancestors, then
/// (M⁻¹)ᵢⱼ = Σₖ (L⁻¹)ᵢₖ (L⁻¹)ⱼₖ / Dₖ over the common ancestors k of i and
/// j, for j ≤ i. `linv` is n×n scratch.
pub fn mass_matrix_inverse<S: Scalar>(model: &Model, factor: &mut [S], linv: &mut [S], minv: &mut [S]) {
    let n = model.nv();
    assert!(linv.len() == n * n && minv.len() == n * n, "mass_matrix_inverse: m must be {n}×{n}");
    ldlt::factorise(model, factor);
    // The tree of the factorisation: the kinematic tree (a floating base's
    // six coordinates a chain ahead of the joints), or with mimic joints the
    // elimination tree of M's pattern.
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

/// ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ (row-major n×n each) of the forward dynamics of
/// `d` at `[q, q̇, τ]`: −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ) = M⁻¹(τ − h), with M
/// by the CRBA (or [`Dynamics::mass`]), h by the RNEA and ∂τ/∂x by
/// `formulation`. The outputs `[∂q̈/∂q, ∂q̈/∂q̇, M⁻¹]`.
pub fn forward_dynamics_derivatives<S: Scalar, J: JointTorques>(
    d: &Dynamics<'_, S, J>,
    dw: &mut DerivativeWorkspace<S>,
    state: [&[S]; 3],
    formulation: Formulation,
    [dqdd_dq, dqdd_dqd, minv]: [&mut [S]; 3],
) {
    let n = d.model.nv();
    assert!(
        dqdd_dq.len() == n * n && dqdd_dqd.len() == n * n,
        "forward_dynamics_derivatives: the matrices must be NV×NV ({n}×{n})"
    );
    let (mut dq, mut dqd) = (std::mem::take(&mut dw.dtau_dq), std::mem::take(&mut dw.dtau_dqd));
    forward_dynamics_derivative_factors(d, dw, state, formulation, [&mut dq, &mut dqd, minv]);
    for (dtau, out) in [(&dq, &mut *dqdd_dq), (&dqd, &mut *dqdd_dqd)] {
        for i in 0..n {
            for j in 0..n {
                out[i * n + j] = -dot(&minv[i * n..(i + 1) * n], &dtau[j..], n);
            }
        }
    }
    (dw.dtau_dq, dw.dtau_dqd) = (dq, dqd);
}

/// The factors of [`forward_dynamics_derivatives`]: ∂τ/∂q and ∂τ/∂q̇ at
/// q̈ = FD(q, q̇, τ), and M⁻¹ (row-major n×n each), whose products
/// −M⁻¹ ∂τ/∂x are ∂q̈/∂x. Code generation emits those products as a loop
/// where that is cheaper than unrolling them (`codegen/emit/products.rs`).
pub fn forward_dynamics_derivative_factors<S: Scalar, J: JointTorques>(
    d: &Dynamics<'_, S, J>,
    dw: &mut DerivativeWorkspace<S>,
    [q, qd, tau]: [&[S]; 3],
    formulation: Formulation,
    [dtau_dq, dtau_dqd, minv]: [&mut [S]; 3],
) {
    let (model, n) = (d.model, d.model.nv());
    assert!(
        tau.len() == n && dtau_dq.len() == n * n && dtau_dqd.len() == n * n && minv.len() == n * n,
        "forward_dynamics_derivatives: τ must have NV entries and the matrices NV×NV ({n}×{n})"
    );
    let (mut factor, mut qdd) = (std::mem::take(&mut dw.factor), std::mem::take(&mut dw.qdd_value));
    // τ − h(q, q̇), M, M⁻¹, q̈ = M⁻¹(τ − h), then ∂τ at q̈.
    d.tau(&mut dw.ws, q, qd, None, &mut dw.rhs);
    for (r, t) in dw.rhs.iter_mut().zip(tau) {
        *r = *t - *r;
    }
    d.mass_matrix(&mut dw.ws, q, &mut factor);
    mass_matrix_inverse(model, &mut factor, &mut dw.linv, minv);
    for i in 0..n {
        qdd[i] = dot(&minv[i * n..(i + 1) * n], &dw.rhs, 1);
    }
    inverse_dynamics_derivatives(d, dw, [q, qd, &qdd], formulation, [dtau_dq, dtau_dqd], None);
    (dw.factor, dw.qdd_value) = (factor, qdd);
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
