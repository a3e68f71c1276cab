//! The operation count of the generic recursion, for comparison with the
//! generated code's: the generic algorithm run on the [`Counting`] scalar.

use crate::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation, RigidBodyOnly};
use crate::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads, Workspace};
use crate::codegen::{ForwardDynamicsMethod, Function};
use crate::model::Model;
use crate::scalar::{Counting, Scalar};
use crate::spatial::Vec3;
use crate::symbolic::OpCount;

/// The operations the generic solver does for one call of `f` on `model`
/// (the same algorithm the generated function was traced from, with every
/// model constant used as a number at run time; the work space is set up
/// beforehand and not counted; `method` picks the forward dynamics'). The
/// state is a fixed non-trivial one; the count does not depend on it, as
/// the algorithms never branch on the state. `None` for a frame the model
/// does not have.
pub fn generic_op_count(model: &Model, f: &Function, method: ForwardDynamicsMethod) -> Option<OpCount> {
    // q has NQ entries, the velocity-side vectors NV (both n on a fixed base);
    // rnea, crba, aba and the LᵀDL forward dynamics take a floating model to
    // its own algorithms.
    let args: Vec<Vec<Counting>> = f
        .vectors()
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let len = if *v == "q" { model.nq() } else { model.nv() };
            (0..len).map(|i| Counting(0.3 + (0.1 + 0.3 * k as f64) * (i as f64 + 1.0))).collect()
        })
        .collect();
    let mut ws = Workspace::<Counting>::new(model);
    let g = Vec3::<Counting>::from_f64(&model.gravity);
    let mut out = vec![Counting::zero(); f.output_len(crate::codegen::emit::Sizes::of(model))];
    let frame = match f.frame() {
        Some(name) => Some(model.frame_index(name)?),
        None => None,
    };
    let mut dw = DerivativeWorkspace::<Counting>::new(model);
    let mut linv = vec![Counting::zero(); model.nv() * model.nv()];
    let (ws, out, a, g) = (&mut ws, &mut out, &args, Some(&g));
    let loads = Loads::new(g, &[], &[]);
    // The generic solver's derivatives: the analytical recursion.
    let dynamics = Dynamics { model, loads, torques: &RigidBodyOnly, mass: None };
    let analytical = Formulation::Analytical;
    let ((), ops) = Counting::count(|| match f {
        Function::InverseDynamics => rnea::rnea(model, ws, &a[0], Some(&a[1]), Some(&a[2]), loads, out),
        Function::MassMatrix => crba::crba(model, ws, &a[0], Loads::none(), out),
        Function::BiasForces => bias::bias_forces(model, ws, &a[0], &a[1], g, out),
        Function::GravityTorques => bias::gravity_torques(model, ws, &a[0], g.expect("given"), out),
        Function::Coriolis => bias::coriolis_torques(model, ws, &a[0], &a[1], out),
        Function::ForwardDynamics if method == ForwardDynamicsMethod::Ldlt => {
            forward_dynamics::forward_dynamics_ldlt(model, ws, &a[0], &a[1], &a[2], loads, out)
        }
        Function::ForwardDynamics => aba::aba(model, ws, &a[0], &a[1], &a[2], loads, out),
        Function::InverseDynamicsDerivatives => {
            let (x, y) = out.split_at_mut(model.nv() * model.nv());
            d::inverse_dynamics_derivatives(&dynamics, &mut dw, [&a[0], &a[1], &a[2]], analytical, [x, y], None)
        }
        Function::ForwardDynamicsDerivatives => {
            let nv = model.nv();
            let (x, rest) = out.split_at_mut(nv * nv);
            let (y, z) = rest.split_at_mut(nv * nv);
            d::forward_dynamics_derivatives(&dynamics, &mut dw, [&a[0], &a[1], &a[2]], analytical, [x, y, z])
        }
        Function::MassMatrixInverse => {
            let mut m = std::mem::take(&mut ws.mat);
            crba::crba(model, ws, &a[0], Loads::none(), &mut m);
            d::mass_matrix_inverse(model, &mut m, &mut linv, out);
            ws.mat = m;
        }
        Function::FramePose(_)
        | Function::FrameJacobian(_)
        | Function::FrameWorldJacobian(_)
        | Function::FrameAccelerationBias(_) => {
            super::frames::frame_outputs(model, ws, f, frame.expect("looked up above"), a, out)
        }
    });
    Some(ops)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Inertial, JointDescription, RobotBuilder};

    #[test]
    fn the_generic_recursion_does_one_sin_cos_per_joint_and_pass_and_more_ops_than_the_trace() {
        let model = RobotBuilder::new("two")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.0, 0.0, -0.5], [0.1, 0.1, 0.01, 0.0, 0.0, 0.0])))
            .link("b", Some(Inertial::new(2.0, [0.1, 0.0, -0.3], [0.2, 0.1, 0.05, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j1", "base", "a", [0.0, 1.0, 0.0]))
            .joint(JointDescription::revolute("j2", "a", "b", [1.0, 0.0, 0.0]).origin([0.0, 0.0, -1.0], [0.0; 3]))
            .build()
            .unwrap();
        let scene = crate::scene::Scene::default().apply(&model).unwrap();
        let methods = [ForwardDynamicsMethod::Aba, ForwardDynamicsMethod::Ldlt];
        for (f, method) in
            Function::DEFAULT.iter().map(|f| (f, methods[0])).chain([(&Function::ForwardDynamics, methods[1])])
        {
            let generic = generic_op_count(&model, f, method).unwrap();
            let traced = super::super::trace(&scene, f, method, Default::default()).unwrap().op_count();
            // Two joints: two sin_cos per pass over the tree (LᵀDL forward
            // dynamics makes two: CRBA for M, RNEA for h).
            let passes = if method == ForwardDynamicsMethod::Ldlt { 2 } else { 1 };
            assert_eq!(generic.sin_cos, 2 * passes, "{f:?} {method:?}");
            assert!(generic.total() > traced.total(), "{f:?} {method:?}: generic {generic} vs traced {traced}");
        }
    }
}
