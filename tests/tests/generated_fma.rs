//! Fused multiply-adds in generated code (`CodegenOptions::fma`, on by
//! default), on both sides of the `cfg`, and the run-time choice of the
//! AVX2 and FMA copies (`CodegenOptions::runtime_dispatch`, on by default):
//!
//! - this test binary's own build (no target-cpu flags, so no `fma` target
//!   feature on x86-64): the UR5 module of `build.rs` without dispatch gives,
//!   bit for bit, what the traced functions give evaluated operation by
//!   operation without fusion (`Function::eval`), i.e. what the code gave
//!   before `fma(a, b, c)` was emitted; the same module with dispatch (the
//!   default) gives that where the processor lacks AVX2 or FMA, and where it
//!   has both (this CI machine) the fused bits (`Function::eval_fused`);
//! - the fused path: when the host has FMA, the same module is compiled by
//!   `rustc -O -C target-feature=+fma` and run. Its results must equal, bit
//!   for bit, the traced functions evaluated with one `mul_add` per fused
//!   sum (`Function::eval_fused`), differ from the unfused ones (so the
//!   instructions really are fused: the check cannot pass by compiling
//!   `a * b + c`), and stay within 1e-12 of the generic solver. The same
//!   for an `f32` module (`fmaf`), within 1e-5. The module's sine-cosine
//!   kernel, whose polynomials are fused there too, must stay within 1 ulp
//!   (of f64; of f32 for `sin_cos_array_f32`) against double-double values,
//!   and its vector path (AVX2 too, where the host has it) must give the
//!   one-angle kernel's bits. Where the host has AVX2 and FMA, the same
//!   program is also compiled by `rustc -O` without target features: its
//!   functions then pick their AVX-512 copies at run time where the host
//!   has AVX-512 (F, VL, DQ), else their AVX2 and FMA copies, and must
//!   print the same bits as the `+fma,+avx2` build, every line; and once
//!   more with the module's AVX-512 check answering no, so that the AVX2
//!   and FMA copies run on an AVX-512 host too.

use approx::abs_diff_eq;
use dynagen::codegen::{generate, CodegenOptions, Function as Kind, GeneratedFunction, ScalarType};
use dynagen::symbolic::Traced;
use dynagen::{DoubleDouble, Robot, Scalar};
use dynagen_tests::{bundled_model, bundled_robot, rel_err, scale, Rng};
use nalgebra::DVector;
use std::fmt::Write;

#[allow(dead_code)]
mod ur5 {
    include!(concat!(env!("OUT_DIR"), "/ur5_f64.rs"));
}

#[allow(dead_code)]
mod ur5_baseline {
    include!(concat!(env!("OUT_DIR"), "/ur5_f64_baseline.rs"));
}

const N: usize = 6;

/// Random states: (s, c, q, qd, qdd, tau), the sines and cosines by std.
struct State {
    s: [f64; N],
    c: [f64; N],
    q: [f64; N],
    qd: [f64; N],
    qdd: [f64; N],
    tau: [f64; N],
}

fn states(count: usize, seed: u64) -> Vec<State> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| {
            let mut arr = |a: f64| -> [f64; N] { core::array::from_fn(|_| rng.range(-a, a)) };
            let (q, qd, qdd, tau) = (arr(3.0), arr(2.0), arr(5.0), arr(30.0));
            State { s: q.map(f64::sin), c: q.map(f64::cos), q, qd, qdd, tau }
        })
        .collect()
}

/// The inputs of an emitted body `NAME_sc` at state `x`.
fn inputs(x: &State) -> Vec<(&'static str, &[f64])> {
    vec![("s", &x.s), ("c", &x.c), ("q", &x.q), ("qd", &x.qd), ("qdd", &x.qdd), ("tau", &x.tau)]
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

fn emitted(options: &CodegenOptions) -> Vec<GeneratedFunction> {
    let module = generate(&bundled_model("ur5"), options).unwrap();
    module.functions.into_iter().filter(|f| f.emitted).collect()
}

/// What the generic solver gives for `kind` at `x` (M row-major).
fn generic(robot: &mut Robot, kind: &Kind, x: &State) -> Vec<f64> {
    let v = |a: &[f64; N]| DVector::from_column_slice(a);
    let (q, qd) = (v(&x.q), v(&x.qd));
    match kind {
        Kind::InverseDynamics => robot.inverse_dynamics(&q, &qd, &v(&x.qdd)).unwrap().as_slice().to_vec(),
        Kind::MassMatrix => robot.mass_matrix(&q).unwrap().transpose().as_slice().to_vec(),
        Kind::BiasForces => robot.bias_forces(&q, &qd).unwrap().as_slice().to_vec(),
        Kind::GravityTorques => robot.gravity_torques(&q).unwrap().as_slice().to_vec(),
        Kind::ForwardDynamics => robot.forward_dynamics(&q, &qd, &v(&x.tau)).unwrap().as_slice().to_vec(),
        other => panic!("{other:?} is not in the UR5 module"),
    }
}

/// The body `NAME_sc` of this test binary's UR5 module at `x`, with run-time
/// dispatch (`ur5`) or without (`ur5_baseline`).
macro_rules! compiled_here {
    ($module:ident, $kind:expr, $x:expr) => {{
        let (s, c, qd, qdd, tau) = (&$x.s, &$x.c, &$x.qd, &$x.qdd, &$x.tau);
        match $kind {
            Kind::InverseDynamics => $module::inverse_dynamics_sc(s, c, qd, qdd).to_vec(),
            Kind::MassMatrix => $module::mass_matrix_sc(s, c).concat(),
            Kind::BiasForces => $module::bias_forces_sc(s, c, qd).to_vec(),
            Kind::GravityTorques => $module::gravity_torques_sc(s, c).to_vec(),
            Kind::ForwardDynamics => $module::forward_dynamics_sc(s, c, qd, tau).to_vec(),
            other => panic!("{other:?} is not in the UR5 module"),
        }
    }};
}

/// Whether this machine has AVX2 and FMA (what the run-time dispatch asks).
fn host_has_avx2_and_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
    #[allow(unreachable_code)]
    false
}

#[test]
fn this_build_gives_the_bits_of_its_target_or_of_its_processor() {
    let functions = emitted(&CodegenOptions::default());
    assert_eq!(functions.len(), 5);
    let fused_target = cfg!(any(
        all(target_arch = "x86_64", target_feature = "fma"),
        all(target_arch = "aarch64", target_feature = "neon")
    ));
    // With dispatch, an x86-64 build runs the AVX2 and FMA copies where the processor has both.
    let fused_dispatched = fused_target || (cfg!(target_arch = "x86_64") && host_has_avx2_and_fma());
    if !fused_dispatched {
        eprintln!("this machine lacks AVX2 or FMA: the dispatched module runs its baseline copy here");
    }
    let mut differ = 0;
    for x in &states(200, 71) {
        for f in &functions {
            let body = &f.sin_cos_inputs.function;
            let fused = body.eval_fused(&body.fusion(), &inputs(x)).unwrap();
            let unfused = body.eval(&inputs(x)).unwrap();
            let label = f.label();
            let want = if fused_dispatched { &fused } else { &unfused };
            assert_eq!(bits(&compiled_here!(ur5, &f.function, x)), bits(want), "{label}, dispatched");
            let want = if fused_target { &fused } else { &unfused };
            assert_eq!(bits(&compiled_here!(ur5_baseline, &f.function, x)), bits(want), "{label}, no dispatch");
            differ += usize::from(bits(&fused) != bits(&unfused));
        }
    }
    // Most results differ between fused and unfused: the checks above tell them apart.
    assert!(differ > 500, "{differ} of 1000");
}

#[test]
fn without_fma_nothing_is_fused() {
    let module = generate(&bundled_model("ur5"), &CodegenOptions::default().fma(false)).unwrap();
    let bodies = |src: &str| src.split("// The sine and cosine of joint angles").next().unwrap().to_string();
    assert_eq!(bodies(&module.source).lines().filter(|l| is_fused_let(l)).count(), 0, "no body calls fma");
    assert!(on_source_has_fused_lets());
    assert!(module.source.contains("// Fused multiply-adds: off"));
    assert!(module.functions.iter().all(|f| f.op_count.fused == 0 && f.op_count.fp_ops() == f.op_count.arithmetic()));
    let on = generate(&bundled_model("ur5"), &CodegenOptions::default()).unwrap();
    for (a, b) in module.functions.iter().zip(&on.functions) {
        // The same traced operations, counted the same; fused on top.
        assert_eq!((a.op_count.add, a.op_count.mul), (b.op_count.add, b.op_count.mul));
        assert!(b.op_count.fused > 0 && b.op_count.fp_ops() < b.op_count.arithmetic());
    }
}

/// A line `let tK = fma(…);` (`I::fma(…)` in a dispatched body) of a body.
fn is_fused_let(line: &str) -> bool {
    let rest = line.trim_start().strip_prefix("let t").unwrap_or_default();
    rest.starts_with(|c: char| c.is_ascii_digit()) && (rest.contains(" = fma(") || rest.contains(" = I::fma("))
}

fn on_source_has_fused_lets() -> bool {
    let on = generate(&bundled_model("ur5"), &CodegenOptions::default()).unwrap();
    on.source.lines().any(is_fused_let)
}

/// Whether this machine runs fused multiply-adds.
fn host_has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::is_x86_feature_detected!("fma");
    #[cfg(target_arch = "aarch64")]
    return true;
    #[allow(unreachable_code)]
    false
}

/// The functions of an x86-64 assembly listing whose names contain
/// `suffix` (`_avx2_fma`, `_avx512`: the copies of the run-time dispatch),
/// with their code.
fn dispatch_copies(asm: &str, suffix: &str) -> Vec<(String, String)> {
    let mut copies: Vec<(String, String)> = Vec::new();
    let mut inside = false;
    for line in asm.lines() {
        let label = !line.starts_with(['.', ' ', '\t', '#']) && line.ends_with(':');
        if label {
            // Not the processor checks (`ask_cpu_for_avx512`, `has_avx512`).
            inside = line.contains(suffix) && !line.contains("ask_cpu") && !line.contains("has_avx");
            if inside {
                copies.push((line.trim_end_matches(':').to_string(), String::new()));
            }
        } else if inside {
            let code = &mut copies.last_mut().unwrap().1;
            code.push_str(line);
            code.push('\n');
        }
    }
    copies
}

fn array_literal(rows: impl Iterator<Item = [f64; N]>) -> String {
    let rows: Vec<String> = rows.map(|r| format!("{r:?}")).collect();
    format!("[{}]", rows.join(", "))
}

/// The kernel's test angles: random ones on a few scales (the fast path)
/// and the doubles nearest to multiples of π/2 (the slow path).
fn angles() -> Vec<f64> {
    let mut rng = Rng::new(73);
    let mut xs: Vec<f64> = [4.0, 100.0, 1e5].iter().flat_map(|&a| (0..600).map(move |_| a)).collect();
    for x in &mut xs {
        *x = rng.range(-*x, *x);
    }
    let half_pi = DoubleDouble::new(core::f64::consts::FRAC_PI_2, 6.123233995736766e-17);
    xs.extend((1..=200).map(|k| half_pi.mul_f64(k as f64).to_f64()));
    xs
}

/// |got − exact| in ulps of the exact value's binade.
fn ulps(got: f64, exact: DoubleDouble) -> f64 {
    let err = (DoubleDouble::from(got) - exact).to_f64().abs();
    let ulp = f64::from_bits(exact.hi.abs().to_bits() & 0x7ff0_0000_0000_0000) * f64::EPSILON;
    err / ulp.max(f64::from_bits(1))
}

/// A program that prints, for every state and every body of the module
/// `m64` (f64) and `m32` (f32), a line `k name bits…`, then the sines and
/// cosines of `angles` by both kernels.
fn program(xs: &[State], f64_fns: &[GeneratedFunction], f32_fns: &[GeneratedFunction], angles: &[f64]) -> String {
    let mut p = String::from(
        "#![allow(dead_code)]\nmod m64 { include!(\"ur5.rs\"); }\nmod m32 { include!(\"ur5_f32.rs\"); }\n",
    );
    for (name, pick) in [
        ("S", (|x: &State| x.s) as fn(&State) -> [f64; N]),
        ("C", |x| x.c),
        ("QD", |x| x.qd),
        ("QDD", |x| x.qdd),
        ("TAU", |x| x.tau),
    ] {
        let _ = writeln!(p, "const {name}: [[f64; {N}]; {}] = {};", xs.len(), array_literal(xs.iter().map(pick)));
    }
    p.push_str("fn out<T: core::fmt::LowerHex>(k: usize, name: &str, x: &[T]) {\n");
    p.push_str("    print!(\"{k} {name}\");\n    for v in x { print!(\" {v:x}\"); }\n    println!();\n}\n");
    p.push_str("fn f32s(x: &[f64; 6]) -> [f32; 6] { x.map(|v| v as f32) }\n");
    p.push_str("fn main() {\n    for k in 0..S.len() {\n");
    for (module, fns, conv, bits) in [("m64", f64_fns, "", "f64::to_bits"), ("m32", f32_fns, "&f32s(", "f32::to_bits")]
    {
        for f in fns {
            let close = if conv.is_empty() { "" } else { ")" };
            let mut args = vec![format!("{conv}&S[k]{close}"), format!("{conv}&C[k]{close}")];
            for input in &f.function.vectors()[1..] {
                args.push(format!("{conv}&{}[k]{close}", input.to_uppercase()));
            }
            let call = format!("{module}::{}_sc({})", f.name, args.join(", "));
            let flat = if f.function == Kind::MassMatrix { ".as_flattened().to_vec()" } else { ".to_vec()" };
            let _ = writeln!(
                p,
                "        out(k, \"{module}_{}\", &{call}{flat}.into_iter().map({bits}).collect::<Vec<_>>());",
                f.name
            );
        }
    }
    p.push_str("    }\n");
    let _ = writeln!(p, "    let x: [f64; {}] = {angles:?};", angles.len());
    p.push_str("    let (s, c) = m64::sin_cos_array(&x);\n");
    p.push_str("    out(0, \"sin64\", &s.map(f64::to_bits));\n    out(0, \"cos64\", &c.map(f64::to_bits));\n");
    p.push_str("    out(0, \"sin64_one\", &x.map(|v| m64::sin_cos_kernel(v).0.to_bits()));\n");
    p.push_str("    out(0, \"avx2_one\", &[u64::from(cfg!(target_feature = \"avx2\"))]);\n");
    p.push_str("    out(0, \"cos64_one\", &x.map(|v| m64::sin_cos_kernel(v).1.to_bits()));\n");
    p.push_str("    let (s, c) = m32::sin_cos_array_f32(&x.map(|v| v as f32));\n");
    p.push_str("    out(0, \"sin32\", &s.map(f32::to_bits));\n    out(0, \"cos32\", &c.map(f32::to_bits));\n");
    p.push_str("}\n");
    p
}

#[test]
fn the_fused_path_compiled_with_the_fma_feature_rounds_once_and_stays_accurate() {
    if !host_has_fma() {
        eprintln!("this machine has no fused multiply-add: the fused path is not run here");
        return;
    }
    let f64_module = generate(&bundled_model("ur5"), &CodegenOptions::default()).unwrap();
    let f32_module = generate(&bundled_model("ur5"), &CodegenOptions::default().scalar(ScalarType::F32)).unwrap();
    let pick = |m: &dynagen::codegen::GeneratedModule| -> Vec<GeneratedFunction> {
        m.functions.iter().filter(|f| f.emitted).cloned().collect()
    };
    let (f64_fns, f32_fns) = (pick(&f64_module), pick(&f32_module));
    let xs = states(40, 72);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("generated_fma");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ur5.rs"), &f64_module.source).unwrap();
    std::fs::write(dir.join("ur5_f32.rs"), &f32_module.source).unwrap();
    let angles = angles();
    std::fs::write(dir.join("main.rs"), program(&xs, &f64_fns, &f32_fns, &angles)).unwrap();
    let exe = dir.join("fused");
    let mut rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()));
    rustc.args(["--edition", "2021", "-O", "-o"]).arg(&exe).arg(dir.join("main.rs"));
    // With AVX2 too where the host has it: sin_cos_array then runs four
    // angles a vector (`sin_cos_lanes`), which must give the bits of the
    // one-angle kernel.
    #[cfg(target_arch = "x86_64")]
    rustc.args([
        "-C",
        if std::is_x86_feature_detected!("avx2") { "target-feature=+fma,+avx2" } else { "target-feature=+fma" },
    ]);
    let built = rustc.output().expect("running rustc");
    assert!(built.status.success(), "rustc failed:\n{}", String::from_utf8_lossy(&built.stderr));
    let run = std::process::Command::new(&exe).output().expect("running the fused program");
    assert!(run.status.success());
    let stdout = String::from_utf8(run.stdout).unwrap();
    if host_has_avx2_and_fma() {
        // The same program without target features: every function runs its AVX-512 copy where
        // the host has it, else its AVX2 and FMA copy; then with the AVX-512 check answering no.
        #[cfg(target_arch = "x86_64")]
        let avx512 = std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl")
            && std::is_x86_feature_detected!("avx512dq");
        #[cfg(not(target_arch = "x86_64"))]
        let avx512 = false;
        for (variant, no_avx512) in [("run_time_dispatch", false), ("run_time_dispatch_avx2", true)] {
            let vdir = dir.join(variant);
            std::fs::create_dir_all(&vdir).unwrap();
            let answer_no = |src: &str| {
                let check = "fn ask_cpu_for_avx512() -> bool {\n";
                assert!(src.contains(check), "no AVX-512 check in the module");
                if no_avx512 {
                    src.replace(check, &format!("{check}    if true {{\n        return false;\n    }}\n"))
                } else {
                    src.to_string()
                }
            };
            std::fs::write(vdir.join("ur5.rs"), answer_no(&f64_module.source)).unwrap();
            std::fs::write(vdir.join("ur5_f32.rs"), answer_no(&f32_module.source)).unwrap();
            std::fs::copy(dir.join("main.rs"), vdir.join("main.rs")).unwrap();
            let (exe, asm) = (vdir.join("dispatched"), vdir.join("dispatched.s"));
            let mut rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()));
            rustc.args(["--edition", "2021", "-O", "--emit"]).arg(format!("link={}", exe.display()));
            rustc.arg("--emit").arg(format!("asm={}", asm.display())).arg(vdir.join("main.rs"));
            let built = rustc.output().expect("running rustc");
            assert!(built.status.success(), "rustc failed:\n{}", String::from_utf8_lossy(&built.stderr));
            let run = std::process::Command::new(&exe).output().expect("running the dispatched program");
            assert!(run.status.success());
            let dispatched = String::from_utf8(run.stdout).unwrap();
            // All but the line that says whether the build has AVX2 (it has not).
            let lines =
                |out: &str| out.lines().filter(|l| !l.starts_with("0 avx2_one")).map(String::from).collect::<Vec<_>>();
            let (native, dispatched) = (lines(&stdout), lines(&dispatched));
            assert_eq!(native.len(), dispatched.len());
            for (a, b) in native.iter().zip(&dispatched) {
                assert!(a == b, "built with +fma,+avx2: {a}\n{variant} at run time: {b}");
            }
            let ran = if avx512 && !no_avx512 { "AVX-512" } else { "AVX2 and FMA" };
            println!("run-time dispatch ({ran} copies): {} lines, the +fma,+avx2 build's bits", native.len());
            let asm = std::fs::read_to_string(&asm).unwrap();
            for suffix in ["_avx2_fma", "_avx512"] {
                let copies = dispatch_copies(&asm, suffix);
                println!("{} {suffix} copies in the release assembly", copies.len());
                assert!(copies.len() >= 2 * f64_fns.len(), "{:?}", copies.iter().map(|c| &c.0).collect::<Vec<_>>());
                for (name, code) in &copies {
                    // Everything inlined: a call left out of line would run outside the copy's target
                    // features (an intrinsic's wrapper, a closure passing vector registers through
                    // memory). Only the kernel's rare slow path is called, and libc's memcpy and memset
                    // (the test's batch of 2,000 angles is copied), also through a register loaded with
                    // their address.
                    let named = ["sin_cos_again", "sin_cos_slow", "memcpy", "memset"];
                    let registers: Vec<String> = code
                        .lines()
                        .filter(|l| l.contains("memcpy@GOTPCREL") || l.contains("memset@GOTPCREL"))
                        .filter_map(|l| l.rsplit(", ").next().map(|reg| format!("*{reg}")))
                        .collect();
                    let allowed =
                        |l: &str| named.iter().any(|n| l.contains(n)) || registers.iter().any(|r| l.ends_with(r));
                    let calls: Vec<&str> =
                        code.lines().filter(|l| l.trim_start().starts_with("call") && !allowed(l.trim_end())).collect();
                    assert!(calls.is_empty(), "{name} calls out of line: {calls:?}");
                    let fused = code.lines().filter(|l| l.trim_start().starts_with("vf") && l.contains("madd")).count();
                    assert!(fused > 0, "{name}: no fused multiply-add");
                    if name.contains("sin_cos_array") {
                        assert!(code.contains("ymm"), "{name}: four angles to a register");
                    }
                }
            }
        }
    } else {
        eprintln!("this machine lacks AVX2 or FMA: the run-time dispatch is not run here");
    }
    let mut robot = bundled_robot("ur5");
    let (mut lines, mut differ, mut worst) = (0, [0usize; 2], [0.0f64; 2]);
    let (mut kernel_worst, mut kernel_differ) = ([0.0f64; 4], 0);
    let exact: Vec<(DoubleDouble, DoubleDouble)> = angles.iter().map(|&x| DoubleDouble::from(x).sin_cos()).collect();
    let unfused = dynagen::codegen::sin_cos_kernel;
    let mut one_by_one = std::collections::BTreeMap::new();
    for line in stdout.lines() {
        let mut words = line.split_whitespace();
        let k: usize = words.next().unwrap().parse().unwrap();
        let name = words.next().unwrap();
        let got: Vec<u64> = words.map(|w| u64::from_str_radix(w, 16).unwrap()).collect();
        if name.ends_with("_one") || name == "sin64" || name == "cos64" {
            one_by_one.insert(name.to_string(), got.clone());
        }
        if name.ends_with("_one") {
            continue;
        }
        if let Some(j) = ["sin64", "cos64", "sin32", "cos32"].iter().position(|n| *n == name) {
            assert_eq!(got.len(), angles.len());
            for (i, (&b, &x)) in got.iter().zip(&angles).enumerate() {
                let u = if j < 2 {
                    let (e, want) = if j == 0 { (exact[i].0, unfused(x).0) } else { (exact[i].1, unfused(x).1) };
                    kernel_differ += usize::from(b != want.to_bits());
                    ulps(f64::from_bits(b), e)
                } else {
                    // In ulps of f32 (2²⁹ of f64's) of the exact value of the f32 angle.
                    let x32 = DoubleDouble::from(f64::from(x as f32)).sin_cos();
                    let e = if j == 2 { x32.0 } else { x32.1 };
                    ulps(f64::from(f32::from_bits(b as u32)), e) / (1u64 << 29) as f64
                };
                assert!(u <= 1.0, "{name}({x:e}): {u} ulp");
                kernel_worst[j] = kernel_worst[j].max(u);
            }
            continue;
        }
        let (module, fn_name) = name.split_at(3);
        let fns = if module == "m64" { &f64_fns } else { &f32_fns };
        let f = fns.iter().find(|f| f.name == fn_name[1..]).unwrap();
        let body: &Traced = &f.sin_cos_inputs.function;
        let (x, fusion) = (&xs[k], body.fusion());
        let want = generic(&mut robot, &f.function, x);
        if module == "m64" {
            let got: Vec<f64> = got.into_iter().map(f64::from_bits).collect();
            let fused = body.eval_fused(&fusion, &inputs(x)).unwrap();
            assert_eq!(bits(&got), bits(&fused), "{name} at state {k}: not the fused interpreter's bits");
            differ[0] += usize::from(bits(&got) != bits(&body.eval(&inputs(x)).unwrap()));
            let epsilon = 1e-12 * scale(&want, 1.0);
            assert!(abs_diff_eq!(&got[..], &want[..], epsilon = epsilon), "{name} at state {k}: {got:?} vs {want:?}");
            worst[0] = worst[0].max(rel_err(&got, &want, 1.0));
        } else {
            let got: Vec<f32> = got.into_iter().map(|b| f32::from_bits(b as u32)).collect();
            let x32 = |a: &[f64; N]| a.map(|v| f64::from(v as f32));
            let (s, c, qd, qdd, tau) = (x32(&x.s), x32(&x.c), x32(&x.qd), x32(&x.qdd), x32(&x.tau));
            let inputs32 = [("s", &s[..]), ("c", &c), ("qd", &qd), ("qdd", &qdd), ("tau", &tau)];
            let fused = body.eval_fused_as::<f32>(&fusion, &inputs32, f32::mul_add).unwrap();
            let b32 = |v: &[f32]| v.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(b32(&got), b32(&fused), "{name} at state {k}: not the fused interpreter's bits");
            differ[1] += usize::from(b32(&got) != b32(&body.eval_as::<f32>(&inputs32).unwrap()));
            let got: Vec<f64> = got.into_iter().map(f64::from).collect();
            let epsilon = 1e-5 * scale(&want, 1.0);
            assert!(abs_diff_eq!(&got[..], &want[..], epsilon = epsilon), "{name} at state {k}: {got:?} vs {want:?}");
            worst[1] = worst[1].max(rel_err(&got, &want, 1.0));
        }
        lines += 1;
    }
    assert_eq!(lines, xs.len() * (f64_fns.len() + f32_fns.len()), "{stdout}");
    // The vector path of sin_cos_array is the one-angle kernel, bit for bit.
    assert_eq!(one_by_one.len(), 5, "{stdout}");
    #[cfg(target_arch = "x86_64")]
    assert_eq!(one_by_one["avx2_one"], [u64::from(std::is_x86_feature_detected!("avx2"))], "built with AVX2");
    assert_eq!(one_by_one["sin64"], one_by_one["sin64_one"]);
    assert_eq!(one_by_one["cos64"], one_by_one["cos64_one"]);
    // The fused kernel rounds differently from the unfused one somewhere
    // (rarely: the fused operations are the polynomials' small corrections).
    assert!(kernel_differ > 0, "no fused kernel result differs from the unfused one");
    println!(
        "fused sin_cos_array: max error sin {:.3}, cos {:.3} ulp ({kernel_differ} of {} results differ from unfused); f32 {:.3}, {:.3} ulp of f32",
        kernel_worst[0],
        kernel_worst[1],
        2 * angles.len(),
        kernel_worst[2],
        kernel_worst[3]
    );
    // Rounding once changes the last bits of most results: fused
    // instructions ran (with `a * b + c` no result would differ).
    let per_module = xs.len() * f64_fns.len();
    assert!(differ.iter().all(|&d| d > per_module / 2), "{differ:?} of {per_module} results differ from unfused");
    println!("fused UR5 module: {differ:?} of {per_module} results (f64, f32) differ from unfused; worst relative error against the generic solver {worst:?}");
}
