//! Scene modules that `build.rs` writes with `dynagen::Builder`, compiled,
//! against the generic solver under the same scene (`SceneRobot`) on random
//! states: the bundled `ur5_controller` scene, a UR5 with every run-time
//! input, and an f32 UR5 with only τ and no gravity.

use dynagen::scene::{PayloadInertia, Scene, SceneInputs, SceneRobot};
use dynagen_tests::{bundled_model, bundled_scene, norm_rel_err, Rng};
use nalgebra::{DVector, Vector3, Vector6};

#[allow(dead_code)]
mod ur5_controller {
    include!(concat!(env!("OUT_DIR"), "/ur5_controller.rs"));
}
#[allow(dead_code)]
mod ur5_inputs {
    include!(concat!(env!("OUT_DIR"), "/ur5_inputs.rs"));
}
#[allow(dead_code)]
mod ur5_tau_f32 {
    include!(concat!(env!("OUT_DIR"), "/ur5_tau_f32.rs"));
}

fn flat<const R: usize, const C: usize>(m: [[f64; C]; R]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

fn rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Vec<f64> {
    (0..m.nrows()).flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)])).collect()
}

#[test]
fn ur5_controller_module_matches_the_scene_robot() {
    use ur5_controller as m;
    let scene = Scene::from_toml_file(bundled_scene("ur5_controller")).unwrap();
    let mut robot = SceneRobot::new(scene.apply(&bundled_model("ur5")).unwrap());
    assert_eq!(m::JOINT_NAMES.to_vec(), robot.joint_names());
    let mut rng = Rng::new(11);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let mut arr = |a: f64| -> [f64; m::DOF] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd, tau) = (arr(3.0), arr(2.0), arr(5.0), arr(30.0));
        let f_tip: [f64; 6] = core::array::from_fn(|i| [0.3, -0.2, 0.1, 5.0, -3.0, 8.0][i] * (1.0 + q[0]));
        let v = |a: &[f64; m::DOF]| DVector::from_column_slice(a);
        let inputs = SceneInputs { tip_wrench: Some(Vector6::from(f_tip)), ..Default::default() };
        let checks = [
            (
                "inverse_dynamics",
                m::inverse_dynamics(&q, &qd, &qdd, &f_tip).to_vec(),
                robot.inverse_dynamics_with(&v(&q), &v(&qd), &v(&qdd), &inputs).unwrap().as_slice().to_vec(),
            ),
            ("mass_matrix", flat(m::mass_matrix(&q)), rows(&robot.mass_matrix(&v(&q)).unwrap())),
            (
                "bias_forces",
                m::bias_forces(&q, &qd).to_vec(),
                robot.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
            ),
            (
                "gravity_torques",
                m::gravity_torques(&q).to_vec(),
                robot.gravity_torques(&v(&q)).unwrap().as_slice().to_vec(),
            ),
            (
                "forward_dynamics",
                m::forward_dynamics(&q, &qd, &tau, &f_tip).to_vec(),
                robot.forward_dynamics_with(&v(&q), &v(&qd), &v(&tau), &inputs).unwrap().as_slice().to_vec(),
            ),
            ("frame_pose", flat(m::frame_pose_ee_link(&q)), rows(&robot.frame_pose("ee_link", &v(&q)).unwrap())),
            (
                "frame_jacobian",
                flat(m::frame_jacobian_ee_link(&q)),
                rows(&robot.frame_jacobian("ee_link", &v(&q)).unwrap()),
            ),
        ];
        for (name, got, want) in checks {
            let e = norm_rel_err(&got, &want, 1e-300);
            worst = worst.max(e);
            assert!(e < 1e-12, "{name}: relative error {e:e}\n got {got:?}\nwant {want:?}");
        }
    }
    println!("ur5_controller: worst relative error {worst:.1e}");
}

#[test]
fn ur5_inputs_module_matches_the_scene_robot() {
    use ur5_inputs as m;
    let scene = Scene::new()
        .gravity(dynagen::scene::Gravity::Input)
        .tip_wrench("ee_link")
        .payload_input("ee_link")
        .lock("wrist_3_joint", 0.2)
        .armature("elbow_joint", 0.2)
        .coulomb("shoulder_lift_joint", 2.0);
    let mut robot = SceneRobot::new(scene.apply(&bundled_model("ur5")).unwrap());
    assert_eq!(m::DOF, 5);
    let mut rng = Rng::new(12);
    for _ in 0..200 {
        let mut arr = |a: f64| -> [f64; m::DOF] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd, tau) = (arr(3.0), arr(2.0), arr(5.0), arr(30.0));
        let gravity = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), -9.81];
        let f_tip: [f64; 6] = core::array::from_fn(|_| rng.range(-5.0, 5.0));
        let p = PayloadInertia::new(
            rng.range(0.5, 2.0),
            [0.0, rng.range(-0.05, 0.05), 0.06],
            [2e-3, 2e-3, 1e-3, 0.0, 1e-4, 0.0],
        );
        let payload = [
            p.mass,
            p.com[0],
            p.com[1],
            p.com[2],
            p.inertia[0],
            p.inertia[1],
            p.inertia[2],
            p.inertia[3],
            p.inertia[4],
            p.inertia[5],
        ];
        let v = |a: &[f64; m::DOF]| DVector::from_column_slice(a);
        let inputs = SceneInputs {
            gravity: Some(Vector3::from(gravity)),
            tip_wrench: Some(Vector6::from(f_tip)),
            payloads: std::slice::from_ref(&p),
        };
        let checks = [
            (
                "inverse_dynamics",
                m::inverse_dynamics(&q, &qd, &qdd, &gravity, &f_tip, &payload).to_vec(),
                robot.inverse_dynamics_with(&v(&q), &v(&qd), &v(&qdd), &inputs).unwrap().as_slice().to_vec(),
            ),
            (
                "mass_matrix",
                flat(m::mass_matrix(&q, &payload)),
                rows(&robot.mass_matrix_with(&v(&q), &inputs).unwrap()),
            ),
            (
                "bias_forces",
                m::bias_forces(&q, &qd, &gravity, &payload).to_vec(),
                robot.bias_forces_with(&v(&q), &v(&qd), &inputs).unwrap().as_slice().to_vec(),
            ),
            (
                "gravity_torques",
                m::gravity_torques(&q, &gravity, &payload).to_vec(),
                robot.gravity_torques_with(&v(&q), &inputs).unwrap().as_slice().to_vec(),
            ),
            (
                "coriolis",
                m::coriolis(&q, &qd, &payload).to_vec(),
                robot.coriolis_with(&v(&q), &v(&qd), &inputs).unwrap().as_slice().to_vec(),
            ),
            (
                "forward_dynamics",
                m::forward_dynamics(&q, &qd, &tau, &gravity, &f_tip, &payload).to_vec(),
                robot.forward_dynamics_with(&v(&q), &v(&qd), &v(&tau), &inputs).unwrap().as_slice().to_vec(),
            ),
        ];
        for (name, got, want) in checks {
            let e = norm_rel_err(&got, &want, 1e-300);
            assert!(e < 1e-12, "{name}: relative error {e:e}\n got {got:?}\nwant {want:?}");
        }
    }
}

#[test]
fn ur5_f32_torque_module_matches_the_scene_robot() {
    use ur5_tau_f32 as m;
    let source = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/ur5_tau_f32.rs")).unwrap();
    assert!(!source.contains("fn mass_matrix") && !source.contains("fn forward_dynamics"));
    let scene = Scene::new().gravity(dynagen::scene::Gravity::None);
    let mut robot = SceneRobot::new(scene.apply(&bundled_model("ur5")).unwrap());
    let mut rng = Rng::new(13);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let mut arr = |a: f64| -> [f64; m::DOF] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd) = (arr(3.0), arr(2.0), arr(5.0));
        let f = |a: &[f64; m::DOF]| a.map(|x| x as f32);
        let got: Vec<f64> = m::inverse_dynamics(&f(&q), &f(&qd), &f(&qdd)).iter().map(|&x| f64::from(x)).collect();
        // The reference at the f32-rounded state.
        let v = |a: &[f64; m::DOF]| DVector::from_iterator(m::DOF, a.iter().map(|&x| f64::from(x as f32)));
        let want = robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap();
        let e = norm_rel_err(&got, want.as_slice(), 1e-300);
        worst = worst.max(e);
        assert!(e < 1e-5, "f32 inverse_dynamics: relative error {e:e}");
    }
    println!("ur5_tau_f32: worst relative error {worst:.1e}");
}
