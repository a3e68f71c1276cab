//! Time integration of a floating-base robot: the explicit schemes of
//! [`integrators`](crate::algorithms::integrators) with every position
//! update `q ← q ⊕ δ` made on the configuration manifold by
//! [`super::integrate`] (the base by the exponential map of its
//! body twist, its quaternion renormalised; the joints by addition), never
//! `q += dt·q̇` for the base. Runge-Kutta is Runge-Kutta-Munthe-Kaas: the
//! stages are `q ⊕ θ` from the step's start, θ's slope the stage velocity
//! through `dexp⁻¹_θ` (the base's part; to the commutators fourth order
//! needs), so the base keeps fourth order too (the drift of a free-floating
//! tree's momentum with and without the correction: `docs/performance.md`).

use super::{aba::aba, integrate, integrate_scaled};
use crate::algorithms::integrators::{implicit_euler_on, rk4_stages, Integrator, IntegratorScratch, StepInputs};
use crate::algorithms::Workspace;
use crate::model::Model;
use crate::spatial::Motion;
use crate::Scalar;

/// `dexp⁻¹_θ(V)` to the terms RK4 needs, `V + ½[θ, V] + [θ, [θ, V]]/12`, with
/// the bracket `[θ, V] = θ ×ₘ V`: the rate of θ for which `q ⊕ θ` moves
/// with body twist V (the right-trivialised form; Munthe-Kaas).
fn dexp_inv<S: Scalar>(theta: &Motion<S>, v: &Motion<S>) -> Motion<S> {
    let b = theta.cross_motion(v);
    *v + b.scale(S::from_f64(0.5)) + theta.cross_motion(&b).scale(S::from_f64(1.0 / 12.0))
}

/// One step of `integrator` for a floating model: `q` (NQ) and `qd` (NV)
/// updated in place, under q̈ from the articulated-body algorithm.
///
/// # Panics
/// If the slices do not have NQ/NV entries, or the scratch is not the
/// model's. The implicit scheme solves for the new velocity v by Newton's
/// method as [`implicit_euler_with`](crate::algorithms::integrators::implicit_euler_with)
/// does, with the configuration q ⊕ dt·v.
pub fn step<S: Scalar>(
    integrator: Integrator,
    model: &Model,
    ws: &mut Workspace<S>,
    scratch: &mut IntegratorScratch<S>,
    inputs: &StepInputs<'_, S>,
    q: &mut [S],
    qd: &mut [S],
) {
    let (nq, nv) = (model.nq(), model.nv());
    assert!(
        q.len() == nq && qd.len() == nv && inputs.tau.len() == nv && scratch.q_stage.len() == nq,
        "floating step: q must have NQ = {nq} entries, qd and tau NV = {nv}, and the scratch be the model's"
    );
    let dt = inputs.dt;
    let accel = |q: &[S], qd: &[S], qdd: &mut [S]| aba(model, ws, q, qd, inputs.tau, inputs.loads, qdd);
    if integrator == Integrator::ImplicitEuler {
        let retract = |q0: &[S], dt: S, v: &[S], q1: &mut [S]| integrate_scaled(model, q0, v, dt, q1);
        implicit_euler_on(scratch, dt, q, qd, retract, accel);
        return;
    }
    let IntegratorScratch { qdd, q_stage, qd_stage, q_sum, qd_sum, delta, .. } = scratch;
    let mut accel = |q: &[S], qd: &[S], qdd: &mut [S]| aba(model, ws, q, qd, inputs.tau, inputs.loads, qdd);
    match integrator {
        Integrator::Euler | Integrator::SemiImplicitEuler => {
            accel(q, qd, qdd);
            let semi = integrator == Integrator::SemiImplicitEuler;
            for k in 0..nv {
                let new = qd[k] + dt * qdd[k];
                // the step of the configuration: dt·q̇, old or new
                q_sum[k] = dt * if semi { new } else { qd[k] };
                qd[k] = new;
            }
            q_stage.copy_from_slice(q);
            integrate(model, q_stage, q_sum, q);
        }
        Integrator::Rk4 => {
            q_stage.copy_from_slice(q);
            qd_stage.copy_from_slice(qd);
            q_sum.fill(S::zero());
            qd_sum.fill(S::zero());
            // delta: the stage's configuration offset θ (q_stage = q ⊕ θ), velocity-side
            delta.fill(S::zero());
            for (weight, next) in rk4_stages(dt) {
                accel(q_stage, qd_stage, qdd);
                // the slope of θ: the base's part through dexp⁻¹ at θ
                let base = dexp_inv(&super::base_motion(delta), &super::base_motion(qd_stage)).to_array();
                for k in 0..nv {
                    let slope = if k < 6 { base[k] } else { qd_stage[k] };
                    q_sum[k] += weight * slope;
                    qd_sum[k] += weight * qdd[k];
                    if let Some(c) = next {
                        delta[k] = c * slope;
                        qd_stage[k] = qd[k] + c * qdd[k];
                    }
                }
                if next.is_some() {
                    integrate(model, q, delta, q_stage);
                }
            }
            let sixth = dt / S::from_f64(6.0);
            for k in 0..nv {
                delta[k] = sixth * q_sum[k];
                qd[k] += sixth * qd_sum[k];
            }
            q_stage.copy_from_slice(q);
            integrate(model, q_stage, delta, q);
        }
        Integrator::ImplicitEuler => unreachable!("stepped above"),
    }
}
