//! The robot file's constants beyond `f64`.
//!
//! A robot file's numbers are exact decimals, and so are the rotations,
//! unit axes and inertias they define. The model holds them rounded to
//! `f64`, which f64, f32 and generated code compute with. Where the
//! torques cancel the bias forces (τ ≈ h at high speed), that rounding, an
//! ε-sized change of the robot, costs as many digits as f64 arithmetic
//! does; so the model also keeps, for the precise scalars
//! ([`Scalar::FILE_CONSTANTS`]), each constant as the file defines it,
//! computed in double-double from the file's decimals: a [`FileValue`].
//!
//! A file value remembers the `f64` value it refines and is used only while
//! the model still holds that value: a model edited after it was read (a
//! field set by hand, a scene that moves inertia) computes with the edited
//! `f64` value, never with a stale file value.

use super::{Body, Frame, Joint, Model};
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};
use crate::{DoubleDouble, Scalar};

/// A model constant as the robot file defines it, to double-double
/// precision, beside the `f64` value the model holds for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FileValue<F, D> {
    of: F,
    value: D,
}

impl<F: PartialEq, D> FileValue<F, D> {
    /// The file's value `value` of the constant the model holds as `of`.
    pub fn new(of: F, value: D) -> Self {
        FileValue { of, value }
    }
    /// The `f64` value this refines.
    pub fn of(&self) -> &F {
        &self.of
    }
    /// The file's value, if the model's value is still `current`.
    #[inline(always)]
    pub fn value_for(&self, current: &F) -> Option<&D> {
        (self.of == *current).then_some(&self.value)
    }
}

/// A placement (rotation and translation) from the file.
pub type FileTransform = FileValue<Transform<f64>, Transform<DoubleDouble>>;
/// A vector (a joint axis as a description writes it) from the file.
pub type FileVec3 = FileValue<Vec3<f64>, Vec3<DoubleDouble>>;
/// A joint's axis from the file, refining [`Joint::axis`].
pub type FileAxis = FileValue<Vec3<f64>, ExactAxis>;

/// A joint axis in double-double: the axis S·q̇ moves along (for a
/// direction, its unit vector), its unit vector, and its length, the factor
/// between the joint's position and its angle (exactly 1 for a direction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactAxis {
    /// The joint's axis ([`Joint::axis`]).
    pub axis: Vec3<DoubleDouble>,
    /// `axis / |axis|`.
    pub unit: Vec3<DoubleDouble>,
    /// `|axis|`.
    pub norm: DoubleDouble,
}

impl ExactAxis {
    /// A direction (the joint turns by exactly q about it: `axis` is its
    /// unit vector), or a screw axis (by `|axis|·q`), from its exact value.
    pub fn new(axis: Vec3<DoubleDouble>, direction: bool) -> Self {
        let norm = axis.norm_squared().sqrt();
        let unit = axis.scale(DoubleDouble::ONE / norm);
        if direction {
            ExactAxis { axis: unit, unit, norm: DoubleDouble::ONE }
        } else {
            ExactAxis { axis, unit, norm }
        }
    }
}
/// A spatial inertia from the file.
pub type FileInertia = FileValue<Inertia<f64>, Inertia<DoubleDouble>>;

/// A joint's constants from the file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointFileValues {
    /// The placement in the parent body's frame (fixed joints above it
    /// composed in).
    pub placement: Option<FileTransform>,
    /// The axis, its unit vector and its length.
    pub axis: Option<FileAxis>,
}

#[inline(always)]
fn vec3<S: Scalar>(v: &Vec3<DoubleDouble>) -> Vec3<S> {
    Vec3(v.0.map(S::from_double_double))
}

#[inline(always)]
fn mat3<S: Scalar>(m: &Mat3<DoubleDouble>) -> Mat3<S> {
    Mat3(m.0.map(|row| row.map(S::from_double_double)))
}

#[inline(always)]
fn transform<S: Scalar>(t: &Transform<DoubleDouble>) -> Transform<S> {
    Transform { rot: mat3(&t.rot), trans: vec3(&t.trans) }
}

#[inline(always)]
fn inertia<S: Scalar>(i: &Inertia<DoubleDouble>) -> Inertia<S> {
    Inertia { mass: S::from_double_double(i.mass), h: vec3(&i.h), ibar: Sym3(i.ibar.0.map(S::from_double_double)) }
}

/// An inertia in `S`: the file's when `S` takes file constants and `file`
/// still refines `value`, else `value` converted.
#[inline(always)]
fn inertia_in<S: Scalar>(value: &Inertia<f64>, file: Option<&FileInertia>) -> Inertia<S> {
    match file.and_then(|f| f.value_for(value)) {
        Some(exact) if S::FILE_CONSTANTS => inertia(exact),
        _ => Inertia::from_f64(value),
    }
}

/// A placement in `S`, as [`inertia_in`].
#[inline(always)]
fn transform_in<S: Scalar>(value: &Transform<f64>, file: Option<&FileTransform>) -> Transform<S> {
    match file.and_then(|f| f.value_for(value)) {
        Some(exact) if S::FILE_CONSTANTS => transform(exact),
        _ => Transform::from_f64(value),
    }
}

impl Joint {
    /// The file's placement, when `S` takes file constants and the model
    /// has it for the current placement.
    #[inline(always)]
    fn file_placement<S: Scalar>(&self) -> Option<&Transform<DoubleDouble>> {
        if !S::FILE_CONSTANTS {
            return None;
        }
        self.file_values.as_ref()?.placement.as_ref()?.value_for(&self.placement)
    }
    /// The placement in the scalar `S`: the file's for a precise scalar
    /// ([`Scalar::FILE_CONSTANTS`]) when the model has it, else the `f64`
    /// one converted ([`Transform::from_f64`]).
    #[inline(always)]
    pub fn placement_in<S: Scalar>(&self) -> Transform<S> {
        match self.file_placement::<S>() {
            Some(t) => transform(t),
            None => Transform::from_f64(&self.placement),
        }
    }
    /// The placement's rotation in `S`, as [`placement_in`](Self::placement_in).
    #[inline(always)]
    pub(crate) fn placement_rotation_in<S: Scalar>(&self) -> Mat3<S> {
        match self.file_placement::<S>() {
            Some(t) => mat3(&t.rot),
            None => S::rotation_constant(&self.placement.rot),
        }
    }
    /// The placement's translation in `S`, as [`placement_in`](Self::placement_in).
    #[inline(always)]
    pub(crate) fn placement_translation_in<S: Scalar>(&self) -> Vec3<S> {
        match self.file_placement::<S>() {
            Some(t) => vec3(&t.trans),
            None => Vec3::from_f64(&self.placement.trans),
        }
    }
    /// The file's axis, when `S` takes file constants and the model has it
    /// for the current axis.
    #[inline(always)]
    fn file_axis<S: Scalar>(&self) -> Option<&ExactAxis> {
        if !S::FILE_CONSTANTS {
            return None;
        }
        self.file_values.as_ref()?.axis.as_ref()?.value_for(&self.axis)
    }
    /// The file's unit axis in `S`, as [`file_axis`](Self::file_axis).
    #[inline(always)]
    pub(crate) fn file_unit_axis<S: Scalar>(&self) -> Option<Vec3<S>> {
        self.file_axis::<S>().map(|a| vec3(&a.unit))
    }
    /// `|axis|` in `S`, the factor between the joint's position and its
    /// angle: the file's for a precise scalar when the model has it, else
    /// [`Scalar::axis_norm_constant`].
    #[inline(always)]
    pub(crate) fn axis_norm_in<S: Scalar>(&self) -> S {
        match self.file_axis::<S>() {
            Some(a) => S::from_double_double(a.norm),
            None => S::axis_norm_constant(&self.axis, self.axis_norm),
        }
    }
    /// The axis (`self.axis`) in `S`: the file's for a precise scalar when
    /// the model has it, else the `f64` one converted.
    #[inline(always)]
    pub fn axis_in<S: Scalar>(&self) -> Vec3<S> {
        match self.file_axis::<S>() {
            Some(a) => vec3(&a.axis),
            None => Vec3::from_f64(&self.axis),
        }
    }
}

impl Body {
    /// The spatial inertia in `S`: the file's for a precise scalar
    /// ([`Scalar::FILE_CONSTANTS`]) when the model has it, else the `f64`
    /// one converted.
    #[inline(always)]
    pub fn inertia_in<S: Scalar>(&self) -> Inertia<S> {
        inertia_in(&self.inertia, self.file_inertia.as_deref())
    }
}

impl Frame {
    /// The placement in `S`, as [`Body::inertia_in`].
    #[inline(always)]
    pub fn placement_in<S: Scalar>(&self) -> Transform<S> {
        transform_in(&self.placement, self.file_placement.as_deref())
    }
}

impl Model {
    /// The root's own inertia (a floating base's) in `S`, as [`Body::inertia_in`].
    #[inline(always)]
    pub fn base_inertia_in<S: Scalar>(&self) -> Inertia<S> {
        inertia_in(&self.base_inertia, self.file_base_inertia.as_deref())
    }
    /// Whether any constant of the model has its file value (a robot read
    /// from a URDF file, or described in Rust with joint origins or
    /// direction axes); a precise scalar then computes the file's robot.
    pub fn has_file_values(&self) -> bool {
        self.bodies.iter().any(|b| b.file_inertia.is_some() || b.joint.file_values.is_some())
    }
    /// This model without its file values: what the precise scalars compute
    /// is then the `f64` model (each rotation re-orthonormalised, each axis
    /// re-normalised at their precision), the robot an ε away from the
    /// file's that f64 computes. For comparisons.
    pub fn without_file_values(mut self) -> Self {
        for b in &mut self.bodies {
            b.file_inertia = None;
            b.joint.file_values = None;
        }
        for f in &mut self.frames {
            f.file_placement = None;
        }
        self.file_base_inertia = None;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const URDF: &str = r#"<robot name="r"><link name="base"/>
      <link name="a"><inertial><origin xyz="0.1 0 0.05" rpy="0.3 0 0"/><mass value="1.7"/>
        <inertia ixx="0.011" iyy="0.013" izz="0.017" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="tool"><inertial><mass value="0.3"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="a"/>
        <origin xyz="0 0.1 0.2" rpy="0.1 0.2 0.3"/><axis xyz="0.267 -0.535 0.802"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="fix" type="fixed"><parent link="a"/><child link="tool"/><origin xyz="0.3 0 0" rpy="0 0.7 0"/></joint>
    </robot>"#;

    #[test]
    fn a_urdf_model_keeps_the_files_values_beside_their_f64_rounding() {
        let model = Model::from_urdf_str(URDF).unwrap();
        assert!(model.has_file_values());
        let (body, joint) = (&model.bodies[0], &model.bodies[0].joint);
        // the file's values round to (within a few ulps of) the model's f64 ones, and differ from them
        let exact = joint.placement_in::<DoubleDouble>();
        let rounded = joint.placement_in::<f64>();
        let diff = |a: DoubleDouble, b: f64| (a - DoubleDouble::from(b)).to_f64().abs();
        let worst = exact.rot.0.iter().flatten().zip(rounded.rot.0.iter().flatten()).map(|(a, b)| diff(*a, *b));
        let worst = worst.fold(0.0, f64::max);
        assert!(worst > 0.0 && worst < 1e-15, "rotation: {worst:e}");
        let axis = joint.axis_in::<DoubleDouble>();
        let norm = (axis.dot(&axis) - DoubleDouble::ONE).to_f64().abs();
        assert!(norm < 1e-31, "the file's unit axis is a unit vector to {norm:e}");
        // the tool's inertia, merged through the rotated fixed joint, in both
        let (i_exact, i_f64) = (body.inertia_in::<DoubleDouble>(), body.inertia_in::<f64>());
        assert!(diff(i_exact.mass, 2.0) < 1e-31, "1.7 kg + 0.3 kg in decimals");
        assert!(diff(i_exact.ibar.0[0], i_f64.ibar.0[0]) < 1e-16 * i_f64.ibar.0[0]);
        let frame = model.frame("tool").unwrap();
        assert!(frame.file_placement.is_some());
        // f64 and f32 take the f64 values, whatever the model holds beside them
        assert_eq!(rounded, joint.placement);
        assert_eq!(body.inertia_in::<f64>(), body.inertia);
    }

    #[test]
    fn a_robot_described_in_rust_is_exact_as_written() {
        use crate::model::{Inertial, JointDescription, RobotBuilder};
        let (rpy, axis) = ([0.1, -0.7, 2.0], [0.3, -0.5, 0.8]);
        let model = RobotBuilder::new("r")
            .link("base", None)
            .link("a", Some(Inertial::new(1.3, [0.1, 0.2, 0.3], [0.02, 0.03, 0.04, 0.001, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", "a", axis).unit_axis().origin([0.1, 0.0, 0.2], rpy))
            .build()
            .unwrap();
        assert!(model.has_file_values());
        let joint = &model.bodies[0].joint;
        // the rotation from the f64 rpy in double-double, the unit axis of the f64 axis
        let [r, p, y] = rpy.map(DoubleDouble::from);
        assert_eq!(joint.placement_in::<DoubleDouble>().rot, Mat3::rpy(r, p, y));
        let a = Vec3(axis.map(DoubleDouble::from));
        assert_eq!(joint.axis_in::<DoubleDouble>(), a.scale(DoubleDouble::ONE / a.norm_squared().sqrt()));
        // the inertia about the joint's origin from the exact mass, centre and inertia
        let exact = model.bodies[0].inertia_in::<DoubleDouble>();
        let dd = |x: f64| DoubleDouble::from(x);
        let c = Vec3([0.1, 0.2, 0.3].map(dd));
        let want = Inertia::from_mass_com_inertia(dd(1.3), c, Sym3([0.02, 0.03, 0.04, 0.001, 0.0, 0.0].map(dd)));
        assert_eq!(exact, want);
        // a screw axis (the Rust constructors' default) turns by |axis|·q: its length in double-double
        let screw = RobotBuilder::new("s")
            .link("base", None)
            .link("a", Some(Inertial::new(1.0, [0.1, 0.0, 0.0], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0])))
            .joint(JointDescription::revolute("j", "base", "a", axis))
            .build()
            .unwrap();
        let joint = &screw.bodies[0].joint;
        assert_eq!(joint.axis_in::<DoubleDouble>(), a);
        assert_eq!(joint.axis_norm_in::<DoubleDouble>(), a.norm_squared().sqrt());
        assert_eq!(joint.axis_norm_in::<f64>(), joint.axis_norm);
    }

    #[test]
    fn an_edited_constant_drops_its_file_value() {
        let mut model = Model::from_urdf_str(URDF).unwrap();
        model.bodies[0].inertia.mass = 3.0;
        model.bodies[0].joint.placement.trans.0[0] = 0.5;
        let body = &model.bodies[0];
        assert_eq!(body.inertia_in::<DoubleDouble>(), Inertia::from_f64(&body.inertia));
        assert_eq!(body.joint.placement_in::<DoubleDouble>(), Transform::from_f64(&body.joint.placement));
        // the axis was not edited: its file value stays
        assert!(body.joint.file_unit_axis::<DoubleDouble>().is_some());
        let plain = model.without_file_values();
        assert!(!plain.has_file_values() && plain.bodies[0].joint.file_unit_axis::<DoubleDouble>().is_none());
    }
}
