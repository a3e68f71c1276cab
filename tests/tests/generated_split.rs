//! Functions emitted as private parts (`CodegenOptions::split_lets`),
//! compiled: the same numbers, bit for bit, as the functions emitted whole
//! (a 4-joint skewed chain cut into parts of at most 100 `let`s, and the
//! UR5 scene with every run-time input cut into parts of at most 60), and a
//! 12-joint chain with the default split against the generic solver. The
//! modules are written by `build_split.rs`; this debug build compiling the
//! 12-joint module is itself the check that no part is too long for rustc
//! with debug information.

use approx::abs_diff_eq;
use dynagen::codegen::DEFAULT_SPLIT_LETS;
use dynagen::scene::{Scene, SceneInputs, SceneRobot};
use dynagen_tests::{bundled_model, scale, Rng};
use nalgebra::DVector;

#[path = "../../dynagen/tests/support/skewed_chain.rs"]
mod skewed_chain;

#[allow(dead_code)]
mod whole {
    include!(concat!(env!("OUT_DIR"), "/chain4_whole.rs"));
}
#[allow(dead_code)]
mod split {
    include!(concat!(env!("OUT_DIR"), "/chain4_split.rs"));
}
#[allow(dead_code)]
mod chain12 {
    include!(concat!(env!("OUT_DIR"), "/chain12.rs"));
}
#[allow(dead_code)]
mod ur5_inputs {
    include!(concat!(env!("OUT_DIR"), "/ur5_inputs.rs"));
}
#[allow(dead_code)]
mod ur5_inputs_split {
    include!(concat!(env!("OUT_DIR"), "/ur5_inputs_split.rs"));
}

const CHAIN4_SPLIT: &str = include_str!(concat!(env!("OUT_DIR"), "/chain4_split.rs"));
const CHAIN4_WHOLE: &str = include_str!(concat!(env!("OUT_DIR"), "/chain4_whole.rs"));
const CHAIN12: &str = include_str!(concat!(env!("OUT_DIR"), "/chain12.rs"));
const UR5_INPUTS_SPLIT: &str = include_str!(concat!(env!("OUT_DIR"), "/ur5_inputs_split.rs"));

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

/// The number of `let`s of each function of `source` (name, count), and
/// the names of the parts.
fn lets_per_function(source: &str) -> Vec<(String, usize)> {
    let mut out: Vec<(String, usize)> = Vec::new();
    for line in source.lines() {
        let name = line.strip_prefix("pub fn ").or_else(|| line.strip_prefix("fn "));
        if let Some(name) = name {
            out.push((name.split('(').next().unwrap_or_default().to_string(), 0));
        } else if line.starts_with("    let ") {
            if let Some(last) = out.last_mut() {
                last.1 += 1;
            }
        }
    }
    out
}

#[test]
fn the_split_modules_are_cut_into_parts_within_the_budget() {
    for (source, max, parts) in [(CHAIN4_SPLIT, 100, 20), (CHAIN12, DEFAULT_SPLIT_LETS, 2), (UR5_INPUTS_SPLIT, 60, 20)]
    {
        let lets = lets_per_function(source);
        let n_parts = lets.iter().filter(|(name, _)| name.contains("_part")).count();
        assert!(n_parts >= parts, "{n_parts} parts, expected at least {parts}");
        for (name, count) in &lets {
            assert!(*count <= max, "{name}: {count} lets, more than {max}");
        }
    }
    assert!(!CHAIN4_WHOLE.contains("_part"));
    // The header names the split functions, and only when one was split.
    assert!(CHAIN12.contains("// Long bodies (over 2500 lets) cut into private parts"));
    assert!(CHAIN12.contains("forward_dynamics_sc ("));
    assert!(!CHAIN4_WHOLE.contains("// Long bodies"));
    // The 12-joint chain's longest body is past the ~2,900 lets at which
    // rustc overflows its stack in debug builds.
    let traced = dynagen::codegen::generate(&skewed_chain::skewed_chain(12), &Default::default()).unwrap();
    let longest = traced.functions.iter().map(|f| f.sin_cos_inputs.function.nodes().len()).max().unwrap();
    assert!(longest > 4000, "the 12-joint chain's longest body has {longest} nodes");
    // Bodies this long have their parts inlined (whole in optimised builds;
    // this debug build compiling them is the check that inlined parts do not
    // overflow rustc's stack either), and no AVX2 + FMA copy of a part.
    for source in [CHAIN4_SPLIT, CHAIN12] {
        assert!(source.contains("#[inline(always)]\n#[allow(clippy::too_many_arguments)]\n#[allow(dead_code)]\nfn forward_dynamics_sc_part1("));
        assert!(
            !source.contains("#[inline(never)]\n#[allow(clippy::too_many_arguments)]")
                && !source.contains("_part1_avx2_fma(")
        );
    }
}

#[test]
fn split_and_whole_give_the_same_bits() {
    let mut rng = Rng::new(31);
    for _ in 0..200 {
        let mut arr = |a: f64| -> [f64; 4] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd, tau) = (arr(3.0), arr(4.0), arr(5.0), arr(20.0));
        assert_eq!(bits(&split::inverse_dynamics(&q, &qd, &qdd)), bits(&whole::inverse_dynamics(&q, &qd, &qdd)), "τ");
        assert_eq!(bits(split::mass_matrix(&q).as_flattened()), bits(whole::mass_matrix(&q).as_flattened()), "M");
        assert_eq!(bits(&split::bias_forces(&q, &qd)), bits(&whole::bias_forces(&q, &qd)), "h");
        assert_eq!(bits(&split::gravity_torques(&q)), bits(&whole::gravity_torques(&q)), "g");
        assert_eq!(bits(&split::forward_dynamics(&q, &qd, &tau)), bits(&whole::forward_dynamics(&q, &qd, &tau)), "FD");
    }
}

#[test]
fn a_split_scene_gives_the_same_bits_as_the_whole_one() {
    use ur5_inputs as w;
    use ur5_inputs_split as s;
    let mut rng = Rng::new(32);
    for _ in 0..100 {
        let mut arr = |a: f64| -> [f64; 5] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd, tau) = (arr(3.0), arr(2.0), arr(5.0), arr(30.0));
        let gravity = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), -9.81];
        let f_tip: [f64; 6] = core::array::from_fn(|_| rng.range(-5.0, 5.0));
        let payload: [f64; 10] = core::array::from_fn(|i| if i == 0 { 1.5 } else { rng.range(-0.01, 0.01) });
        assert_eq!(
            bits(&s::inverse_dynamics(&q, &qd, &qdd, &gravity, &f_tip, &payload)),
            bits(&w::inverse_dynamics(&q, &qd, &qdd, &gravity, &f_tip, &payload))
        );
        assert_eq!(
            bits(s::mass_matrix(&q, &payload).as_flattened()),
            bits(w::mass_matrix(&q, &payload).as_flattened())
        );
        assert_eq!(bits(&s::coriolis(&q, &qd, &payload)), bits(&w::coriolis(&q, &qd, &payload)));
        assert_eq!(
            bits(&s::forward_dynamics(&q, &qd, &tau, &gravity, &f_tip, &payload)),
            bits(&w::forward_dynamics(&q, &qd, &tau, &gravity, &f_tip, &payload))
        );
    }
    // The split scene is the whole one's scene (a sanity check that both
    // are the UR5 with the inputs, against the generic solver once).
    let ur5 = bundled_model("ur5");
    let scene = Scene::new()
        .gravity(dynagen::scene::Gravity::Input)
        .tip_wrench("ee_link")
        .payload_input("ee_link")
        .lock("wrist_3_joint", 0.2)
        .armature("elbow_joint", 0.2)
        .coulomb("shoulder_lift_joint", 2.0);
    let robot = SceneRobot::new(scene.apply(&ur5).unwrap());
    let q = [0.3, -0.7, 1.1, 0.2, -0.4];
    let p = dynagen::scene::PayloadInertia::new(1.5, [0.0, 0.0, 0.06], [2e-3, 2e-3, 1e-3, 0.0, 0.0, 0.0]);
    let payload = [1.5, 0.0, 0.0, 0.06, 2e-3, 2e-3, 1e-3, 0.0, 0.0, 0.0];
    let inputs = SceneInputs { gravity: None, tip_wrench: None, payloads: std::slice::from_ref(&p) };
    let mut robot = robot;
    let want = robot.mass_matrix_with(&DVector::from_column_slice(&q), &inputs).unwrap();
    let got = s::mass_matrix(&q, &payload);
    let want: Vec<f64> = (0..5).flat_map(|i| (0..5).map(move |j| (i, j))).map(|(i, j)| want[(i, j)]).collect();
    assert!(abs_diff_eq!(got.as_flattened(), &want[..], epsilon = 1e-12 * scale(&want, 1.0)), "{got:?} vs {want:?}");
}

#[test]
fn split_twelve_joint_chain_matches_the_generic_solver() {
    let mut robot = dynagen::Robot::new(skewed_chain::skewed_chain(12));
    let mut rng = Rng::new(33);
    let v = |a: &[f64; 12]| DVector::from_column_slice(a);
    for _ in 0..50 {
        let mut arr = |a: f64| -> [f64; 12] { core::array::from_fn(|_| rng.range(-a, a)) };
        let (q, qd, qdd, tau) = (arr(3.0), arr(4.0), arr(5.0), arr(20.0));
        let m = robot.mass_matrix(&v(&q)).unwrap();
        let m: Vec<f64> = (0..12).flat_map(|i| (0..12).map(move |j| (i, j))).map(|(i, j)| m[(i, j)]).collect();
        let checks = [
            (
                "τ",
                chain12::inverse_dynamics(&q, &qd, &qdd).to_vec(),
                robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap().as_slice().to_vec(),
            ),
            ("M", chain12::mass_matrix(&q).as_flattened().to_vec(), m),
            (
                "h",
                chain12::bias_forces(&q, &qd).to_vec(),
                robot.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
            ),
            ("g", chain12::gravity_torques(&q).to_vec(), robot.gravity_torques(&v(&q)).unwrap().as_slice().to_vec()),
            (
                "FD",
                chain12::forward_dynamics(&q, &qd, &tau).to_vec(),
                robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap().as_slice().to_vec(),
            ),
        ];
        for (what, got, want) in checks {
            let epsilon = 1e-12 * scale(&want, 1.0);
            assert!(abs_diff_eq!(&got[..], &want[..], epsilon = epsilon), "{what}: {got:?} vs {want:?}");
        }
    }
}
