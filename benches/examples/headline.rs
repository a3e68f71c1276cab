//! The headline of `docs/performance.md`: the UR5, the Panda and the KUKA
//! iiwa 14 (fixed base), dynagen's generated `inverse_dynamics`,
//! `mass_matrix`, `bias_forces` and `forward_dynamics` (the `*_batched`
//! modules of build.rs: default options, what `dynagen generate
//! dynagen/robots/ROBOT.urdf` writes) and the generic solver's (`Robot`,
//! the `_into` forms), with the statistic of
//! `scripts/reference/pinocchio_bench.cpp` (1000 random states, median of
//! 300 batches of 1000 calls after a warm-up, and the minimum).
//! `scripts/reference/headline_bench.sh` runs it and Pinocchio's C++ in
//! alternation.
//!
//! `cargo run --release -p dynagen-bench --example headline [ROBOT ...]`
//! (ROBOT: ur5, panda, iiwa14; all three without one)

use dynagen_bench::{fixed_base_states, print_rows, time_generated, time_generic, urdf};

/// Times the generated module `$m` and the generic solver on `$robot`.
macro_rules! headline {
    ($robot:literal, $m:ident) => {{
        use dynagen_bench::$m as m;
        let (mut robot, st, v) = fixed_base_states::<{ m::DOF }>(&urdf($robot));
        let mut rows = time_generated!(dynagen_bench::$m, &st);
        rows.extend(time_generic(&mut robot, &v));
        print_rows(concat!($robot, ".urdf"), m::DOF, &rows);
    }};
}

fn main() {
    let robots: Vec<String> = std::env::args().skip(1).collect();
    let wants = |name: &str| robots.is_empty() || robots.iter().any(|r| r == name);
    if wants("ur5") {
        headline!("ur5", ur5_batched);
    }
    if wants("panda") {
        headline!("panda", panda_batched);
    }
    if wants("iiwa14") {
        headline!("iiwa14", iiwa14_batched);
    }
}
