//! The floating base against Pinocchio with a `JointModelFreeFlyer` root,
//! on a 12-joint quadruped (Unitree A1 parameters), the 7-joint
//! torso_two_arms, a random 20-joint tree (prismatic and fixed joints,
//! non-aligned axes, rotated origins) and the 32-joint humanoid32 (TALOS
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
use dynagen::codegen::{generate, CodegenOptions};
use dynagen::spatial::Vec3;
use dynagen::{Model, Robot};
use nalgebra::{DMatrix, DVector};
use serde_json::Value;
use std::path::Path;
use support::rel_err;

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn flat(v: &Value) -> Vec<f64> {
    v.as_array().expect("rows").iter().flat_map(vector).collect()
}

/// The data file of `name` and its model with a floating root.
fn load(name: &str) -> (Value, Model) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(format!("tests/data/pinocchio_floating_{name}.json"))).unwrap(),
    )
    .unwrap();
    let model =
        Model::from_urdf_file(dir.join("..").join(data["robot"].as_str().unwrap())).unwrap().with_floating_base();
    (data, model)
}

/// Pinocchio's values; the largest relative error seen, per quantity.
fn check(name: &str) -> Vec<(&'static str, f64)> {
    let (data, model) = load(name);
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
