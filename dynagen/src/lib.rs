//! dynagen: a dynamics compiler for robots.
//!
//! This crate holds the robot model ([`model`]), scalar-generic spatial
//! algebra ([`spatial`]), the dynamics algorithms ([`algorithms`]), and a
//! numeric API on nalgebra types ([`Robot`]) that runs them on `f64` for any
//! robot at run time. A [`scene`] says what a controller needs from a robot
//! (functions, gravity, tip wrench, sub-tree, locked joints, payloads,
//! armature and friction); [`SceneRobot`] runs it on the generic solver.
//!
//! Conventions (see DESIGN.md): spatial vectors are (angular; linear);
//! joint order is depth-first over the URDF tree, children in file order;
//! gravity defaults to (0, 0, −9.81) m/s² in the base frame; a tip wrench is
//! the wrench the robot applies to its environment, in the tip frame.

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
    Compensated, CompensatedFma, CompensatedWith, Counting, Dekker, DoubleDouble, ExactProduct, Fused, Scalar,
};
pub use scene::{Scene, SceneError, SceneModel, SceneRobot};
