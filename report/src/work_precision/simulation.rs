//! Simulation work-precision: each integrator over a sweep of step sizes on
//! an ordinary scene and a stiff one; the final state's error against a
//! reference trajectory versus the wall time of the run.

use crate::plot::{loglog, Series};
use crate::report::Report;
use dynagen::algorithms::integrators::{step_with, Integrator, IntegratorScratch};
use dynagen::algorithms::{aba, Loads, Workspace};
use dynagen::Model;
use std::fmt::Write as _;
use std::time::Instant;

/// A simulation scene: a robot, a time span, an initial state and a joint
/// spring-damper τ = −k(q − q_rest) − d·q̇ applied in the simulation loop
/// (k = d = 0: no spring).
pub(super) struct Scene {
    pub name: &'static str,
    pub title: &'static str,
    pub model: Model,
    pub span: f64,
    pub q0: Vec<f64>,
    pub qd0: Vec<f64>,
    pub q_rest: Vec<f64>,
    pub k: f64,
    pub d: f64,
    /// Numbers of steps of the sweep.
    pub steps: Vec<usize>,
    /// Steps of the reference (RK4).
    pub reference_steps: usize,
}

/// The integrators compared, with their names in the report.
pub(super) const INTEGRATORS: [(Integrator, &str); 4] = [
    (Integrator::Euler, "Euler (MR EulerStep)"),
    (Integrator::SemiImplicitEuler, "semi-implicit Euler"),
    (Integrator::Rk4, "RK4"),
    (Integrator::ImplicitEuler, "implicit Euler (Newton, FD Jacobian)"),
];

/// Runs `scene` with `integrator` in `steps` equal steps; the final (q, q̇).
fn simulate(scene: &Scene, integrator: Integrator, steps: usize) -> Vec<f64> {
    let model = &scene.model;
    let n = model.dof();
    let mut ws = Workspace::<f64>::new(model);
    let mut scratch = IntegratorScratch::<f64>::new(model);
    let (mut q, mut qd) = (scene.q0.clone(), scene.qd0.clone());
    let mut tau = vec![0.0; n];
    let g = model.gravity;
    let dt = scene.span / steps as f64;
    for _ in 0..steps {
        step_with(integrator, &mut scratch, dt, &mut q, &mut qd, |q, qd, qdd| {
            for i in 0..n {
                tau[i] = -scene.k * (q[i] - scene.q_rest[i]) - scene.d * qd[i];
            }
            aba::aba(model, &mut ws, q, qd, &tau, Loads::gravity(&g), qdd);
        });
    }
    q.extend_from_slice(&qd);
    q
}

/// One run of the sweep.
pub(super) struct Run {
    pub integrator: &'static str,
    pub steps: usize,
    pub dt: f64,
    /// max |x − x_ref| / max |x_ref| over x = (q, q̇) at the end (∞ if not finite).
    pub error: f64,
    /// Wall time of one run (s): the fastest of a few repetitions.
    pub time: f64,
    pub unstable: bool,
}

/// Runs the sweep of one scene.
pub(super) fn sweep(scene: &Scene, report: &Report) -> Vec<Run> {
    report.progress(&format!("work-precision: {} reference ({} RK4 steps)", scene.name, scene.reference_steps));
    let reference = simulate(scene, Integrator::Rk4, scene.reference_steps);
    let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut runs = Vec::new();
    for (integrator, name) in INTEGRATORS {
        report.progress(&format!("work-precision: {} {name}", scene.name));
        for &steps in &scene.steps {
            // Repeat short runs so the time is not all timer noise.
            let (mut best, mut total, mut reps) = (f64::INFINITY, 0.0, 0);
            let mut x = Vec::new();
            while reps < 3 || (total < if report.quick { 2e-3 } else { 2e-2 } && reps < 1000) {
                let t = Instant::now();
                x = simulate(scene, integrator, steps);
                let e = t.elapsed().as_secs_f64();
                best = best.min(e);
                total += e;
                reps += 1;
            }
            let finite = x.iter().all(|v| v.is_finite());
            let diff = x.iter().zip(&reference).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            let error = if finite { diff / scale } else { f64::INFINITY };
            let size = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            runs.push(Run {
                integrator: name,
                steps,
                dt: scene.span / steps as f64,
                error,
                time: best,
                // Blown up: not finite, or ten times larger than the reference state.
                unstable: !finite || size > 10.0 * scale,
            });
        }
    }
    runs
}

/// The ordinary and the stiff scene.
pub(super) fn scenes(quick: bool) -> Vec<Scene> {
    let ur5 = dynagen_tests::bundled_model("ur5");
    let q0 = vec![0.3, -1.0, 1.2, -0.5, 0.8, 0.2];
    let qd0 = vec![0.5, -0.3, 0.4, 1.0, -0.6, 0.8];
    let pow2 = |from: u32, to: u32, base: usize| (from..=to).map(|k| base << k).collect::<Vec<_>>();
    vec![
        Scene {
            name: "ur5",
            title: "UR5 swinging under gravity (τ = 0), 1 s",
            model: ur5.clone(),
            span: 1.0,
            q0: q0.clone(),
            qd0: qd0.clone(),
            q_rest: vec![0.0; 6],
            k: 0.0,
            d: 0.0,
            steps: if quick { pow2(0, 6, 16) } else { pow2(0, 9, 16) },
            reference_steps: if quick { 1 << 13 } else { 1 << 16 },
        },
        Scene {
            name: "ur5_stiff_springs",
            title: "UR5 with stiff joint springs and dampers (k = 1e5 N·m/rad, d = 2e3 N·m·s/rad), 0.2 s",
            model: ur5,
            span: 0.2,
            q_rest: q0.iter().map(|x| x + 0.1).collect(),
            q0,
            qd0,
            k: 1e5,
            d: 2e3,
            steps: if quick { pow2(0, 7, 20) } else { pow2(0, 10, 20) },
            reference_steps: if quick { 1 << 15 } else { 1 << 17 },
        },
    ]
}

/// Writes the section: one plot and one table per scene.
pub fn run(report: &mut Report) {
    let mut body = String::from(
        "Each integrator of `dynagen::algorithms::integrators` simulates a fixed time span in N equal steps, for a \
         sweep of N; the error is max |x − x_ref| / max |x_ref| over the final state x = (q, q̇), against RK4 with \
         a far smaller step (the reference); the time is the wall time of the whole run (the fastest of a few \
         repetitions). Unstable runs (a final state that is not finite or ten times larger than the reference's) \
         are marked with crosses (drawn at error 1) and in the tables; a stable run can still be \
         inaccurate (an error near 1: implicit Euler damps the oscillations it does not resolve). The implicit Euler step solves its Newton system with a Jacobian of the dynamics by \
         forward differences (n + 1 forward dynamics per step, then one per iteration).\n\n\
         The stiff scene's springs τ = −k(q − q_rest) − d·q̇ on every joint are part of the simulation loop \
         (the acceleration function passed to `integrators::step_with`), not of the robot model: the bundled \
         robots have no springs. The dampers make every joint overdamped: the state relaxes smoothly towards \
         q_rest (rates k/d = 50 1/s) while the fastest mode decays at d/I ≈ 7e4 1/s at the UR5's wrist, so the \
         explicit schemes need dt ≲ 3e-5 s (Euler) or 4e-5 s (RK4) to stay stable, and implicit Euler does not.\n\n",
    );
    for scene in scenes(report.quick) {
        let runs = sweep(&scene, report);
        let mut series = Vec::new();
        for (_, name) in INTEGRATORS {
            let mine: Vec<&Run> = runs.iter().filter(|r| r.integrator == name).collect();
            let mut s =
                Series::new(name, mine.iter().filter(|r| !r.unstable).map(|r| (r.time, r.error)).collect::<Vec<_>>());
            s.marked = mine.iter().filter(|r| r.unstable).map(|r| (r.time, 1.0)).collect();
            // Stable but inaccurate runs are drawn too (errors above 1 as 1).
            series.push(s);
        }
        let file = format!("work_precision_{}.svg", scene.name);
        let (path, link) = report.plot_path(&file);
        if let Err(e) = loglog(&path, scene.title, "wall time of the run [s]", "final-state error (relative)", &series)
        {
            report.progress(&format!("plot failed: {e}"));
        }
        let _ = write!(
            body,
            "### {}\n\nReference: RK4 with {} steps. Robot: `{}` ({} joints).\n\n![{}]({link})\n\n\
             | integrator | N | dt [s] | error | time [ms] | |\n| --- | --- | --- | --- | --- | --- |\n",
            scene.title,
            scene.reference_steps,
            scene.model.name,
            scene.model.dof(),
            scene.title
        );
        for r in &runs {
            let _ = writeln!(
                body,
                "| {} | {} | {:.2e} | {:.2e} | {:.3} | {} |",
                r.integrator,
                r.steps,
                r.dt,
                r.error,
                r.time * 1e3,
                if r.unstable { "**unstable**" } else { "" }
            );
        }
        body.push('\n');
    }
    report.section("Simulation: work versus precision", &body);
}
