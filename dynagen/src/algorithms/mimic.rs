//! Mimic joints: a joint that follows its master (URDF `<mimic>`,
//! [`Mimic`](crate::model::Mimic)) has no coordinate of its own.
//!
//! The recursions run over the bodies, one coordinate each (the *tree*
//! coordinates, [`Model::tree_nq`]). With G the coupling matrix (a row per
//! body, a column per joint with a coordinate, `G[i][column(i)]` the body's
//! multiplier, 1 for an independent joint) and o the offsets, the bodies'
//! coordinates are
//!
//! ```text
//! q_tree = G q + o,   q̇_tree = G q̇,   q̈_tree = G q̈,
//! ```
//!
//! and by virtual work (a joint's torque does work on its own coordinate,
//! which moves by its multiplier times the master's)
//!
//! ```text
//! τ = Gᵀ τ_tree,   M = Gᵀ M_tree G,   h = Gᵀ h_tree,   g = Gᵀ g_tree,   J = J_tree G.
//! ```
//!
//! **Inside the recursion or around it.** Pinocchio's `JointModelMimic`
//! reads the master's coordinate inside the forward pass and adds the
//! mimic's projected force to the master's torque in the backward pass.
//! Expanding the coordinates before the recursion and projecting its result
//! after is the same arithmetic: one multiply-add per mimic coordinate in,
//! one per mimic torque out (none for a multiplier of 1 and an offset of 0,
//! the Panda's fingers), and each entry of M the same sum of the same tree
//! entries. So the recursions stay as they are and this file does the rest:
//! [`rnea`] and [`crba`] expand and project; the Jacobians add a mimic
//! body's column into its master's.
//!
//! **Forward dynamics.** The articulated-body algorithm cannot take the
//! coupling: its recursion eliminates each body's joint acceleration on its
//! own, which a mimic joint does not have (Pinocchio refuses `aba` on such a
//! model too). A model with mimic joints gets q̈ from the projected system
//! instead, M q̈ = τ − h, by the sparse LᵀDL factorisation
//! ([`ldlt`](super::ldlt)) along the elimination tree of M's pattern (two
//! joints share an entry when a body of one and a body of the other are on
//! one path from the root). On a chain of a few joints (a hand, a gripper)
//! that is as accurate as ABA; on long chains ABA would be the more
//! accurate (`docs/performance.md`).

use super::{crba, kinematics, rnea, Loads, Workspace};
use crate::model::Model;
use crate::Scalar;

/// The bodies' coordinates and results of a coupled call, sized for the
/// tree (empty for a model without mimic joints).
#[derive(Clone, Debug)]
pub(crate) struct TreeScratch<S> {
    pub(crate) q: Vec<S>,
    pub(crate) qd: Vec<S>,
    pub(crate) qdd: Vec<S>,
    pub(crate) out: Vec<S>,
    pub(crate) m: Vec<S>,
}

impl<S> Default for TreeScratch<S> {
    fn default() -> Self {
        TreeScratch { q: Vec::new(), qd: Vec::new(), qdd: Vec::new(), out: Vec::new(), m: Vec::new() }
    }
}

impl<S: Scalar> TreeScratch<S> {
    pub(crate) fn new(model: &Model) -> Self {
        if !model.has_mimic() {
            return TreeScratch::default();
        }
        let (nq, nv) = (model.tree_nq(), model.tree_nv());
        let zeros = |n: usize| vec![S::zero(); n];
        TreeScratch { q: zeros(nq), qd: zeros(nv), qdd: zeros(nv), out: zeros(nv), m: zeros(nv * nv) }
    }
}

/// The leading entries of a floating base in a configuration and in a
/// velocity-side vector (0 and 0 on a fixed base).
fn base_entries(model: &Model) -> (usize, usize) {
    if model.is_floating() {
        (7, 6)
    } else {
        (0, 0)
    }
}

/// Body `i`'s column in the joint vectors (without a floating base's
/// entries) and its factor: its multiplier, 1 for an independent joint.
#[inline(always)]
pub(crate) fn body_column(model: &Model, i: usize) -> (usize, f64) {
    (model.column(i), model.mimic(i).map_or(1.0, |m| m.multiplier))
}

/// Velocity-side tree coordinate `t`: its column in the velocity-side
/// vectors and its factor (a floating base's entries are their own).
#[inline(always)]
fn column_of(model: &Model, t: usize) -> (usize, f64) {
    let (_, base) = base_entries(model);
    match t.checked_sub(base) {
        None => (t, 1.0),
        Some(i) => {
            let (c, k) = body_column(model, i);
            (base + c, k)
        }
    }
}

/// `k·x`, without the product when `k` is 1.
#[inline(always)]
pub(crate) fn times<S: Scalar>(k: f64, x: S) -> S {
    if k == 1.0 {
        x
    } else {
        S::from_f64(k) * x
    }
}

/// Body `i`'s coordinate from the joints' (`q` without a floating base's
/// entries): `m·q_master + o` for a mimic joint.
#[inline(always)]
fn coordinate<S: Scalar>(model: &Model, i: usize, joints: &[S]) -> S {
    let x = joints[model.column(i)];
    match model.mimic(i) {
        Some(m) if m.offset != 0.0 => times(m.multiplier, x) + S::from_f64(m.offset),
        Some(m) => times(m.multiplier, x),
        None => x,
    }
}

/// The bodies' coordinates of a configuration: `m·q_master + o` for a mimic
/// joint, a floating base's seven entries as they are.
pub fn tree_positions<S: Scalar>(model: &Model, q: &[S], out: &mut [S]) {
    let (base, _) = base_entries(model);
    assert!(q.len() == model.nq() && out.len() == model.tree_nq(), "tree_positions: q must have NQ entries");
    out[..base].copy_from_slice(&q[..base]);
    for i in 0..model.bodies.len() {
        out[base + i] = coordinate(model, i, &q[base..]);
    }
}

/// The bodies' rates (or accelerations) of a velocity-side vector: `G v`.
pub fn tree_rates<S: Scalar>(model: &Model, v: &[S], out: &mut [S]) {
    assert!(v.len() == model.nv() && out.len() == model.tree_nv(), "tree_rates: v must have NV entries");
    for (t, o) in out.iter_mut().enumerate() {
        let (c, k) = column_of(model, t);
        *o = times(k, v[c]);
    }
}

/// `Gᵀ f` of a velocity-side tree vector (torques): each column the sum of
/// its bodies' entries times their multipliers.
pub fn project<S: Scalar>(model: &Model, tree: &[S], out: &mut [S]) {
    assert!(tree.len() == model.tree_nv() && out.len() == model.nv(), "project: sizes must fit the model");
    out.fill(S::zero());
    for (t, &x) in tree.iter().enumerate() {
        let (c, k) = column_of(model, t);
        out[c] += times(k, x);
    }
}

/// `Gᵀ M G` of a row-major tree matrix.
pub fn project_matrix<S: Scalar>(model: &Model, tree: &[S], out: &mut [S]) {
    let (nt, n) = (model.tree_nv(), model.nv());
    assert!(tree.len() == nt * nt && out.len() == n * n, "project_matrix: sizes must fit the model");
    out.fill(S::zero());
    for r in 0..nt {
        let (a, ka) = column_of(model, r);
        for c in 0..nt {
            let (b, kb) = column_of(model, c);
            out[a * n + b] += times(ka * kb, tree[r * nt + c]);
        }
    }
}

/// `f` run on the bodies' coordinates of `q` (and of the rates `qd`): the
/// arguments as they are without mimic joints, expanded with them.
pub(crate) fn on_tree<S: Scalar, R>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    f: impl FnOnce(&mut Workspace<S>, &[S], Option<&[S]>) -> R,
) -> R {
    if !model.has_mimic() {
        return f(ws, q, qd);
    }
    let mut t = std::mem::take(&mut ws.tree);
    tree_positions(model, q, &mut t.q);
    if let Some(qd) = qd {
        tree_rates(model, qd, &mut t.qd);
    }
    let out = f(ws, &t.q, qd.map(|_| &t.qd[..]));
    ws.tree = t;
    out
}

/// Inverse dynamics of a model with mimic joints: [`rnea::rnea`] on the
/// bodies' coordinates, projected (the armature, per joint with a
/// coordinate, added after). Not inlined into [`rnea::rnea`], whose callers
/// inline it: a second copy of the recursion in their frames would
/// overflow the stack of unoptimised builds.
#[inline(never)]
pub(crate) fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    (q, qd, qdd): rnea::State<'_, S>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    let mut t = std::mem::take(&mut ws.tree);
    tree_positions(model, q, &mut t.q);
    if let Some(qd) = qd {
        tree_rates(model, qd, &mut t.qd);
    }
    if let Some(qdd) = qdd {
        tree_rates(model, qdd, &mut t.qdd);
    }
    let state = (&t.q[..], qd.map(|_| &t.qd[..]), qdd.map(|_| &t.qdd[..]));
    rnea::rnea_bodies(model, ws, state, loads.with_armature(None), &mut t.out);
    project(model, &t.out, tau);
    if let (Some(armature), Some(qdd)) = (loads.armature, qdd) {
        let base = model.nv() - model.dof();
        for (i, &a) in armature.iter().enumerate().filter(|(_, &a)| a != 0.0) {
            tau[base + i] += S::from_f64(a) * qdd[base + i];
        }
    }
    ws.tree = t;
}

/// M(q) of a model with mimic joints: [`crba::crba`] on the bodies'
/// coordinates, `Gᵀ M_tree G`, the armature on its diagonal.
pub(crate) fn crba<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], loads: Loads<'_, S>, m: &mut [S]) {
    let mut t = std::mem::take(&mut ws.tree);
    tree_positions(model, q, &mut t.q);
    crba::crba_tree(model, ws, &t.q, loads.with_armature(None), &mut t.m);
    project_matrix(model, &t.m, m);
    if let Some(armature) = loads.armature {
        let (n, base) = (model.nv(), model.nv() - model.dof());
        for (i, &a) in armature.iter().enumerate().filter(|(_, &a)| a != 0.0) {
            m[(base + i) * n + base + i] += S::from_f64(a);
        }
    }
    ws.tree = t;
}

/// Forward kinematics of a model with mimic joints: every body placed at
/// its coordinate `m·q_master + o` (`q` without a floating base's entries).
pub(crate) fn forward_kinematics<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    let mut t = std::mem::take(&mut ws.tree);
    let n = model.bodies.len();
    for i in 0..n {
        t.q[i] = coordinate(model, i, q);
    }
    kinematics::forward_kinematics_tree(model, ws, &t.q[..n]);
    ws.tree = t;
}
