//! Compensated forward dynamics: q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip) with
//! the cancelling part carried in a more precise scalar.
//!
//! When the joint torques nearly balance the bias forces at high speed
//! (τ ≈ h, with ‖h‖ ≫ ‖τ − h‖), the subtraction τ − h cancels: an `f64`
//! h(q, q̇) is only known to ε·‖h‖, so every plain `f64` method — the
//! articulated-body algorithm as much as a factorisation of M — returns q̈
//! with an error of about ε·‖h‖/‖M‖, however small q̈ is. Here the bias
//! forces h(q, q̇) + J(q)ᵀF_tip (gravity, the sines and cosines of q and the
//! model's constants included) are computed by the recursive Newton-Euler
//! algorithm in a precise scalar `P` (normally [`Compensated`],
//! ≈ 20 digits at a few times the cost of `f64`; [`DoubleDouble`](crate::DoubleDouble)
//! works too, slower), u = τ − h is formed in `P` and rounded once to `f64`,
//! and the articulated-body algorithm solves M q̈ = u in `f64` with zero
//! velocity and no gravity. The error is then about ε·‖u‖/‖M‖ plus `P`'s
//! error on h, instead of ε·‖h‖/‖M‖: as many digits won as ‖h‖/‖τ − h‖ has.
//! On ordinary states (no cancellation) it is as accurate as the plain
//! algorithm. `P` takes the model's constants from the robot file's
//! decimals where the model has them ([`Scalar::FILE_CONSTANTS`]): h is the
//! file's robot's, not that of the `f64` model an ε away.
//!
//! What remains is the `f64` solve's error, about ε·cond(M)·‖q̈‖. On request
//! ([`CompensatedScratch::with_refinement`]) each step of iterative
//! refinement computes the residual r = τ − RNEA(q, q̇, q̈) in `P` (with
//! every load: gravity, tip wrenches, payloads, armature), rounds it once,
//! and adds the correction M⁻¹r (the `f64` articulated-body algorithm at
//! rest again): one step takes the error to about (ε·cond(M))²·‖q̈‖ plus
//! `P`'s own, for about the cost of the first pass again. It pays where
//! ε·cond(M) is large; `docs/performance.md` has the measurements.

use super::aba::aba_at_rest;
use super::rnea::rnea;
use super::{BodyInertia, Loads, TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Vec3};
use crate::{Compensated, CompensatedFma, Scalar};

/// Scratch for [`forward_dynamics_compensated`]: the workspace and the
/// arguments in the precise scalar `P`, and the `f64` workspace of the
/// articulated-body solve. Create it once per model, outside a control loop.
#[derive(Clone, Debug)]
pub struct CompensatedScratch<P> {
    ws: Workspace<P>,
    ws_f64: Workspace<f64>,
    q: Vec<P>,
    qd: Vec<P>,
    h: Vec<P>,
    tips: Vec<TipWrench<P>>,
    payloads: Vec<BodyInertia<P>>,
    /// The right-hand side u = τ − h, rounded to `f64`.
    rhs: Vec<f64>,
    /// Steps of iterative refinement, and their scratch: q̈ in `P`, the
    /// residual rounded to `f64` and the correction.
    refinements: usize,
    qdd: Vec<P>,
    residual: Vec<f64>,
    correction: Vec<f64>,
}

impl<P: Scalar> CompensatedScratch<P> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        // NQ and NV entries (both n for a fixed base)
        let (nq, n) = (model.nq(), model.nv());
        CompensatedScratch {
            ws: Workspace::new(model),
            ws_f64: Workspace::new(model),
            q: vec![P::zero(); nq],
            qd: vec![P::zero(); n],
            h: vec![P::zero(); n],
            tips: Vec::new(),
            payloads: Vec::new(),
            rhs: vec![0.0; n],
            refinements: 0,
            qdd: vec![P::zero(); n],
            residual: vec![0.0; n],
            correction: vec![0.0; n],
        }
    }
    /// This scratch with `steps` steps of iterative refinement (0, the
    /// default: none): see the module documentation.
    pub fn with_refinement(mut self, steps: usize) -> Self {
        self.refinements = steps;
        self
    }
    /// The steps of iterative refinement each call takes.
    pub fn refinements(&self) -> usize {
        self.refinements
    }
    /// The number of joints this scratch is for (NV for a floating base).
    pub fn dof(&self) -> usize {
        self.qd.len()
    }
    /// The right-hand side τ − h(q, q̇) − J(q)ᵀF_tip of the last call,
    /// rounded to `f64` once.
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }
}

/// Forward dynamics with the bias forces and τ − h in the precise scalar `P`
/// (see the module documentation). Arguments as [`aba`](super::aba::aba), plus the scratch
/// (in `P`, and the `f64` workspace of the articulated-body solve). Allocates
/// nothing once `scratch` has seen as many tip wrenches and payloads as
/// `loads` holds.
///
/// # Panics
/// If a slice or the scratch does not have the model's number of joints, or
/// a payload's body is not a body of the model.
pub fn forward_dynamics_compensated<P: Scalar>(
    model: &Model,
    scratch: &mut CompensatedScratch<P>,
    q: &[f64],
    qd: &[f64],
    tau: &[f64],
    loads: Loads<'_, f64>,
    qdd: &mut [f64],
) {
    compensated(model, scratch, [q, qd, tau], loads, qdd)
}

/// [`forward_dynamics_compensated`], inlined into its caller so that the FMA
/// form (`solve_fma`) compiles it, and the algorithms it inlines, with FMA
/// enabled. (The public function is not inlined: a debug build keeps each
/// inlined call's locals apart, and a caller with several calls would need
/// a stack that many times as deep.)
#[inline(always)]
fn compensated<P: Scalar>(
    model: &Model,
    scratch: &mut CompensatedScratch<P>,
    [q, qd, tau]: [&[f64]; 3],
    loads: Loads<'_, f64>,
    qdd: &mut [f64],
) {
    // NQ and NV (n and n for a fixed base)
    let (nq, n) = (model.nq(), model.nv());
    assert!(
        q.len() == nq && qd.len() == n && tau.len() == n && qdd.len() == n && scratch.dof() == n,
        "forward_dynamics_compensated: slices and scratch must have the model's {n} joints (NQ/NV with a floating base)"
    );
    let CompensatedScratch {
        ws: ws_p,
        ws_f64: ws,
        q: qp,
        qd: qdp,
        h,
        tips: tips_p,
        payloads: payloads_p,
        rhs,
        refinements,
        qdd: qdd_p,
        residual,
        correction,
    } = scratch;
    for i in 0..nq {
        qp[i] = P::from_f64(q[i]);
    }
    for i in 0..n {
        qdp[i] = P::from_f64(qd[i]);
    }
    tips_p.clear();
    tips_p.extend(loads.tips.iter().map(|t| TipWrench {
        frame: t.frame,
        wrench: Force::new(Vec3::from_f64(&t.wrench.ang), Vec3::from_f64(&t.wrench.lin)),
    }));
    payloads_p.clear();
    payloads_p
        .extend(loads.payloads.iter().map(|p| BodyInertia { body: p.body, inertia: Inertia::from_f64(&p.inertia) }));
    let g = loads.gravity.map(Vec3::<P>::from_f64);
    // The loads in P; the armature counts only with q̈ (in the residuals).
    let loads_p = Loads::new(g.as_ref(), tips_p, payloads_p).with_armature(loads.armature);
    // Pass 0: u = τ − (h(q, q̇) + JᵀF_tip) in P, rounded once, and q̈ = M⁻¹u.
    // Each refinement: r = τ − RNEA(q, q̇, q̈) in P, rounded once, q̈ += M⁻¹r.
    // (One call of each algorithm: they are inlined, and a debug build's
    // stack holds each call's locals apart.)
    for pass in 0..=*refinements {
        let accelerations = if pass == 0 {
            None
        } else {
            for i in 0..n {
                qdd_p[i] = P::from_f64(qdd[i]);
            }
            Some(&qdd_p[..])
        };
        rnea(model, ws_p, qp, Some(qdp), accelerations, loads_p, h);
        let right = if pass == 0 { &mut *rhs } else { &mut *residual };
        for i in 0..n {
            right[i] = (P::from_f64(tau[i]) - h[i]).to_f64().unwrap_or(f64::NAN);
        }
        // (M + diag(armature)) x = right: the articulated-body algorithm at rest, without gravity.
        aba_at_rest(model, ws, q, right, loads, correction);
        for i in 0..n {
            qdd[i] = if pass == 0 { correction[i] } else { qdd[i] + correction[i] };
        }
    }
}

/// The compensated forward dynamics with its scratch, choosing at run time
/// how exact products are formed: by fused multiply-adds when the CPU has
/// them (the whole computation compiled with FMA enabled, about twice as fast),
/// else by Dekker's splitting ([`Compensated`]). Both give the same results
/// (exact products either way).
#[derive(Clone, Debug)]
pub enum CompensatedSolver {
    /// Products by Dekker's splitting, or FMA if the build already targets it.
    Portable(CompensatedScratch<Compensated>),
    /// Products by FMA instructions, detected at run time.
    Fused(CompensatedScratch<CompensatedFma>),
}

impl CompensatedSolver {
    /// The solver for `model`, with FMA when this CPU has it.
    pub fn new(model: &Model) -> Self {
        if fma_detected() {
            CompensatedSolver::Fused(CompensatedScratch::new(model))
        } else {
            CompensatedSolver::Portable(CompensatedScratch::new(model))
        }
    }
    /// The solver for `model` with Dekker's splitting, whatever the CPU (for comparisons).
    pub fn portable(model: &Model) -> Self {
        CompensatedSolver::Portable(CompensatedScratch::new(model))
    }
    /// Whether products use FMA instructions detected at run time.
    pub fn uses_fma(&self) -> bool {
        matches!(self, CompensatedSolver::Fused(_))
    }
    /// Takes `steps` steps of iterative refinement in each call (0, the
    /// default: none); see the [module documentation](self).
    pub fn set_refinement(&mut self, steps: usize) {
        match self {
            CompensatedSolver::Portable(s) => s.refinements = steps,
            CompensatedSolver::Fused(s) => s.refinements = steps,
        }
    }
    /// [`forward_dynamics_compensated`] with this solver's scratch.
    ///
    /// # Panics
    /// As [`forward_dynamics_compensated`].
    pub fn solve(&mut self, model: &Model, q: &[f64], qd: &[f64], tau: &[f64], loads: Loads<'_, f64>, qdd: &mut [f64]) {
        match self {
            CompensatedSolver::Portable(s) => forward_dynamics_compensated(model, s, q, qd, tau, loads, qdd),
            CompensatedSolver::Fused(s) => {
                #[cfg(target_arch = "x86_64")]
                // SAFETY: `Fused` is only built when the CPU has FMA (`fma_detected`).
                unsafe {
                    solve_fma(model, s, q, qd, tau, loads, qdd)
                }
                #[cfg(not(target_arch = "x86_64"))]
                forward_dynamics_compensated(model, s, q, qd, tau, loads, qdd)
            }
        }
    }
}

/// Whether to build the FMA variant: the CPU has FMA and the build does not
/// already use it everywhere.
fn fma_detected() -> bool {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(all(target_arch = "x86_64", not(target_feature = "fma"))))]
    {
        false
    }
}

/// [`forward_dynamics_compensated`] in `CompensatedFma`, compiled with FMA
/// enabled (the generic algorithms are instantiated, and inlined, here).
///
/// # Safety
/// The CPU must support FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn solve_fma(
    model: &Model,
    scratch: &mut CompensatedScratch<CompensatedFma>,
    q: &[f64],
    qd: &[f64],
    tau: &[f64],
    loads: Loads<'_, f64>,
    qdd: &mut [f64],
) {
    compensated(model, scratch, [q, qd, tau], loads, qdd)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::aba::aba;
    use crate::spatial::Inertia;

    /// Every load reaches the compensated forward dynamics: with gravity, a
    /// tip wrench, a payload and armature (on an ordinary state, where
    /// nothing cancels) it agrees with the articulated-body algorithm under
    /// the same loads, and each load changes the answer.
    #[test]
    fn takes_every_load_as_aba_does() {
        let model = Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap();
        let n = model.dof();
        let val = |k: usize, scale: f64| scale * (0.37 * k as f64 + 0.2).sin();
        let q: Vec<f64> = (0..n).map(|k| val(k, 2.0)).collect();
        let qd: Vec<f64> = (0..n).map(|k| val(k + 11, 1.5)).collect();
        let tau: Vec<f64> = (0..n).map(|k| val(k + 23, 10.0)).collect();
        let g = Vec3([0.0, 0.0, -9.81]);
        let tips =
            [TipWrench { frame: model.frames.len() - 1, wrench: Force::from_array([0.3, -0.2, 0.5, 4.0, -1.0, 2.5]) }];
        let payload = Inertia::from_mass_com_inertia(
            1.5,
            Vec3([0.05, 0.0, 0.1]),
            crate::spatial::Sym3([0.01, 0.02, 0.015, 0.0, 0.0, 0.0]),
        );
        let payloads = [BodyInertia { body: n - 1, inertia: payload }];
        let armature: Vec<f64> = (0..n).map(|k| 0.1 * (k % 2) as f64).collect();
        let all = Loads::gravity(&g).with_tips(&tips).with_payloads(&payloads).with_armature(Some(&armature));
        let mut ws = Workspace::<f64>::new(&model);
        // without and with refinement: its residual takes every load too
        for steps in [0, 1] {
            let mut scratch = CompensatedScratch::<Compensated>::new(&model).with_refinement(steps);
            let mut run = |loads: Loads<'_, f64>| {
                let (mut plain, mut comp) = (vec![0.0; n], vec![0.0; n]);
                aba(&model, &mut ws, &q, &qd, &tau, loads, &mut plain);
                forward_dynamics_compensated(&model, &mut scratch, &q, &qd, &tau, loads, &mut comp);
                let scale = plain.iter().fold(1.0f64, |m, x| m.max(x.abs()));
                for k in 0..n {
                    assert!((plain[k] - comp[k]).abs() <= 1e-12 * scale, "q̈[{k}]: {} vs {}", plain[k], comp[k]);
                }
                comp
            };
            let with_all = run(all);
            for fewer in
                [all.with_tips(&[]), all.with_payloads(&[]), all.with_armature(None), Loads { gravity: None, ..all }]
            {
                let other = run(fewer);
                assert!(other.iter().zip(&with_all).any(|(a, b)| (a - b).abs() > 1e-6), "a load had no effect");
            }
        }
    }
}
