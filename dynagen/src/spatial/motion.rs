//! Twists (motion vectors) and wrenches (force vectors), (angular; linear).

use super::Vec3;
use crate::Scalar;
use core::ops::{Add, AddAssign, Neg, Sub, SubAssign};

/// A spatial motion vector: a twist `V = (ω, v)` or a spatial acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<S> {
    /// Angular part ω (rad/s).
    pub ang: Vec3<S>,
    /// Linear part v (m/s): the velocity of the point at the frame's origin.
    pub lin: Vec3<S>,
}

/// A spatial force vector: a wrench `F = (m, f)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Force<S> {
    /// Moment m about the frame's origin (N·m).
    pub ang: Vec3<S>,
    /// Force f (N).
    pub lin: Vec3<S>,
}

impl<S: Scalar> Motion<S> {
    /// The zero twist.
    #[inline(always)]
    pub fn zero() -> Self {
        Motion { ang: Vec3::zero(), lin: Vec3::zero() }
    }
    /// A twist from its parts.
    #[inline(always)]
    pub fn new(ang: Vec3<S>, lin: Vec3<S>) -> Self {
        Motion { ang, lin }
    }
    /// From a 6-array (ω; v).
    #[inline(always)]
    pub fn from_array(a: [S; 6]) -> Self {
        Motion { ang: Vec3([a[0], a[1], a[2]]), lin: Vec3([a[3], a[4], a[5]]) }
    }
    /// As a 6-array (ω; v).
    #[inline(always)]
    pub fn to_array(&self) -> [S; 6] {
        let (a, l) = (self.ang.0, self.lin.0);
        [a[0], a[1], a[2], l[0], l[1], l[2]]
    }
    /// Multiplication by a scalar.
    #[inline(always)]
    pub fn scale(&self, s: S) -> Self {
        Motion { ang: self.ang.scale(s), lin: self.lin.scale(s) }
    }
    /// The Lie bracket `[ad_self] m = self ×ₘ m`
    /// (Featherstone's motion cross product).
    #[inline(always)]
    pub fn cross_motion(&self, m: &Motion<S>) -> Motion<S> {
        Motion { ang: self.ang.cross(&m.ang), lin: self.ang.cross(&m.lin) + self.lin.cross(&m.ang) }
    }
    /// `self ×_f f = −[ad_self]ᵀ f` (Featherstone's force cross product).
    #[inline(always)]
    pub fn cross_force(&self, f: &Force<S>) -> Force<S> {
        Force { ang: self.ang.cross(&f.ang) + self.lin.cross(&f.lin), lin: self.ang.cross(&f.lin) }
    }
    /// `[ad_self]ᵀ f`, as in the *Modern Robotics* equations of motion.
    #[inline(always)]
    pub fn ad_transpose(&self, f: &Force<S>) -> Force<S> {
        -self.cross_force(f)
    }
    /// The power `fᵀ self` of a wrench on this twist.
    #[inline(always)]
    pub fn dot(&self, f: &Force<S>) -> S {
        self.ang.dot(&f.ang) + self.lin.dot(&f.lin)
    }
}

impl<S: Scalar> Force<S> {
    /// The zero wrench.
    #[inline(always)]
    pub fn zero() -> Self {
        Force { ang: Vec3::zero(), lin: Vec3::zero() }
    }
    /// A wrench from its parts.
    #[inline(always)]
    pub fn new(ang: Vec3<S>, lin: Vec3<S>) -> Self {
        Force { ang, lin }
    }
    /// From a 6-array (m; f).
    #[inline(always)]
    pub fn from_array(a: [S; 6]) -> Self {
        Force { ang: Vec3([a[0], a[1], a[2]]), lin: Vec3([a[3], a[4], a[5]]) }
    }
    /// As a 6-array (m; f).
    #[inline(always)]
    pub fn to_array(&self) -> [S; 6] {
        let (a, l) = (self.ang.0, self.lin.0);
        [a[0], a[1], a[2], l[0], l[1], l[2]]
    }
    /// Multiplication by a scalar.
    #[inline(always)]
    pub fn scale(&self, s: S) -> Self {
        Force { ang: self.ang.scale(s), lin: self.lin.scale(s) }
    }
}

macro_rules! vector_ops {
    ($t:ident) => {
        impl<S: Scalar> Add for $t<S> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                $t { ang: self.ang + o.ang, lin: self.lin + o.lin }
            }
        }
        impl<S: Scalar> Sub for $t<S> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                $t { ang: self.ang - o.ang, lin: self.lin - o.lin }
            }
        }
        impl<S: Scalar> Neg for $t<S> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                $t { ang: -self.ang, lin: -self.lin }
            }
        }
        impl<S: Scalar> AddAssign for $t<S> {
            #[inline(always)]
            fn add_assign(&mut self, o: Self) {
                self.ang += o.ang;
                self.lin += o.lin;
            }
        }
        impl<S: Scalar> SubAssign for $t<S> {
            #[inline(always)]
            fn sub_assign(&mut self, o: Self) {
                self.ang -= o.ang;
                self.lin -= o.lin;
            }
        }
    };
}
vector_ops!(Motion);
vector_ops!(Force);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ad_of_the_modern_robotics_docstring() {
        // Modern Robotics code library, `ad` docstring: V = [1, 2, 3, 4, 5, 6]
        // gives [[0,-3,2,0,0,0],[3,0,-1,0,0,0],[-2,1,0,0,0,0],
        //        [0,-6,5,0,-3,2],[6,0,-4,3,0,-1],[-5,4,0,-2,1,0]].
        let v = Motion::from_array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let expected = [
            [0.0, -3.0, 2.0, 0.0, 0.0, 0.0],
            [3.0, 0.0, -1.0, 0.0, 0.0, 0.0],
            [-2.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, -6.0, 5.0, 0.0, -3.0, 2.0],
            [6.0, 0.0, -4.0, 3.0, 0.0, -1.0],
            [-5.0, 4.0, 0.0, -2.0, 1.0, 0.0],
        ];
        for j in 0..6 {
            let mut e = [0.0; 6];
            e[j] = 1.0;
            let col = v.cross_motion(&Motion::from_array(e)).to_array();
            for i in 0..6 {
                assert_eq!(col[i], expected[i][j], "entry ({i},{j})");
            }
        }
    }

    #[test]
    fn force_cross_is_minus_ad_transpose() {
        let v: Motion<f64> = Motion::from_array([0.1, -2.0, 0.3, 1.5, 0.2, -0.7]);
        let f = Force::from_array([2.0, 0.5, -1.0, 0.3, 4.0, -0.2]);
        let m = Motion::from_array([-0.4, 1.0, 0.6, 0.9, -1.1, 0.25]);
        // (v ×f f)·m = −f·(v ×m m)
        let lhs = m.dot(&v.cross_force(&f));
        let rhs = -v.cross_motion(&m).dot(&f);
        assert!((lhs - rhs).abs() < 1e-14);
    }
}
