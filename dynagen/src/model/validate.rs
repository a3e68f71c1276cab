//! Checks of a description that do not need the tree: names, numbers,
//! axes, inertias and unsupported features.

use super::description::{Inertial, JointDescription, JointType, RobotDescription};
use super::{BuildOptions, MimicJoints, ModelError, ModelWarning};
use crate::spatial::{Mat3, Sym3};
use std::collections::HashSet;

/// Relative tolerance of the inertia checks: eigenvalues may be this far
/// below zero relative to the largest one (rounding in a file's printed
/// digits), and no further.
const INERTIA_RTOL: f64 = 1e-9;

/// The lengths a screw axis (one that is not a mere direction) may have.
const SCREW_AXIS_RANGE: (f64, f64) = (1e-100, 1e100);

pub(super) fn check(
    desc: &RobotDescription,
    opts: &BuildOptions,
    warnings: &mut Vec<ModelWarning>,
) -> Result<(), ModelError> {
    if desc.links.is_empty() {
        return Err(ModelError::NoLinks);
    }
    let mut names = HashSet::new();
    for l in &desc.links {
        if !names.insert(l.name.as_str()) {
            return Err(ModelError::DuplicateLink(l.name.clone()));
        }
    }
    let mut jnames = HashSet::new();
    for j in &desc.joints {
        if !jnames.insert(j.name.as_str()) {
            return Err(ModelError::DuplicateJoint(j.name.clone()));
        }
        for (role, link) in [("parent", &j.parent), ("child", &j.child)] {
            if !names.contains(link.as_str()) {
                return Err(ModelError::MissingLink { joint: j.name.clone(), role, link: link.clone() });
            }
        }
        let item = format!("joint \"{}\"", j.name);
        let unsupported = match j.joint_type {
            JointType::Planar => Some("planar joints are"),
            JointType::Spherical => Some("spherical joints are"),
            _ => None,
        };
        if let Some(what) = unsupported {
            return Err(ModelError::Unsupported { joint: j.name.clone(), what: what.to_string() });
        }
        if !j.origin.trans.is_finite() {
            return Err(ModelError::NonFinite { item, what: "origin xyz" });
        }
        check_rotation(&j.origin.rot, &item, "origin")?;
        // a floating joint's axis means nothing (urdf-rs fills in a default)
        if !matches!(j.joint_type, JointType::Fixed | JointType::Floating) {
            if !j.axis.is_finite() {
                return Err(ModelError::NonFinite { item, what: "axis" });
            }
            let norm = j.axis.norm();
            if norm == 0.0 {
                return Err(ModelError::ZeroAxis(j.name.clone()));
            }
            // A screw axis's length scales the joint's motion, and every
            // entry of M(q) by its square: refuse lengths that overflow it
            // rather than report the overflowed inertia.
            if !j.axis_is_direction && !(SCREW_AXIS_RANGE.0..=SCREW_AXIS_RANGE.1).contains(&norm) {
                return Err(ModelError::AxisOutOfRange { joint: j.name.clone(), norm });
            }
        }
        if let Some(l) = &j.limits {
            if ![l.lower, l.upper, l.velocity, l.effort].iter().all(|x| !x.is_nan()) {
                return Err(ModelError::NonFinite { item, what: "limit" });
            }
            // A continuous joint's limits are ignored (URDF); a revolute or
            // prismatic joint whose range is empty is a broken file, and the
            // limits would reach users through inspect and the API.
            if j.joint_type != JointType::Continuous && l.lower > l.upper {
                return Err(ModelError::LimitsReversed { joint: j.name.clone(), lower: l.lower, upper: l.upper });
            }
        }
    }
    if opts.mimic == MimicJoints::Follow {
        for j in desc.joints.iter().filter(|j| j.mimic.is_some()) {
            check_mimic(j, desc)?;
        }
    }
    for l in &desc.links {
        if let Some(inertial) = &l.inertial {
            check_inertial(&l.name, inertial, opts, warnings)?;
        }
    }
    Ok(())
}

/// Whether a joint of this type moves (has a coordinate).
fn moves(t: JointType) -> bool {
    matches!(t, JointType::Revolute | JointType::Continuous | JointType::Prismatic)
}

/// A joint that follows another: finite multiplier and offset, itself a
/// moving joint, and a master that exists, moves and follows no other
/// (so no cycle of masters is possible).
fn check_mimic(j: &JointDescription, desc: &RobotDescription) -> Result<(), ModelError> {
    let Some(m) = &j.mimic else { return Ok(()) };
    let err = |why: String| Err(ModelError::Mimic { joint: j.name.clone(), why });
    let item = format!("joint \"{}\"", j.name);
    if !m.multiplier.is_finite() {
        return Err(ModelError::NonFinite { item, what: "mimic multiplier" });
    }
    if !m.offset.is_finite() {
        return Err(ModelError::NonFinite { item, what: "mimic offset" });
    }
    let kind = |t: JointType| format!("{t:?}").to_lowercase();
    if !moves(j.joint_type) {
        return err(format!(
            "a {} joint cannot follow another (only revolute, continuous and prismatic joints mimic): remove its \
             <mimic>, or read mimic joints as independent joints (the option mimic = independent), which ignores it",
            kind(j.joint_type)
        ));
    }
    if m.joint == j.name {
        return err("it mimics itself".to_string());
    }
    let Some(master) = desc.joints.iter().find(|k| k.name == m.joint) else {
        return err(format!("its master joint \"{}\" does not exist", m.joint));
    };
    if !moves(master.joint_type) {
        return err(format!(
            "its master joint \"{}\" is {}: a mimic joint follows a revolute, continuous or prismatic joint",
            m.joint,
            kind(master.joint_type)
        ));
    }
    if let Some(mm) = &master.mimic {
        if mm.joint == j.name {
            return err(format!(
                "its master joint \"{}\" follows it in turn: mimic joints cannot form a cycle",
                m.joint
            ));
        }
        return err(format!(
            "its master joint \"{}\" follows \"{}\" itself: mimic joints cannot be chained; make \"{}\" follow \"{}\" \
             directly (multiplier {} and offset {})",
            m.joint,
            mm.joint,
            j.name,
            mm.joint,
            m.multiplier * mm.multiplier,
            m.multiplier * mm.offset + m.offset
        ));
    }
    Ok(())
}

/// Checks that a matrix is a rotation (orthonormal, det +1) to a tolerance
/// that admits a file's printed digits.
fn check_rotation(r: &Mat3<f64>, item: &str, what: &'static str) -> Result<(), ModelError> {
    if !r.is_finite() {
        return Err(ModelError::NonFinite { item: item.to_string(), what: "origin rotation" });
    }
    let rtr = r.transpose().mul_mat(r);
    let mut off = 0.0f64;
    for (i, row) in rtr.0.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            off = off.max((x - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let m = &r.0;
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if off > 1e-6 || (det - 1.0).abs() > 1e-6 {
        return Err(ModelError::NotARotation { item: item.to_string(), what });
    }
    Ok(())
}

fn check_inertial(
    link: &str,
    i: &Inertial,
    opts: &BuildOptions,
    warnings: &mut Vec<ModelWarning>,
) -> Result<(), ModelError> {
    let item = format!("link \"{link}\"");
    if !i.mass.is_finite() {
        return Err(ModelError::NonFinite { item, what: "mass" });
    }
    if !i.origin.trans.is_finite() {
        return Err(ModelError::NonFinite { item, what: "inertial origin" });
    }
    check_rotation(&i.origin.rot, &item, "inertial origin")?;
    if !i.inertia.is_finite() {
        return Err(ModelError::NonFinite { item, what: "inertia" });
    }
    if i.mass < 0.0 {
        return Err(ModelError::NegativeMass { link: link.to_string(), mass: i.mass });
    }
    // The eigenvalues of the inertia divided by its largest entry: the
    // closed form squares the entries, which would overflow for entries
    // beyond 1e154 and turn every comparison below false.
    let largest = i.inertia.0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let unit = if largest > 0.0 { Sym3(i.inertia.0.map(|x| x / largest)).eigenvalues() } else { [0.0; 3] };
    let moments = unit.map(|x| x * largest);
    let scale = unit[2].abs().max(f64::MIN_POSITIVE);
    if unit.iter().any(|x| x.is_nan()) {
        return Err(ModelError::InertiaNotPositive { link: link.to_string(), moments });
    }
    if unit[0] < -INERTIA_RTOL * scale {
        if !opts.allow_nonphysical_inertia {
            return Err(ModelError::InertiaNotPositive { link: link.to_string(), moments });
        }
        warnings.push(ModelWarning::NonPhysicalInertia { link: link.to_string(), moments });
        return Ok(());
    }
    if i.mass == 0.0 && unit[2] > 0.0 {
        warnings.push(ModelWarning::InertiaWithoutMass { link: link.to_string() });
    }
    // Σ = tr(I)/2 · 1 − I is the second moment of the mass distribution;
    // it is positive semi-definite for every physical body, which is the
    // triangle inequality on the principal moments.
    let half_trace = 0.5 * (unit[0] + unit[1] + unit[2]);
    if half_trace - unit[2] < -INERTIA_RTOL * scale {
        if opts.strict {
            return Err(ModelError::TriangleInequality { link: link.to_string(), moments });
        }
        warnings.push(ModelWarning::TriangleInequality { link: link.to_string(), moments });
    }
    Ok(())
}
