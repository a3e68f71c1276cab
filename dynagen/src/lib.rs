//! dynagen: a dynamics compiler for robots.
//!
//! Give it a robot (a URDF file, the Modern Robotics lists, or a
//! [`RobotBuilder`] description) and it writes specialised, allocation-free
//! Rust for that one robot: joint torques τ(q, q̇, q̈) by the recursive
//! Newton-Euler algorithm, the mass matrix M(q), the bias forces h(q, q̇),
//! the gravity torques g(q) and forward dynamics q̈, with the recursion
//! unrolled and every constant of the robot folded in. The generated module
//! depends on nothing, not even `std`. A generic solver ([`Robot`]) computes
//! the same quantities for any robot at run time, and every generated
//! function is tested against it.
//!
//! There are four ways in: a build script ([`Builder`]), the proc-macros
//! (the `dynagen-macros` crate), the generic solver ([`Robot`]), and the
//! `dynagen` command. How fast and how accurate each is, measured, is in the
//! repository's `docs/performance.md`; how the crate is laid out, in
//! `docs/architecture.md`.
//!
//! # Quick start: a build script
//!
//! With `dynagen` as a build dependency (`default-features = false` leaves
//! out the command line's dependencies), `build.rs` writes the module into
//! `OUT_DIR`:
//!
//! ```no_run
//! // build.rs, in `fn main()`:
//! dynagen::Builder::new()
//!     .urdf("robots/ur5.urdf")
//!     .generate()
//!     .expect("generating the UR5 dynamics");
//! ```
//!
//! and the crate includes it:
//!
//! ```ignore
//! pub mod ur5 {
//!     include!(concat!(env!("OUT_DIR"), "/ur5.rs"));
//! }
//! let tau: [f64; 6] = ur5::inverse_dynamics(&q, &qd, &qdd);
//! let m: [[f64; 6]; 6] = ur5::mass_matrix(&q);
//! ```
//!
//! # Quick start: the macros
//!
//! `dynagen_macros::urdf!` and `dynagen_macros::robot!` expand to the same
//! module in place, at compile time (this crate cannot show them compiled:
//! the macro crate depends on it; `tests/user-macro` in the repository
//! does):
//!
//! ```ignore
//! pub mod ur5 {
//!     dynagen_macros::urdf!("robots/ur5.urdf", functions = [inverse_dynamics, mass_matrix]);
//! }
//! ```
//!
//! # Quick start: the generic solver
//!
//! [`Robot`] runs the algorithms on `f64` and nalgebra types for a robot
//! known only at run time:
//!
//! ```
//! use dynagen::Robot;
//! use nalgebra::DVector;
//!
//! let mut robot = Robot::from_urdf_file("robots/ur5.urdf")?;
//! let q = DVector::from_vec(vec![0.1, -0.5, 0.3, 0.0, 0.2, 0.0]);
//! let qd = DVector::zeros(6);
//! let tau = robot.inverse_dynamics(&q, &qd, &DVector::zeros(6))?;
//! let qdd = robot.forward_dynamics(&q, &qd, &tau)?;
//! assert!(qdd.norm() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Quick start: the command
//!
//! ```text
//! cargo run -p dynagen -- generate -o ur5.rs        # the bundled UR5, or a URDF path
//! cargo run -p dynagen -- inspect robot.urdf        # joint order, axes, masses, warnings
//! ```
//!
//! # What else is here
//!
//! The robot model ([`model`]), scalar-generic spatial algebra
//! ([`spatial`]), the algorithms, one a file and generic over [`Scalar`]
//! ([`algorithms`]), the expression graph that code generation traces them
//! on ([`symbolic`]), the code generator ([`codegen`]), and [`scene`]s: what
//! a controller needs from a robot (gravity, sub-tree, locked joints,
//! payloads, armature, friction, tip wrench), in generated code or on the
//! generic solver ([`SceneRobot`]).
//!
//! Conventions: spatial vectors are (angular; linear); joint order is
//! depth-first over the URDF tree, children in file order; gravity defaults
//! to (0, 0, −9.81) m/s² in the base frame; a tip wrench is the wrench the
//! robot applies to its environment, in the tip frame.

/// `impl Debug` for error types that writes their `Display` message. A
/// build script's `.expect(..)` and `.unwrap()` print an error's Debug form;
/// for these errors it is then the message a user acts on (the file, the
/// link or joint, what to change) instead of the enum's fields
/// (`Robot { path: .., source: Io { .. } }`). The fields stay readable by
/// matching on the variants.
macro_rules! debug_as_display {
    ($($t:ty),* $(,)?) => {
        $(
            impl core::fmt::Debug for $t {
                fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                    core::fmt::Display::fmt(self, f)
                }
            }
        )*
    };
}

pub mod algorithms;
pub mod codegen;
pub mod model;
mod robot;
mod scalar;
pub mod scene;
pub mod spatial;
pub mod symbolic;

pub use algorithms::integrators::Integrator;
pub use codegen::Builder;
pub use model::{Model, ModelError, ModelWarning, RobotBuilder};
pub use robot::{InputError, Robot, Stepping, TipWrenchHistory};
pub use scalar::{
    Compensated, CompensatedFma, CompensatedWith, Counting, Dekker, DoubleDouble, Dual, ExactProduct, Fused, Scalar,
};
pub use scene::{Scene, SceneError, SceneModel, SceneRobot};
