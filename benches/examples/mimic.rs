//! The Panda with franka_description's mimic finger (8 joints; the module
//! of `dynagen generate dynagen/tests/data/panda_mimic.urdf`, written by
//! build.rs): the generated `inverse_dynamics`, `mass_matrix`,
//! `bias_forces` and `forward_dynamics` (M by CRBA and LᵀDL: the
//! articulated-body algorithm cannot take mimic joints), and the generic
//! solver's, with the statistic of `scripts/reference/pinocchio_bench.cpp`
//! (1000 random states, median of 300 batches of 1000 calls after a
//! warm-up, and the minimum). `scripts/reference/mimic_bench.sh` runs it
//! and Pinocchio's C++ with its URDF parser's mimic option in alternation.
//!
//! `cargo run --release -p dynagen-bench --example mimic`

use dynagen_bench::{fixed_base_states, panda_mimic as m, print_rows, time_generated, time_generic};

fn main() {
    let urdf = format!("{}/../dynagen/tests/data/panda_mimic.urdf", env!("CARGO_MANIFEST_DIR"));
    let (mut robot, st, v) = fixed_base_states::<{ m::DOF }>(&urdf);
    let mut rows = time_generated!(dynagen_bench::panda_mimic, &st);
    rows.extend(time_generic(&mut robot, &v));
    print_rows("panda_mimic.urdf", m::DOF, &rows);
}
