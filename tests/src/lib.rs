//! Shared helpers of the integration tests in `tests/tests/`: a small
//! deterministic random generator, robot families for stiff and extreme
//! cases, and error measures.

use dynagen::model::{Inertial, JointDescription, RobotBuilder};
use dynagen::Model;

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

/// max |a − b| over max(max |b|, floor): an error relative to the
/// reference's scale.
pub fn rel_err(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(floor, |m, x| m.max(x.abs()));
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

/// The bundled robots vendored in `generated/` (each `dynagen/robots/<name>.urdf`
/// → `generated/src/<name>.rs`).
pub const BUNDLED: [&str; 4] = ["ur5", "panda", "torso_two_arms", "planar_2link"];

/// The command that rewrites `generated/src/*.rs` from the bundled robots.
pub const REGENERATE_COMMAND: &str = "cargo run -p dynagen-tests --bin regenerate";

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
