//! Where the generated code takes its sines and cosines from (`Trig`): the
//! functions each kind emits, and that the `NAME_sc` body computes the same
//! numbers as the function of `q` when given the sines and cosines.

mod support;

use dynagen::codegen::{generate, CodegenOptions, Function, ScalarType, Trig};
use dynagen::model::{Inertial, JointDescription, RobotBuilder};
use dynagen::Model;

/// A chain with a non-unit revolute axis (turns by 2q) and a prismatic joint.
fn skewed() -> Model {
    RobotBuilder::new("skewed")
        .link("base", None)
        .link("a", Some(Inertial::point_mass(1.5, [0.1, 0.0, -0.4])))
        .link("b", Some(Inertial::point_mass(0.7, [0.0, 0.2, -0.3])))
        .link("c", Some(Inertial::point_mass(0.4, [0.0, 0.0, -0.2])))
        .joint(JointDescription::revolute("j0", "base", "a", [0.0, 2.0, 0.0]))
        .joint(JointDescription::prismatic("j1", "a", "b", [0.0, 0.0, 1.0]))
        .joint(JointDescription::revolute("j2", "b", "c", [1.0, 0.0, 0.0]))
        .build()
        .unwrap()
}

fn source(model: &Model, trig: Trig) -> String {
    generate(model, &CodegenOptions::default().trig(trig)).unwrap().source
}

#[test]
fn each_trig_kind_emits_its_functions() {
    let model = support::model("ur5");
    let std = source(&model, Trig::Std);
    assert!(std.contains("let (s1, c1) = q[1].sin_cos();"));
    assert!(std.contains("// Trigonometry: NAME(q, ...) computes the sines and cosines by std's sin_cos (needs std)."));
    let libm = source(&model, Trig::Libm);
    assert!(libm.contains("libm::sincos(q[1])") && !libm.contains(".sin_cos()"));
    assert!(libm.contains("needs the `libm` crate"));
    let batched = source(&model, Trig::Batched);
    assert!(!batched.contains(".sin_cos()"));
    // Only the angles each body reads: τ, M, h, FD of the UR5 not q[0] (its axis is gravity's), g only q[1..4].
    assert!(batched.contains("let (s, c) = sin_cos_array(&[q[1], q[2], q[3], q[4], q[5]]);"), "{batched}");
    assert!(batched.contains("let (s, c) = sin_cos_array(&[q[1], q[2], q[3]]);"), "{batched}");
    assert!(
        batched.contains("&[0.0, s[0], s[1], s[2], 0.0, 0.0],")
            && batched.contains("&[1.0, c[0], c[1], c[2], 1.0, 1.0],")
    );
    assert!(batched.contains("pub fn sin_cos_all(q: &[f64; DOF]) -> ([f64; DOF], [f64; DOF])"));
    let inputs = source(&model, Trig::Inputs);
    assert!(!inputs.contains("sin_cos()") && !inputs.contains("libm"));
    for name in ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"] {
        for src in [&std, &libm, &batched, &inputs] {
            assert!(src.contains(&format!("pub fn {name}_sc(")), "{name}_sc");
        }
        for src in [&std, &libm, &batched] {
            assert!(src.contains(&format!("pub fn {name}(")), "{name}");
        }
        assert!(!inputs.contains(&format!("pub fn {name}(")), "{name} in an Inputs module");
    }
    // Without prismatic joints the _sc functions do not take q.
    assert!(inputs.contains("pub fn mass_matrix_sc(s: &[f64; DOF], c: &[f64; DOF]) -> [[f64; DOF]; DOF]"));
    // f32 with libm calls sincosf.
    let f32_libm = generate(&model, &CodegenOptions::default().trig(Trig::Libm).scalar(ScalarType::F32)).unwrap();
    assert!(f32_libm.source.contains("libm::sincosf(q[1])"));
    assert!(Trig::Std.needs_std() && !Trig::Libm.needs_std() && !Trig::Inputs.needs_std());
}

/// The default is the batched trigonometry: the module's own
/// `sin_cos_array`, no `.sin_cos()` (nothing from std), the same module as
/// asked for by name. (Compiled and checked against the generic solver in
/// `tests/tests/generated_bundled.rs`, and inside a `#![no_std]` crate in
/// `tests/no-std-check`.)
#[test]
fn the_default_is_the_batched_trigonometry() {
    assert_eq!(Trig::default(), Trig::Batched);
    assert_eq!(CodegenOptions::default().trig, Trig::Batched);
    for model in [support::model("ur5"), skewed()] {
        let default = generate(&model, &CodegenOptions::default()).unwrap().source;
        assert_eq!(default, source(&model, Trig::Batched), "{}", model.name);
        assert!(default.contains("= sin_cos_array(&["), "{default}");
        assert!(!default.contains(".sin_cos()") && !default.contains("libm"), "{default}");
        assert!(
            default.contains("// Trigonometry: NAME(q, ...) computes the sines and cosines it reads by sin_cos_array")
        );
        // std's is one option away.
        assert!(source(&model, Trig::Std).contains(".sin_cos();"));
    }
}

/// A scene file's target: `std` takes the options' trigonometry, the no_std
/// targets their own whatever the options say.
#[test]
fn a_scene_target_picks_the_trigonometry() {
    use dynagen::scene::SceneFile;
    let keys = |target: &str| SceneFile::from_toml_str(&format!("target = \"{target}\"\n")).unwrap().code;
    assert_eq!(keys("std").trig, None);
    assert_eq!(keys("no_std_libm").trig, Some(Trig::Libm));
    assert_eq!(keys("no_std_sincos").trig, Some(Trig::Inputs));
    for trig in [Trig::Std, Trig::Batched, Trig::Libm, Trig::Inputs] {
        let options = CodegenOptions::default().trig(trig);
        assert_eq!(keys("std").apply(options.clone()).trig, trig);
        assert_eq!(keys("no_std_libm").apply(options.clone()).trig, Trig::Libm);
        assert_eq!(keys("no_std_sincos").apply(options).trig, Trig::Inputs);
    }
}

#[test]
fn non_unit_axes_and_prismatic_joints() {
    let model = skewed();
    let std = source(&model, Trig::Std);
    // j0 turns by 2·q[0]: the caller of the body scales the angle.
    assert!(std.contains("let (s0, c0) = (q[0] * 2.0).sin_cos();"), "{std}");
    assert!(std.contains("let (s2, c2) = q[2].sin_cos();"));
    let batched = source(&model, Trig::Batched);
    assert!(batched.contains("sin_cos_array(&[q[0] * 2.0, q[2]])"), "{batched}");
    assert!(batched.contains("&[s[0], 0.0, s[1]]") && batched.contains("&[c[0], 1.0, c[1]]"), "{batched}");
    // A prismatic joint: the bodies take q.
    assert!(std.contains("pub fn gravity_torques_sc(s: &[f64; DOF], c: &[f64; DOF], q: &[f64; DOF]) -> [f64; DOF]"));
}

#[test]
fn the_body_with_sines_and_cosines_given_computes_the_function_of_q() {
    for model in [support::model("ur5"), skewed()] {
        let module = generate(&model, &CodegenOptions::default()).unwrap();
        let n = model.dof();
        for f in &module.functions {
            let sc = &f.sin_cos_inputs;
            for trial in 0..5 {
                let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.7 * i as f64 - 1.1 * trial as f64).collect();
                let qd: Vec<f64> = (0..n).map(|i| 0.5 - 0.2 * i as f64 + 0.1 * trial as f64).collect();
                let third: Vec<f64> = (0..n).map(|i| 1.5 * i as f64 - 2.0).collect();
                let angle: Vec<f64> = (0..n).map(|i| q[i] * sc.angle_scale[i].unwrap_or(1.0)).collect();
                let s: Vec<f64> = angle.iter().map(|a| a.sin()).collect();
                let c: Vec<f64> = angle.iter().map(|a| a.cos()).collect();
                let third_name = match f.function {
                    Function::InverseDynamics => "qdd",
                    _ => "tau",
                };
                let inputs = [("q", &q[..]), ("qd", &qd[..]), (third_name, &third[..]), ("s", &s[..]), ("c", &c[..])];
                let want = f.traced.eval(&inputs).unwrap();
                let got = sc.function.eval(&inputs).unwrap();
                for (a, b) in got.iter().zip(&want) {
                    assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{} {} vs {}", f.label(), a, b);
                }
            }
            // The sc body has no sine left, and the q function one per joint angle it reads.
            assert_eq!(sc.function.op_count().sin_cos, 0);
            assert_eq!(f.op_count.sin_cos, sc.angle_scale.iter().filter(|k| k.is_some()).count());
        }
    }
}

/// With batched trigonometry and run-time dispatch, the AVX2 and FMA copy of
/// `NAME` inlines both the kernel and the body (`NAME_sc_on::<Avx2Fma>`), so
/// the sines and cosines stay in registers; a body split into parts has no
/// `NAME_sc_on`, and `NAME_avx2_fma` calls the chain of its parts'
/// copies, `NAME_sc_avx2_fma`.
#[test]
fn the_dispatched_batched_copy_inlines_its_body_unless_it_is_split() {
    let fast_copy = |src: &str, name: &str| -> String {
        let head = format!("unsafe fn {name}_avx2_fma(");
        src.split(&head).nth(1).unwrap_or_else(|| panic!("no {head}")).split("\n}\n").next().unwrap().to_string()
    };
    let whole = source(&support::model("ur5"), Trig::Batched);
    let split = generate(&support::model("ur5"), &CodegenOptions::default().trig(Trig::Batched).split_lets(Some(40)))
        .unwrap()
        .source;
    for name in ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"] {
        let copy = fast_copy(&whole, name);
        assert!(copy.contains("sin_cos_array_on::<Avx2Fma,"), "{name}: {copy}");
        assert!(copy.contains(&format!("{name}_sc_on::<")) && copy.contains("Avx2Fma"), "{name}: {copy}");
        assert!(!copy.contains(&format!("{name}_sc_avx2_fma(")), "{name}: {copy}");
        // Split at 40 lets: every body but g's is in parts.
        let copy = fast_copy(&split, name);
        if split.contains(&format!("fn {name}_sc_part1_on<")) {
            assert!(copy.contains(&format!("{name}_sc_avx2_fma(")), "{name}: {copy}");
            assert!(!copy.contains(&format!("{name}_sc_on::<")), "{name}: {copy}");
        } else {
            assert_eq!(name, "gravity_torques");
            assert!(copy.contains(&format!("{name}_sc_on::<")), "{name}: {copy}");
        }
    }
}
