//! Benchmarks of the generic `f64` solver on the bundled UR5 (6 DoF) and
//! Panda (7 DoF arm + 2 prismatic fingers = 9 DoF).
//!
//! Each benchmark runs the allocation-free path (`algorithms::*` with a
//! preallocated [`Workspace`]) on a few fixed pseudo-random states, cycled
//! call after call so that the branch predictor does not learn one state.
//!
//! Run with `cargo bench --bench generic -- --warm-up-time 1 --measurement-time 3`;
//! results are in `docs/performance.md` (how to run it: `benches/README.md`).

// The integration tests' support module: its xorshift generator.
#[path = "../tests/support/mod.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion};
use dynagen::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use std::hint::black_box;
use std::path::Path;
use support::Rng;

/// How many states are cycled through.
const STATES: usize = 16;

/// One input state: q, q̇, q̈ (also used as τ for forward dynamics).
struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
}

fn states(n: usize) -> Vec<State> {
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    (0..STATES).map(|_| State { q: rng.vec(n, 3.0), qd: rng.vec(n, 2.0), qdd: rng.vec(n, 5.0) }).collect()
}

fn load(file: &str) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("robots").join(file);
    Model::from_urdf_file(&path).unwrap_or_else(|e| panic!("cannot load {}: {e}", path.display()))
}

fn bench_robot(c: &mut Criterion, name: &str, file: &str) {
    let model = load(file);
    let n = model.dof();
    let st = states(n);
    let g = Vec3(model.gravity.0);
    let mut ws = Workspace::<f64>::new(&model);
    let mut out = vec![0.0; n];
    let mut m = vec![0.0; n * n];
    let mut group = c.benchmark_group(name);
    let mut k = 0usize;
    let mut next = || {
        k = (k + 1) % STATES;
        &st[k]
    };

    group.bench_function("rnea", |b| {
        b.iter(|| {
            let s = next();
            rnea::rnea(
                &model,
                &mut ws,
                black_box(&s.q),
                Some(black_box(&s.qd)),
                Some(black_box(&s.qdd)),
                Loads::gravity(&g),
                &mut out,
            );
            black_box(&out);
        })
    });
    group.bench_function("bias_forces", |b| {
        b.iter(|| {
            let s = next();
            bias::bias_forces(&model, &mut ws, black_box(&s.q), black_box(&s.qd), Some(&g), &mut out);
            black_box(&out);
        })
    });
    group.bench_function("crba", |b| {
        b.iter(|| {
            let s = next();
            crba::crba(&model, &mut ws, black_box(&s.q), Loads::none(), &mut m);
            black_box(&m);
        })
    });
    group.bench_function("aba", |b| {
        b.iter(|| {
            let s = next();
            aba::aba(
                &model,
                &mut ws,
                black_box(&s.q),
                black_box(&s.qd),
                black_box(&s.qdd),
                Loads::gravity(&g),
                &mut out,
            );
            black_box(&out);
        })
    });
    group.bench_function("forward_dynamics_ldlt", |b| {
        b.iter(|| {
            let s = next();
            forward_dynamics::forward_dynamics_ldlt(
                &model,
                &mut ws,
                black_box(&s.q),
                black_box(&s.qd),
                black_box(&s.qdd),
                Loads::gravity(&g),
                &mut out,
            );
            black_box(&out);
        })
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_robot(c, "ur5", "ur5.urdf");
    bench_robot(c, "panda", "panda.urdf");
}

criterion_group!(generic, benches);
criterion_main!(generic);
