//! Spatial inertia of a rigid body.

use super::{Force, Motion, Sym3, Vec3};
use crate::Scalar;

/// The spatial inertia of a rigid body in some frame, stored as its mass
/// `m`, first moment `h = m·c` (c: centre of mass in this frame) and
/// rotational inertia `Ī` about the frame's origin. As a 6×6 matrix, in
/// (angular; linear) order, it is `[[Ī, [h]], [[h]ᵀ, m·1]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia<S> {
    /// Mass (kg).
    pub mass: S,
    /// First moment of mass `m·c` (kg·m).
    pub h: Vec3<S>,
    /// Rotational inertia about the frame's origin (kg·m²).
    pub ibar: Sym3<S>,
}

impl<S: Scalar> Inertia<S> {
    /// No mass.
    #[inline(always)]
    pub fn zero() -> Self {
        Inertia { mass: S::zero(), h: Vec3::zero(), ibar: Sym3::zero() }
    }
    /// From the mass, the centre of mass `c` and the rotational inertia
    /// `I_c` about the centre of mass (axes parallel to this frame's).
    pub fn from_mass_com_inertia(mass: S, com: Vec3<S>, i_c: Sym3<S>) -> Self {
        // Ī = I_c + m [c]ᵀ[c]
        let shift = Sym3::cross_shift(&com, &com).scale(mass * S::from_f64(0.5));
        Inertia { mass, h: com.scale(mass), ibar: i_c + shift }
    }
    /// Converts an `f64` inertia (a model constant) to this scalar.
    #[inline(always)]
    pub fn from_f64(i: &Inertia<f64>) -> Self {
        Inertia { mass: S::from_f64(i.mass), h: Vec3::from_f64(&i.h), ibar: Sym3::from_f64(&i.ibar) }
    }
    /// The momentum `I·V` of the body moving with twist `V`.
    #[inline(always)]
    pub fn mul_motion(&self, v: &Motion<S>) -> Force<S> {
        // f = m v − h × ω ;  n = Ī ω + h × v
        Force {
            ang: self.ibar.mul_vec(&v.ang) + self.h.cross(&v.lin),
            lin: v.lin.scale(self.mass) - self.h.cross(&v.ang),
        }
    }
    /// The sum of two inertias in the same frame.
    #[inline(always)]
    pub fn add(&self, o: &Inertia<S>) -> Inertia<S> {
        Inertia { mass: self.mass + o.mass, h: self.h + o.h, ibar: self.ibar + o.ibar }
    }
    /// As a 6×6 matrix in (angular; linear) order.
    pub fn to_matrix(&self) -> [[S; 6]; 6] {
        let i = self.ibar.to_mat().0;
        let [hx, hy, hz] = self.h.0;
        let (z, m) = (S::zero(), self.mass);
        [
            [i[0][0], i[0][1], i[0][2], z, -hz, hy],
            [i[1][0], i[1][1], i[1][2], hz, z, -hx],
            [i[2][0], i[2][1], i[2][2], -hy, hx, z],
            [z, hz, -hy, m, z, z],
            [-hz, z, hx, z, m, z],
            [hy, -hx, z, z, z, m],
        ]
    }
}

impl Inertia<f64> {
    /// The centre of mass, if the mass is not zero.
    pub fn com(&self) -> Option<Vec3<f64>> {
        (self.mass != 0.0).then(|| self.h.scale(1.0 / self.mass))
    }
    /// The rotational inertia about the centre of mass (zero mass: about
    /// the origin).
    pub fn inertia_at_com(&self) -> Sym3<f64> {
        match self.com() {
            Some(c) => self.ibar + Sym3::cross_shift(&c, &c).scale(-0.5 * self.mass),
            None => self.ibar,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrix_form_agrees_with_mul_motion() {
        let i = Inertia::from_mass_com_inertia(3.0, Vec3([0.2, -0.1, 0.4]), Sym3([0.5, 0.6, 0.7, 0.05, -0.01, 0.02]));
        let v = [0.3, -0.2, 0.9, 1.1, -0.4, 0.25];
        let f = i.mul_motion(&Motion::from_array(v)).to_array();
        let m = i.to_matrix();
        for r in 0..6 {
            let e: f64 = (0..6).map(|c| m[r][c] * v[c]).sum();
            assert!((e - f[r]).abs() < 1e-14);
        }
        // round trip to the centre of mass
        let ic = i.inertia_at_com();
        for (a, b) in ic.0.iter().zip([0.5, 0.6, 0.7, 0.05, -0.01, 0.02]) {
            assert!((a - b).abs() < 1e-14);
        }
    }
}
