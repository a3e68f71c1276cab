//! The derivatives of the dynamics: for the benchmark's robots (UR5, Panda,
//! KUKA iiwa 14, the quadruped12 with its trunk fixed) and each derivative
//! function (∂τ/∂(q, q̇), ∂q̈/∂(q, q̇) with M⁻¹, M⁻¹ alone), the generic
//! algorithm in f64 (what `Robot` runs: the analytical recursion) and the
//! generated modules in f64 and f32 (default options: each keeps the
//! formulation with fewer operations), their time per call and their error
//! against the same derivatives computed by dual numbers in double-double
//! (an independent formulation at about 32 digits).
//!
//! The timing and the statistics are those of the error-versus-time
//! section ([`error_vs_time`](crate::error_vs_time)): the variants of one
//! function run in turn, batch by batch; the error of a state is the norm
//! of the difference of all the function's matrices over the reference's.

use crate::error_vs_time::{
    error_states, fmt_err, fmt_stats, fmt_time, generated_variant, median_max, relative_error, time, Arrays, Flatten,
    State, Timing, Variant,
};
use crate::report::Report;
use dynagen::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation, RigidBodyOnly};
use dynagen::algorithms::{crba, Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, Model, Scalar};
use dynagen_tests::workspace_root;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Duration;

#[allow(dead_code)]
mod generated {
    include!(concat!(env!("OUT_DIR"), "/derivatives.rs"));
}

/// The robots, as `report/build.rs` generates their modules.
const ROBOTS: [&str; 4] = ["ur5", "panda", "iiwa14", "quadruped12"];

/// The functions measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DFunc {
    /// (∂τ/∂q, ∂τ/∂q̇) at (q, q̇, q̈).
    Inverse,
    /// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) at (q, q̇, τ).
    Forward,
    /// M⁻¹(q).
    Minv,
}

impl DFunc {
    const ALL: [DFunc; 3] = [DFunc::Inverse, DFunc::Forward, DFunc::Minv];

    fn label(self) -> &'static str {
        match self {
            DFunc::Inverse => "∂τ/∂q, ∂τ/∂q̇",
            DFunc::Forward => "∂q̈/∂q, ∂q̈/∂q̇, M⁻¹",
            DFunc::Minv => "M⁻¹",
        }
    }

    /// The function on the scalar `S`: the generic algorithm (formulation
    /// `f`), its matrices concatenated, row-major.
    fn run<S: Scalar>(
        self,
        model: &Model,
        dw: &mut DerivativeWorkspace<S>,
        state: [&[S]; 4],
        f: Formulation,
    ) -> Vec<S> {
        let n = model.dof();
        let g = Vec3::<S>::from_f64(&model.gravity);
        let dynamics = Dynamics { model, loads: Loads::gravity(&g), torques: &RigidBodyOnly, mass: None };
        let [q, qd, qdd, tau] = state;
        let mut m = [vec![S::zero(); n * n], vec![S::zero(); n * n], vec![S::zero(); n * n]];
        let [a, b, c] = &mut m;
        match self {
            DFunc::Inverse => d::inverse_dynamics_derivatives(&dynamics, dw, [q, qd, qdd], f, [a, b], None),
            DFunc::Forward => d::forward_dynamics_derivatives(&dynamics, dw, [q, qd, tau], f, [a, b, c]),
            DFunc::Minv => {
                let mut ws = Workspace::new(model);
                crba::crba(model, &mut ws, q, Loads::none(), a);
                d::mass_matrix_inverse(model, a, b, c);
            }
        }
        let count = match self {
            DFunc::Inverse => 2,
            DFunc::Forward => 3,
            DFunc::Minv => 1,
        };
        match self {
            DFunc::Minv => m[2].clone(),
            _ => m[..count].concat(),
        }
    }
}

/// The state's vectors on the scalar `S`.
fn on<S: Scalar>(state: &State) -> [Vec<S>; 4] {
    [&state.q, &state.qd, &state.qdd, &state.tau].map(|v| v.iter().map(|&x| S::from_f64(x)).collect())
}

/// The reference: dual numbers in double-double.
fn reference(model: &Model, f: DFunc, dw: &mut DerivativeWorkspace<DoubleDouble>, state: &State) -> Vec<f64> {
    let [q, qd, qdd, tau] = on::<DoubleDouble>(state);
    let out = f.run(model, dw, [&q, &qd, &qdd, &tau], Formulation::DualNumbers);
    out.iter().map(|x| x.to_f64()).collect()
}

/// The generic f64 algorithm as a variant.
fn generic<'a>(model: &'a Model, f: DFunc, timing: &[State]) -> Variant<'a> {
    let inputs: Vec<[Vec<f64>; 4]> = timing.iter().map(on::<f64>).collect();
    let mut dw = DerivativeWorkspace::new(model);
    let mut dw_eval = DerivativeWorkspace::new(model);
    Variant {
        name: "generic f64",
        eval: Box::new(move |state| {
            let [q, qd, qdd, tau] = on::<f64>(state);
            f.run(model, &mut dw_eval, [&q, &qd, &qdd, &tau], Formulation::Analytical)
        }),
        run: Box::new(move |rounds| {
            for _ in 0..rounds {
                for [q, qd, qdd, tau] in &inputs {
                    black_box(f.run(model, &mut dw, black_box([q, qd, qdd, tau]), Formulation::Analytical));
                }
            }
        }),
    }
}

impl<const N: usize> Flatten for ([[f64; N]; N], [[f64; N]; N]) {
    fn flat(&self) -> Vec<f64> {
        [self.0.flat(), self.1.flat()].concat()
    }
}
impl<const N: usize> Flatten for ([[f32; N]; N], [[f32; N]; N]) {
    fn flat(&self) -> Vec<f64> {
        [self.0.flat(), self.1.flat()].concat()
    }
}
impl<const N: usize> Flatten for ([[f64; N]; N], [[f64; N]; N], [[f64; N]; N]) {
    fn flat(&self) -> Vec<f64> {
        [self.0.flat(), self.1.flat(), self.2.flat()].concat()
    }
}
impl<const N: usize> Flatten for ([[f32; N]; N], [[f32; N]; N], [[f32; N]; N]) {
    fn flat(&self) -> Vec<f64> {
        [self.0.flat(), self.1.flat(), self.2.flat()].concat()
    }
}

/// `fn $robot(f, model, timing)`: its generated variants of `f`.
macro_rules! generated_robot {
    ($robot:ident) => {
        fn $robot<'a>(f: DFunc, model: &'a Model, timing: &[State]) -> Vec<Variant<'a>> {
            use generated::$robot::{f32 as g32, f64 as g64};
            const N: usize = g64::DOF;
            let (v64, v32) = ("generated f64", "generated f32");
            match f {
                DFunc::Inverse => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g64::inverse_dynamics_derivatives(
                        &a.q, &a.qd, &a.qdd
                    )),
                    generated_variant!(v32, f32, N, model, timing, |a| g32::inverse_dynamics_derivatives(
                        &a.q, &a.qd, &a.qdd
                    )),
                ],
                DFunc::Forward => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g64::forward_dynamics_derivatives(
                        &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(v32, f32, N, model, timing, |a| g32::forward_dynamics_derivatives(
                        &a.q, &a.qd, &a.tau
                    )),
                ],
                DFunc::Minv => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g64::mass_matrix_inverse(&a.q)),
                    generated_variant!(v32, f32, N, model, timing, |a| g32::mass_matrix_inverse(&a.q)),
                ],
            }
        }
    };
}

generated_robot!(ur5);
generated_robot!(panda);
generated_robot!(iiwa14);
generated_robot!(quadruped12);

/// Every variant of `f` for `robot`: generic f64, generated f64, generated f32.
fn variants<'a>(robot: &str, model: &'a Model, f: DFunc, timing: &[State]) -> Vec<Variant<'a>> {
    let generated = match robot {
        "ur5" => ur5,
        "panda" => panda,
        "iiwa14" => iiwa14,
        "quadruped12" => quadruped12,
        other => unreachable!("no generated derivatives for {other}: add it to build.rs"),
    };
    let mut v = vec![generic(model, f, timing)];
    v.extend(generated(f, model, timing));
    v
}

/// One row: a function, a variant, its time and its errors.
struct Row {
    func: DFunc,
    variant: &'static str,
    time: Timing,
    errors: Vec<f64>,
}

/// How many states and repetitions.
fn sizes(quick: bool) -> (usize, usize, usize, usize, Duration) {
    // (random states, extreme states, timing states, repetitions, batch)
    if quick {
        (12, 5, 4, 11, Duration::from_micros(10))
    } else {
        (600, 101, 8, 1001, Duration::from_micros(40))
    }
}

/// Measures every function and variant of one robot.
fn measure(report: &Report, robot: &str, model: &Model) -> Vec<Row> {
    let (random, extreme, timing, reps, batch) = sizes(report.quick);
    let (random, extreme) = error_states(model, 0xde71 ^ model.dof() as u64, random, extreme);
    let states = [random, extreme].concat();
    let timing: Vec<State> = error_states(model, 0x7136, timing, 0).0;
    let mut dd = DerivativeWorkspace::<DoubleDouble>::new(model);
    let mut rows = Vec::new();
    for f in DFunc::ALL {
        report.progress(&format!("{robot}: derivatives, {}", f.label()));
        let mut vs = variants(robot, model, f, &timing);
        let mut errors = vec![Vec::with_capacity(states.len()); vs.len()];
        for state in &states {
            let r = reference(model, f, &mut dd, state);
            for (v, e) in vs.iter_mut().zip(&mut errors) {
                if let Some(x) = relative_error(&(v.eval)(state), &r) {
                    e.push(x);
                }
            }
        }
        let times = time(&mut vs, timing.len(), reps, batch);
        for ((v, t), e) in vs.iter().zip(times).zip(errors) {
            rows.push(Row { func: f, variant: v.name, time: t, errors: e });
        }
    }
    rows
}

/// The section.
pub fn run(report: &mut Report) {
    let (random, extreme, timing, reps, batch) = sizes(report.quick);
    let mut body = format!(
        "The derivatives of the dynamics of the benchmark's robots (`scripts/reference/derivatives_bench.sh` \
         times them against Pinocchio, `docs/performance.md`): the generic algorithm in f64 \
         (`dynagen::algorithms::derivatives`, the analytical recursion `Robot` runs) and the generated \
         modules (`functions = [inverse_dynamics_derivatives, forward_dynamics_derivatives, \
         mass_matrix_inverse]`, otherwise the default options: batched sines and cosines, run-time dispatch, \
         each function traced by the analytical recursion and by dual numbers and the one with fewer \
         operations kept) in f64 and f32.\n\n\
         **Error**: ‖x − x_ref‖₂ / ‖x_ref‖₂ over all of a function's matrices together (Frobenius), against \
         the same derivatives by dual numbers through the RNEA in double-double (≈ 32 digits; a formulation \
         independent of the analytical recursion), on {random} random states (|q| ≤ π, |q̇| ≤ 2 rad/s, \
         |q̈| ≤ 5 rad/s², |τ| ≤ 30 N·m) and {extreme} extreme ones (the zero state, |q̇| ≤ 100 rad/s, \
         |q| ≤ 1e3 rad), every input an f32 number. **Time** per call: {reps} repetitions of one batch \
         (≈ {batch} µs over {timing} states) of each variant in turn; median and minimum.\n\n\
         Source: `report/src/derivatives.rs`; the generated modules are written by `report/build.rs`.\n\n\
         | robot | function | variant | median [ns] | min [ns] | vs generic f64 | error: median | error: max |\n\
         | --- | --- | --- | ---: | ---: | ---: | ---: | ---: |\n",
        batch = batch.as_micros(),
    );
    let mut worst_f64: f64 = 0.0;
    let mut worst_f32: f64 = 0.0;
    for robot in ROBOTS {
        let urdf = workspace_root().join(format!("dynagen/robots/{robot}.urdf"));
        let model = match Model::from_urdf_file(&urdf) {
            Ok(m) => m,
            Err(e) => {
                let _ = writeln!(body, "| {robot} | not measured: {e} | | | | | | |");
                continue;
            }
        };
        let rows = measure(report, robot, &model);
        for r in &rows {
            let generic = rows.iter().find(|g| g.func == r.func && g.variant == "generic f64").map(|g| g.time.median);
            let speedup = generic.map_or("–".into(), |g| format!("{:.1}×", g / r.time.median));
            let (median, max) = fmt_stats(&r.errors);
            let _ = writeln!(
                body,
                "| {robot} ({} joints) | {} | {} | {} | {} | {speedup} | {median} | {max} |",
                model.dof(),
                r.func.label(),
                r.variant,
                fmt_time(r.time.median),
                fmt_time(r.time.min)
            );
            let m = median_max(&r.errors).map_or(f64::NAN, |x| x.1);
            if r.variant.ends_with("f32") {
                worst_f32 = worst_f32.max(m);
            } else {
                worst_f64 = worst_f64.max(m);
            }
        }
    }
    let _ = writeln!(
        body,
        "\nLargest error of an f64 variant: {}; of an f32 variant: {}.\n",
        fmt_err(worst_f64),
        fmt_err(worst_f32)
    );
    report.section("Derivatives of the dynamics", &body);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the UR5 and the quadruped12: the f64 variants agree with the
    /// double-double dual numbers to 1e-12, the f32 ones to 1e-4 (and no
    /// better than 1e-9, as f32 must).
    #[test]
    fn errors_are_those_of_each_precision() {
        for robot in ["ur5", "quadruped12"] {
            let model = Model::from_urdf_file(workspace_root().join(format!("dynagen/robots/{robot}.urdf"))).unwrap();
            let (states, _) = error_states(&model, 3, 6, 0);
            let mut dd = DerivativeWorkspace::<DoubleDouble>::new(&model);
            for f in DFunc::ALL {
                let mut vs = variants(robot, &model, f, &states[..1]);
                for state in &states {
                    let r = reference(&model, f, &mut dd, state);
                    for v in &mut vs {
                        let e = relative_error(&(v.eval)(state), &r).unwrap();
                        let ok = if v.name.ends_with("f32") { (1e-9..1e-4).contains(&e) } else { e <= 1e-12 };
                        assert!(ok, "{robot} {f:?} {}: {e:e}", v.name);
                    }
                }
                for v in &mut vs {
                    (v.run)(1);
                }
            }
        }
    }
}
