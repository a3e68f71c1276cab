//! What acts on the robot besides its own rigid bodies, in one value for
//! every algorithm: gravity, wrenches at its frames, and the inertias it
//! carries beyond the model's (payloads on bodies, armature on joints).

use crate::spatial::{Force, Inertia, Vec3};

/// A wrench that a frame of the robot applies to its environment, in that
/// frame's coordinates: the Modern Robotics library's `Ftip` (m; f).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TipWrench<S> {
    /// The frame's index in [`Model::frames`](crate::model::Model::frames).
    pub frame: usize,
    /// The wrench (N·m; N).
    pub wrench: Force<S>,
}

/// The `body` of a [`BodyInertia`] carried by the root body: a floating
/// base adds it to its own inertia; on a fixed base it moves nothing and
/// every algorithm leaves it out.
pub const BASE_BODY: usize = usize::MAX;

/// An inertia carried by a body in addition to the model's own, in the
/// body's frame: a payload known only at run time (its parameters are
/// inputs of the generated code), added where the body's inertia enters the
/// recursion ([`Loads::payloads`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyInertia<S> {
    /// The body's index (its joint's index), or [`BASE_BODY`] for the root
    /// body (in the root's frame).
    pub body: usize,
    /// The inertia, in the body's frame.
    pub inertia: Inertia<S>,
}

/// The loads of one call of an algorithm ([`rnea`](super::rnea::rnea),
/// [`crba`](super::crba::crba), [`aba`](super::aba::aba), the forward
/// dynamics, the integrators, a scene's dynamics). An algorithm reads what
/// its quantity depends on: the mass matrix only the inertias (payloads and
/// armature), the others everything.
///
/// ```
/// use dynagen::algorithms::{Loads, TipWrench};
/// use dynagen::spatial::{Force, Vec3};
/// let g = Vec3([0.0, 0.0, -9.81]);
/// let tips = [TipWrench { frame: 0, wrench: Force::from_array([0.0, 0.0, 0.0, 0.0, 0.0, 5.0]) }];
/// let loads = Loads::gravity(&g).with_tips(&tips);
/// assert!(loads.gravity.is_some() && loads.payloads.is_empty() && Loads::<f64>::none().tips.is_empty());
/// ```
#[derive(Debug)]
pub struct Loads<'a, S> {
    /// Gravity in the base frame (m/s²); `None` for none.
    pub gravity: Option<&'a Vec3<S>>,
    /// Wrenches the robot applies to its environment at its frames (the
    /// Modern Robotics `Ftip`), each in its frame.
    pub tips: &'a [TipWrench<S>],
    /// Inertias carried by bodies in addition to their own (any number per
    /// body), each in its body's frame: each adds the wrench that produces
    /// its motion, exactly as if the body's own inertia were the sum.
    pub payloads: &'a [BodyInertia<S>],
    /// A per-joint armature (reflected rotor inertia, kg·m² or kg), felt by
    /// the joint coordinate alone: M(q) + diag(a). `None` for none. Model
    /// constants, like the model's own inertias.
    pub armature: Option<&'a [f64]>,
}

// By hand: a derive would ask `S: Copy`, and these are references.
impl<S> Clone for Loads<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S> Copy for Loads<'_, S> {}

impl<'a, S> Loads<'a, S> {
    /// Nothing: no gravity, no tip wrench, no payload, no armature.
    pub const fn none() -> Self {
        Loads { gravity: None, tips: &[], payloads: &[], armature: None }
    }
    /// Gravity `g` (base frame, m/s²) alone.
    pub const fn gravity(g: &'a Vec3<S>) -> Self {
        Loads { gravity: Some(g), ..Self::none() }
    }
    /// Gravity (`None`: none), tip wrenches and payloads, without armature.
    pub const fn new(gravity: Option<&'a Vec3<S>>, tips: &'a [TipWrench<S>], payloads: &'a [BodyInertia<S>]) -> Self {
        Loads { gravity, tips, payloads, armature: None }
    }
    /// These loads with the tip wrenches `tips` instead.
    pub const fn with_tips(self, tips: &'a [TipWrench<S>]) -> Self {
        Loads { tips, ..self }
    }
    /// These loads with the payloads `payloads` instead.
    pub const fn with_payloads(self, payloads: &'a [BodyInertia<S>]) -> Self {
        Loads { payloads, ..self }
    }
    /// These loads with the armature `armature` instead (`None`: none).
    pub const fn with_armature(self, armature: Option<&'a [f64]>) -> Self {
        Loads { armature, ..self }
    }
    /// These loads without gravity and tip wrenches: what a mass matrix, or
    /// a solve with it, reads.
    pub const fn inertias(self) -> Self {
        Loads { gravity: None, tips: &[], ..self }
    }
    /// Panics unless every payload's body (or [`BASE_BODY`]), and the
    /// armature, fit a model of `n` joints; `what` names the algorithm.
    pub(crate) fn check(&self, n: usize, what: &str) {
        assert!(
            self.payloads.iter().all(|p| p.body < n || p.body == BASE_BODY),
            "{what}: a payload's body is not one of the model's {n}"
        );
        assert!(self.armature.is_none_or(|a| a.len() == n), "{what}: the armature must have the model's {n} joints");
    }
}

impl<S> Default for Loads<'_, S> {
    fn default() -> Self {
        Self::none()
    }
}
