//! The dynamics algorithms, one per file, each generic over the scalar
//! ([`Scalar`](crate::Scalar)): run on `f64` or `f32` they are the generic
//! solver; run on a symbolic scalar they are traced into generated code.
//!
//! All of them work in body frames (each body's frame is its joint's frame),
//! take the model's constants as `f64`, write into caller-provided slices
//! and allocate nothing: their scratch lives in a [`Workspace`].
//!
//! Joint order is the model's: body `i` carries joint `i`. The public
//! algorithms take the joint vectors ([`Model::dof`](crate::Model::dof)
//! entries, a floating base's first); with mimic joints they run over the
//! bodies' own coordinates and project ([`mimic`]).

pub mod aba;
pub mod bias;
pub mod compensated;
pub mod crba;
pub mod derivatives;
pub mod energy;
pub mod floating;
pub mod forward_dynamics;
pub mod frame_acceleration;
pub mod integrators;
pub mod joint;
pub mod kinematics;
pub mod ldlt;
mod loads;
mod lu;
pub mod mimic;
pub mod rnea;
pub mod rnea_derivatives;
mod workspace;

pub(crate) use loads::add_tip_wrenches;
pub use loads::{BodyInertia, Loads, TipWrench, BASE_BODY};
pub use workspace::Workspace;
