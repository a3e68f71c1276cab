//! The stiff and extreme suite (`tests/tests/stiff_extreme.rs`): its bounds
//! and the worst cases observed, measured here on more states than the test
//! runs.

use crate::report::Report;
use dynagen::algorithms::compensated::{forward_dynamics_compensated, CompensatedScratch};
use dynagen::algorithms::Loads;
use dynagen::{DoubleDouble, Robot};
use dynagen_tests::suite::{eval, fd_bound, id_bound, spd_condition, states};
use dynagen_tests::{rel_err, stiff_case, STIFF_CASES};
use nalgebra::DVector;
use std::fmt::Write as _;

/// Worst values over a case's states.
#[derive(Default)]
struct Worst {
    cond: f64,
    id: f64,
    id_used: f64,
    aba: f64,
    ldlt: f64,
    comp: f64,
    /// RNEA + ABA at rest, all in f64.
    split: f64,
    /// The largest error / bound of the three forward dynamics.
    fd_used: f64,
}

/// Writes the section.
pub fn run(report: &mut Report) {
    let count = if report.quick { 4 } else { 40 };
    let mut body = String::from(
        "`cargo test -p dynagen-tests --test stiff_extreme` checks the generic solver in `f64`, the compensated \
         forward dynamics and the generated code of three stiff robots against the same algorithms in \
         double-double. Its bounds, relative to the largest entry of the reference output:\n\n\
         - τ, M, h, g: **100·n·ε** (each entry is a sum of O(n) products along the tree);\n\
         - forward dynamics (ABA, CRBA + LTDL, compensated, generated): **10·cond(M)·ε·(1 + (max(‖τ‖, ‖h‖)/‖M‖_F) \
         / ‖q̈‖)**, the error of a backward-stable solve of M q̈ = τ − h when τ and h are as large as they are;\n\
         - every output finite, M symmetric positive definite; non-finite input to `Robot` is an `InputError` \
         naming the argument and the joint. Generated code checks nothing (straight-line arithmetic, no error \
         path): a NaN or an infinity in its input propagates to NaN or infinite outputs, and the test asserts \
         exactly that; callers that may pass non-finite values check them.\n\n",
    );
    let _ = write!(
        body,
        "Worst cases over {count} states per robot (q̈ and τ in ±10), errors relative; \"used\" is the largest \
         error/bound ratio:\n\n\
         | case | n | cond(M) ≤ | τ/M/h/g error | used | ABA error | CRBA + LTDL error | compensated error \
         | forward dynamics, used | h by RNEA, then ABA at rest, all f64 |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
    );
    // (case, ABA's worst error / LTDL's, ABA's / the RNEA-then-ABA-at-rest split's)
    let mut ratios: Vec<(&'static str, f64, f64)> = Vec::new();
    for name in STIFF_CASES {
        let case = stiff_case(name);
        report.progress(&format!("stiff suite: {}", case.title));
        let model = &case.model;
        let n = model.dof();
        let mut robot = Robot::new(model.clone());
        let mut w = Worst::default();
        let mut scratch = CompensatedScratch::<f64>::new(model);
        let mut split = vec![0.0; n];
        let count = if n > 20 { count.min(4) } else { count };
        for (q, qd, qdd, tau) in states(&case, count) {
            let f = eval::<f64>(model, &q, &qd, &qdd, &tau);
            let r = eval::<DoubleDouble>(model, &q, &qd, &qdd, &tau);
            let v = |x: &[f64]| DVector::from_column_slice(x);
            let comp = robot.forward_dynamics_compensated(&v(&q), &v(&qd), &v(&tau)).expect("finite input");
            let g = model.gravity;
            forward_dynamics_compensated(model, &mut scratch, &q, &qd, &tau, Loads::gravity(&g), &mut split);
            w.split = w.split.max(rel_err(&split, &r.qdd_aba, 0.0));
            let (cond, _) = spd_condition(n, &f.m);
            w.cond = w.cond.max(cond);
            for (a, b) in [(&f.tau, &r.tau), (&f.m, &r.m), (&f.h, &r.h), (&f.g, &r.g)] {
                let e = rel_err(a, b, 0.0);
                w.id = w.id.max(e);
                w.id_used = w.id_used.max(e / id_bound(n));
            }
            let fdb = fd_bound(n, cond, &r, &tau);
            let (ea, el, ec) = (
                rel_err(&f.qdd_aba, &r.qdd_aba, 0.0),
                rel_err(&f.qdd_ldlt, &r.qdd_aba, 0.0),
                rel_err(comp.as_slice(), &r.qdd_aba, 0.0),
            );
            w.aba = w.aba.max(ea);
            w.ldlt = w.ldlt.max(el);
            w.comp = w.comp.max(ec);
            w.fd_used = w.fd_used.max(ea.max(el).max(ec) / fdb);
        }
        let _ = writeln!(
            body,
            "| {} | {n} | {:.1e} | {:.1e} | {:.0e} | {:.1e} | {:.1e} | {:.1e} | {:.0e} | {:.1e} |",
            case.title, w.cond, w.id, w.id_used, w.aba, w.ldlt, w.comp, w.fd_used, w.split
        );
        ratios.push((case.title, w.aba / w.ldlt, w.aba / w.split));
    }
    // The case where `ratio` is largest (or, with `largest` false, smallest).
    let pick = |ratio: fn(&(&'static str, f64, f64)) -> f64, largest: bool| {
        let better = |a: f64, b: f64| if largest { a > b } else { a < b };
        ratios.iter().fold(ratios[0], |acc, r| if better(ratio(r), ratio(&acc)) { *r } else { acc })
    };
    let (vs_ldlt, best, vs_split) = (pick(|r| r.1, true), pick(|r| r.1, false), pick(|r| r.2, true));
    let _ = write!(
        body,
        "\nThe default forward dynamics (`Robot::forward_dynamics`, and the generated `forward_dynamics`) is the \
         articulated-body algorithm; the test checks that it is exactly that. In this run its worst error is at \
         most {:.1}× that of CRBA + LTDL ({}) and as little as {:.1e}× of it ({}); at most {:.1}× that of \
         h by RNEA followed by ABA at rest ({}). Factors within a few units are rounding noise of errors near ε; \
         a loss of digits would show as a factor of 100 or more.\n",
        vs_ldlt.1, vs_ldlt.0, best.1, best.0, vs_split.2, vs_split.0
    );
    report.section("Stiff and extreme suite: bounds and worst cases", &body);
}
