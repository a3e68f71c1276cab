//! A URDF's numbers as the file writes them: each decimal read to
//! double-double precision ([`DoubleDouble::from_decimal`]), and the poses,
//! axes and inertias they define, for the model's file values
//! ([`FileValue`](super::FileValue)).
//!
//! Each is checked against what urdf-rs read (the `f64` the description
//! holds): a number must round to the same `f64`, a rotation agree to
//! 1e-12. Where they do not, the item has no file value and the precise
//! scalars compute with its `f64` value, as f64 does. (urdf-rs turns a
//! quaternion within 0.00447 rad of gimbal lock into the rpy of the lock
//! itself; such an origin has no file value.)

use super::description::{FileInertial, Inertial};
use super::file_values::{FileTransform, FileValue, FileVec3};
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};
use crate::DoubleDouble;

type DD = DoubleDouble;

/// `N` decimals separated by white space, each to double-double precision
/// and rounding to the `f64` Rust's parser reads; `None` otherwise.
pub(super) fn decimals<const N: usize>(text: &str) -> Option<[DD; N]> {
    let mut out = [DD::ZERO; N];
    let mut tokens = text.split_whitespace();
    for x in &mut out {
        let token = tokens.next()?;
        let value = DD::from_decimal(token)?;
        let parsed: f64 = token.parse().ok()?;
        // the nearest f64 to the value: its leading part, or a neighbour at a tie
        if (value - DD::from(parsed)).to_f64().abs() > 0.500_001 * ulp(parsed) {
            return None;
        }
        *x = value;
    }
    tokens.next().is_none().then_some(out)
}

/// The spacing of the `f64` numbers at `x`.
fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x == 0.0 {
        f64::from_bits(1)
    } else {
        f64::from_bits(x.to_bits() + 1) - x
    }
}

/// The rotation of the quaternion (x, y, z, w), normalised.
fn quaternion_rotation([x, y, z, w]: [DD; 4]) -> Mat3<DD> {
    let s = DD::from(2.0) / (x * x + y * y + z * z + w * w);
    let (xx, yy, zz) = (x * x * s, y * y * s, z * z * s);
    let (xy, xz, yz) = (x * y * s, x * z * s, y * z * s);
    let (wx, wy, wz) = (w * x * s, w * y * s, w * z * s);
    let one = DD::ONE;
    Mat3([
        [one - (yy + zz), xy - wz, xz + wy],
        [xy + wz, one - (xx + zz), yz - wx],
        [xz - wy, yz + wx, one - (xx + yy)],
    ])
}

/// The pose an `<origin>` element's attributes give, from the file's
/// decimals: `xyz`, and `rpy` or (from URDF 1.1 on, as urdf-rs reads it)
/// `quat_xyzw`; a missing attribute is zero. `None` if a number does not read.
pub(super) fn origin(attrs: &[(String, String)], version: (u32, u32)) -> Option<Transform<DD>> {
    let get = |key: &str| attrs.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
    let zeros = [DD::ZERO; 3];
    let xyz = get("xyz").map_or(Some(zeros), decimals::<3>)?;
    let rot = match get("quat_xyzw") {
        Some(q) if version >= (1, 1) => quaternion_rotation(decimals::<4>(q)?),
        _ => {
            let [r, p, y] = get("rpy").map_or(Some(zeros), decimals::<3>)?;
            Mat3::rpy(r, p, y)
        }
    };
    Some(Transform::new(rot, Vec3(xyz)))
}

/// The file's pose as the file value of `pose` (what urdf-rs read), if
/// they agree: the translation rounds to it, the rotation is within 1e-12.
pub(super) fn file_transform(file: Option<Transform<DD>>, pose: &Transform<f64>) -> Option<FileTransform> {
    let file = file?;
    let rounds = file.trans.0.iter().zip(&pose.trans.0).all(|(a, b)| a.to_f64() == *b);
    let close =
        file.rot.0.iter().flatten().zip(pose.rot.0.iter().flatten()).all(|(a, b)| (a.to_f64() - b).abs() <= 1e-12);
    (rounds && close).then(|| FileValue::new(*pose, file))
}

/// The file's axis as the file value of `axis` (the description's, maybe
/// normalised), if it rounds to `read` (what urdf-rs read).
pub(super) fn file_axis(file: Option<[DD; 3]>, read: &[f64; 3], axis: &Vec3<f64>) -> Option<FileVec3> {
    let file = file?;
    file.iter().zip(read).all(|(a, b)| a.to_f64() == *b).then(|| FileValue::new(*axis, Vec3(file)))
}

/// A link's `<inertial>` as the file writes it: the mass, the `<origin>`
/// (the centre of mass and the inertia's axes) and `[ixx, iyy, izz, ixy,
/// ixz, iyz]`.
#[derive(Clone, Copy, Debug)]
pub(super) struct RawInertial {
    pub mass: DD,
    pub origin: Transform<DD>,
    pub inertia: [DD; 6],
}

/// An `<inertial>`'s numbers from the file's decimals, as the elements
/// are read.
#[derive(Debug, Default)]
pub(super) struct InertialDecimals {
    /// The `<origin>`'s pose, once it is read (`Some(None)`: unreadable).
    pub origin: Option<Option<Transform<DD>>>,
    pub mass: Option<DD>,
    pub inertia: Option<[DD; 6]>,
}

impl InertialDecimals {
    /// The `<inertial>` (a missing origin is the identity), if every number read.
    pub fn read(&self) -> Option<RawInertial> {
        let origin = self.origin.unwrap_or(Some(Transform::identity()))?;
        Some(RawInertial { mass: self.mass?, origin, inertia: self.inertia? })
    }
}

/// The `<inertia>` element's six numbers, in dynagen's order.
pub(super) fn inertia(attrs: &[(String, String)]) -> Option<[DD; 6]> {
    let get = |key: &str| attrs.iter().find(|(k, _)| k == key).and_then(|(_, v)| decimals::<1>(v)).map(|[x]| x);
    Some([get("ixx")?, get("iyy")?, get("izz")?, get("ixy")?, get("ixz")?, get("iyz")?])
}

/// The link's spatial inertia in its frame from the file's decimals, as
/// the file value of `inertial` (what urdf-rs read), if the numbers round
/// to it and the origin agrees.
pub(super) fn file_inertial(file: Option<RawInertial>, inertial: &Inertial) -> Option<FileInertial> {
    let file = file?;
    let origin = file_transform(Some(file.origin), &inertial.origin)?;
    let numbers = core::iter::once(&file.mass).chain(&file.inertia);
    let read = core::iter::once(&inertial.mass).chain(&inertial.inertia.0);
    if !numbers.zip(read).all(|(a, b)| a.to_f64() == *b) {
        return None;
    }
    let t = origin.value_for(&inertial.origin)?;
    let at_com = Sym3(file.inertia).rotate(&t.rot);
    Some(FileValue::new(*inertial, Inertia::from_mass_com_inertia(file.mass, t.trans, at_com)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_written_or_not_at_all() {
        let [a, b] = decimals::<2>(" 0.1  -2.5e-3 ").unwrap();
        assert_eq!((a.hi, b.hi), (0.1, -2.5e-3));
        assert!(a.lo != 0.0, "one tenth is not an f64");
        for bad in ["0.1", "0.1 0.2 0.3", "0.1 nan", "0.1 1e999", "0.1 0x1"] {
            assert!(decimals::<2>(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn rotations_from_rpy_and_quaternions_are_orthonormal_to_thirty_digits() {
        let attrs = |k: &str, v: &str| vec![(k.to_string(), v.to_string())];
        let rpy = origin(&attrs("rpy", "0.1 -1.2 2.3"), (1, 0)).unwrap().rot;
        // half a turn about (1, 1, 0)/√2: x = y = 1/√2, a quaternion of length 1 ± ulp
        let quat = origin(&attrs("quat_xyzw", "0.7071067811865476 0.7071067811865476 0 0"), (1, 1)).unwrap().rot;
        for r in [rpy, quat] {
            let rtr = r.transpose().mul_mat(&r);
            for i in 0..3 {
                for j in 0..3 {
                    let want = if i == j { DD::ONE } else { DD::ZERO };
                    assert!((rtr.0[i][j] - want).to_f64().abs() < 1e-30, "RᵀR[{i}][{j}]");
                }
            }
        }
        // the quaternion's axis is fixed: R·(1, 1, 0) = (1, 1, 0)
        let v = quat.mul_vec(&Vec3([DD::ONE, DD::ONE, DD::ZERO]));
        assert!((v.0[0] - DD::ONE).to_f64().abs() < 1e-30 && v.0[2].to_f64().abs() < 1e-30);
        // before URDF 1.1 the quaternion is ignored, as urdf-rs does
        let ignored = origin(&attrs("quat_xyzw", "0 0 1 0"), (1, 0)).unwrap().rot;
        assert_eq!(ignored, Mat3::identity());
    }

    #[test]
    fn a_file_value_needs_what_urdf_rs_read() {
        let file = origin(&[("xyz".into(), "0.1 0.2 0.3".into()), ("rpy".into(), "0 0 0.5".into())], (1, 0));
        let pose = Transform::new(Mat3::from_rpy(0.0, 0.0, 0.5), Vec3([0.1, 0.2, 0.3]));
        assert!(file_transform(file, &pose).is_some());
        let moved = Transform::new(pose.rot, Vec3([0.1, 0.2, 0.30000000000000004]));
        assert!(file_transform(file, &moved).is_none(), "a translation one ulp off");
        let turned = Transform::new(Mat3::from_rpy(0.0, 0.0, 0.5001), pose.trans);
        assert!(file_transform(file, &turned).is_none(), "a rotation 1e-4 rad off");
    }
}
