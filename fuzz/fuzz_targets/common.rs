//! What both targets do with a model that loaded: check the invariants the
//! rest of dynagen relies on, and run every algorithm once (none may panic,
//! whatever finite numbers the model holds).

use dynagen::{Model, Robot};
use nalgebra::{DVector, Vector6};

/// Models larger than this are checked but not run (the mass matrix is n²).
const RUN_UP_TO_DOF: usize = 40;

pub fn exercise(model: Model) {
    let n = model.dof();
    for (i, b) in model.bodies.iter().enumerate() {
        if let Some(p) = b.parent {
            assert!(p < i, "body {i} has parent {p}: not topological");
        }
        assert!(b.joint.placement.is_finite(), "joint {} placement not finite", b.joint.name);
        assert!(b.joint.axis_norm.is_finite() && b.joint.axis_norm > 0.0, "joint {} axis", b.joint.name);
        assert!(b.inertia.mass.is_finite() && b.inertia.mass >= 0.0, "body {} mass", b.name);
    }
    let mut names: Vec<&str> = model.frames.iter().map(|f| f.name.as_str()).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(before, names.len(), "two frames share a name");
    for f in &model.frames {
        assert!(f.placement.is_finite(), "frame {} placement not finite", f.name);
        assert!(f.body.is_none_or(|b| b < n), "frame {} on body {:?} of {n}", f.name, f.body);
    }
    let mut joints: Vec<&str> = model.joint_names();
    joints.sort_unstable();
    joints.dedup();
    assert_eq!(joints.len(), n, "two joints share a name");
    if n > RUN_UP_TO_DOF {
        return;
    }
    let frames: Vec<String> = model.frames.iter().map(|f| f.name.clone()).collect();
    let mut robot = Robot::new(model);
    let q = DVector::from_fn(n, |i, _| 0.3 - 0.1 * i as f64);
    let qd = DVector::from_fn(n, |i, _| 0.5 + 0.2 * i as f64);
    let tau = robot.inverse_dynamics(&q, &qd, &qd).expect("right lengths");
    robot.mass_matrix(&q).expect("right lengths");
    robot.bias_forces(&q, &qd).expect("right lengths");
    robot.gravity_torques(&q).expect("right lengths");
    robot.forward_dynamics(&q, &qd, &tau).expect("right lengths");
    robot.forward_dynamics_ldlt(&q, &qd, &tau).expect("right lengths");
    for f in frames.iter().take(8) {
        robot.frame_pose(f, &q).expect("a frame of the model");
        robot.space_jacobian(f, &q).expect("a frame of the model");
        robot.body_jacobian(f, &q).expect("a frame of the model");
    }
    if let Some(f) = frames.last() {
        robot.set_tip_wrench(f, Vector6::new(0.1, 0.2, 0.3, 1.0, 2.0, 3.0)).expect("a frame of the model");
        robot.inverse_dynamics(&q, &qd, &qd).expect("right lengths");
    }
}
