//! Generated dynamics of dynagen's bundled robots: `no_std`, no
//! dependencies, nothing allocated.
//!
//! Each module (`ur5`, `panda`, `torso_two_arms`, `planar_2link`) is the
//! output of dynagen's code generator for `dynagen/robots/<robot>.urdf` with
//! the default options, committed as `src/<robot>.rs`: `DOF`,
//! `JOINT_NAMES`, `inverse_dynamics`, `mass_matrix`, `bias_forces`,
//! `gravity_torques` and `forward_dynamics` on `f64` arrays.
//!
//! Regenerate them after changing the generator or a robot with
//!
//! ```text
//! cargo run -p dynagen-tests --bin regenerate
//! ```
//!
//! (a test in `tests/` fails, naming that command, when a committed file is
//! stale). The files are the generator's output byte for byte, so
//! `rustfmt` is told to skip them (`#[rustfmt::skip]` on each `mod`).
//!
//! # `no_std`
//!
//! The crate is `#![no_std]` with no dependency: the modules are generated
//! with `Trig::Batched`, so their sines and cosines come from each module's
//! own `sin_cos_all` (within 1 ulp, like libm). Each function also has a
//! `NAME_sc` form that takes the sines and cosines, for a controller that
//! already has them.
#![no_std]

/// The Universal Robots UR5 (6 revolute joints).
#[rustfmt::skip]
pub mod ur5;

/// The Franka Emika Panda (7 revolute joints and 2 prismatic fingers).
#[rustfmt::skip]
pub mod panda;

/// A torso with two arms (a branched tree).
#[rustfmt::skip]
pub mod torso_two_arms;

/// A planar two-link arm (the textbook closed form is in dynagen's tests).
#[rustfmt::skip]
pub mod planar_2link;
