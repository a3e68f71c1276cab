//! The generated derivatives of the dynamics of the UR5, the Panda, the
//! KUKA iiwa 14 and the quadruped12 with its trunk fixed and floating
//! (`inverse_dynamics_derivatives`, `forward_dynamics_derivatives`,
//! `mass_matrix_inverse`, and `inverse_dynamics` for scale), and the generic
//! solver's (`Robot`), with the statistic of
//! `scripts/reference/pinocchio_derivatives_bench.cpp`: 1000 random states,
//! batches of 1000 calls cycling through them after a warm-up, the median
//! over 300 batches of the batch time / 1000, in ns per call (and the
//! minimum). `scripts/reference/derivatives_bench.sh` runs it and the
//! Pinocchio program in alternation.
//!
//! `cargo run --release -p dynagen-bench --example derivatives`

use dynagen::Robot;
use dynagen_bench::{pinocchio_states as states, time, urdf, BATCH, BATCHES};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

#[allow(dead_code)]
mod ur5 {
    include!(concat!(env!("OUT_DIR"), "/ur5_derivatives.rs"));
}
#[allow(dead_code)]
mod panda {
    include!(concat!(env!("OUT_DIR"), "/panda_derivatives.rs"));
}
#[allow(dead_code)]
mod iiwa14 {
    include!(concat!(env!("OUT_DIR"), "/iiwa14_derivatives.rs"));
}
#[allow(dead_code)]
mod quadruped12 {
    include!(concat!(env!("OUT_DIR"), "/quadruped12_derivatives.rs"));
}
#[allow(dead_code)]
mod iiwa14_tau {
    include!(concat!(env!("OUT_DIR"), "/iiwa14_batched.rs"));
}
#[allow(dead_code)]
mod quadruped12_tau {
    include!(concat!(env!("OUT_DIR"), "/quadruped12_batched.rs"));
}
#[allow(dead_code)]
mod quadruped12_floating {
    include!(concat!(env!("OUT_DIR"), "/quadruped12_floating_derivatives.rs"));
}
use dynagen_bench::quadruped12_floating as quadruped12_floating_tau;
#[allow(dead_code)]
mod ur5_tau {
    include!(concat!(env!("OUT_DIR"), "/ur5_batched.rs"));
}
#[allow(dead_code)]
mod panda_tau {
    include!(concat!(env!("OUT_DIR"), "/panda_batched.rs"));
}

/// Times module `$m`'s derivatives (and `$tau`'s τ) on `$robot` (a
/// `Robot`, fixed or floating, named `$name`).
macro_rules! bench {
    ($m:ident, $tau:ident, $name:expr, $robot:expr) => {{
        const N: usize = $m::NV;
        let mut robot: Robot = $robot;
        let prismatic: Vec<bool> = robot.model().bodies.iter().map(|b| !b.joint.is_revolute()).collect();
        let st = states::<{ $m::NQ }, N>(&prismatic);
        let rows = [
            (
                "inverse_dynamics (τ)",
                time(|i| {
                    let s = black_box(&st[i]);
                    let out = $tau::inverse_dynamics(&s.q, &s.v[0], &s.v[1]);
                    black_box(&out);
                }),
            ),
            (
                "inverse_dynamics_derivatives",
                time(|i| {
                    let s = black_box(&st[i]);
                    let out = $m::inverse_dynamics_derivatives(&s.q, &s.v[0], &s.v[1]);
                    black_box(&out);
                }),
            ),
            (
                "forward_dynamics_derivatives",
                time(|i| {
                    let s = black_box(&st[i]);
                    let out = $m::forward_dynamics_derivatives(&s.q, &s.v[0], &s.v[2]);
                    black_box(&out);
                }),
            ),
            (
                "mass_matrix_inverse",
                time(|i| {
                    let s = black_box(&st[i]);
                    let out = $m::mass_matrix_inverse(&s.q);
                    black_box(&out);
                }),
            ),
        ];
        let v: Vec<[DVector<f64>; 4]> = st.iter().map(|s| s.vectors()).collect();
        let (mut a, mut b, mut c) = (DMatrix::zeros(N, N), DMatrix::zeros(N, N), DMatrix::zeros(N, N));
        let generic = [
            (
                "generic inverse_dynamics_derivatives_into",
                time(|i| {
                    let s = black_box(&v[i]);
                    robot.inverse_dynamics_derivatives_into(&s[0], &s[1], &s[2], &mut a, &mut b).unwrap();
                    black_box(&a);
                }),
            ),
            (
                "generic forward_dynamics_derivatives_into",
                time(|i| {
                    let s = black_box(&v[i]);
                    robot.forward_dynamics_derivatives_into(&s[0], &s[1], &s[3], &mut a, &mut b, &mut c).unwrap();
                    black_box(&a);
                }),
            ),
        ];
        for (name, (median, min)) in rows.iter().chain(&generic) {
            println!("{:<20} {name:<44} median {median:9.1} ns  min {min:9.1} ns", $name);
        }
    }};
}

fn main() {
    println!(
        "dynagen generated (default options) and generic, ns per call (median and minimum of {BATCHES} batches of \
         {BATCH} calls), code layout {}",
        dynagen_bench::layout()
    );
    let fixed = |name: &str| Robot::from_urdf_file(urdf(name)).unwrap();
    bench!(ur5, ur5_tau, "ur5", fixed("ur5"));
    bench!(panda, panda_tau, "panda", fixed("panda"));
    bench!(iiwa14, iiwa14_tau, "iiwa14", fixed("iiwa14"));
    bench!(quadruped12, quadruped12_tau, "quadruped12", fixed("quadruped12"));
    let model = dynagen::Model::from_urdf_file(urdf("quadruped12")).unwrap().with_floating_base();
    bench!(quadruped12_floating, quadruped12_floating_tau, "quadruped12:floating", Robot::new(model));
}
