//! Regrouping of inertial parameters: the part of a body's inertia that its
//! own joint cannot move is carried by the parent instead.
//!
//! A revolute joint turns its body about an axis through the body frame's
//! origin. Along an axis `e_K` of that frame (`I`, `J` the other two), the
//! spatial inertia
//!
//! ```text
//! mass m,   first moment h_K·e_K,   rotational inertia Ī_JJ·(e_I e_Iᵀ + e_J e_Jᵀ)
//! ```
//!
//! is unchanged by a rotation about `e_K`, and its kinetic energy does not
//! depend on the joint's rate either: `ωᵀ(e_I e_Iᵀ + e_J e_Jᵀ)ω = |ω|² − ω_K²`
//! and `ω × e_K` do not change when `q̇` is added to `ω_K`. So moving that
//! part from the body to its parent (rigidly, through the joint's placement)
//! leaves the Lagrangian, hence τ, M, h, g and q̈, exactly as they were. What
//! stays on the body is its mass-free remainder `(0, h_I e_I + h_J e_J,
//! Ī − Ī_JJ·(e_I e_Iᵀ + e_J e_Jᵀ))`: the mass, `h_K` and `Ī_JJ` are now
//! zeros the symbolic graph folds away. A part that reaches a fixed base
//! is dropped; a floating base carries it. For a prismatic joint the body
//! does not turn relative to its parent, and a rotational inertia without
//! mass is the same about every point: its whole `Ī` moves to the parent
//! (so that a prismatic body without children, its frame first moved to its
//! centre of mass by [`center_prismatic_leaves`], keeps only a point mass).
//! This is the regrouping of inertial parameters of Khalil and Kleinfinger
//! (the "base parameters"), written as a transformation of the model's
//! spatial inertias.
//!
//! A difference `Ī_II − Ī_JJ` within [`ROUNDING_TOLERANCE`] of its operands
//! (a body symmetric about its axis, whose two moments differ only by the
//! rounding of the sums that made them) is taken as 0, as the rounding snap
//! does for the model's constants.
//!
//! Bodies are processed from the tips to the root so that a parent is
//! regrouped after what its children moved into it. Joints whose axis is not
//! along a coordinate axis are left as they are. The regrouped inertias are
//! not physical (a body may have no mass and an indefinite `Ī`); they are
//! only used for the generated code, whose results equal the original
//! model's up to rounding (tested against the generic solver).

use super::rounding::ROUNDING_TOLERANCE;
use crate::model::{AxisAlignment, JointKind, Model};
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};

/// The index of the aligned axis and the other two, in `Sym3` storage
/// order `[xx, yy, zz, xy, xz, yz]`: `(K, I, J)`.
fn indices(alignment: AxisAlignment) -> Option<(usize, usize, usize)> {
    match alignment {
        AxisAlignment::X => Some((0, 1, 2)),
        AxisAlignment::Y => Some((1, 2, 0)),
        AxisAlignment::Z => Some((2, 0, 1)),
        AxisAlignment::General => None,
    }
}

/// A copy of `model` with the inertial parameters regrouped (see the
/// documentation of [`CodegenOptions::regroup_inertia`](crate::codegen::CodegenOptions::regroup_inertia)
/// and the comments of `codegen/prepare/regroup.rs`).
pub fn regroup_inertia(model: &Model) -> Model {
    let mut m = model.clone();
    for i in (0..m.bodies.len()).rev() {
        let body = &m.bodies[i];
        let inertia = body.inertia;
        let moved = match (body.joint.kind, indices(body.joint.alignment)) {
            (JointKind::Prismatic, _) => Inertia { mass: 0.0, h: Vec3::zero(), ibar: inertia.ibar },
            (_, Some((k, _, j))) => {
                let mut h = Vec3::zero();
                h.0[k] = inertia.h.0[k];
                let yy = inertia.ibar.0[j];
                let mut ibar = Sym3::zero();
                for d in [0, 1, 2] {
                    if d != k {
                        ibar.0[d] = yy;
                    }
                }
                Inertia { mass: inertia.mass, h, ibar }
            }
            (_, None) => continue,
        };
        // Exact zeros where a parameter moved entirely (x − x = 0).
        let mut rest = Inertia { mass: inertia.mass - moved.mass, h: inertia.h - moved.h, ibar: inertia.ibar };
        for d in 0..6 {
            let (x, y) = (inertia.ibar.0[d], moved.ibar.0[d]);
            let r = x - y;
            // XX − YY of a body symmetric about its axis: 0 up to the
            // rounding of the sums that made XX and YY.
            rest.ibar.0[d] = if r.abs() <= ROUNDING_TOLERANCE * x.abs().max(y.abs()) { 0.0 } else { r };
        }
        let (parent, placement) = (body.parent, body.joint.placement);
        m.bodies[i].inertia = rest;
        let carried = placement.inertia_to_parent(&moved);
        match parent {
            Some(p) => m.bodies[p].inertia = m.bodies[p].inertia.add(&carried),
            // A floating base moves: it carries what reaches it.
            None if m.is_floating() => m.base_inertia = m.base_inertia.add(&carried),
            None => {}
        }
    }
    m
}

/// A copy of `model` in which the frame of every body turning about an
/// aligned axis `e_K` has slid along that axis, so that the placement of
/// its first child has no component along `e_K`.
///
/// A translation along a revolute joint's axis commutes with the turn about
/// it: `T_place·R_K(q)·Trans(δ e_K) = T_place·Trans(δ e_K)·R_K(q)`. Moving a
/// body's origin by `δ e_K` therefore only moves the constant `δ` from the
/// children's placements (and the body's frames and inertia) into the
/// body's own placement, where it is a constant too. Done from the tips to
/// the root, the offsets along the axes move towards the base, and the
/// placements in the middle of a chain get sparser (the UR5's elbow
/// placement `(0, −0.1197, 0.425)` becomes `(0, 0, 0.425)`), which saves
/// products in every `ω × (ω × p)` and `p × f`. The dynamics are those of
/// the original model (the joint axes are the same lines); the frames keep
/// their poses.
pub fn slide_origins_along_axes(model: &Model) -> Model {
    slide_origins_except(model, &[])
}

/// [`slide_origins_along_axes`], leaving the bodies `keep` where they are
/// (the parents of branches run in a loop: sliding one to its first child
/// would make that child's placement differ in shape from its siblings').
pub(crate) fn slide_origins_except(model: &Model, keep: &[usize]) -> Model {
    let mut m = model.clone();
    for i in (0..m.bodies.len()).rev().filter(|i| !keep.contains(i)) {
        let joint = &m.bodies[i].joint;
        let k = match (joint.kind, indices(joint.alignment)) {
            (JointKind::Revolute | JointKind::Continuous, Some((k, _, _))) => k,
            _ => continue,
        };
        let Some(first) = m.bodies.iter().position(|b| b.parent == Some(i)) else { continue };
        let delta = m.bodies[first].joint.placement.trans.0[k];
        if delta == 0.0 {
            continue;
        }
        let mut shift = Vec3::zero();
        shift.0[k] = delta;
        // The body's frame B' sits at δ e_K in B: T_B'B = Trans(−δ e_K).
        let to_new = crate::spatial::Transform::translation(-shift);
        for b in m.bodies.iter_mut().filter(|b| b.parent == Some(i)) {
            b.joint.placement.trans -= shift;
        }
        for f in m.frames.iter_mut().filter(|f| f.body == Some(i)) {
            f.placement.trans -= shift;
        }
        let body = &mut m.bodies[i];
        body.inertia = to_new.inertia_to_parent(&body.inertia);
        let place = &mut body.joint.placement;
        place.trans += place.rot.mul_vec(&shift);
    }
    m
}

/// A copy of `model` in which the frame of every body on a prismatic joint
/// that has no children (a gripper's finger) sits at the body's centre of
/// mass with its parent's axes: the joint's placement loses its rotation,
/// which turns the joint's axis instead.
///
/// A prismatic joint translates its body without turning it, so the body's
/// frame may be any frame fixed to the body: with `T_BB' = (Q, c)` (the new
/// frame in the old), `T_place·Trans(a q)·T_BB' = (T_place·T_BB')·Trans(Qᵀa q)`.
/// With `Q = R_placeᵀ` and `c` the centre of mass, the new placement is the
/// translation to the centre of mass at `q = 0`, the axis is `R_place·a`
/// (components equal up to the rounding of that product are made equal,
/// `equal_magnitudes`) and the body's first moment is zero. Once
/// [`regroup_inertia`] has moved its whole rotational inertia to the parent,
/// the body is a point mass at its origin: its wrench is `m·a` with no
/// moment, the products of its angular velocity are never needed, no
/// rotation is applied between it and its parent, and the parent receives
/// `p × f`. The frames attached to the body keep their poses (the
/// children it has none of would have to move). The Lagrangian is the
/// same: only coordinates fixed to the body change.
pub fn center_prismatic_leaves(model: &Model) -> Model {
    let mut m = model.clone();
    for i in 0..m.bodies.len() {
        let (joint0, inertia0) = (m.bodies[i].joint.clone(), m.bodies[i].inertia);
        if joint0.kind != JointKind::Prismatic || inertia0.mass <= 0.0 || m.bodies.iter().any(|b| b.parent == Some(i)) {
            continue;
        }
        let place = joint0.placement;
        let to_new = Transform::new(place.rot.transpose(), inertia0.h.scale(1.0 / inertia0.mass));
        let back = to_new.inverse();
        let mut inertia = back.inertia_to_parent(&inertia0);
        // m·c − m·(h/m): zero up to rounding
        inertia.h = Vec3::zero();
        let joint = &mut m.bodies[i].joint;
        joint.placement = Transform::new(Mat3::identity(), equal_magnitudes(place.compose(&to_new).trans));
        joint.axis = equal_magnitudes(place.rot.mul_vec(&joint0.axis));
        joint.unit_axis = equal_magnitudes(place.rot.mul_vec(&joint0.unit_axis));
        joint.refresh_derived();
        m.bodies[i].inertia = inertia;
        for f in m.frames.iter_mut().filter(|f| f.body == Some(i)) {
            f.placement = back.compose(&f.placement);
        }
    }
    m
}

/// `v` with components whose magnitudes differ only by rounding (within
/// [`ROUNDING_TOLERANCE`] of the largest) given one magnitude, the larger:
/// `Rz(−π/4)·e_y` is `(0.7071067811865475, 0.7071067811865476, 0)`, and
/// with equal components its products with `q` are one.
fn equal_magnitudes(mut v: Vec3<f64>) -> Vec3<f64> {
    let scale = v.0.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for a in 0..3 {
        for b in a + 1..3 {
            let (x, y) = (v.0[a], v.0[b]);
            if x != 0.0 && x.abs() != y.abs() && (x.abs() - y.abs()).abs() <= ROUNDING_TOLERANCE * scale {
                let m = x.abs().max(y.abs());
                v.0[a] = m.copysign(x);
                v.0[b] = m.copysign(y);
            }
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::{crba, rnea, Loads, Workspace};
    use crate::model::AxisAlignment;

    fn ur5() -> Model {
        Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap()
    }

    /// τ and M of the regrouped model equal the original's (the generic
    /// solver on both), and the regrouped bodies lost their mass.
    /// Sliding the body frames along their axes keeps every frame's pose.
    #[test]
    fn slid_frames_keep_their_poses() {
        use crate::algorithms::kinematics::{forward_kinematics, frame_pose};
        for name in ["ur5", "panda", "torso_two_arms"] {
            let path = format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"));
            let model = Model::from_urdf_file(&path).unwrap();
            let slid = slide_origins_along_axes(&center_prismatic_leaves(&model));
            let q: Vec<f64> = (0..model.dof()).map(|i| 0.3 + 0.8 * i as f64).collect();
            let (mut wa, mut wb) = (Workspace::new(&model), Workspace::new(&slid));
            forward_kinematics(&model, &mut wa, &q);
            forward_kinematics(&slid, &mut wb, &q);
            for f in 0..model.frames.len() {
                let (a, b) = (frame_pose(&model, &wa, f), frame_pose(&slid, &wb, f));
                for (x, y) in a.trans.0.iter().zip(&b.trans.0) {
                    assert!((x - y).abs() < 1e-14, "{name} frame {f}: {:?} vs {:?}", a.trans, b.trans);
                }
                for (x, y) in a.rot.0.iter().flatten().zip(b.rot.0.iter().flatten()) {
                    assert!((x - y).abs() < 1e-14, "{name} frame {f}");
                }
            }
        }
    }

    /// The Panda's fingers become point masses at their origins, placed
    /// without rotation, mirror images of each other to the bit; a finger
    /// frame keeps its pose; and the centred (not yet regrouped) model has
    /// the original's τ, M and ABA forward dynamics.
    #[test]
    fn prismatic_leaves_become_point_masses() {
        use crate::algorithms::aba::aba;
        use crate::algorithms::kinematics::{forward_kinematics, frame_pose};
        let path = format!("{}/robots/panda.urdf", env!("CARGO_MANIFEST_DIR"));
        let model = Model::from_urdf_file(&path).unwrap();
        let centred = center_prismatic_leaves(&model);
        let grouped = regroup_inertia(&slide_origins_along_axes(&centred));
        let (f1, f2) = (model.dof() - 2, model.dof() - 1);
        for f in [f1, f2] {
            let (b, c) = (&grouped.bodies[f], &centred.bodies[f]);
            assert_eq!(b.joint.kind, JointKind::Prismatic);
            assert_eq!((b.inertia.mass, b.inertia.h.0, b.inertia.ibar.0), (0.015, [0.0; 3], [0.0; 6]), "finger {f}");
            assert!(b.joint.placement_rotation_is_identity && b.joint.alignment == AxisAlignment::General);
            // the axis is the hand's ±y, both components 1/√2 exactly alike
            let a = c.joint.axis.0;
            assert_eq!(a[0].abs(), a[1].abs());
            assert!((a[0].abs() - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-16 && a[2] == 0.0);
            assert_eq!(c.inertia.h.0, [0.0; 3]);
        }
        let (p1, p2) = (&centred.bodies[f1].joint, &centred.bodies[f2].joint);
        assert_eq!(p1.axis.0, (-p2.axis).0);
        assert_eq!(p1.placement.trans.0[..2], (-p2.placement.trans).0[..2]);
        assert_eq!(p1.placement.trans.0[2], p2.placement.trans.0[2]);
        let n = model.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.4 * i as f64 - 1.0 + if i >= f1 { 1.01 } else { 0.0 }).collect();
        let qd: Vec<f64> = (0..n).map(|i| 0.9 - 0.3 * i as f64).collect();
        let qdd: Vec<f64> = (0..n).map(|i| -0.5 + 0.7 * (i % 4) as f64).collect();
        let (mut wa, mut wb) = (Workspace::new(&model), Workspace::new(&centred));
        forward_kinematics(&model, &mut wa, &q);
        forward_kinematics(&centred, &mut wb, &q);
        let tcp = model.frame_index("panda_leftfinger").unwrap();
        let (a, b) = (frame_pose(&model, &wa, tcp), frame_pose(&centred, &wb, tcp));
        for (x, y) in
            a.trans.0.iter().chain(a.rot.0.iter().flatten()).zip(b.trans.0.iter().chain(b.rot.0.iter().flatten()))
        {
            assert!((x - y).abs() < 1e-15, "finger frame: {x} vs {y}");
        }
        let g = model.gravity;
        let close = |a: &[f64], b: &[f64], what: &str| {
            let norm = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (x, y) in a.iter().zip(b) {
                assert!((x - y).abs() <= 1e-13 * norm, "{what}: {x} vs {y}");
            }
        };
        let (mut ta, mut tb) = (vec![0.0; n], vec![0.0; n]);
        rnea::rnea(&model, &mut wa, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut ta);
        rnea::rnea(&centred, &mut wb, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut tb);
        close(&ta, &tb, "τ");
        let (mut ma, mut mb) = (vec![0.0; n * n], vec![0.0; n * n]);
        crba::crba(&model, &mut wa, &q, Loads::none(), &mut ma);
        crba::crba(&centred, &mut wb, &q, Loads::none(), &mut mb);
        close(&ma, &mb, "M");
        aba(&model, &mut wa, &q, &qd, &ta, Loads::gravity(&g), &mut ma[..n]);
        aba(&centred, &mut wb, &q, &qd, &ta, Loads::gravity(&g), &mut mb[..n]);
        close(&ma[..n], &mb[..n], "q̈");
        close(&ma[..n], &qdd, "q̈ = the q̈ τ was made of");
    }

    #[test]
    fn regrouped_model_has_the_same_dynamics() {
        for name in ["ur5", "panda", "torso_two_arms"] {
            let path = format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"));
            let model = Model::from_urdf_file(&path).unwrap();
            let grouped = regroup_inertia(&slide_origins_along_axes(&center_prismatic_leaves(&model)));
            let n = model.dof();
            let (mut wa, mut wb) = (Workspace::new(&model), Workspace::new(&grouped));
            let q: Vec<f64> = (0..n).map(|i| 0.7 * i as f64 - 1.1).collect();
            let qd: Vec<f64> = (0..n).map(|i| 1.3 - 0.4 * i as f64).collect();
            let qdd: Vec<f64> = (0..n).map(|i| 0.5 + 0.9 * (i % 3) as f64).collect();
            let g = model.gravity;
            let (mut ta, mut tb) = (vec![0.0; n], vec![0.0; n]);
            rnea::rnea(&model, &mut wa, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut ta);
            rnea::rnea(&grouped, &mut wb, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut tb);
            let norm = ta.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (a, b) in ta.iter().zip(&tb) {
                assert!((a - b).abs() <= 1e-13 * norm, "{name} τ: {a} vs {b}");
            }
            let (mut ma, mut mb) = (vec![0.0; n * n], vec![0.0; n * n]);
            crba::crba(&model, &mut wa, &q, Loads::none(), &mut ma);
            crba::crba(&grouped, &mut wb, &q, Loads::none(), &mut mb);
            let norm = ma.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (a, b) in ma.iter().zip(&mb) {
                assert!((a - b).abs() <= 1e-13 * norm, "{name} M: {a} vs {b}");
            }
        }
        let grouped = regroup_inertia(&ur5());
        assert!(grouped.bodies.iter().all(|b| b.inertia.mass == 0.0));
        // the elbow's placement lost its component along the shoulder's axis
        let slid = slide_origins_along_axes(&ur5());
        assert_eq!(ur5().bodies[2].joint.placement.trans.0, [0.0, -0.1197, 0.425]);
        assert_eq!(slid.bodies[2].joint.placement.trans.0[1], 0.0);
        // the first body keeps only its rotational inertia about its axis
        let first = &grouped.bodies[0].inertia;
        assert_eq!(first.h.0[2], 0.0);
        assert_eq!(first.ibar.0[1], 0.0);
    }
}
