//! The trace stage: the traced functions, evaluated by the graph
//! interpreter, against the generic f64 solver on random states of every
//! bundled robot, and the UR5's operation counts.

mod support;

use dynagen::codegen::{generate, CodegenOptions, ForwardDynamicsMethod, Function};
use dynagen::symbolic::Rewrites;
use dynagen::{Model, Robot};
use nalgebra::DVector;
use support::{norm_rel_err, Rng};

fn check_model(model: &Model, options: &CodegenOptions, states: usize, tol: f64) {
    let n = model.dof();
    let module = generate(model, options).unwrap();
    // Every function of the module is traced (the forward dynamics both
    // ways, the one not emitted counted in the header), and each is checked
    // below.
    use ForwardDynamicsMethod::{Aba, Ldlt};
    let methods = vec![Aba, Ldlt];
    let mut expected: Vec<(Function, Option<ForwardDynamicsMethod>)> =
        [Function::InverseDynamics, Function::MassMatrix, Function::BiasForces, Function::GravityTorques]
            .into_iter()
            .map(|f| (f, None))
            .collect();
    expected.extend(methods.into_iter().map(|m| (Function::ForwardDynamics, Some(m))));
    let traced: Vec<_> = module.functions.iter().map(|f| (f.function.clone(), f.method)).collect();
    assert_eq!(traced, expected, "{}", model.name);
    let mut robot = Robot::new(model.clone());
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let mut worst = [0.0f64; 6];
    for _ in 0..states {
        let (q, qd, qdd, tau) = (rng.vec(n, 3.0), rng.vec(n, 2.0), rng.vec(n, 5.0), rng.vec(n, 20.0));
        let dv = |v: &Vec<f64>| DVector::from_column_slice(v);
        for (k, f) in module.functions.iter().enumerate() {
            let got = f.traced.eval(&[("q", &q), ("qd", &qd), ("qdd", &qdd), ("tau", &tau)]).unwrap();
            let want: Vec<f64> = match (&f.function, f.method) {
                (Function::InverseDynamics, None) => {
                    robot.inverse_dynamics(&dv(&q), &dv(&qd), &dv(&qdd)).unwrap().as_slice().to_vec()
                }
                (Function::MassMatrix, None) => robot.mass_matrix(&dv(&q)).unwrap().transpose().as_slice().to_vec(),
                (Function::BiasForces, None) => robot.bias_forces(&dv(&q), &dv(&qd)).unwrap().as_slice().to_vec(),
                (Function::GravityTorques, None) => robot.gravity_torques(&dv(&q)).unwrap().as_slice().to_vec(),
                (Function::ForwardDynamics, Some(Aba)) => {
                    robot.forward_dynamics(&dv(&q), &dv(&qd), &dv(&tau)).unwrap().as_slice().to_vec()
                }
                (Function::ForwardDynamics, Some(Ldlt)) => {
                    robot.forward_dynamics_ldlt(&dv(&q), &dv(&qd), &dv(&tau)).unwrap().as_slice().to_vec()
                }
                other => panic!("unexpected function {other:?}"),
            };
            let e = norm_rel_err(&got, &want, 1e-300);
            worst[k] = worst[k].max(e);
            assert!(e < tol, "{} {}: relative error {e:e}\n got {got:?}\nwant {want:?}", model.name, f.label());
        }
    }
    println!("{}: worst relative errors {:?}", model.name, worst.map(|e| format!("{e:.1e}")));
}

#[test]
fn interpreter_matches_generic_solver_on_bundled_robots() {
    for name in ["ur5", "panda", "torso_two_arms", "planar_2link"] {
        let model = support::model(name);
        check_model(&model, &CodegenOptions::default(), 50, 1e-12);
    }
}

/// A 12-joint chain with skewed placements, full inertias and a prismatic
/// joint: nothing folds by symmetry.
fn skewed_chain() -> Model {
    use dynagen::model::{Inertial, JointDescription, RobotBuilder};
    let mut b = RobotBuilder::new("skewed").link("l0", None);
    for i in 1..=12 {
        let k = i as f64;
        b = b.link(
            &format!("l{i}"),
            Some(Inertial::new(1.0 + 0.1 * k, [0.05, 0.02, 0.2], [0.03, 0.04, 0.02, 0.001, -0.002, 0.003])),
        );
        let (p, c) = (format!("l{}", i - 1), format!("l{i}"));
        let j = match i % 4 {
            0 => JointDescription::prismatic(&format!("j{i}"), &p, &c, [0.0, 0.6, 0.8]),
            1 => JointDescription::revolute(&format!("j{i}"), &p, &c, [0.0, 0.0, 1.0]),
            2 => JointDescription::continuous(&format!("j{i}"), &p, &c, [1.0, 2.0, 2.0]),
            _ => JointDescription::revolute(&format!("j{i}"), &p, &c, [1.0, 0.0, 0.0]),
        };
        b = b.joint(j.origin([0.1, 0.02 * k, 0.3], [0.1 * k, 0.2, -0.3]));
    }
    b.build().unwrap()
}

#[test]
fn interpreter_matches_generic_solver_on_a_skewed_chain() {
    check_model(&skewed_chain(), &CodegenOptions::default(), 20, 1e-12);
}

/// A two-joint arm with a skewed two-finger gripper: prismatic leaves on
/// rotated placements along a non-aligned axis, mirror images of each
/// other, with full inertias off their axes, and a third prismatic leaf on
/// the first link (code generation centres them, mirrors M's column and
/// folds their weights in g).
#[test]
fn interpreter_matches_generic_solver_on_a_skewed_gripper() {
    use dynagen::model::{Inertial, JointDescription, RobotBuilder};
    let inertia = [0.003, 0.004, 0.002, 0.0001, -0.0002, 0.0003];
    let mirrored = [0.003, 0.004, 0.002, -0.0001, 0.0002, 0.0003];
    let model = RobotBuilder::new("gripper")
        .link("base", None)
        .link("l1", Some(Inertial::new(2.0, [0.05, 0.02, 0.2], [0.03, 0.04, 0.02, 0.001, -0.002, 0.003])))
        .link("hand", Some(Inertial::new(0.8, [0.01, -0.02, 0.05], [0.01, 0.02, 0.015, 0.001, 0.0, -0.002])))
        .link("left", Some(Inertial::new(0.05, [0.01, 0.02, 0.03], inertia)))
        .link("right", Some(Inertial::new(0.05, [-0.01, 0.02, -0.03], mirrored)))
        .link("slider", Some(Inertial::new(0.3, [0.0, 0.05, 0.0], inertia)))
        .joint(JointDescription::revolute("j1", "base", "l1", [0.0, 0.0, 1.0]).origin([0.0, 0.0, 0.3], [0.0; 3]))
        .joint(
            JointDescription::revolute("j2", "l1", "hand", [1.0, 2.0, 2.0]).origin([0.1, 0.02, 0.4], [0.3, -0.2, 0.5]),
        )
        .joint(
            JointDescription::prismatic("f1", "hand", "left", [0.6, 0.0, 0.8])
                .origin([0.02, 0.03, 0.1], [0.4, 0.1, -0.7]),
        )
        .joint(
            JointDescription::prismatic("f2", "hand", "right", [-0.6, 0.0, -0.8])
                .origin([0.02, 0.03, 0.1], [0.4, 0.1, -0.7]),
        )
        .joint(
            JointDescription::prismatic("s", "l1", "slider", [0.0, 1.0, 0.0]).origin([0.0, 0.1, 0.05], [0.0, 0.0, 0.9]),
        )
        .build()
        .unwrap();
    check_model(&model, &CodegenOptions::default(), 20, 1e-12);
}

#[test]
fn interpreter_matches_without_snap_or_rewrites() {
    let model = support::model("ur5");
    let opts = CodegenOptions::default().snap_rounding(false).rewrites(Rewrites::exact());
    check_model(&model, &opts, 50, 1e-12);
    let opts = CodegenOptions::default().forward_dynamics(ForwardDynamicsMethod::Ldlt);
    check_model(&model, &opts, 10, 1e-12);
}

#[test]
fn ur5_op_counts() {
    let model = support::model("ur5");
    for (label, opts) in [
        ("default", CodegenOptions::default()),
        ("no snap", CodegenOptions::default().snap_rounding(false)),
        ("exact rewrites only", CodegenOptions::default().rewrites(Rewrites::exact())),
    ] {
        let module = generate(&model, &opts).unwrap();
        println!("UR5, {label} ({} constants snapped):", module.snapped.len());
        for (l, c) in module.op_counts() {
            println!("  {l:32} {c}");
        }
    }
}
