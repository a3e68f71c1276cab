//! Generated against generic dynamics, in one run: τ, M, h, g and forward
//! dynamics (ABA) of the UR5 and the Panda, for
//!
//! - `generic`: dynagen::algorithms on f64 with a Workspace (no allocation);
//! - `gen_std`: the generated `NAME(q, …)`, sines and cosines by `f64::sin_cos`;
//! - `gen_sc`: the generated `NAME_sc(s, c, …)`, sines and cosines given (trig excluded);
//! - `gen_batched`: the generated `NAME(q, …)` of a `Trig::Batched` module (`sin_cos_all`);
//! - `gen_sc_base`: `NAME_sc` without fused multiply-adds and run-time dispatch (`CodegenOptions::fma(false)`,
//!   `runtime_dispatch(false)`: on a default build the SSE2 body that ran before either, on a native build the unfused body);
//!
//! and `sin_cos_all` against a loop of `f64::sin_cos` (and the `f32` batch,
//! `dynagen::codegen::sin_cos_array_f32`, against `f32::sin_cos`). Each benchmark
//! cycles through 8 random states. Command and results: README.md.

use criterion::{criterion_group, criterion_main, Criterion};
use dynagen::algorithms::{aba, bias, crba, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use dynagen_bench::{panda_batched, panda_std, ur5_batched, ur5_std, urdf};
use std::hint::black_box;

/// xorshift64*, uniform in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// One state: q, q̇, q̈, τ, and sin q, cos q.
#[derive(Clone, Copy)]
struct State<const N: usize> {
    q: [f64; N],
    qd: [f64; N],
    qdd: [f64; N],
    tau: [f64; N],
    s: [f64; N],
    c: [f64; N],
}

fn states<const N: usize>(seed: u64) -> Vec<State<N>> {
    let mut rng = Rng(seed);
    (0..8)
        .map(|_| {
            let q: [f64; N] = core::array::from_fn(|_| 2.0 * rng.next());
            State {
                q,
                qd: core::array::from_fn(|_| 2.0 * rng.next()),
                qdd: core::array::from_fn(|_| 5.0 * rng.next()),
                tau: core::array::from_fn(|_| 20.0 * rng.next()),
                s: q.map(f64::sin),
                c: q.map(f64::cos),
            }
        })
        .collect()
}

/// Benchmarks `f` on the states in turn. Its output stays where `f` wrote
/// it, behind a `black_box` of its address: a by-value `black_box` of a
/// returned array made the compiler copy it (for the 6×6 M a 288-byte
/// `memcpy`), which no controller reading its result pays.
fn cycle<const N: usize, R>(c: &mut Criterion, name: &str, states: &[State<N>], mut f: impl FnMut(&State<N>) -> R) {
    c.bench_function(name, |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 7;
            let out = f(black_box(&states[i]));
            black_box(&out);
        })
    });
}

macro_rules! robot_benches {
    ($fn_name:ident, $robot:literal, $n:literal, $std:ident, $batched:ident) => {
        fn $fn_name(c: &mut Criterion) {
            let model = Model::from_urdf_file(urdf($robot)).unwrap();
            assert_eq!(model.dof(), $n);
            let st = states::<$n>(0x5eed_0000 + $n);
            let mut ws = Workspace::<f64>::new(&model);
            let g = Vec3::<f64>::from_f64(&model.gravity);
            let mut out = [0.0; $n];
            let mut mm = [0.0; $n * $n];
            let r = $robot;
            // τ
            cycle(c, &format!("{r}/tau/generic"), &st, |s| {
                rnea::rnea(&model, &mut ws, &s.q, Some(&s.qd), Some(&s.qdd), Loads::gravity(&g), &mut out);
                out[0]
            });
            cycle(c, &format!("{r}/tau/gen_std"), &st, |s| $std::inverse_dynamics(&s.q, &s.qd, &s.qdd));
            cycle(c, &format!("{r}/tau/gen_sc"), &st, |s| sc::$fn_name::tau(s));
            cycle(c, &format!("{r}/tau/gen_sc_base"), &st, |s| sc::$fn_name::tau_base(s));
            cycle(c, &format!("{r}/tau/gen_batched"), &st, |s| $batched::inverse_dynamics(&s.q, &s.qd, &s.qdd));
            // M
            cycle(c, &format!("{r}/M/generic"), &st, |s| {
                crba::crba(&model, &mut ws, &s.q, Loads::none(), &mut mm);
                mm[0]
            });
            cycle(c, &format!("{r}/M/gen_std"), &st, |s| $std::mass_matrix(&s.q));
            cycle(c, &format!("{r}/M/gen_sc"), &st, |s| sc::$fn_name::m(s));
            cycle(c, &format!("{r}/M/gen_sc_base"), &st, |s| sc::$fn_name::m_base(s));
            cycle(c, &format!("{r}/M/gen_batched"), &st, |s| $batched::mass_matrix(&s.q));
            // h
            cycle(c, &format!("{r}/h/generic"), &st, |s| {
                bias::bias_forces(&model, &mut ws, &s.q, &s.qd, Some(&g), &mut out);
                out[0]
            });
            cycle(c, &format!("{r}/h/gen_std"), &st, |s| $std::bias_forces(&s.q, &s.qd));
            cycle(c, &format!("{r}/h/gen_sc"), &st, |s| sc::$fn_name::h(s));
            cycle(c, &format!("{r}/h/gen_sc_base"), &st, |s| sc::$fn_name::h_base(s));
            cycle(c, &format!("{r}/h/gen_batched"), &st, |s| $batched::bias_forces(&s.q, &s.qd));
            // g
            cycle(c, &format!("{r}/g/generic"), &st, |s| {
                bias::gravity_torques(&model, &mut ws, &s.q, &g, &mut out);
                out[0]
            });
            cycle(c, &format!("{r}/g/gen_std"), &st, |s| $std::gravity_torques(&s.q));
            cycle(c, &format!("{r}/g/gen_sc"), &st, |s| sc::$fn_name::g(s));
            cycle(c, &format!("{r}/g/gen_sc_base"), &st, |s| sc::$fn_name::g_base(s));
            cycle(c, &format!("{r}/g/gen_batched"), &st, |s| $batched::gravity_torques(&s.q));
            // forward dynamics (ABA in both)
            cycle(c, &format!("{r}/fd/generic"), &st, |s| {
                aba::aba(&model, &mut ws, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut out);
                out[0]
            });
            cycle(c, &format!("{r}/fd/gen_std"), &st, |s| $std::forward_dynamics(&s.q, &s.qd, &s.tau));
            cycle(c, &format!("{r}/fd/gen_sc"), &st, |s| sc::$fn_name::fd(s));
            cycle(c, &format!("{r}/fd/gen_sc_base"), &st, |s| sc::$fn_name::fd_base(s));
            cycle(c, &format!("{r}/fd/gen_batched"), &st, |s| $batched::forward_dynamics(&s.q, &s.qd, &s.tau));
            // sin/cos of all joints
            cycle(c, &format!("{r}/sincos/std_loop"), &st, |s| {
                let mut sc = ([0.0; $n], [0.0; $n]);
                for i in 0..$n {
                    (sc.0[i], sc.1[i]) = s.q[i].sin_cos();
                }
                sc
            });
            cycle(c, &format!("{r}/sincos/sin_cos_all"), &st, |s| $batched::sin_cos_all(&s.q));
            // f32: the same angles rounded (sin_cos_array_f32 is what an f32 module's sin_cos_all runs).
            cycle(c, &format!("{r}/sincos/std_loop_f32"), &st, |s| {
                let mut sc = ([0.0f32; $n], [0.0f32; $n]);
                for i in 0..$n {
                    (sc.0[i], sc.1[i]) = (s.q[i] as f32).sin_cos();
                }
                sc
            });
            cycle(c, &format!("{r}/sincos/sin_cos_all_f32"), &st, |s| {
                dynagen::codegen::sin_cos_array_f32(&s.q.map(|x| x as f32))
            });
        }
    };
}

/// The `NAME_sc` calls (their argument lists differ: the Panda's take `q`).
mod sc {
    pub mod ur5_benches {
        use crate::State;
        use dynagen_bench::ur5_base as b;
        use dynagen_bench::ur5_std as m;
        pub fn tau_base(s: &State<6>) -> [f64; 6] {
            b::inverse_dynamics_sc(&s.s, &s.c, &s.qd, &s.qdd)
        }
        pub fn m_base(s: &State<6>) -> [[f64; 6]; 6] {
            b::mass_matrix_sc(&s.s, &s.c)
        }
        pub fn h_base(s: &State<6>) -> [f64; 6] {
            b::bias_forces_sc(&s.s, &s.c, &s.qd)
        }
        pub fn g_base(s: &State<6>) -> [f64; 6] {
            b::gravity_torques_sc(&s.s, &s.c)
        }
        pub fn fd_base(s: &State<6>) -> [f64; 6] {
            b::forward_dynamics_sc(&s.s, &s.c, &s.qd, &s.tau)
        }
        pub fn tau(s: &State<6>) -> [f64; 6] {
            m::inverse_dynamics_sc(&s.s, &s.c, &s.qd, &s.qdd)
        }
        pub fn m(s: &State<6>) -> [[f64; 6]; 6] {
            m::mass_matrix_sc(&s.s, &s.c)
        }
        pub fn h(s: &State<6>) -> [f64; 6] {
            m::bias_forces_sc(&s.s, &s.c, &s.qd)
        }
        pub fn g(s: &State<6>) -> [f64; 6] {
            m::gravity_torques_sc(&s.s, &s.c)
        }
        pub fn fd(s: &State<6>) -> [f64; 6] {
            m::forward_dynamics_sc(&s.s, &s.c, &s.qd, &s.tau)
        }
    }
    pub mod panda_benches {
        use crate::State;
        use dynagen_bench::panda_base as b;
        use dynagen_bench::panda_std as m;
        pub fn tau_base(s: &State<9>) -> [f64; 9] {
            b::inverse_dynamics_sc(&s.s, &s.c, &s.q, &s.qd, &s.qdd)
        }
        pub fn m_base(s: &State<9>) -> [[f64; 9]; 9] {
            b::mass_matrix_sc(&s.s, &s.c, &s.q)
        }
        pub fn h_base(s: &State<9>) -> [f64; 9] {
            b::bias_forces_sc(&s.s, &s.c, &s.q, &s.qd)
        }
        pub fn g_base(s: &State<9>) -> [f64; 9] {
            b::gravity_torques_sc(&s.s, &s.c, &s.q)
        }
        pub fn fd_base(s: &State<9>) -> [f64; 9] {
            b::forward_dynamics_sc(&s.s, &s.c, &s.q, &s.qd, &s.tau)
        }
        pub fn tau(s: &State<9>) -> [f64; 9] {
            m::inverse_dynamics_sc(&s.s, &s.c, &s.q, &s.qd, &s.qdd)
        }
        pub fn m(s: &State<9>) -> [[f64; 9]; 9] {
            m::mass_matrix_sc(&s.s, &s.c, &s.q)
        }
        pub fn h(s: &State<9>) -> [f64; 9] {
            m::bias_forces_sc(&s.s, &s.c, &s.q, &s.qd)
        }
        pub fn g(s: &State<9>) -> [f64; 9] {
            m::gravity_torques_sc(&s.s, &s.c, &s.q)
        }
        pub fn fd(s: &State<9>) -> [f64; 9] {
            m::forward_dynamics_sc(&s.s, &s.c, &s.q, &s.qd, &s.tau)
        }
    }
}

robot_benches!(ur5_benches, "ur5", 6, ur5_std, ur5_batched);
robot_benches!(panda_benches, "panda", 9, panda_std, panda_batched);

criterion_group!(benches, ur5_benches, panda_benches);
criterion_main!(benches);
