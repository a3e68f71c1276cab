//! Generates into OUT_DIR with [`dynagen::Builder`]: the UR5 module in f32,
//! for `tests/generated_bundled.rs` (the f64 modules are the committed ones
//! in `generated/`), and in f64 (with and without run-time dispatch) for `tests/generated_fma.rs` (and, the default options' module, `tests/generated_bundled.rs`), and three scene modules for `tests/generated_scene.rs`:
//! the bundled `ur5_controller` scene (from its TOML file), a UR5 with every
//! run-time input (gravity, tip wrench, a payload) and a lock, and an f32
//! UR5 with only τ and no gravity; the derivatives of the UR5, the Panda,
//! the two-armed torso, an f32 UR5 and the `ur5_controller` scene
//! (`tests/generated_derivatives.rs`); the stiff robots (`build_stiff.rs`) and
//! the split long-chain modules (`build_split.rs`); the floating quadruped and
//! the legged manipulator's controller scene (`tests/generated_floating.rs`);
//! the Panda with its mimic finger and the mimic gripper linkage, with the
//! batched and with std's trigonometry (`tests/generated_mimic.rs`).

use dynagen::codegen::ScalarType;
use dynagen::scene::{Gravity, Scene};

mod build_split;
mod build_stiff;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let ur5 = "../dynagen/robots/ur5.urdf";
    // Default options (batched trigonometry, fused multiply-adds, run-time
    // dispatch), for tests/generated_fma.rs and tests/generated_bundled.rs.
    dynagen::Builder::new().urdf(ur5).file_name("ur5_f64.rs").generate().expect("generating the UR5 module");
    // The same without run-time dispatch: the build's target features only.
    dynagen::Builder::new()
        .urdf(ur5)
        .runtime_dispatch(false)
        .file_name("ur5_f64_baseline.rs")
        .generate()
        .expect("generating the UR5 module without dispatch");
    dynagen::Builder::new()
        .urdf(ur5)
        .scalar(ScalarType::F32)
        .file_name("ur5_f32.rs")
        .generate()
        .expect("generating the f32 UR5 module");
    dynagen::Builder::new()
        .urdf(ur5)
        .scene_file("../dynagen/scenes/ur5_controller.toml")
        .generate()
        .expect("generating the ur5_controller scene");
    dynagen::Builder::new()
        .urdf(ur5)
        .scene(ur5_inputs_scene())
        .name("ur5_inputs")
        .functions(UR5_INPUTS_FUNCTIONS)
        .generate()
        .expect("generating the ur5_inputs scene");
    dynagen::Builder::new()
        .urdf(ur5)
        .scene(Scene::new().gravity(Gravity::None))
        .name("ur5_tau_f32")
        .functions(&["inverse_dynamics"])
        .scalar(ScalarType::F32)
        .generate()
        .expect("generating the ur5_tau_f32 scene");
    // The derivatives, generated only on request (tests/generated_derivatives.rs).
    let derivatives = ["inverse_dynamics_derivatives", "forward_dynamics_derivatives", "mass_matrix_inverse"];
    for (robot, name, scalar) in [
        (ur5, "ur5_derivatives", ScalarType::F64),
        ("../dynagen/robots/panda.urdf", "panda_derivatives", ScalarType::F64),
        ("../dynagen/robots/torso_two_arms.urdf", "torso_two_arms_derivatives", ScalarType::F64),
        ("../dynagen/robots/iiwa14.urdf", "iiwa14_derivatives", ScalarType::F64),
        ("../dynagen/robots/quadruped12.urdf", "quadruped12_derivatives", ScalarType::F64),
        (ur5, "ur5_derivatives_f32", ScalarType::F32),
        ("../dynagen/robots/panda.urdf", "panda_derivatives_f32", ScalarType::F32),
    ] {
        dynagen::Builder::new()
            .urdf(robot)
            .name(name)
            .functions(&derivatives)
            .scalar(scalar)
            .generate()
            .expect("generating a derivatives module");
    }
    dynagen::Builder::new()
        .urdf(ur5)
        .scene_file("../dynagen/scenes/ur5_controller.toml")
        .name("ur5_controller_derivatives")
        .functions(&derivatives)
        .generate()
        .expect("generating the ur5_controller scene's derivatives");
    // A floating-base quadruped, and the legged manipulator's controller
    // scene (armature, friction, a tool wrench, a run-time payload, contact
    // frames), for tests/generated_floating.rs.
    dynagen::Builder::new()
        .urdf("../dynagen/robots/quadruped12.urdf")
        .floating_base(true)
        .file_name("quadruped12_floating.rs")
        .generate()
        .expect("generating the floating quadruped");
    // Its derivatives (tests/generated_derivatives.rs).
    dynagen::Builder::new()
        .urdf("../dynagen/robots/quadruped12.urdf")
        .floating_base(true)
        .name("quadruped12_floating_derivatives")
        .functions(&derivatives)
        .generate()
        .expect("generating the floating quadruped's derivatives");
    // The floating humanoid's M unrolled: a body long enough to store its
    // entries where they are computed (statements::EARLY_STORES_MIN_LETS).
    dynagen::Builder::new()
        .urdf("../dynagen/robots/humanoid32.urdf")
        .floating_base(true)
        .name("humanoid32_floating_mass_matrix")
        .functions(&["mass_matrix"])
        .branch_loops(false)
        .generate()
        .expect("generating the floating humanoid's mass matrix");
    // τ, M, h and q̈ with the legs and arms run as one body in vector lanes or a loop
    // (codegen/trace/branches.rs): the humanoid's two legs with the run-time
    // dispatch (two to a register); the quadruped's four with it (four to a
    // register on a processor with AVX2), without it (two to a register in
    // a default build), and in f32 (a scalar loop).
    let loops = [
        ("humanoid32", "humanoid32_branch_loops", true, ScalarType::F64),
        ("quadruped12", "quadruped12_branch_loops", true, ScalarType::F64),
        ("quadruped12", "quadruped12_branch_loops_no_dispatch", false, ScalarType::F64),
        ("quadruped12", "quadruped12_branch_loops_f32", false, ScalarType::F32),
    ];
    for (robot, name, dispatch, scalar) in loops {
        dynagen::Builder::new()
            .urdf(format!("../dynagen/robots/{robot}.urdf"))
            .floating_base(true)
            .name(name)
            .functions(&["inverse_dynamics", "mass_matrix", "bias_forces", "forward_dynamics"])
            .branch_loops(true)
            .runtime_dispatch(dispatch)
            .scalar(scalar)
            .generate()
            .unwrap_or_else(|e| panic!("generating {name}: {e}"));
    }
    // The quadruped with motors: armature (each leg its own) and viscous and
    // Coulomb friction, which its forward dynamics' legs take in their lanes.
    dynagen::Builder::new()
        .urdf("../dynagen/robots/quadruped12.urdf")
        .floating_base(true)
        .scene(build_stiff::cases::quadruped_motors_scene())
        .name("quadruped12_motors")
        .functions(&["inverse_dynamics", "mass_matrix", "bias_forces", "forward_dynamics"])
        .generate()
        .expect("generating the quadruped with motors");
    dynagen::Builder::new()
        .urdf("../dynagen/robots/legged_manipulator.urdf")
        .floating_base(true)
        .scene_file("../dynagen/scenes/legged_manipulator.toml")
        .generate()
        .expect("generating the legged manipulator's controller scene");
    // Robots with mimic joints, as users have them (tests/generated_mimic.rs).
    for robot in ["panda", "gripper"] {
        let urdf = format!("../dynagen/tests/data/{robot}_mimic.urdf");
        println!("cargo:rerun-if-changed={urdf}");
        dynagen::Builder::new()
            .urdf(&urdf)
            .file_name(&format!("{robot}_mimic.rs"))
            .generate()
            .expect("generating a mimic module");
        dynagen::Builder::new()
            .urdf(&urdf)
            .trig(dynagen::codegen::Trig::Std)
            .file_name(&format!("{robot}_mimic_std.rs"))
            .generate()
            .expect("generating a mimic module with std's trigonometry");
    }
    build_stiff::generate();
    build_split::generate();
}

/// The functions of the `ur5_inputs` scene's module: the five, and coriolis.
const UR5_INPUTS_FUNCTIONS: &[&str] =
    &["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics", "coriolis"];

/// The UR5 with every run-time input (gravity, tip wrench, a payload), a
/// lock, armature and friction.
fn ur5_inputs_scene() -> Scene {
    Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("ee_link")
        .payload_input("ee_link")
        .lock("wrist_3_joint", 0.2)
        .armature("elbow_joint", 0.2)
        .coulomb("shoulder_lift_joint", 2.0)
}
