//! The Panda with franka_description's mimic finger (8 joints; the module
//! of `dynagen generate dynagen/tests/data/panda_mimic.urdf`, written by
//! build.rs): the generated `inverse_dynamics`, `mass_matrix` and
//! `forward_dynamics` (M by CRBA and LᵀDL: the articulated-body algorithm
//! cannot take mimic joints), and the generic solver's, with the statistic
//! of `scripts/reference/pinocchio_bench.cpp` (1000 random states, median of
//! 300 batches of 1000 calls after a warm-up, and the minimum).
//! `scripts/reference/mimic_bench.sh` runs it and Pinocchio's C++ with its
//! URDF parser's mimic option in alternation.
//!
//! `cargo run --release -p dynagen-bench --example mimic`

use dynagen::Robot;
use dynagen_bench::{panda_mimic as m, pinocchio_states, time, BATCH, BATCHES};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

fn main() {
    const N: usize = m::DOF;
    let urdf = format!("{}/../dynagen/tests/data/panda_mimic.urdf", env!("CARGO_MANIFEST_DIR"));
    let mut robot = Robot::from_urdf_file(&urdf).unwrap();
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
            "generic forward_dynamics_into",
            time(|i| robot.forward_dynamics_into(black_box(&v[i][0]), &v[i][1], &v[i][3], &mut out).unwrap()),
        ),
    ];
    black_box((&out, &mm));
    println!(
        "dynagen, panda_mimic.urdf nv={N}, ns per call (median and minimum of {BATCHES} batches of {BATCH} calls)"
    );
    for (name, (median, min)) in rows {
        println!("  {name:<32} median {median:8.1} ns  min {min:8.1} ns");
    }
}
