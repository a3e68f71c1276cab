//! Scalar-generic spatial algebra, in the conventions of *Modern Robotics*:
//! spatial vectors are (angular; linear). A twist is `Motion { ang: ω, lin: v }`,
//! a wrench is `Force { ang: m, lin: f }`.
//!
//! Everything here is generic over [`Scalar`](crate::Scalar), works on plain
//! arrays and allocates nothing.

mod inertia;
mod linalg;
mod motion;
mod transform;

pub use inertia::Inertia;
pub(crate) use linalg::{rodrigues as linalg_rodrigues, rodrigues_generic};
pub use linalg::{Mat3, Sym3, Vec3};
pub use motion::{Force, Motion};
pub use transform::Transform;
