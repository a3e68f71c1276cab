//! A crate that includes a generated module in a private `mod` and calls
//! one of its functions compiles without a warning (`-D warnings`): no
//! dead-code warning about the functions it does not call, whatever the
//! options (trigonometry, scalar, dispatch, split bodies, a scene's frame
//! functions and run-time inputs).

mod support;

use dynagen::codegen::{Builder, ScalarType, Trig};
use std::path::Path;

/// Type-checks (and lints) `lib.rs` including `module` privately and
/// calling `call` with `-D warnings` and `extra` rustc arguments; panics
/// with rustc's messages on a warning.
fn compiles_without_warnings(case: &str, module: &str, call: &str, extra: &[&str]) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("codegen_unused").join(case);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("robot.rs"), module).unwrap();
    let lib = format!("mod robot {{\n    include!(\"robot.rs\");\n}}\n\npub fn one() -> f64 {{\n    {call}\n}}\n");
    std::fs::write(dir.join("lib.rs"), lib).unwrap();
    let out = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .args(["--edition", "2021", "--crate-type", "lib", "--emit", "metadata", "-D", "warnings", "--out-dir"])
        .arg(&dir)
        .args(extra)
        .arg(dir.join("lib.rs"))
        .output()
        .expect("running rustc");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && stderr.trim().is_empty(), "{case}: rustc says:\n{stderr}");
}

fn module(builder: Builder) -> String {
    builder.generate_module().unwrap().source
}

#[test]
fn a_module_of_which_one_function_is_called_compiles_without_a_warning() {
    let ur5 = || Builder::new().urdf(support::robot_path("ur5"));
    let gravity = "robot::gravity_torques(&[0.1; robot::DOF])[1]";
    let default = module(ur5());
    compiles_without_warnings("default", &default, gravity, &[]);
    // The same with the target features of the AVX2 + FMA copies (which
    // are then left out, as are the dispatch's helpers).
    compiles_without_warnings("native", &default, gravity, &["-C", "target-feature=+avx2,+fma"]);
    compiles_without_warnings(
        "f32_std_no_dispatch",
        &module(ur5().scalar(ScalarType::F32).trig(Trig::Std).runtime_dispatch(false).fma(false)),
        "robot::mass_matrix(&[0.1; robot::DOF])[0][0] as f64",
        &[],
    );
    compiles_without_warnings(
        "inputs_split",
        &module(ur5().trig(Trig::Inputs).split_lets(Some(40))),
        "robot::inverse_dynamics_sc(&[0.1; 6], &[0.9; 6], &[0.0; 6], &[0.0; 6])[0]",
        &[],
    );
    compiles_without_warnings(
        "scene",
        &module(ur5().scene_file(support::scene_path("ur5_controller"))),
        "robot::frame_pose_ee_link(&[0.1; robot::DOF])[0][3]",
        &[],
    );
    // Mimic joints, with angles of their own among the sines and cosines.
    let gripper = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gripper_mimic.urdf");
    compiles_without_warnings(
        "mimic",
        &module(Builder::new().urdf(&gripper)),
        "robot::gravity_torques(&[0.1; robot::DOF])[2]",
        &[],
    );
    // floating, with a base of 1 kg (the file's base link has no mass, which
    // would make the base and the first joint dependent: no forward dynamics)
    let mut model = dynagen::Model::from_urdf_file(&gripper).unwrap();
    model.base_inertia = dynagen::spatial::Inertia::from_mass_com_inertia(
        1.0,
        dynagen::spatial::Vec3([0.0; 3]),
        dynagen::spatial::Sym3([0.01, 0.01, 0.01, 0.0, 0.0, 0.0]),
    );
    compiles_without_warnings(
        "mimic_floating",
        &module(Builder::new().model(model).floating_base(true)),
        "robot::gravity_torques(&[0.1; robot::NQ])[2]",
        &[],
    );
}
