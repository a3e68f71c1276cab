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

use dynagen::Robot;
use dynagen_bench::{pinocchio_states, time, urdf, BATCH, BATCHES};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

/// Times the generated module `$m` and the generic solver on `$robot`.
macro_rules! headline {
    ($robot:literal, $m:path) => {{
        use $m as m;
        const N: usize = m::DOF;
        let mut robot = Robot::from_urdf_file(urdf($robot)).unwrap();
        let model = robot.model().clone();
        let prismatic: Vec<bool> = (0..N).map(|k| !model.bodies[model.joint_body(k)].joint.is_revolute()).collect();
        let st = pinocchio_states::<N, N>(&prismatic);
        let v: Vec<[DVector<f64>; 4]> = st.iter().map(|s| s.vectors()).collect();
        let (mut out, mut mm) = (DVector::zeros(N), DMatrix::zeros(N, N));
        // each call's inputs behind a black_box and its whole output behind one too
        let rows = [
            (
                "generated inverse_dynamics",
                time(|i| {
                    black_box(&m::inverse_dynamics(black_box(&st[i].q), &st[i].v[0], &st[i].v[1]));
                }),
            ),
            (
                "generated mass_matrix",
                time(|i| {
                    black_box(&m::mass_matrix(black_box(&st[i].q)));
                }),
            ),
            (
                "generated bias_forces",
                time(|i| {
                    black_box(&m::bias_forces(black_box(&st[i].q), &st[i].v[0]));
                }),
            ),
            (
                "generated forward_dynamics",
                time(|i| {
                    black_box(&m::forward_dynamics(black_box(&st[i].q), &st[i].v[0], &st[i].v[2]));
                }),
            ),
            (
                "generic inverse_dynamics_into",
                time(|i| robot.inverse_dynamics_into(black_box(&v[i][0]), &v[i][1], &v[i][2], &mut out).unwrap()),
            ),
            ("generic mass_matrix_into", time(|i| robot.mass_matrix_into(black_box(&v[i][0]), &mut mm).unwrap())),
            (
                "generic bias_forces_into",
                time(|i| robot.bias_forces_into(black_box(&v[i][0]), &v[i][1], &mut out).unwrap()),
            ),
            (
                "generic forward_dynamics_into",
                time(|i| robot.forward_dynamics_into(black_box(&v[i][0]), &v[i][1], &v[i][3], &mut out).unwrap()),
            ),
        ];
        black_box((&out, &mm));
        println!(
            "dynagen, {}.urdf nv={N}, ns per call (median and minimum of {BATCHES} batches of {BATCH} calls)",
            $robot
        );
        for (name, (median, min)) in rows {
            println!("  {name:<32} median {median:8.1} ns  min {min:8.1} ns");
        }
    }};
}

fn main() {
    let robots: Vec<String> = std::env::args().skip(1).collect();
    let wants = |name: &str| robots.is_empty() || robots.iter().any(|r| r == name);
    if wants("ur5") {
        headline!("ur5", dynagen_bench::ur5_batched);
    }
    if wants("panda") {
        headline!("panda", dynagen_bench::panda_batched);
    }
    if wants("iiwa14") {
        headline!("iiwa14", dynagen_bench::iiwa14_batched);
    }
}
