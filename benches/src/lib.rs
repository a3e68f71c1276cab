//! The generated modules benchmarked by `benches/codegen.rs` (written by
//! build.rs from the bundled URDFs), and the path of the bundled robots.
//! See README.md for the results and the command. The timing with
//! Pinocchio's statistic ([`time`], [`pinocchio_states`]) is shared by the
//! examples that run beside a Pinocchio program.

use nalgebra::{DMatrix, DVector};
use std::hint::black_box;
use std::time::Instant;

// `LAYOUT` and a function whose size it sets, ahead of the generated
// modules (build.rs): see [`layout`].
include!(concat!(env!("OUT_DIR"), "/layout_pad.rs"));

/// The code layout of this build (`DYNAGEN_BENCH_LAYOUT`, 0 by default),
/// for the timing's header. Calling it keeps the padding function that
/// sets it in the binary, ahead of the modules, so that builds with other
/// values time the same code at other addresses
/// (`scripts/reference/layouts.sh`).
pub fn layout() -> usize {
    black_box(layout_pad(black_box(1.0)));
    LAYOUT
}

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
generated!(iiwa14_batched, "iiwa14_batched.rs", "The KUKA iiwa 14, `NAME(q, …)` by `sin_cos_all`.");
generated!(
    panda_mimic,
    "panda_mimic.rs",
    "The Panda with franka_description's mimic finger (`dynagen/tests/data/panda_mimic.urdf`), default options."
);
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
generated!(
    quadruped12_floating_unrolled,
    "quadruped12_floating_unrolled.rs",
    "The quadruped12's floating τ, M and h with every branch unrolled (`--floating-base --no-branch-loops`)."
);
generated!(
    humanoid32_floating_unrolled,
    "humanoid32_floating_unrolled.rs",
    "The humanoid32's floating τ, M and h with every branch unrolled (`--floating-base --no-branch-loops`)."
);

/// The states, calls per batch, batches and warm-up batches of the
/// timings with Pinocchio's statistic (`scripts/reference/bench_common.hpp`).
pub const STATES: usize = 1000;
/// Calls per batch.
pub const BATCH: usize = 1000;
/// Batches timed.
pub const BATCHES: usize = 300;
/// Batches run before.
pub const WARMUP: usize = 20;

/// (median, minimum) ns per call of `call(state index)`.
pub fn time(mut call: impl FnMut(usize)) -> (f64, f64) {
    for _ in 0..WARMUP {
        for i in 0..BATCH {
            call(i % STATES);
        }
    }
    let mut per = Vec::with_capacity(BATCHES);
    for _ in 0..BATCHES {
        let t = Instant::now();
        for i in 0..BATCH {
            call(i % STATES);
        }
        per.push(t.elapsed().as_nanos() as f64 / BATCH as f64);
    }
    per.sort_by(f64::total_cmp);
    (per[BATCHES / 2], per[0])
}

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

/// One state: q, and q̇, q̈, τ.
pub struct State<const NQ: usize, const NV: usize> {
    /// The configuration (NQ).
    pub q: [f64; NQ],
    /// q̇, q̈ and τ (NV each).
    pub v: [[f64; NV]; 3],
}

impl<const NQ: usize, const NV: usize> State<NQ, NV> {
    /// q, q̇, q̈ and τ as vectors, for the generic solver.
    pub fn vectors(&self) -> [nalgebra::DVector<f64>; 4] {
        let v = |x: &[f64]| nalgebra::DVector::from_column_slice(x);
        [v(&self.q), v(&self.v[0]), v(&self.v[1]), v(&self.v[2])]
    }
}

/// Random states as the Pinocchio program draws them (its distribution, not
/// its generator): q in [-π, π] (prismatic joints, flagged in `prismatic`,
/// within 0..0.04 m; a floating base's position too, its quaternion made a
/// unit one), q̇ in [-2, 2], q̈ in [-5, 5], τ in [-10, 10].
pub fn pinocchio_states<const NQ: usize, const NV: usize>(prismatic: &[bool]) -> Vec<State<NQ, NV>> {
    let mut unit = uniform(0x2024_0611);
    let base = NQ - prismatic.len();
    (0..STATES)
        .map(|_| {
            let mut q: [f64; NQ] = core::array::from_fn(|j| match j.checked_sub(base) {
                Some(j) if prismatic[j] => 0.02 * (unit() + 1.0),
                _ => std::f64::consts::PI * unit(),
            });
            if base == 7 {
                let n = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
                q[3..7].iter_mut().for_each(|x| *x /= n);
            }
            let v = [2.0, 5.0, 10.0].map(|scale| core::array::from_fn(|_| scale * unit()));
            State { q, v }
        })
        .collect()
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

/// The generic solver of the fixed-base robot in the URDF file `path`, and
/// [`pinocchio_states`] for it (its prismatic joints flagged), with the same
/// states as vectors ([`State::vectors`]).
pub fn fixed_base_states<const N: usize>(path: &str) -> (dynagen::Robot, Vec<State<N, N>>, Vec<[DVector<f64>; 4]>) {
    let robot = dynagen::Robot::from_urdf_file(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let model = robot.model();
    let prismatic: Vec<bool> = (0..N).map(|k| !model.bodies[model.joint_body(k)].joint.is_revolute()).collect();
    let st = pinocchio_states::<N, N>(&prismatic);
    let v = st.iter().map(State::vectors).collect();
    (robot, st, v)
}

/// The generic solver's `inverse_dynamics_into`, `mass_matrix_into`,
/// `bias_forces_into` and `forward_dynamics_into` on the states `v` of
/// [`fixed_base_states`], each [`time`]d.
pub fn time_generic(robot: &mut dynagen::Robot, v: &[[DVector<f64>; 4]]) -> Vec<(&'static str, (f64, f64))> {
    let n = v[0][0].len();
    let (mut out, mut mm) = (DVector::zeros(n), DMatrix::zeros(n, n));
    let rows = vec![
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
    rows
}

/// The generated module `$m`'s `inverse_dynamics`, `mass_matrix`,
/// `bias_forces` and `forward_dynamics` on the states `$st` of
/// [`fixed_base_states`], each [`time`]d (each call's input behind a
/// `black_box` and its whole output behind one too).
#[macro_export]
macro_rules! time_generated {
    ($m:path, $st:expr) => {{
        use std::hint::black_box;
        use $m as m;
        let st = $st;
        vec![
            (
                "generated inverse_dynamics",
                $crate::time(|i| {
                    black_box(&m::inverse_dynamics(black_box(&st[i].q), &st[i].v[0], &st[i].v[1]));
                }),
            ),
            (
                "generated mass_matrix",
                $crate::time(|i| {
                    black_box(&m::mass_matrix(black_box(&st[i].q)));
                }),
            ),
            (
                "generated bias_forces",
                $crate::time(|i| {
                    black_box(&m::bias_forces(black_box(&st[i].q), &st[i].v[0]));
                }),
            ),
            (
                "generated forward_dynamics",
                $crate::time(|i| {
                    black_box(&m::forward_dynamics(black_box(&st[i].q), &st[i].v[0], &st[i].v[2]));
                }),
            ),
        ]
    }};
}

/// Prints the rows of [`time_generated!`] and [`time_generic`] for `robot`
/// (its file name) with `n` joints.
pub fn print_rows(robot: &str, n: usize, rows: &[(&str, (f64, f64))]) {
    println!(
        "dynagen, {robot} nv={n}, ns per call (median and minimum of {BATCHES} batches of {BATCH} calls), code layout {}",
        layout()
    );
    for (name, (median, min)) in rows {
        println!("  {name:<32} median {median:8.1} ns  min {min:8.1} ns");
    }
}
