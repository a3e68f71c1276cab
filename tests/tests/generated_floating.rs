//! The compiled floating-base modules (written by `build.rs`) against the
//! generic solver, at random unit quaternions and |q̇| up to 50: the
//! quadruped's against the floating-base algorithms, the legged
//! manipulator's controller scene (inputs, contact frames) against
//! `SceneRobot`; the generated code computes what the generic solver
//! computes, with the contract's NQ/NV signatures.

use approx::assert_relative_eq;
use dynagen::algorithms::floating::{aba, crba, rnea};
use dynagen::algorithms::{Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use dynagen_tests::{norm_rel_err, normalize_quaternion, workspace_root, Rng};

#[allow(dead_code)] // the module's helpers this test does not call
mod quad {
    include!(concat!(env!("OUT_DIR"), "/quadruped12_floating.rs"));
}

#[test]
fn the_compiled_floating_quadruped_matches_the_generic_solver() {
    let model =
        Model::from_urdf_file(workspace_root().join("dynagen/robots/quadruped12.urdf")).unwrap().with_floating_base();
    assert_eq!((quad::DOF, quad::NQ, quad::NV), (model.dof(), model.nq(), model.nv()));
    let names: Vec<&str> = model.joint_names();
    assert_eq!(quad::JOINT_NAMES.to_vec(), names);
    let g = Vec3::from_f64(&model.gravity);
    let mut ws = Workspace::<f64>::new(&model);
    let mut rng = Rng::new(5);
    let mut worst = 0.0f64;
    for k in 0..50 {
        let speed = if k % 2 == 0 { 2.0 } else { 50.0 };
        let mut q: [f64; quad::NQ] = core::array::from_fn(|_| rng.range(-1.0, 1.0));
        normalize_quaternion(&mut q);
        let mut v = |s: f64| -> [f64; quad::NV] { core::array::from_fn(|_| rng.range(-s, s)) };
        let (qd, qdd, tau) = (v(speed), v(5.0), v(20.0));
        let nv = quad::NV;
        let mut want = vec![0.0; nv];
        let mut check = |got: &[f64], want: &[f64], what: &str| {
            let e = norm_rel_err(got, want, 1e-300);
            assert!(e < 1e-12, "{what} at state {k}: relative error {e:e}");
            worst = worst.max(e);
        };
        rnea::rnea(&model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut want);
        check(&quad::inverse_dynamics(&q, &qd, &qdd), &want, "tau");
        rnea::rnea(&model, &mut ws, &q, Some(&qd), None, Loads::gravity(&g), &mut want);
        check(&quad::bias_forces(&q, &qd), &want, "h");
        rnea::rnea(&model, &mut ws, &q, None, None, Loads::gravity(&g), &mut want);
        check(&quad::gravity_torques(&q), &want, "g");
        aba::aba(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut want);
        check(&quad::forward_dynamics(&q, &qd, &tau), &want, "qdd");
        let mut m = vec![0.0; nv * nv];
        crba::crba(&model, &mut ws, &q, Loads::none(), &mut m);
        check(quad::mass_matrix(&q).as_flattened(), &m, "M");
    }
    println!("floating quadruped, compiled: worst relative error {worst:.1e}");
}

#[allow(dead_code)] // the module's helpers this test does not call
mod humanoid {
    include!(concat!(env!("OUT_DIR"), "/humanoid32_floating_mass_matrix.rs"));
}

/// The floating humanoid's M, whose body stores each entry where it is
/// computed (a body of more than `EARLY_STORES_MIN_LETS` statements), not as
/// one array literal at the end.
#[test]
fn the_compiled_floating_humanoid_mass_matrix_matches_the_generic_solver() {
    let source = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/humanoid32_floating_mass_matrix.rs")).unwrap();
    assert!(source.contains("let mut out = [[0.0; NV]; NV];"), "the humanoid's M is written entry by entry");
    let model =
        Model::from_urdf_file(workspace_root().join("dynagen/robots/humanoid32.urdf")).unwrap().with_floating_base();
    let mut ws = Workspace::<f64>::new(&model);
    let mut rng = Rng::new(7);
    let nv = humanoid::NV;
    for k in 0..20 {
        let mut q: [f64; humanoid::NQ] = core::array::from_fn(|_| rng.range(-3.0, 3.0));
        normalize_quaternion(&mut q);
        let mut want = vec![0.0; nv * nv];
        crba::crba(&model, &mut ws, &q, Loads::none(), &mut want);
        let e = norm_rel_err(humanoid::mass_matrix(&q).as_flattened(), &want, 1e-300);
        assert!(e < 1e-12, "M at state {k}: relative error {e:e}");
    }
}

#[allow(dead_code)] // the modules' helpers this test does not call
mod loops {
    pub mod humanoid {
        include!(concat!(env!("OUT_DIR"), "/humanoid32_branch_loops.rs"));
    }
    pub mod quadruped {
        include!(concat!(env!("OUT_DIR"), "/quadruped12_branch_loops.rs"));
    }
    pub mod quadruped_no_dispatch {
        include!(concat!(env!("OUT_DIR"), "/quadruped12_branch_loops_no_dispatch.rs"));
    }
    pub mod quadruped_f32 {
        include!(concat!(env!("OUT_DIR"), "/quadruped12_branch_loops_f32.rs"));
    }
    pub mod motors {
        include!(concat!(env!("OUT_DIR"), "/quadruped12_motors.rs"));
    }
}

/// The quadruped with motors (`dynagen_tests::quadruped_motors_scene`:
/// armature, a little different on each leg, and viscous and Coulomb
/// friction on every joint), compiled with its legs in lanes, against the
/// generic solver under the same scene: the forward dynamics' legs subtract
/// their friction (a square root in every lane) and add their armature
/// themselves.
#[test]
fn the_compiled_legs_with_motors_match_the_scene_robot() {
    use dynagen::scene::SceneRobot;
    use dynagen_tests::quadruped_motors_scene;
    use loops::motors as module;
    use nalgebra::DVector;
    let source = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/quadruped12_motors.rs")).unwrap();
    for name in ["inverse_dynamics", "mass_matrix", "bias_forces", "forward_dynamics"] {
        assert!(source.contains(&format!("{name}_branch0_run::<")), "{name}'s legs run in lanes");
    }
    assert!(source.contains(".sqrt()"), "the legs' Coulomb friction, in lanes");
    let model =
        Model::from_urdf_file(workspace_root().join("dynagen/robots/quadruped12.urdf")).unwrap().with_floating_base();
    let mut robot = SceneRobot::new(quadruped_motors_scene().apply(&model).unwrap());
    let mut rng = Rng::new(5);
    let d = |x: &[f64]| DVector::from_column_slice(x);
    for k in 0..20 {
        let mut q: [f64; module::NQ] = core::array::from_fn(|_| rng.range(-3.0, 3.0));
        normalize_quaternion(&mut q);
        let speed = if k % 2 == 0 { 50.0 } else { 0.5 };
        let qd: [f64; module::NV] = core::array::from_fn(|_| rng.range(-speed, speed));
        let qdd: [f64; module::NV] = core::array::from_fn(|_| rng.range(-10.0, 10.0));
        let tau: [f64; module::NV] = core::array::from_fn(|_| rng.range(-20.0, 20.0));
        let (qv, qdv) = (d(&q), d(&qd));
        let want = robot.forward_dynamics(&qv, &qdv, &d(&tau)).unwrap();
        assert_relative_eq!(d(&module::forward_dynamics(&q, &qd, &tau)), want, max_relative = 1e-12, epsilon = 1e-12);
        let want = robot.inverse_dynamics(&qv, &qdv, &d(&qdd)).unwrap();
        assert_relative_eq!(d(&module::inverse_dynamics(&q, &qd, &qdd)), want, max_relative = 1e-12, epsilon = 1e-11);
        let want = robot.bias_forces(&qv, &qdv).unwrap();
        assert_relative_eq!(d(&module::bias_forces(&q, &qd)), want, max_relative = 1e-12, epsilon = 1e-11);
        let want = robot.mass_matrix(&qv).unwrap();
        let got = nalgebra::DMatrix::from_row_slice(module::NV, module::NV, module::mass_matrix(&q).as_flattened());
        assert_relative_eq!(got, want, max_relative = 1e-12, epsilon = 1e-13);
    }
}

/// τ, M, h and q̈ with the legs (and the humanoid's arms) run as one body
/// over a table of their constants (`branch_loops`), compiled, against the
/// generic RNEA, CRBA and ABA on random states (|q̇| up to about 50), in each
/// form the body takes: in vector
/// lanes, two legs to a register (the humanoid's; the quadruped's without
/// the run-time dispatch in a default build) or four (the quadruped's with
/// it, on a processor with AVX2), and a scalar loop (f32, ≤ 1e-4).
#[test]
fn the_compiled_branch_loops_match_the_generic_solver() {
    macro_rules! check {
        ($module:ident, $file:literal, $robot:literal, $lanes:literal, $t:ty, $form:expr, $also:literal, $tol:expr) => {{
            use loops::$module as module;
            let file = concat!(env!("OUT_DIR"), "/", $file);
            let source = std::fs::read_to_string(file).unwrap();
            for name in ["inverse_dynamics", "mass_matrix", "bias_forces", "forward_dynamics"] {
                let table = format!("const {}_BRANCH0: [[{}; ", name.to_uppercase(), stringify!($t));
                assert!(source.contains(&table), "{}: {name} has a table of its legs' constants", $file);
                assert!(source.contains(&format!("; {}] = [", $lanes)), "{}: one row per leg", $file);
                let form = $form.replace("{}", name);
                assert!(source.contains(&form), "{}: {name}'s legs run as {form}", $file);
            }
            assert!(source.contains($also), "{}: {}", $file, $also);
            let counted = format!("emitted with branches in loops ({} × ", $lanes);
            assert!(source.contains(&counted), "{}: the header counts the loop's operations", $file);
            let path = workspace_root().join(concat!("dynagen/robots/", $robot, ".urdf"));
            let model = Model::from_urdf_file(path).unwrap().with_floating_base();
            let mut ws = Workspace::<f64>::new(&model);
            let mut rng = Rng::new(11);
            let g = model.gravity;
            let wide = |x: &[$t]| x.iter().map(|&v| v as f64).collect::<Vec<f64>>();
            for k in 0..20 {
                let mut q: [f64; module::NQ] = core::array::from_fn(|_| rng.range(-3.0, 3.0));
                normalize_quaternion(&mut q);
                let speed = if k % 2 == 0 { 50.0 } else { 2.0 };
                let qd: [f64; module::NV] = core::array::from_fn(|_| rng.range(-speed, speed));
                let qdd: [f64; module::NV] = core::array::from_fn(|_| rng.range(-10.0, 10.0));
                // The state as the module's scalar holds it, and back.
                let (q, qd, qdd) = (q.map(|v| v as $t), qd.map(|v| v as $t), qdd.map(|v| v as $t));
                let (q64, qd64, qdd64) = (wide(&q), wide(&qd), wide(&qdd));
                let mut want = vec![0.0; module::NV];
                rnea::rnea(&model, &mut ws, &q64, Some(&qd64), Some(&qdd64), Loads::gravity(&g), &mut want);
                let e = norm_rel_err(&wide(&module::inverse_dynamics(&q, &qd, &qdd)), &want, 1e-300);
                assert!(e < $tol, "{} τ at state {k}: relative error {e:e}", $file);
                rnea::rnea(&model, &mut ws, &q64, Some(&qd64), None, Loads::gravity(&g), &mut want);
                let e = norm_rel_err(&wide(&module::bias_forces(&q, &qd)), &want, 1e-300);
                assert!(e < $tol, "{} h at state {k}: relative error {e:e}", $file);
                let tau: [f64; module::NV] = core::array::from_fn(|_| rng.range(-20.0, 20.0));
                let tau = tau.map(|v| v as $t);
                aba::aba(&model, &mut ws, &q64, &qd64, &wide(&tau), Loads::gravity(&g), &mut want);
                let e = norm_rel_err(&wide(&module::forward_dynamics(&q, &qd, &tau)), &want, 1e-300);
                assert!(e < $tol, "{} q̈ at state {k}: relative error {e:e}", $file);
                let mut want = vec![0.0; module::NV * module::NV];
                crba::crba(&model, &mut ws, &q64, Loads::none(), &mut want);
                let e = norm_rel_err(&wide(module::mass_matrix(&q).as_flattened()), &want, 1e-300);
                assert!(e < $tol, "{} M at state {k}: relative error {e:e}", $file);
            }
        }};
    }
    let (lanes, looped) = ("{}_branch0_run::<", "{}_branch0(");
    check!(humanoid, "humanoid32_branch_loops.rs", "humanoid32", 2, f64, lanes, "_run::<I, 2>(", 1e-12);
    check!(quadruped, "quadruped12_branch_loops.rs", "quadruped12", 4, f64, lanes, "if I::QUADS {", 1e-12);
    check!(
        quadruped_no_dispatch,
        "quadruped12_branch_loops_no_dispatch.rs",
        "quadruped12",
        4,
        f64,
        lanes,
        "if Baseline::QUADS {",
        1e-12
    );
    check!(quadruped_f32, "quadruped12_branch_loops_f32.rs", "quadruped12", 4, f32, looped, "for l in 0..4 {", 1e-4);
}

#[allow(dead_code)] // the module's helpers this test does not call
mod controller {
    include!(concat!(env!("OUT_DIR"), "/legged_manipulator_controller.rs"));
}

/// The legged manipulator's controller scene (`dynagen/scenes/
/// legged_manipulator.toml`: armature and friction on the joints, the
/// tool's wrench and the grasped payload as run-time inputs, the feet and
/// the tool as contact frames), compiled, against the generic solver under
/// the same scene ([`SceneRobot`]).
#[test]
fn the_compiled_legged_manipulator_controller_matches_the_scene_robot() {
    use dynagen::scene::{PayloadInertia, SceneFile, SceneInputs, SceneRobot};
    use nalgebra::{DVector, Vector6};
    let model = Model::from_urdf_file(workspace_root().join("dynagen/robots/legged_manipulator.urdf"))
        .unwrap()
        .with_floating_base();
    let file = SceneFile::from_toml_file(workspace_root().join("dynagen/scenes/legged_manipulator.toml")).unwrap();
    let mut robot = SceneRobot::new(file.scene.apply(&model).unwrap());
    assert_eq!((controller::NQ, controller::NV), (robot.nq(), robot.nv()));
    let mut rng = Rng::new(9);
    let mut worst = 0.0f64;
    for k in 0..20 {
        let mut q: [f64; controller::NQ] = core::array::from_fn(|_| rng.range(-1.5, 1.5));
        normalize_quaternion(&mut q);
        let speed = if k % 2 == 0 { 2.0 } else { 30.0 };
        let mut v = |s: f64| -> [f64; controller::NV] { core::array::from_fn(|_| rng.range(-s, s)) };
        let (qd, qdd, tau) = (v(speed), v(5.0), v(20.0));
        let f_tip: [f64; 6] = core::array::from_fn(|_| rng.range(-10.0, 10.0));
        let p = PayloadInertia::new(rng.range(0.2, 1.0), [0.02, -0.01, 0.03], [4e-4, 5e-4, 3e-4, 1e-5, 0.0, 0.0]);
        let payload = [p.mass, p.com[0], p.com[1], p.com[2], 4e-4, 5e-4, 3e-4, 1e-5, 0.0, 0.0];
        let values = [p];
        let inputs = SceneInputs { tip_wrench: Some(Vector6::from(f_tip)), payloads: &values, ..Default::default() };
        let no_tip = SceneInputs { payloads: &values, ..Default::default() };
        let d = |x: &[f64]| DVector::from_column_slice(x);
        let (qv, qdv) = (d(&q), d(&qd));
        let mut check = |what: &str, got: &[f64], want: &[f64]| {
            let e = norm_rel_err(got, want, 1e-300);
            assert!(e < 1e-12, "{what} at state {k}: relative error {e:e}");
            worst = worst.max(e);
        };
        let want = robot.inverse_dynamics_with(&qv, &qdv, &d(&qdd), &inputs).unwrap();
        check("tau", &controller::inverse_dynamics(&q, &qd, &qdd, &f_tip, &payload), want.as_slice());
        let want = robot.mass_matrix_with(&qv, &no_tip).unwrap();
        check("M", controller::mass_matrix(&q, &payload).as_flattened(), want.as_slice());
        let want = robot.bias_forces_with(&qv, &qdv, &no_tip).unwrap();
        check("h", &controller::bias_forces(&q, &qd, &payload), want.as_slice());
        let want = robot.gravity_torques_with(&qv, &no_tip).unwrap();
        check("g", &controller::gravity_torques(&q, &payload), want.as_slice());
        let want = robot.forward_dynamics_with(&qv, &qdv, &d(&tau), &inputs).unwrap();
        check("qdd", &controller::forward_dynamics(&q, &qd, &tau, &f_tip, &payload), want.as_slice());
        // row-major: the transpose's column-major storage
        let rows = |m: nalgebra::Matrix6xX<f64>| m.transpose().as_slice().to_vec();
        type Jacobian = fn(&[f64; controller::NQ]) -> [[f64; controller::NV]; 6];
        type Bias = fn(&[f64; controller::NQ], &[f64; controller::NV]) -> [f64; 6];
        let contacts: [(&str, Jacobian, Bias); 5] = [
            ("FL_foot", controller::frame_jacobian_fl_foot, controller::frame_acceleration_bias_fl_foot),
            ("FR_foot", controller::frame_jacobian_fr_foot, controller::frame_acceleration_bias_fr_foot),
            ("RL_foot", controller::frame_jacobian_rl_foot, controller::frame_acceleration_bias_rl_foot),
            ("RR_foot", controller::frame_jacobian_rr_foot, controller::frame_acceleration_bias_rr_foot),
            ("arm_ee", controller::frame_jacobian_arm_ee, controller::frame_acceleration_bias_arm_ee),
        ];
        for (frame, jacobian, bias) in contacts {
            check(frame, jacobian(&q).as_flattened(), &rows(robot.frame_jacobian(frame, &qv).unwrap()));
            check(frame, &bias(&q, &qd), robot.frame_acceleration_bias(frame, &qv, &qdv).unwrap().as_slice());
        }
        let world = rows(robot.frame_world_jacobian("arm_ee", &qv).unwrap());
        check("arm_ee world", controller::frame_world_jacobian_arm_ee(&q).as_flattened(), &world);
        let pose = robot.frame_pose("arm_ee", &qv).unwrap().transpose();
        check("arm_ee pose", controller::frame_pose_arm_ee(&q).as_flattened(), pose.as_slice());
    }
    println!("legged manipulator controller, compiled: worst relative error {worst:.1e}");
}
