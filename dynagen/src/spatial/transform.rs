//! Rigid transforms and their action on twists, wrenches and inertias.

use super::{Force, Inertia, Mat3, Motion, Sym3, Vec3};
use crate::Scalar;

/// The pose of a frame B in a frame A: a point with coordinates `x_B` in B has
/// coordinates `rot · x_B + trans` in A. As a homogeneous matrix it is
/// `T_AB = [[rot, trans], [0, 1]]` in *Modern Robotics* notation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform<S> {
    /// R_AB: the axes of B in A's coordinates (columns).
    pub rot: Mat3<S>,
    /// p_AB: the origin of B in A's coordinates.
    pub trans: Vec3<S>,
}

impl<S: Scalar> Transform<S> {
    /// The identity transform.
    #[inline(always)]
    pub fn identity() -> Self {
        Transform { rot: Mat3::identity(), trans: Vec3::zero() }
    }
    /// A transform from its rotation and translation.
    #[inline(always)]
    pub fn new(rot: Mat3<S>, trans: Vec3<S>) -> Self {
        Transform { rot, trans }
    }
    /// A pure translation.
    #[inline(always)]
    pub fn translation(trans: Vec3<S>) -> Self {
        Transform { rot: Mat3::identity(), trans }
    }
    /// Converts an `f64` transform (a model constant) to this scalar (see
    /// [`Scalar::rotation_constant`]).
    #[inline(always)]
    pub fn from_f64(t: &Transform<f64>) -> Self {
        Transform { rot: S::rotation_constant(&t.rot), trans: Vec3::from_f64(&t.trans) }
    }
    /// `T_AC = T_AB · T_BC` where `self = T_AB`.
    #[inline(always)]
    pub fn compose(&self, bc: &Transform<S>) -> Transform<S> {
        Transform { rot: self.rot.mul_mat(&bc.rot), trans: self.rot.mul_vec(&bc.trans) + self.trans }
    }
    /// `T_BA = T_AB⁻¹`.
    #[inline(always)]
    pub fn inverse(&self) -> Transform<S> {
        let rt = self.rot.transpose();
        Transform { rot: rt, trans: -rt.mul_vec(&self.trans) }
    }
    /// A point given in B, in A's coordinates.
    #[inline(always)]
    pub fn apply_point(&self, p: &Vec3<S>) -> Vec3<S> {
        self.rot.mul_vec(p) + self.trans
    }
    /// A twist given in B, in A's coordinates: `[Ad_T_AB] V_B`.
    #[inline(always)]
    pub fn motion_to_parent(&self, m: &Motion<S>) -> Motion<S> {
        let ang = self.rot.mul_vec(&m.ang);
        Motion { ang, lin: self.rot.mul_vec(&m.lin) + self.trans.cross(&ang) }
    }
    /// A twist given in A, in B's coordinates: `[Ad_T_BA] V_A`.
    #[inline(always)]
    pub fn motion_to_child(&self, m: &Motion<S>) -> Motion<S> {
        Motion { ang: self.rot.tr_mul_vec(&m.ang), lin: self.rot.tr_mul_vec(&(m.lin + m.ang.cross(&self.trans))) }
    }
    /// A wrench given in B, in A's coordinates: `[Ad_T_BA]ᵀ F_B`.
    #[inline(always)]
    pub fn force_to_parent(&self, f: &Force<S>) -> Force<S> {
        let lin = self.rot.mul_vec(&f.lin);
        Force { ang: self.rot.mul_vec(&f.ang) + self.trans.cross(&lin), lin }
    }
    /// A wrench given in A, in B's coordinates: `[Ad_T_AB]ᵀ F_A`.
    #[inline(always)]
    pub fn force_to_child(&self, f: &Force<S>) -> Force<S> {
        Force { ang: self.rot.tr_mul_vec(&(f.ang - self.trans.cross(&f.lin))), lin: self.rot.tr_mul_vec(&f.lin) }
    }
    /// A spatial inertia given in B, in A's coordinates.
    #[inline(always)]
    pub fn inertia_to_parent(&self, i: &Inertia<S>) -> Inertia<S> {
        let h = self.rot.mul_vec(&i.h);
        let r = &self.trans;
        // Ī_A = R Ī Rᵀ − [h'][r] − [r][h'] − m[r][r], with h' = R h.
        let ibar = i.ibar.rotate(&self.rot)
            + Sym3::cross_shift(&h, r)
            + Sym3::cross_shift(r, r).scale(i.mass * S::from_f64(0.5));
        Inertia { mass: i.mass, h: h + r.scale(i.mass), ibar }
    }
    /// The homogeneous 4×4 matrix, row-major.
    pub fn to_homogeneous(&self) -> [[S; 4]; 4] {
        let (r, p) = (&self.rot.0, &self.trans.0);
        let (z, o) = (S::zero(), S::one());
        [
            [r[0][0], r[0][1], r[0][2], p[0]],
            [r[1][0], r[1][1], r[1][2], p[1]],
            [r[2][0], r[2][1], r[2][2], p[2]],
            [z, z, z, o],
        ]
    }
}

impl Transform<f64> {
    /// From a homogeneous 4×4 matrix (the last row is not checked).
    pub fn from_homogeneous(m: &[[f64; 4]; 4]) -> Self {
        Transform {
            rot: Mat3([[m[0][0], m[0][1], m[0][2]], [m[1][0], m[1][1], m[1][2]], [m[2][0], m[2][1], m[2][2]]]),
            trans: Vec3([m[0][3], m[1][3], m[2][3]]),
        }
    }
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.rot.is_finite() && self.trans.is_finite()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t() -> Transform<f64> {
        Transform::new(Mat3::from_rpy(0.3, -1.1, 2.0), Vec3([0.5, -0.2, 1.3]))
    }

    #[test]
    fn motion_round_trip_and_power_is_invariant() {
        let x = t();
        let m = Motion::from_array([0.1, 0.2, -0.3, 1.0, -2.0, 0.5]);
        let f = Force::from_array([-0.7, 0.4, 0.9, 2.0, 0.1, -1.5]);
        let back = x.motion_to_child(&x.motion_to_parent(&m));
        for (a, b) in back.to_array().iter().zip(m.to_array()) {
            assert!((a - b).abs() < 1e-14);
        }
        let p1 = m.dot(&f);
        let p2 = x.motion_to_parent(&m).dot(&x.force_to_parent(&f));
        assert!((p1 - p2).abs() < 1e-14);
        let f2 = x.force_to_child(&x.force_to_parent(&f));
        for (a, b) in f2.to_array().iter().zip(f.to_array()) {
            assert!((a - b).abs() < 1e-14);
        }
    }

    #[test]
    fn inertia_transform_preserves_momentum_and_energy() {
        let x = t();
        let i = Inertia::from_mass_com_inertia(2.5, Vec3([0.1, -0.3, 0.2]), Sym3([0.3, 0.4, 0.5, 0.01, -0.02, 0.03]));
        let ip = x.inertia_to_parent(&i);
        let v = Motion::from_array([0.3, -0.1, 0.8, 0.5, 0.7, -0.4]);
        // momentum: X* (I v) = I_A (X v)
        let lhs = x.force_to_parent(&i.mul_motion(&v));
        let rhs = ip.mul_motion(&x.motion_to_parent(&v));
        for (a, b) in lhs.to_array().iter().zip(rhs.to_array()) {
            assert!((a - b).abs() < 1e-13, "{lhs:?} {rhs:?}");
        }
    }

    #[test]
    fn compose_and_inverse() {
        let a = t();
        let b = Transform::new(Mat3::from_rpy(-0.4, 0.2, 0.1), Vec3([1.0, 2.0, 3.0]));
        let id = a.compose(&b).compose(&b.inverse()).compose(&a.inverse());
        let h = id.to_homogeneous();
        for (i, row) in h.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((x - e).abs() < 1e-14);
            }
        }
    }
}
