//! Scenes against independent computations: every reduction against the
//! full model (locked joints as entries of the full model's τ, M, h and g;
//! sub-trees against the full model with the removed joints held; constant
//! payloads against a URDF with the payload as a fixed link), armature and
//! friction against the formulas written out by hand, gravity options
//! against the plain solver with that gravity, forward dynamics against
//! inverse dynamics, TOML round trips, and every error naming its item.

mod support;

use approx::abs_diff_eq;
use dynagen::codegen::{generate_scene, CodegenError, CodegenOptions, Function, ScalarType, Trig};
use dynagen::scene::{
    CodeKeys, Gravity, PayloadInertia, Scene, SceneError, SceneFile, SceneInputError, SceneInputs, SceneModel,
    SceneRobot, SceneWarning,
};
use dynagen::{Model, Robot};
use nalgebra::{DMatrix, DVector, Vector3, Vector6};
use std::path::PathBuf;
use support::{model, robot as full, robot_path, scale};

/// A deterministic pseudo-random vector with entries in (−scale, scale).
fn state(n: usize, seed: u64, scale: f64) -> DVector<f64> {
    let mut x = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    DVector::from_fn(n, |_, _| {
        x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        scale * (2.0 * ((x >> 11) as f64 / (1u64 << 53) as f64) - 1.0)
    })
}

/// max |a − b| ≤ tol · max(1, max |b|), by `approx`.
#[track_caller]
fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    let epsilon = tol * scale(b, 1.0);
    assert!(abs_diff_eq!(a, b, epsilon = epsilon), "{what}: ε = {epsilon:e}\n  got  {a:?}\n  want {b:?}");
}

fn pick(v: &DVector<f64>, idx: &[usize]) -> Vec<f64> {
    idx.iter().map(|&i| v[i]).collect()
}

fn pick_m(m: &DMatrix<f64>, idx: &[usize]) -> Vec<f64> {
    idx.iter().flat_map(|&r| idx.iter().map(move |&c| m[(r, c)])).collect()
}

/// Indices in the full robot of the reduced model's joints.
fn full_indices(scene: &SceneModel, full: &Robot) -> Vec<usize> {
    scene.joint_names().iter().map(|n| full.model().joint_index(n).expect("kept joint in full model")).collect()
}

/// Compares τ, M, h and g of a reduced scene with the full robot, with the
/// full robot's removed joints at `held` (position; velocity and
/// acceleration zero) and its other joints at the reduced state; `free`
/// joints of the full model (not held, not kept) get arbitrary states.
fn compare_with_full(scene: &SceneModel, full: &mut Robot, held: &[(&str, f64)], free: &[&str], seed: u64) {
    let idx = full_indices(scene, full);
    let (n, nf) = (scene.dof(), full.dof());
    let mut robot = SceneRobot::new(scene.clone());
    for k in 0..4 {
        let s = seed * 10 + k;
        let (q, qd, qdd) = (state(n, s, 2.5), state(n, s + 100, 3.0), state(n, s + 200, 5.0));
        let mut qf = state(nf, s + 300, 2.0);
        let mut qdf = state(nf, s + 400, 2.0);
        let mut qddf = state(nf, s + 500, 4.0);
        for (name, pos) in held {
            let i = full.model().joint_index(name).unwrap();
            (qf[i], qdf[i], qddf[i]) = (*pos, 0.0, 0.0);
        }
        for (r, &i) in idx.iter().enumerate() {
            (qf[i], qdf[i], qddf[i]) = (q[r], qd[r], qdd[r]);
        }
        let covered = held.len() + free.len() + n;
        assert_eq!(covered, nf, "every full joint must be kept, held or free");
        let tau = robot.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let tau_f = full.inverse_dynamics(&qf, &qdf, &qddf).unwrap();
        assert_close(tau.as_slice(), &pick(&tau_f, &idx), 1e-12, "tau");
        let m = robot.mass_matrix(&q).unwrap();
        let m_f = full.mass_matrix(&qf).unwrap();
        assert_close(&pick_m(&m, &(0..n).collect::<Vec<_>>()), &pick_m(&m_f, &idx), 1e-12, "M");
        let h = robot.bias_forces(&q, &qd).unwrap();
        assert_close(h.as_slice(), &pick(&full.bias_forces(&qf, &qdf).unwrap(), &idx), 1e-12, "h");
        let g = robot.gravity_torques(&q).unwrap();
        assert_close(g.as_slice(), &pick(&full.gravity_torques(&qf).unwrap(), &idx), 1e-12, "g");
        let c = robot.coriolis(&q, &qd).unwrap();
        assert_close(c.as_slice(), &pick(&full.coriolis_torques(&qf, &qdf).unwrap(), &idx), 1e-12, "C qd");
    }
}

#[test]
fn locked_joints_give_the_full_models_entries() {
    let scene = Scene::new().lock("elbow_joint", 0.7).lock("wrist_3_joint", -0.4).apply(&model("ur5")).unwrap();
    assert_eq!(scene.joint_names(), ["shoulder_pan_joint", "shoulder_lift_joint", "wrist_1_joint", "wrist_2_joint"]);
    assert_eq!(scene.fixed_joints, [("elbow_joint".to_string(), 0.7), ("wrist_3_joint".to_string(), -0.4)]);
    compare_with_full(&scene, &mut full("ur5"), &[("elbow_joint", 0.7), ("wrist_3_joint", -0.4)], &[], 1);

    // A prismatic joint and a mid-chain revolute joint of the Panda.
    let held = [("panda_joint4", -1.2), ("panda_finger_joint1", 0.03)];
    let scene = Scene::new().lock(held[0].0, held[0].1).lock(held[1].0, held[1].1).apply(&model("panda")).unwrap();
    assert_eq!(scene.dof(), 7);
    compare_with_full(&scene, &mut full("panda"), &held, &[], 2);
}

#[test]
fn subtree_with_a_mid_root_reexpresses_gravity() {
    // Root at the upper arm: shoulder pan and lift are above it, held at
    // their lock positions (the lift turns gravity in the root's frame);
    // wrist 3 is below the tip, merged at its lock position.
    let held = [("shoulder_pan_joint", 0.4), ("shoulder_lift_joint", -0.9), ("wrist_3_joint", 0.3)];
    let mut s = Scene::new().subtree("upper_arm_link", &["wrist_2_link"]);
    for (j, q) in held {
        s = s.lock(j, q);
    }
    let scene = s.apply(&model("ur5")).unwrap();
    assert_eq!(scene.joint_names(), ["elbow_joint", "wrist_1_joint", "wrist_2_joint"]);
    assert_eq!(scene.model.root, "upper_arm_link");
    assert_eq!(scene.removed_joints, ["shoulder_pan_joint", "shoulder_lift_joint"]);
    assert_eq!(scene.fixed_joints, [("wrist_3_joint".to_string(), 0.3)]);
    compare_with_full(&scene, &mut full("ur5"), &held, &[], 3);

    // Without locks the joints above are at zero, and so is wrist 3.
    let scene = Scene::new().subtree("upper_arm_link", &["wrist_2_link"]).apply(&model("ur5")).unwrap();
    let zero = [("shoulder_pan_joint", 0.0), ("shoulder_lift_joint", 0.0), ("wrist_3_joint", 0.0)];
    compare_with_full(&scene, &mut full("ur5"), &zero, &[], 4);

    // The root at a link fixed to a body (not the body's own link): the
    // left wrist mount, fixed to the left forearm with an offset.
    let held = [("torso_yaw_joint", 0.5), ("left_shoulder_joint", -0.7), ("left_elbow_joint", 1.1)];
    let mut s = Scene::new().subtree("left_wrist_mount", &["left_ee"]);
    for (j, q) in held {
        s = s.lock(j, q);
    }
    let scene = s.apply(&model("torso_two_arms")).unwrap();
    assert_eq!(scene.joint_names(), ["left_wrist_joint"]);
    let right = ["right_shoulder_joint", "right_elbow_joint", "right_wrist_joint"];
    compare_with_full(&scene, &mut full("torso_two_arms"), &held, &right, 5);
}

#[test]
fn subtree_drops_branches_off_the_paths() {
    // The left arm of the torso robot: the right arm hangs off the root
    // (the torso) and is dropped. The full robot's right arm may move at
    // will: with the torso held, it does not load the left arm's joints.
    let scene = Scene::new().subtree("torso", &["left_ee"]).apply(&model("torso_two_arms")).unwrap();
    assert_eq!(scene.joint_names(), ["left_shoulder_joint", "left_elbow_joint", "left_wrist_joint"]);
    assert_eq!(
        scene.warnings,
        [SceneWarning::DroppedBranch {
            joint: "right_shoulder_joint".to_string(),
            links: vec!["right_upper_arm".into(), "right_forearm".into(), "right_hand".into()]
        }]
    );
    assert!(scene.warnings[0].to_string().contains("right_shoulder_joint"));
    assert_eq!(scene.dropped_links, ["right_upper_arm", "right_forearm", "right_hand"]);
    assert!(scene.model.frame_index("right_ee").is_none() && scene.model.frame_index("left_ee").is_some());
    let right = ["right_shoulder_joint", "right_elbow_joint", "right_wrist_joint"];
    compare_with_full(&scene, &mut full("torso_two_arms"), &[("torso_yaw_joint", 0.0)], &right, 6);

    // Both arms from the base: the torso joint is on both paths.
    let scene = Scene::new().subtree("base", &["left_hand", "right_forearm"]).apply(&model("torso_two_arms")).unwrap();
    assert_eq!(
        scene.joint_names(),
        [
            "torso_yaw_joint",
            "left_shoulder_joint",
            "left_elbow_joint",
            "left_wrist_joint",
            "right_shoulder_joint",
            "right_elbow_joint"
        ]
    );
    assert!(scene.warnings.is_empty());
    compare_with_full(&scene, &mut full("torso_two_arms"), &[("right_wrist_joint", 0.0)], &[], 7);

    // The Panda's arm without its fingers: merged into the hand at their
    // lock positions.
    let held = [("panda_finger_joint1", 0.035), ("panda_finger_joint2", 0.01)];
    let scene = Scene::new()
        .subtree("panda_link0", &["panda_hand"])
        .lock(held[0].0, held[0].1)
        .lock(held[1].0, held[1].1)
        .apply(&model("panda"))
        .unwrap();
    assert_eq!(scene.dof(), 7);
    assert!(scene.model.frame_index("panda_leftfinger").is_some());
    compare_with_full(&scene, &mut full("panda"), &held, &[], 8);
}

/// The torso robot's URDF without the right arm (every link and joint whose
/// name starts with `right_`), written out by hand.
fn torso_without_right_arm() -> Robot {
    let xml = std::fs::read_to_string(robot_path("torso_two_arms")).unwrap();
    let mut out = String::new();
    let mut skipping: Option<&str> = None;
    for line in xml.lines() {
        let t = line.trim_start();
        if skipping.is_none() {
            if t.starts_with("<link name=\"right_") && !t.ends_with("/>") {
                skipping = Some("</link>");
            } else if t.starts_with("<joint name=\"right_") {
                skipping = Some("</joint>");
            } else if !t.starts_with("<link name=\"right_") {
                out.push_str(line);
                out.push('\n');
            }
            continue;
        }
        if t.starts_with(skipping.unwrap()) {
            skipping = None;
        }
    }
    assert!(!out.contains("name=\"right_"));
    Robot::from_urdf_str(&out).unwrap()
}

#[test]
fn a_dropped_branch_off_a_moving_body_no_longer_loads_it() {
    // Root at the base, one tip in the left arm: the right arm hangs off the
    // torso, whose joint is kept, and is dropped, so the scene equals the
    // robot without a right arm, on every joint including the torso's.
    let scene = Scene::new().subtree("base", &["left_ee"]).apply(&model("torso_two_arms")).unwrap();
    assert!(
        matches!(&scene.warnings[..], [SceneWarning::DroppedBranch { joint, .. }] if joint == "right_shoulder_joint")
    );
    let mut reference = torso_without_right_arm();
    assert_eq!(reference.joint_names(), scene.joint_names());
    compare_with_full(&scene, &mut reference, &[], &[], 9);
}

/// The UR5 URDF with a link carrying `p` fixed to `link`.
fn ur5_with_payload_link(link: &str, p: &PayloadInertia) -> Robot {
    let xml = std::fs::read_to_string(robot_path("ur5")).unwrap();
    let [ixx, iyy, izz, ixy, ixz, iyz] = p.inertia;
    let [x, y, z] = p.com;
    let extra = format!(
        r#"<link name="payload_link"><inertial><origin xyz="{x} {y} {z}" rpy="0 0 0"/><mass value="{}"/>
        <inertia ixx="{ixx}" iyy="{iyy}" izz="{izz}" ixy="{ixy}" ixz="{ixz}" iyz="{iyz}"/></inertial></link>
        <joint name="payload_joint" type="fixed"><parent link="{link}"/><child link="payload_link"/>
        <origin xyz="0 0 0" rpy="0 0 0"/></joint></robot>"#,
        p.mass
    );
    Robot::from_urdf_str(&xml.replace("</robot>", &extra)).unwrap()
}

#[test]
fn constant_and_input_payloads_equal_a_fixed_payload_link() {
    let p = PayloadInertia::new(2.3, [0.05, -0.02, 0.11], [0.02, 0.03, 0.025, 0.002, -0.001, 0.003]);
    for link in ["ee_link", "wrist_2_link"] {
        let mut reference = ur5_with_payload_link(link, &p);
        let mut constant = SceneRobot::new(Scene::new().payload(link, p).apply(&model("ur5")).unwrap());
        let input_scene = Scene::new().payload_input(link).apply(&model("ur5")).unwrap();
        let as_model = input_scene.model_with_payloads(&[p]).unwrap();
        let mut input = SceneRobot::new(input_scene);
        let inputs = SceneInputs { payloads: &[p], ..Default::default() };
        for k in 0..3 {
            let (q, qd, qdd) = (state(6, k, 3.0), state(6, k + 10, 2.0), state(6, k + 20, 4.0));
            let want = reference.inverse_dynamics(&q, &qd, &qdd).unwrap();
            assert_close(constant.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), want.as_slice(), 1e-12, "tau");
            let got = input.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap();
            assert_close(got.as_slice(), want.as_slice(), 1e-12, "tau, input payload");
            let m = reference.mass_matrix(&q).unwrap();
            assert_close(constant.mass_matrix(&q).unwrap().as_slice(), m.as_slice(), 1e-12, "M");
            assert_close(input.mass_matrix_with(&q, &inputs).unwrap().as_slice(), m.as_slice(), 1e-12, "M, input");
            let g = reference.gravity_torques(&q).unwrap();
            assert_close(constant.gravity_torques(&q).unwrap().as_slice(), g.as_slice(), 1e-12, "g");
            assert_close(input.gravity_torques_with(&q, &inputs).unwrap().as_slice(), g.as_slice(), 1e-12, "g, in");
            let h = reference.bias_forces(&q, &qd).unwrap();
            assert_close(input.bias_forces_with(&q, &qd, &inputs).unwrap().as_slice(), h.as_slice(), 1e-12, "h");
        }
        let mut from_model = Robot::new(as_model);
        let q = state(6, 99, 2.0);
        let want = reference.gravity_torques(&q).unwrap();
        assert_close(from_model.gravity_torques(&q).unwrap().as_slice(), want.as_slice(), 1e-12, "model_with_payloads");
    }
    // An input payload changes per call: a second value replaces the first.
    let mut input = SceneRobot::new(Scene::new().payload_input("ee_link").apply(&model("ur5")).unwrap());
    let light = PayloadInertia::new(0.1, [0.0, 0.0, 0.02], [1e-4, 1e-4, 1e-4, 0.0, 0.0, 0.0]);
    let q = state(6, 5, 2.0);
    input.gravity_torques_with(&q, &SceneInputs { payloads: &[p], ..Default::default() }).unwrap();
    let got = input.gravity_torques_with(&q, &SceneInputs { payloads: &[light], ..Default::default() }).unwrap();
    let want = ur5_with_payload_link("ee_link", &light).gravity_torques(&q).unwrap();
    assert_close(got.as_slice(), want.as_slice(), 1e-12, "second payload value");
}

#[test]
fn armature_and_friction_follow_the_formulas() {
    let a = [0.3, 0.25, 0.2, 0.05, 0.04, 0.03];
    let b = [1.5, 0.0, 1.2, 0.4, 0.3, 0.2];
    let f = [4.0, 3.5, 0.0, 1.0, 0.8, 0.6];
    let v_eps = 0.05;
    let names = full("ur5").joint_names().iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let mut s = Scene::new().coulomb_velocity(v_eps);
    for (i, j) in names.iter().enumerate() {
        s = s.armature(j, a[i]).viscous(j, b[i]).coulomb(j, f[i]);
    }
    let mut robot = SceneRobot::new(s.apply(&model("ur5")).unwrap());
    let mut plain = full("ur5");
    for k in 0..4 {
        let q = state(6, k, 3.0);
        // Speeds from well inside the smoothing band to far outside it.
        let qd = state(6, k + 10, [0.01, 0.1, 1.0, 5.0][k as usize]);
        let qdd = state(6, k + 20, 4.0);
        let friction: Vec<f64> =
            (0..6).map(|i| b[i] * qd[i] + f[i] * qd[i] / (qd[i] * qd[i] + v_eps * v_eps).sqrt()).collect();
        let tau0 = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let want: Vec<f64> = (0..6).map(|i| tau0[i] + a[i] * qdd[i] + friction[i]).collect();
        assert_close(robot.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), &want, 1e-13, "tau");
        let mut m = plain.mass_matrix(&q).unwrap();
        for i in 0..6 {
            m[(i, i)] += a[i];
        }
        assert_close(robot.mass_matrix(&q).unwrap().as_slice(), m.as_slice(), 1e-13, "M");
        let h0 = plain.bias_forces(&q, &qd).unwrap();
        let want: Vec<f64> = (0..6).map(|i| h0[i] + friction[i]).collect();
        assert_close(robot.bias_forces(&q, &qd).unwrap().as_slice(), &want, 1e-13, "h");
        let g = plain.gravity_torques(&q).unwrap();
        assert_close(robot.gravity_torques(&q).unwrap().as_slice(), g.as_slice(), 1e-13, "g has no friction");
        let c = plain.coriolis_torques(&q, &qd).unwrap();
        assert_close(robot.coriolis(&q, &qd).unwrap().as_slice(), c.as_slice(), 1e-13, "C qd has no friction");
        // Forward dynamics by an independent dense solve of M_s q̈ = τ − h_s.
        let tau = state(6, k + 30, 20.0);
        let rhs = DVector::from_fn(6, |i, _| tau[i] - h0[i] - friction[i]);
        let want = m.clone().lu().solve(&rhs).unwrap();
        assert_close(robot.forward_dynamics(&q, &qd, &tau).unwrap().as_slice(), want.as_slice(), 1e-11, "qdd");
    }
    // Friction opposes motion, is odd, and Coulomb friction saturates at f.
    let q = DVector::zeros(6);
    let mut r2 =
        SceneRobot::new(Scene::new().gravity(Gravity::None).coulomb("elbow_joint", 2.0).apply(&model("ur5")).unwrap());
    let e = |v: f64| DVector::from_fn(6, |i, _| if i == 2 { v } else { 0.0 });
    let at = |r: &mut SceneRobot, v: f64| r.bias_forces(&q, &e(v)).unwrap()[2];
    assert_eq!(at(&mut r2, 0.0), 0.0);
    assert_close(&[at(&mut r2, 0.01)], &[2.0 / 2f64.sqrt()], 1e-15, "σ(v_ε) = 1/√2");
    assert_close(&[at(&mut r2, -1.0)], &[-2.0 * 1.0 / (1.0f64 + 1e-4).sqrt()], 1e-15, "σ(−100 v_ε)");
}

#[test]
fn gravity_options_match_the_plain_solver() {
    let mut plain = full("panda");
    let n = plain.dof();
    let (q, qd, qdd) = (state(n, 1, 2.0), state(n, 2, 2.0), state(n, 3, 3.0));
    let tau = state(n, 4, 10.0);

    // None == zero gravity.
    let mut none = SceneRobot::new(Scene::new().gravity(Gravity::None).apply(&model("panda")).unwrap());
    plain.set_gravity(Vector3::zeros()).unwrap();
    assert_close(none.gravity_torques(&q).unwrap().as_slice(), &vec![0.0; n], 0.0, "g = 0");
    let want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
    assert_close(none.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), want.as_slice(), 1e-13, "tau, none");
    let want = plain.bias_forces(&q, &qd).unwrap();
    assert_close(none.bias_forces(&q, &qd).unwrap().as_slice(), want.as_slice(), 1e-13, "h, none");
    let want = plain.forward_dynamics(&q, &qd, &tau).unwrap();
    assert_close(none.forward_dynamics(&q, &qd, &tau).unwrap().as_slice(), want.as_slice(), 1e-12, "qdd, none");

    // A constant.
    let gv = [1.2, -0.5, -9.7];
    let mut constant = SceneRobot::new(Scene::new().gravity(Gravity::Constant(gv)).apply(&model("panda")).unwrap());
    plain.set_gravity(Vector3::from(gv)).unwrap();
    let want = plain.gravity_torques(&q).unwrap();
    assert_close(constant.gravity_torques(&q).unwrap().as_slice(), want.as_slice(), 1e-13, "g, constant");
    let want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
    assert_close(constant.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), want.as_slice(), 1e-13, "tau");

    // An input, per call.
    let mut input = SceneRobot::new(Scene::new().gravity(Gravity::Input).apply(&model("panda")).unwrap());
    for gv in [[0.0, 0.0, -9.81], [3.0, 2.0, -1.0]] {
        plain.set_gravity(Vector3::from(gv)).unwrap();
        let inputs = SceneInputs { gravity: Some(Vector3::from(gv)), ..Default::default() };
        let want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let got = input.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap();
        assert_close(got.as_slice(), want.as_slice(), 1e-13, "tau, input gravity");
        let want = plain.forward_dynamics(&q, &qd, &tau).unwrap();
        let got = input.forward_dynamics_with(&q, &qd, &tau, &inputs).unwrap();
        assert_close(got.as_slice(), want.as_slice(), 1e-12, "qdd, input gravity");
    }
    // M and C q̇ do not need gravity; τ does.
    assert!(input.mass_matrix(&q).is_ok() && input.coriolis(&q, &qd).is_ok());
    assert!(matches!(input.inverse_dynamics(&q, &qd, &qdd), Err(SceneInputError::MissingInput("gravity"))));
    let stray = SceneInputs { gravity: Some(Vector3::zeros()), ..Default::default() };
    assert!(matches!(constant.gravity_torques_with(&q, &stray), Err(SceneInputError::UnexpectedInput("gravity"))));
    let nan = SceneInputs { gravity: Some(Vector3::new(0.0, f64::NAN, 0.0)), ..Default::default() };
    assert!(input.gravity_torques_with(&q, &nan).unwrap_err().to_string().contains("gravity"));
}

#[test]
fn tip_wrench_input_matches_the_plain_solver() {
    let mut plain = full("ur5");
    let mut robot = SceneRobot::new(Scene::new().tip_wrench("ee_link").apply(&model("ur5")).unwrap());
    let w = Vector6::new(0.5, -1.0, 2.0, 10.0, -20.0, 5.0);
    plain.set_tip_wrench("ee_link", w).unwrap();
    let inputs = SceneInputs { tip_wrench: Some(w), ..Default::default() };
    let (q, qd, qdd, tau) = (state(6, 1, 3.0), state(6, 2, 2.0), state(6, 3, 3.0), state(6, 4, 30.0));
    let want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
    assert_close(
        robot.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap().as_slice(),
        want.as_slice(),
        1e-13,
        "tau",
    );
    let want = plain.forward_dynamics(&q, &qd, &tau).unwrap();
    assert_close(
        robot.forward_dynamics_with(&q, &qd, &tau, &inputs).unwrap().as_slice(),
        want.as_slice(),
        1e-12,
        "qdd",
    );
    // J_bᵀ F_tip is the torque of the wrench alone.
    let jt = robot.frame_jacobian("ee_link", &q).unwrap().transpose() * w;
    let want = plain.tip_wrench_torques(&q).unwrap();
    assert_close(jt.as_slice(), want.as_slice(), 1e-13, "J_b^T F");
    let pose = robot.frame_pose("ee_link", &q).unwrap();
    assert_close(pose.as_slice(), plain.frame_pose("ee_link", &q).unwrap().as_slice(), 1e-14, "pose");
    // h has no tip wrench; τ needs one.
    assert!(robot.bias_forces(&q, &qd).is_ok());
    assert!(matches!(robot.inverse_dynamics(&q, &qd, &qdd), Err(SceneInputError::MissingInput("a tip wrench"))));
}

/// Every option at once, and each alone: q̈ = FD(q, q̇, ID(q, q̇, q̈)).
#[test]
fn forward_dynamics_inverts_inverse_dynamics_under_every_option() {
    let p = PayloadInertia::new(1.5, [0.0, 0.02, 0.08], [0.004, 0.005, 0.003, 0.0, 0.0, 0.0005]);
    let all_ur5 = Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("ee_link")
        .lock("wrist_1_joint", 0.4)
        .payload("ee_link", p)
        .payload_input("forearm_link")
        .armature("shoulder_pan_joint", 0.3)
        .armature("elbow_joint", 0.2)
        .viscous("shoulder_lift_joint", 1.0)
        .coulomb("wrist_2_joint", 2.0)
        .coulomb("elbow_joint", 1.0);
    let cases: Vec<(&str, Scene)> = vec![
        ("ur5", Scene::new()),
        ("ur5", Scene::new().gravity(Gravity::None)),
        ("ur5", Scene::new().gravity(Gravity::Input)),
        ("ur5", Scene::new().tip_wrench("ee_link")),
        ("ur5", Scene::new().lock("elbow_joint", 1.0)),
        ("ur5", Scene::new().payload_input("wrist_3_link")),
        ("ur5", Scene::new().armature("wrist_3_joint", 0.1)),
        ("ur5", Scene::new().viscous("wrist_3_joint", 0.5).coulomb("elbow_joint", 3.0)),
        ("ur5", all_ur5),
        (
            "panda",
            Scene::new()
                .subtree("panda_link2", &["panda_hand"])
                .lock("panda_joint2", 0.5)
                .armature("panda_joint5", 0.1),
        ),
        (
            "torso_two_arms",
            Scene::new()
                .subtree("torso", &["right_hand", "left_forearm"])
                .lock("torso_yaw_joint", 0.3)
                .coulomb("right_elbow_joint", 1.0)
                .payload_input("right_ee")
                .tip_wrench("left_forearm")
                .gravity(Gravity::Input),
        ),
    ];
    let pl = [PayloadInertia::new(0.7, [0.01, 0.0, 0.03], [0.001, 0.002, 0.002, 0.0, 0.0, 0.0])];
    for (k, (robot_name, scene)) in cases.into_iter().enumerate() {
        let applied = scene.apply(&model(robot_name)).unwrap();
        let inputs = SceneInputs {
            gravity: (scene.gravity == Gravity::Input).then(|| Vector3::new(0.3, -0.2, -9.8)),
            tip_wrench: scene.tip_wrench.is_some().then(|| Vector6::new(0.4, -0.3, 0.2, 5.0, -8.0, 12.0)),
            payloads: if applied.input_payloads.is_empty() { &[] } else { &pl },
        };
        let n = applied.dof();
        let mut robot = SceneRobot::new(applied);
        for s in 0..3 {
            let seed = 1000 + 10 * k as u64 + s;
            let (q, qd, qdd) = (state(n, seed, 3.0), state(n, seed + 1, 2.0), state(n, seed + 2, 5.0));
            let tau = robot.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap();
            let back = robot.forward_dynamics_with(&q, &qd, &tau, &inputs).unwrap();
            assert_close(back.as_slice(), qdd.as_slice(), 1e-10, &format!("case {k} ({robot_name})"));
            // and τ = M q̈ + h + Jᵀ F: the pieces add up
            let m = robot.mass_matrix_with(&q, &inputs).unwrap();
            let h = robot.bias_forces_with(&q, &qd, &inputs).unwrap();
            let mut parts = &m * &qdd + h;
            if let (Some(w), Some(frame)) = (inputs.tip_wrench, &scene.tip_wrench) {
                parts += robot.frame_jacobian(frame, &q).unwrap().transpose() * w;
            }
            assert_close(parts.as_slice(), tau.as_slice(), 1e-12, &format!("case {k}: M qdd + h + J^T F"));
        }
    }
}

#[test]
fn toml_round_trip_and_the_example_scene() {
    // The file's code-generation keys are in `SceneFile::code`, its physics
    // in `SceneFile::scene` (which `Scene::from_toml_file` gives alone).
    let file = SceneFile::from_toml_file(support::scene_path("ur5_controller")).unwrap();
    let example = Scene::from_toml_file(support::scene_path("ur5_controller")).unwrap();
    assert_eq!(file.scene, example);
    assert_eq!(file.code.name.as_deref(), Some("ur5_controller"));
    assert_eq!(example.armature.len(), 6);
    assert!(file.code.functions.as_ref().unwrap().contains(&Function::FrameJacobian("ee_link".into())));
    let applied = example.apply(&model("ur5")).unwrap();
    assert_eq!(applied.dof(), 6);
    assert_eq!(applied.tip_wrench_frame, applied.model.frame_index("ee_link"));
    let back = Scene::from_toml_str(&example.to_toml_string().unwrap()).unwrap();
    assert_eq!(back, example);

    let text = r#"
        name = "left_arm"
        functions = ["inverse_dynamics", "coriolis"]
        frame_pose = ["left_ee"]
        scalar = "f32"
        target = "no_std_libm"
        tip_wrench = "left_ee"
        coulomb_velocity = 0.002
        [gravity]
        mode = "input"
        [subtree]
        root = "torso"
        tips = ["left_ee"]
        [joints.torso_yaw_joint]
        lock = 0.25
        [joints.left_elbow_joint]
        armature = 0.1
        coulomb = 0.5
        [[payload]]
        link = "left_ee"
        input = true
        [[payload]]
        link = "left_forearm"
        mass = 0.4
        com = [0.1, 0.0, 0.0]
    "#;
    let file = SceneFile::from_toml_str(text).unwrap();
    let scene = Scene::from_toml_str(text).unwrap();
    assert_eq!(file.scene, scene);
    // The code keys: `target = "no_std_libm"` is the libm trigonometry.
    let code = CodeKeys {
        name: Some("left_arm".into()),
        functions: Some(vec![Function::InverseDynamics, Function::Coriolis, Function::FramePose("left_ee".into())]),
        scalar: Some(ScalarType::F32),
        trig: Some(Trig::Libm),
    };
    assert_eq!(file.code, code);
    let options = CodegenOptions::default()
        .name("left_arm")
        .functions([Function::InverseDynamics, Function::Coriolis, Function::FramePose("left_ee".into())])
        .scalar(ScalarType::F32)
        .trig(Trig::Libm);
    assert_eq!(file.code.apply(CodegenOptions::default()), options);
    let built = Scene::new()
        .tip_wrench("left_ee")
        .coulomb_velocity(0.002)
        .gravity(Gravity::Input)
        .subtree("torso", &["left_ee"])
        .armature("left_elbow_joint", 0.1)
        .coulomb("left_elbow_joint", 0.5)
        .lock("torso_yaw_joint", 0.25)
        .payload_input("left_ee")
        .payload("left_forearm", PayloadInertia::new(0.4, [0.1, 0.0, 0.0], [0.0; 6]));
    // The lists are grouped by joint in name order when read from TOML.
    let mut sorted = built.clone();
    sorted.locks.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(scene, sorted);
    assert_eq!(Scene::from_toml_str(&scene.to_toml_string().unwrap()).unwrap(), scene);
    assert_eq!(scene.apply(&model("torso_two_arms")).unwrap(), built.apply(&model("torso_two_arms")).unwrap());
    // Defaults: an empty file is the default scene.
    assert_eq!(Scene::from_toml_str("").unwrap(), Scene::new());
    assert_eq!(SceneFile::from_toml_str("").unwrap().code, CodeKeys::default());
    assert_eq!(CodeKeys::default().apply(CodegenOptions::default()), CodegenOptions::default());
    // The other targets: std leaves the options' trigonometry, no_std_sincos
    // is sines and cosines as inputs.
    let trig = |t: &str| SceneFile::from_toml_str(&format!("target = \"{t}\"")).unwrap().code.trig;
    assert_eq!(trig("std"), None);
    assert_eq!(trig("no_std_sincos"), Some(Trig::Inputs));
    assert_eq!(trig("no_std_libm"), Some(Trig::Libm));
    // `trig` in the options' own spelling; not beside `target`.
    let by_trig = |t: &str| SceneFile::from_toml_str(&format!("trig = \"{t}\"")).unwrap().code.trig;
    for t in [Trig::Batched, Trig::Std, Trig::Libm, Trig::Inputs] {
        assert_eq!(by_trig(t.name()), Some(t));
    }
    assert!(SceneFile::from_toml_str("trig = \"libm\"\ntarget = \"std\"").is_err());
    assert!(SceneFile::from_toml_str("trig = \"fast\"").unwrap_err().to_string().contains("fast"));
    assert!(SceneFile::from_toml_str("scalar = \"f16\"").unwrap_err().to_string().contains("f16"));
    // A whole scene file, code keys included, reads back as it was written.
    let back = SceneFile::from_toml_str(&file.to_toml_string().unwrap()).unwrap();
    let mut want = file.clone();
    want.scene = sorted.clone();
    assert_eq!(back, want);
    let example_file = SceneFile::from_toml_file(support::scene_path("ur5_controller")).unwrap();
    assert_eq!(SceneFile::from_toml_str(&example_file.to_toml_string().unwrap()).unwrap(), example_file);
    // A vector alone means a constant.
    let s = Scene::from_toml_str("[gravity]\nvector = [0.0, 0.0, -1.62]").unwrap();
    assert_eq!(s.gravity, Gravity::Constant([0.0, 0.0, -1.62]));
}

/// The error's message, which must name `item`.
#[track_caller]
fn assert_names(result: Result<impl std::fmt::Debug, SceneError>, item: &str) {
    let e = result.expect_err("the scene must be refused");
    let msg = e.to_string();
    assert!(msg.contains(item), "error does not name {item:?}: {msg}");
}

/// Code generation of `function` on `scene` is refused with the scene's
/// error, which names `item`.
#[track_caller]
fn assert_frame_refused(scene: &SceneModel, function: Function, item: &str) {
    match generate_scene(scene, &CodegenOptions::default().functions([function])) {
        Err(CodegenError::Scene(e)) => assert!(e.to_string().contains(item), "error does not name {item:?}: {e}"),
        other => panic!("the frame {item:?} must be refused with a scene error: {:?}", other.map(|m| m.source.len())),
    }
}

#[test]
fn every_error_names_its_item() {
    let ur5 = model("ur5");
    let torso = model("torso_two_arms");
    let ok = PayloadInertia::new(1.0, [0.0; 3], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0]);

    // Unknown names.
    assert_names(Scene::new().subtree("nope_link", &["ee_link"]).apply(&ur5), "nope_link");
    assert_names(Scene::new().subtree("base_link", &["nope_tip"]).apply(&ur5), "nope_tip");
    assert_names(Scene::new().lock("nope_joint", 0.0).apply(&ur5), "nope_joint");
    assert_names(Scene::new().lock("ee_fixed_joint", 0.0).apply(&ur5), "ee_fixed_joint");
    assert_names(Scene::new().armature("nope_joint", 0.1).apply(&ur5), "nope_joint");
    assert_names(Scene::new().tip_wrench("nope_frame").apply(&ur5), "nope_frame");
    assert_names(Scene::new().payload("nope_link", ok).apply(&ur5), "nope_link");
    // A frame function's frame is checked on the applied scene (and by
    // code generation, which refuses it with the scene's error).
    let plain = Scene::new().apply(&ur5).unwrap();
    assert_names(plain.frame("frame_pose", "nope_frame"), "nope_frame");
    assert_frame_refused(&plain, Function::FramePose("nope_frame".into()), "nope_frame");
    // Sub-trees.
    assert_names(Scene::new().subtree("wrist_2_link", &["upper_arm_link"]).apply(&ur5), "upper_arm_link");
    assert_names(Scene::new().subtree("wrist_2_link", &["wrist_2_link"]).apply(&ur5), "wrist_2_link");
    assert_names(Scene::new().subtree("torso", &["left_hand", "right_forearm"]).apply(&ur5), "torso");
    assert_names(Scene::new().subtree("upper_arm_link", &[]).apply(&ur5), "upper_arm_link");
    assert_names(Scene::new().subtree("base_link", &["ee_link", "ee_link"]).apply(&ur5), "ee_link");
    // Payloads.
    let mut neg = ok;
    neg.mass = -1.0;
    assert_names(Scene::new().payload("ee_link", neg).apply(&ur5), "ee_link");
    let tri = PayloadInertia::new(1.0, [0.0; 3], [0.01, 0.01, 0.05, 0.0, 0.0, 0.0]);
    assert_names(Scene::new().payload("wrist_1_link", tri).apply(&ur5), "wrist_1_link");
    let indefinite = PayloadInertia::new(1.0, [0.0; 3], [0.01, 0.01, 0.01, 0.02, 0.0, 0.0]);
    assert_names(Scene::new().payload("wrist_1_link", indefinite).apply(&ur5), "wrist_1_link");
    let nan = PayloadInertia::new(1.0, [f64::NAN, 0.0, 0.0], [0.0; 6]);
    assert_names(Scene::new().payload("wrist_1_link", nan).apply(&ur5), "wrist_1_link");
    let massless = PayloadInertia::new(0.0, [0.0; 3], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0]);
    assert_names(Scene::new().payload("wrist_1_link", massless).apply(&ur5), "wrist_1_link");
    assert_names(Scene::new().payload("ee_link", ok).payload_input("ee_link").apply(&ur5), "ee_link");
    // Coefficients and locks.
    assert_names(Scene::new().armature("elbow_joint", -0.1).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().viscous("elbow_joint", f64::NAN).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().coulomb("elbow_joint", -2.0).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().lock("elbow_joint", f64::INFINITY).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().lock("elbow_joint", 0.1).lock("elbow_joint", 0.2).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().armature("elbow_joint", 0.1).armature("elbow_joint", 0.2).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().coulomb_velocity(0.0).apply(&ur5), "coulomb_velocity");
    // Contradictions.
    assert_names(Scene::new().lock("elbow_joint", 0.1).armature("elbow_joint", 0.2).apply(&ur5), "elbow_joint");
    assert_names(Scene::new().lock("elbow_joint", 0.1).coulomb("elbow_joint", 0.2).apply(&ur5), "elbow_joint");
    let arm = Scene::new().subtree("torso", &["left_hand"]);
    assert_names(arm.clone().tip_wrench("right_hand").apply(&torso), "right_hand");
    assert_names(arm.clone().payload("right_forearm", ok).apply(&torso), "right_forearm");
    assert_names(arm.clone().armature("right_elbow_joint", 0.1).apply(&torso), "right_elbow_joint");
    assert_names(arm.clone().viscous("torso_yaw_joint", 0.1).apply(&torso), "torso_yaw_joint");
    let arm_applied = arm.clone().apply(&torso).unwrap();
    assert_names(arm_applied.frame("frame_jacobian", "base"), "base");
    assert_frame_refused(&arm_applied, Function::FrameJacobian("base".into()), "base");
    assert_names(
        arm.clone().lock("left_wrist_joint", 0.0).armature("left_wrist_joint", 1.0).apply(&torso),
        "left_wrist_joint",
    );
    assert_names(Scene::new().gravity(Gravity::Constant([0.0, f64::NAN, 0.0])).apply(&ur5), "gravity");

    // TOML: malformed input, unknown keys and values, duplicate tables,
    // contradictions.
    assert_names(Scene::from_toml_str("gravty = 1"), "gravty");
    assert_names(Scene::from_toml_str("[joints.elbow_joint]\narmatrue = 0.1"), "armatrue");
    assert_names(Scene::from_toml_str("[subtree]\nroot = \"a\"\ntips = [\"b\"]\nextra = 1"), "extra");
    assert_names(Scene::from_toml_str("[[payload]]\nlink = \"x\"\nmas = 1.0"), "mas");
    assert_names(Scene::from_toml_str("functions = [\"inverse_dynamix\"]"), "inverse_dynamix");
    assert_names(Scene::from_toml_str("scalar = \"f16\""), "f16");
    assert_names(
        Scene::from_toml_str("[joints.elbow_joint]\nlock = 0.1\n[joints.elbow_joint]\nlock = 0.2"),
        "elbow_joint",
    );
    assert_names(Scene::from_toml_str("[joints.elbow_joint]\nlock = 0.1\narmature = 0.2"), "elbow_joint");
    assert_names(Scene::from_toml_str("[gravity]\nmode = \"none\"\nvector = [0.0, 0.0, -9.81]"), "none");
    assert_names(Scene::from_toml_str("[gravity]\nmode = \"constant\""), "constant");
    assert_names(Scene::from_toml_str("[[payload]]\nlink = \"tool\"\ninput = true\nmass = 1.0"), "tool");
    assert_names(Scene::from_toml_str("[[payload]]\nlink = \"tool\""), "tool");
    assert_names(Scene::from_toml_str("[joints.elbow_joint]\narmature = \"big\""), "armature");
    assert_names(Scene::from_toml_str("[gravity\nmode = 1"), "gravity");
    assert_names(Scene::from_toml_file("/nonexistent/scene.toml"), "/nonexistent/scene.toml");
}

#[test]
fn run_time_inputs_are_checked() {
    let mut robot = SceneRobot::new(Scene::new().payload_input("ee_link").apply(&model("ur5")).unwrap());
    let q = state(6, 1, 1.0);
    let short = state(5, 1, 1.0);
    assert!(robot.mass_matrix(&short).unwrap_err().to_string().contains("5"));
    let mut bad = q.clone();
    bad[2] = f64::NAN;
    assert!(robot.mass_matrix(&bad).unwrap_err().to_string().contains("elbow_joint"));
    assert!(matches!(robot.mass_matrix(&q), Err(SceneInputError::MissingInput(_))));
    let neg = [PayloadInertia::new(-1.0, [0.0; 3], [0.0; 6])];
    let e = robot.mass_matrix_with(&q, &SceneInputs { payloads: &neg, ..Default::default() }).unwrap_err();
    assert!(e.to_string().contains("ee_link"), "{e}");
    let two = [PayloadInertia::default(); 2];
    let e = robot.mass_matrix_with(&q, &SceneInputs { payloads: &two, ..Default::default() }).unwrap_err();
    assert!(e.to_string().contains("ee_link"), "{e}");
    let stray = SceneInputs { tip_wrench: Some(Vector6::zeros()), payloads: &two[..1], ..Default::default() };
    assert!(matches!(robot.mass_matrix_with(&q, &stray), Err(SceneInputError::UnexpectedInput(_))));
    assert!(robot.frame_pose("nope", &q).unwrap_err().to_string().contains("nope"));
}

/// The scene's dynamics are generic over the scalar, as code generation
/// needs: f32 and the double-double reference agree with f64.
#[test]
fn scene_dynamics_run_on_every_scalar() {
    use dynagen::algorithms::{Loads, TipWrench, Workspace};
    use dynagen::scene::dynamics;
    use dynagen::spatial::{Force, Vec3};
    use dynagen::{DoubleDouble, Scalar};

    let scene = Scene::new()
        .subtree("panda_link1", &["panda_hand"])
        .lock("panda_joint1", 0.6)
        .lock("panda_finger_joint1", 0.02)
        .payload("panda_hand", PayloadInertia::new(0.5, [0.0, 0.0, 0.05], [1e-3, 1e-3, 5e-4, 0.0, 0.0, 0.0]))
        .armature("panda_joint3", 0.2)
        .viscous("panda_joint2", 0.7)
        .coulomb("panda_joint6", 1.5)
        .tip_wrench("panda_hand")
        .apply(&model("panda"))
        .unwrap();
    let n = scene.dof();
    assert_eq!(n, 6);
    let (q, qd, qdd) = (state(n, 7, 2.0), state(n, 8, 1.0), state(n, 9, 3.0));
    let w = [0.2, -0.1, 0.3, 4.0, -2.0, 6.0];
    let gravity = scene.gravity_vector(None).unwrap();

    fn run<S: Scalar>(
        scene: &SceneModel,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        w: [f64; 6],
        g: Vec3<f64>,
    ) -> [Vec<f64>; 3] {
        let n = scene.dof();
        let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
        let (q, qd, qdd) = (c(q), c(qd), c(qdd));
        let g = Vec3::<S>::from_f64(&g);
        let tips =
            [TipWrench { frame: scene.tip_wrench_frame.unwrap(), wrench: Force::from_array(w.map(S::from_f64)) }];
        let mut ws = Workspace::<S>::new(&scene.model);
        let (mut tau, mut m, mut qdd2) = (vec![S::zero(); n], vec![S::zero(); n * n], vec![S::zero(); n]);
        dynamics::inverse_dynamics(scene, &mut ws, &q, &qd, &qdd, Loads::gravity(&g).with_tips(&tips), &mut tau);
        dynamics::mass_matrix(scene, &mut ws, &q, &mut m);
        dynamics::forward_dynamics(scene, &mut ws, &q, &qd, &tau, Loads::gravity(&g).with_tips(&tips), &mut qdd2);
        let f = |x: &[S]| x.iter().map(|v| v.to_f64().unwrap()).collect::<Vec<f64>>();
        [f(&tau), f(&m), f(&qdd2)]
    }
    let [tau, m, back] = run::<f64>(&scene, q.as_slice(), qd.as_slice(), qdd.as_slice(), w, gravity);
    assert_close(&back, qdd.as_slice(), 1e-11, "f64 FD(ID)");
    let [tau32, m32, back32] = run::<f32>(&scene, q.as_slice(), qd.as_slice(), qdd.as_slice(), w, gravity);
    assert_close(&tau32, &tau, 1e-5, "f32 tau");
    assert_close(&m32, &m, 1e-5, "f32 M");
    assert_close(&back32, qdd.as_slice(), 1e-3, "f32 FD(ID)");
    let [tau_dd, m_dd, back_dd] = run::<DoubleDouble>(&scene, q.as_slice(), qd.as_slice(), qdd.as_slice(), w, gravity);
    assert_close(&tau, &tau_dd, 1e-13, "f64 tau against double-double");
    assert_close(&m, &m_dd, 1e-13, "f64 M against double-double");
    assert_close(&back_dd, qdd.as_slice(), 1e-25, "double-double FD(ID)");
    // and the numeric API runs the same code
    let mut robot = SceneRobot::new(scene);
    let inputs = SceneInputs { tip_wrench: Some(Vector6::from(w)), ..Default::default() };
    assert_eq!(robot.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap().as_slice(), &tau[..]);
}

/// The empty scene rebuilds the model through a description: it must give
/// the same robot, on every bundled robot, on a Modern Robotics chain with a
/// non-unit screw axis, and on a pendulum of point masses.
#[test]
fn the_empty_scene_is_the_robot_itself() {
    use dynagen::model::{Inertial, JointDescription};
    use nalgebra::{dmatrix, Matrix4, Matrix6};
    let mut robots: Vec<(String, Model)> =
        ["ur5", "panda", "torso_two_arms", "planar_2link"].iter().map(|n| (n.to_string(), model(n))).collect();
    let m01 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.089159, 0., 0., 0., 1.);
    let m12 = Matrix4::new(0., 0., 1., 0.28, 0., 1., 0., 0.13585, -1., 0., 0., 0., 0., 0., 0., 1.);
    let m23 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., -0.1197, 0., 0., 1., 0.395, 0., 0., 0., 1.);
    let m34 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.14225, 0., 0., 0., 1.);
    let g1 = Matrix6::from_diagonal(&Vector6::new(0.010267, 0.010267, 0.00666, 3.7, 3.7, 3.7));
    let g2 = Matrix6::from_diagonal(&Vector6::new(0.22689, 0.22689, 0.0151074, 8.393, 8.393, 8.393));
    let g3 = Matrix6::from_diagonal(&Vector6::new(0.0494433, 0.0494433, 0.004095, 2.275, 2.275, 2.275));
    let slist = dmatrix![1., 0., 0.; 0., 1., 1.; 1., 0., 0.; 0., -0.089, -0.089; 1., 0., 0.; 0., 0., 0.425];
    robots.push(("mr".into(), Model::from_modern_robotics(&[m01, m12, m23, m34], &[g1, g2, g3], &slist).unwrap()));
    let pendulum = dynagen::RobotBuilder::new("double_pendulum")
        .link("base", None)
        .link("a", Some(Inertial::point_mass(1.0, [0.0, 0.0, -1.0])))
        .link("b", Some(Inertial::point_mass(0.5, [0.3, 0.0, -0.7])))
        .joint(JointDescription::revolute("j1", "base", "a", [0.0, 1.0, 0.0]))
        .joint(JointDescription::revolute("j2", "a", "b", [0.0, 1.0, 0.0]).origin([0.0, 0.0, -1.0], [0.0, 0.0, 0.0]))
        .build()
        .unwrap();
    robots.push(("pendulum".into(), pendulum));
    for (name, m) in robots {
        let scene = Scene::new().apply(&m).unwrap();
        assert_eq!(scene.joint_names(), m.joint_names(), "{name}");
        assert_eq!(scene.model.frames.len(), m.frames.len(), "{name}: frames");
        for f in &m.frames {
            assert!(scene.model.frame_index(&f.name).is_some(), "{name}: frame {} lost", f.name);
        }
        let mut full = Robot::new(m);
        compare_with_full(&scene, &mut full, &[], &[], 11);
    }
}

#[test]
fn into_calls_match_and_check_their_outputs() {
    let scene = Scene::new().tip_wrench("ee_link").armature("elbow_joint", 0.2).coulomb("wrist_1_joint", 1.0);
    let mut robot = SceneRobot::new(scene.apply(&model("ur5")).unwrap());
    assert_eq!(robot.scene().scene, scene);
    let w = Vector6::new(1.0, 0.0, -1.0, 3.0, 2.0, -4.0);
    let inputs = SceneInputs { tip_wrench: Some(w), ..Default::default() };
    let (q, qd, qdd) = (state(6, 1, 2.0), state(6, 2, 2.0), state(6, 3, 2.0));
    let mut out = DVector::zeros(6);
    robot.inverse_dynamics_into(&q, &qd, &qdd, &inputs, &mut out).unwrap();
    assert_eq!(out, robot.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap());
    let tau = out.clone();
    robot.forward_dynamics_into(&q, &qd, &tau, &inputs, &mut out).unwrap();
    assert_close(out.as_slice(), qdd.as_slice(), 1e-11, "FD into");
    robot.bias_forces_into(&q, &qd, &inputs, &mut out).unwrap();
    assert_eq!(out, robot.bias_forces_with(&q, &qd, &inputs).unwrap());
    robot.gravity_torques_into(&q, &inputs, &mut out).unwrap();
    assert_eq!(out, robot.gravity_torques(&q).unwrap());
    robot.coriolis_into(&q, &qd, &inputs, &mut out).unwrap();
    assert_eq!(out, robot.coriolis(&q, &qd).unwrap());
    let mut m = DMatrix::zeros(6, 6);
    robot.mass_matrix_into(&q, &inputs, &mut m).unwrap();
    assert_eq!(m, robot.mass_matrix(&q).unwrap());
    let mut short = DVector::zeros(5);
    let e = robot.inverse_dynamics_into(&q, &qd, &qdd, &inputs, &mut short).unwrap_err();
    assert!(e.to_string().contains("tau"), "{e}");
    let mut wrong = DMatrix::zeros(6, 5);
    assert!(robot.mass_matrix_into(&q, &inputs, &mut wrong).unwrap_err().to_string().contains('M'));
}

/// The TOML example of the module documentation is a valid scene for the UR5.
#[test]
fn the_documented_toml_example_works() {
    let src = std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src/scene/mod.rs")).unwrap();
    let lines: Vec<&str> = src.lines().map(|l| l.strip_prefix("//!").unwrap_or("")).collect();
    let start = lines.iter().position(|l| l.trim() == "```toml").expect("a toml example") + 1;
    let end = start + lines[start..].iter().position(|l| l.trim() == "```").unwrap();
    let text: String = lines[start..end].iter().map(|l| format!("{}\n", l.strip_prefix(' ').unwrap_or(l))).collect();
    let scene = Scene::from_toml_str(&text).unwrap();
    assert_eq!(scene.gravity, Gravity::Constant([0.0, 0.0, -9.81]));
    assert_eq!(scene.locks, [("wrist_3_joint".to_string(), 0.0)]);
    assert_eq!(scene.payloads.len(), 2);
    let applied = scene.apply(&model("ur5")).unwrap();
    assert_eq!(applied.dof(), 5);
    assert_eq!(applied.input_payloads.len(), 1);
    assert_eq!(applied.armature[0], 0.1);
}

/// The documented way to keep a branch's mass: a tip inside it, its joints
/// locked. The torso's joint then carries the right arm, rigid.
#[test]
fn a_locked_branch_with_a_tip_keeps_its_mass() {
    let held = [("right_shoulder_joint", 0.4), ("right_elbow_joint", -0.8), ("right_wrist_joint", 0.2)];
    let mut s = Scene::new().subtree("base", &["left_ee", "right_ee"]);
    for (j, q) in held {
        s = s.lock(j, q);
    }
    let scene = s.apply(&model("torso_two_arms")).unwrap();
    assert!(scene.warnings.is_empty());
    assert_eq!(scene.joint_names(), ["torso_yaw_joint", "left_shoulder_joint", "left_elbow_joint", "left_wrist_joint"]);
    compare_with_full(&scene, &mut full("torso_two_arms"), &held, &[], 12);
}

/// Armature inside the articulated-body algorithm (D_i = S_iᵀU_i + a_i)
/// against the mass matrix with the armature on its diagonal, solved by
/// nalgebra's LU, and against the scene's CRBA + LᵀDL path, on the panda
/// (branched hand merged) and the two-armed torso, with gravity, friction and
/// a tip wrench.
#[test]
fn armature_in_the_articulated_body_algorithm_matches_m_plus_armature_solve() {
    use dynagen::algorithms::{Loads, TipWrench, Workspace};
    use dynagen::scene::dynamics;
    use dynagen::spatial::Force;
    for (name, scene) in [
        (
            "panda",
            Scene::new()
                .armature("panda_joint1", 0.4)
                .armature("panda_joint4", 0.05)
                .armature("panda_finger_joint1", 0.3)
                .viscous("panda_joint2", 0.5)
                .tip_wrench("panda_hand"),
        ),
        ("torso_two_arms", Scene::new().armature("left_elbow_joint", 0.2).armature("right_shoulder_joint", 1e-3)),
        ("ur5", Scene::new().armature("shoulder_lift_joint", 2.0).tip_wrench("ee_link")),
    ] {
        let scene = scene.apply(&model(name)).unwrap();
        let n = scene.dof();
        let g = scene.gravity_vector(None).unwrap();
        let mut ws = Workspace::<f64>::new(&scene.model);
        for seed in 0..5u64 {
            let (q, qd, tau) = (state(n, 40 + seed, 2.0), state(n, 50 + seed, 1.5), state(n, 60 + seed, 10.0));
            let tips: Vec<TipWrench<f64>> = scene
                .tip_wrench_frame
                .map(|frame| TipWrench { frame, wrench: Force::from_array([0.1, -0.2, 0.3, 3.0, 1.0, -5.0]) })
                .into_iter()
                .collect();
            let (mut aba, mut ldlt) = (vec![0.0; n], vec![0.0; n]);
            let (q, qd, tau) = (q.as_slice(), qd.as_slice(), tau.as_slice());
            dynamics::forward_dynamics(&scene, &mut ws, q, qd, tau, Loads::gravity(&g).with_tips(&tips), &mut aba);
            dynamics::forward_dynamics_ldlt(
                &scene,
                &mut ws,
                q,
                qd,
                tau,
                Loads::gravity(&g).with_tips(&tips),
                &mut ldlt,
            );
            // M + diag(a) and τ − h − JᵀF − friction, solved by LU.
            let mut m = vec![0.0; n * n];
            dynamics::mass_matrix(&scene, &mut ws, q, &mut m);
            let mut rhs = vec![0.0; n];
            dynamics::inverse_dynamics(
                &scene,
                &mut ws,
                q,
                qd,
                &vec![0.0; n],
                Loads::gravity(&g).with_tips(&tips),
                &mut rhs,
            );
            let rhs = DVector::from_iterator(n, tau.iter().zip(&rhs).map(|(t, h)| t - h));
            let lu = DMatrix::from_row_slice(n, n, &m).lu().solve(&rhs).unwrap();
            assert_close(&aba, lu.as_slice(), 1e-11, &format!("{name}: ABA with armature vs LU"));
            assert_close(&aba, &ldlt, 1e-11, &format!("{name}: ABA with armature vs LTDL"));
            // and armature changes the answer (the same τ − friction, without it)
            let mut plain = vec![0.0; n];
            let mut scratch = tau.to_vec();
            dynamics::sub_friction(&scene, qd, &mut scratch);
            dynagen::algorithms::aba::aba(
                &scene.model,
                &mut ws,
                q,
                qd,
                &scratch,
                Loads::gravity(&g).with_tips(&tips),
                &mut plain,
            );
            assert!(plain.iter().zip(&aba).any(|(a, b)| (a - b).abs() > 1e-6), "{name}: armature had no effect");
        }
    }
}
