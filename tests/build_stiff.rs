//! Part of `build.rs`: generates the stiff robots of the stiff and extreme
//! suite (`dynagen_tests::STIFF_GENERATED`, defined in `src/lib.rs`, which is
//! compiled into the build script too) into `OUT_DIR/stiff_<name>.rs`, for
//! `tests/stiff_extreme.rs` to check against the generic solver and the
//! double-double reference.

#[path = "src/lib.rs"]
#[allow(dead_code, unused_imports)]
pub mod cases;

/// Writes the modules.
pub fn generate() {
    println!("cargo:rerun-if-changed=src/lib.rs");
    println!("cargo:rerun-if-changed=build_stiff.rs");
    for name in cases::STIFF_GENERATED {
        dynagen::Builder::new()
            .model(cases::stiff_case(name).model)
            .file_name(&format!("stiff_{name}.rs"))
            .generate()
            .unwrap_or_else(|e| panic!("generating the stiff case {name}: {e}"));
    }
}
