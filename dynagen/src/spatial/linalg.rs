//! 3-vectors, 3×3 matrices and symmetric 3×3 matrices over any scalar.

use crate::Scalar;
use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A 3-vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3<S>(pub [S; 3]);

/// A 3×3 matrix, row-major: `self.0[row][col]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3<S>(pub [[S; 3]; 3]);

/// A symmetric 3×3 matrix stored as its six distinct entries
/// `[xx, yy, zz, xy, xz, yz]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sym3<S>(pub [S; 6]);

impl<S: Scalar> Vec3<S> {
    /// The zero vector.
    #[inline(always)]
    pub fn zero() -> Self {
        Vec3([S::zero(); 3])
    }
    /// A vector from components.
    #[inline(always)]
    pub fn new(x: S, y: S, z: S) -> Self {
        Vec3([x, y, z])
    }
    /// Converts an `f64` vector (a model constant) to this scalar.
    #[inline(always)]
    pub fn from_f64(v: &Vec3<f64>) -> Self {
        Vec3([S::from_f64(v.0[0]), S::from_f64(v.0[1]), S::from_f64(v.0[2])])
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(&self, o: &Self) -> S {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }
    /// Cross product `self × o`.
    #[inline(always)]
    pub fn cross(&self, o: &Self) -> Self {
        let (a, b) = (&self.0, &o.0);
        Vec3([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])
    }
    /// Multiplication by a scalar.
    #[inline(always)]
    pub fn scale(&self, s: S) -> Self {
        Vec3([self.0[0] * s, self.0[1] * s, self.0[2] * s])
    }
    /// Squared Euclidean norm.
    #[inline(always)]
    pub fn norm_squared(&self) -> S {
        self.dot(self)
    }
}

impl Vec3<f64> {
    /// Euclidean norm. Where the sum of squares would overflow or lose
    /// its digits to underflow (components beyond about 1e150 or below
    /// 1e-150), the vector is scaled by its largest component first, so
    /// that the norm of (1e200, 0, 0) is 1e200 and that of (1e-200, 0, 0)
    /// is 1e-200 rather than infinity and zero.
    pub fn norm(&self) -> f64 {
        let n2 = self.norm_squared();
        if n2.is_finite() && n2 >= 1e-290 || n2 == 0.0 && self.0.iter().all(|&x| x == 0.0) {
            return n2.sqrt();
        }
        let m = self.0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !m.is_finite() || m == 0.0 {
            return n2.sqrt();
        }
        m * Vec3(self.0.map(|x| x / m)).norm_squared().sqrt()
    }
    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|x| x.is_finite())
    }
}

impl<S: Scalar> Add for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Vec3([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}
impl<S: Scalar> Sub for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Vec3([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}
impl<S: Scalar> Neg for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Vec3([-self.0[0], -self.0[1], -self.0[2]])
    }
}
impl<S: Scalar> AddAssign for Vec3<S> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<S: Scalar> SubAssign for Vec3<S> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<S: Scalar> Mat3<S> {
    /// The identity.
    #[inline(always)]
    pub fn identity() -> Self {
        let (o, z) = (S::one(), S::zero());
        Mat3([[o, z, z], [z, o, z], [z, z, o]])
    }
    /// The zero matrix.
    #[inline(always)]
    pub fn zero() -> Self {
        Mat3([[S::zero(); 3]; 3])
    }
    /// Converts an `f64` matrix (a model constant) to this scalar.
    #[inline(always)]
    pub fn from_f64(m: &Mat3<f64>) -> Self {
        Mat3(m.0.map(|r| r.map(S::from_f64)))
    }
    /// The skew-symmetric matrix `[v]` with `[v] w = v × w`.
    #[inline(always)]
    pub fn skew(v: &Vec3<S>) -> Self {
        let z = S::zero();
        let [x, y, w] = v.0;
        Mat3([[z, -w, y], [w, z, -x], [-y, x, z]])
    }
    /// The transpose.
    #[inline(always)]
    pub fn transpose(&self) -> Self {
        let m = &self.0;
        Mat3([[m[0][0], m[1][0], m[2][0]], [m[0][1], m[1][1], m[2][1]], [m[0][2], m[1][2], m[2][2]]])
    }
    /// `self · v`.
    #[inline(always)]
    pub fn mul_vec(&self, v: &Vec3<S>) -> Vec3<S> {
        let m = &self.0;
        Vec3([
            m[0][0] * v.0[0] + m[0][1] * v.0[1] + m[0][2] * v.0[2],
            m[1][0] * v.0[0] + m[1][1] * v.0[1] + m[1][2] * v.0[2],
            m[2][0] * v.0[0] + m[2][1] * v.0[1] + m[2][2] * v.0[2],
        ])
    }
    /// `selfᵀ · v`.
    #[inline(always)]
    pub fn tr_mul_vec(&self, v: &Vec3<S>) -> Vec3<S> {
        let m = &self.0;
        Vec3([
            m[0][0] * v.0[0] + m[1][0] * v.0[1] + m[2][0] * v.0[2],
            m[0][1] * v.0[0] + m[1][1] * v.0[1] + m[2][1] * v.0[2],
            m[0][2] * v.0[0] + m[1][2] * v.0[1] + m[2][2] * v.0[2],
        ])
    }
    /// The matrix product `self · o`.
    #[inline(always)]
    pub fn mul_mat(&self, o: &Self) -> Self {
        let (a, b) = (&self.0, &o.0);
        let mut r = [[S::zero(); 3]; 3];
        for (i, ri) in r.iter_mut().enumerate() {
            for (j, rij) in ri.iter_mut().enumerate() {
                *rij = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
            }
        }
        Mat3(r)
    }
    /// The column `j`.
    #[inline(always)]
    pub fn col(&self, j: usize) -> Vec3<S> {
        Vec3([self.0[0][j], self.0[1][j], self.0[2][j]])
    }
    /// Rotation matrix from URDF roll-pitch-yaw, in this scalar (see
    /// [`Mat3::from_rpy`]).
    pub fn rpy(roll: S, pitch: S, yaw: S) -> Self {
        let (sr, cr) = roll.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        let (sy, cy) = yaw.sin_cos();
        Mat3([
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ])
    }
}

impl Mat3<f64> {
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }
    /// Rotation matrix from URDF roll-pitch-yaw: fixed axes X, Y, Z, so
    /// `R = Rz(yaw) · Ry(pitch) · Rx(roll)`.
    pub fn from_rpy(roll: f64, pitch: f64, yaw: f64) -> Self {
        Mat3::rpy(roll, pitch, yaw)
    }
    /// The rotation by `angle` radians about the unit vector `axis`
    /// (Rodrigues' formula).
    pub fn from_axis_angle(axis: &Vec3<f64>, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        rodrigues(axis, s, c)
    }
}

/// `I + s[a] + (1 − c)[a]²` for a unit axis `a`: the rotation whose sine and
/// cosine of angle are `s` and `c`. The axis is a model constant, so a
/// symbolic trace folds the zero components of an axis-aligned joint.
#[inline(always)]
pub(crate) fn rodrigues<S: Scalar>(axis: &Vec3<f64>, s: S, c: S) -> Mat3<S> {
    let [x, y, z] = axis.0;
    let t = S::one() - c;
    let k = |v: f64| S::from_f64(v);
    // Entries of t·a·aᵀ + c·I + s·[a], written so that a zero component of
    // the axis makes whole terms vanish.
    let txy = t * k(x * y);
    let txz = t * k(x * z);
    let tyz = t * k(y * z);
    let (sx, sy, sz) = (s * k(x), s * k(y), s * k(z));
    Mat3([
        [c + t * k(x * x), txy - sz, txz + sy],
        [txy + sz, c + t * k(y * y), tyz - sx],
        [txz - sy, tyz + sx, c + t * k(z * z)],
    ])
}

/// [`rodrigues`] with the axis in the scalar itself: the products of its
/// components are computed in `S`.
#[inline(always)]
pub(crate) fn rodrigues_generic<S: Scalar>(axis: &Vec3<S>, s: S, c: S) -> Mat3<S> {
    let [x, y, z] = axis.0;
    let t = S::one() - c;
    let (txy, txz, tyz) = (t * (x * y), t * (x * z), t * (y * z));
    let (sx, sy, sz) = (s * x, s * y, s * z);
    Mat3([
        [c + t * (x * x), txy - sz, txz + sy],
        [txy + sz, c + t * (y * y), tyz - sx],
        [txz - sy, tyz + sx, c + t * (z * z)],
    ])
}

impl<S: Scalar> Mul<Vec3<S>> for Mat3<S> {
    type Output = Vec3<S>;
    #[inline(always)]
    fn mul(self, v: Vec3<S>) -> Vec3<S> {
        self.mul_vec(&v)
    }
}

impl<S: Scalar> Sym3<S> {
    /// The zero matrix.
    #[inline(always)]
    pub fn zero() -> Self {
        Sym3([S::zero(); 6])
    }
    /// Converts an `f64` matrix (a model constant) to this scalar.
    #[inline(always)]
    pub fn from_f64(m: &Sym3<f64>) -> Self {
        Sym3(m.0.map(S::from_f64))
    }
    /// The full matrix.
    #[inline(always)]
    pub fn to_mat(&self) -> Mat3<S> {
        let [xx, yy, zz, xy, xz, yz] = self.0;
        Mat3([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    }
    /// The symmetric matrix whose upper triangle is that of `m` (for a
    /// matrix known to be symmetric).
    #[inline(always)]
    pub fn from_mat_upper(m: &Mat3<S>) -> Self {
        let m = &m.0;
        Sym3([m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]])
    }
    /// `self · v`.
    #[inline(always)]
    pub fn mul_vec(&self, v: &Vec3<S>) -> Vec3<S> {
        let [xx, yy, zz, xy, xz, yz] = self.0;
        let [a, b, c] = v.0;
        Vec3([xx * a + xy * b + xz * c, xy * a + yy * b + yz * c, xz * a + yz * b + zz * c])
    }
    /// `R · self · Rᵀ`.
    #[inline(always)]
    pub fn rotate(&self, r: &Mat3<S>) -> Self {
        let a = r.mul_mat(&self.to_mat());
        let r = &r.0;
        let e = |i: usize, j: usize| a.0[i][0] * r[j][0] + a.0[i][1] * r[j][1] + a.0[i][2] * r[j][2];
        Sym3([e(0, 0), e(1, 1), e(2, 2), e(0, 1), e(0, 2), e(1, 2)])
    }
    /// `-[a][b] - [b][a]`, the symmetric matrix that appears when an inertia
    /// is shifted (for `a = b` it is `2[a]ᵀ[a]`).
    #[inline(always)]
    pub fn cross_shift(a: &Vec3<S>, b: &Vec3<S>) -> Self {
        // -[a][b] = (a·b) I - b aᵀ; symmetrised with the other term.
        let d = a.dot(b);
        let [a0, a1, a2] = a.0;
        let [b0, b1, b2] = b.0;
        let two = S::from_f64(2.0);
        Sym3([
            two * (d - a0 * b0),
            two * (d - a1 * b1),
            two * (d - a2 * b2),
            -(a0 * b1 + a1 * b0),
            -(a0 * b2 + a2 * b0),
            -(a1 * b2 + a2 * b1),
        ])
    }
    /// The trace.
    #[inline(always)]
    pub fn trace(&self) -> S {
        self.0[0] + self.0[1] + self.0[2]
    }
}

impl<S: Scalar> Add for Sym3<S> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let mut r = self.0;
        for (x, y) in r.iter_mut().zip(o.0) {
            *x += y;
        }
        Sym3(r)
    }
}

impl<S: Scalar> Sym3<S> {
    /// Multiplication by a scalar.
    #[inline(always)]
    pub fn scale(&self, s: S) -> Self {
        Sym3(self.0.map(|x| x * s))
    }
}

impl Sym3<f64> {
    /// The eigenvalues in ascending order (closed form for symmetric 3×3).
    pub fn eigenvalues(&self) -> [f64; 3] {
        let [a, b, c, d, e, f] = self.0; // xx yy zz xy xz yz
        let p1 = d * d + e * e + f * f;
        if p1 == 0.0 {
            let mut v = [a, b, c];
            v.sort_by(|x, y| x.total_cmp(y));
            return v;
        }
        let q = (a + b + c) / 3.0;
        let p2 = (a - q).powi(2) + (b - q).powi(2) + (c - q).powi(2) + 2.0 * p1;
        let p = (p2 / 6.0).sqrt();
        let bm = Sym3([(a - q) / p, (b - q) / p, (c - q) / p, d / p, e / p, f / p]).to_mat();
        let m = &bm.0;
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let r = (det / 2.0).clamp(-1.0, 1.0);
        let phi = r.acos() / 3.0;
        let e1 = q + 2.0 * p * phi.cos();
        let e3 = q + 2.0 * p * (phi + 2.0 * core::f64::consts::PI / 3.0).cos();
        let e2 = 3.0 * q - e1 - e3;
        let mut v = [e1, e2, e3];
        v.sort_by(|x, y| x.total_cmp(y));
        v
    }
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rpy_matches_product_of_axis_rotations() {
        let (r, p, y) = (0.3, -0.7, 1.9);
        let rx = Mat3::from_axis_angle(&Vec3([1.0, 0.0, 0.0]), r);
        let ry = Mat3::from_axis_angle(&Vec3([0.0, 1.0, 0.0]), p);
        let rz = Mat3::from_axis_angle(&Vec3([0.0, 0.0, 1.0]), y);
        let expected = rz.mul_mat(&ry).mul_mat(&rx);
        let got = Mat3::from_rpy(r, p, y);
        for i in 0..3 {
            for j in 0..3 {
                assert!((got.0[i][j] - expected.0[i][j]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn eigenvalues_of_a_rotated_diagonal_matrix() {
        let d = Sym3([1.0, 2.0, 5.0, 0.0, 0.0, 0.0]);
        let r = Mat3::from_rpy(0.4, 1.1, -2.3);
        let ev = d.rotate(&r).eigenvalues();
        for (got, want) in ev.iter().zip([1.0, 2.0, 5.0]) {
            assert!((got - want).abs() < 1e-13, "{ev:?}");
        }
    }

    #[test]
    fn cross_shift_is_the_inertia_shift() {
        let a: Vec3<f64> = Vec3([0.3, -1.2, 0.7]);
        let b = Vec3([2.0, 0.1, -0.4]);
        let s = Sym3::cross_shift(&a, &b).to_mat();
        let (sa, sb) = (Mat3::skew(&a), Mat3::skew(&b));
        let full = sa.mul_mat(&sb);
        let full2 = sb.mul_mat(&sa);
        for i in 0..3 {
            for j in 0..3 {
                assert!((s.0[i][j] + full.0[i][j] + full2.0[i][j]).abs() < 1e-14);
            }
        }
    }
}
