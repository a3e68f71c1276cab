//! Rewrites the vendored modules `generated/src/<robot>.rs` of the bundled
//! robots from `dynagen/robots/<robot>.urdf`:
//!
//! ```text
//! cargo run -p dynagen-tests --bin regenerate
//! ```
//!
//! `tests/tests/generated_bundled.rs` fails when a committed file differs
//! from a fresh generation.

fn main() {
    let dir = dynagen_tests::workspace_root().join("generated/src");
    for name in dynagen_tests::BUNDLED {
        let source = dynagen_tests::bundled_module(name).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join(format!("{name}.rs"));
        let old = std::fs::read_to_string(&path).unwrap_or_default();
        if old == source {
            println!("{}: unchanged", path.display());
        } else {
            std::fs::write(&path, &source).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
            println!("{}: written", path.display());
        }
    }
}
