//! The operation count of the generic recursion, for comparison with the
//! generated code's: the generic algorithm run on the [`Counting`] scalar.

use super::FunctionKind;
use crate::algorithms::Workspace;
use crate::model::Model;
use crate::scalar::{Counting, Scalar};
use crate::spatial::Vec3;
use crate::symbolic::OpCount;

/// The operations the generic solver does for one call of `kind` on `model`
/// (the same algorithm the generated function was traced from, with every
/// model constant used as a number at run time; the work space is set up
/// beforehand and not counted). The state is a fixed non-trivial one; the
/// count does not depend on it, as the algorithms never branch on the state.
pub fn generic_op_count(model: &Model, kind: FunctionKind) -> OpCount {
    let n = model.dof();
    let args: Vec<Vec<Counting>> = (0..kind.inputs().len())
        .map(|k| (0..n).map(|i| Counting(0.3 + (0.1 + 0.3 * k as f64) * (i as f64 + 1.0))).collect())
        .collect();
    let mut ws = Workspace::<Counting>::new(model);
    let g = Vec3::<Counting>::from_f64(&model.gravity);
    let mut out = vec![Counting::zero(); if kind.is_matrix() { n * n } else { n }];
    let ((), ops) = Counting::count(|| kind.run(model, &mut ws, &args, &g, &mut out));
    ops
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
        for kind in FunctionKind::ALL {
            let generic = generic_op_count(&model, kind);
            let traced = super::super::trace(&model, kind, Default::default()).unwrap().op_count();
            // Two joints: two sin_cos per pass over the tree (LᵀDL forward
            // dynamics makes two: CRBA for M, RNEA for h).
            let passes = if kind == FunctionKind::ForwardDynamicsLdlt { 2 } else { 1 };
            assert_eq!(generic.sin_cos, 2 * passes, "{kind:?}");
            assert!(generic.total() > traced.total(), "{kind:?}: generic {generic} vs traced {traced}");
        }
    }
}
