//! Generates the modules that `src/lib.rs` includes: the UR5 and the Panda
//! with each no_std kind of trigonometry, into OUT_DIR.

use dynagen::codegen::{generate, CodegenOptions, ScalarType, Trig};
use dynagen::Model;
use std::path::Path;

fn main() {
    let robots = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../dynagen/robots");
    println!("cargo:rerun-if-changed=build.rs");
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    let modules = [
        ("ur5", "ur5_libm.rs", Trig::Libm, ScalarType::F64),
        ("ur5", "ur5_inputs.rs", Trig::Inputs, ScalarType::F64),
        ("ur5", "ur5_batched.rs", Trig::Batched, ScalarType::F64),
        ("ur5", "ur5_libm_f32.rs", Trig::Libm, ScalarType::F32),
        ("ur5", "ur5_batched_f32.rs", Trig::Batched, ScalarType::F32),
        ("panda", "panda_inputs.rs", Trig::Inputs, ScalarType::F64),
    ];
    for (robot, file, trig, scalar) in modules {
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        let opts = CodegenOptions::default().trig(trig).scalar(scalar).source(format!("dynagen/robots/{robot}.urdf"));
        let module = generate(&model, &opts).unwrap_or_else(|e| panic!("generating {file}: {e}"));
        std::fs::write(Path::new(&out).join(file), module.source).expect("writing the generated module");
    }
}
