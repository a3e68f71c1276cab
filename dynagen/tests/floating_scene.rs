//! Scenes on a floating base against independent computations with the
//! full model ([`Robot`]) on the legged manipulator (Go1 legs, a Z1 arm,
//! a floating trunk): armature and friction against their formulas, on the
//! joints only; payloads (constant and run-time, on the floating trunk and
//! on the arm) against a URDF with the payload as a fixed link; tip
//! wrenches (at a foot and at the base) against Jᵀ F with the body
//! Jacobian; gravity in the world frame; locked joints against the full
//! model's entries with the joint held; a sub-tree of the legs against a
//! URDF without the arm; a sub-tree on the arm's mount against the full
//! model with the base held level. `tests/floating_pinocchio.rs` checks a
//! scene against Pinocchio, `tests/codegen_scene.rs` the generated code
//! against [`SceneRobot`].

mod support;

use dynagen::scene::{Gravity, PayloadInertia, Scene, SceneInputs, SceneModel, SceneRobot, SceneWarning};
use dynagen::{Model, Robot};
use nalgebra::{DMatrix, DVector, Vector3, Vector6};
use support::{rel_err, Rng};

fn legged_manipulator() -> Model {
    support::model("legged_manipulator").with_floating_base()
}

/// The legged manipulator's URDF text.
fn urdf() -> String {
    std::fs::read_to_string(support::robot_path("legged_manipulator")).unwrap()
}

/// A random floating state of `model`: q (a unit quaternion), q̇ of norm up
/// to `speed`, q̈ and τ.
fn state(model: &Model, rng: &mut Rng, speed: f64) -> [DVector<f64>; 4] {
    let (nq, nv) = (model.nq(), model.nv());
    let mut q = DVector::from_vec(rng.vec(nq, 2.0));
    let norm = q.rows(3, 4).norm();
    q.rows_mut(3, 4).iter_mut().for_each(|x| *x /= norm);
    let qd = DVector::from_vec(rng.vec(nv, 1.0));
    let qd = &qd * (speed * rng.unit() / qd.norm());
    [q, qd, DVector::from_vec(rng.vec(nv, 5.0)), DVector::from_vec(rng.vec(nv, 20.0))]
}

#[track_caller]
fn close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    let e = rel_err(got, want, 1.0);
    assert!(e < tol, "{what}: relative error {e:e}\n got {got:?}\nwant {want:?}");
}

/// Armature adds a·q̈ and friction b·q̇ + f·σ(q̇) to the joints' rows of τ
/// and h, and armature to the joints' diagonal of M; the base's six rows
/// get neither. Forward dynamics inverts the scene's inverse dynamics.
#[test]
fn armature_and_friction_act_on_the_joints_only() {
    let model = legged_manipulator();
    let scene = Scene::new()
        .armature("FL_hip_joint", 0.011)
        .armature("arm_joint2", 0.004)
        .viscous("RR_calf_joint", 0.3)
        .coulomb("arm_joint1", 1.2)
        .coulomb_velocity(0.05);
    let applied = scene.apply(&model).unwrap();
    assert!(applied.model.is_floating() && applied.model == model, "a scene that reduces nothing keeps the model");
    let mut sr = SceneRobot::new(applied);
    let mut full = Robot::new(model.clone());
    let j = |name: &str| 6 + model.joint_index(name).unwrap();
    let mut rng = Rng::new(3);
    for _ in 0..5 {
        let [q, qd, qdd, tau] = state(&model, &mut rng, 50.0);
        let mut extra = DVector::zeros(model.nv());
        extra[j("FL_hip_joint")] += 0.011 * qdd[j("FL_hip_joint")];
        extra[j("arm_joint2")] += 0.004 * qdd[j("arm_joint2")];
        let mut friction = DVector::zeros(model.nv());
        friction[j("RR_calf_joint")] = 0.3 * qd[j("RR_calf_joint")];
        let v = qd[j("arm_joint1")];
        friction[j("arm_joint1")] = 1.2 * v / (v * v + 0.05 * 0.05).sqrt();
        let want = full.inverse_dynamics(&q, &qd, &qdd).unwrap() + &extra + &friction;
        let got = sr.inverse_dynamics(&q, &qd, &qdd).unwrap();
        close(got.as_slice(), want.as_slice(), 1e-13, "tau");
        let h = sr.bias_forces(&q, &qd).unwrap();
        close(h.as_slice(), (full.bias_forces(&q, &qd).unwrap() + &friction).as_slice(), 1e-13, "h");
        let mut m = full.mass_matrix(&q).unwrap();
        m[(j("FL_hip_joint"), j("FL_hip_joint"))] += 0.011;
        m[(j("arm_joint2"), j("arm_joint2"))] += 0.004;
        close(sr.mass_matrix(&q).unwrap().as_slice(), m.as_slice(), 1e-14, "M");
        close(sr.gravity_torques(&q).unwrap().as_slice(), full.gravity_torques(&q).unwrap().as_slice(), 1e-14, "g");
        let qdd_s = sr.forward_dynamics(&q, &qd, &tau).unwrap();
        close(sr.inverse_dynamics(&q, &qd, &qdd_s).unwrap().as_slice(), tau.as_slice(), 1e-10, "ID(FD(τ))");
        let by_m = m.clone().cholesky().unwrap().solve(&(&tau - &h));
        close(qdd_s.as_slice(), by_m.as_slice(), 1e-9, "q̈ against (M + diag a)⁻¹(τ − h)");
    }
}

/// The legged manipulator's URDF with a payload fixed to `link` as a link.
fn with_payload_links(payloads: &[(&str, PayloadInertia)]) -> Model {
    let mut text = urdf();
    for (k, (link, p)) in payloads.iter().enumerate() {
        let i = p.inertia;
        let extra = format!(
            "<link name=\"payload{k}\"><inertial><origin xyz=\"{} {} {}\"/><mass value=\"{}\"/><inertia ixx=\"{}\" \
             iyy=\"{}\" izz=\"{}\" ixy=\"{}\" ixz=\"{}\" iyz=\"{}\"/></inertial></link><joint name=\"payload{k}_fixed\" \
             type=\"fixed\"><parent link=\"{link}\"/><child link=\"payload{k}\"/></joint></robot>",
            p.com[0], p.com[1], p.com[2], p.mass, i[0], i[1], i[2], i[3], i[4], i[5]
        );
        text = text.replace("</robot>", &extra);
    }
    Model::from_urdf_str(&text).unwrap().with_floating_base()
}

/// Payloads on the floating trunk (the base) and on the arm's last link,
/// constant and as run-time inputs, against the robot with each payload a
/// fixed link: τ, M, h, g and q̈ (the base's payload changes the base rows
/// and, through them, every acceleration).
#[test]
fn payloads_on_the_base_and_the_arm_equal_payload_links() {
    let model = legged_manipulator();
    let p_trunk = PayloadInertia::new(3.0, [0.05, -0.02, 0.06], [0.02, 0.03, 0.04, 0.002, -0.001, 0.0005]);
    let p_arm = PayloadInertia::new(0.5, [0.04, 0.0, 0.01], [0.0005, 0.0006, 0.0004, 0.0, 0.0, 0.0]);
    let mut full = Robot::new(with_payload_links(&[("trunk", p_trunk), ("arm_link06", p_arm)]));
    let constant = Scene::new().payload("trunk", p_trunk).payload("arm_link06", p_arm).apply(&model).unwrap();
    let input = Scene::new().payload_input("trunk").payload_input("arm_link06").apply(&model).unwrap();
    for s in [&constant, &input] {
        assert!(s.warnings.is_empty(), "a payload on a floating base warns of nothing: {:?}", s.warnings);
    }
    assert_eq!(input.input_payloads[0].body, None, "the trunk is the base");
    let values = [p_trunk, p_arm];
    let (mut rc, mut ri) = (SceneRobot::new(constant), SceneRobot::new(input));
    let (none, given) = (SceneInputs::default(), SceneInputs { payloads: &values, ..Default::default() });
    let mut rng = Rng::new(11);
    for _ in 0..5 {
        let [q, qd, qdd, tau] = state(&model, &mut rng, 20.0);
        let want = [
            full.inverse_dynamics(&q, &qd, &qdd).unwrap(),
            full.bias_forces(&q, &qd).unwrap(),
            full.gravity_torques(&q).unwrap(),
            full.forward_dynamics(&q, &qd, &tau).unwrap(),
        ];
        let m = full.mass_matrix(&q).unwrap();
        for (r, i) in [(&mut rc, &none), (&mut ri, &given)] {
            let got = [
                r.inverse_dynamics_with(&q, &qd, &qdd, i).unwrap(),
                r.bias_forces_with(&q, &qd, i).unwrap(),
                r.gravity_torques_with(&q, i).unwrap(),
                r.forward_dynamics_with(&q, &qd, &tau, i).unwrap(),
            ];
            for ((g, w), what) in got.iter().zip(&want).zip(["tau", "h", "g", "qdd"]) {
                close(g.as_slice(), w.as_slice(), 1e-12, what);
            }
            close(r.mass_matrix_with(&q, i).unwrap().as_slice(), m.as_slice(), 1e-12, "M");
        }
    }
    // The whole robot's mass on the base's diagonal.
    let q = state(&model, &mut rng, 0.0)[0].clone();
    let mass = ri.mass_matrix_with(&q, &given).unwrap()[(3, 3)];
    assert!((mass - (full.total_mass().unwrap())).abs() < 1e-12, "{mass}");
}

/// A tip wrench at a foot and at the floating trunk itself adds `J_bᵀ F`
/// (the frame's body Jacobian, NV columns) to τ and takes it off q̈'s
/// right-hand side; at the base it loads the base rows only.
#[test]
fn tip_wrenches_at_a_foot_and_at_the_base_are_jacobian_transposed_times_the_wrench() {
    let model = legged_manipulator();
    let mut full = Robot::new(model.clone());
    let mut rng = Rng::new(5);
    for frame in ["RL_foot", "trunk", "arm_ee"] {
        let applied = Scene::new().tip_wrench(frame).apply(&model).unwrap();
        assert!(applied.warnings.is_empty(), "{frame}: {:?}", applied.warnings);
        let mut sr = SceneRobot::new(applied);
        for _ in 0..3 {
            let [q, qd, qdd, tau] = state(&model, &mut rng, 20.0);
            let f = Vector6::from_iterator(rng.vec(6, 30.0));
            let inputs = SceneInputs { tip_wrench: Some(f), ..Default::default() };
            let jt_f = full.body_jacobian(frame, &q).unwrap().transpose() * f;
            let want = full.inverse_dynamics(&q, &qd, &qdd).unwrap() + &jt_f;
            close(sr.inverse_dynamics_with(&q, &qd, &qdd, &inputs).unwrap().as_slice(), want.as_slice(), 1e-12, frame);
            let want = full.forward_dynamics(&q, &qd, &(&tau - &jt_f)).unwrap();
            let got = sr.forward_dynamics_with(&q, &qd, &tau, &inputs).unwrap();
            close(got.as_slice(), want.as_slice(), 1e-12, frame);
            if frame == "trunk" {
                assert!(jt_f.rows(6, model.dof()).iter().all(|x| *x == 0.0));
            }
        }
    }
}

/// Gravity on a floating base is in the world frame, never re-expressed: a
/// constant, an input and the default against the plain solver with that
/// gravity; none leaves g = 0 and h = C(q, q̇)q̇.
#[test]
fn gravity_is_given_in_the_world_frame() {
    let model = legged_manipulator();
    let g = [1.5, -0.7, -9.6];
    let mut tilted = Robot::new(model.clone().with_gravity(g));
    let mut plain = Robot::new(model.clone());
    let mut constant = SceneRobot::new(Scene::new().gravity(Gravity::Constant(g)).apply(&model).unwrap());
    let mut input = SceneRobot::new(Scene::new().gravity(Gravity::Input).apply(&model).unwrap());
    let mut none = SceneRobot::new(Scene::new().gravity(Gravity::None).apply(&model).unwrap());
    let mut default = SceneRobot::new(Scene::new().apply(&model).unwrap());
    let gi = SceneInputs { gravity: Some(Vector3::from(g)), ..Default::default() };
    let mut rng = Rng::new(7);
    for _ in 0..3 {
        let [q, qd, qdd, _] = state(&model, &mut rng, 20.0);
        let want = tilted.inverse_dynamics(&q, &qd, &qdd).unwrap();
        close(constant.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), want.as_slice(), 1e-14, "constant");
        close(input.inverse_dynamics_with(&q, &qd, &qdd, &gi).unwrap().as_slice(), want.as_slice(), 1e-14, "input");
        let want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
        close(default.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), want.as_slice(), 1e-15, "default");
        assert!(none.gravity_torques(&q).unwrap().iter().all(|x| *x == 0.0));
        let c = plain.coriolis_torques(&q, &qd).unwrap();
        close(none.bias_forces(&q, &qd).unwrap().as_slice(), c.as_slice(), 1e-14, "none");
    }
}

/// τ, M, h and g of a reduced scene against the full robot with the
/// removed joints held at `held` (velocity and acceleration zero) and the
/// base and kept joints at the reduced state.
fn compare_with_full(scene: &SceneModel, full: &mut Robot, held: &[(&str, f64)], seed: u64) {
    let reduced = &scene.model;
    assert!(reduced.is_floating());
    let fm = full.model().clone();
    // where each reduced velocity coordinate is in the full robot's
    let idx: Vec<usize> =
        (0..6).chain(scene.joint_names().iter().map(|n| 6 + fm.joint_index(n).expect("a kept joint"))).collect();
    let mut sr = SceneRobot::new(scene.clone());
    let mut rng = Rng::new(seed);
    for _ in 0..4 {
        let [q, qd, qdd, _] = state(reduced, &mut rng, 20.0);
        let [mut qf, mut qdf, mut qddf, _] = state(&fm, &mut rng, 20.0);
        qf.rows_mut(0, 7).copy_from(&q.rows(0, 7));
        for (name, pos) in held {
            let i = fm.joint_index(name).unwrap();
            (qf[7 + i], qdf[6 + i], qddf[6 + i]) = (*pos, 0.0, 0.0);
        }
        for (r, &k) in idx.iter().enumerate() {
            if k >= 6 {
                qf[k + 1] = q[r + 1];
            }
            (qdf[k], qddf[k]) = (qd[r], qdd[r]);
        }
        assert_eq!(held.len() + scene.dof(), fm.dof(), "every full joint is kept or held");
        let pick = |v: &DVector<f64>| idx.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        let pick_m =
            |m: &DMatrix<f64>| idx.iter().flat_map(|&r| idx.iter().map(move |&c| m[(r, c)])).collect::<Vec<_>>();
        let tau = sr.inverse_dynamics(&q, &qd, &qdd).unwrap();
        close(tau.as_slice(), &pick(&full.inverse_dynamics(&qf, &qdf, &qddf).unwrap()), 1e-12, "tau");
        let m = sr.mass_matrix(&q).unwrap();
        close(m.transpose().as_slice(), &pick_m(&full.mass_matrix(&qf).unwrap()), 1e-12, "M");
        close(sr.bias_forces(&q, &qd).unwrap().as_slice(), &pick(&full.bias_forces(&qf, &qdf).unwrap()), 1e-12, "h");
        close(sr.gravity_torques(&q).unwrap().as_slice(), &pick(&full.gravity_torques(&qf).unwrap()), 1e-12, "g");
    }
}

/// Locked joints merge their bodies into their parents (a hip's into the
/// floating trunk), the base stays floating, and the reduced τ, M, h and g
/// are the full robot's entries with the joints held at their locks.
#[test]
fn locked_joints_merge_and_the_base_keeps_floating() {
    let model = legged_manipulator();
    let locks = [("FR_hip_joint", 0.2), ("arm_joint1", -0.4), ("arm_joint4", 0.9)];
    let scene = locks.iter().fold(Scene::new(), |s, (j, q)| s.lock(j, *q)).armature("FL_hip_joint", 0.0);
    let applied = scene.apply(&model).unwrap();
    assert!(applied.model.is_floating());
    assert_eq!((applied.model.nq(), applied.model.nv()), (model.nq() - 3, model.nv() - 3));
    // FR_hip and arm_link01 (below arm_link00, fixed to the trunk) merged
    // into the trunk: the base carries their mass now
    let merged = applied.model.base_inertia.mass - model.base_inertia.mass;
    assert!((merged - (0.510299 + 0.67332551)).abs() < 1e-12, "{merged}");
    compare_with_full(&applied, &mut Robot::new(model), &locks, 21);
}

/// A sub-tree rooted at the floating trunk keeps the floating base: the
/// legs alone (the arm dropped, with a warning) are the robot without the
/// arm in its file; with the arm's tool as a tip and its joints locked,
/// the arm stays, rigid, as the full robot with the arm held.
#[test]
fn a_sub_tree_rooted_at_the_base_keeps_it_floating() {
    let model = legged_manipulator();
    let feet = ["FL_foot", "FR_foot", "RL_foot", "RR_foot"];
    let legs = Scene::new().subtree("trunk", &feet).apply(&model).unwrap();
    assert!(legs.model.is_floating() && legs.dof() == 12);
    assert!(
        matches!(&legs.warnings[..], [SceneWarning::DroppedBranch { joint, .. }] if joint == "arm_joint1"),
        "{:?}",
        legs.warnings
    );
    // the file without the arm's moving part (its base, fixed to the trunk,
    // is part of the floating body)
    let text = urdf();
    let cut = text.find("  <joint name=\"arm_joint1\"").unwrap();
    let quadruped = Model::from_urdf_str(&format!("{}</robot>\n", &text[..cut])).unwrap().with_floating_base();
    compare_with_full(&legs, &mut Robot::new(quadruped), &[], 31);
    let held = [("arm_joint1", 0.3), ("arm_joint2", 1.0), ("arm_joint3", -1.1)]
        .into_iter()
        .chain([("arm_joint4", 0.2), ("arm_joint5", -0.5), ("arm_joint6", 0.7)])
        .collect::<Vec<_>>();
    let mut tips = feet.to_vec();
    tips.push("arm_ee");
    let scene = held.iter().fold(Scene::new().subtree("trunk", &tips), |s, (j, q)| s.lock(j, *q));
    let rigid_arm = scene.apply(&model).unwrap();
    assert!(rigid_arm.warnings.is_empty(), "{:?}", rigid_arm.warnings);
    compare_with_full(&rigid_arm, &mut Robot::new(model), &held, 41);
}

/// A sub-tree rooted on the arm's mount (a link fixed to the trunk, not
/// the trunk) is a fixed-base arm, with a warning naming both links: its τ
/// and M are the full floating robot's arm entries with the base held
/// still and level (identity quaternion) and the legs still.
#[test]
fn a_sub_tree_below_the_floating_base_is_a_fixed_base_robot() {
    let model = legged_manipulator();
    let arm = Scene::new().subtree("arm_link00", &["arm_ee"]).apply(&model).unwrap();
    assert!(!arm.model.is_floating() && arm.dof() == 6);
    let w = arm.warnings.iter().find(|w| matches!(w, SceneWarning::SubTreeOffFloatingBase { .. })).expect("a warning");
    let text = w.to_string();
    assert!(text.contains("\"arm_link00\"") && text.contains("\"trunk\"") && text.contains("fixed-base"), "{text}");
    let mut full = Robot::new(model.clone());
    let mut sr = SceneRobot::new(arm);
    let mut rng = Rng::new(51);
    let (nq, nv, n) = (model.nq(), model.nv(), model.dof());
    for _ in 0..4 {
        let (q, qd, qdd) = (rng.vec(6, 2.0), rng.vec(6, 3.0), rng.vec(6, 5.0));
        let (mut qf, mut qdf, mut qddf) = (DVector::zeros(nq), DVector::zeros(nv), DVector::zeros(nv));
        qf[6] = 1.0;
        for k in 0..6 {
            let i = 6 + model.joint_index(&format!("arm_joint{}", k + 1)).unwrap();
            (qf[i + 1], qdf[i], qddf[i]) = (q[k], qd[k], qdd[k]);
        }
        let want = full.inverse_dynamics(&qf, &qdf, &qddf).unwrap();
        let (q, qd, qdd) = (DVector::from_vec(q), DVector::from_vec(qd), DVector::from_vec(qdd));
        let got = sr.inverse_dynamics(&q, &qd, &qdd).unwrap();
        close(got.as_slice(), &want.as_slice()[nv - 6..], 1e-12, "arm tau");
        let m = full.mass_matrix(&qf).unwrap();
        let arm_m = m.view((6 + n - 6, 6 + n - 6), (6, 6)).clone_owned();
        close(sr.mass_matrix(&q).unwrap().as_slice(), arm_m.as_slice(), 1e-12, "arm M");
    }
}

/// A scene file for a floating base: every key applies, and TOML written
/// back reads the same.
#[test]
fn a_floating_scene_file_reads_and_applies() {
    let file = dynagen::scene::SceneFile::from_toml_file(support::scene_path("legged_manipulator")).unwrap();
    let applied = file.scene.apply(&legged_manipulator()).unwrap();
    assert!(applied.model.is_floating() && applied.warnings.is_empty(), "{:?}", applied.warnings);
    assert!(applied.has_armature() && applied.has_friction() && applied.tip_wrench_frame.is_some());
    let functions = file.code.functions.clone().unwrap();
    assert!(functions.contains(&dynagen::codegen::Function::FrameAccelerationBias("FL_foot".into())));
    let again = dynagen::scene::SceneFile::from_toml_str(&file.to_toml_string().unwrap()).unwrap();
    assert_eq!(again, file);
}

/// The numeric API of a floating scene checks NQ/NV lengths and the
/// quaternion as [`Robot`] does, naming them (the derivatives too).
#[test]
fn a_floating_scene_robot_checks_its_inputs() {
    let model = legged_manipulator();
    let mut sr = SceneRobot::new(Scene::new().armature("FL_hip_joint", 0.01).apply(&model).unwrap());
    assert_eq!((sr.nq(), sr.nv(), sr.dof()), (25, 24, 18));
    let mut q = DVector::zeros(25);
    q[6] = 1.0;
    let v = DVector::zeros(24);
    assert_eq!(sr.mass_matrix(&q).unwrap().shape(), (24, 24));
    let e = sr.inverse_dynamics(&DVector::zeros(18), &v, &v).unwrap_err().to_string();
    assert!(e.contains("NQ = n + 7"), "{e}");
    q[6] = 0.0;
    let e = sr.forward_dynamics(&q, &v, &v).unwrap_err().to_string();
    assert!(e.contains("quaternion") && e.contains("norm 0"), "{e}");
    q[6] = 1.0;
    let e = sr.inverse_dynamics_derivatives_with(&q, &v, &DVector::zeros(18), &SceneInputs::default());
    let e = e.unwrap_err().to_string();
    assert!(e.contains("qdd") && e.contains("NV = n + 6"), "{e}");
    let (dq, _) = sr.inverse_dynamics_derivatives_with(&q, &v, &v, &SceneInputs::default()).unwrap();
    assert_eq!(dq.shape(), (24, 24), "NV × NV derivatives (tests/derivatives.rs checks their values)");
}
