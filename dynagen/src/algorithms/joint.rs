//! Joint kinematics: the pose of a body in its parent's frame as a function
//! of the joint position, and the joint's motion subspace.
//!
//! A joint whose axis lies along a coordinate axis of its frame
//! ([`AxisAlignment`]) and a placement without rotation are common in robot
//! descriptions. The functions here branch on these model constants (never
//! on the state) and then compute only the terms that are not multiplied by
//! an exact zero: for `f64` this skips work the compiler may not skip (it
//! cannot fold `0·x`), and a symbolic trace gets the same short expressions.
//! The results are those of the general formulas, up to rounding.

use crate::model::{AxisAlignment, Joint, JointKind};
use crate::spatial::{Force, Inertia, Mat3, Motion, Sym3, Transform, Vec3};
use crate::Scalar;

/// The coordinate index of an aligned axis, and the other two in cyclic
/// order: `(k, i, j)` with `e_i × e_j = e_k`.
#[inline(always)]
fn aligned_indices(alignment: AxisAlignment) -> Option<(usize, usize, usize)> {
    match alignment {
        AxisAlignment::X => Some((0, 1, 2)),
        AxisAlignment::Y => Some((1, 2, 0)),
        AxisAlignment::Z => Some((2, 0, 1)),
        AxisAlignment::General => None,
    }
}

/// The pose of the joint's body in its parent's frame at position `q`:
/// the fixed placement, then the joint's own motion (a rotation by
/// `|axis|·q` about the axis, or a translation by `axis·q`).
#[inline(always)]
pub fn joint_transform<S: Scalar>(joint: &Joint, q: S) -> Transform<S> {
    match joint.alignment {
        AxisAlignment::X => joint_transform_aligned::<S, 0, 1, 2>(joint, q),
        AxisAlignment::Y => joint_transform_aligned::<S, 1, 2, 0>(joint, q),
        AxisAlignment::Z => joint_transform_aligned::<S, 2, 0, 1>(joint, q),
        AxisAlignment::General => joint_transform_general(joint, q),
    }
}

/// The angle of a revolute joint at position `q`: `|axis|·q`.
#[inline(always)]
fn joint_angle<S: Scalar>(joint: &Joint, q: S) -> S {
    if joint.axis_norm == 1.0 {
        q
    } else {
        q * joint.axis_norm_in::<S>()
    }
}

/// [`joint_transform`] for any axis, by Rodrigues' formula and full products
/// with the placement.
#[inline(always)]
pub(crate) fn joint_transform_general<S: Scalar>(joint: &Joint, q: S) -> Transform<S> {
    let place = joint.placement_in::<S>();
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => {
            let (s, c) = joint_angle(joint, q).sin_cos();
            let r = match joint.file_unit_axis::<S>() {
                Some(unit) => crate::spatial::rodrigues_generic(&unit, s, c),
                None => S::axis_rotation(&joint.axis, &joint.unit_axis, s, c),
            };
            let rot = if joint.placement_rotation_is_identity { r } else { place.rot.mul_mat(&r) };
            Transform { rot, trans: place.trans }
        }
        JointKind::Prismatic => {
            let d = joint.axis_in::<S>().scale(q);
            let d = if joint.placement_rotation_is_identity { d } else { place.rot.mul_vec(&d) };
            Transform { rot: place.rot, trans: place.trans + d }
        }
    }
}

/// [`joint_transform`] for an axis along `±e_K`; `(I, J)` are the other two
/// indices in cyclic order.
#[inline(always)]
fn joint_transform_aligned<S: Scalar, const K: usize, const I: usize, const J: usize>(
    joint: &Joint,
    q: S,
) -> Transform<S> {
    let identity = joint.placement_rotation_is_identity;
    let trans = joint.placement_translation_in::<S>();
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => {
            let (s, c) = joint_angle(joint, q).sin_cos();
            // About −e_K the rotation is the one about e_K by minus the angle.
            let s = if joint.unit_axis.0[K] < 0.0 { -s } else { s };
            // The rotation about e_K: c, −s / s, c in rows and columns I, J.
            let rot = if identity {
                let (z, o) = (S::zero(), S::one());
                let mut r = [[z; 3]; 3];
                r[K][K] = o;
                r[I][I] = c;
                r[I][J] = -s;
                r[J][I] = s;
                r[J][J] = c;
                Mat3(r)
            } else {
                // P·R: column I is c·P_I + s·P_J, column J is c·P_J − s·P_I,
                // column K is P_K.
                let p = joint.placement_rotation_in::<S>().0;
                let mut r = p;
                for row in 0..3 {
                    r[row][I] = p[row][I] * c + p[row][J] * s;
                    r[row][J] = p[row][J] * c - p[row][I] * s;
                }
                Mat3(r)
            };
            Transform { rot, trans }
        }
        JointKind::Prismatic => {
            let d = S::from_f64(joint.axis.0[K]) * q;
            if identity {
                let mut t = trans;
                t.0[K] += d;
                Transform { rot: Mat3::identity(), trans: t }
            } else {
                let p = joint.placement_rotation_in::<S>();
                Transform { rot: p, trans: trans + p.col(K).scale(d) }
            }
        }
    }
}

/// `S·x`: the twist of a joint moving at rate `x`, in the joint's frame.
#[inline(always)]
pub fn motion<S: Scalar>(joint: &Joint, x: S) -> Motion<S> {
    let a = match aligned_indices(joint.alignment) {
        Some((k, _, _)) => {
            let mut a = Vec3::zero();
            a.0[k] = S::from_f64(joint.axis.0[k]) * x;
            a
        }
        None => joint.axis_in::<S>().scale(x),
    };
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => Motion::new(a, Vec3::zero()),
        JointKind::Prismatic => Motion::new(Vec3::zero(), a),
    }
}

/// `m + S·x`, adding only the non-zero terms.
#[inline(always)]
pub fn add_motion<S: Scalar>(joint: &Joint, m: &mut Motion<S>, x: S) {
    let part = match joint.kind {
        JointKind::Revolute | JointKind::Continuous => &mut m.ang,
        JointKind::Prismatic => &mut m.lin,
    };
    add_axis(joint, part, x);
}

/// `u + a·x` for the joint's axis `a`, adding only the non-zero terms.
#[inline(always)]
pub(crate) fn add_axis<S: Scalar>(joint: &Joint, u: &mut Vec3<S>, x: S) {
    match aligned_indices(joint.alignment) {
        Some((k, _, _)) => u.0[k] += S::from_f64(joint.axis.0[k]) * x,
        None => *u += joint.axis_in::<S>().scale(x),
    }
}

/// `u × (a·x)` for the joint's axis `a`, computing only the non-zero terms.
#[inline(always)]
pub(crate) fn cross_axis<S: Scalar>(joint: &Joint, u: &Vec3<S>, x: S) -> Vec3<S> {
    match aligned_indices(joint.alignment) {
        Some((k, i, j)) => {
            // u × e_k = u_j e_i − u_i e_j
            let w = S::from_f64(joint.axis.0[k]) * x;
            let mut r = Vec3::zero();
            r.0[i] = u.0[j] * w;
            r.0[j] = -(u.0[i] * w);
            r
        }
        None => u.cross(&joint.axis_in::<S>().scale(x)),
    }
}

/// `v ×ₘ (S·x)`: the velocity-product acceleration of a body moving with
/// twist `v` whose joint moves at rate `x`.
#[inline(always)]
pub fn cross_motion<S: Scalar>(joint: &Joint, v: &Motion<S>, x: S) -> Motion<S> {
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => {
            Motion { ang: cross_axis(joint, &v.ang, x), lin: cross_axis(joint, &v.lin, x) }
        }
        JointKind::Prismatic => Motion { ang: Vec3::zero(), lin: cross_axis(joint, &v.ang, x) },
    }
}

/// `I·S`: the momentum of a rigid body moving with its joint at unit rate.
#[inline(always)]
pub fn inertia_times_subspace<S: Scalar>(joint: &Joint, inertia: &Inertia<S>) -> Force<S> {
    match aligned_indices(joint.alignment) {
        Some((k, _, _)) => {
            let a = S::from_f64(joint.axis.0[k]);
            match joint.kind {
                // (Ī e_k a, −h × e_k a)
                JointKind::Revolute | JointKind::Continuous => {
                    let [xx, yy, zz, xy, xz, yz] = inertia.ibar.0;
                    let col = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]][k];
                    Force { ang: Vec3(col).scale(a), lin: -cross_axis(joint, &inertia.h, S::one()) }
                }
                // (h × e_k a, m e_k a)
                JointKind::Prismatic => {
                    let mut lin = Vec3::zero();
                    lin.0[k] = a * inertia.mass;
                    Force { ang: cross_axis(joint, &inertia.h, S::one()), lin }
                }
            }
        }
        None => inertia.mul_motion(&motion(joint, S::one())),
    }
}

/// `Sᵀ·f`: the generalised force of a wrench on the joint.
#[inline(always)]
pub fn project<S: Scalar>(joint: &Joint, f: &Force<S>) -> S {
    let part = match joint.kind {
        JointKind::Revolute | JointKind::Continuous => &f.ang,
        JointKind::Prismatic => &f.lin,
    };
    match aligned_indices(joint.alignment) {
        Some((k, _, _)) => S::from_f64(joint.axis.0[k]) * part.0[k],
        None => joint.axis_in::<S>().dot(part),
    }
}

/// `Sᵀ·m` for a motion vector (used where a motion is projected, e.g. the
/// body Jacobian's transpose).
#[inline(always)]
pub fn motion_dot<S: Scalar>(joint: &Joint, m: &Motion<S>) -> S {
    project(joint, &Force { ang: m.ang, lin: m.lin })
}

/// The rotation part of a joint's transform (its pose in the parent), as an
/// operator on 3-vectors. Besides the general matrix, a revolute joint with
/// an aligned axis and an unrotated placement turns about a coordinate axis
/// (one row and column of the matrix are those of the identity): the
/// products then skip the known zeros and ones. The stored matrix is the
/// same in every case, so the results are those of the general products up
/// to rounding.
pub(crate) trait Rotation<S: Scalar> {
    /// `R·v`.
    fn mul(&self, v: &Vec3<S>) -> Vec3<S>;
    /// `Rᵀ·v`.
    fn tr_mul(&self, v: &Vec3<S>) -> Vec3<S>;
    /// `R·S·Rᵀ` for a symmetric `S`.
    #[inline(always)]
    fn rotate_sym(&self, s: &Sym3<S>) -> Sym3<S> {
        let m = s.to_mat();
        // T = R·S column by column; R·S·Rᵀ = R·Tᵀ, whose column c is R·(row c of T).
        let t = [self.mul(&m.col(0)), self.mul(&m.col(1)), self.mul(&m.col(2))];
        let row = |c: usize| Vec3([t[0].0[c], t[1].0[c], t[2].0[c]]);
        let (c0, c1, c2) = (self.mul(&row(0)), self.mul(&row(1)), self.mul(&row(2)));
        Sym3([c0.0[0], c1.0[1], c2.0[2], c1.0[0], c2.0[0], c2.0[1]])
    }
    /// `R·M·Rᵀ`.
    #[inline(always)]
    fn rotate_mat(&self, m: &Mat3<S>) -> Mat3<S> {
        let t = [self.mul(&m.col(0)), self.mul(&m.col(1)), self.mul(&m.col(2))];
        let row = |c: usize| Vec3([t[0].0[c], t[1].0[c], t[2].0[c]]);
        // R·M·Rᵀ = (R·(R·M)ᵀ)ᵀ: its row c is R·(row c of R·M)
        Mat3([self.mul(&row(0)).0, self.mul(&row(1)).0, self.mul(&row(2)).0])
    }
}

/// Any rotation matrix.
pub(crate) struct Dense<'a, S>(pub &'a Mat3<S>);

/// A rotation matrix about `e_K`; `(I, J)` are the other indices in cyclic
/// order.
pub(crate) struct AboutAxis<'a, S, const K: usize, const I: usize, const J: usize>(pub &'a Mat3<S>);

impl<S: Scalar> Rotation<S> for Dense<'_, S> {
    #[inline(always)]
    fn mul(&self, v: &Vec3<S>) -> Vec3<S> {
        self.0.mul_vec(v)
    }
    #[inline(always)]
    fn tr_mul(&self, v: &Vec3<S>) -> Vec3<S> {
        self.0.tr_mul_vec(v)
    }
    #[inline(always)]
    fn rotate_sym(&self, s: &Sym3<S>) -> Sym3<S> {
        s.rotate(self.0)
    }
    #[inline(always)]
    fn rotate_mat(&self, m: &Mat3<S>) -> Mat3<S> {
        self.0.mul_mat(m).mul_mat(&self.0.transpose())
    }
}

impl<S: Scalar, const K: usize, const I: usize, const J: usize> Rotation<S> for AboutAxis<'_, S, K, I, J> {
    #[inline(always)]
    fn mul(&self, v: &Vec3<S>) -> Vec3<S> {
        let (m, v) = (&self.0 .0, &v.0);
        let mut o = *v;
        o[I] = m[I][I] * v[I] + m[I][J] * v[J];
        o[J] = m[J][I] * v[I] + m[J][J] * v[J];
        Vec3(o)
    }
    #[inline(always)]
    fn tr_mul(&self, v: &Vec3<S>) -> Vec3<S> {
        let (m, v) = (&self.0 .0, &v.0);
        let mut o = *v;
        o[I] = m[I][I] * v[I] + m[J][I] * v[J];
        o[J] = m[I][J] * v[I] + m[J][J] * v[J];
        Vec3(o)
    }
    /// In the plane (I, J) a symmetric 2×2 block is `yy·1 + [[d, e], [e, 0]]`
    /// with `d = xx − yy`: the rotation leaves `yy·1` alone, and the rest
    /// takes five products with the joint's `c²`, `s²`, `s·c`, `2s·c` and
    /// `c² − s²` (fewer when `yy` or `e` is zero, as in a regrouped inertia);
    /// column K turns by θ.
    #[inline(always)]
    fn rotate_sym(&self, s: &Sym3<S>) -> Sym3<S> {
        let m = s.to_mat().0;
        let (c, sn) = (self.0 .0[I][I], self.0 .0[J][I]);
        let (cc, ss, sc) = (c * c, sn * sn, sn * c);
        let (sc2, c2) = (sc * S::from_f64(2.0), cc - ss);
        let (yy, d, e) = (m[J][J], m[I][I] - m[J][J], m[I][J]);
        let col = self.mul(&Vec3([m[0][K], m[1][K], m[2][K]]));
        let mut r = [[S::zero(); 3]; 3];
        r[I][I] = (cc * d - sc2 * e) + yy;
        r[J][J] = (ss * d + sc2 * e) + yy;
        r[I][J] = sc * d + c2 * e;
        r[J][I] = r[I][J];
        r[K][K] = m[K][K];
        r[I][K] = col.0[I];
        r[K][I] = col.0[I];
        r[J][K] = col.0[J];
        r[K][J] = col.0[J];
        Sym3::from_mat_upper(&Mat3(r))
    }
    /// As [`Self::rotate_sym`]: the (I, J) block is `yy·1 + [[d, p], [q, 0]]`;
    /// column K and row K turn by θ.
    #[inline(always)]
    fn rotate_mat(&self, b: &Mat3<S>) -> Mat3<S> {
        let m = &b.0;
        let (c, sn) = (self.0 .0[I][I], self.0 .0[J][I]);
        let (cc, ss, sc) = (c * c, sn * sn, sn * c);
        let (yy, d, p, q) = (m[J][J], m[I][I] - m[J][J], m[I][J], m[J][I]);
        let scd = sc * d;
        let scpq = sc * (p + q);
        let col = self.mul(&Vec3([m[0][K], m[1][K], m[2][K]]));
        let row = self.mul(&Vec3([m[K][0], m[K][1], m[K][2]]));
        let mut r = [[S::zero(); 3]; 3];
        r[I][I] = (cc * d - scpq) + yy;
        r[J][J] = (ss * d + scpq) + yy;
        r[I][J] = (scd - ss * q) + cc * p;
        r[J][I] = (scd + cc * q) - ss * p;
        r[K][K] = m[K][K];
        r[I][K] = col.0[I];
        r[J][K] = col.0[J];
        r[K][I] = row.0[I];
        r[K][J] = row.0[J];
        Mat3(r)
    }
}

/// A rotation whose entries are all 0 or ±1 (a quarter-turn placement):
/// row `a` has `sign[a]` in column `col[a]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SignedPermutation {
    col: [usize; 3],
    negative: [bool; 3],
}

impl SignedPermutation {
    /// `r` as a signed permutation, if it is one.
    #[inline(always)]
    pub(crate) fn of(r: &Mat3<f64>) -> Option<SignedPermutation> {
        let mut col = [0; 3];
        let mut negative = [false; 3];
        for a in 0..3 {
            let row = &r.0[a];
            let mut found = None;
            for (b, &x) in row.iter().enumerate() {
                if x == 1.0 || x == -1.0 {
                    if found.is_some() {
                        return None;
                    }
                    found = Some(b);
                    negative[a] = x < 0.0;
                } else if x != 0.0 {
                    return None;
                }
            }
            col[a] = found?;
        }
        (col[0] != col[1] && col[1] != col[2] && col[0] != col[2]).then_some(SignedPermutation { col, negative })
    }
    #[inline(always)]
    fn signed<S: Scalar>(negative: bool, x: S) -> S {
        if negative {
            -x
        } else {
            x
        }
    }
    /// `P·M·Pᵀ`: entry (a, b) is `±M[col a][col b]`.
    #[inline(always)]
    fn conjugate<S: Scalar>(&self, m: &Mat3<S>) -> Mat3<S> {
        Mat3(std::array::from_fn(|a| {
            std::array::from_fn(|b| Self::signed(self.negative[a] != self.negative[b], m.0[self.col[a]][self.col[b]]))
        }))
    }
    /// `Pᵀ·M`.
    #[inline(always)]
    fn tr_mul_mat<S: Scalar>(&self, m: &Mat3<S>) -> Mat3<S> {
        let mut o = *m;
        for a in 0..3 {
            o.0[self.col[a]] = m.0[a].map(|x| Self::signed(self.negative[a], x));
        }
        o
    }
}

/// A rotation `P·R_K(θ)`: a signed permutation `P` after a turn about
/// `e_K`. Vectors are rotated by the product itself, as [`Dense`] does;
/// inertias and 3×3 blocks are turned about `e_K` first (the short products
/// of [`AboutAxis`] on `turn = Pᵀ·rot`), then permuted, which the dense
/// products with `P·R_K(θ)` cannot see.
pub(crate) struct Permuted<'a, S, const K: usize, const I: usize, const J: usize> {
    rot: &'a Mat3<S>,
    p: SignedPermutation,
    turn: Mat3<S>,
}

impl<'a, S: Scalar, const K: usize, const I: usize, const J: usize> Permuted<'a, S, K, I, J> {
    #[inline(always)]
    pub(crate) fn new(p: SignedPermutation, rot: &'a Mat3<S>) -> Self {
        Permuted { rot, p, turn: p.tr_mul_mat(rot) }
    }
}

impl<S: Scalar, const K: usize, const I: usize, const J: usize> Rotation<S> for Permuted<'_, S, K, I, J> {
    #[inline(always)]
    fn mul(&self, v: &Vec3<S>) -> Vec3<S> {
        self.rot.mul_vec(v)
    }
    #[inline(always)]
    fn tr_mul(&self, v: &Vec3<S>) -> Vec3<S> {
        self.rot.tr_mul_vec(v)
    }
    #[inline(always)]
    fn rotate_sym(&self, s: &Sym3<S>) -> Sym3<S> {
        let t = AboutAxis::<S, K, I, J>(&self.turn).rotate_sym(s);
        Sym3::from_mat_upper(&self.p.conjugate(&t.to_mat()))
    }
    #[inline(always)]
    fn rotate_mat(&self, m: &Mat3<S>) -> Mat3<S> {
        self.p.conjugate(&AboutAxis::<S, K, I, J>(&self.turn).rotate_mat(m))
    }
}

/// [`Scalar::TRACED`] of a matrix's scalar.
#[inline(always)]
pub(crate) fn traced<S: Scalar>(_: &Mat3<S>) -> bool {
    S::TRACED
}

/// Runs `$body` with `$r` bound to the [`Rotation`] of the joint's transform
/// `$x` (a `Transform` computed by [`joint_transform`] for this joint),
/// chosen from the model's constants. A quarter-turn placement before an
/// aligned axis is taken as [`Permuted`] only when tracing
/// ([`Scalar::TRACED`]): on `f64` the extra arms made the generic CRBA
/// slower (code size; `docs/performance.md`), and there the arm is compiled
/// out.
macro_rules! with_rotation {
    ($joint:expr, $x:expr, |$r:ident| $body:expr) => {{
        use $crate::algorithms::joint::{AboutAxis, Dense};
        use $crate::model::{AxisAlignment, JointKind};
        let joint: &$crate::model::Joint = $joint;
        let rot = &$x.rot;
        match (joint.placement_rotation_is_identity, joint.kind, joint.alignment) {
            (_, JointKind::Prismatic, _) => {
                let $r = Dense(rot);
                $body
            }
            (true, _, AxisAlignment::X) => {
                let $r = AboutAxis::<_, 0, 1, 2>(rot);
                $body
            }
            (true, _, AxisAlignment::Y) => {
                let $r = AboutAxis::<_, 1, 2, 0>(rot);
                $body
            }
            (true, _, AxisAlignment::Z) => {
                let $r = AboutAxis::<_, 2, 0, 1>(rot);
                $body
            }
            (false, _, alignment) if $crate::algorithms::joint::traced(rot) => {
                match ($crate::algorithms::joint::SignedPermutation::of(&joint.placement.rot), alignment) {
                    (Some(p), AxisAlignment::X) => {
                        let $r = $crate::algorithms::joint::Permuted::<_, 0, 1, 2>::new(p, rot);
                        $body
                    }
                    (Some(p), AxisAlignment::Y) => {
                        let $r = $crate::algorithms::joint::Permuted::<_, 1, 2, 0>::new(p, rot);
                        $body
                    }
                    (Some(p), AxisAlignment::Z) => {
                        let $r = $crate::algorithms::joint::Permuted::<_, 2, 0, 1>::new(p, rot);
                        $body
                    }
                    _ => {
                        let $r = Dense(rot);
                        $body
                    }
                }
            }
            _ => {
                let $r = Dense(rot);
                $body
            }
        }
    }};
}
pub(crate) use with_rotation;

/// [`Transform::motion_to_child`] for a joint's transform.
#[inline(always)]
pub fn motion_to_child<S: Scalar>(joint: &Joint, x: &Transform<S>, m: &Motion<S>) -> Motion<S> {
    with_rotation!(joint, x, |r| Motion { ang: r.tr_mul(&m.ang), lin: r.tr_mul(&(m.lin + m.ang.cross(&x.trans))) })
}

/// [`Transform::force_to_parent`] for a joint's transform.
#[inline(always)]
pub fn force_to_parent<S: Scalar>(joint: &Joint, x: &Transform<S>, f: &Force<S>) -> Force<S> {
    with_rotation!(joint, x, |r| {
        let lin = r.mul(&f.lin);
        Force { ang: r.mul(&f.ang) + x.trans.cross(&lin), lin }
    })
}

/// [`Transform::inertia_to_parent`] for a joint's transform.
#[inline(always)]
pub fn inertia_to_parent<S: Scalar>(joint: &Joint, x: &Transform<S>, i: &Inertia<S>) -> Inertia<S> {
    with_rotation!(joint, x, |r| {
        let h = r.mul(&i.h);
        let p = &x.trans;
        let ibar =
            r.rotate_sym(&i.ibar) + Sym3::cross_shift(&h, p) + Sym3::cross_shift(p, p).scale(i.mass * S::from_f64(0.5));
        Inertia { mass: i.mass, h: h + p.scale(i.mass), ibar }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn joint(kind: JointKind, axis: [f64; 3], placement: Transform<f64>) -> Joint {
        let axis = Vec3(axis);
        let n = axis.norm();
        Joint {
            name: "j".into(),
            kind,
            placement,
            axis,
            limits: None,
            unit_axis: axis.scale(1.0 / n),
            axis_norm: n,
            alignment: AxisAlignment::of(&axis),
            placement_rotation_is_identity: placement.rot == Mat3::identity(),
            file_values: None,
        }
    }

    fn assert_close(a: &[f64], b: &[f64], what: &str) {
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!((x - y).abs() <= 1e-15, "{what}[{i}]: {x} vs {y}");
        }
    }

    /// Every aligned class, both signs, unit and non-unit axes, revolute and
    /// prismatic, with and without a rotated placement: the short cuts give
    /// Rodrigues' formula and the dense spatial products.
    #[test]
    fn aligned_short_cuts_equal_the_general_formulas() {
        let placements = [
            Transform::new(Mat3::identity(), Vec3([0.1, -0.2, 0.3])),
            Transform::new(Mat3::from_rpy(0.4, -1.2, 2.5), Vec3([-0.3, 0.05, 0.2])),
            // quarter turns (signed permutations)
            Transform::new(Mat3([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]), Vec3([0.0, 0.136, 0.0])),
            Transform::new(Mat3([[0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]]), Vec3([0.2, 0.0, -0.1])),
        ];
        let inertia = crate::spatial::Inertia::from_mass_com_inertia(
            2.0,
            Vec3([0.1, -0.05, 0.2]),
            crate::spatial::Sym3([0.3, 0.25, 0.2, 0.01, -0.02, 0.015]),
        );
        let v = Motion::from_array([0.3, -0.7, 0.5, 0.2, 0.9, -0.4]);
        let f = Force::from_array([1.5, -0.3, 0.8, -2.0, 0.6, 1.1]);
        let mut cases = 0;
        let mut permuted = 0;
        for k in 0..3 {
            for sign in [1.0, -1.0] {
                for len in [1.0, 0.6] {
                    for kind in [JointKind::Revolute, JointKind::Continuous, JointKind::Prismatic] {
                        for place in &placements {
                            let mut axis = [0.0; 3];
                            axis[k] = sign * len;
                            let j = joint(kind, axis, *place);
                            assert_eq!(j.alignment, [AxisAlignment::X, AxisAlignment::Y, AxisAlignment::Z][k]);
                            for q in [0.0, 0.3, -1.7, 2.9, 12.0] {
                                let got = joint_transform(&j, q);
                                let (rot, trans) = if kind == JointKind::Prismatic {
                                    (place.rot, place.trans + place.rot.mul_vec(&j.axis.scale(q)))
                                } else {
                                    (place.rot.mul_mat(&Mat3::from_axis_angle(&j.unit_axis, len * q)), place.trans)
                                };
                                let flat = |m: &Mat3<f64>| m.0.concat();
                                assert_close(&flat(&got.rot), &flat(&rot), "rotation");
                                assert_close(&got.trans.0, &trans.0, "translation");
                                // the general path agrees too
                                let gen = joint_transform_general(&j, q);
                                assert_close(&flat(&gen.rot), &flat(&rot), "general rotation");
                                // the joint-aware products equal the transform's own
                                let m = motion_to_child(&j, &got, &v).to_array();
                                assert_close(&m, &got.motion_to_child(&v).to_array(), "motion_to_child");
                                let p = force_to_parent(&j, &got, &f).to_array();
                                assert_close(&p, &got.force_to_parent(&f).to_array(), "force_to_parent");
                                let (ia, ib) = (inertia_to_parent(&j, &got, &inertia), got.inertia_to_parent(&inertia));
                                assert_close(&ia.ibar.0, &ib.ibar.0, "inertia_to_parent");
                                assert_close(&ia.h.0, &ib.h.0, "inertia_to_parent h");
                                let b = Mat3([[0.3, -1.2, 0.4], [0.9, 0.1, -0.5], [0.2, 0.7, 1.1]]);
                                let dense = got.rot.mul_mat(&b).mul_mat(&got.rot.transpose());
                                let sparse = with_rotation!(&j, got, |r| r.rotate_mat(&b));
                                assert_close(&flat(&sparse), &flat(&dense), "rotate_mat");
                                // The traced form of a quarter-turn placement, on f64.
                                if let (Some(p), false) =
                                    (SignedPermutation::of(&place.rot), kind == JointKind::Prismatic)
                                {
                                    let s3 = crate::spatial::Sym3([0.3, 0.25, 0.2, 0.01, -0.02, 0.015]);
                                    fn check<R: Rotation<f64>>(r: R, s3: &Sym3<f64>, b: &Mat3<f64>) -> [Vec<f64>; 4] {
                                        let v = Vec3([0.4, -1.1, 0.7]);
                                        [
                                            r.rotate_sym(s3).0.to_vec(),
                                            r.rotate_mat(b).0.concat(),
                                            r.mul(&v).0.to_vec(),
                                            r.tr_mul(&v).0.to_vec(),
                                        ]
                                    }
                                    let got_p = match k {
                                        0 => check(Permuted::<f64, 0, 1, 2>::new(p, &got.rot), &s3, &b),
                                        1 => check(Permuted::<f64, 1, 2, 0>::new(p, &got.rot), &s3, &b),
                                        _ => check(Permuted::<f64, 2, 0, 1>::new(p, &got.rot), &s3, &b),
                                    };
                                    let want_p = check(Dense(&got.rot), &s3, &b);
                                    for (g, w) in got_p.iter().zip(&want_p) {
                                        assert_close(g, w, "permuted");
                                    }
                                    permuted += 1;
                                }
                            }
                            // S·x, Sᵀf, v ×ₘ S·x, I·S, m + S·x against the dense forms
                            let s = Motion::from_array(j.motion_subspace());
                            let x = -1.3;
                            assert_close(&motion(&j, x).to_array(), &s.scale(x).to_array(), "motion");
                            assert_close(&[project(&j, &f)], &[s.dot(&f)], "project");
                            assert_close(&[motion_dot(&j, &v)], &[s.dot(&Force::new(v.ang, v.lin))], "motion_dot");
                            let c = cross_motion(&j, &v, x);
                            assert_close(&c.to_array(), &v.cross_motion(&s.scale(x)).to_array(), "cross");
                            let is = inertia_times_subspace(&j, &inertia);
                            assert_close(&is.to_array(), &inertia.mul_motion(&s).to_array(), "I·S");
                            let mut m = v;
                            add_motion(&j, &mut m, x);
                            assert_close(&m.to_array(), &(v + s.scale(x)).to_array(), "add_motion");
                            cases += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(cases, 144);
        // identity and the two quarter turns, revolute and continuous, 5 angles
        assert_eq!(permuted, 3 * 2 * 2 * 3 * 2 * 5);
    }
}
