//! How code generation scales: for the Panda and serial chains of 2 to 64
//! joints, the operation counts of τ, M, h, g and forward dynamics, the
//! generation time, the longest emitted function, and (with `--compile`)
//! the time rustc takes to compile the module.
//!
//! ```text
//! cargo run --release -p dynagen --example codegen_scaling -- [--compile] [--debug]
//!     [--per-function] [--split N|none] [--max-joints N] [--out DIR]
//! ```
//!
//! - `--compile`: `rustc --edition 2021 --crate-type lib -O` on each module
//!   (wall-clock seconds; CPU seconds and peak memory from `/usr/bin/time`
//!   if present);
//! - `--debug`: also `rustc … -g` (no optimisation, full debug information:
//!   cargo's `dev` profile), which is where rustc's stack overflows on long
//!   bodies;
//! - `--per-function`: compile a module per function (τ, M, h, g, FD)
//!   instead of the whole module;
//! - `--split N|none`: [`CodegenOptions::split_lets`] (default
//!   [`DEFAULT_SPLIT_LETS`]);
//! - `--max-joints N`: the longest chain (64);
//! - `--derivatives`: the derivatives of the dynamics instead
//!   (`inverse_dynamics_derivatives`, `forward_dynamics_derivatives`,
//!   `mass_matrix_inverse`; the counts of the formulation each keeps);
//! - `--runtime N`: instead of the table, the run time of the functions of
//!   the `N`-joint chain emitted whole and split (a harness compiled with
//!   `rustc -O` that includes both modules; best of 31 rounds alternating
//!   whole and split, ns per call);
//! - `--out DIR`: where the modules are written (a folder under the system's
//!   temporary folder).
//!
//! The generation time is the best of several runs (one run from 30
//! joints on), in milliseconds of wall-clock time and of the thread's CPU
//! time (which a loaded machine disturbs less), in the process that runs
//! this example: build it in release mode. The chain is the one of
//! `tests/codegen_growth.rs` (skewed placements, full inertias, axes
//! cycling through z, y, x). Results: `docs/performance.md`.

#[path = "../tests/support/skewed_chain.rs"]
mod skewed_chain;

use dynagen::codegen::{generate, CodegenOptions, ForwardDynamicsMethod, Function, DEFAULT_SPLIT_LETS};
use dynagen::Model;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

struct Args {
    compile: bool,
    debug: bool,
    per_function: bool,
    split: Option<usize>,
    max_joints: usize,
    derivatives: bool,
    runtime: Option<usize>,
    out: PathBuf,
}

fn args() -> Args {
    let mut a = Args {
        compile: false,
        debug: false,
        per_function: false,
        split: Some(DEFAULT_SPLIT_LETS),
        max_joints: 64,
        derivatives: false,
        runtime: None,
        out: std::env::temp_dir().join("dynagen_codegen_scaling"),
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--compile" => a.compile = true,
            "--debug" => a.debug = true,
            "--per-function" => a.per_function = true,
            "--derivatives" => a.derivatives = true,
            "--split" => {
                let v = it.next().expect("--split N|none");
                a.split = if v == "none" { None } else { Some(v.parse().expect("--split N|none")) };
            }
            "--max-joints" => a.max_joints = it.next().and_then(|v| v.parse().ok()).expect("--max-joints N"),
            "--runtime" => a.runtime = Some(it.next().and_then(|v| v.parse().ok()).expect("--runtime N")),
            "--out" => a.out = it.next().expect("--out DIR").into(),
            other => panic!("unknown argument {other} (see the example's documentation)"),
        }
    }
    a
}

/// The number of `let`s of the longest function of `source`, and how many
/// functions are parts of split ones.
fn longest_and_parts(source: &str) -> (usize, usize) {
    let (mut longest, mut current, mut parts) = (0, 0, 0);
    for line in source.lines() {
        if line.starts_with("pub fn ") || line.starts_with("fn ") {
            current = 0;
            parts += usize::from(line.contains("_part"));
        } else if line.starts_with("    let ") {
            current += 1;
            longest = longest.max(current);
        }
    }
    (longest, parts)
}

/// The CPU time of this thread so far, in ms (Linux: the first field of
/// `/proc/thread-self/schedstat`, in ns; `None` elsewhere).
fn thread_cpu_ms() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse::<f64>().ok().map(|ns| ns * 1e-6)
}

/// `rustc` on `file`: wall-clock seconds, and CPU seconds (user + system,
/// all threads) and peak memory if `/usr/bin/time` is there (CPU time
/// varies less than wall-clock time on a loaded machine), or that it failed.
fn compile(file: &Path, flags: &[&str]) -> String {
    let out = file.with_extension("rlib");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let timer = Path::new("/usr/bin/time").exists();
    let mut cmd = if timer {
        let mut c = Command::new("/usr/bin/time");
        c.args(["-f", "%U %S %M", &rustc]);
        c
    } else {
        Command::new(&rustc)
    };
    cmd.args(["--edition", "2021", "--crate-type", "lib"]).args(flags).arg(file).arg("-o").arg(&out);
    let t = Instant::now();
    let result = cmd.output().expect("running rustc");
    let secs = t.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&result.stderr);
    let cpu_mem = if timer {
        stderr.lines().last().and_then(|l| {
            let v: Vec<f64> = l.split_whitespace().filter_map(|x| x.parse().ok()).collect();
            (v.len() == 3).then(|| format!(" (cpu {:.2} s, {:.0} MB)", v[0] + v[1], v[2] / 1024.0))
        })
    } else {
        None
    };
    let _ = std::fs::remove_file(&out);
    if result.status.success() {
        format!("{secs:.2} s{}", cpu_mem.unwrap_or_default())
    } else if stderr.contains("overflowed its stack") {
        format!("STACK OVERFLOW after {secs:.1} s")
    } else {
        format!("FAILED after {secs:.1} s")
    }
}

/// The harness of `--runtime`: both modules included, each function timed
/// on the same 16 states, whole and split alternately.
const HARNESS: &str = r#"
mod whole { include!("whole.rs"); }
mod split { include!("split.rs"); }
use std::hint::black_box;
const N: usize = whole::DOF;
fn time(f: &mut impl FnMut(usize) -> f64) -> f64 {
    let t = std::time::Instant::now();
    let mut acc = 0.0;
    for i in 0..2000 { acc += f(i % 16); }
    black_box(acc);
    t.elapsed().as_secs_f64() / 2000.0 * 1e9
}
// The best of 31 rounds each, the two alternating round by round.
fn best2(mut a: impl FnMut(usize) -> f64, mut b: impl FnMut(usize) -> f64) -> (f64, f64) {
    let (mut ta, mut tb) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..31 {
        ta = ta.min(time(&mut a));
        tb = tb.min(time(&mut b));
    }
    (ta, tb)
}
fn main() {
    let st = |k: usize, a: f64| -> [f64; N] { core::array::from_fn(|i| a * (1.7 * (i + 3 * k) as f64 + 0.3).sin()) };
    let q: Vec<[f64; N]> = (0..16).map(|k| st(k, 2.0)).collect();
    let qd: Vec<[f64; N]> = (0..16).map(|k| st(k + 16, 3.0)).collect();
    let qdd: Vec<[f64; N]> = (0..16).map(|k| st(k + 32, 4.0)).collect();
    macro_rules! pair {
        ($label:literal, $f:ident, $($arg:ident),*) => {{
            let (w, s) = best2(
                |i| whole::$f($(black_box(&$arg[i])),*).as_flattened()[0],
                |i| split::$f($(black_box(&$arg[i])),*).as_flattened()[0],
            );
            println!("{:>6} whole {w:>10.0} ns, split {s:>10.0} ns ({:+.1} %)", $label, (s / w - 1.0) * 100.0);
        }};
    }
    trait Flat { fn as_flattened(&self) -> &[f64]; }
    impl Flat for [f64; N] { fn as_flattened(&self) -> &[f64] { self } }
    pair!("tau", inverse_dynamics, q, qd, qdd);
    pair!("M", mass_matrix, q);
    pair!("h", bias_forces, q, qd);
    pair!("g", gravity_torques, q);
    pair!("FD", forward_dynamics, q, qd, qdd);
}
"#;

/// `--runtime n`: times the `n`-joint chain's functions whole and split.
fn runtime(n: usize, a: &Args) {
    let model = skewed_chain::skewed_chain(n);
    let dir = a.out.join(format!("runtime{n}"));
    std::fs::create_dir_all(&dir).expect("creating the folder");
    for (file, split) in [("whole.rs", None), ("split.rs", a.split)] {
        let m = generate(&model, &CodegenOptions::default().split_lets(split)).expect("generating");
        let (lets, parts) = longest_and_parts(&m.source);
        println!("{file}: longest function {lets} lets, {parts} parts");
        std::fs::write(dir.join(file), m.source).expect("writing");
    }
    std::fs::write(dir.join("main.rs"), HARNESS).expect("writing");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let exe = dir.join("harness");
    let status = Command::new(rustc)
        .args(["--edition", "2021", "-O", "-A", "dead_code", "-o"])
        .arg(&exe)
        .arg(dir.join("main.rs"))
        .status()
        .expect("running rustc");
    assert!(status.success(), "compiling the harness");
    let status = Command::new(&exe).status().expect("running the harness");
    assert!(status.success());
}

fn main() {
    let a = args();
    std::fs::create_dir_all(&a.out).expect("creating the output folder");
    if let Some(n) = a.runtime {
        runtime(n, &a);
        return;
    }
    let panda = Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/panda.urdf")).expect("the Panda");
    let mut models = vec![("panda".to_string(), panda)];
    for n in [2usize, 4, 8, 16, 30, 32, 64].into_iter().filter(|&n| n <= a.max_joints) {
        models.push((format!("chain{n}"), skewed_chain::skewed_chain(n)));
    }
    let derivatives =
        [Function::InverseDynamicsDerivatives, Function::ForwardDynamicsDerivatives, Function::MassMatrixInverse];
    let mut options = CodegenOptions::default().split_lets(a.split);
    if a.derivatives {
        options = options.functions(derivatives.clone());
    }
    println!(
        "split_lets {:?}; operation counts; generation ms, best of 5 runs (1 from 30 joints), wall-clock and \
         CPU time of the thread; KB of source; lets: the longest function's; parts: private parts of split functions",
        a.split
    );
    let heads = if a.derivatives { ["dtau", "dqdd", "Minv", "", ""] } else { ["tau", "M", "h", "g", "FD"] };
    println!(
        "{:>8} {:>6} {:>6} {:>6} {:>6} {:>7} {:>9} {:>9} {:>7} {:>6} {:>5}",
        "model", heads[0], heads[1], heads[2], heads[3], heads[4], "gen wall", "gen cpu", "KB", "lets", "parts"
    );
    for (name, model) in &models {
        let runs = if model.dof() >= 30 { 1 } else { 5 };
        let (mut best, mut best_cpu) = (f64::INFINITY, f64::INFINITY);
        let mut module = None;
        for _ in 0..runs {
            let (t, cpu) = (Instant::now(), thread_cpu_ms());
            let m = generate(model, &options).expect("generating");
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            best_cpu = best_cpu.min(thread_cpu_ms().zip(cpu).map_or(f64::NAN, |(b, a)| b - a));
            module = Some(m);
        }
        let module = module.expect("one run");
        let count = |k: Function, method: Option<ForwardDynamicsMethod>| {
            let f = module.functions.iter().find(|f| f.function == k && f.method == method && f.emitted);
            f.map_or(0, |f| f.op_count.total())
        };
        let counts = if a.derivatives {
            [
                count(derivatives[0].clone(), None),
                count(derivatives[1].clone(), None),
                count(derivatives[2].clone(), None),
                0,
                0,
            ]
        } else {
            [
                count(Function::InverseDynamics, None),
                count(Function::MassMatrix, None),
                count(Function::BiasForces, None),
                count(Function::GravityTorques, None),
                module
                    .functions
                    .iter()
                    .find(|f| f.method == Some(ForwardDynamicsMethod::Aba))
                    .map_or(0, |f| f.op_count.total()),
            ]
        };
        let (lets, parts) = longest_and_parts(&module.source);
        println!(
            "{name:>8} {:>6} {:>6} {:>6} {:>6} {:>7} {best:>9.1} {best_cpu:>9.1} {:>7} {lets:>6} {parts:>5}",
            counts[0],
            counts[1],
            counts[2],
            counts[3],
            counts[4],
            module.source.len() / 1024,
        );
        if !a.compile {
            continue;
        }
        let mut modules = Vec::new();
        if a.per_function && !a.derivatives {
            for (label, function) in [
                ("tau", Function::InverseDynamics),
                ("M", Function::MassMatrix),
                ("h", Function::BiasForces),
                ("g", Function::GravityTorques),
                ("FD", Function::ForwardDynamics),
            ] {
                let m = generate(model, &options.clone().functions([function])).expect("generating");
                modules.push((label, m.source));
            }
        } else {
            modules.push(("module", module.source));
        }
        for (label, source) in modules {
            let file = a.out.join(format!("{name}_{label}.rs"));
            std::fs::write(&file, &source).expect("writing the module");
            let lets = longest_and_parts(&source).0;
            let release = compile(&file, &["-O"]);
            let debug = if a.debug { format!(", -g: {}", compile(&file, &["-g"])) } else { String::new() };
            println!("{:>8}   {label:<6} rustc -O: {release}{debug} (longest function {lets} lets)", "");
        }
    }
}
