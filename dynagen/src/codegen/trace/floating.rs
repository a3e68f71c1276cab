//! The functions of a floating-base module, traced from the floating-base
//! algorithms (`algorithms/floating/`): `q` has NQ = n + 7 entries (base
//! position, quaternion (x, y, z, w), joints), the velocity-side vectors
//! NV = n + 6 (the base's body twist, angular first, then the joints).
//! The base's orientation enters as a polynomial in the quaternion, so the
//! only sines and cosines are the joints' (`q[7 + i]`). The algorithms are
//! called through their dispatching forms, which send a floating model to
//! `algorithms/floating/` (and expand and project mimic joints first).

use super::{CodegenError, SceneLoads};
use crate::algorithms::{crba, rnea};
use crate::algorithms::{Loads, Workspace};
use crate::codegen::emit::Sizes;
use crate::codegen::{ForwardDynamicsMethod, Function};
use crate::scene::{dynamics, SceneModel};
use crate::symbolic::{Expr, Rewrites, Traced, Tracer};

/// Where a floating-base module's joint angles start in `q`.
pub(crate) const JOINTS_IN_Q: usize = 7;

/// Traces `f` of a floating-base `scene` without factoring: the functions
/// of the contract and `coriolis`, with the scene's armature, friction and
/// run-time loads (gravity in the world frame, the tip wrench, payloads, on
/// the base too). Frame functions are traced in `frames.rs`.
pub(crate) fn trace_unfactored(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
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
        _ => {
            let name = &model.name;
            let what = format!("`{}` is not generated yet for a floating base", f.rust_name());
            return Err(CodegenError::Unsupported(format!("floating-base robot \"{name}\": {what}")));
        }
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(Traced::new(&f.rust_name(), &graph, &out))
}
