//! What dynagen's integration tests share: a deterministic random
//! generator, the error measures `approx` does not provide ([`measure`]),
//! the bundled robots and scenes, and the skewed chain. A test file takes it with
//! `mod support;` (each test file is its own crate, so what one file does
//! not use is dead code there: allowed).
#![allow(dead_code)]

pub mod measure;
pub mod skewed_chain;

// Under their short names for the test files (each a crate of its own,
// most of which use one or none of them).
#[allow(unused_imports)]
pub use measure::{norm_rel_err, rel_err, scale};

use dynagen::{Model, Robot};
use std::path::PathBuf;

/// Scales a floating-base configuration's quaternion, `q[3..7]`, to unit
/// norm.
pub fn normalize_quaternion(q: &mut [f64]) {
    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
    q[3..7].iter_mut().for_each(|x| *x /= norm);
}

/// A small deterministic generator (xorshift64*), so that every run sees
/// the same states without a dependency.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a (non-zero) seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    /// 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [−1, 1).
    pub fn signed(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    /// `n` values uniform in [−`scale`, `scale`).
    pub fn vec(&mut self, n: usize, scale: f64) -> Vec<f64> {
        (0..n).map(|_| scale * self.signed()).collect()
    }
}

/// The folder of the bundled robots, `dynagen/robots`.
pub const ROBOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/robots");

/// The URDF file of the bundled robot `name` (`dynagen/robots/<name>.urdf`).
pub fn robot_path(name: &str) -> PathBuf {
    PathBuf::from(ROBOTS).join(format!("{name}.urdf"))
}

/// The model of the bundled robot `name`.
pub fn model(name: &str) -> Model {
    Model::from_urdf_file(robot_path(name)).unwrap_or_else(|e| panic!("the bundled robot {name}: {e}"))
}

/// The bundled robot `name`, for the generic solver.
pub fn robot(name: &str) -> Robot {
    Robot::from_urdf_file(robot_path(name)).unwrap_or_else(|e| panic!("the bundled robot {name}: {e}"))
}

/// The bundled scene `name` (`dynagen/scenes/<name>.toml`).
pub fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"))
}
