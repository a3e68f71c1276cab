//! The macros as a user meets them: one crate that compiles and runs, and
//! each kind of mistake giving a compile error at the offending token (the
//! expected messages are the `.stderr` files beside the cases).

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.pass("tests/ui/pass_inline_robot.rs");
    t.pass("tests/ui/pass_scene.rs");
    t.pass("tests/ui/pass_nonphysical_inertia.rs");
    t.compile_fail("tests/ui/fail_*.rs");
}
