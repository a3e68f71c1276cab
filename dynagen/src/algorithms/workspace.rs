//! Scratch space for the algorithms, allocated once per model.

use crate::model::Model;
use crate::spatial::{Force, Inertia, Mat3, Motion, Transform};
use crate::Scalar;

/// Preallocated scratch for every algorithm on one model. Create it once
/// (outside a control loop) and pass it to each call.
#[derive(Clone, Debug)]
pub struct Workspace<S> {
    /// Pose of each body in its parent's frame (the base's for a root body).
    pub(crate) x: Vec<Transform<S>>,
    /// Twist of each body, in its frame (RNEA keeps only the angular part ω).
    pub(crate) v: Vec<Motion<S>>,
    /// Acceleration of each body (including −g), in its frame: spatial in
    /// ABA; in RNEA (ω̇; ordinary acceleration of the frame's origin).
    pub(crate) a: Vec<Motion<S>>,
    /// Net wrench transmitted by each joint, in the body's frame.
    pub(crate) f: Vec<Force<S>>,
    /// RNEA: `[ω̇×] + [ω×][ω×]` of each body, in its frame.
    pub(crate) u: Vec<Mat3<S>>,
    /// Per body, whether `ω × (Ī ω)` is computed from the products `ω ωᵀ`
    /// (decided once from the model's `Ī`, see `rnea::use_products_for_gyroscopic`;
    /// either form gives the same value up to rounding; a traced RNEA groups
    /// the whole moment by `Ī`'s entries instead).
    pub(crate) gyro_products: Vec<bool>,
    /// Composite or articulated quantities, per body.
    pub(crate) inertia: Vec<Inertia<S>>,
    /// Articulated-body inertias, per body.
    pub(crate) art: Vec<crate::algorithms::aba::ArticulatedInertia<S>>,
    /// Per-body 6-vectors of the articulated-body algorithm.
    pub(crate) u6: Vec<Force<S>>,
    /// Per-joint scalars.
    pub(crate) s1: Vec<S>,
    pub(crate) s2: Vec<S>,
    /// An NV×NV matrix, row-major (n×n for a fixed base).
    pub(crate) mat: Vec<S>,
    /// A joint-space right-hand side (a scene's τ − friction).
    pub(crate) rhs: Vec<S>,
    /// Pose of each body in the base frame.
    pub(crate) world: Vec<Transform<S>>,
    /// The bodies' coordinates and results of a model with mimic joints
    /// (empty without).
    pub(crate) tree: crate::algorithms::mimic::TreeScratch<S>,
}

impl<S: Scalar> Workspace<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.bodies.len();
        Workspace {
            x: vec![Transform::identity(); n],
            v: vec![Motion::zero(); n],
            a: vec![Motion::zero(); n],
            f: vec![Force::zero(); n],
            u: vec![Mat3::zero(); n],
            gyro_products: model
                .bodies
                .iter()
                .map(|b| crate::algorithms::rnea::use_products_for_gyroscopic(&b.inertia.ibar))
                .collect(),
            inertia: vec![Inertia::zero(); n],
            art: vec![crate::algorithms::aba::ArticulatedInertia::zero(); n],
            u6: vec![Force::zero(); n],
            s1: vec![S::zero(); n],
            s2: vec![S::zero(); n],
            mat: vec![S::zero(); model.nv() * model.nv()],
            rhs: vec![S::zero(); model.nv()],
            world: vec![Transform::identity(); n],
            tree: crate::algorithms::mimic::TreeScratch::new(model),
        }
    }
    /// The number of bodies this workspace is for (of joints, without
    /// mimic joints).
    pub fn dof(&self) -> usize {
        self.x.len()
    }
}
