//! Robots as their files define them: forward dynamics on cancelling states
//! (τ ≈ h at |q̇| of 1e2-1e3 rad/s, τ from an f64 RNEA) against references
//! computed at 50 digits from the files' decimals taken as exact
//! (`scripts/reference/make_file_precision_data.py`, data in
//! `tests/data/file_precision.json`), on robots with non-aligned axes and
//! rotated frames: an 8-joint chain, an 18-joint hand, a chain of 1-3 mm
//! links and one of 60-100 m links.
//!
//! The double-double algorithms compute the file's robot (its constants
//! from the decimals), the compensated forward dynamics is at least 100×
//! more accurate than the f64 articulated-body algorithm where ε·cond(M) ≤
//! 1e-6, and f64 computes exactly what it computed before the model kept
//! the file's values.

mod support;

use dynagen::algorithms::compensated::{forward_dynamics_compensated, CompensatedScratch, CompensatedSolver};
use dynagen::algorithms::{aba, bias, crba, rnea, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::{Compensated, DoubleDouble, Model, Scalar};
use serde_json::Value;
use std::path::Path;
use support::norm_rel_err;

const EPS: f64 = f64::EPSILON;

struct State {
    cancelling: bool,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd_in: Vec<f64>,
    tau: Vec<f64>,
    cond: f64,
    cancellation: f64,
    /// The references, at 50 digits, as double-double.
    qdd: Vec<DoubleDouble>,
    h: Vec<DoubleDouble>,
    g: Vec<DoubleDouble>,
    tau_of_qdd_in: Vec<DoubleDouble>,
    m: Vec<DoubleDouble>,
}

struct Case {
    name: String,
    model: Model,
    states: Vec<State>,
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("an array").iter().map(|x| x.as_f64().expect("a number")).collect()
}

fn decimals(v: &Value) -> Vec<DoubleDouble> {
    let strings = v.as_array().expect("an array");
    strings.iter().map(|x| DoubleDouble::from_decimal(x.as_str().expect("a string")).expect("a decimal")).collect()
}

fn cases() -> Vec<Case> {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let text = std::fs::read_to_string(data.join("file_precision.json")).expect("file_precision.json");
    let json: Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(floats(&json["gravity"]), [0.0, 0.0, -9.81], "the data's gravity is the model's default");
    let robots = json["robots"].as_array().expect("robots");
    robots
        .iter()
        .map(|r| {
            let model = Model::from_urdf_file(data.join(r["urdf"].as_str().unwrap())).expect("a test robot");
            let names: Vec<&str> = r["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
            assert_eq!(model.joint_names(), names, "joint order");
            assert!(model.has_file_values());
            let states = r["states"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| State {
                    cancelling: s["kind"] == "cancelling",
                    q: floats(&s["q"]),
                    qd: floats(&s["qd"]),
                    qdd_in: floats(&s["qdd_in"]),
                    tau: floats(&s["tau"]),
                    cond: s["cond_M"].as_f64().unwrap(),
                    cancellation: s["cancellation"].as_f64().unwrap(),
                    qdd: decimals(&s["qdd"]),
                    h: decimals(&s["h"]),
                    g: decimals(&s["g"]),
                    tau_of_qdd_in: decimals(&s["tau_of_qdd_in"]),
                    m: s["M"].as_array().unwrap().iter().flat_map(decimals).collect(),
                })
                .collect();
            Case { name: r["name"].as_str().unwrap().to_string(), model, states }
        })
        .collect()
}

/// ‖a − b‖ / ‖b‖ in double-double.
fn dd_err(a: &[DoubleDouble], b: &[DoubleDouble]) -> f64 {
    let norm = |v: &mut dyn Iterator<Item = DoubleDouble>| v.map(|x| x * x).fold(DoubleDouble::ZERO, |s, x| s + x);
    let diff = norm(&mut a.iter().zip(b).map(|(x, y)| *x - *y)).to_f64().sqrt();
    diff / norm(&mut b.iter().copied()).to_f64().sqrt()
}

fn to_f64(v: &[DoubleDouble]) -> Vec<f64> {
    v.iter().map(|x| x.to_f64()).collect()
}

/// (τ(q, q̇, q̈_in), h, g, M row-major, q̈ by ABA) of the generic algorithms in `S`.
fn outputs<S: Scalar>(model: &Model, s: &State) -> [Vec<S>; 5] {
    let n = model.dof();
    let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
    let (q, qd) = (c(&s.q), c(&s.qd));
    let grav = Vec3::<S>::from_f64(&model.gravity);
    let gravity = Loads::gravity(&grav);
    let mut ws = Workspace::<S>::new(model);
    let mut out =
        [vec![S::zero(); n], vec![S::zero(); n], vec![S::zero(); n], vec![S::zero(); n * n], vec![S::zero(); n]];
    rnea::rnea(model, &mut ws, &q, Some(&qd), Some(&c(&s.qdd_in)), gravity, &mut out[0]);
    bias::bias_forces(model, &mut ws, &q, &qd, Some(&grav), &mut out[1]);
    bias::gravity_torques(model, &mut ws, &q, &grav, &mut out[2]);
    crba::crba(model, &mut ws, &q, Loads::none(), &mut out[3]);
    aba::aba(model, &mut ws, &q, &qd, &c(&s.tau), gravity, &mut out[4]);
    out
}

/// The errors of the double-double algorithms against the reference:
/// (τ, h, g, M, q̈).
fn dd_errors(model: &Model, s: &State) -> [f64; 5] {
    let out = outputs::<DoubleDouble>(model, s);
    let refs = [&s.tau_of_qdd_in, &s.h, &s.g, &s.m, &s.qdd];
    std::array::from_fn(|k| dd_err(&out[k], refs[k]))
}

/// Runs `check` on every state of every case, with the case's model
/// without its file values (the f64 model) and the state's name.
fn each_state(mut check: impl FnMut(&Case, &Model, &State, &str)) {
    for case in cases() {
        let rounded = case.model.clone().without_file_values();
        for (k, s) in case.states.iter().enumerate() {
            check(&case, &rounded, s, &format!("{} state {k}", case.name));
        }
    }
}

#[test]
fn double_double_computes_the_files_robot() {
    each_state(|case, rounded, s, at| {
        let n = case.model.dof() as f64;
        let file = dd_errors(&case.model, s);
        // τ, h, g and M to double-double precision; q̈ loses the digits
        // τ − h cancels, and cond(M)'s, of double-double's 32.
        for (what, e) in ["τ", "h", "g", "M"].iter().zip(&file) {
            assert!(*e < 1e-29, "{at}: {what} off the file's robot by {e:e}");
        }
        let bound = 1e-31 * n * s.cond * (1.0 + s.cancellation);
        assert!(file[4] < bound, "{at}: q̈ off by {:e} > {bound:e}", file[4]);
        // The f64 model, re-orthonormalised: a robot an ε away, which the
        // cancellation amplifies; this is what the reference computed
        // before the model kept the file's values.
        let other = dd_errors(rounded, s);
        let worst = |e: &[f64]| e[..4].iter().copied().fold(0.0, f64::max);
        let (worst_file, worst_other) = (worst(&file), worst(&other));
        assert!(worst_other > 1e3 * worst_file, "{at}: the rounded model is as close ({worst_other:e})");
        if s.cancelling {
            assert!(other[4] > 1e-13 && other[4] > 1e4 * file[4], "{at}: q̈ of the rounded model off by {:e}", other[4]);
        }
    });
}

/// The relative error of a forward dynamics that solves M q̈ = τ − h stably:
/// 10·cond(M)·ε·(1 + max(‖τ‖, ‖h‖)/(‖M‖_F·‖q̈‖)).
fn solve_bound(s: &State) -> f64 {
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (tau, h, m, qdd) = (norm(&s.tau), norm(&to_f64(&s.h)), norm(&to_f64(&s.m)), norm(&to_f64(&s.qdd)));
    10.0 * s.cond * EPS * (1.0 + tau.max(h) / (m * qdd))
}

#[test]
fn f64_is_unchanged_by_the_file_values_and_within_its_bounds() {
    each_state(|case, rounded, s, at| {
        let n = case.model.dof() as f64;
        // f64 computes the f64 model, bit for bit, with or without the file's values
        let f = outputs::<f64>(&case.model, s);
        assert_eq!(f, outputs::<f64>(rounded, s), "{at}: f64 results changed");
        assert_eq!(outputs::<f32>(&case.model, s), outputs::<f32>(rounded, s), "{at}: f32 results changed");
        // and against the file's robot, the model's rounding is ε there
        let refs = [&s.tau_of_qdd_in, &s.h, &s.g, &s.m];
        for ((what, got), want) in ["τ", "h", "g", "M"].iter().zip(&f).zip(refs) {
            let e = norm_rel_err(got, &to_f64(want), 0.0);
            assert!(e < 100.0 * n * EPS, "{at}: f64 {what} off by {e:e}");
        }
        let e = norm_rel_err(&f[4], &to_f64(&s.qdd), 0.0);
        assert!(e < solve_bound(s), "{at}: f64 ABA off by {e:e} > {:e}", solve_bound(s));
    });
}

#[test]
fn compensated_is_a_hundredfold_more_accurate_than_aba_where_m_is_well_conditioned() {
    let mut cancelling = 0;
    for case in cases() {
        let n = case.model.dof();
        let mut scratch = CompensatedScratch::<Compensated>::new(&case.model);
        // and the solver `Robot` uses: products by FMA instructions where the CPU has them
        let mut solver = CompensatedSolver::new(&case.model);
        let mut ws = Workspace::<f64>::new(&case.model);
        let g = case.model.gravity;
        for (k, s) in case.states.iter().enumerate() {
            let at = format!("{} state {k}", case.name);
            let (mut plain, mut comp, mut by_solver) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            aba::aba(&case.model, &mut ws, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut plain);
            forward_dynamics_compensated(&case.model, &mut scratch, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut comp);
            solver.solve(&case.model, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut by_solver);
            let reference = to_f64(&s.qdd);
            let ea = norm_rel_err(&plain, &reference, 0.0);
            for (how, ec) in
                [("", norm_rel_err(&comp, &reference, 0.0)), (" (solver)", norm_rel_err(&by_solver, &reference, 0.0))]
            {
                // As accurate as a stable solve of M q̈ = u with u exact: its
                // error no longer grows with ‖h‖/‖τ − h‖.
                let bound = 10.0 * n as f64 * EPS * s.cond;
                assert!(ec < bound, "{at}: compensated{how} off by {ec:e} > {bound:e}");
                if s.cancelling && EPS * s.cond <= 1e-6 {
                    assert!(100.0 * ec <= ea, "{at}: compensated{how} {ec:e} against ABA {ea:e}");
                }
            }
            if s.cancelling && EPS * s.cond <= 1e-6 {
                cancelling += 1;
            }
        }
    }
    assert!(cancelling >= 16, "the data has {cancelling} cancelling states with ε·cond(M) ≤ 1e-6");
}

/// One step of refinement (residual in compensated arithmetic, one more
/// articulated-body solve) takes the f64 solve's ε·cond(M) away: on the
/// nearly dependent chains (ε·cond(M) from 2e-7 to 4e-5) the error drops by
/// at least a thousandfold, and it is never worse. With `--nocapture` it
/// prints every state's errors (ABA, compensated on the f64 model's
/// constants as before the model kept the file's, compensated, refined), the
/// table in `docs/performance.md`.
#[test]
fn refinement_pays_where_m_is_ill_conditioned() {
    let mut ill = 0;
    println!(
        "| robot | state | ε·cond(M) | ‖h‖/‖τ − h‖ | ABA f64 | compensated, f64 model's constants \
         | compensated | compensated + 1 refinement |"
    );
    println!("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    for case in cases() {
        let n = case.model.dof();
        let rounded = case.model.clone().without_file_values();
        let mut before = CompensatedScratch::<Compensated>::new(&rounded);
        let mut once = CompensatedScratch::<Compensated>::new(&case.model);
        let mut refined = CompensatedScratch::<Compensated>::new(&case.model).with_refinement(1);
        assert_eq!((once.refinements(), refined.refinements()), (0, 1));
        let mut ws = Workspace::<f64>::new(&case.model);
        let g = case.model.gravity;
        for (k, s) in case.states.iter().enumerate() {
            let at = format!("{} state {k}", case.name);
            let (mut a, mut b, mut plain, mut old) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            aba::aba(&case.model, &mut ws, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut plain);
            forward_dynamics_compensated(&rounded, &mut before, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut old);
            forward_dynamics_compensated(&case.model, &mut once, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut a);
            forward_dynamics_compensated(&case.model, &mut refined, &s.q, &s.qd, &s.tau, Loads::gravity(&g), &mut b);
            let reference = to_f64(&s.qdd);
            let (e1, e2) = (norm_rel_err(&a, &reference, 0.0), norm_rel_err(&b, &reference, 0.0));
            let kind = if s.cancelling { "cancelling" } else { "ordinary" };
            println!(
                "| {} | {k}, {kind} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {e1:.1e} | {e2:.1e} |",
                case.name,
                EPS * s.cond,
                s.cancellation,
                norm_rel_err(&plain, &reference, 0.0),
                norm_rel_err(&old, &reference, 0.0)
            );
            assert!(e2 <= 1.5 * e1 + 2.0 * EPS, "{at}: refined {e2:e} against {e1:e}");
            if EPS * s.cond >= 1e-7 {
                ill += 1;
                assert!(e2 <= 1e-3 * e1, "{at}: refined {e2:e} against {e1:e} (ε·cond(M) = {:e})", EPS * s.cond);
            }
        }
    }
    assert!(ill >= 12, "{ill} ill-conditioned states");
}
