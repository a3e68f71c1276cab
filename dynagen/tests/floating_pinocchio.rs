//! The floating base against Pinocchio with a `JointModelFreeFlyer` root,
//! on a 12-joint quadruped (Unitree A1 parameters), the 7-joint
//! torso_two_arms, a random 20-joint tree (prismatic and fixed joints,
//! non-aligned axes, rotated origins), the 18-joint legged manipulator
//! (Go1 legs, a Z1 arm: its contact frames, and a scene with armature,
//! payloads and a tip wrench) and the 32-joint humanoid32 (TALOS
//! parameters), 10 states each with random unit quaternions and |q̇| of 2
//! and 50: the generic solver, and the generated functions (their traced
//! graphs, evaluated as the emitted code computes them, fused and unfused,
//! so that no 38×38 module is compiled in a test run).
//!
//! The values in `tests/data/pinocchio_floating_<robot>.json` were computed
//! by Pinocchio with `scripts/reference/make_pinocchio_floating.py`
//! (version, seed in each file's "source"), converted there to dynagen's
//! conventions ((angular; linear) base velocity and wrench, our joint order).

mod support;

use dynagen::algorithms::floating::{aba, centroidal, crba, forward_dynamics, kinematics, rnea};
use dynagen::algorithms::{Loads, Workspace};
use dynagen::codegen::{generate, generate_scene, payload_argument, CodegenOptions, Function, GeneratedFunction};
use dynagen::scene::{PayloadInertia, Scene, SceneInputs, SceneRobot};
use dynagen::spatial::Vec3;
use dynagen::{Model, Robot};
use nalgebra::{DMatrix, DVector, Vector6};
use serde_json::Value;
use std::path::Path;
use support::rel_err;

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn flat(v: &Value) -> Vec<f64> {
    v.as_array().expect("rows").iter().flat_map(vector).collect()
}

/// Pinocchio's values; the largest relative error seen, per quantity.
fn check(name: &str) -> Vec<(&'static str, f64)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(format!("tests/data/pinocchio_floating_{name}.json"))).unwrap(),
    )
    .unwrap();
    let model =
        Model::from_urdf_file(Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(data["robot"].as_str().unwrap()))
            .unwrap()
            .with_floating_base();
    let names: Vec<&str> = data["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
    assert_eq!(model.joint_names(), names, "{name}: joint order");
    let frame = model.frame_index(data["frame"].as_str().unwrap()).unwrap();
    let mass = data["total_mass"].as_f64().unwrap();
    assert!((centroidal::total_mass(&model) - mass).abs() < 1e-13 * mass, "{name}: total mass");
    let (nv, g) = (model.nv(), Vec3([0.0, 0.0, -9.81]));
    let mut ws = Workspace::new(&model);
    let mut worst: Vec<(&'static str, f64)> = Vec::new();
    let mut record = |what: &'static str, got: &[f64], want: &[f64], k: usize| {
        let e = rel_err(got, want, 1.0);
        assert!(e < 1e-12, "{name}, state {k}: {what} differs from Pinocchio by {e:e}");
        match worst.iter_mut().find(|(w, _)| *w == what) {
            Some((_, x)) => *x = x.max(e),
            None => worst.push((what, e)),
        }
    };
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let (q, qd, qdd, tau) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]), vector(&s["tau"]));
        let mut out = vec![0.0; nv];
        rnea::rnea(&model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut out);
        record("tau", &out, &vector(&s["tau_id"]), k);
        let mut m = vec![0.0; nv * nv];
        crba::crba(&model, &mut ws, &q, Loads::none(), &mut m);
        record("M", &m, &flat(&s["M"]), k);
        dynagen::algorithms::bias::bias_forces(&model, &mut ws, &q, &qd, Some(&g), &mut out);
        record("h", &out, &vector(&s["h"]), k);
        dynagen::algorithms::bias::gravity_torques(&model, &mut ws, &q, &g, &mut out);
        record("g", &out, &vector(&s["g"]), k);
        aba::aba(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut out);
        record("qdd (ABA)", &out, &vector(&s["qdd_fd"]), k);
        forward_dynamics::forward_dynamics_ldlt(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut out);
        record("qdd (CRBA + LTDL)", &out, &vector(&s["qdd_fd"]), k);
        kinematics::forward_kinematics(&model, &mut ws, &q);
        let pose = kinematics::frame_pose_world(&model, &ws, &q, frame).to_homogeneous();
        record("frame pose", &pose.concat(), &flat(&s["frame_pose"]), k);
        let mut j = vec![0.0; 6 * nv];
        kinematics::space_jacobian_world(&model, &ws, &q, frame, &mut j);
        record("Jacobian (world)", &j, &flat(&s["jacobian_world"]), k);
        kinematics::body_jacobian(&model, &ws, frame, &mut j);
        record("Jacobian (local)", &j, &flat(&s["jacobian_local"]), k);
        let c = centroidal::center_of_mass(&model, &mut ws, &q);
        record("centre of mass", &c.0, &vector(&s["com"]), k);
        centroidal::centroidal_momentum_matrix(&model, &mut ws, &q, &mut j);
        record("centroidal momentum matrix", &j, &flat(&s["centroidal_momentum_matrix"]), k);
    }
    println!("{name}: {worst:?}");
    check_robot_api(&data, model);
    worst
}

/// The same values through the checked numeric API ([`Robot`]), on nalgebra
/// types: every method takes NQ/NV-long vectors on a floating model.
fn check_robot_api(data: &Value, model: Model) {
    let frame = data["frame"].as_str().unwrap().to_string();
    let mut robot = Robot::new(model);
    let nv = robot.nv();
    assert_eq!((robot.nq(), nv), (robot.dof() + 7, robot.dof() + 6));
    let dv = |v: &Value| DVector::from_vec(vector(v));
    let mat = |m: &DMatrix<f64>| {
        (0..m.nrows()).flat_map(|r| m.row(r).iter().copied().collect::<Vec<_>>()).collect::<Vec<f64>>()
    };
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let (q, qd, qdd, tau) = (dv(&s["q"]), dv(&s["qd"]), dv(&s["qdd"]), dv(&s["tau"]));
        let ok = |what: &str, got: &[f64], want: &[f64]| {
            let e = rel_err(got, want, 1.0);
            assert!(e < 1e-12, "Robot, state {k}: {what} differs from Pinocchio by {e:e}");
        };
        ok("tau", robot.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), &vector(&s["tau_id"]));
        ok("M", robot.mass_matrix(&q).unwrap().as_slice(), &flat(&s["M"]));
        ok("h", robot.bias_forces(&q, &qd).unwrap().as_slice(), &vector(&s["h"]));
        ok("g", robot.gravity_torques(&q).unwrap().as_slice(), &vector(&s["g"]));
        ok("qdd", robot.forward_dynamics(&q, &qd, &tau).unwrap().as_slice(), &vector(&s["qdd_fd"]));
        let comp = robot.forward_dynamics_compensated(&q, &qd, &tau).unwrap();
        ok("qdd (compensated)", comp.as_slice(), &vector(&s["qdd_fd"]));
        ok("qdd (LTDL)", robot.forward_dynamics_ldlt(&q, &qd, &tau).unwrap().as_slice(), &vector(&s["qdd_fd"]));
        let c = robot.coriolis_torques(&q, &qd).unwrap() + robot.gravity_torques(&q).unwrap();
        ok("C q̇ + g", c.as_slice(), &vector(&s["h"]));
        let pose = robot.frame_pose(&frame, &q).unwrap();
        ok(
            "pose",
            &(0..4).flat_map(|r| (0..4).map(move |c| (r, c))).map(|(r, c)| pose[(r, c)]).collect::<Vec<_>>(),
            &flat(&s["frame_pose"]),
        );
        ok(
            "J world",
            &mat(&DMatrix::from_iterator(6, nv, robot.space_jacobian(&frame, &q).unwrap().iter().copied())),
            &flat(&s["jacobian_world"]),
        );
        ok(
            "J local",
            &mat(&DMatrix::from_iterator(6, nv, robot.body_jacobian(&frame, &q).unwrap().iter().copied())),
            &flat(&s["jacobian_local"]),
        );
        ok("com", robot.center_of_mass(&q).unwrap().as_slice(), &vector(&s["com"]));
        let ag = robot.centroidal_momentum_matrix(&q).unwrap();
        ok("A_G", &mat(&DMatrix::from_iterator(6, nv, ag.iter().copied())), &flat(&s["centroidal_momentum_matrix"]));
    }
}

#[test]
fn quadruped12_agrees_with_pinocchio() {
    check("quadruped12");
}

#[test]
fn torso_two_arms_floating_agrees_with_pinocchio() {
    check("torso_two_arms");
}

#[test]
fn random_tree20_agrees_with_pinocchio() {
    check("random_tree20");
}

#[test]
fn humanoid32_agrees_with_pinocchio() {
    check("humanoid32");
}

/// The functions of the default floating-base module of `name`, as traced
/// (what the emitted code computes, with its fused multiply-adds and
/// without), against Pinocchio's values; the largest relative error.
fn check_generated(name: &str) -> f64 {
    let (data, model) = load(name);
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    let mut worst = 0.0f64;
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        for f in &module.functions {
            let want = match f.name.as_str() {
                "inverse_dynamics" => vector(&s["tau_id"]),
                "mass_matrix" => flat(&s["M"]),
                "bias_forces" => vector(&s["h"]),
                "gravity_torques" => vector(&s["g"]),
                "forward_dynamics" => vector(&s["qdd_fd"]),
                other => panic!("{name}: unexpected function {other}"),
            };
            let args: Vec<Vec<f64>> = f.function.vectors().iter().map(|v| vector(&s[*v])).collect();
            let inputs: Vec<(&str, &[f64])> =
                f.function.vectors().iter().zip(&args).map(|(n, v)| (*n, v.as_slice())).collect();
            for (got, how) in [
                (f.traced.eval(&inputs).unwrap(), "unfused"),
                (f.traced.eval_fused(&f.traced.fusion(), &inputs).unwrap(), "fused"),
            ] {
                let e = rel_err(&got, &want, 1.0);
                assert!(e < 1e-12, "{name} generated {} ({how}), state {k}: {e:e} from Pinocchio", f.label());
                worst = worst.max(e);
            }
        }
    }
    println!("{name}: generated functions within {worst:.1e} of Pinocchio");
    worst
}

#[test]
fn generated_floating_functions_agree_with_pinocchio() {
    for name in ["quadruped12", "torso_two_arms", "random_tree20", "humanoid32"] {
        check_generated(name);
    }
}

#[test]
fn legged_manipulator_agrees_with_pinocchio() {
    check("legged_manipulator");
}

/// The legged manipulator's plain floating module, as emitted (both
/// forward dynamics traced, each checked), against Pinocchio: τ, M, h, g
/// and q̈ within 1e-12.
#[test]
fn legged_manipulator_module_agrees_with_pinocchio() {
    let (data, model) = load("legged_manipulator");
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    assert_eq!(module.functions.len(), 6);
    let mut worst = 0.0f64;
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let vectors: Vec<(&'static str, Vec<f64>)> = ["q", "qd", "qdd", "tau"].map(|n| (n, vector(&s[n]))).to_vec();
        for f in &module.functions {
            let (key, want) = match f.function {
                Function::InverseDynamics => ("tau_id", vector(&s["tau_id"])),
                Function::MassMatrix => ("M", flat(&s["M"])),
                Function::BiasForces => ("h", vector(&s["h"])),
                Function::GravityTorques => ("g", vector(&s["g"])),
                _ => ("qdd_fd", vector(&s["qdd_fd"])),
            };
            let e = rel_err(&f.traced.eval(&state_inputs(&vectors, f)).unwrap(), &want, 1.0);
            assert!(e < 1e-12, "state {k}: {} ({key}) differs from Pinocchio by {e:e}", f.label());
            worst = worst.max(e);
        }
    }
    println!("legged manipulator module: worst relative error {worst:.1e}");
}

/// `tests/data/pinocchio_floating_<name>.json` and its floating model.
fn load(name: &str) -> (Value, Model) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(dir.join(format!("tests/data/pinocchio_floating_{name}.json"))).unwrap();
    let data: Value = serde_json::from_str(&text).unwrap();
    let model =
        Model::from_urdf_file(dir.join("..").join(data["robot"].as_str().unwrap())).unwrap().with_floating_base();
    (data, model)
}

/// The state vectors a traced function reads, by name.
fn state_inputs<'a>(s: &'a [(&'static str, Vec<f64>)], f: &GeneratedFunction) -> Vec<(&'a str, &'a [f64])> {
    f.inputs.iter().filter_map(|(name, _)| s.iter().find(|(n, _)| n == name).map(|(n, v)| (*n, v.as_slice()))).collect()
}

/// The contact frames of the legged manipulator (its four feet and the
/// arm's tool) against Pinocchio: the world pose, the WORLD and LOCAL
/// Jacobians and the classical acceleration bias J̇q̇
/// (`getFrameClassicalAcceleration` at q̈ = 0, LOCAL), by the generic
/// solver ([`Robot`], [`SceneRobot`]) and by the module's frame functions
/// as emitted (their traces, fused and not).
#[test]
fn contact_frames_agree_with_pinocchio() {
    let (data, model) = load("legged_manipulator");
    let frames: Vec<&str> = data["contact_frames"].as_array().unwrap().iter().map(|f| f.as_str().unwrap()).collect();
    let functions: Vec<Function> = frames
        .iter()
        .flat_map(|f| Function::FRAME_KINDS.iter().map(|k| Function::frame_function(k, f).unwrap()))
        .collect();
    let module = generate(&model, &CodegenOptions::default().functions(functions)).unwrap();
    assert_eq!(module.functions.len(), 4 * frames.len());
    let mut robot = Robot::new(model.clone());
    let mut scene = SceneRobot::new(Scene::default().apply(&model).unwrap());
    let mut worst = 0.0f64;
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let (q, qd) = (DVector::from_vec(vector(&s["q"])), DVector::from_vec(vector(&s["qd"])));
        let mut ok = |what: String, got: &[f64], want: &[f64]| {
            let e = rel_err(got, want, 1.0);
            assert!(e < 1e-12, "state {k}: {what} differs from Pinocchio by {e:e}");
            worst = worst.max(e);
        };
        for frame in &frames {
            let c = &s["contacts"][*frame];
            let want = |kind: &str| match kind {
                "frame_pose" => flat(&c["pose"]),
                "frame_jacobian" => flat(&c["jacobian_local"]),
                "frame_world_jacobian" => flat(&c["jacobian_world"]),
                _ => vector(&c["acceleration_bias"]),
            };
            let rows = |m: nalgebra::Matrix6xX<f64>| m.transpose().as_slice().to_vec();
            let pose = robot.frame_pose(frame, &q).unwrap();
            ok(format!("{frame} pose"), pose.transpose().as_slice(), &want("frame_pose"));
            ok(
                format!("{frame} J world"),
                &rows(robot.space_jacobian(frame, &q).unwrap()),
                &want("frame_world_jacobian"),
            );
            ok(format!("{frame} J local"), &rows(robot.body_jacobian(frame, &q).unwrap()), &want("frame_jacobian"));
            let bias = robot.frame_acceleration_bias(frame, &q, &qd).unwrap();
            ok(format!("{frame} J̇q̇"), bias.as_slice(), &want("frame_acceleration_bias"));
            ok(
                format!("{frame} scene J world"),
                &rows(scene.frame_world_jacobian(frame, &q).unwrap()),
                &want("frame_world_jacobian"),
            );
            let bias = scene.frame_acceleration_bias(frame, &q, &qd).unwrap();
            ok(format!("{frame} scene J̇q̇"), bias.as_slice(), &want("frame_acceleration_bias"));
            let vectors = [("q", vector(&s["q"])), ("qd", vector(&s["qd"]))];
            for f in module.functions.iter().filter(|f| f.function.frame() == Some(frame)) {
                let inputs = state_inputs(&vectors, f);
                let want = want(f.function.name());
                ok(format!("{} (generated)", f.name), &f.traced.eval(&inputs).unwrap(), &want);
                let fused = f.traced.eval_fused(&f.traced.fusion(), &inputs).unwrap();
                ok(format!("{} (generated, fused)", f.name), &fused, &want);
            }
        }
    }
    println!("contact frames: worst relative error {worst:.1e}");
}

/// The scene of the data file: armature on every joint, constant payloads
/// (or the same as run-time inputs), a tip wrench at a foot as an input.
fn data_scene(data: &Value, inputs: bool) -> (Scene, Vec<PayloadInertia>, [f64; 6], String) {
    let sc = &data["scene"];
    let mut scene = Scene::new();
    for (joint, a) in sc["armature"].as_object().unwrap() {
        scene = scene.armature(joint, a.as_f64().unwrap());
    }
    let mut values = Vec::new();
    for p in sc["payloads"].as_array().unwrap() {
        let link = p["link"].as_str().unwrap();
        let (com, i) = (vector(&p["com"]), vector(&p["inertia"]));
        let v =
            PayloadInertia::new(p["mass"].as_f64().unwrap(), [com[0], com[1], com[2]], core::array::from_fn(|k| i[k]));
        scene = if inputs { scene.payload_input(link) } else { scene.payload(link, v) };
        values.push(v);
    }
    let tip = sc["tip_wrench"]["frame"].as_str().unwrap().to_string();
    let w = vector(&sc["tip_wrench"]["wrench"]);
    (scene.tip_wrench(&tip), values, core::array::from_fn(|k| w[k]), tip)
}

/// A scene on the floating legged manipulator (armature on every joint,
/// payloads on the floating trunk and on the arm's last link, a tip wrench
/// at a foot) against Pinocchio with the same armature (`model.armature`),
/// the payloads added to its joints' inertias and the wrench as `fext`:
/// τ, M, h, g and q̈, by [`SceneRobot`] and by the scene's module (its
/// traces as emitted), the payloads constants and run-time inputs.
#[test]
fn legged_manipulator_scene_agrees_with_pinocchio() {
    let (data, model) = load("legged_manipulator");
    let mut worst = 0.0f64;
    for inputs in [false, true] {
        let (scene, values, wrench, tip) = data_scene(&data, inputs);
        let applied = scene.apply(&model).unwrap();
        assert!(applied.warnings.is_empty(), "{:?}", applied.warnings);
        assert_eq!(applied.model.nv(), model.nv());
        let options = CodegenOptions::default().functions(Function::DEFAULT);
        let module = generate_scene(&applied, &options).unwrap();
        let mut robot = SceneRobot::new(applied);
        let given: &[PayloadInertia] = if inputs { &values } else { &[] };
        let si = SceneInputs { tip_wrench: Some(Vector6::from(wrench)), payloads: given, ..Default::default() };
        let no_tip = SceneInputs { payloads: given, ..Default::default() };
        let payload_args: Vec<(String, Vec<f64>)> = data["scene"]["payloads"]
            .as_array()
            .unwrap()
            .iter()
            .zip(&values)
            .map(|(p, v)| {
                let mut x = vec![v.mass];
                x.extend(v.com);
                x.extend(v.inertia);
                (payload_argument(p["link"].as_str().unwrap()), x)
            })
            .collect();
        for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
            let want = &s["scene"];
            let dv = |v: &Value| DVector::from_vec(vector(v));
            let (q, qd, qdd, tau) = (dv(&s["q"]), dv(&s["qd"]), dv(&s["qdd"]), dv(&s["tau"]));
            let mut ok = |what: &str, got: &[f64], want: &[f64]| {
                let e = rel_err(got, want, 1.0);
                assert!(e < 1e-12, "inputs {inputs}, state {k}: {what} ({tip}) differs from Pinocchio by {e:e}");
                worst = worst.max(e);
            };
            ok("tau", robot.inverse_dynamics_with(&q, &qd, &qdd, &si).unwrap().as_slice(), &vector(&want["tau_id"]));
            ok("M", robot.mass_matrix_with(&q, &no_tip).unwrap().as_slice(), &flat(&want["M"]));
            ok("h", robot.bias_forces_with(&q, &qd, &no_tip).unwrap().as_slice(), &vector(&want["h"]));
            ok("g", robot.gravity_torques_with(&q, &no_tip).unwrap().as_slice(), &vector(&want["g"]));
            ok("qdd", robot.forward_dynamics_with(&q, &qd, &tau, &si).unwrap().as_slice(), &vector(&want["qdd_fd"]));
            let mut vectors: Vec<(&str, Vec<f64>)> = ["q", "qd", "qdd", "tau"].map(|n| (n, vector(&s[n]))).to_vec();
            vectors.push(("f_tip", wrench.to_vec()));
            for f in module.functions.iter() {
                let mut args: Vec<(&str, &[f64])> = f
                    .inputs
                    .iter()
                    .filter_map(|(n, _)| vectors.iter().find(|(v, _)| v == n).map(|(v, x)| (*v, x.as_slice())))
                    .collect();
                args.extend(payload_args.iter().map(|(n, x)| (n.as_str(), x.as_slice())));
                let key = match f.function {
                    Function::InverseDynamics => "tau_id",
                    Function::MassMatrix => "M",
                    Function::BiasForces => "h",
                    Function::GravityTorques => "g",
                    _ => "qdd_fd",
                };
                let want = if key == "M" { flat(&want[key]) } else { vector(&want[key]) };
                ok(&format!("{} (generated)", f.label()), &f.traced.eval(&args).unwrap(), &want);
            }
        }
    }
    println!("legged manipulator scene: worst relative error {worst:.1e}");
}
