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
//! The crate is `#![no_std]`. The generated code computes sines and cosines
//! with `f64::sin_cos`, which lives in `std`, so the robot modules need the
//! `std` feature (on by default); without it the crate is empty. A no_std
//! emission (sines and cosines from `libm`, or as inputs) is planned in the
//! generator; these modules will use it then.
#![no_std]

#[cfg(feature = "std")]
extern crate std;

/// The Universal Robots UR5 (6 revolute joints).
#[cfg(feature = "std")]
#[rustfmt::skip]
pub mod ur5;

/// The Franka Emika Panda (7 revolute joints and 2 prismatic fingers).
#[cfg(feature = "std")]
#[rustfmt::skip]
pub mod panda;

/// A torso with two arms (a branched tree).
#[cfg(feature = "std")]
#[rustfmt::skip]
pub mod torso_two_arms;

/// A planar two-link arm (the textbook closed form is in dynagen's tests).
#[cfg(feature = "std")]
#[rustfmt::skip]
pub mod planar_2link;
