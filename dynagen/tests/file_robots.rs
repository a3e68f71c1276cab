//! Robot files as other tools load them: a non-physical inertia accepted on
//! request (and matched against Pinocchio, which loads it), joints that
//! depend on each other found at load time and named, and the messages that
//! used to mislead (an axis of 1e200 or 1e-200).

mod support;

use dynagen::algorithms::{crba, rnea, Loads, Workspace};
use dynagen::codegen::{generate, CodegenError, CodegenOptions, Function};
use dynagen::model::{BuildOptions, Inertial, JointDescription, ModelError, ModelWarning, RobotBuilder};
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, InputError, Model, Robot, Scalar};
use nalgebra::DVector;
use serde_json::Value;
use std::path::{Path, PathBuf};
use support::rel_err;

fn data_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

/// τ and M (row-major) of the generic algorithms in the scalar `S`.
fn tau_m<S: Scalar>(model: &Model, q: &[f64], qd: &[f64], qdd: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = model.dof();
    let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
    let back = |x: &[S]| x.iter().map(|v| v.to_f64().unwrap()).collect::<Vec<f64>>();
    let grav = Vec3::<S>::from_f64(&model.gravity);
    let mut ws = Workspace::<S>::new(model);
    let mut tau = vec![S::zero(); n];
    rnea::rnea(model, &mut ws, &c(q), Some(&c(qd)), Some(&c(qdd)), Loads::gravity(&grav), &mut tau);
    let mut m = vec![S::zero(); n * n];
    crba::crba(model, &mut ws, &c(q), Loads::none(), &mut m);
    (back(&tau), back(&m))
}

const ALLOW: BuildOptions =
    BuildOptions { strict: false, allow_nonphysical_inertia: true, mimic: dynagen::model::MimicJoints::Follow };

#[test]
fn a_nonphysical_inertia_is_refused_naming_the_link_and_the_option() {
    let e = Model::from_urdf_file(data_path("nonphysical_inertia.urdf")).unwrap_err();
    assert!(matches!(&e, ModelError::InertiaNotPositive { link, .. } if link == "utorso"), "{e:?}");
    let text = e.to_string();
    for want in
        ["link \"utorso\"", "not positive semi-definite", "allow_nonphysical_inertia", "--allow-nonphysical-inertia"]
    {
        assert!(text.contains(want), "{want:?} not in {text}");
    }
}

#[test]
fn a_nonphysical_inertia_loads_on_request_and_matches_pinocchio() {
    let model = Model::from_urdf_file_with(data_path("nonphysical_inertia.urdf"), &ALLOW).unwrap();
    let w: Vec<&ModelWarning> =
        model.warnings.iter().filter(|w| matches!(w, ModelWarning::NonPhysicalInertia { .. })).collect();
    assert_eq!(w.len(), 1, "{:?}", model.warnings);
    let text = w[0].to_string();
    for want in ["link \"utorso\"", "indefinite", "forward dynamics may fail"] {
        assert!(text.contains(want), "{want:?} not in {text}");
    }
    assert!(w[0].is_about_the_dynamics());
    let ModelWarning::NonPhysicalInertia { moments, .. } = w[0] else { unreachable!() };
    // the moments the script wrote (GRiD's Atlas utorso)
    for (a, b) in moments.iter().zip([-0.65, 1.65, 2.86]) {
        assert!((a - b).abs() < 1e-12, "{moments:?}");
    }
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(data_path("pinocchio_nonphysical_inertia.json")).unwrap())
            .unwrap();
    let mut indefinite = false;
    for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
        let (q, qd, qdd) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]));
        let (tau, m) = tau_m::<f64>(&model, &q, &qd, &qdd);
        let m_pin: Vec<f64> = s["M"].as_array().unwrap().iter().flat_map(vector).collect();
        let (tau_dd, m_dd) = tau_m::<DoubleDouble>(&model, &q, &qd, &qdd);
        // Pinocchio (f64, its own order of operations) and our f64 agree to
        // rounding; both are within rounding of the double-double values.
        for (what, ours, pin, dd) in [("tau", &tau, &vector(&s["tau"]), &tau_dd), ("M", &m, &m_pin, &m_dd)] {
            let e = rel_err(ours, pin, 1e-3);
            assert!(e < 1e-13, "state {k}: {what} differs from Pinocchio by {e:e}");
            let e = rel_err(ours, dd, 1e-3);
            assert!(e < 1e-14, "state {k}: {what} differs from double-double by {e:e}");
        }
        indefinite |= (0..3).any(|i| m[i * 3 + i] < 0.0);
    }
    assert!(indefinite, "the data should show an indefinite M");
}

#[test]
fn the_builder_and_the_rust_description_take_the_option() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("file_robots_builder");
    let urdf = data_path("nonphysical_inertia.urdf");
    let e = dynagen::Builder::new().urdf(&urdf).out_dir(&dir).cargo_output(false).generate().unwrap_err();
    assert!(e.to_string().contains("utorso") && e.to_string().contains("allow_nonphysical_inertia"), "{e}");
    let written = dynagen::Builder::new()
        .urdf(&urdf)
        .allow_nonphysical_inertia(true)
        .functions(&["inverse_dynamics", "mass_matrix"])
        .out_dir(&dir)
        .cargo_output(false)
        .generate()
        .unwrap();
    assert!(written.module.source.contains("pub fn mass_matrix"));
    let bad = || {
        RobotBuilder::new("r")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [-0.1, 0.2, 0.2, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", "a", [0.0, 0.0, 1.0]))
    };
    assert!(matches!(bad().build(), Err(ModelError::InertiaNotPositive { .. })));
    let m = bad().allow_nonphysical_inertia(true).build().unwrap();
    assert!(matches!(&m.warnings[..], [ModelWarning::NonPhysicalInertia { link, .. }] if link == "a"));
}

/// Two coincident joints with one axis moving one body: M = [[a, a], [a, a]].
fn coincident_joints() -> String {
    r#"<robot name="twin">
  <link name="base"/>
  <link name="mid"/>
  <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/><inertia ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="hand"><inertial><origin xyz="0.1 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="mid"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="continuous"><parent link="mid"/><child link="arm"/><axis xyz="0 0 1"/></joint>
  <joint name="j3" type="continuous"><parent link="arm"/><child link="hand"/><origin xyz="0.6 0 0"/><axis xyz="0 1 0"/></joint>
</robot>"#
        .to_string()
}

#[test]
fn dependent_joints_are_named_at_load_time() {
    let model = Model::from_urdf_str(&coincident_joints()).unwrap();
    assert_eq!(model.dependent_joints(), [["j1".to_string(), "j2".to_string()]]);
    let w = model.warnings.iter().find(|w| matches!(w, ModelWarning::DependentJoints { .. })).unwrap();
    let text = w.to_string();
    for want in ["joints \"j1\" and \"j2\" are dependent", "singular at every configuration", "forward dynamics"] {
        assert!(text.contains(want), "{want:?} not in {text}");
    }
    // M(q) really is singular: rows j1 and j2 equal, at any q
    let (_, m) = tau_m::<f64>(&model, &[0.3, -1.2, 0.8], &[0.0; 3], &[0.0; 3]);
    assert_eq!(m[0..3], m[3..6]);
    // a robot whose M is regular has no such warning (the bundled ones)
    for name in ["ur5", "panda", "torso_two_arms", "planar_2link"] {
        assert!(support::model(name).dependent_joints().is_empty(), "{name}");
    }
}

#[test]
fn dependent_joints_allow_inverse_dynamics_and_refuse_forward_dynamics() {
    let mut robot = Robot::new(Model::from_urdf_str(&coincident_joints()).unwrap());
    let v = |x: [f64; 3]| DVector::from_vec(x.to_vec());
    let (q, qd) = (v([0.3, -1.2, 0.8]), v([0.5, 0.1, -0.3]));
    let tau = robot.inverse_dynamics(&q, &qd, &v([1.0, 2.0, 3.0])).unwrap();
    assert!(tau.iter().all(|x| x.is_finite()));
    let e = robot.forward_dynamics(&q, &qd, &tau).unwrap_err();
    assert_eq!(e, InputError::DependentJoints { joints: vec!["j1".into(), "j2".into()] });
    let text = e.to_string();
    assert!(text.contains("forward dynamics is undefined") && text.contains("joints \"j1\" and \"j2\""), "{text}");
    assert!(robot.forward_dynamics_ldlt(&q, &qd, &tau).is_err());
    // generated: forward dynamics refused, the rest generated
    let model = robot.model().clone();
    let e = generate(&model, &CodegenOptions::default()).unwrap_err();
    assert!(matches!(&e, CodegenError::DependentJoints(j) if j == &["j1", "j2"]), "{e:?}");
    assert!(e.to_string().contains("leave forward_dynamics out"), "{e}");
    let options = CodegenOptions::default().functions([Function::InverseDynamics, Function::MassMatrix]);
    let module = generate(&model, &options).unwrap();
    assert!(!module.source.contains("pub fn forward_dynamics"));
}

#[test]
fn a_robot_singular_at_one_configuration_is_not_dependent() {
    // A massless upper arm and a point mass on the forearm (planar, both
    // axes z): det M = m²·l1²·l2²·sin²(q_elbow), singular only with the
    // elbow straight. Not dependent; singular there, naming both joints.
    let model = RobotBuilder::new("planar")
        .link("base", None)
        .link("upper", None)
        .link("fore", Some(Inertial::point_mass(1.0, [1.0, 0.0, 0.0])))
        .joint(JointDescription::revolute("shoulder", "base", "upper", [0.0, 0.0, 1.0]))
        .joint(JointDescription::revolute("elbow", "upper", "fore", [0.0, 0.0, 1.0]).origin([1.0, 0.0, 0.0], [0.0; 3]))
        .build()
        .unwrap();
    assert!(model.dependent_joints().is_empty(), "{:?}", model.warnings);
    assert!(model.singular_joints_at(&[0.2, 0.7]).is_empty());
    assert_eq!(model.singular_joints_at(&[0.2, 0.0]), [["shoulder".to_string(), "elbow".to_string()]]);
}

#[test]
fn axes_of_1e200_and_1e_200_are_directions_not_overflows() {
    let inertial = r#"<inertial><mass value="1"/><origin xyz="0.1 0.2 0"/><inertia ixx="0.1" iyy="0.2" izz="0.15" ixy="0" ixz="0" iyz="0"/></inertial>"#;
    let xml = |axis: &str| {
        format!(
            r#"<robot name="r"><link name="base"/><link name="a">{inertial}</link>
            <joint name="j" type="continuous"><parent link="base"/><child link="a"/><axis xyz="{axis}"/></joint></robot>"#
        )
    };
    let unit = Model::from_urdf_str(&xml("0 0.6 0.8")).unwrap();
    for (axis, norm) in [("0 6e199 8e199", 1e200), ("0 6e-201 8e-201", 1e-200), ("0 6e-311 8e-311", 1e-310)] {
        // a subnormal length (1e-310) holds its components to about 1e-13
        let tol = if norm < 1e-300 { 1e-12 } else { 1e-15 };
        let m = Model::from_urdf_str(&xml(axis)).unwrap_or_else(|e| panic!("axis {axis}: {e}"));
        match &m.warnings[..] {
            [ModelWarning::AxisNormalised { joint, norm: n }] => {
                assert_eq!(joint, "j");
                assert!((n / norm - 1.0).abs() < tol, "{n:e}");
            }
            w => panic!("axis {axis}: {w:?}"),
        }
        assert!(m.warnings[0].to_string().contains("normalised to unit length"));
        let a = m.bodies[0].joint.axis.0;
        assert!((a[1] - 0.6).abs() < tol && (a[2] - 0.8).abs() < tol, "{a:?}");
        let (t, u) = (tau_m::<f64>(&m, &[0.4], &[1.0], &[2.0]), tau_m::<f64>(&unit, &[0.4], &[1.0], &[2.0]));
        assert!(rel_err(&t.0, &u.0, 0.0) < tol);
    }
    // A screw axis (Rust, Modern Robotics) of such a length scales the
    // motion: refused naming the joint and the length, not as an inertia.
    for axis in [[0.0, 0.0, 1e200], [0.0, 0.0, 1e-200]] {
        let e = RobotBuilder::new("r")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.1, 0.2, 0.2, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", "a", axis))
            .build()
            .unwrap_err();
        assert!(matches!(&e, ModelError::AxisOutOfRange { joint, .. } if joint == "j"), "{e:?}");
        let text = e.to_string();
        assert!(text.contains("joint \"j\": the axis has length") && !text.contains("inertia"), "{text}");
        // the same axis as a direction is fine
        let m = RobotBuilder::new("r")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.1, 0.2, 0.2, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", "a", axis).unit_axis())
            .build()
            .unwrap();
        assert_eq!(m.bodies[0].joint.axis.0, [0.0, 0.0, 1.0]);
    }
}

const RACECAR_LIKE: &str = r#"<?xml version="1.0"?>
<robot name="racecar">
  <material name="black"><color rgba="0 0 0"/></material>
  <link name="base"/>
  <link name="wheel">
    <visual>
      <geometry>
        <mesh filename="package://racecar/meshes/wheel.STL" scale="1 1"/>
        <material name="black"/>
      </geometry>
    </visual>
    <collision><geometry><cylinder length="0.045"/></geometry></collision>
    <inertial><origin xyz="0 0 0.01"/><mass value="0.34"/><inertia ixx="0.0003" iyy="0.0004" izz="0.0003" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base"/><child link="wheel"/><origin xyz="0.1 0.2 0"/><axis xyz="0 1 0"/>
  </joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type><oops/></transmission>
</robot>
"#;

#[test]
fn what_urdfdom_loads_and_dynagen_does_not_read_is_accepted() {
    // A <material> inside <geometry>, a mesh scale of two numbers, a
    // cylinder without radius, a colour of three numbers: urdf-rs refused
    // the file with no place named; the dynamics do not depend on them.
    let m = Model::from_urdf_str(RACECAR_LIKE).unwrap();
    let bare = RACECAR_LIKE
        .lines()
        .filter(|l| {
            !["visual", "geometry", "mesh", "material", "collision", "transmission"].iter().any(|t| l.contains(t))
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert!(!bare.contains("<visual"), "{bare}");
    let b = Model::from_urdf_str(&bare).unwrap();
    assert_eq!(m.bodies, b.bodies);
    // a byte-order mark before the declaration too
    let with_bom = format!("\u{feff}{RACECAR_LIKE}");
    assert_eq!(Model::from_urdf_str(&with_bom).unwrap().bodies, m.bodies);
}

#[test]
fn what_urdf_rs_still_refuses_is_placed_by_line_column_and_joint() {
    let xml = RACECAR_LIKE.replace(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 1 0"/><dynamics damping="abc"/>"#);
    let e = Model::from_urdf_str(&xml).unwrap_err();
    let text = e.to_string();
    assert_eq!(text, "malformed URDF: line 15 column 3: joint \"wheel_joint\": invalid float literal");
}

#[test]
fn a_build_script_warning_stays_on_one_line_whatever_the_link_is_called() {
    // The Builder prints these as `cargo:warning=…`: a newline in a name
    // would start a cargo directive of the file's choosing.
    let name = "evil\ncargo:rustc-link-lib=evil\u{2028}";
    let m = RobotBuilder::new("r")
        .link("base", None)
        .link(name, Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [-0.1, 0.2, 0.2, 0.0, 0.0, 0.0])))
        .joint(JointDescription::revolute("j", "base", name, [0.0, 0.0, 1.0]))
        .allow_nonphysical_inertia(true)
        .build()
        .unwrap();
    let w = m.warnings.iter().find(|w| w.is_about_the_dynamics()).unwrap();
    let line = w.one_line();
    assert!(!line.contains('\n') && !line.contains('\u{2028}'), "{line}");
    assert!(line.contains("evil\\u{a}cargo:rustc-link-lib=evil\\u{2028}"), "{line}");
}
