//! The vendored modules of `generated/` (the bundled robots): each is what
//! the generator writes today, byte for byte, and each computes what the
//! generic solver computes, to 1e-12 of the output's norm, on 1,000 states each
//! (the zero state, ordinary ones, |q̇| ≈ 100 rad/s and |q| ≈ 1e3 rad),
//! for every function. Plus the UR5 modules that `build.rs` writes with
//! `dynagen::Builder`: with the default options (the batched trigonometry,
//! no std) and in f32.

use dynagen_generated::{panda, planar_2link, torso_two_arms, ur5};
use dynagen_tests::{
    bundled_model, bundled_module, bundled_robot, norm_rel_err, workspace_root, Rng, BUNDLED, REGENERATE_COMMAND,
};
use nalgebra::DVector;

#[allow(dead_code)]
mod ur5_f32 {
    include!(concat!(env!("OUT_DIR"), "/ur5_f32.rs"));
}

#[test]
fn committed_modules_equal_a_fresh_generation() {
    let mut stale = Vec::new();
    for name in BUNDLED {
        let path = workspace_root().join(format!("generated/src/{name}.rs"));
        let committed = std::fs::read(&path).unwrap_or_default();
        let fresh = bundled_module(name).unwrap_or_else(|e| panic!("{e}"));
        if committed != fresh.as_bytes() {
            stale.push(path.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "the vendored generated code is stale: {} differ(s) from what the generator writes now; \
         regenerate with `{REGENERATE_COMMAND}` and commit the result",
        stale.join(", ")
    );
}

/// Checks one generated module against the generic solver on `cases` random
/// states; returns the worst relative error of (τ, M, h, g, q̈).
macro_rules! check_module {
    ($m:ident, $cases:expr, $seed:expr) => {{
        const N: usize = $m::DOF;
        let mut robot = bundled_robot(stringify!($m));
        assert_eq!(N, robot.dof());
        assert_eq!($m::JOINT_NAMES.to_vec(), robot.joint_names());
        let mut rng = Rng::new($seed);
        let mut arr = |a: f64| -> [f64; N] { core::array::from_fn(|_| rng.range(-a, a)) };
        let v = |a: &[f64; N]| DVector::from_column_slice(a);
        let mut worst = [0.0f64; 5];
        for case in 0..$cases {
            // The zero state first, then ordinary states, fast ones
            // (|q̇| ≈ 100 rad/s) and wound-up ones (|q| ≈ 1e3 rad) in turn.
            let (qs, qds) = match case % 3 {
                0 => (3.0, 2.0),
                1 => (3.0, 100.0),
                _ => (1e3, 2.0),
            };
            let (mut q, qd, qdd, tau) = if case == 0 {
                ([0.0; N], [0.0; N], [0.0; N], [0.0; N])
            } else {
                (arr(qs), arr(qds), arr(5.0), arr(30.0))
            };
            // Winding up is for angles: a prismatic joint (the Panda's
            // fingers) stays within a few centimetres.
            for (i, b) in robot.model().bodies.iter().enumerate() {
                if !b.joint.is_revolute() {
                    q[i] = (q[i] / qs) * 0.04;
                }
            }
            let checks: [(&str, Vec<f64>, Vec<f64>); 5] = [
                (
                    "inverse_dynamics",
                    $m::inverse_dynamics(&q, &qd, &qdd).to_vec(),
                    robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap().as_slice().to_vec(),
                ),
                (
                    "mass_matrix",
                    $m::mass_matrix(&q).concat(),
                    // row-major, as the generated [[row]; DOF]
                    robot.mass_matrix(&v(&q)).unwrap().transpose().as_slice().to_vec(),
                ),
                (
                    "bias_forces",
                    $m::bias_forces(&q, &qd).to_vec(),
                    robot.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
                ),
                (
                    "gravity_torques",
                    $m::gravity_torques(&q).to_vec(),
                    robot.gravity_torques(&v(&q)).unwrap().as_slice().to_vec(),
                ),
                (
                    "forward_dynamics",
                    $m::forward_dynamics(&q, &qd, &tau).to_vec(),
                    robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap().as_slice().to_vec(),
                ),
            ];
            for (k, (name, got, want)) in checks.iter().enumerate() {
                let e = norm_rel_err(got, want, 1e-300);
                worst[k] = worst[k].max(e);
                assert!(
                    e < 1e-12,
                    "{}::{name} at q = {q:?}: relative error {e:e}\n got {got:?}\nwant {want:?}",
                    stringify!($m)
                );
            }
        }
        println!("{}: worst relative errors (τ, M, h, g, q̈): {worst:?}", stringify!($m));
    }};
}

#[test]
fn ur5_matches_the_generic_solver() {
    check_module!(ur5, 1000, 1);
}

#[test]
fn panda_matches_the_generic_solver() {
    check_module!(panda, 1000, 2);
}

#[test]
fn torso_two_arms_matches_the_generic_solver() {
    check_module!(torso_two_arms, 1000, 3);
}

#[test]
fn planar_2link_matches_the_generic_solver() {
    check_module!(planar_2link, 1000, 4);
}

/// The UR5 module `build.rs` writes with `Builder::new()`'s options, the
/// library's default.
mod default_options {
    #[allow(dead_code)]
    pub mod ur5 {
        include!(concat!(env!("OUT_DIR"), "/ur5_f64.rs"));
    }
}

#[test]
fn the_default_module_is_batched_without_std_and_matches_the_generic_solver() {
    use dynagen::codegen::{generate, CodegenOptions};
    let source = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/ur5_f64.rs")).unwrap();
    let model = bundled_model("ur5");
    let library = generate(&model, &CodegenOptions::default().source("../dynagen/robots/ur5.urdf")).unwrap();
    assert!(source == library.source, "the build script's module is not generate()'s with the default options");
    // The module's own batched sines and cosines: nothing from std.
    assert!(source.contains("let (s, c) = sin_cos_array(&[q[1], q[2], q[3], q[4], q[5]]);"));
    assert!(!source.contains(".sin_cos()") && !source.contains(".sqrt()") && !source.contains("libm"));
    use default_options::ur5;
    check_module!(ur5, 300, 5);
}

#[test]
fn ur5_f32_is_close() {
    let mut robot = bundled_robot("ur5");
    let mut rng = Rng::new(7);
    for _ in 0..100 {
        let mut arr = |a: f64| -> [f64; 6] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd) = (arr(3.0), arr(2.0), arr(5.0));
        let f = |a: &[f64; 6]| a.map(|x| x as f32);
        let got = ur5_f32::inverse_dynamics(&f(&q), &f(&qd), &f(&qdd)).map(f64::from);
        let v = |a: &[f64; 6]| DVector::from_column_slice(a);
        let want = robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap();
        let e = norm_rel_err(&got, want.as_slice(), 1e-300);
        assert!(e < 1e-4, "f32 inverse dynamics: relative error {e:e}");
    }
}
