//! The functions of a floating-base module, traced from the floating-base
//! algorithms (`algorithms/floating/`): `q` has NQ = n + 7 entries (base
//! position, quaternion (x, y, z, w), joints), the velocity-side vectors
//! NV = n + 6 (the base's body twist, angular first, then the joints).
//! The base's orientation enters as a polynomial in the quaternion, so the
//! only sines and cosines are the joints' (`q[7 + i]`).

use super::CodegenError;
use crate::algorithms::derivatives::{self, DerivativeWorkspace, Dynamics, Formulation, RigidBodyOnly};
use crate::algorithms::floating::{aba, crba, forward_dynamics, rnea};
use crate::algorithms::{Loads, Workspace};
use crate::codegen::emit::Sizes;
use crate::codegen::{ForwardDynamicsMethod, Function};
use crate::scene::{ResolvedGravity, Scene, SceneModel};
use crate::spatial::Vec3;
use crate::symbolic::{Expr, Rewrites, Traced, Tracer};

/// Where a floating-base module's joint angles start in `q`.
pub(crate) const JOINTS_IN_Q: usize = 7;

/// Traces `f` of a floating-base `scene` without factoring. Only the default
/// scene, the five functions of the contract and the derivatives (their
/// ∂τ by `formulation`, in the tangent space of the base's body twist) are
/// supported so far.
pub(crate) fn trace_unfactored(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
    formulation: Formulation,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    let unsupported =
        |what: String| CodegenError::Unsupported(format!("floating-base robot \"{}\": {what}", scene.model.name));
    if scene.scene != Scene::default() {
        return Err(unsupported("scenes other than the default one are not generated yet".into()));
    }
    if !matches!(
        f,
        Function::InverseDynamics
            | Function::MassMatrix
            | Function::BiasForces
            | Function::GravityTorques
            | Function::ForwardDynamics
            | Function::InverseDynamicsDerivatives
            | Function::ForwardDynamicsDerivatives
            | Function::MassMatrixInverse
    ) {
        return Err(unsupported(format!("`{}` is not generated yet for a floating base", f.rust_name())));
    }
    let model = &scene.model;
    let sizes = Sizes::of(model);
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> = f.params(scene).iter().map(|p| tracer.inputs(&p.name, p.len_value(sizes))).collect();
    let gravity: Option<Vec3<Expr>> = match scene.gravity {
        ResolvedGravity::Constant(_) => Some(Vec3::from_f64(&model.gravity)),
        _ => None,
    };
    let g = gravity.as_ref();
    let mut ws = Workspace::<Expr>::new(model);
    let mut out = vec![tracer.constant(0.0); f.output_len(sizes)];
    let q = &args[0];
    match f {
        Function::InverseDynamics => {
            rnea::rnea(model, &mut ws, q, Some(&args[1]), Some(&args[2]), Loads::new(g, &[], &[]), &mut out)
        }
        Function::MassMatrix => crba::crba(model, &mut ws, q, Loads::none(), &mut out),
        Function::BiasForces => rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(g, &[], &[]), &mut out),
        Function::GravityTorques => {
            if g.is_some() {
                rnea::rnea(model, &mut ws, q, None, None, Loads::new(g, &[], &[]), &mut out)
            }
        }
        Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives | Function::MassMatrixInverse => {
            let nv = sizes.nv;
            let d = Dynamics { model, loads: Loads::new(g, &[], &[]), torques: &RigidBodyOnly, mass: None };
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
                    crba::crba(model, &mut ws, q, Loads::none(), &mut m);
                    derivatives::mass_matrix_inverse(model, &mut m, &mut linv, a);
                }
            }
        }
        _ if method == ForwardDynamicsMethod::Ldlt => forward_dynamics::forward_dynamics_ldlt(
            model,
            &mut ws,
            q,
            &args[1],
            &args[2],
            Loads::new(g, &[], &[]),
            &mut out,
        ),
        _ => aba::aba(model, &mut ws, q, &args[1], &args[2], Loads::new(g, &[], &[]), &mut out),
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(Traced::new(&f.rust_name(), &graph, &out))
}
