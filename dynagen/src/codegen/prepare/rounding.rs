//! Model constants that are 0 or ±1 up to rounding.
//!
//! A robot file that turns a frame by `rpy="0 1.5707963267948966 0"` means
//! a quarter turn, but `cos(1.5707963267948966)` is `6.1e-17` in `f64`, not
//! 0, and every product with it would survive into the generated code as an
//! operation. With [`CodegenOptions::snap_rounding`](crate::codegen::CodegenOptions::snap_rounding) (on by default) the
//! generator first replaces, in a copy of the model, every constant within
//! [`ROUNDING_TOLERANCE`] (4 ulps) *times the scale of the quantity it
//! belongs to* of 0, or (rotation entries and unit axes) of ±1, by that
//! value:
//!
//! - rotation entries and unit-axis components: scale 1 (both are entries
//!   of unit vectors);
//! - translations, first moments of mass `m·c`, axes as given, gravity:
//!   the vector's norm;
//! - rotational inertias: the sum of the diagonal's magnitudes.
//!
//! Why this tolerance: each of these constants was itself computed in `f64`
//! (from rpy angles, a normalisation, an inertia rotation and shift), which
//! already put rounding errors of a few ulps of the quantity's scale in it.
//! A change of that size is below what the file's own numbers determine
//! after parsing, and it changes the generated results by no more than the
//! generic solver's own rounding (the tests compare at 1e-12). A larger
//! tolerance would need the precision the file printed, which the model no
//! longer knows, and a file's number is taken at its word: `1.570796325`
//! (the ur_description UR5's quarter turn) is 1.8e-9 rad away from π/2,
//! more than its nine printed decimals allow for, so its `cos` of `1.8e-9`
//! stays. Masses are never changed. What was replaced is listed in
//! [`GeneratedModule::snapped`](crate::codegen::GeneratedModule::snapped) and counted in the header.

use crate::model::Model;
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};

/// The tolerance, relative to the scale of the quantity a constant belongs
/// to: four units of roundoff. A rotation entry computed from an rpy angle
/// carries rounding errors of this size already.
pub const ROUNDING_TOLERANCE: f64 = 4.0 * f64::EPSILON;

/// A model constant that was replaced by 0 or ±1.
#[derive(Clone, Debug, PartialEq)]
pub struct SnappedConstant {
    /// Where it is, e.g. `joint shoulder_lift_joint: placement rotation [0][0]`.
    pub place: String,
    /// The value in the model.
    pub from: f64,
    /// The value used (0, 1 or −1).
    pub to: f64,
}

struct Snapper {
    snapped: Vec<SnappedConstant>,
}

impl Snapper {
    fn value(&mut self, x: &mut f64, scale: f64, unit: bool, place: impl Fn() -> String) {
        if !x.is_finite() || !scale.is_finite() {
            // Not a rounding matter; the generator reports it.
            return;
        }
        let tol = ROUNDING_TOLERANCE * scale;
        let to = if *x != 0.0 && x.abs() <= tol {
            0.0
        } else if unit && x.abs() != 1.0 && (x.abs() - 1.0).abs() <= tol {
            x.signum()
        } else {
            return;
        };
        self.snapped.push(SnappedConstant { place: place(), from: *x, to });
        *x = to;
    }
    fn rotation(&mut self, m: &mut Mat3<f64>, place: &str) {
        for (i, row) in m.0.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                self.value(x, 1.0, true, || format!("{place}: rotation [{i}][{j}]"));
            }
        }
    }
    fn vector(&mut self, v: &mut Vec3<f64>, place: &str) {
        let scale = v.norm();
        for (i, x) in v.0.iter_mut().enumerate() {
            self.value(x, scale, false, || format!("{place}[{i}]"));
        }
    }
    fn transform(&mut self, t: &mut Transform<f64>, place: &str) {
        self.rotation(&mut t.rot, &format!("{place} placement"));
        self.vector(&mut t.trans, &format!("{place} placement translation"));
    }
    fn inertia(&mut self, i: &mut Inertia<f64>, place: &str) {
        self.vector(&mut i.h, &format!("{place} first moment of mass"));
        let s: &mut Sym3<f64> = &mut i.ibar;
        let scale = s.0[0].abs() + s.0[1].abs() + s.0[2].abs();
        let names = ["xx", "yy", "zz", "xy", "xz", "yz"];
        for (k, x) in s.0.iter_mut().enumerate() {
            self.value(x, scale, false, || format!("{place} rotational inertia {}", names[k]));
        }
    }
}

/// A copy of `model` with every rotation entry, unit-axis component, axis
/// norm, translation, first-moment and rotational-inertia component that is
/// within [`ROUNDING_TOLERANCE`] of 0 (or, for rotations and unit axes, of
/// ±1) times the scale of its quantity replaced by that value, and the list
/// of what was replaced. Masses and the joint's own numbers otherwise are
/// left as they are.
pub fn snap_rounding(model: &Model) -> (Model, Vec<SnappedConstant>) {
    let mut m = model.clone();
    let mut s = Snapper { snapped: Vec::new() };
    for b in &mut m.bodies {
        let j = &mut b.joint;
        let place = format!("joint {}", j.name);
        s.transform(&mut j.placement, &place);
        s.rotation_axis(j, &place);
        // what the algorithms read from the placement and the axis
        j.refresh_derived();
        s.inertia(&mut b.inertia, &format!("body {}", b.name));
    }
    for f in &mut m.frames {
        s.transform(&mut f.placement, &format!("frame {}", f.name));
    }
    s.vector(&mut m.gravity, "gravity");
    (m, s.snapped)
}

impl Snapper {
    fn rotation_axis(&mut self, j: &mut crate::model::Joint, place: &str) {
        for (i, x) in j.unit_axis.0.iter_mut().enumerate() {
            self.value(x, 1.0, true, || format!("{place}: unit axis[{i}]"));
        }
        let mut norm = j.axis_norm;
        self.value(&mut norm, 1.0, true, || format!("{place}: axis norm"));
        if norm == 1.0 && j.axis_norm != 1.0 {
            j.axis_norm = 1.0;
            j.axis = j.unit_axis;
        } else {
            self.vector(&mut j.axis, &format!("{place}: axis"));
        }
    }
}
