//! Joints that move together without moving any mass: structurally
//! dependent joints, whose mass matrix is singular at every configuration
//! (two coincident joints with one axis moving one body give
//! M = [[a, a], [a, a]]). Inverse dynamics is still defined; forward
//! dynamics is not.
//!
//! Found by factorising M(q) = LᵀDL ([`crate::algorithms::ldlt`]'s order,
//! from the tips up) at a few pseudo-random configurations: a pivot at or
//! below [`PIVOT_RTOL`] times its joint's diagonal entry vanishes, and the
//! joints that then move without moving mass are the non-zero entries of
//! the null vector x with L·x = e_k. A joint whose pivot vanishes at every
//! configuration tried is dependent.

use super::{JointKind, Model};
use crate::algorithms::{crba, ldlt, Loads, Workspace};

/// A pivot this small relative to its joint's diagonal entry of M vanishes
/// (rounding leaves about 1e-16 of it when joints coincide).
const PIVOT_RTOL: f64 = 1e-10;

/// The configurations tried at load time.
const CONFIGURATIONS: usize = 3;

/// The check runs on models up to this many joints (M is n×n).
const MAX_DOF: usize = 1000;

/// Each set of joints (indices, ascending) that moves without moving any
/// mass at configuration `q`: one per vanishing pivot of M(q).
pub(crate) fn singular_sets_at(model: &Model, q: &[f64]) -> Vec<Vec<usize>> {
    let n = model.nv();
    // the tree of the factorisation (the kinematic tree without mimic
    // joints; a floating base's six coordinates as a chain ahead of them)
    let parent = |k: usize| ldlt::parent(model, k);
    let mut m = vec![0.0; n * n];
    let mut ws = Workspace::<f64>::new(model);
    crba::crba(model, &mut ws, q, Loads::none(), &mut m);
    let diag: Vec<f64> = (0..n).map(|i| m[i * n + i].abs()).collect();
    // LᵀDL from the tips up, as ldlt::factorise, but a vanishing pivot's
    // row is left out of the elimination (its L entries set to zero).
    let mut vanished = Vec::new();
    for k in (0..n).rev() {
        let d = m[k * n + k];
        if !d.is_finite() || d.abs() <= PIVOT_RTOL * diag[k] {
            vanished.push(k);
            let mut i = parent(k);
            while let Some(ii) = i {
                m[k * n + ii] = 0.0;
                i = parent(ii);
            }
            continue;
        }
        ldlt::eliminate(n, &parent, &mut m, k, |x| x / d);
    }
    // For each vanishing pivot k, x with L·x = e_k (from the base down:
    // x_i = [i = k] − Σ over ancestors j of L[i][j]·x_j) is a motion of
    // the joints that moves no mass.
    vanished
        .into_iter()
        .rev()
        .map(|k| {
            let mut x = vec![0.0; n];
            for i in k..n {
                let mut acc = if i == k { 1.0 } else { 0.0 };
                let mut j = parent(i);
                while let Some(jj) = j {
                    if jj < k {
                        break;
                    }
                    acc -= m[i * n + jj] * x[jj];
                    j = parent(jj);
                }
                x[i] = acc;
            }
            let big = x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            (0..n).filter(|&i| x[i].abs() > 1e-8 * big).collect()
        })
        .collect()
}

/// The sets of structurally dependent joints: those whose pivot vanishes
/// at every one of a few pseudo-random configurations (joint names).
pub(super) fn dependent_joints(model: &Model) -> Vec<Vec<String>> {
    let n = model.dof();
    if model.nv() == 0 || model.nv() > MAX_DOF {
        return Vec::new();
    }
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        // xorshift64*: deterministic, so a model loads the same every time
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut common: Option<Vec<Vec<usize>>> = None;
    for _ in 0..CONFIGURATIONS {
        // a floating base: a position and a unit quaternion ahead of the joints
        let mut pose: Vec<f64> = (0..7 * usize::from(model.is_floating())).map(|_| next()).collect();
        if let Some(quat) = pose.get_mut(3..7) {
            let norm = quat.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
            quat.iter_mut().for_each(|x| *x /= norm);
        }
        let q: Vec<f64> = pose
            .into_iter()
            .chain((0..n).map(|k| &model.bodies[model.joint_body(k)]).map(|b| match (b.joint.kind, &b.joint.limits) {
                (JointKind::Prismatic, Some(l)) if l.lower.is_finite() && l.upper.is_finite() => {
                    0.5 * (l.lower + l.upper) + 0.5 * (l.upper - l.lower) * next()
                }
                (JointKind::Prismatic, _) => 0.3 * next(),
                _ => std::f64::consts::PI * next(),
            }))
            .collect();
        let sets = singular_sets_at(model, &q);
        common = Some(match common {
            None => sets,
            Some(c) => c.into_iter().filter(|s| sets.contains(s)).collect(),
        });
    }
    common.unwrap_or_default().iter().map(|s| names(model, s)).collect()
}

/// The names of a set of velocity coordinates: the joints', and a floating
/// base's six coordinates as one entry naming its link.
fn names(model: &Model, set: &[usize]) -> Vec<String> {
    let base = model.nv() - model.dof();
    let mut out = Vec::new();
    if set.iter().any(|&k| k < base) {
        out.push(format!("{} (the floating base)", model.root));
    }
    out.extend(
        set.iter().filter(|&&k| k >= base).map(|&k| model.bodies[model.joint_body(k - base)].joint.name.clone()),
    );
    out
}

impl Model {
    /// The joints whose motion together moves no mass at configuration `q`
    /// (NQ entries: on a floating base, the base's pose first), M(q)
    /// singular there: one list of names per vanishing pivot of M(q), a
    /// floating base named by its link; empty where M(q) is regular.
    /// Forward dynamics is undefined at such a q.
    ///
    /// # Panics
    /// If `q` does not have NQ entries.
    pub fn singular_joints_at(&self, q: &[f64]) -> Vec<Vec<String>> {
        assert_eq!(q.len(), self.nq(), "singular_joints_at: q must have NQ entries");
        singular_sets_at(self, q).iter().map(|s| names(self, s)).collect()
    }
    /// The sets of joints found dependent at load time (a
    /// [`ModelWarning::DependentJoints`](super::ModelWarning::DependentJoints)
    /// each): forward dynamics is undefined for this model.
    pub fn dependent_joints(&self) -> Vec<&[String]> {
        self.warnings
            .iter()
            .filter_map(|w| match w {
                super::ModelWarning::DependentJoints { joints } => Some(joints.as_slice()),
                _ => None,
            })
            .collect()
    }
}
