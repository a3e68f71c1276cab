//! Shared helpers of the integration tests in `tests/tests/` (and of the
//! tests of `tests/no-std-check`): a small deterministic random generator,
//! the bundled robots, robot families for stiff and extreme cases, and
//! the error measures (`dynagen/tests/support/measure.rs`).

use dynagen::model::{Inertial, JointDescription, RobotBuilder};
use dynagen::scene::Scene;
use dynagen::Model;

pub mod suite;

/// A small deterministic generator (SplitMix64), so that every test run sees
/// the same states without a dependency.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    /// A uniform integer.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A vector of `n` values uniform in [-a, a).
    pub fn vec(&mut self, n: usize, a: f64) -> Vec<f64> {
        (0..n).map(|_| self.range(-a, a)).collect()
    }
    /// A random unit vector.
    pub fn unit_vector(&mut self) -> [f64; 3] {
        loop {
            let v = [self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.range(-1.0, 1.0)];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.1 && n <= 1.0 {
                return [v[0] / n, v[1] / n, v[2] / n];
            }
        }
    }
}

/// One link of a serial chain.
#[derive(Clone, Copy, Debug)]
pub struct LinkSpec {
    /// Mass (kg).
    pub mass: f64,
    /// Length (m): the next joint sits this far along the link.
    pub length: f64,
    /// The joint axis (unit) in the joint frame.
    pub axis: [f64; 3],
    /// Whether the joint is prismatic.
    pub prismatic: bool,
}

/// A serial chain of the given links: each link a slender body whose centre
/// of mass is half-way to the next joint, with a solid-rod inertia and a
/// small transverse thickness (10% of the length), so every inertia is
/// physical.
pub fn chain(name: &str, links: &[LinkSpec]) -> Model {
    let mut b = RobotBuilder::new(name).link("base", None);
    let mut parent = "base".to_string();
    let mut offset = 0.1;
    for (i, l) in links.iter().enumerate() {
        let child = format!("link{i}");
        let (m, len) = (l.mass, l.length);
        let r = 0.1 * len;
        let axial = 0.5 * m * r * r;
        let trans = m * (3.0 * r * r + len * len) / 12.0;
        b = b.link(&child, Some(Inertial::new(m, [0.0, 0.0, 0.5 * len], [trans, trans, axial, 0.0, 0.0, 0.0])));
        let j = if l.prismatic {
            JointDescription::prismatic(&format!("joint{i}"), &parent, &child, l.axis)
        } else {
            JointDescription::revolute(&format!("joint{i}"), &parent, &child, l.axis)
        };
        b = b.joint(j.origin([0.0, 0.0, offset], [0.0, 0.0, 0.0]));
        offset = len;
        parent = child;
    }
    b.build().expect("a chain of physical links is a valid model")
}

// The error measures, one file shared with dynagen's own integration tests.
#[path = "../../dynagen/tests/support/measure.rs"]
mod measure;
pub use measure::{norm_rel_err, rel_err, scale};

/// The bundled robots vendored in `generated/` (each `dynagen/robots/<name>.urdf`
/// → `generated/src/<name>.rs`).
pub const BUNDLED: [&str; 4] = ["ur5", "panda", "torso_two_arms", "planar_2link"];

/// The command that rewrites `generated/src/*.rs` from the bundled robots.
pub const REGENERATE_COMMAND: &str = "cargo run -p dynagen-tests --bin regenerate";

/// Scales a floating-base configuration's quaternion, `q[3..7]`, to unit
/// norm.
pub fn normalize_quaternion(q: &mut [f64]) {
    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
    q[3..7].iter_mut().for_each(|x| *x /= norm);
}

/// The workspace's root folder.
pub fn workspace_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("tests/ is in the workspace").to_path_buf()
}

/// The module of the bundled robot `name` as `generated/src/<name>.rs` must
/// hold it: the default options, the source named relative to the workspace
/// root so the file does not depend on where the workspace is.
pub fn bundled_module(name: &str) -> Result<String, dynagen::codegen::BuildError> {
    let rel = format!("dynagen/robots/{name}.urdf");
    // Batched sines and cosines (the module's own sin_cos_all): no_std and no
    // dependency, as the vendored crate promises.
    let options = dynagen::codegen::CodegenOptions::default().source(rel.clone()).trig(dynagen::codegen::Trig::Batched);
    let module = dynagen::Builder::new().urdf(workspace_root().join(&rel)).options(options).generate_module()?;
    Ok(module.source)
}

/// Forward dynamics by the articulated-body algorithm in double-double
/// (the reference), under the model's gravity, from `f64` inputs.
pub fn reference_forward_dynamics(model: &Model, q: &[f64], qd: &[f64], tau: &[f64]) -> Vec<f64> {
    use dynagen::algorithms::{aba, Loads, Workspace};
    use dynagen::DoubleDouble;
    let c = |x: &[f64]| x.iter().map(|&v| DoubleDouble::from(v)).collect::<Vec<_>>();
    let mut ws = Workspace::<DoubleDouble>::new(model);
    let g = dynagen::spatial::Vec3::<DoubleDouble>::from_f64(&model.gravity);
    let mut out = vec![DoubleDouble::ZERO; model.dof()];
    aba::aba(model, &mut ws, &c(q), &c(qd), &c(tau), Loads::gravity(&g), &mut out);
    out.iter().map(|x| x.to_f64()).collect()
}

/// A state where τ nearly balances the bias forces: random q (in ±`q_scale`)
/// and q̇ (in ±`qd_scale`), and τ = h(q, q̇) + M(q)·q̈ for a small random q̈
/// (in ±`qdd_scale`), computed in double-double and rounded once, so that
/// τ − h cancels to ‖M q̈‖ ≪ ‖h‖. Returns (q, q̇, τ).
pub fn cancelling_state(
    model: &Model,
    rng: &mut Rng,
    q_scale: f64,
    qd_scale: f64,
    qdd_scale: f64,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    use dynagen::algorithms::{rnea, Loads, Workspace};
    use dynagen::DoubleDouble;
    let n = model.dof();
    let (q, qd, qdd) = (rng.vec(n, q_scale), rng.vec(n, qd_scale), rng.vec(n, qdd_scale));
    let c = |x: &[f64]| x.iter().map(|&v| DoubleDouble::from(v)).collect::<Vec<_>>();
    let mut ws = Workspace::<DoubleDouble>::new(model);
    let g = dynagen::spatial::Vec3::<DoubleDouble>::from_f64(&model.gravity);
    let mut tau = vec![DoubleDouble::ZERO; n];
    rnea::rnea(model, &mut ws, &c(&q), Some(&c(&qd)), Some(&c(&qdd)), Loads::gravity(&g), &mut tau);
    let tau = tau.iter().map(|x| x.to_f64()).collect();
    (q, qd, tau)
}

/// A bundled robot's URDF file, `dynagen/robots/<name>.urdf`.
pub fn bundled_urdf(name: &str) -> std::path::PathBuf {
    workspace_root().join(format!("dynagen/robots/{name}.urdf"))
}

/// A bundled robot's model (`dynagen/robots/<name>.urdf`).
pub fn bundled_model(name: &str) -> Model {
    Model::from_urdf_file(bundled_urdf(name)).expect("a bundled robot")
}

/// A bundled robot for the generic solver.
pub fn bundled_robot(name: &str) -> dynagen::Robot {
    dynagen::Robot::from_urdf_file(bundled_urdf(name)).expect("a bundled robot")
}

/// A bundled scene's file, `dynagen/scenes/<name>.toml`.
pub fn bundled_scene(name: &str) -> std::path::PathBuf {
    workspace_root().join(format!("dynagen/scenes/{name}.toml"))
}

/// A chain of `n` links with random unit axes (every fifth joint prismatic),
/// masses `mass(i)` and lengths `length(i)`.
pub fn random_axes(
    rng: &mut Rng,
    n: usize,
    mass: impl Fn(usize) -> f64,
    length: impl Fn(usize) -> f64,
) -> Vec<LinkSpec> {
    (0..n)
        .map(|i| LinkSpec { mass: mass(i), length: length(i), axis: rng.unit_vector(), prismatic: i % 5 == 4 })
        .collect()
}

/// Masses (kg) of [`stiff_chain`]'s links: neighbours differ by up to 1e6.
pub const STIFF_MASSES: [f64; 8] = [1e3, 1e-3, 1.0, 1e2, 1e-2, 1.0, 1e-1, 10.0];
/// Lengths (m) of [`stiff_chain`]'s links.
pub const STIFF_LENGTHS: [f64; 8] = [1.0, 0.01, 0.3, 2.0, 0.05, 0.5, 0.1, 1.0];

/// An 8-joint chain with random axes, [`STIFF_MASSES`] and [`STIFF_LENGTHS`]:
/// a stiff robot (a 1 g link after a 1 t one) for the compensated forward
/// dynamics comparisons.
pub fn stiff_chain() -> Model {
    let mut rng = Rng::new(9);
    chain("stiff_chain", &random_axes(&mut rng, 8, |i| STIFF_MASSES[i], |i| STIFF_LENGTHS[i]))
}

/// One robot of the stiff and extreme suite (`tests/tests/stiff_extreme.rs`),
/// shared with `build.rs` (which generates code for some) and the report.
#[derive(Clone, Debug)]
pub struct StiffCase {
    /// What is extreme about it.
    pub title: &'static str,
    /// The robot.
    pub model: Model,
    /// Joint positions are drawn in ±`q_scale` (rad or m).
    pub q_scale: f64,
    /// Joint velocities are drawn in ±`qd_scale` (rad/s or m/s).
    pub qd_scale: f64,
}

/// The names of the suite's cases, for [`stiff_case`].
pub const STIFF_CASES: [&str; 10] = [
    "ordinary",
    "mass_ratios",
    "lengths",
    "fast",
    "wound",
    "long64",
    "dependent",
    "aligned_mass_ratios",
    "aligned_lengths",
    "mixed10",
];

/// The cases `build.rs` generates code for (`OUT_DIR/stiff_<name>.rs`). Their
/// joint axes lie along coordinate axes, as in most robot descriptions: with
/// random axes the generated forward dynamics of a 7-joint chain has ~3,600
/// `let` statements in one function, which overflows rustc's default 8 MB
/// stack in a debug build; and not the 64-joint chain (compile time).
pub const STIFF_GENERATED: [&str; 3] = ["aligned_mass_ratios", "aligned_lengths", "mixed10"];

/// A chain of `n` links whose joint axes cycle through z, y, x, −y, and
/// every fifth joint is prismatic.
pub fn aligned_axes(n: usize, mass: impl Fn(usize) -> f64, length: impl Fn(usize) -> f64) -> Vec<LinkSpec> {
    let axes = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]];
    (0..n).map(|i| LinkSpec { mass: mass(i), length: length(i), axis: axes[i % 4], prismatic: i % 5 == 4 }).collect()
}

/// The suite's case `name` (one of [`STIFF_CASES`]).
///
/// # Panics
/// For another name.
pub fn stiff_case(name: &str) -> StiffCase {
    let case = |title, model, q_scale, qd_scale| StiffCase { title, model, q_scale, qd_scale };
    match name {
        "ordinary" => {
            let links = random_axes(&mut Rng::new(1), 7, |_| 2.0, |_| 0.3);
            case("ordinary 7-link chain", chain(name, &links), 3.0, 2.0)
        }
        "mass_ratios" => {
            // Heavy to light: 1e6 kg down to 1e-6 kg, a ratio of 1e6 each
            // step, then alternating 1e-3 / 1e3 (a ratio of 1e6 the other way too).
            let masses = [1e6, 1.0, 1e-6, 1e-3, 1e3, 1e-3, 1e3];
            let links = random_axes(&mut Rng::new(2), masses.len(), |i| masses[i], |_| 0.5);
            case("mass ratios 1e-6..1e6", chain(name, &links), 3.0, 2.0)
        }
        "lengths" => {
            let lengths = [1e2, 1e-3, 1.0, 1e-3, 1e2, 0.1, 1e-3];
            let links = random_axes(&mut Rng::new(3), lengths.len(), |_| 1.0, |i| lengths[i]);
            case("lengths 1e-3..1e2 m", chain(name, &links), 3.0, 2.0)
        }
        "fast" | "wound" => {
            let links = random_axes(&mut Rng::new(4), 6, |_| 1.5, |_| 0.4);
            if name == "fast" {
                case("|qd| up to 1e3 rad/s", chain(name, &links), 3.0, 1e3)
            } else {
                case("|q| up to 1e4 rad", chain(name, &links), 1e4, 2.0)
            }
        }
        "aligned_mass_ratios" => {
            let masses = [1e6, 1.0, 1e-6, 1e-3, 1e3, 1e-3, 1e3];
            let links = aligned_axes(masses.len(), |i| masses[i], |_| 0.5);
            case("mass ratios 1e-6..1e6, aligned axes", chain(name, &links), 3.0, 2.0)
        }
        "aligned_lengths" => {
            let lengths = [1e2, 1e-3, 1.0, 1e-3, 1e2, 0.1, 1e-3];
            let links = aligned_axes(lengths.len(), |_| 1.0, |i| lengths[i]);
            case("lengths 1e-3..1e2 m, aligned axes", chain(name, &links), 3.0, 2.0)
        }
        "mixed10" => {
            // Ten joints: masses and lengths both swing by 1e3..1e6 between
            // neighbours, at speeds up to 100 rad/s.
            let masses = [1e3, 1e-3, 1.0, 1e2, 1e-4, 10.0, 1e-2, 1e2, 1e-3, 1.0];
            let lengths = [2.0, 1e-3, 0.5, 1e2, 1e-2, 1.0, 1e-3, 0.3, 10.0, 0.05];
            let links = aligned_axes(10, |i| masses[i], |i| lengths[i]);
            case("10 joints, mixed masses and lengths", chain(name, &links), 3.0, 100.0)
        }
        "long64" => {
            let links = random_axes(&mut Rng::new(5), 64, |_| 1.0, |_| 0.1);
            case("64-joint chain", chain(name, &links), 3.0, 2.0)
        }
        "dependent" => {
            // Two joints at the same point with axes 1e-5 rad apart: M is
            // nearly singular (cond ≈ 1e10).
            let eps: f64 = 1e-5;
            let spec = |axis| LinkSpec { mass: 1.0, length: 0.5, axis, prismatic: false };
            let mut links = vec![
                spec([0.0, 0.0, 1.0]),
                spec([eps.sin(), 0.0, eps.cos()]),
                spec([0.0, 1.0, 0.0]),
                spec([1.0, 0.0, 0.0]),
            ];
            links[0].length = 0.0;
            case("axes 1e-5 rad apart", chain(name, &links), 3.0, 2.0)
        }
        other => panic!("no stiff case named {other}"),
    }
}

/// The quadruped's motors (`quadruped12.urdf`): the rotor's armature on
/// every joint, a little different on each leg (so that the legs' lanes
/// hold their own values), and viscous and Coulomb friction.
pub fn quadruped_motors_scene() -> Scene {
    let mut scene = Scene::new();
    for (k, leg) in ["FR", "FL", "RR", "RL"].into_iter().enumerate() {
        for (j, part) in ["hip", "thigh", "calf"].into_iter().enumerate() {
            let joint = format!("{leg}_{part}_joint");
            scene = scene
                .armature(&joint, 0.01 + 0.004 * j as f64 + 0.001 * k as f64)
                .viscous(&joint, 0.05 + 0.01 * j as f64)
                .coulomb(&joint, 0.3 + 0.1 * k as f64);
        }
    }
    scene
}
