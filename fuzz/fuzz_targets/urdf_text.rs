//! Any bytes as a URDF document: the import must return a model or an
//! error, never panic, overflow the stack or hang.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let Ok(xml) = std::str::from_utf8(data) else {
        return;
    };
    match dynagen::Model::from_urdf_str(xml) {
        Ok(model) => common::exercise(model),
        // dynagen's pre-check and urdf-rs must agree on which elements are
        // links and joints
        Err(dynagen::ModelError::Urdf(m)) => assert!(!m.starts_with("the XML reads differently"), "{m}"),
        Err(_) => {}
    }
});
