//! The generated derivatives, compiled: the modules `build.rs` writes with
//! `functions = [inverse_dynamics_derivatives, forward_dynamics_derivatives,
//! mass_matrix_inverse]` (UR5, Panda, the two-armed torso, the KUKA iiwa 14,
//! the quadruped12 with its trunk fixed, an f32 UR5 and Panda, the
//! `ur5_controller` scene) against the generic derivatives (`Robot`,
//! `SceneRobot`, themselves checked against double-double finite
//! differences in `dynagen/tests/derivatives.rs`): ≤ 1e-12 of each matrix's
//! norm in f64, ≤ 1e-4 in f32.

use dynagen::scene::{SceneFile, SceneInputs, SceneRobot};
use dynagen_tests::{bundled_model, bundled_robot, bundled_scene, norm_rel_err, normalize_quaternion, Rng};
use nalgebra::{DMatrix, DVector, Vector6};

macro_rules! module {
    ($name:ident) => {
        #[allow(dead_code)]
        mod $name {
            include!(concat!(env!("OUT_DIR"), "/", stringify!($name), ".rs"));
        }
    };
}
module!(ur5_derivatives);
module!(panda_derivatives);
module!(torso_two_arms_derivatives);
module!(iiwa14_derivatives);
module!(quadruped12_derivatives);
module!(ur5_derivatives_f32);
module!(panda_derivatives_f32);
module!(quadruped12_floating_derivatives);
module!(ur5_controller_derivatives);

/// Row-major entries.
fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// What a derivatives module returns, in the order [`compare`] takes it.
const MATRICES: [&str; 6] =
    ["dtau/dq", "dtau/dqd", "dqdd/dq", "dqdd/dqd", "Minv (forward_dynamics_derivatives)", "mass_matrix_inverse"];

/// A module's six matrices (row-major: ∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q, ∂q̈/∂q̇, M⁻¹
/// of forward_dynamics_derivatives, mass_matrix_inverse) against the
/// generic ones (∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q, ∂q̈/∂q̇, M⁻¹): each within `tol` of
/// the matrix's norm; returns the largest error.
fn compare(tag: &str, got: [Vec<f64>; 6], [wa, wb, wc, wd, we]: [&DMatrix<f64>; 5], tol: f64) -> f64 {
    let mut worst = 0.0_f64;
    for ((what, got), want) in MATRICES.iter().zip(got).zip([wa, wb, wc, wd, we, we]) {
        let err = norm_rel_err(&got, &rows(want), 1e-300);
        assert!(err <= tol, "{tag} {what}: {err:e}");
        worst = worst.max(err);
    }
    worst
}

/// Checks a derivatives module against `Robot` on `cases` random states.
macro_rules! check {
    ($m:ident, $robot:expr, $cases:expr) => {{
        const N: usize = $m::DOF;
        let mut robot = bundled_robot($robot);
        assert_eq!($m::JOINT_NAMES.to_vec(), robot.joint_names());
        let mut rng = Rng::new(0xde71);
        let mut worst = 0.0_f64;
        for _ in 0..$cases {
            let mut arr = |a: f64| -> [f64; N] { core::array::from_fn(|_| rng.range(-a, a)) };
            let (q, qd, x) = (arr(3.0), arr(2.0), arr(10.0));
            let v = |a: &[f64; N]| DVector::from_column_slice(a);
            let (a, b) = $m::inverse_dynamics_derivatives(&q, &qd, &x);
            let (wa, wb) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
            let (c, d, e) = $m::forward_dynamics_derivatives(&q, &qd, &x);
            let (wc, wd, we) = robot.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
            let minv = $m::mass_matrix_inverse(&q);
            let got = [a.concat(), b.concat(), c.concat(), d.concat(), e.concat(), minv.concat()];
            let tag = format!("{} at q = {q:?}:", stringify!($m));
            worst = worst.max(compare(&tag, got, [&wa, &wb, &wc, &wd, &we], 1e-12));
        }
        println!("{}: worst relative error {worst:.1e}", stringify!($m));
    }};
}

/// The torso's ∂τ, a whole body of more than `EARLY_STORES_MIN_LETS`
/// statements, stores its matrices' entries where they are computed
/// (`statements::store_early`); the comparisons below check its values.
#[test]
fn the_torsos_derivatives_store_their_entries_early() {
    let torso = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/torso_two_arms_derivatives.rs")).unwrap();
    assert!(torso.contains("let mut out = ([[0.0; DOF]; DOF], [[0.0; DOF]; DOF]);"));
}

/// The five fixed-base modules (states: 200 on the arms of 6 and 9 joints,
/// 100 on the others).
#[test]
fn fixed_base_derivatives_match_the_generic_ones() {
    check!(ur5_derivatives, "ur5", 200);
    check!(panda_derivatives, "panda", 200);
    check!(torso_two_arms_derivatives, "torso_two_arms", 100);
    check!(iiwa14_derivatives, "iiwa14", 100);
    check!(quadruped12_derivatives, "quadruped12", 100);
}

/// The floating quadruped's derivatives (NQ-long q, NV × NV matrices in the
/// tangent of the base's body twist) against the generic ones.
#[test]
fn floating_quadruped12_derivatives_match_the_generic_ones() {
    use quadruped12_floating_derivatives as m;
    let mut robot = dynagen::Robot::new(bundled_model("quadruped12").with_floating_base());
    assert_eq!(m::JOINT_NAMES.to_vec(), robot.joint_names());
    let mut rng = Rng::new(0xf10a7);
    let mut worst = 0.0_f64;
    for _ in 0..50 {
        let mut q: [f64; m::NQ] = core::array::from_fn(|_| rng.range(-2.0, 2.0));
        normalize_quaternion(&mut q);
        let mut arr = |a: f64| -> [f64; m::NV] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (qd, x) = (arr(2.0), arr(10.0));
        let v = |a: &[f64]| DVector::from_column_slice(a);
        let (a, b) = m::inverse_dynamics_derivatives(&q, &qd, &x);
        let (wa, wb) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
        let (c, d, e) = m::forward_dynamics_derivatives(&q, &qd, &x);
        let (wc, wd, we) = robot.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
        let minv = m::mass_matrix_inverse(&q);
        let got = [a.concat(), b.concat(), c.concat(), d.concat(), e.concat(), minv.concat()];
        worst = worst.max(compare("floating quadruped12", got, [&wa, &wb, &wc, &wd, &we], 1e-12));
    }
    println!("floating quadruped12: worst relative error {worst:.1e}");
}

/// An f32 module against the generic f64 derivatives, ≤ 1e-4 of each
/// matrix's norm.
macro_rules! check_f32 {
    ($m:ident, $robot:expr) => {{
        const N: usize = $m::DOF;
        let mut robot = bundled_robot($robot);
        let mut rng = Rng::new(0xf32);
        for _ in 0..100 {
            let mut arr = |a: f64| -> [f64; N] { core::array::from_fn(|_| rng.range(-a, a)) };
            let (q, qd, x) = (arr(3.0), arr(2.0), arr(10.0));
            let f = |a: &[f64; N]| a.map(|x| x as f32);
            let v = |a: &[f64; N]| DVector::from_column_slice(a);
            let wide = |m: [[f32; N]; N]| m.concat().into_iter().map(f64::from).collect::<Vec<_>>();
            let (a, b) = $m::inverse_dynamics_derivatives(&f(&q), &f(&qd), &f(&x));
            let (wa, wb) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
            let (c, d, e) = $m::forward_dynamics_derivatives(&f(&q), &f(&qd), &f(&x));
            let (wc, wd, we) = robot.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
            let minv = $m::mass_matrix_inverse(&f(&q));
            let got = [wide(a), wide(b), wide(c), wide(d), wide(e), wide(minv)];
            compare(&format!("{} f32", stringify!($m)), got, [&wa, &wb, &wc, &wd, &we], 1e-4);
        }
    }};
}

#[test]
fn f32_derivatives_are_close() {
    check_f32!(ur5_derivatives_f32, "ur5");
    check_f32!(panda_derivatives_f32, "panda");
}

/// The scene's armature, friction and constant payload enter; its tip
/// wrench input is held constant.
#[test]
fn ur5_controller_scene_derivatives_match_the_generic_ones() {
    use ur5_controller_derivatives as m;
    let file = SceneFile::from_toml_file(bundled_scene("ur5_controller")).unwrap();
    let mut robot = SceneRobot::new(file.scene.apply(&bundled_model("ur5")).unwrap());
    let mut rng = Rng::new(0x5ce);
    for _ in 0..100 {
        let mut arr = |a: f64| -> [f64; 6] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, x, f_tip) = (arr(3.0), arr(2.0), arr(10.0), arr(20.0));
        let v = |a: &[f64; 6]| DVector::from_column_slice(a);
        let inputs = SceneInputs { tip_wrench: Some(Vector6::from_column_slice(&f_tip)), ..Default::default() };
        let (a, b) = m::inverse_dynamics_derivatives(&q, &qd, &x, &f_tip);
        let (wa, wb) = robot.inverse_dynamics_derivatives_with(&v(&q), &v(&qd), &v(&x), &inputs).unwrap();
        let (c, d, e) = m::forward_dynamics_derivatives(&q, &qd, &x, &f_tip);
        let (wc, wd, we) = robot.forward_dynamics_derivatives_with(&v(&q), &v(&qd), &v(&x), &inputs).unwrap();
        let minv = m::mass_matrix_inverse(&q);
        let got = [a.concat(), b.concat(), c.concat(), d.concat(), e.concat(), minv.concat()];
        compare("ur5_controller", got, [&wa, &wb, &wc, &wd, &we], 1e-12);
    }
}
