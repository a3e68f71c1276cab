//! Batch timing of the generic `f64` solver, with the statistic of
//! `scripts/reference/pinocchio_bench.cpp` (Pinocchio's C++), so that the two
//! can be compared when run one after the other on the same machine.
//!
//! Each algorithm is called in 300 batches of 1000 calls (after 20 batches of
//! warm-up), cycling through 16 fixed pseudo-random states; the time per call
//! of each batch is recorded and the minimum and the median over the batches
//! are printed, in ns per call. The minimum is the batch that ran with the
//! least interference from other processes, the steadier number on a shared
//! machine.
//!
//! ```sh
//! cargo run --release -p dynagen --example batch_timing [ALGORITHM ...]
//! ```
//!
//! `ALGORITHM` filters by name (`rnea`, `bias`, `crba`, `aba`, `ldlt`), the
//! environment variable `ROBOT` (`ur5`, `panda`, `quadruped12` on a fixed
//! base, `quadruped12-floating` with its trunk floating: NQ = 19, NV = 18,
//! random unit quaternions) selects one robot, and
//! `CALLS=n` makes n calls of each algorithm without timing (for counting
//! instructions under `valgrind --tool=callgrind`).

// The integration tests' support module: its xorshift generator.
#[path = "../tests/support/mod.rs"]
mod support;

use dynagen::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;
use support::Rng;

const STATES: usize = 16;
const BATCH: usize = 1000;
const BATCHES: usize = 300;

/// "min/median" ns per call of `f(state index)`.
fn time(calls: Option<usize>, mut f: impl FnMut(usize)) -> String {
    if let Some(c) = calls {
        (0..c).for_each(|k| f(k % STATES));
        return String::new();
    }
    (0..20 * BATCH).for_each(|k| f(k % STATES));
    let mut per_call: Vec<f64> = (0..BATCHES)
        .map(|_| {
            let t = Instant::now();
            (0..BATCH).for_each(|k| f(k % STATES));
            t.elapsed().as_secs_f64() / BATCH as f64 * 1e9
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    format!("{:5.0}/{:5.0}", per_call[0], per_call[BATCHES / 2])
}

fn main() {
    let filter: Vec<String> = std::env::args().skip(1).collect();
    let calls: Option<usize> = std::env::var("CALLS").ok().map(|c| c.parse().expect("CALLS must be a number"));
    let only = std::env::var("ROBOT").ok();
    println!("dynagen generic f64 solver, ns per call: min/median over {BATCHES} batches of {BATCH} calls");
    for robot in ["ur5", "panda", "quadruped12", "quadruped12-floating"] {
        if only.as_ref().is_some_and(|r| r != robot) {
            continue;
        }
        let file = robot.trim_end_matches("-floating");
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("robots").join(format!("{file}.urdf"));
        let model = Model::from_urdf_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let model = if robot.ends_with("-floating") { model.with_floating_base() } else { model };
        let (nq, n) = (model.nq(), model.nv());
        let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
        let states: Vec<[Vec<f64>; 3]> = (0..STATES)
            .map(|_| {
                let mut q = rng.vec(nq, 3.0);
                if model.is_floating() {
                    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
                    q[3..7].iter_mut().for_each(|x| *x /= norm);
                }
                [q, rng.vec(n, 2.0), rng.vec(n, 5.0)]
            })
            .collect();
        let g = Vec3(model.gravity.0);
        let mut ws = Workspace::<f64>::new(&model);
        let (mut out, mut m) = (vec![0.0; n], vec![0.0; n * n]);
        let want = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()));
        let mut line = format!("{robot:6} nv={n}");
        if want("rnea") {
            let t = time(calls, |k| {
                let [q, qd, qdd] = &states[k];
                rnea::rnea(&model, &mut ws, black_box(q), Some(qd), Some(qdd), Loads::gravity(&g), &mut out);
                black_box(&out);
            });
            line += &format!("  rnea {t}");
        }
        if want("bias") {
            let t = time(calls, |k| {
                let [q, qd, _] = &states[k];
                bias::bias_forces(&model, &mut ws, black_box(q), qd, Some(&g), &mut out);
                black_box(&out);
            });
            line += &format!("  bias {t}");
        }
        if want("crba") {
            let t = time(calls, |k| {
                crba::crba(&model, &mut ws, black_box(&states[k][0]), Loads::none(), &mut m);
                black_box(&m);
            });
            line += &format!("  crba {t}");
        }
        if want("aba") {
            let t = time(calls, |k| {
                let [q, qd, tau] = &states[k];
                aba::aba(&model, &mut ws, black_box(q), qd, tau, Loads::gravity(&g), &mut out);
                black_box(&out);
            });
            line += &format!("  aba {t}");
        }
        if want("ldlt") {
            let t = time(calls, |k| {
                let [q, qd, tau] = &states[k];
                forward_dynamics::forward_dynamics_ldlt(
                    &model,
                    &mut ws,
                    black_box(q),
                    qd,
                    tau,
                    Loads::gravity(&g),
                    &mut out,
                );
                black_box(&out);
            });
            line += &format!("  ldlt {t}");
        }
        println!("{line}");
    }
}
