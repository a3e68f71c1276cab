//! Generated against generic on a shared, noisy machine: each generated
//! function of the UR5 and the Panda with its trigonometry (`NAME(q, …)`
//! of the `Trig::Std` module, by std's `sin_cos`, and of the
//! `Trig::Batched` module, by the module's `sin_cos_array`), its body alone
//! (`NAME_sc`, sines and cosines given), the same body without fused
//! multiply-adds and without run-time dispatch (`*_base` modules: on a
//! default build the SSE2 code that ran before either, on a native build the
//! unfused body), and the generic solver, timed in
//! alternating rounds (each call's whole
//! output stays behind a `black_box` of its address, so nothing of a body is left out) of 2,000 calls on 8
//! states; the minimum over rounds per call is reported (interference only
//! ever adds time, so the minimum is the least disturbed estimate).
//!
//! `cargo run --release -p dynagen-bench --example interleaved [ROUNDS]`

use dynagen::algorithms::{aba, bias, crba, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use dynagen_bench::urdf;
use std::hint::black_box;
use std::time::Instant;

const CALLS: usize = 2000;

/// One state: q, q̇, q̈, τ, sin q, cos q.
type State<const N: usize> = [[f64; N]; 6];
/// A body on a state (one entry of its output).
type Body<const N: usize> = fn(&State<N>) -> f64;

fn states<const N: usize>(seed: u64) -> Vec<[[f64; N]; 6]> {
    let mut next = dynagen_bench::uniform(seed);
    (0..8)
        .map(|_| {
            let q: [f64; N] = core::array::from_fn(|_| 2.0 * next());
            let qd = core::array::from_fn(|_| 2.0 * next());
            let qdd = core::array::from_fn(|_| 5.0 * next());
            let tau = core::array::from_fn(|_| 20.0 * next());
            [q, qd, qdd, tau, q.map(f64::sin), q.map(f64::cos)]
        })
        .collect()
}

/// Nanoseconds per call of each closure: the minimum over `rounds`
/// alternating rounds.
fn race<const N: usize>(rounds: usize, st: &[[[f64; N]; 6]], fs: &mut [&mut dyn FnMut(&State<N>) -> f64]) -> Vec<f64> {
    let mut best = vec![f64::INFINITY; fs.len()];
    let n = fs.len();
    for r in 0..rounds {
        // Alternate the order too, so that no variant always follows another.
        for j in 0..n {
            let k = if r % 2 == 0 { j } else { n - 1 - j };
            let f = &mut fs[k];
            let t = Instant::now();
            for i in 0..CALLS {
                black_box(f(black_box(&st[i & 7])));
            }
            best[k] = best[k].min(t.elapsed().as_nanos() as f64 / CALLS as f64);
        }
    }
    best
}

/// The first entry of a function's output, the whole output left where the
/// function wrote it behind a `black_box` of its address, so that every store
/// of it stays. (A by-value `black_box` of the returned array made the
/// compiler copy it, for the 6×6 M a 288-byte `memcpy` whose wide loads read
/// the function's fresh 8-byte stores; a controller reading its result pays
/// neither. The generic solver writes into its buffers in place.)
#[inline(always)]
fn first<T: Copy, const K: usize>(out: &[T; K]) -> T {
    black_box(out);
    out[0]
}

/// `tau`, `m`, `h`, `fd` of a module's bodies on a state `[q, qd, qdd, tau, s, c]`.
macro_rules! bodies {
    ($name:ident, $m:ident, $n:literal) => {
        mod $name {
            use super::first;
            use dynagen_bench::$m as m;
            pub fn tau(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::inverse_dynamics_sc(&s[4], &s[5], &s[1], &s[2]))
            }
            pub fn m(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::mass_matrix_sc(&s[4], &s[5]))[0]
            }
            pub fn h(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::bias_forces_sc(&s[4], &s[5], &s[1]))
            }
            pub fn fd(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::forward_dynamics_sc(&s[4], &s[5], &s[1], &s[3]))
            }
        }
    };
    ($name:ident, $m:ident, $n:literal, q) => {
        mod $name {
            use super::first;
            use dynagen_bench::$m as m;
            pub fn tau(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::inverse_dynamics_sc(&s[4], &s[5], &s[0], &s[1], &s[2]))
            }
            pub fn m(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::mass_matrix_sc(&s[4], &s[5], &s[0]))[0]
            }
            pub fn h(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::bias_forces_sc(&s[4], &s[5], &s[0], &s[1]))
            }
            pub fn fd(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::forward_dynamics_sc(&s[4], &s[5], &s[0], &s[1], &s[3]))
            }
        }
    };
}
/// `tau`, `m`, `h`, `fd` of a module's `NAME(q, …)` functions, the
/// sines and cosines computed inside.
macro_rules! with_trig {
    ($name:ident, $m:ident, $n:literal) => {
        mod $name {
            use super::first;
            use dynagen_bench::$m as m;
            pub fn tau(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::inverse_dynamics(&s[0], &s[1], &s[2]))
            }
            pub fn m(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::mass_matrix(&s[0]))[0]
            }
            pub fn h(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::bias_forces(&s[0], &s[1]))
            }
            pub fn fd(s: &[[f64; $n]; 6]) -> f64 {
                first(&m::forward_dynamics(&s[0], &s[1], &s[3]))
            }
        }
    };
}
with_trig!(ur5_std_trig, ur5_std, 6);
with_trig!(ur5_batched_trig, ur5_batched, 6);
with_trig!(panda_std_trig, panda_std, 9);
with_trig!(panda_batched_trig, panda_batched, 9);
bodies!(ur5_new, ur5_std, 6);
bodies!(ur5_old, ur5_base, 6);
bodies!(panda_new, panda_std, 9, q);
bodies!(panda_old, panda_base, 9, q);

/// The functions of one robot: generic, then std trig, batched trig, the
/// body, the body without fused multiply-adds and run-time dispatch.
struct Variants<const N: usize> {
    std: [Body<N>; 4],
    batched: [Body<N>; 4],
    new: [Body<N>; 4],
    old: [Body<N>; 4],
}

fn robot<const N: usize>(name: &str, rounds: usize, v: Variants<N>) {
    let model = Model::from_urdf_file(urdf(name)).unwrap();
    let st = states::<N>(0x5eed);
    let mut ws = Workspace::<f64>::new(&model);
    let g = Vec3::<f64>::from_f64(&model.gravity);
    let mut out = vec![0.0; N];
    let mut mm = vec![0.0; N * N];
    for (k, f) in ["tau", "M", "h", "fd"].into_iter().enumerate() {
        let mut generic = |s: &[[f64; N]; 6]| {
            match k {
                0 => rnea::rnea(&model, &mut ws, &s[0], Some(&s[1]), Some(&s[2]), Loads::gravity(&g), &mut out),
                1 => crba::crba(&model, &mut ws, &s[0], Loads::none(), &mut mm),
                2 => bias::bias_forces(&model, &mut ws, &s[0], &s[1], Some(&g), &mut out),
                _ => aba::aba(&model, &mut ws, &s[0], &s[1], &s[3], Loads::gravity(&g), &mut out),
            }
            out[0] + mm[0]
        };
        let (mut a, mut b, mut c, mut d) = (v.std[k], v.batched[k], v.new[k], v.old[k]);
        let t = race(rounds, &st, &mut [&mut generic, &mut a, &mut b, &mut c, &mut d]);
        let cell = |i: usize| format!("{:.1} ns ({:.1}x)", t[i], t[0] / t[i]);
        println!(
            "| {name} | {f} | {:.0} ns | {} | {} | {} | {} | {:.2} |",
            t[0],
            cell(1),
            cell(2),
            cell(3),
            cell(4),
            t[4] / t[3]
        );
    }
}

fn main() {
    let rounds: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(200);
    println!(
        "| robot | function | generic | gen_std (std sin_cos) | gen_batched (sin_cos_array) | gen_sc (body, trig excluded) | gen_sc_base (body, fma and dispatch off) | base / gen_sc |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    robot::<6>(
        "ur5",
        rounds,
        Variants {
            std: [ur5_std_trig::tau, ur5_std_trig::m, ur5_std_trig::h, ur5_std_trig::fd],
            batched: [ur5_batched_trig::tau, ur5_batched_trig::m, ur5_batched_trig::h, ur5_batched_trig::fd],
            new: [ur5_new::tau, ur5_new::m, ur5_new::h, ur5_new::fd],
            old: [ur5_old::tau, ur5_old::m, ur5_old::h, ur5_old::fd],
        },
    );
    robot::<9>(
        "panda",
        rounds,
        Variants {
            std: [panda_std_trig::tau, panda_std_trig::m, panda_std_trig::h, panda_std_trig::fd],
            batched: [panda_batched_trig::tau, panda_batched_trig::m, panda_batched_trig::h, panda_batched_trig::fd],
            new: [panda_new::tau, panda_new::m, panda_new::h, panda_new::fd],
            old: [panda_old::tau, panda_old::m, panda_old::h, panda_old::fd],
        },
    );
}
