//! Generates the UR5 module with dynagen's code generator into OUT_DIR, for
//! `tests/generated_ur5.rs` to compile and check against the generic solver.

use dynagen::codegen::{generate, CodegenOptions, ScalarType};
use dynagen::Model;
use std::path::Path;

fn main() {
    let urdf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../dynagen/robots/ur5.urdf");
    println!("cargo:rerun-if-changed={}", urdf.display());
    println!("cargo:rerun-if-changed=build.rs");
    let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    for (file, scalar) in [("ur5.rs", ScalarType::F64), ("ur5_f32.rs", ScalarType::F32)] {
        let opts = CodegenOptions::default().scalar(scalar).source("dynagen/robots/ur5.urdf");
        let module = generate(&model, &opts).unwrap_or_else(|e| panic!("generating {file}: {e}"));
        std::fs::write(Path::new(&out).join(file), module.source).expect("writing the generated module");
    }
}
