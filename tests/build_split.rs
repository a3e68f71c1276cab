//! Part of `build.rs`: the modules of `tests/generated_split.rs`, on the
//! skewed chain of `dynagen/tests/support/skewed_chain.rs` (the chain of the
//! operation-count growth test): 4 joints whole and cut into parts of at
//! most 100 `let`s (every function split, to compare bit for bit), and 12
//! joints with the default split (its forward dynamics, about 3,900 `let`s,
//! would overflow rustc's stack in this debug build if it were one
//! function). The UR5 scene with every run-time input is written again cut
//! into parts of at most 60 `let`s (`ur5_inputs_split.rs`), for the
//! parameters a scene adds.

#[path = "../dynagen/tests/support/skewed_chain.rs"]
mod skewed_chain;

use dynagen::codegen::{CodegenOptions, DEFAULT_SPLIT_LETS};

/// Writes the modules.
pub fn generate() {
    println!("cargo:rerun-if-changed=build_split.rs");
    println!("cargo:rerun-if-changed=../dynagen/tests/support/skewed_chain.rs");
    let modules =
        [(4, None, "chain4_whole.rs"), (4, Some(100), "chain4_split.rs"), (12, Some(DEFAULT_SPLIT_LETS), "chain12.rs")];
    for (n, split, file) in modules {
        dynagen::Builder::new()
            .model(skewed_chain::skewed_chain(n))
            .options(CodegenOptions::default().split_lets(split))
            .file_name(file)
            .generate()
            .unwrap_or_else(|e| panic!("generating {file}: {e}"));
    }
    dynagen::Builder::new()
        .urdf("../dynagen/robots/ur5.urdf")
        .scene(super::ur5_inputs_scene())
        .functions(super::UR5_INPUTS_FUNCTIONS)
        .options(CodegenOptions::default().split_lets(Some(60)))
        .file_name("ur5_inputs_split.rs")
        .generate()
        .expect("generating the split ur5_inputs scene");
}
