//! A serial chain with skewed placements and full inertias, so that nothing
//! folds away by accident of symmetry: the chain of the operation-count
//! growth test (`tests/codegen_growth.rs`, through the support module), of
//! the code-generation scaling example (`examples/codegen_scaling.rs`) and
//! of the split modules of `tests/build_split.rs` and
//! `tests/tests/generated_split.rs` in the workspace, which include this file.

use dynagen::model::{Inertial, JointDescription, RobotBuilder};
use dynagen::Model;

/// The chain of `n` revolute joints (axes cycling through z, y, x).
pub fn skewed_chain(n: usize) -> Model {
    let mut b = RobotBuilder::new("chain").link("l0", None);
    for i in 1..=n {
        let k = i as f64;
        b = b.link(
            &format!("l{i}"),
            Some(Inertial::new(1.0 + 0.1 * k, [0.05, 0.02, 0.2], [0.03, 0.04, 0.02, 0.001, -0.002, 0.003])),
        );
        let axis = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]][i % 3];
        let j = JointDescription::revolute(&format!("j{i}"), &format!("l{}", i - 1), &format!("l{i}"), axis)
            .origin([0.1, 0.02 * k, 0.3], [0.1 * k, 0.2, -0.3]);
        b = b.joint(j);
    }
    b.build().expect("a chain of physical links is a valid model")
}
