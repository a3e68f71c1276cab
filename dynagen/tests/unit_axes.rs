//! A URDF axis is a direction: the joint turns by exactly q about the unit
//! axis, as urdfdom, Pinocchio and MuJoCo read it. An axis written with all
//! its decimals has a length of 1 ± 1 ulp; were the angle |axis|·q, every
//! angle would be off by ulp·|q|, and at |q| = 1e4 rad τ, M, h and g would
//! lose three digits.
//!
//! `tests/data/unit_axes_chain.urdf` is a 7-joint chain with random axes
//! normalised in f64 and printed with 17 digits (four of length 1 − 1 ulp);
//! `tests/data/pinocchio_unit_axes.json` holds Pinocchio's τ, M, h and g on
//! it at |q| up to 1e4 rad (scripts/reference/make_file_robots_data.py).
//! The reference is the same algorithms in double-double (≈32 digits) on
//! the model dynagen reads: dynagen's f64 results, generic and generated,
//! must be within 1e-14 of it, and within twice Pinocchio's own error.

mod support;

use approx::abs_diff_eq;
use dynagen::algorithms::{bias, crba, rnea, Loads, Workspace};
use dynagen::codegen::{generate, CodegenOptions, Function};
use dynagen::model::{JointDescription, ModelWarning, RobotDescription};
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, Model, Scalar};
use serde_json::Value;
use std::path::Path;
use support::{rel_err, scale};

fn data_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

/// τ, M (row-major), h and g of the generic algorithms in the scalar `S`.
fn eval<S: Scalar>(model: &Model, q: &[f64], qd: &[f64], qdd: &[f64]) -> [Vec<f64>; 4] {
    let n = model.dof();
    let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
    let back = |x: &[S]| x.iter().map(|v| v.to_f64().unwrap()).collect::<Vec<f64>>();
    let (q, qd, qdd) = (c(q), c(qd), c(qdd));
    let grav = Vec3::<S>::from_f64(&model.gravity);
    let mut ws = Workspace::<S>::new(model);
    let mut out = vec![S::zero(); n];
    rnea::rnea(model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&grav), &mut out);
    let tau = back(&out);
    let mut m = vec![S::zero(); n * n];
    crba::crba(model, &mut ws, &q, Loads::none(), &mut m);
    bias::bias_forces(model, &mut ws, &q, &qd, Some(&grav), &mut out);
    let h = back(&out);
    bias::gravity_torques(model, &mut ws, &q, &grav, &mut out);
    [tau, back(&m), h, back(&out)]
}

fn chain() -> Model {
    Model::from_urdf_file(data_path("unit_axes_chain.urdf")).unwrap()
}

#[test]
fn every_urdf_axis_is_a_unit_axis_with_scale_one() {
    let model = chain();
    // every axis of the file has length 1 ± 1 ulp: none is "visibly" off
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    let xml = std::fs::read_to_string(data_path("unit_axes_chain.urdf")).unwrap();
    let (desc, _) = RobotDescription::from_urdf_str(&xml).unwrap();
    let off = desc.joints.iter().filter(|j| j.axis.norm() != 1.0).count();
    assert!(off >= 3, "the file should hold axes of length 1 − 1 ulp, has {off}");
    for b in &model.bodies {
        assert_eq!(b.joint.axis_norm, 1.0, "joint {}", b.joint.name);
        assert!(desc.joints.iter().all(|j| j.axis_is_direction));
    }
    // The generated code reads each angle as q itself: scale exactly 1.
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    for f in &module.functions {
        for (i, k) in f.sin_cos_inputs.angle_scale.iter().enumerate() {
            assert!(k.is_none_or(|k| k == 1.0), "{}: joint {i} scaled by {k:?}", f.label());
        }
    }
}

#[test]
fn a_visibly_non_unit_urdf_axis_turns_by_q_too() {
    // (0 0 2) and (3 4 0): normalised with a warning; the angle is q.
    let inertial = r#"<inertial><mass value="1"/><origin xyz="0.1 0.2 0.3"/><inertia ixx="0.1" iyy="0.2" izz="0.15" ixy="0" ixz="0" iyz="0"/></inertial>"#;
    let xml = format!(
        r#"<robot name="r"><link name="base"/><link name="a">{inertial}</link>
        <joint name="j" type="continuous"><parent link="base"/><child link="a"/><axis xyz="3 4 0"/></joint></robot>"#
    );
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.warnings, [ModelWarning::AxisNormalised { joint: "j".into(), norm: 5.0 }]);
    let unit = Model::from_urdf_str(&xml.replace("3 4 0", "0.6 0.8 0")).unwrap();
    // (3 4 0)/5 and (0.6 0.8 0) differ by an ulp, not the angle by ulp·q
    for q in [0.3, 1e4] {
        let (a, b) = (eval::<f64>(&m, &[q], &[0.7], &[0.2]), eval::<f64>(&unit, &[q], &[0.7], &[0.2]));
        for (x, y) in a.iter().zip(&b) {
            assert!(abs_diff_eq!(&x[..], &y[..], epsilon = 1e-15 * scale(y, 0.0)), "q = {q}: {x:?} against {y:?}");
        }
    }
}

#[test]
fn screw_axes_of_the_rust_constructors_keep_their_length() {
    // The Modern Robotics semantics: angle = |ω|·θ.
    let desc = |axis: [f64; 3], direction: bool| {
        let mut j = JointDescription::continuous("j", "base", "a", axis);
        j.axis_is_direction = direction;
        dynagen::RobotBuilder::new("r")
            .link("base", None)
            .link("a", Some(dynagen::model::Inertial::new(1.0, [0.1, 0.2, 0.0], [0.1, 0.2, 0.15, 0.0, 0.0, 0.0])))
            .joint(j)
            .build()
            .unwrap()
    };
    let screw = desc([0.0, 0.0, 2.0], false);
    assert_eq!(screw.bodies[0].joint.axis_norm, 2.0);
    let direction = desc([0.0, 0.0, 2.0], true);
    assert_eq!(direction.bodies[0].joint.axis_norm, 1.0);
    let unit = desc([0.0, 0.0, 1.0], false);
    // g of the screw joint at q is that of the unit joint at 2q
    let g = |m: &Model, q: f64| eval::<f64>(m, &[q], &[0.0], &[0.0])[3][0];
    assert!((g(&screw, 0.4) - 2.0 * g(&unit, 0.8)).abs() < 1e-15);
    assert_eq!(g(&direction, 0.4), g(&unit, 0.4));
}

#[test]
fn tau_m_h_g_at_1e4_rad_within_1e_14_and_twice_pinocchios_error() {
    let model = chain();
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(data_path("pinocchio_unit_axes.json")).unwrap()).unwrap();
    let names = ["tau", "M", "h", "g"];
    let (mut ours, mut generated, mut pin) = ([0.0f64; 4], [0.0f64; 4], [0.0f64; 4]);
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let (q, qd, qdd) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]));
        let f = eval::<f64>(&model, &q, &qd, &qdd);
        let r = eval::<DoubleDouble>(&model, &q, &qd, &qdd);
        let p: Vec<Vec<f64>> = names
            .iter()
            .map(|w| match *w {
                "M" => s["M"].as_array().unwrap().iter().flat_map(vector).collect(),
                w => vector(&s[w]),
            })
            .collect();
        // Each entry within 1e-14 of the double-double value's largest; the
        // largest errors are measured for the comparison with Pinocchio's.
        let within = |got: &[f64], want: &[f64]| abs_diff_eq!(got, want, epsilon = 1e-14 * scale(want, 0.0));
        for i in 0..4 {
            assert!(within(&f[i], &r[i]), "state {k}: {} {:?} against {:?}", names[i], f[i], r[i]);
            ours[i] = ours[i].max(rel_err(&f[i], &r[i], 0.0));
            pin[i] = pin[i].max(rel_err(&p[i], &r[i], 0.0));
        }
        // the generated code, as traced (the emitted module's arithmetic)
        for func in &module.functions {
            let (i, third) = match func.function {
                Function::InverseDynamics => (0, ("qdd", &qdd[..])),
                Function::MassMatrix => (1, ("tau", &[][..])),
                Function::BiasForces => (2, ("tau", &[][..])),
                Function::GravityTorques => (3, ("tau", &[][..])),
                _ => continue,
            };
            let got = func.traced.eval(&[("q", &q), ("qd", &qd), third]).unwrap();
            assert!(within(&got, &r[i]), "state {k}: generated {} {got:?} against {:?}", names[i], r[i]);
            generated[i] = generated[i].max(rel_err(&got, &r[i], 0.0));
        }
    }
    // Pinocchio's own errors are those of an f64 evaluation (≈1e-16–1e-15),
    // which the angle |axis|·q would have exceeded by a factor of 1000.
    for i in 0..4 {
        assert!(pin[i] < 1e-14, "{}: Pinocchio's error {:e}: a different model?", names[i], pin[i]);
        for (who, e) in [("generic", ours[i]), ("generated", generated[i])] {
            assert!(e <= 2.0 * pin[i], "{who} {}: error {e:e} is more than twice Pinocchio's {:e}", names[i], pin[i]);
        }
    }
    println!("max relative errors (tau, M, h, g): ours {ours:?}, generated {generated:?}, Pinocchio {pin:?}");
}
