//! The generated floating-base functions of the quadruped12 and the
//! humanoid32 (the modules of `dynagen generate dynagen/robots/ROBOT.urdf
//! --floating-base`, written by build.rs): `inverse_dynamics`,
//! `mass_matrix`, `bias_forces` and `forward_dynamics`, each from q (its
//! sines and cosines computed inside; the legs and arms in vector lanes, as by
//! default), and τ, h and M of the modules made with `--no-branch-loops` too
//! (every branch unrolled), timed as `examples/interleaved.rs`
//! times the fixed-base ones and as
//! `scripts/reference/pinocchio_floating_bench.cpp` times Pinocchio: 8
//! states, alternating rounds of 2,000 calls (each call's output left where
//! it was written, behind a `black_box` of its address), the minimum over
//! rounds per call (and the median). Run alternately with Pinocchio by
//! `scripts/reference/floating_bench.sh`.
//!
//! Then the same functions called cold, as
//! `pinocchio_floating_bench.cpp` calls Pinocchio's: before each call a
//! sweep writes one byte in every line of an 8 MiB buffer, which evicts the
//! function's code and data from the core's caches (the L1s and the L2:
//! 1 MiB on Zen 5, 2 MiB on recent Intel cores) but not from the shared L3,
//! as when a controller does other work between two calls; each call is
//! timed on its own (two `Instant::now`), and the median and tenth
//! percentile over the samples printed, with those of an empty function
//! (the timer's cost, not subtracted).
//!
//! `DYNAGEN_BENCH_STACK=BYTES` makes every timed call that many bytes deeper
//! in the stack (a multiple of 16 below 4096): a function's time depends on
//! where the stack puts its frame (`docs/performance.md`, "Where the frame
//! lies"). Linux starts each process's stack at a random place within a
//! page, so an offset names the same place in every run only without that
//! randomisation (`setarch -R`), as `floating_bench.sh` runs with `STACKS`.
//!
//! `cargo run --release -p dynagen-bench --example floating [ROUNDS] [ROBOT] [COLD]`
//! (ROBOT: quadruped12 or humanoid32; both without it or with `all`; COLD:
//! cold samples a function, default 1000, 0 for none)

use std::hint::black_box;
use std::time::Instant;

const CALLS: usize = 2000;

/// One state: q, q̇, q̈, τ.
struct State<const NQ: usize, const NV: usize> {
    q: [f64; NQ],
    qd: [f64; NV],
    qdd: [f64; NV],
    tau: [f64; NV],
}

/// A timed function on a state (the first entry of its output).
type Timed<const NQ: usize, const NV: usize> = fn(&State<NQ, NV>) -> f64;

/// 8 states: base position in [-1, 1]³, a uniformly random unit quaternion,
/// joints in [-π, π], q̇ in [-2, 2], q̈ in [-5, 5], τ in [-20, 20].
fn states<const NQ: usize, const NV: usize>(seed: u64) -> Vec<State<NQ, NV>> {
    let mut next = dynagen_bench::uniform(seed);
    (0..8)
        .map(|_| {
            let mut q = [0.0; NQ];
            for p in &mut q[..3] {
                *p = next();
            }
            // Uniform on the unit sphere of R⁴: rejection from the unit ball.
            let quat = loop {
                let v: [f64; 4] = core::array::from_fn(|_| next());
                let n = v.iter().map(|a| a * a).sum::<f64>().sqrt();
                if n > 0.1 && n <= 1.0 {
                    break v.map(|a| a / n);
                }
            };
            q[3..7].copy_from_slice(&quat);
            for j in &mut q[7..] {
                *j = std::f64::consts::PI * next();
            }
            State {
                q,
                qd: core::array::from_fn(|_| 2.0 * next()),
                qdd: core::array::from_fn(|_| 5.0 * next()),
                tau: core::array::from_fn(|_| 20.0 * next()),
            }
        })
        .collect()
}

/// The first entry of a function's output, the whole output left where the
/// function wrote it behind a `black_box` of its address (as in
/// `examples/interleaved.rs`).
#[inline(always)]
fn first<T: Copy, const K: usize>(out: &[T; K]) -> T {
    black_box(out);
    out[0]
}

/// The four timed functions of a generated floating-base module `$m`, and
/// τ, h and M of `$unrolled` (the same robot with `--no-branch-loops`).
macro_rules! timed {
    ($m:path, $unrolled:path) => {{
        use $m as m;
        use $unrolled as unrolled;
        fn tau(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&m::inverse_dynamics(&s.q, &s.qd, &s.qdd))
        }
        fn mass(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&m::mass_matrix(&s.q))[0]
        }
        fn h(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&m::bias_forces(&s.q, &s.qd))
        }
        fn fd(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&m::forward_dynamics(&s.q, &s.qd, &s.tau))
        }
        fn tau_unrolled(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&unrolled::inverse_dynamics(&s.q, &s.qd, &s.qdd))
        }
        fn h_unrolled(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&unrolled::bias_forces(&s.q, &s.qd))
        }
        fn mass_unrolled(s: &State<{ m::NQ }, { m::NV }>) -> f64 {
            first(&unrolled::mass_matrix(&s.q))[0]
        }
        let fs: [(&str, Timed<{ m::NQ }, { m::NV }>); 7] = [
            ("inverse_dynamics", tau),
            ("mass_matrix", mass),
            ("bias_forces", h),
            ("forward_dynamics", fd),
            ("inverse_dyn. unrolled", tau_unrolled),
            ("bias_forces unrolled", h_unrolled),
            ("mass_matrix unrolled", mass_unrolled),
        ];
        fs
    }};
}

/// Times `fs` on `robot`'s states in alternating rounds and prints the
/// minimum and median per call.
/// `stack`: the offset of [`at_stack_offset`].
fn run<const NQ: usize, const NV: usize>(robot: &str, fs: [(&str, Timed<NQ, NV>); 7], rounds: usize, stack: usize) {
    let st = states::<NQ, NV>(0x5eed);
    let n = fs.len();
    let mut times = vec![Vec::with_capacity(rounds); n];
    at_stack_offset(stack, &mut || {
        for (_, f) in fs {
            for i in 0..20 * CALLS {
                black_box(f(black_box(&st[i & 7])));
            }
        }
        for r in 0..rounds {
            // Alternate the order too, so that no function always follows another.
            for j in 0..n {
                let k = if r % 2 == 0 { j } else { n - 1 - j };
                let f = fs[k].1;
                let t = Instant::now();
                for i in 0..CALLS {
                    black_box(f(black_box(&st[i & 7])));
                }
                times[k].push(t.elapsed().as_nanos() as f64 / CALLS as f64);
            }
        }
    });
    let layout = dynagen_bench::layout();
    println!(
        "dynagen generated, {robot} floating (NQ = {NQ}, NV = {NV}), {rounds} rounds of {CALLS} calls, code layout \
         {layout}, stack offset {stack}"
    );
    for ((name, _), t) in fs.iter().zip(&mut times) {
        t.sort_by(f64::total_cmp);
        println!("dynagen   {name:<20} min {:8.1} ns  median {:8.1} ns", t[0], t[t.len() / 2]);
    }
}

/// Runs `f` with `B` bytes of this function's frame between it and the
/// caller's.
#[inline(never)]
fn deeper<const B: usize>(f: &mut dyn FnMut()) {
    let mut pad = core::mem::MaybeUninit::<[u8; B]>::uninit();
    black_box(&mut pad);
    f();
    black_box(&mut pad);
}

/// Runs `f` `bytes` deeper in the stack (a multiple of 16 below 4096: the
/// positions within a page).
fn at_stack_offset(bytes: usize, f: &mut dyn FnMut()) {
    assert!(bytes < 4096 && bytes.is_multiple_of(16), "DYNAGEN_BENCH_STACK={bytes}: a multiple of 16 below 4096");
    // The page's 256-byte blocks, then 16-byte steps within one.
    macro_rules! offsets {
        ($x:expr, $unit:literal, $inner:expr; $($k:literal)*) => {
            match $x {
                $($k => deeper::<{ $k * $unit }>($inner),)*
                _ => unreachable!("checked above"),
            }
        };
    }
    let fine = |f: &mut dyn FnMut()| offsets!((bytes % 256) / 16, 16, f; 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
    offsets!(bytes / 256, 256, &mut || fine(f); 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15)
}

/// The cold sweep's buffer: 8 MiB, more than any core's L2.
const SWEEP: usize = 8 << 20;

/// Writes one byte in every 64-byte line of `buf`: evicts what the core's
/// caches held (the shared L3 keeps it).
#[inline(never)]
fn sweep(buf: &mut [u8]) {
    for i in (0..buf.len()).step_by(64) {
        buf[i] = buf[i].wrapping_add(1);
    }
    black_box(buf);
}

/// Times `fs` cold (see the module documentation): `samples` calls each, the
/// functions in alternating order, and prints the median and tenth
/// percentile per call.
/// `stack`: the offset of [`at_stack_offset`].
fn cold<const NQ: usize, const NV: usize>(robot: &str, fs: [(&str, Timed<NQ, NV>); 7], samples: usize, stack: usize) {
    fn empty<const NQ: usize, const NV: usize>(_: &State<NQ, NV>) -> f64 {
        0.0
    }
    let st = states::<NQ, NV>(0x5eed);
    let mut all: Vec<(&str, Timed<NQ, NV>)> = fs.to_vec();
    all.push(("(empty: the timer)", empty::<NQ, NV>));
    let n = all.len();
    let mut buf = vec![0u8; SWEEP];
    let mut times = vec![Vec::with_capacity(samples); n];
    at_stack_offset(stack, &mut || {
        for r in 0..samples {
            for j in 0..n {
                let k = if r % 2 == 0 { j } else { n - 1 - j };
                sweep(&mut buf);
                let s = black_box(&st[r & 7]);
                let t = Instant::now();
                black_box((all[k].1)(s));
                times[k].push(t.elapsed().as_nanos() as f64);
            }
        }
    });
    println!("dynagen generated, {robot} floating, cold: {samples} calls each, each after an 8 MiB sweep");
    for ((name, _), t) in all.iter().zip(&mut times) {
        t.sort_by(f64::total_cmp);
        println!("dynagen   {name:<20} cold median {:8.1} ns  p10 {:8.1} ns", t[t.len() / 2], t[t.len() / 10]);
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let rounds: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(200);
    let robot = args.next().filter(|r| r != "all");
    let samples: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1000);
    let wants = |name: &str| robot.as_deref().is_none_or(|r| r == name);
    let stack = std::env::var("DYNAGEN_BENCH_STACK")
        .map_or(0, |v| v.parse().unwrap_or_else(|_| panic!("DYNAGEN_BENCH_STACK={v}: a number of bytes")));
    if wants("quadruped12") {
        let fs = timed!(dynagen_bench::quadruped12_floating, dynagen_bench::quadruped12_floating_unrolled);
        run("quadruped12", fs, rounds, stack);
        if samples > 0 {
            cold("quadruped12", fs, samples, stack);
        }
    }
    if wants("humanoid32") {
        let fs = timed!(dynagen_bench::humanoid32_floating, dynagen_bench::humanoid32_floating_unrolled);
        run("humanoid32", fs, rounds, stack);
        if samples > 0 {
            cold("humanoid32", fs, samples, stack);
        }
    }
}
