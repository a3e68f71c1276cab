//! The generated modules benchmarked by `benches/codegen.rs` (written by
//! build.rs from the bundled URDFs), and the path of the bundled robots.
//! See README.md for the results and the command.

macro_rules! generated {
    ($name:ident, $file:literal, $what:literal) => {
        #[doc = $what]
        #[allow(missing_docs)]
        pub mod $name {
            include!(concat!(env!("OUT_DIR"), "/", $file));
        }
    };
}

generated!(ur5_std, "ur5_std.rs", "The UR5, `NAME(q, …)` by std's `sin_cos`.");
generated!(ur5_batched, "ur5_batched.rs", "The UR5, `NAME(q, …)` by `sin_cos_all`.");
generated!(panda_std, "panda_std.rs", "The Panda, `NAME(q, …)` by std's `sin_cos`.");
generated!(ur5_base, "ur5_base.rs", "The UR5's `NAME_sc` bodies without fused multiply-adds and run-time dispatch.");
generated!(
    panda_base,
    "panda_base.rs",
    "The Panda's `NAME_sc` bodies without fused multiply-adds and run-time dispatch."
);
generated!(panda_batched, "panda_batched.rs", "The Panda, `NAME(q, …)` by `sin_cos_all`.");
generated!(
    quadruped12_floating,
    "quadruped12_floating.rs",
    "The quadruped12 with a floating base (`--floating-base`), default options."
);
generated!(
    humanoid32_floating,
    "humanoid32_floating.rs",
    "The humanoid32 with a floating base (`--floating-base`), default options."
);

/// A deterministic generator of numbers uniform in [−1, 1) (xorshift64*),
/// the examples' states: the same every run, no dependency.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    move || {
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        (x.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The URDF of a bundled robot.
pub fn urdf(robot: &str) -> String {
    format!("{}/../dynagen/robots/{robot}.urdf", env!("CARGO_MANIFEST_DIR"))
}

/// `sin_cos_all` of the Panda (9 angles), not inlined: for reading the assembly.
#[inline(never)]
pub fn sin_cos_9(q: &[f64; 9]) -> ([f64; 9], [f64; 9]) {
    panda_batched::sin_cos_all(q)
}
