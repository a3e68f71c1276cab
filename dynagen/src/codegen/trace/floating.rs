//! The functions of a floating-base module, traced from the floating-base
//! algorithms (`algorithms/floating/`): `q` has NQ = n + 7 entries (base
//! position, quaternion (x, y, z, w), joints), the velocity-side vectors
//! NV = n + 6 (the base's body twist, angular first, then the joints).
//! The base's orientation enters as a polynomial in the quaternion, so the
//! only sines and cosines are the joints' (`q[7 + i]`). The algorithms are
//! called through their dispatching forms, which send a floating model to
//! `algorithms/floating/` (and expand and project mimic joints first).

use super::{CodegenError, SceneLoads};
use crate::algorithms::derivatives::{self, DerivativeWorkspace, Dynamics, Formulation};
use crate::algorithms::{crba, rnea};
use crate::algorithms::{Loads, Workspace};
use crate::codegen::emit::Sizes;
use crate::codegen::{ForwardDynamicsMethod, Function};
use crate::scene::{dynamics, SceneModel};
use crate::symbolic::{Expr, Rewrites, Traced, Tracer};

/// Where a floating-base module's joint angles start in `q`.
pub(crate) const JOINTS_IN_Q: usize = 7;

/// Traces `f` of a floating-base `scene` without factoring: the functions
/// of the contract, `coriolis` and the derivatives (their ∂τ by
/// `formulation`, in the tangent space of the base's body twist), with the
/// scene's armature, friction and run-time loads (gravity in the world
/// frame, the tip wrench, payloads, on the base too; held constant in the
/// derivatives). Frame functions are traced in `frames.rs`.
pub(crate) fn trace_unfactored(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
    formulation: Formulation,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    let model = &scene.model;
    let sizes = Sizes::of(model);
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> =
        f.vectors().iter().map(|v| tracer.inputs(v, if *v == "q" { model.nq() } else { model.nv() })).collect();
    let loads = SceneLoads::of(scene, f, &tracer);
    let (g, tips, pl) = (loads.gravity.as_ref(), &loads.tips[..], &loads.payloads[..]);
    let mut ws = Workspace::<Expr>::new(model);
    let mut out = vec![tracer.constant(0.0); f.output_len(sizes)];
    let q = &args[0];
    match f {
        Function::InverseDynamics => {
            dynamics::inverse_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, pl), &mut out)
        }
        Function::MassMatrix => {
            crba::crba(model, &mut ws, q, Loads::new(None, &[], pl), &mut out);
            dynamics::add_armature_diagonal(scene, &mut out);
        }
        Function::BiasForces => {
            rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(g, &[], pl), &mut out);
            dynamics::add_friction(scene, &args[1], &mut out);
        }
        Function::GravityTorques => {
            if g.is_some() {
                rnea::rnea(model, &mut ws, q, None, None, Loads::new(g, &[], pl), &mut out)
            }
        }
        Function::Coriolis => rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(None, &[], pl), &mut out),
        Function::ForwardDynamics if method == ForwardDynamicsMethod::Ldlt => {
            dynamics::forward_dynamics_ldlt(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, pl), &mut out)
        }
        Function::ForwardDynamics => {
            dynamics::forward_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, pl), &mut out)
        }
        Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives | Function::MassMatrixInverse => {
            // The scene's dynamics (armature, friction), its run-time loads
            // held constant; M by the floating CRBA with payloads and armature.
            let nv = sizes.nv;
            let loads = dynamics::with_armature(scene, Loads::new(g, tips, pl));
            let d = Dynamics { model, loads, torques: scene, mass: None };
            let mut dw = DerivativeWorkspace::<Expr>::new(model);
            let (a, rest) = out.split_at_mut(nv * nv);
            let state = || [q.as_slice(), &args[1], &args[2]];
            match f {
                Function::InverseDynamicsDerivatives => {
                    derivatives::inverse_dynamics_derivatives(&d, &mut dw, state(), formulation, [a, rest], None)
                }
                Function::ForwardDynamicsDerivatives => {
                    let (b, c) = rest.split_at_mut(nv * nv);
                    derivatives::forward_dynamics_derivatives(&d, &mut dw, state(), formulation, [a, b, c])
                }
                _ => {
                    let mut m = vec![tracer.constant(0.0); nv * nv];
                    let mut linv = m.clone();
                    crba::crba(model, &mut ws, q, loads.inertias(), &mut m);
                    derivatives::mass_matrix_inverse(model, &mut m, &mut linv, a);
                }
            }
        }
        Function::FramePose(_)
        | Function::FrameJacobian(_)
        | Function::FrameWorldJacobian(_)
        | Function::FrameAccelerationBias(_) => unreachable!("traced in frames.rs"),
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(Traced::new(&f.rust_name(), &graph, &out))
}
