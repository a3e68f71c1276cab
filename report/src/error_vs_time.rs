//! Error versus run time: for each bundled robot, each function (τ, M, h, g,
//! forward dynamics by ABA and by CRBA + LTDL) and each way dynagen computes
//! it — the generic algorithms in f64 and f32, the generated code in f64
//! (std's `sin_cos`, the batched `sin_cos_all`, or the sines and cosines as
//! inputs) and in f32 — its time per call and its error against the
//! double-double reference.
//!
//! Timing: every variant of one function runs a batch of calls over the same
//! few ordinary states, the variants in turn (round-robin, starting at a
//! different one each repetition) so that they share the machine's state;
//! the batch is long enough that the timer's own cost is negligible; the
//! report gives the median and the minimum over the repetitions.
//!
//! Error: ‖x − x_ref‖₂ / ‖x_ref‖₂ (Frobenius for M), where x_ref is the same
//! algorithm run in [`DoubleDouble`] (≈ 32 digits) on the robot as its file
//! defines it (every constant from the file's decimals:
//! [`Scalar::FILE_CONSTANTS`]), on random and on extreme states. Every state
//! is made of f32 numbers, so that f32 and f64 variants compute from the
//! same input and the f32 error is the computation's, not the rounding of
//! its input. A row [`MODEL_ROUNDING`] gives the part of the error that is
//! the model's rounding alone: the `f64` model (its constants rounded as
//! f64 code computes with them) run in double-double, against the file's.

use crate::plot::{self, Series};
use crate::report::Report;
use dynagen::algorithms::Workspace;
use dynagen::algorithms::{aba, bias, crba, forward_dynamics, rnea, Loads};
use dynagen::model::JointKind;
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, Model, Scalar};
use dynagen_tests::{workspace_root, Rng, BUNDLED};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

#[allow(dead_code)]
mod generated {
    include!(concat!(env!("OUT_DIR"), "/generated.rs"));
}

/// The functions measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// Inverse dynamics τ(q, q̇, q̈).
    Tau,
    /// The mass matrix M(q).
    M,
    /// The bias forces h(q, q̇).
    H,
    /// The gravity torques g(q).
    G,
    /// Forward dynamics by the articulated-body algorithm.
    FdAba,
    /// Forward dynamics by CRBA, RNEA and LᵀDL.
    FdLdlt,
}

impl Func {
    /// Every function, in the report's order.
    pub const ALL: [Func; 6] = [Func::Tau, Func::M, Func::H, Func::G, Func::FdAba, Func::FdLdlt];

    /// The name in tables.
    pub fn label(self) -> &'static str {
        match self {
            Func::Tau => "τ (RNEA)",
            Func::M => "M (CRBA)",
            Func::H => "h",
            Func::G => "g",
            Func::FdAba => "q̈ by ABA",
            Func::FdLdlt => "q̈ by CRBA + LTDL",
        }
    }

    /// The label of a point in the plots.
    pub fn short(self) -> &'static str {
        match self {
            Func::Tau => "τ",
            Func::M => "M",
            Func::H => "h",
            Func::G => "g",
            Func::FdAba => "ABA",
            Func::FdLdlt => "LTDL",
        }
    }

    /// Its input vectors, in argument order.
    fn inputs(self) -> &'static [&'static str] {
        match self {
            Func::Tau => &["q", "qd", "qdd"],
            Func::M | Func::G => &["q"],
            Func::H => &["q", "qd"],
            Func::FdAba | Func::FdLdlt => &["q", "qd", "tau"],
        }
    }

    /// The length of its output for `n` joints.
    fn output_len(self, n: usize) -> usize {
        if self == Func::M {
            n * n
        } else {
            n
        }
    }

    /// Runs the generic algorithm behind it on any scalar: `args` in the
    /// order of [`inputs`](Self::inputs), the result into `out`.
    fn run<S: Scalar>(self, model: &Model, ws: &mut Workspace<S>, args: &[Vec<S>], gravity: &Vec3<S>, out: &mut [S]) {
        let g = Some(gravity);
        match self {
            Func::Tau => rnea::rnea(model, ws, &args[0], Some(&args[1]), Some(&args[2]), Loads::gravity(gravity), out),
            Func::M => crba::crba(model, ws, &args[0], Loads::none(), out),
            Func::H => bias::bias_forces(model, ws, &args[0], &args[1], g, out),
            Func::G => bias::gravity_torques(model, ws, &args[0], gravity, out),
            Func::FdAba => aba::aba(model, ws, &args[0], &args[1], &args[2], Loads::gravity(gravity), out),
            Func::FdLdlt => forward_dynamics::forward_dynamics_ldlt(
                model,
                ws,
                &args[0],
                &args[1],
                &args[2],
                Loads::gravity(gravity),
                out,
            ),
        }
    }
}

/// The variants, in the report's order.
pub const VARIANTS: [&str; 6] = [
    "generic f64",
    "generic f32",
    "generated f64",
    "generated f64, sin_cos_all",
    "generated f64, sin/cos inputs",
    "generated f32",
];

/// The row of the model's rounding: the `f64` model computed in
/// double-double, against the file's robot; it has no time.
pub const MODEL_ROUNDING: &str = "f64 model, exact arithmetic (the model's rounding)";

/// One state of the robot. Every entry is an f32 number.
#[derive(Clone, Debug)]
pub struct State {
    /// Joint positions.
    pub q: Vec<f64>,
    /// Joint velocities.
    pub qd: Vec<f64>,
    /// Joint accelerations (the input of τ).
    pub qdd: Vec<f64>,
    /// Joint forces (the input of forward dynamics).
    pub tau: Vec<f64>,
}

impl State {
    /// The inputs of `f`, in its argument order.
    fn args(&self, f: Func) -> Vec<&[f64]> {
        f.inputs()
            .iter()
            .map(|name| match *name {
                "q" => &self.q[..],
                "qd" => &self.qd[..],
                "qdd" => &self.qdd[..],
                _ => &self.tau[..],
            })
            .collect()
    }
}

/// Random states: q ∈ ±`q_max` rad (prismatic joints ±4 cm), q̇ ∈ ±`qd_max`
/// rad/s, q̈ ∈ ±5 rad/s², τ ∈ ±30 N·m; rounded to f32.
fn random_state(model: &Model, rng: &mut Rng, q_max: f64, qd_max: f64) -> State {
    let n = model.dof();
    let f32_vec = |v: Vec<f64>| v.into_iter().map(|x| x as f32 as f64).collect::<Vec<f64>>();
    let mut q = rng.vec(n, q_max);
    for (i, b) in model.bodies.iter().enumerate() {
        if b.joint.kind == JointKind::Prismatic {
            q[i] = q[i] / q_max * 0.04;
        }
    }
    State {
        q: f32_vec(q),
        qd: f32_vec(rng.vec(n, qd_max)),
        qdd: f32_vec(rng.vec(n, 5.0)),
        tau: f32_vec(rng.vec(n, 30.0)),
    }
}

/// The states of the error measurement: `random` ordinary ones (|q| ≤ π,
/// |q̇| ≤ 2 rad/s), and `extreme` ones: the zero state, then fast ones
/// (|q̇| ≤ 100 rad/s) and wound-up ones (|q| ≤ 1e3 rad) in turn.
pub fn error_states(model: &Model, seed: u64, random: usize, extreme: usize) -> (Vec<State>, Vec<State>) {
    let mut rng = Rng::new(seed);
    let ordinary = (0..random).map(|_| random_state(model, &mut rng, std::f64::consts::PI, 2.0)).collect();
    let n = model.dof();
    let mut hard = vec![State { q: vec![0.0; n], qd: vec![0.0; n], qdd: vec![0.0; n], tau: vec![0.0; n] }];
    for k in 1..extreme {
        hard.push(if k % 2 == 1 {
            random_state(model, &mut rng, std::f64::consts::PI, 100.0)
        } else {
            random_state(model, &mut rng, 1e3, 2.0)
        });
    }
    (ordinary, hard)
}

/// A variant's result at a state, flattened (M row-major), as f64.
pub type Eval<'a> = Box<dyn FnMut(&State) -> Vec<f64> + 'a>;

/// One way of computing one function.
pub struct Variant<'a> {
    /// Its name (one of [`VARIANTS`]).
    pub name: &'static str,
    /// Its result at a state, flattened (M row-major), as f64.
    pub eval: Eval<'a>,
    /// Calls it `rounds` times on each of the timing states.
    pub run: Box<dyn FnMut(usize) + 'a>,
}

fn to_scalar<S: Scalar>(args: &[&[f64]]) -> Vec<Vec<S>> {
    args.iter().map(|v| v.iter().map(|&x| S::from_f64(x)).collect()).collect()
}

/// `f` by the generic algorithm on the scalar `S`, at `state`, as f64.
pub fn generic_eval<S: Scalar>(model: &Model, f: Func, state: &State) -> Vec<f64> {
    let kind = f;
    let n = model.dof();
    let mut ws = Workspace::<S>::new(model);
    let mut out = vec![S::zero(); kind.output_len(n)];
    kind.run(model, &mut ws, &to_scalar::<S>(&state.args(kind)), &Vec3::from_f64(&model.gravity), &mut out);
    out.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect()
}

/// The generic algorithm on `S` as a variant.
fn generic<'a, S: Scalar>(name: &'static str, model: &'a Model, f: Func, timing: &[State]) -> Variant<'a> {
    let kind = f;
    let n = model.dof();
    let inputs: Vec<Vec<Vec<S>>> = timing.iter().map(|s| to_scalar::<S>(&s.args(kind))).collect();
    let mut ws = Workspace::<S>::new(model);
    let mut out = vec![S::zero(); kind.output_len(n)];
    let gravity = Vec3::<S>::from_f64(&model.gravity);
    Variant {
        name,
        eval: Box::new(move |state| generic_eval::<S>(model, f, state)),
        run: Box::new(move |rounds| {
            for _ in 0..rounds {
                for args in &inputs {
                    kind.run(model, &mut ws, black_box(args), &gravity, &mut out);
                    black_box(&mut out);
                }
            }
        }),
    }
}

/// A state as the arrays a generated function takes, with the sines and
/// cosines of the joint angles (computed in f64 by std).
pub(crate) struct Arrays<T, const N: usize> {
    pub q: [T; N],
    pub qd: [T; N],
    pub qdd: [T; N],
    pub tau: [T; N],
    pub s: [T; N],
    pub c: [T; N],
}

impl<T: Scalar, const N: usize> Arrays<T, N> {
    pub(crate) fn new(state: &State, model: &Model) -> Self {
        let arr = |v: &[f64]| -> [T; N] { core::array::from_fn(|i| T::from_f64(v[i])) };
        let angle = |i: usize| {
            let j = &model.bodies[i].joint;
            if j.kind == JointKind::Prismatic {
                0.0
            } else {
                j.axis_norm * state.q[i]
            }
        };
        Arrays {
            q: arr(&state.q),
            qd: arr(&state.qd),
            qdd: arr(&state.qdd),
            tau: arr(&state.tau),
            s: core::array::from_fn(|i| T::from_f64(angle(i).sin())),
            c: core::array::from_fn(|i| T::from_f64(angle(i).cos())),
        }
    }
}

/// A generated function's result, flattened to f64.
pub(crate) trait Flatten {
    fn flat(&self) -> Vec<f64>;
}
impl<const N: usize> Flatten for [f64; N] {
    fn flat(&self) -> Vec<f64> {
        self.to_vec()
    }
}
impl<const N: usize> Flatten for [f32; N] {
    fn flat(&self) -> Vec<f64> {
        self.iter().map(|&x| x as f64).collect()
    }
}
impl<const N: usize> Flatten for [[f64; N]; N] {
    fn flat(&self) -> Vec<f64> {
        self.iter().flatten().copied().collect()
    }
}
impl<const N: usize> Flatten for [[f32; N]; N] {
    fn flat(&self) -> Vec<f64> {
        self.iter().flatten().map(|&x| x as f64).collect()
    }
}

/// A generated function as a variant: `$a` is the [`Arrays`] of the state
/// in `$call`.
macro_rules! generated_variant {
    ($name:expr, $t:ty, $n:expr, $model:expr, $timing:expr, |$a:ident| $call:expr) => {{
        let model: &Model = $model;
        let inputs: Vec<Arrays<$t, { $n }>> = $timing.iter().map(|s| Arrays::new(s, model)).collect();
        Variant {
            name: $name,
            eval: Box::new(move |state: &State| {
                let $a = Arrays::<$t, { $n }>::new(state, model);
                Flatten::flat(&$call)
            }),
            run: Box::new(move |rounds: usize| {
                for _ in 0..rounds {
                    for x in &inputs {
                        let $a = black_box(x);
                        black_box($call);
                    }
                }
            }),
        }
    }};
}
pub(crate) use generated_variant;

/// `fn $robot(f, model, timing) -> Vec<Variant>`: the generated variants of
/// one robot's function `f`.
macro_rules! generated_robot {
    ($robot:ident) => {
        pub(super) fn $robot<'a>(f: Func, model: &'a Model, timing: &[State]) -> Vec<Variant<'a>> {
            use generated::$robot as g;
            const N: usize = g::f64::DOF;
            let [v64, batched, sc, v32] = [VARIANTS[2], VARIANTS[3], VARIANTS[4], VARIANTS[5]];
            match f {
                Func::Tau => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64::inverse_dynamics(&a.q, &a.qd, &a.qdd)),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_batched::inverse_dynamics(
                        &a.q, &a.qd, &a.qdd
                    )),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::inverse_dynamics(
                        &a.s, &a.c, &a.q, &a.qd, &a.qdd
                    )),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32::inverse_dynamics(&a.q, &a.qd, &a.qdd)),
                ],
                Func::M => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64::mass_matrix(&a.q)),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_batched::mass_matrix(&a.q)),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::mass_matrix(&a.s, &a.c, &a.q)),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32::mass_matrix(&a.q)),
                ],
                Func::H => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64::bias_forces(&a.q, &a.qd)),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_batched::bias_forces(&a.q, &a.qd)),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::bias_forces(&a.s, &a.c, &a.q, &a.qd)),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32::bias_forces(&a.q, &a.qd)),
                ],
                Func::G => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64::gravity_torques(&a.q)),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_batched::gravity_torques(&a.q)),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::gravity_torques(&a.s, &a.c, &a.q)),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32::gravity_torques(&a.q)),
                ],
                Func::FdAba => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64::forward_dynamics(&a.q, &a.qd, &a.tau)),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_batched::forward_dynamics(
                        &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::forward_dynamics(
                        &a.s, &a.c, &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32::forward_dynamics(&a.q, &a.qd, &a.tau)),
                ],
                Func::FdLdlt => vec![
                    generated_variant!(v64, f64, N, model, timing, |a| g::f64_ldlt::forward_dynamics(
                        &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(batched, f64, N, model, timing, |a| g::f64_ldlt_batched::forward_dynamics(
                        &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(sc, f64, N, model, timing, |a| g::sc::forward_dynamics_ldlt(
                        &a.s, &a.c, &a.q, &a.qd, &a.tau
                    )),
                    generated_variant!(v32, f32, N, model, timing, |a| g::f32_ldlt::forward_dynamics(
                        &a.q, &a.qd, &a.tau
                    )),
                ],
            }
        }
    };
}

mod robots {
    use super::*;
    generated_robot!(ur5);
    generated_robot!(panda);
    generated_robot!(torso_two_arms);
    generated_robot!(planar_2link);
}

/// The generated variants of a bundled robot.
type GeneratedVariants = for<'a> fn(Func, &'a Model, &[State]) -> Vec<Variant<'a>>;

fn generated_variants(robot: &str) -> GeneratedVariants {
    match robot {
        "ur5" => robots::ur5,
        "panda" => robots::panda,
        "torso_two_arms" => robots::torso_two_arms,
        "planar_2link" => robots::planar_2link,
        other => unreachable!("no generated variants for {other}: add it to build.rs"),
    }
}

/// Every variant of `f` for the bundled `robot`, in the order of [`VARIANTS`].
pub fn variants<'a>(robot: &str, model: &'a Model, f: Func, timing: &[State]) -> Vec<Variant<'a>> {
    let mut v = vec![generic::<f64>(VARIANTS[0], model, f, timing), generic::<f32>(VARIANTS[1], model, f, timing)];
    v.extend(generated_variants(robot)(f, model, timing));
    v
}

/// ‖x − r‖₂ / ‖r‖₂; `None` when the reference is zero. A non-finite `x` gives NaN.
pub fn relative_error(x: &[f64], r: &[f64]) -> Option<f64> {
    assert_eq!(x.len(), r.len());
    let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm == 0.0 {
        return None;
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Some(f64::NAN);
    }
    Some(x.iter().zip(r).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt() / norm)
}

/// Median and maximum (NaN if any value is NaN); `None` for no values.
pub fn median_max(values: &[f64]) -> Option<(f64, f64)> {
    if values.is_empty() {
        return None;
    }
    if values.iter().any(|v| v.is_nan()) {
        return Some((f64::NAN, f64::NAN));
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let mid = v.len() / 2;
    let median = if v.len() % 2 == 1 { v[mid] } else { 0.5 * (v[mid - 1] + v[mid]) };
    Some((median, v[v.len() - 1]))
}

/// The errors of each variant (in `variants`' order) over `states`, against
/// the double-double reference on the file's robot, then those of the
/// double-double computation on the `f64` model (the model's rounding);
/// states where the reference is zero are left out.
pub fn errors(model: &Model, f: Func, variants: &mut [Variant], states: &[State]) -> Vec<Vec<f64>> {
    // The two forward dynamics have one exact answer: both are measured
    // against the double-double articulated-body algorithm.
    let reference_f = if f == Func::FdLdlt { Func::FdAba } else { f };
    let rounded = model.clone().without_file_values();
    let mut errs = vec![Vec::with_capacity(states.len()); variants.len() + 1];
    for state in states {
        let r = generic_eval::<DoubleDouble>(model, reference_f, state);
        let results = variants.iter_mut().map(|v| (v.eval)(state));
        let results = results.chain(std::iter::once(generic_eval::<DoubleDouble>(&rounded, reference_f, state)));
        for (x, e) in results.zip(&mut errs) {
            if let Some(x) = relative_error(&x, &r) {
                e.push(x);
            }
        }
    }
    errs
}

/// Time per call, in seconds.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    /// The median over the repetitions.
    pub median: f64,
    /// The minimum over the repetitions.
    pub min: f64,
}

/// Times each variant: `reps` repetitions, each running one batch of every
/// variant in turn (starting one further each repetition), a batch being
/// enough passes over the `states` timing states to take about `batch`.
pub fn time(variants: &mut [Variant], states: usize, reps: usize, batch: Duration) -> Vec<Timing> {
    let rounds: Vec<usize> = variants
        .iter_mut()
        .map(|v| {
            (v.run)(1);
            let one = (0..5)
                .map(|_| {
                    let t = Instant::now();
                    (v.run)(1);
                    t.elapsed()
                })
                .min()
                .unwrap_or_default();
            ((batch.as_secs_f64() / one.as_secs_f64().max(1e-9)).ceil() as usize).max(1)
        })
        .collect();
    let k = variants.len();
    let mut samples = vec![Vec::with_capacity(reps); k];
    for rep in 0..reps {
        for j in 0..k {
            let i = (rep + j) % k;
            let t = Instant::now();
            (variants[i].run)(rounds[i]);
            let dt = t.elapsed().as_secs_f64();
            samples[i].push(dt / (rounds[i] * states) as f64);
        }
    }
    samples
        .iter()
        .map(|s| {
            let (median, _) = median_max(s).unwrap_or((f64::NAN, f64::NAN));
            Timing { median, min: s.iter().copied().fold(f64::INFINITY, f64::min) }
        })
        .collect()
}

/// One row of a robot's table.
pub struct Row {
    /// The function.
    pub func: Func,
    /// The variant.
    pub variant: &'static str,
    /// Time per call.
    pub time: Timing,
    /// Errors on the random states.
    pub random: Vec<f64>,
    /// Errors on the extreme states.
    pub extreme: Vec<f64>,
}

impl Row {
    /// The largest error over all states (NaN if any is NaN).
    pub fn max_error(&self) -> f64 {
        median_max(&[&self.random[..], &self.extreme[..]].concat()).map_or(f64::NAN, |m| m.1)
    }
}

/// How many states and repetitions.
struct Sizes {
    random: usize,
    extreme: usize,
    timing: usize,
    reps: usize,
    batch: Duration,
}

fn sizes(quick: bool) -> Sizes {
    if quick {
        Sizes { random: 40, extreme: 21, timing: 8, reps: 15, batch: Duration::from_micros(5) }
    } else {
        Sizes { random: 4000, extreme: 2001, timing: 16, reps: 2001, batch: Duration::from_micros(25) }
    }
}

/// Measures every function and variant of one robot.
pub fn measure(report: &Report, robot: &str, model: &Model, quick: bool) -> Vec<Row> {
    let z = sizes(quick);
    let (random, extreme) = error_states(model, 0xd1a9 ^ model.dof() as u64, z.random, z.extreme);
    let mut timing_rng = Rng::new(0x7135);
    let timing: Vec<State> =
        (0..z.timing).map(|_| random_state(model, &mut timing_rng, std::f64::consts::PI, 2.0)).collect();
    let mut rows = Vec::new();
    for f in Func::ALL {
        report.progress(&format!("{robot}: {} ({} variants)", f.label(), VARIANTS.len()));
        let mut vs = variants(robot, model, f, &timing);
        let e_random = errors(model, f, &mut vs, &random);
        let e_extreme = errors(model, f, &mut vs, &extreme);
        let mut times = time(&mut vs, timing.len(), z.reps, z.batch);
        times.push(Timing { median: f64::NAN, min: f64::NAN });
        let names = vs.iter().map(|v| v.name).chain([MODEL_ROUNDING]);
        for (((name, t), r), e) in names.zip(times).zip(e_random).zip(e_extreme) {
            rows.push(Row { func: f, variant: name, time: t, random: r, extreme: e });
        }
    }
    rows
}

pub(crate) fn fmt_time(s: f64) -> String {
    let ns = s * 1e9;
    if !ns.is_finite() {
        "–".into()
    } else if ns < 10.0 {
        format!("{ns:.2}")
    } else if ns < 100.0 {
        format!("{ns:.1}")
    } else {
        format!("{ns:.0}")
    }
}

pub(crate) fn fmt_err(e: f64) -> String {
    if e.is_nan() {
        "NaN".into()
    } else if e == 0.0 {
        "0".into()
    } else {
        format!("{e:.1e}")
    }
}

pub(crate) fn fmt_stats(v: &[f64]) -> (String, String) {
    median_max(v).map_or(("–".into(), "–".into()), |(m, x)| (fmt_err(m), fmt_err(x)))
}

/// The Markdown table of one robot.
fn table(rows: &[Row]) -> String {
    let mut t = String::from(
        "| function | variant | median [ns] | min [ns] | vs generic f64 | error, random: median | random: max | extreme: median | extreme: max |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
    );
    for r in rows {
        let generic = rows.iter().find(|g| g.func == r.func && g.variant == VARIANTS[0]).map(|g| g.time.median);
        let speedup = generic
            .filter(|_| r.time.median.is_finite())
            .map_or("–".into(), |g| format!("{:.1}×", g / r.time.median));
        let (rm, rx) = fmt_stats(&r.random);
        let (em, ex) = fmt_stats(&r.extreme);
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} | {speedup} | {rm} | {rx} | {em} | {ex} |",
            r.func.label(),
            r.variant,
            fmt_time(r.time.median),
            fmt_time(r.time.min)
        );
    }
    t
}

/// The error-versus-time plot of one robot: one series per variant, one
/// point per function (labelled), y = the largest error over all states.
fn plot(report: &Report, robot: &str, rows: &[Row]) -> Result<String, String> {
    let (path, link) = report.plot_path(&format!("{robot}_error_vs_time.svg"));
    let series: Vec<(Series, Vec<String>)> = VARIANTS
        .iter()
        .map(|&v| {
            let mine: Vec<&Row> = rows.iter().filter(|r| r.variant == v).collect();
            let points = mine.iter().map(|r| (r.time.median, r.max_error())).collect();
            (Series::new(v, points), mine.iter().map(|r| r.func.short().to_string()).collect())
        })
        .collect();
    plot::scatter_loglog(
        &path,
        &format!("{robot}: largest error vs median time per call"),
        "median time per call [s]",
        "largest relative error vs double-double",
        &series,
    )?;
    Ok(link)
}

/// The section: every bundled robot.
pub fn run(report: &mut Report) {
    if env!("DYNAGEN_REPORT_PROFILE") != "release" {
        report.progress("warning: not an optimised build: the times mean nothing (use cargo run --release)");
    }
    let z = sizes(report.quick);
    let mut body = format!(
        "Every function of every bundled robot, computed each way dynagen can: the generic algorithms \
         (`dynagen::algorithms`, what `Robot` runs) in f64 and f32, and the code `dynagen::codegen` generates \
         in f64 — with std's `sin_cos` (`Trig::Std`), with the batched `sin_cos_all` (`Trig::Batched`, the \
         default, which the vendored `generated/` modules use), or with the sines and cosines passed in (`NAME_sc`, their \
         cost not counted) — and in f32. Forward dynamics appears twice: by the articulated-body algorithm \
         (`--aba`) and by CRBA + RNEA + sparse LᵀDL (`--ldlt`); by default the generator picks one per robot \
         (the module header says which).\n\n\
         **Time** per call: {reps} repetitions; in each, every variant of the function runs one batch \
         (≈ {batch} µs, passes over {timing} ordinary states), the variants in turn, so they share the \
         machine's state; median and minimum over the repetitions. Inputs go through `std::hint::black_box`. \
         On a shared machine the median carries the other processes' load (see the load average above); the \
         minimum is closer to what a quiet machine gives, and the ratios between variants, measured \
         interleaved, hold better than either.\n\n\
         **Error**: ‖x − x_ref‖₂ / ‖x_ref‖₂ (Frobenius for M) against the same algorithm run in \
         double-double (≈ 32 digits) on the robot as its URDF file defines it (rotations from rpy, unit \
         axes, inertias moved to body frames and fixed links merged, all in double-double from the file's \
         decimals), both forward dynamics against the double-double ABA. The row *{rounding}* is that \
         computation on the f64 model (each constant rounded to f64, as every f64 and f32 variant and the \
         generated code compute with it) against the file's robot: the part of each variant's error that is \
         the model's rounding, not its arithmetic. \
         *Random*: {random} states with |q| ≤ π, |q̇| ≤ 2 rad/s, |q̈| ≤ 5 rad/s², |τ| ≤ 30 N·m. \
         *Extreme*: {extreme} states: the zero state, then alternately |q̇| ≤ 100 rad/s and |q| ≤ 1e3 rad \
         (prismatic joints stay within ±4 cm). Every input is an f32 number, so f32 and f64 variants see the \
         same input and the f32 error is the computation's own. States where the reference is zero are left \
         out of that function's statistics.\n\n\
         Source: `report/src/error_vs_time.rs`; the generated variants are written by `report/build.rs`.\n\n",
        reps = z.reps,
        batch = z.batch.as_micros(),
        timing = z.timing,
        random = z.random,
        extreme = z.extreme,
        rounding = MODEL_ROUNDING,
    );
    let mut summary = String::from(
        "| robot | function | generic f64 [ns] | generated f64, default (`sin_cos_all`) [ns] | speed-up | \
         generated f32 [ns] | max error f64 gen. | max error f32 gen. |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
    );
    let mut details = String::new();
    let mut all: Vec<(&str, Vec<Row>)> = Vec::new();
    for robot in BUNDLED {
        let urdf = workspace_root().join(format!("dynagen/robots/{robot}.urdf"));
        let model = match Model::from_urdf_file(&urdf) {
            Ok(m) => m,
            Err(e) => {
                let _ = writeln!(details, "### {robot}\n\nnot measured: {}: {e}\n", urdf.display());
                continue;
            }
        };
        let rows = measure(report, robot, &model, report.quick);
        for f in Func::ALL {
            let get = |v: &str| rows.iter().find(|r| r.func == f && r.variant == v);
            // The generated f64 column is the default module's: the batched sines and cosines.
            if let (Some(g), Some(d), Some(d32)) = (get(VARIANTS[0]), get(VARIANTS[3]), get(VARIANTS[5])) {
                let _ = writeln!(
                    summary,
                    "| {robot} | {} | {} | {} | {:.1}× | {} | {} | {} |",
                    f.label(),
                    fmt_time(g.time.median),
                    fmt_time(d.time.median),
                    g.time.median / d.time.median,
                    fmt_time(d32.time.median),
                    fmt_err(d.max_error()),
                    fmt_err(d32.max_error()),
                );
            }
        }
        let _ = writeln!(details, "### {robot} ({} joints)\n\n{}", model.dof(), table(&rows));
        match plot(report, robot, &rows) {
            Ok(link) => {
                let _ = writeln!(details, "![{robot}: error versus time]({link})\n");
            }
            Err(e) => {
                let _ = writeln!(details, "(plot failed: {e})\n");
            }
        }
        all.push((robot, rows));
    }
    let _ = write!(
        body,
        "What this run shows (computed from the tables below):\n\n{}\n\
         Summary (median times; largest error over random and extreme states):\n\n{summary}\n{details}",
        observations(&all)
    );
    report.section("Error versus run time", &body);
}

/// The smallest and the largest of `values` (value, where), as text.
fn spread(values: &[(f64, String)], fmt: impl Fn(f64) -> String) -> String {
    let finite: Vec<&(f64, String)> = values.iter().filter(|v| v.0.is_finite()).collect();
    let lo = finite.iter().min_by(|a, b| a.0.total_cmp(&b.0));
    let hi = finite.iter().max_by(|a, b| a.0.total_cmp(&b.0));
    match (lo, hi) {
        (Some(lo), Some(hi)) => format!("{} ({}) to {} ({})", fmt(lo.0), lo.1, fmt(hi.0), hi.1),
        _ => "–".into(),
    }
}

/// Ratios of median times and the worst errors, across robots and functions.
fn observations(all: &[(&str, Vec<Row>)]) -> String {
    let find =
        |rows: &[Row], f: Func, v: &str| rows.iter().find(|r| r.func == f && r.variant == v).map(|r| r.time.median);
    let ratio = |num: &str, den: &str| -> Vec<(f64, String)> {
        all.iter()
            .flat_map(|(robot, rows)| {
                Func::ALL.iter().filter_map(move |&f| {
                    Some((find(rows, f, num)? / find(rows, f, den)?, format!("{robot} {}", f.short())))
                })
            })
            .collect()
    };
    let times = |x: f64| format!("{x:.1}×");
    let percent = |x: f64| format!("{:.0} %", 100.0 * x);
    let trig_share: Vec<(f64, String)> =
        ratio(VARIANTS[4], VARIANTS[2]).into_iter().map(|(r, w)| (1.0 - r, w)).collect();
    let worst = |pick: &dyn Fn(&str) -> bool| -> Vec<(f64, String)> {
        all.iter()
            .flat_map(|(robot, rows)| {
                rows.iter()
                    .filter(|r| pick(r.variant))
                    .map(move |r| (r.max_error(), format!("{robot} {}, {}", r.func.short(), r.variant)))
            })
            .collect()
    };
    let f32_worst = worst(&|v: &str| v.ends_with("f32"));
    let f64_worst = worst(&|v: &str| !v.ends_with("f32") && v != MODEL_ROUNDING);
    let rounding: Vec<(f64, String)> = all
        .iter()
        .flat_map(|(robot, rows)| {
            rows.iter()
                .filter(|r| r.variant == MODEL_ROUNDING)
                .map(move |r| (r.max_error(), format!("{robot} {}", r.func.short())))
        })
        .collect();
    let nan = all.iter().flat_map(|(_, rows)| rows).filter(|r| r.max_error().is_nan()).count();
    let ldlt_vs_aba: Vec<(f64, String)> = all
        .iter()
        .filter_map(|(robot, rows)| {
            Some((find(rows, Func::FdLdlt, VARIANTS[2])? / find(rows, Func::FdAba, VARIANTS[2])?, robot.to_string()))
        })
        .collect();
    format!(
        "- Generated f64 code (the default: batched sines and cosines) against the generic f64 algorithms: {} \
         faster.\n\
         - In the generated f64 code, std's `sin_cos` takes {} of the time (1 − time with the sines and cosines \
         given / time with std's).\n\
         - The batched `sin_cos_all` against std's `sin_cos`, whole function: {} the time.\n\
         - Generated f32 against generated f64: {} the time.\n\
         - Forward dynamics, generated f64, CRBA + LTDL against ABA: {} the time.\n\
         - Largest error of any f64 variant: {}; of any f32 variant: {}; non-finite results: {nan}.\n\
         - The model's rounding alone (the f64 model computed in double-double, against the file's robot): \
         {}; against the same reference, the f64 variants' errors above are their arithmetic plus this.\n",
        spread(&ratio(VARIANTS[0], VARIANTS[3]), times),
        spread(&trig_share, percent),
        spread(&ratio(VARIANTS[3], VARIANTS[2]), times),
        spread(&ratio(VARIANTS[5], VARIANTS[2]), times),
        spread(&ldlt_vs_aba, times),
        spread(&f64_worst, fmt_err).split(" to ").last().unwrap_or("–"),
        spread(&f32_worst, fmt_err).split(" to ").last().unwrap_or("–"),
        spread(&rounding, fmt_err),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The planar two-link arm: the f64 variants agree with the double-double
    /// reference to a few ulps, the f32 ones to f32 precision (and no better,
    /// which they could only if they secretly computed in f64).
    #[test]
    fn errors_of_the_planar_arm_are_those_of_each_precision() {
        let model = Model::from_urdf_file(workspace_root().join("dynagen/robots/planar_2link.urdf")).unwrap();
        let (random, extreme) = error_states(&model, 7, 20, 7);
        let states = [random, extreme].concat();
        for f in Func::ALL {
            let mut vs = variants("planar_2link", &model, f, &states[..2]);
            assert_eq!(vs.iter().map(|v| v.name).collect::<Vec<_>>(), VARIANTS);
            let errs = errors(&model, f, &mut vs, &states);
            assert_eq!(errs.len(), VARIANTS.len() + 1, "the variants and the model's rounding");
            let (median, max) = median_max(&errs[VARIANTS.len()]).unwrap();
            assert!(max < 1e-14 && median > 1e-20, "{f:?}: the model's rounding, median {median:e}, max {max:e}");
            for (name, e) in VARIANTS.iter().zip(&errs) {
                assert!(e.len() >= states.len() - 1, "{f:?} {name}: only {} states measured", e.len());
                let (median, max) = median_max(e).unwrap();
                if name.ends_with("f32") {
                    assert!(max < 1e-4 && median > 1e-9, "{f:?} {name}: median {median:e}, max {max:e}");
                } else {
                    assert!(max <= 1e-13, "{f:?} {name}: max {max:e}");
                }
            }
            // The timing closure runs (one pass; no timing asserted).
            for v in &mut vs {
                (v.run)(1);
            }
        }
    }

    #[test]
    fn relative_error_and_statistics() {
        assert_eq!(relative_error(&[3.0, 4.0], &[0.0, 0.0]), None);
        assert_eq!(relative_error(&[3.0, 5.0], &[3.0, 4.0]), Some(0.2));
        assert!(relative_error(&[f64::INFINITY, 4.0], &[3.0, 4.0]).unwrap().is_nan());
        assert_eq!(median_max(&[3.0, 1.0, 2.0, 10.0]), Some((2.5, 10.0)));
        assert!(median_max(&[1.0, f64::NAN]).unwrap().1.is_nan());
        assert_eq!(median_max(&[]), None);
    }
}
