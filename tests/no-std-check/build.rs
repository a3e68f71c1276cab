//! Generates the modules that `src/lib.rs` includes: the UR5 and the Panda
//! with each no_std kind of trigonometry (the default options' among them),
//! and scene modules, into OUT_DIR.

use dynagen::codegen::{generate, CodegenOptions, ScalarType, Trig};
use dynagen::Model;
use std::path::Path;

fn main() {
    let robots = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../dynagen/robots");
    println!("cargo:rerun-if-changed=build.rs");
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    // `None`: the default options' trigonometry (batched), which must need no std either.
    let modules = [
        ("ur5", "ur5_libm.rs", Some(Trig::Libm), ScalarType::F64),
        ("ur5", "ur5_inputs.rs", Some(Trig::Inputs), ScalarType::F64),
        ("ur5", "ur5_batched.rs", None, ScalarType::F64),
        ("ur5", "ur5_libm_f32.rs", Some(Trig::Libm), ScalarType::F32),
        ("ur5", "ur5_batched_f32.rs", Some(Trig::Batched), ScalarType::F32),
        ("panda", "panda_inputs.rs", Some(Trig::Inputs), ScalarType::F64),
    ];
    for (robot, file, trig, scalar) in modules {
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        let mut opts = CodegenOptions::default().scalar(scalar).source(format!("dynagen/robots/{robot}.urdf"));
        if let Some(trig) = trig {
            opts = opts.trig(trig);
        }
        let module = generate(&model, &opts).unwrap_or_else(|e| panic!("generating {file}: {e}"));
        std::fs::write(Path::new(&out).join(file), module.source).expect("writing the generated module");
    }
    // Scenes without std: the UR5 controller scene (Coulomb friction, whose
    // smoothing takes a square root) on libm (libm's sqrt), with the sines and
    // cosines as inputs and with the batched ones in f64 and f32 (the module's
    // own sqrt and sqrtf); and a torque scene with the sines and cosines as
    // inputs and the tip wrench and gravity as arguments.
    use dynagen::codegen::Function;
    use dynagen::scene::{Gravity, Scene, SceneFile};
    let ur5 = Model::from_urdf_file(robots.join("ur5.urdf")).expect("the UR5");
    let file = SceneFile::from_toml_file(robots.join("../scenes/ur5_controller.toml")).expect("the controller scene");
    println!("cargo:rerun-if-changed={}", robots.join("../scenes/ur5_controller.toml").display());
    let base = file.code.apply(CodegenOptions::default().source("dynagen/robots/ur5.urdf"));
    let controller = &file.scene;
    let torque = Scene::new().gravity(Gravity::Input).tip_wrench("ee_link").viscous("elbow_joint", 0.5);
    let scenes = [
        ("ur5_controller_libm.rs", controller, base.clone().trig(Trig::Libm)),
        ("ur5_controller_sincos.rs", controller, base.clone().trig(Trig::Inputs)),
        ("ur5_controller_batched.rs", controller, base.clone().trig(Trig::Batched)),
        ("ur5_controller_batched_f32.rs", controller, base.clone().trig(Trig::Batched).scalar(ScalarType::F32)),
        ("ur5_tau_sincos.rs", &torque, base.clone().functions([Function::InverseDynamics]).trig(Trig::Inputs)),
    ];
    for (file, scene, opts) in scenes {
        let applied = scene.apply(&ur5).unwrap_or_else(|e| panic!("{file}: {e}"));
        let module = dynagen::codegen::generate_scene(&applied, &opts).unwrap_or_else(|e| panic!("{file}: {e}"));
        std::fs::write(Path::new(&out).join(file), module.source).expect("writing the generated module");
    }
}
