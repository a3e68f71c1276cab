//! Cross-check against Pinocchio on the bundled robots.
//!
//! The reference values in `tests/data/pinocchio_<robot>.json` were computed
//! by Pinocchio (pip package `pin`; version, seed and states recorded in each
//! file's "source" field) with `scripts/reference/make_pinocchio_data.py` on
//! the same URDF files. CI has no Python: the values are stored data.

mod support;

use approx::abs_diff_eq;
use dynagen::Robot;
use nalgebra::DVector;
use serde_json::Value;
use std::path::Path;
use support::scale;

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().expect("rows").iter().map(vector).collect()
}

fn check_robot(name: &str) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(format!("tests/data/pinocchio_{name}.json"))).unwrap())
            .unwrap();
    let mut robot = support::robot(name);
    let names: Vec<String> =
        data["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap().to_string()).collect();
    assert_eq!(robot.joint_names(), names, "{name}: joint order differs from Pinocchio's");
    let frame = data["frame"].as_str().unwrap();
    let n = robot.dof();
    // Observed: at most ~4e-16 (a few ulps) on every quantity; the bound leaves room
    // for a different but equally valid order of floating-point operations.
    let tol = 1e-13;
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let q = DVector::from_vec(vector(&s["q"]));
        let qd = DVector::from_vec(vector(&s["qd"]));
        let qdd = DVector::from_vec(vector(&s["qdd"]));
        let tau_in = DVector::from_vec(vector(&s["tau_in"]));
        let ctx = format!("{name}, state {k}");
        // Every entry within tol of the reference's largest (at least 1).
        let close = |what: &str, got: &[f64], want: &[f64]| {
            let epsilon = tol * scale(want, 1.0);
            assert!(abs_diff_eq!(got, want, epsilon = epsilon), "{ctx}: {what}: {got:?} against {want:?}");
        };
        close("tau", robot.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), &vector(&s["tau"]));
        let m = robot.mass_matrix(&q).unwrap();
        let mref: Vec<f64> = matrix(&s["M"]).into_iter().flatten().collect();
        let mours: Vec<f64> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).map(|(i, j)| m[(i, j)]).collect();
        close("M", &mours, &mref);
        close("h", robot.bias_forces(&q, &qd).unwrap().as_slice(), &vector(&s["h"]));
        close("g", robot.gravity_torques(&q).unwrap().as_slice(), &vector(&s["g"]));
        let want_qdd = vector(&s["qdd_fd"]);
        close("forward dynamics (ABA)", robot.forward_dynamics(&q, &qd, &tau_in).unwrap().as_slice(), &want_qdd);
        let ldlt = robot.forward_dynamics_ldlt(&q, &qd, &tau_in).unwrap();
        close("forward dynamics (LTDL)", ldlt.as_slice(), &want_qdd);
        let pose = robot.frame_pose(frame, &q).unwrap();
        let pref: Vec<f64> = matrix(&s["frame_pose"]).into_iter().flatten().collect();
        let pours: Vec<f64> = (0..4).flat_map(|i| (0..4).map(move |j| (i, j))).map(|(i, j)| pose[(i, j)]).collect();
        close(&format!("pose of {frame}"), &pours, &pref);
        for (key, jac) in [
            ("jacobian_world", robot.space_jacobian(frame, &q).unwrap()),
            ("jacobian_local", robot.body_jacobian(frame, &q).unwrap()),
        ] {
            let jref: Vec<f64> = matrix(&s[key]).into_iter().flatten().collect();
            let jours: Vec<f64> = (0..6).flat_map(|i| (0..n).map(move |j| (i, j))).map(|(i, j)| jac[(i, j)]).collect();
            close(&format!("{key} of {frame}"), &jours, &jref);
        }
    }
}

#[test]
fn ur5_agrees_with_pinocchio() {
    check_robot("ur5");
}

#[test]
fn panda_agrees_with_pinocchio() {
    check_robot("panda");
}

#[test]
fn torso_two_arms_agrees_with_pinocchio() {
    check_robot("torso_two_arms");
}

#[test]
fn planar_2link_agrees_with_pinocchio() {
    check_robot("planar_2link");
}

/// The UR5 built from the Modern Robotics book's lists (stored beside the
/// Pinocchio data, `mr_lists`) against Pinocchio on the URDF: the two
/// descriptions are the same robot (the reference script measured 5.7e-14
/// between the MR library and Pinocchio), so both importers must agree.
#[test]
fn ur5_from_modern_robotics_lists_agrees_with_pinocchio_on_the_urdf() {
    use nalgebra::{DMatrix, Matrix4, Matrix6};
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("tests/data/pinocchio_ur5.json")).unwrap()).unwrap();
    let lists = &data["mr_lists"];
    let mlist: Vec<Matrix4<f64>> = lists["Mlist"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| {
            let rows = matrix(m);
            Matrix4::from_fn(|r, c| rows[r][c])
        })
        .collect();
    let glist: Vec<Matrix6<f64>> = lists["Glist"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| {
            let rows = matrix(m);
            Matrix6::from_fn(|r, c| rows[r][c])
        })
        .collect();
    let srows = matrix(&lists["Slist"]);
    let slist = DMatrix::from_fn(6, 6, |r, c| srows[r][c]);
    let mut robot = Robot::new(dynagen::Model::from_modern_robotics(&mlist, &glist, &slist).unwrap());
    // The URDF's gravity is the default (0, 0, −9.81), as Pinocchio's.
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let q = DVector::from_vec(vector(&s["q"]));
        let qd = DVector::from_vec(vector(&s["qd"]));
        let qdd = DVector::from_vec(vector(&s["qdd"]));
        let tau_in = DVector::from_vec(vector(&s["tau_in"]));
        // Every entry within 1e-12 of the reference's largest (at least 1).
        let close = |what: &str, got: &[f64], want: &[f64]| {
            let epsilon = 1e-12 * scale(want, 1.0);
            assert!(abs_diff_eq!(got, want, epsilon = epsilon), "state {k}: {what}: {got:?} against {want:?}");
        };
        close("tau", robot.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice(), &vector(&s["tau"]));
        close("forward dynamics", robot.forward_dynamics(&q, &qd, &tau_in).unwrap().as_slice(), &vector(&s["qdd_fd"]));
        let m = robot.mass_matrix(&q).unwrap();
        let mref: Vec<f64> = matrix(&s["M"]).into_iter().flatten().collect();
        close("M", m.transpose().as_slice(), &mref);
        // The MR end-effector frame is the URDF's ee_link.
        let pose = robot.frame_pose("ee", &q).unwrap();
        let pref: Vec<f64> = matrix(&s["frame_pose"]).into_iter().flatten().collect();
        close("end-effector pose", pose.transpose().as_slice(), &pref);
    }
}

/// One robot's derivatives against Pinocchio's recorded ones (`doc`): every
/// matrix the record has, ≤ 1e-10 of its norm; returns the worst error.
fn check_derivatives(name: &str, robot: &mut Robot, doc: &Value) -> f64 {
    let names: Vec<String> =
        doc["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap().to_string()).collect();
    assert_eq!(robot.joint_names(), names, "{name}: joint order differs from Pinocchio's");
    let rows = |m: &nalgebra::DMatrix<f64>| m.transpose().as_slice().to_vec();
    let mut worst = 0.0_f64;
    for (k, s) in doc["states"].as_array().unwrap().iter().enumerate() {
        let v = |key: &str| DVector::from_vec(vector(&s[key]));
        let (q, qd, qdd, tau) = (v("q"), v("qd"), v("qdd"), v("tau_in"));
        let (a, b) = robot.inverse_dynamics_derivatives(&q, &qd, &qdd).unwrap();
        let (c, d, e) = robot.forward_dynamics_derivatives(&q, &qd, &tau).unwrap();
        let m = robot.mass_matrix(&q).unwrap();
        let alone = robot.mass_matrix_inverse(&q).unwrap();
        for (what, got, key) in [
            ("dtau_dq", rows(&a), "dtau_dq"),
            ("dtau_dqd", rows(&b), "dtau_dqd"),
            ("dtau_dqdd = M", rows(&m), "dtau_dqdd"),
            ("dqdd_dq", rows(&c), "dqdd_dq"),
            ("dqdd_dqd", rows(&d), "dqdd_dqd"),
            ("minv", rows(&e), "minv"),
            ("mass_matrix_inverse", rows(&alone), "minv_alone"),
            ("mass_matrix_inverse (= minv)", rows(&alone), "minv"),
        ] {
            if s[key].is_null() {
                continue;
            }
            let want = matrix(&s[key]).concat();
            let err = support::norm_rel_err(&got, &want, 1e-300);
            assert!(err <= 1e-10, "{name} state {k} {what}: {err:e}\n got {got:?}\nwant {want:?}");
            worst = worst.max(err);
        }
    }
    worst
}

/// The derivatives against Pinocchio's analytical ones (`computeRNEADerivatives`,
/// `computeABADerivatives`, `computeMinverse`; `tests/data/pinocchio_derivatives.json`,
/// made by `scripts/reference/make_pinocchio_derivatives.py`, origin in its
/// "source" field), on every bundled robot: ≤ 1e-10 of each matrix's norm.
#[test]
fn derivatives_match_pinocchio() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("tests/data/pinocchio_derivatives.json")).unwrap())
            .unwrap();
    assert_eq!(data["source"]["generator"], "pinocchio");
    let robots = data["robots"].as_object().unwrap();
    assert_eq!(robots.len(), 6);
    for (name, doc) in robots {
        let worst = check_derivatives(name, &mut support::robot(name), doc);
        println!("{name}: worst relative error against Pinocchio's derivatives {worst:.1e}");
    }
}

/// A floating base's derivatives against Pinocchio's with a
/// `JointModelFreeFlyer` root (`tests/data/pinocchio_floating_derivatives.json`,
/// made by `scripts/reference/make_pinocchio_floating_derivatives.py`, which
/// converts Pinocchio's (linear; angular) base coordinates to dynagen's):
/// the quadruped12, the two-armed torso and a random 20-joint tree, the
/// configuration's tangent the base's body twist in both; ≤ 1e-10.
#[test]
fn floating_base_derivatives_match_pinocchio() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = dir.join("tests/data/pinocchio_floating_derivatives.json");
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert_eq!(data["source"]["generator"], "pinocchio");
    let robots = data["robots"].as_object().unwrap();
    assert_eq!(robots.len(), 3);
    for (name, doc) in robots {
        let urdf = dir.join("..").join(doc["urdf"].as_str().unwrap());
        let model = dynagen::Model::from_urdf_file(urdf).unwrap().with_floating_base();
        let worst = check_derivatives(name, &mut Robot::new(model), doc);
        println!("{name} (floating): worst relative error against Pinocchio's derivatives {worst:.1e}");
    }
}
