//! The compensated forward dynamics against the generic `f64`
//! articulated-body algorithm, on cancelling states (|q̇| up to 300 rad/s,
//! τ from an `f64` RNEA at a small q̈), interleaved in one run: ABA,
//! compensated (`CompensatedSolver::new`: FMA when the CPU has it),
//! compensated with Dekker's products (`CompensatedSolver::portable`),
//! compensated with one step of refinement, and for the UR5 and the Panda
//! the generated `forward_dynamics` (batched sines and cosines). The robots:
//! the UR5, the Panda and the test robots of `dynagen/tests/file_precision.rs`.
//!
//! Each round runs every variant on the same 8 states, 500 calls each, in
//! turn; the table gives the minimum and the median per call over the
//! rounds, and each variant's times over ABA's in the same rounds.
//!
//! `cargo run --release -p dynagen-bench --example compensated [ROUNDS]`

use dynagen::algorithms::compensated::CompensatedSolver;
use dynagen::algorithms::{aba, rnea, Loads, Workspace};
use dynagen::Model;
use std::hint::black_box;
use std::time::Instant;

const CALLS: usize = 500;

/// (q, q̇, τ): q in ±π, q̇ in ±300, τ = RNEA(q, q̇, q̈) in f64 for q̈ in ±1.
fn states(model: &Model, seed: u64) -> Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let mut next = dynagen_bench::uniform(seed);
    let n = model.dof();
    let mut ws = Workspace::<f64>::new(model);
    let g = model.gravity;
    (0..8)
        .map(|_| {
            let q: Vec<f64> = (0..n).map(|_| 3.0 * next()).collect();
            let qd: Vec<f64> = (0..n).map(|_| 300.0 * next()).collect();
            let qdd: Vec<f64> = (0..n).map(|_| next()).collect();
            let mut tau = vec![0.0; n];
            rnea::rnea(model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut tau);
            (q, qd, tau)
        })
        .collect()
}

/// A variant: runs one call on state `k`, writing q̈.
type Variant<'a> = Box<dyn FnMut(usize, &mut [f64]) + 'a>;

/// A state's vector as the array a generated function takes.
fn array<const N: usize>(x: &[f64]) -> &[f64; N] {
    x.try_into().expect("the robot's joints")
}

fn stats(per_call: &mut [f64]) -> (f64, f64) {
    per_call.sort_by(f64::total_cmp);
    (per_call[0], per_call[per_call.len() / 2])
}

fn main() {
    let rounds: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(200);
    let data = format!("{}/../dynagen/tests/data", env!("CARGO_MANIFEST_DIR"));
    let mut robots: Vec<(String, Model)> = ["ur5", "panda"]
        .iter()
        .map(|r| (r.to_string(), Model::from_urdf_file(dynagen_bench::urdf(r)).expect("bundled robot")))
        .collect();
    for r in ["chain8", "hand", "tiny", "huge", "near_dependent", "dependent"] {
        let path = format!("{data}/precision_{r}.urdf");
        robots.push((r.to_string(), Model::from_urdf_file(&path).expect("test robot")));
    }
    println!("FMA detected: {}", CompensatedSolver::new(&robots[0].1).uses_fma());
    println!(
        "| robot | n | ABA f64 min / median [ns] | compensated | ratio | Dekker's products | ratio \
         | compensated + 1 refinement | ratio | generated ABA | ratio |"
    );
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (name, model) in &robots {
        let st = states(model, 0x9e37_79b9);
        let g = model.gravity;
        let n = model.dof();
        let mut ws = Workspace::<f64>::new(model);
        let mut comp = CompensatedSolver::new(model);
        let mut portable = CompensatedSolver::portable(model);
        let mut refined = CompensatedSolver::new(model);
        refined.set_refinement(1);
        let mut variants: Vec<Variant> = vec![
            Box::new(|k, out| {
                let (q, qd, tau) = &st[k];
                aba::aba(model, &mut ws, q, qd, tau, Loads::gravity(&g), out)
            }),
            Box::new(|k, out| {
                let (q, qd, tau) = &st[k];
                comp.solve(model, q, qd, tau, Loads::gravity(&g), out)
            }),
            Box::new(|k, out| {
                let (q, qd, tau) = &st[k];
                portable.solve(model, q, qd, tau, Loads::gravity(&g), out)
            }),
            Box::new(|k, out| {
                let (q, qd, tau) = &st[k];
                refined.solve(model, q, qd, tau, Loads::gravity(&g), out)
            }),
        ];
        // The generated forward dynamics of a bundled robot's default module.
        macro_rules! generated {
            ($module:ident) => {
                Some(Box::new(|k, out: &mut [f64]| {
                    let (q, qd, tau) = &st[k];
                    out.copy_from_slice(&dynagen_bench::$module::forward_dynamics(array(q), array(qd), array(tau)));
                }))
            };
        }
        let generated: Option<Variant> = match name.as_str() {
            "ur5" => generated!(ur5_batched),
            "panda" => generated!(panda_batched),
            _ => None,
        };
        variants.extend(generated);
        let mut times = vec![Vec::with_capacity(rounds); variants.len()];
        let mut out = vec![0.0; n];
        for _ in 0..rounds {
            for (v, t) in variants.iter_mut().zip(&mut times) {
                let start = Instant::now();
                for c in 0..CALLS {
                    v(c % st.len(), black_box(&mut out));
                }
                t.push(start.elapsed().as_secs_f64() * 1e9 / CALLS as f64);
            }
        }
        let s: Vec<(f64, f64)> = times.iter_mut().map(|t| stats(t)).collect();
        let cell = |k: usize| -> String {
            s.get(k).map_or("".into(), |(min, med)| {
                format!("{min:.0} / {med:.0} | {:.2}× / {:.2}×", min / s[0].0, med / s[0].1)
            })
        };
        println!(
            "| {name} | {n} | {:.0} / {:.0} | {} | {} | {} | {} |",
            s[0].0,
            s[0].1,
            cell(1),
            cell(2),
            cell(3),
            if s.len() > 4 { cell(4) } else { " | ".into() }
        );
    }
}
