//! Generates the UR5 module in f32 into OUT_DIR with [`dynagen::Builder`],
//! for `tests/generated_bundled.rs` to compile and check against the
//! generic solver (the f64 modules are the committed ones in `generated/`).

use dynagen::codegen::ScalarType;

mod build_stiff;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    dynagen::Builder::new()
        .urdf("../dynagen/robots/ur5.urdf")
        .scalar(ScalarType::F32)
        .file_name("ur5_f32.rs")
        .generate()
        .expect("generating the f32 UR5 module");
    build_stiff::generate();
}
