//! Branches: sibling subtrees of one shape (a humanoid's two legs and two
//! arms, a quadruped's four legs), traced once and emitted as one body that
//! runs on all of them: in vector lanes, two or four branches at once
//! (`codegen/emit/branches.rs`), reading its constants from a table.
//!
//! A body unrolled for the whole robot is as long as the robot is big; past
//! a few thousand instructions it no longer fits in the processor's
//! micro-op cache and runs at the rate the decoders take its bytes
//! (`docs/performance.md`, "Long bodies: the front end"). One body for the
//! branches runs the bytes of one branch, and each of its instructions on
//! several branches.
//!
//! Each branch is traced with every constant an input `k[i]` of its own
//! (0 and ±1 too, see [`Graph::with_lane_constants`]), so that branches
//! that take the same code paths give the same graph whatever their
//! numbers. Where the algorithms choose a path from a joint's numbers (an
//! identity or quarter-turn placement, an axis along a coordinate axis),
//! `harmonise` sends every branch down the general path if they differ.
//! The constants every branch shares are then folded back in (and
//! simplified); the others are the table. Branches whose graphs still
//! differ stay in the unrolled body.
//!
//! For the recursive Newton-Euler functions (τ, h), the branch takes its
//! parent's motion (ω, ω̇, the origin's acceleration and `U`, 18 numbers in
//! the parent's frame) and its joints' state, and returns its joints' τ and
//! the wrench it puts on its parent (parent frame). The rest of the robot
//! is traced with the branches' wrenches as inputs, acting on their parents
//! as tip wrenches do, and the parents' motions as extra outputs, which the
//! emitted body computes before the calls (`codegen/emit/statements.rs`).
//! For the mass matrix, the branch takes its joints' angles alone and
//! returns its own block, each joint's `Iᶜ·S` at its parent and its
//! composite inertia there; the rest's CRBA carries the composite inertias
//! as payloads on the parents and the `Iᶜ·S` up to the base. For the
//! forward dynamics by the articulated-body algorithm, the branch's whole
//! algorithm is traced and cut where its parent's acceleration enters
//! (`cut_at`): its first part ([`Kind::AbaUp`]) takes the parent's ω and
//! returns the articulated inertia and bias force it passes to the parent,
//! the rest's ABA takes those and computes the parents' accelerations, and
//! the second part ([`Kind::AbaDown`]) takes them and the values of the
//! first part it needs, and returns the branch's q̈.

use super::sin_cos::{sin_cos_inputs, SinCosTrace};
use super::SceneLoads;
use crate::algorithms::aba::{aba_impl, inward, outward, velocities, ArticulatedInertia, Carried, RootArticulated};
use crate::algorithms::floating;
use crate::algorithms::floating::crba::carry_to_base;
use crate::algorithms::floating::rnea::base_motion;
use crate::algorithms::joint::{force_to_parent, inertia_to_parent, project};
use crate::algorithms::rnea::{add_armature, rnea_tree, Root, RootMotion};
use crate::algorithms::{crba, rnea, BodyInertia, Loads, TipWrench, Workspace, BASE_BODY};
use crate::codegen::{CodegenError, Function};
use crate::model::{Body, Coupling, Frame, Model, RootJoint};
use crate::scene::{dynamics, SceneModel};
use crate::spatial::{Force, Inertia, Mat3, Motion, Sym3, Transform, Vec3};
use crate::symbolic::{Expr, Graph, Node, NodeId, Rewrites, Traced, Tracer, LANE_CONSTANTS};
use crate::Scalar;
use std::collections::HashMap;

/// The numbers of a parent's motion a branch reads: ω, ω̇, the acceleration
/// of the parent's origin, and `U` row by row (parent frame).
pub const MOTION: usize = 18;

/// The fewest bodies a branch has for a loop to be worth its call.
pub const MIN_BODIES: usize = 3;

/// Branches of one parent alike in shape: one lane per branch, each its
/// bodies in the same order (a body's parent before it).
#[derive(Clone, Debug, PartialEq)]
pub struct BranchGroup {
    /// The parent body; `None` for a floating base.
    pub parent: Option<usize>,
    /// Each branch's bodies; the k-th of every lane correspond.
    pub lanes: Vec<Vec<usize>>,
}

/// What a branch's body computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The recursive Newton-Euler algorithm (τ, or h without q̈): from its
    /// parent's motion, its joints' τ and its wrench on the parent.
    Rnea {
        /// Whether q̈ is an input (τ) or zero (h).
        accelerations: bool,
    },
    /// The composite-rigid-body algorithm (M): its own block of M (row
    /// after row), each joint's `Iᶜ·S` carried to the parent's frame (six
    /// entries each, moment first), and its composite inertia in the
    /// parent's frame (mass, `m·c`, `Ī` as xx, yy, zz, xy, xz, yz).
    Crba,
    /// The articulated-body algorithm (q̈), its part before the rest's:
    /// from its parent's ω (parent frame) and its joints' state and τ, its
    /// articulated inertia and bias force in the parent's frame
    /// ([`ABA_UP`] numbers: the inertia's parts, moment, force), then what
    /// [`Kind::AbaDown`] reads of it (its input `x`).
    AbaUp,
    /// The articulated-body algorithm's part after the rest's: from its
    /// parent's classic acceleration (ω̇ and the origin's acceleration,
    /// gravity folded in; parent frame) and `x`, its joints' q̈.
    AbaDown,
}

/// The numbers a branch's articulated-body part passes to its parent: the
/// articulated inertia's 21, the bias force's 6.
pub const ABA_UP: usize = 27;

/// One group's body, traced once.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchBody {
    /// The branches.
    pub group: BranchGroup,
    /// What it computes.
    pub kind: Kind,
    /// Inputs `k` (the lane's constants), `m` (the parent's motion,
    /// [`MOTION`]; RNEA only), `s`, `c`, `q`, `qd`, `qdd` of the branch's
    /// joints in lane order; outputs as [`Kind`] says.
    pub body: SinCosTrace,
    /// The values of `k`, lane by lane.
    pub table: Vec<Vec<f64>>,
    /// For [`Kind::AbaDown`]: the index (among the function's branch
    /// bodies) of the [`Kind::AbaUp`] body whose outputs past [`ABA_UP`]
    /// are its input `x`.
    pub up: Option<usize>,
}

impl BranchBody {
    /// The FP operations of its body as written, once (a fused
    /// multiply-add counted once with `fma`).
    pub fn fp_ops(&self, fma: bool) -> usize {
        crate::codegen::counted(&self.body.function, fma).fp_ops()
    }
    /// The number of the branch's outputs.
    pub fn outputs(&self) -> usize {
        self.body.function.outputs().len()
    }
    /// How many numbers of its parent's motion it reads (`m`): [`MOTION`]
    /// for the RNEA, ω for [`Kind::AbaUp`], the classic acceleration for
    /// [`Kind::AbaDown`], none for the CRBA.
    pub fn motion(&self) -> usize {
        match self.kind {
            Kind::Rnea { .. } => MOTION,
            Kind::Crba => 0,
            Kind::AbaUp => 3,
            Kind::AbaDown => 6,
        }
    }
    /// When its calls run: 0 before the rest, 1 after the rest's part that
    /// computes what it reads ([`Kind::AbaDown`]).
    pub fn phase(&self) -> usize {
        usize::from(self.kind == Kind::AbaDown)
    }
    /// The length of its input `x` (the values [`Kind::AbaDown`] takes from
    /// [`Kind::AbaUp`]), or 0.
    pub fn carried(&self) -> usize {
        if self.kind == Kind::AbaDown {
            self.body.function.input_names().iter().position(|n| n == "x").map_or(0, |x| {
                let max = self.body.function.nodes().iter().filter_map(|n| match *n {
                    Node::Input { name, index } if name as usize == x => Some(index as usize + 1),
                    _ => None,
                });
                max.max().unwrap_or(0)
            })
        } else {
            0
        }
    }
}

/// A function emitted with its branches in a loop.
#[derive(Clone, Debug, PartialEq)]
pub struct Branched {
    /// The rest of the robot: inputs those of `NAME_sc` and, for group g,
    /// `r{g}` (the branches' outputs, lane after lane); outputs the
    /// function's, then the parent motion ([`MOTION`]) of each group that
    /// reads it.
    pub body: SinCosTrace,
    /// The function's own outputs (the first of `body`'s).
    pub outputs: usize,
    /// The groups' bodies (two for each group of the articulated-body
    /// algorithm: [`Kind::AbaUp`], then [`Kind::AbaDown`]).
    pub branches: Vec<BranchBody>,
}

/// The name of group `g`'s results in the emitted body.
pub fn results_name(g: usize) -> String {
    format!("r{g}")
}

/// Where entry `i` of branch `l` is among the results of a group of
/// `branches`: entry by entry, so that the branches' values of one entry are
/// next to each other (one vector store when they are computed in lanes).
pub fn result_index(branches: usize, l: usize, i: usize) -> usize {
    i * branches + l
}

/// Entries `range` of branch `l` among the results `r` of a group of
/// `branches` ([`result_index`]).
fn lane_entries<T: Copy>(r: &[T], branches: usize, l: usize, range: std::ops::Range<usize>) -> Vec<T> {
    range.map(|i| r[result_index(branches, l, i)]).collect()
}

/// Each joint of `x`'s branches (its body's index) with its value: the
/// first entries of each branch's results `r` (τ, or q̈).
fn joint_results<'a>(x: &'a BranchBody, r: &'a [Expr]) -> impl Iterator<Item = (usize, Expr)> + 'a {
    let branches = x.group.lanes.len();
    x.group
        .lanes
        .iter()
        .enumerate()
        .flat_map(move |(l, lane)| lane.iter().enumerate().map(move |(j, &b)| (b, r[result_index(branches, l, j)])))
}

/// The groups of branches of `model`: for each parent (a floating base,
/// then the bodies in order, none inside a branch already taken), its
/// children whose subtrees have the same shape (joint kinds, children),
/// at least two of them with at least `min_bodies` bodies each.
pub fn groups(model: &Model, min_bodies: usize) -> Vec<BranchGroup> {
    let n = model.bodies.len();
    let children = |p: Option<usize>| (0..n).filter(move |&b| model.bodies[b].parent == p);
    let mut taken = vec![false; n];
    let mut found = Vec::new();
    let parents = model.is_floating().then_some(None).into_iter().chain((0..n).map(Some));
    for parent in parents {
        if parent.is_some_and(|p| taken[p]) {
            continue;
        }
        let mut shapes: Vec<(String, Vec<usize>)> = Vec::new();
        for child in children(parent) {
            let s = shape(model, child);
            match shapes.iter_mut().find(|(t, _)| *t == s) {
                Some((_, list)) => list.push(child),
                None => shapes.push((s, vec![child])),
            }
        }
        for (_, roots) in shapes.into_iter().filter(|(_, r)| r.len() > 1) {
            let lanes: Vec<Vec<usize>> = roots.iter().map(|&r| subtree(model, r)).collect();
            if lanes[0].len() < min_bodies {
                continue;
            }
            for &b in lanes.iter().flatten() {
                taken[b] = true;
            }
            found.push(BranchGroup { parent, lanes });
        }
    }
    found
}

/// The shape of the subtree of `b`: its joint's kind, then its children's.
fn shape(model: &Model, b: usize) -> String {
    let kids: Vec<String> =
        (0..model.bodies.len()).filter(|&c| model.bodies[c].parent == Some(b)).map(|c| shape(model, c)).collect();
    format!("{:?}({})", model.bodies[b].joint.kind, kids.join(","))
}

/// The bodies of the subtree of `b`, depth first, children in order.
fn subtree(model: &Model, b: usize) -> Vec<usize> {
    let mut out = vec![b];
    for c in (0..model.bodies.len()).filter(|&c| model.bodies[c].parent == Some(b)) {
        out.extend(subtree(model, c));
    }
    out
}

/// The model of `model`'s `bodies` alone (a body whose parent is not among
/// them hangs from the root), with `frames` at the origins of the bodies
/// given (by their index in `model`; `None` the base), on a fixed or a
/// floating root.
fn part(model: &Model, bodies: &[usize], frames: &[(String, Option<usize>)], root: RootJoint) -> Model {
    let at = |b: usize| bodies.iter().position(|&x| x == b);
    let list: Vec<Body> = bodies
        .iter()
        .map(|&b| {
            let mut body = model.bodies[b].clone();
            body.parent = body.parent.and_then(at);
            body
        })
        .collect();
    let frames = frames
        .iter()
        .map(|(name, body)| Frame {
            name: name.clone(),
            body: body.and_then(at),
            placement: Transform::identity(),
            file_placement: None,
        })
        .collect();
    let coupling = Coupling::new(&list, vec![None; list.len()]);
    Model {
        name: model.name.clone(),
        root: model.root.clone(),
        bodies: list,
        frames,
        gravity: model.gravity,
        warnings: Vec::new(),
        base_mass: model.base_mass,
        root_joint: root,
        base_inertia: model.base_inertia,
        coupling,
        file_base_inertia: None,
    }
}

/// The scene's armature and friction on one branch's joints (the forward
/// dynamics reads them; the other functions add them in the rest).
struct JointTerms {
    armature: Option<Vec<f64>>,
    viscous: Vec<f64>,
    coulomb: Vec<f64>,
    coulomb_velocity: f64,
}

impl JointTerms {
    /// Those of `scene` on the joints `lane`.
    fn of(scene: &SceneModel, lane: &[usize]) -> JointTerms {
        JointTerms {
            armature: scene.has_armature().then(|| lane.iter().map(|&b| scene.armature[b]).collect()),
            viscous: lane.iter().map(|&b| scene.viscous_friction[b]).collect(),
            coulomb: lane.iter().map(|&b| scene.coulomb_friction[b]).collect(),
            coulomb_velocity: scene.coulomb_velocity,
        }
    }

    /// τ − friction(q̇) on these joints, as `dynamics::sub_friction` does.
    fn sub_friction(&self, qd: &[Expr], tau: &[Expr]) -> Vec<Expr> {
        let mut out = tau.to_vec();
        for (i, t) in out.iter_mut().enumerate() {
            dynamics::sub_joint_friction(t, qd[i], self.viscous[i], self.coulomb[i], self.coulomb_velocity);
        }
        out
    }
}

/// One branch traced with its constants as inputs: the graph and the
/// constants' values.
/// `gyro`: for each body, whether its gyroscopic moment takes the products
/// of ω (`Workspace::gyro_products`, which the lanes must share).
/// `terms`: its joints' armature and friction, which its forward dynamics reads.
/// `compact`: the articulated-body algorithm in its compact arm (see
/// [`branch_body`]), else the distributed one.
fn trace_lane(
    model: &Model,
    gyro: &[bool],
    terms: &JointTerms,
    rewrites: Rewrites,
    kind: Kind,
    compact: bool,
) -> Result<(Traced, Vec<f64>), CodegenError> {
    let tracer = Tracer::start_lanes(rewrites)?;
    // The constants' vector first, so that every lane names its inputs alike.
    let _ = tracer.input(LANE_CONSTANTS, 0);
    let nb = model.bodies.len();
    let mut ws = Workspace::<Expr>::new(model);
    ws.gyro_products = gyro.to_vec();
    let out = match kind {
        Kind::Rnea { accelerations } => {
            let m = tracer.inputs("m", MOTION);
            let q = tracer.inputs("q", nb);
            let qd = tracer.inputs("qd", nb);
            let qdd = accelerations.then(|| tracer.inputs("qdd", nb));
            let v = |k: usize| Vec3([m[k], m[k + 1], m[k + 2]]);
            let u = Mat3([[m[9], m[10], m[11]], [m[12], m[13], m[14]], [m[15], m[16], m[17]]]);
            let root = RootMotion { w: v(0), wd: v(3), a: v(6), u };
            let mut out = vec![Expr::zero(); nb];
            let state = (Some(qd.as_slice()), qdd.as_deref());
            let f = rnea_tree(model, &mut ws, &q, state, Root::Moving(&root), Loads::none(), &mut out);
            out.extend(f.ang.0);
            out.extend(f.lin.0);
            out
        }
        Kind::Crba => {
            let q = tracer.inputs("q", nb);
            let mut out = vec![Expr::zero(); nb * nb];
            crba::crba(model, &mut ws, &q, Loads::none(), &mut out);
            // Each joint's Iᶜ·S carried to the root body, then across its
            // joint to the parent (as to a floating base).
            for j in 0..nb {
                out.extend(carry_to_base(model, &ws, j, |_, _| {}).to_array());
            }
            let Inertia { mass, h, ibar } = inertia_to_parent(&model.bodies[0].joint, &ws.x[0], &ws.inertia[0]);
            out.push(mass);
            out.extend(h.0);
            out.extend(ibar.0);
            out
        }
        Kind::AbaUp | Kind::AbaDown => {
            // The whole algorithm on the branch, its root moving with the
            // parent's ω and accelerating with "ap"; `cut_at` splits it.
            let m = tracer.inputs("m", 3);
            let ap = tracer.inputs("ap", 6);
            let q = tracer.inputs("q", nb);
            let qd = tracer.inputs("qd", nb);
            let tau = terms.sub_friction(&qd, &tracer.inputs("tau", nb));
            let w = Vec3([m[0], m[1], m[2]]);
            velocities(model, &mut ws, &q, Some(&qd), Some(&w), Loads::none());
            let mut root = RootArticulated { inertia: ArticulatedInertia::zero(), bias: Force::zero() };
            inward(model, &mut ws, (&tau, true), terms.armature.as_deref(), Some(&mut root), !compact);
            let mut qdd = vec![Expr::zero(); nb];
            let a = Motion::new(Vec3([ap[0], ap[1], ap[2]]), Vec3([ap[3], ap[4], ap[5]]));
            outward(model, &mut ws, &a, &mut qdd, !compact);
            let mut out = root.inertia.to_parts().to_vec();
            out.extend(root.bias.to_array());
            out.extend(qdd);
            out
        }
    };
    drop(ws);
    let graph = tracer.finish();
    let values = graph.lane_constants().map(<[f64]>::to_vec).unwrap_or_default();
    Ok((Traced::new("branch", &graph, &out), values))
}

/// `t` with the constants all lanes share folded in (and simplified with
/// the rest), the others renumbered, one entry for each distinct column of
/// the lanes' values; the lanes' values of those.
fn fold_shared(t: &Traced, tables: &[Vec<f64>], rewrites: Rewrites) -> (Traced, Vec<Vec<f64>>) {
    let p = tables[0].len();
    let column = |i: usize| -> Vec<u64> { tables.iter().map(|l| l[i].to_bits()).collect() };
    let shared: Vec<bool> = (0..p).map(|i| tables.iter().all(|l| l[i].to_bits() == tables[0][i].to_bits())).collect();
    let mut slot = vec![usize::MAX; p];
    let mut kept = Vec::new();
    let mut slots: HashMap<Vec<u64>, usize> = HashMap::new();
    for i in (0..p).filter(|&i| !shared[i]) {
        slot[i] = *slots.entry(column(i)).or_insert_with(|| {
            kept.push(i);
            kept.len() - 1
        });
    }
    let k = t.input_names().iter().position(|s| s == LANE_CONSTANTS).map(|i| i as u32);
    let mut g = Graph::with_rewrites(rewrites);
    for name in t.input_names() {
        g.input(name, 0);
    }
    // Each SinCos node's cosine in `g` (its sine is its own id there).
    let mut cos: Vec<NodeId> = vec![0; t.nodes().len()];
    let copied: Result<Vec<NodeId>, std::convert::Infallible> = t.copy_into(&mut g, |g, id, node, new| {
        Ok(match node {
            Node::Input { name, index } if Some(name) == k => match shared[index as usize] {
                true => g.constant(tables[0][index as usize]),
                false => g.input(LANE_CONSTANTS, slot[index as usize]),
            },
            Node::Input { name, index } => g.input(&t.input_names()[name as usize], index as usize),
            Node::SinCos(a) => {
                let (s, c) = g.sin_cos(new[a as usize]);
                cos[id] = c;
                s
            }
            Node::Sin(sc) => new[sc as usize],
            Node::Cos(sc) => cos[sc as usize],
            _ => unreachable!("arithmetic and constants are copied by copy_into"),
        })
    });
    let Ok(new) = copied;
    let outputs: Vec<NodeId> = t.outputs().iter().map(|&o| new[o as usize]).collect();
    let table = tables.iter().map(|l| kept.iter().map(|&i| l[i]).collect()).collect();
    (Traced::from_ids(t.name(), &g, &outputs), table)
}

/// Makes the lanes' models (of the same shape) take the same code paths: a
/// joint whose lanes differ in what the algorithms branch on (a placement
/// whose rotation is the identity or a quarter turn, an axis along a
/// coordinate axis and its sign there) takes the general path in every
/// lane, where its numbers are constants like any other. (The humanoid's
/// grippers: one placed by the identity, the other turned by π less 1e-11.)
fn harmonise(models: &mut [Model]) {
    use crate::algorithms::joint::SignedPermutation;
    use crate::model::{AxisAlignment, Joint};
    let paths = |j: &Joint| {
        let sign = j.unit_axis.0.map(|a| a < 0.0);
        let turn = SignedPermutation::of(&j.placement.rot);
        (j.placement_rotation_is_identity, j.alignment, sign, turn)
    };
    for b in 0..models[0].bodies.len() {
        let first = paths(&models[0].bodies[b].joint);
        if models.iter().all(|m| paths(&m.bodies[b].joint) == first) {
            continue;
        }
        for m in models.iter_mut() {
            let joint = &mut m.bodies[b].joint;
            joint.alignment = AxisAlignment::General;
            joint.placement_rotation_is_identity = false;
        }
    }
}

/// The group's body (for the articulated-body algorithm its two parts, the
/// second's `up` counted from `first`, the index of the first), if its
/// lanes trace alike.
///
/// `compact`: the articulated-body algorithm in its compact arm, not the
/// distributed one that traced code takes elsewhere (`aba_impl`). The
/// distributed arm shortens the chain of dependent operations for a few
/// more of them; in a body too long for the micro-op cache the operations
/// (the bytes) set the time, and the compact arm has fewer on long chains
/// (the humanoid's arms), more on short ones (`docs/performance.md`).
fn branch_body(
    scene: &SceneModel,
    group: BranchGroup,
    rewrites: Rewrites,
    kind: Kind,
    first: usize,
    compact: bool,
) -> Result<Vec<BranchBody>, CodegenError> {
    let model = &scene.model;
    let mut models: Vec<Model> = group.lanes.iter().map(|lane| part(model, lane, &[], RootJoint::Fixed)).collect();
    harmonise(&mut models);
    // The gyroscopic moments by the products of ω where every lane's
    // inertia has them cheaper, else directly (a choice made on the values).
    let gyro: Vec<bool> = (0..models[0].bodies.len())
        .map(|b| models.iter().all(|m| crate::algorithms::rnea::use_products_for_gyroscopic(&m.bodies[b].inertia.ibar)))
        .collect();
    let mut traces: Vec<Traced> = Vec::new();
    let mut tables: Vec<Vec<f64>> = Vec::new();
    for (lane, bodies) in models.iter().zip(&group.lanes) {
        let (t, values) = trace_lane(lane, &gyro, &JointTerms::of(scene, bodies), rewrites, kind, compact)?;
        if traces.first().is_some_and(|first| *first != t) {
            return Ok(Vec::new());
        }
        traces.push(t);
        tables.push(values);
    }
    let (folded, table) = fold_shared(&traces[0], &tables, rewrites);
    let body = match sin_cos_inputs(&folded, group.lanes[0].len(), 0, rewrites) {
        Ok(body) => body,
        // an angle scaled by a lane's constant (a screw axis of a lane's own length)
        Err(_) => return Ok(Vec::new()),
    };
    if kind != Kind::AbaUp {
        return Ok(vec![BranchBody { group, kind, body, table, up: None }]);
    }
    let Some((up, down)) = cut_at(&body.function, ABA_UP, rewrites) else { return Ok(Vec::new()) };
    let part = |function: Traced| SinCosTrace { function, ..body.clone() };
    Ok(vec![
        BranchBody { group: group.clone(), kind: Kind::AbaUp, body: part(up), table: table.clone(), up: None },
        BranchBody { group, kind: Kind::AbaDown, body: part(down), table, up: Some(first) },
    ])
}

/// A branch's whole articulated-body trace `t` cut where its input `ap`
/// (the parent's acceleration) enters: the part that does not read it (the
/// first `first` outputs, then the values the other part reads), and the
/// part that does (the other outputs, reading those values as its input
/// `x` and `ap` as `m`). `None` if one of the first outputs reads `ap`.
fn cut_at(t: &Traced, first: usize, rewrites: Rewrites) -> Option<(Traced, Traced)> {
    let names = t.input_names();
    let named = |n: &str| names.iter().position(|s| s == n).map(|i| i as u32);
    let (ap, m) = (named("ap")?, named("m"));
    let nodes = t.nodes();
    let mut dep = vec![false; nodes.len()];
    for (id, n) in nodes.iter().enumerate() {
        dep[id] = match *n {
            Node::Input { name, .. } => name == ap,
            _ => n.operands().any(|o| dep[o as usize]),
        };
    }
    let outputs = t.outputs();
    if outputs[..first].iter().any(|&o| dep[o as usize]) {
        return None;
    }
    // The values computed before `ap` that the second part reads (the
    // parent's ω too, which only the first part's calls are given).
    let carried = |o: usize| match nodes[o] {
        Node::Input { name, .. } => Some(name) == m,
        n => n.constant().is_none(),
    };
    let mut cut = vec![false; nodes.len()];
    for n in nodes.iter().zip(&dep).filter(|(_, &d)| d).map(|(n, _)| n) {
        for o in n.operands() {
            let o = o as usize;
            cut[o] |= !dep[o] && carried(o);
        }
    }
    for &o in &outputs[first..] {
        let o = o as usize;
        cut[o] |= !dep[o] && carried(o);
    }
    let cuts: Vec<usize> = (0..nodes.len()).filter(|&i| cut[i]).collect();
    let copy = |down: bool| {
        let mut g = Graph::with_rewrites(rewrites);
        let mut new: Vec<NodeId> = Vec::with_capacity(nodes.len());
        for (id, node) in nodes.iter().enumerate() {
            let x = if down && cut[id] {
                g.input("x", cuts.iter().position(|&c| c == id).expect("a cut node"))
            } else if dep[id] != down && node.constant().is_none() && !matches!(node, Node::Input { .. }) {
                // not in this part
                g.constant(0.0)
            } else if let Some(x) = g.arithmetic(node.map_operands(|x| new[x as usize])) {
                x
            } else if let Some(c) = node.constant() {
                g.constant(c)
            } else if let Node::Input { name, index } = *node {
                let name = if name == ap { "m" } else { names[name as usize].as_str() };
                g.input(name, index as usize)
            } else {
                unreachable!("a branch body reads its sines and cosines as inputs")
            };
            new.push(x);
        }
        (g, new)
    };
    let (g, new) = copy(false);
    let ids: Vec<NodeId> =
        outputs[..first].iter().map(|&o| new[o as usize]).chain(cuts.iter().map(|&c| new[c])).collect();
    let up = Traced::from_ids(t.name(), &g, &ids);
    let (g, new) = copy(true);
    let ids: Vec<NodeId> = outputs[first..].iter().map(|&o| new[o as usize]).collect();
    Some((up, Traced::from_ids(t.name(), &g, &ids)))
}

/// `f` of `scene` with its branches in a loop, where it has branches that
/// trace alike: τ, h and M of a model without mimic joints, payload inputs
/// or a tip wrench. `None` where there is nothing to gain.
pub(crate) fn branched(scene: &SceneModel, f: &Function, rewrites: Rewrites) -> Result<Option<Branched>, CodegenError> {
    let model = &scene.model;
    let kind = match f {
        Function::InverseDynamics => Kind::Rnea { accelerations: true },
        Function::BiasForces => Kind::Rnea { accelerations: false },
        Function::MassMatrix => Kind::Crba,
        // By the articulated-body algorithm (the branches subtract their
        // joints' friction from τ and add their armature, the rest its own).
        Function::ForwardDynamics => Kind::AbaUp,
        _ => return Ok(None),
    };
    if model.has_mimic() || !scene.input_payloads.is_empty() || scene.tip_wrench_frame.is_some() {
        return Ok(None);
    }
    let mut branches = Vec::new();
    for group in groups(model, MIN_BODIES) {
        let first = branches.len();
        branches.extend(branch_body(scene, group, rewrites, kind, first, false)?);
    }
    if branches.is_empty() {
        return Ok(None);
    }
    let distributed = with_rest(scene, f, rewrites, kind, branches)?;
    if kind != Kind::AbaUp || distributed.fp_ops(true).1 <= FRONT_END_FP_OPS {
        return Ok(Some(distributed));
    }
    // A long body: each group's algorithm (its two parts) in the arm with
    // fewer operations.
    let mut branches: Vec<BranchBody> = Vec::new();
    for pair in distributed.branches.chunks(2) {
        let first = branches.len();
        let compact = branch_body(scene, pair[0].group.clone(), rewrites, kind, first, true)?;
        let fewer = !compact.is_empty() && fp_ops_written(&compact) < fp_ops_written(pair);
        branches.extend(if fewer { compact } else { pair.to_vec() });
    }
    with_rest(scene, f, rewrites, kind, branches).map(Some)
}

/// The FP operations of `bodies` as written (a fused multiply-add once).
fn fp_ops_written(bodies: &[BranchBody]) -> usize {
    bodies.iter().map(|b| b.fp_ops(true)).sum()
}

/// Above this many FP operations written (a fused multiply-add counted
/// once), a function's body no longer fits the processor's micro-op cache
/// (about 5,000 instructions, of which about two per FP operation of our
/// long bodies, with their loads and stores) and runs at the decoders' rate
/// of bytes: there the articulated-body algorithm's branches take the arm
/// with fewer operations (see [`branch_body`]; `docs/performance.md`, "Long
/// bodies: the front end").
const FRONT_END_FP_OPS: usize = 2500;

/// The function of `scene` with `branches` (traced for `kind`) and the rest
/// of the robot traced around them.
fn with_rest(
    scene: &SceneModel,
    f: &Function,
    rewrites: Rewrites,
    kind: Kind,
    branches: Vec<BranchBody>,
) -> Result<Branched, CodegenError> {
    let model = &scene.model;
    let n = model.bodies.len();
    let in_branch = |b: usize| branches.iter().any(|x| x.group.lanes.iter().flatten().any(|&y| y == b));
    let keep: Vec<usize> = (0..n).filter(|&b| !in_branch(b)).collect();
    let tips: Vec<(String, Option<usize>)> = branches
        .iter()
        .enumerate()
        .flat_map(|(g, x)| (0..x.group.lanes.len()).map(move |l| (format!("branch {g}.{l}"), x.group.parent)))
        .collect();
    let rest = part(model, &keep, &tips, model.root_joint);
    // A body's index in the rest.
    let kept = |b: usize| keep.iter().position(|&k| k == b);
    let (nq, nv) = (model.nq(), model.nv());
    let (qo, vo) = (nq - n, nv - n);

    let tracer = Tracer::start_with(rewrites)?;
    let q = tracer.inputs("q", nq);
    let qd = match kind {
        Kind::Rnea { .. } | Kind::AbaUp | Kind::AbaDown => tracer.inputs("qd", nv),
        Kind::Crba => Vec::new(),
    };
    let qdd = matches!(kind, Kind::Rnea { accelerations: true }).then(|| tracer.inputs("qdd", nv));
    let tau = matches!(kind, Kind::AbaUp).then(|| tracer.inputs("tau", nv));
    let loads = SceneLoads::of(scene, f, &tracer);
    let results: Vec<Vec<Expr>> = branches
        .iter()
        .enumerate()
        .map(|(g, x)| tracer.inputs(&results_name(g), x.group.lanes.len() * x.outputs()))
        .collect();
    // The rest's state: the base's entries, then the kept joints'.
    let gather =
        |x: &[Expr], o: usize| -> Vec<Expr> { x[..o].iter().chain(keep.iter().map(|&b| &x[o + b])).copied().collect() };
    let q_rest = gather(&q, qo);
    let mut ws = Workspace::<Expr>::new(&rest);
    let mut out = vec![Expr::zero(); if kind == Kind::Crba { nv * nv } else { nv }];
    match kind {
        Kind::Rnea { .. } => {
            let qd_rest = gather(&qd, vo);
            let qdd_rest = qdd.as_ref().map(|x| gather(x, vo));
            // Each branch's wrench on its parent, as a tip wrench at the parent's origin.
            let mut wrenches = Vec::new();
            for (x, r) in branches.iter().zip(&results) {
                let (nb, len) = (x.group.lanes[0].len(), x.outputs());
                for l in 0..x.group.lanes.len() {
                    let w = lane_entries(r, x.group.lanes.len(), l, nb..len);
                    let wrench = Force::new(Vec3([w[0], w[1], w[2]]), Vec3([w[3], w[4], w[5]]));
                    wrenches.push(TipWrench { frame: wrenches.len(), wrench });
                }
            }
            let gravity = loads.gravity.as_ref();
            let mut tau = vec![Expr::zero(); rest.nv()];
            let state = (Some(qd_rest.as_slice()), qdd_rest.as_deref());
            rnea::rnea(&rest, &mut ws, &q_rest, state.0, state.1, Loads::new(gravity, &wrenches, &[]), &mut tau);
            out[..vo].copy_from_slice(&tau[..vo]);
            for (k, &b) in keep.iter().enumerate() {
                out[vo + b] = tau[vo + k];
            }
            for (x, r) in branches.iter().zip(&results) {
                for (b, v) in joint_results(x, r) {
                    out[vo + b] = v;
                }
            }
            // The scene's armature and friction, on every joint, as the unbranched trace adds them.
            if let Some(qdd) = &qdd {
                let armature = scene.has_armature().then_some(scene.armature.as_slice());
                add_armature(armature, Some(&qdd[vo..]), &mut out[vo..]);
            }
            dynamics::add_friction(scene, &qd, &mut out);
            // The parents' motions, for the calls.
            for x in &branches {
                let motion = match x.group.parent.and_then(kept) {
                    Some(p) => RootMotion { w: ws.v[p].ang, wd: ws.a[p].ang, a: ws.a[p].lin, u: ws.u[p] },
                    None => base_motion(&rest, &q_rest, state.0, state.1, Loads::new(gravity, &[], &[])).1,
                };
                let (w, wd, a, u) = (motion.w.0, motion.wd.0, motion.a.0, motion.u.0);
                out.extend(w.into_iter().chain(wd).chain(a).chain(u.into_iter().flatten()));
            }
        }
        Kind::Crba => {
            // The branches' composite inertias carried by their parents, as payloads.
            let mut carried = Vec::new();
            for (x, r) in branches.iter().zip(&results) {
                let (nb, len) = (x.group.lanes[0].len(), x.outputs());
                let body = x.group.parent.and_then(kept).unwrap_or(BASE_BODY);
                for l in 0..x.group.lanes.len() {
                    let c = lane_entries(r, x.group.lanes.len(), l, nb * nb + 6 * nb..len);
                    let inertia = Inertia {
                        mass: c[0],
                        h: Vec3([c[1], c[2], c[3]]),
                        ibar: Sym3([c[4], c[5], c[6], c[7], c[8], c[9]]),
                    };
                    carried.push(BodyInertia { body, inertia });
                }
            }
            let mut m = vec![Expr::zero(); rest.nv() * rest.nv()];
            crba::crba(&rest, &mut ws, &q_rest, Loads::new(None, &[], &carried), &mut m);
            let (nr, at) = (rest.nv(), |b: usize| vo + b);
            // The rest's entries.
            let index = |k: usize| if k < vo { k } else { at(keep[k - vo]) };
            for i in 0..nr {
                for j in 0..nr {
                    out[index(i) * nv + index(j)] = m[i * nr + j];
                }
            }
            for (x, r) in branches.iter().zip(&results) {
                let (nb, len) = (x.group.lanes[0].len(), x.outputs());
                for (l, lane) in x.group.lanes.iter().enumerate() {
                    let r = lane_entries(r, x.group.lanes.len(), l, 0..len);
                    // The branch's own block.
                    for (a, &i) in lane.iter().enumerate() {
                        for (b, &j) in lane.iter().enumerate() {
                            out[at(i) * nv + at(j)] = r[a * nb + b];
                        }
                    }
                    // Its joints against their ancestors': Iᶜ·S carried up the rest.
                    for (a, &i) in lane.iter().enumerate() {
                        let e = &r[nb * nb + 6 * a..nb * nb + 6 * a + 6];
                        let mut f = Force::new(Vec3([e[0], e[1], e[2]]), Vec3([e[3], e[4], e[5]]));
                        let mut above = x.group.parent.and_then(kept);
                        while let Some(p) = above {
                            let body = &rest.bodies[p];
                            let mij = project(&body.joint, &f);
                            out[at(i) * nv + at(keep[p])] = mij;
                            out[at(keep[p]) * nv + at(i)] = mij;
                            f = force_to_parent(&body.joint, &ws.x[p], &f);
                            above = body.parent;
                        }
                        if vo > 0 {
                            for (k, v) in f.to_array().into_iter().enumerate() {
                                out[at(i) * nv + k] = v;
                                out[k * nv + at(i)] = v;
                            }
                        }
                    }
                }
            }
            dynamics::add_armature_diagonal(scene, &mut out);
        }
        Kind::AbaUp | Kind::AbaDown => {
            let qd_rest = gather(&qd, vo);
            // τ − friction on the rest's joints, and their armature (the branches do theirs).
            let terms = JointTerms::of(scene, &keep);
            let tau_rest = gather(tau.as_deref().expect("traced with τ"), vo);
            let tau_rest: Vec<Expr> =
                tau_rest[..vo].iter().copied().chain(terms.sub_friction(&qd_rest[vo..], &tau_rest[vo..])).collect();
            // What each branch passes to its parent.
            let mut carried = Vec::new();
            for (x, r) in branches.iter().zip(&results).filter(|(x, _)| x.kind == Kind::AbaUp) {
                let lanes = x.group.lanes.len();
                for l in 0..lanes {
                    let p = lane_entries(r, lanes, l, 0..ABA_UP);
                    let bias = Force::new(Vec3([p[21], p[22], p[23]]), Vec3([p[24], p[25], p[26]]));
                    let parent = x.group.parent.and_then(kept);
                    carried.push(Carried { parent, inertia: ArticulatedInertia::from_parts(&p[..21]), bias });
                }
            }
            let mut qdd_rest = vec![Expr::zero(); rest.nv()];
            let l = Loads::new(loads.gravity.as_ref(), &[], &[]).with_armature(terms.armature.as_deref());
            let a0 = match rest.is_floating() {
                true => floating::aba::aba_impl(
                    &rest,
                    &mut ws,
                    &q_rest,
                    Some(&qd_rest),
                    &tau_rest,
                    l,
                    &carried,
                    &mut qdd_rest,
                ),
                false => {
                    let state = (&q_rest[..], Some(&qd_rest[..]), &tau_rest[..]);
                    aba_impl::<Expr, true>(&rest, &mut ws, state.0, state.1, state.2, l, &carried, &mut qdd_rest);
                    Motion::new(Vec3::zero(), l.gravity.map_or(Vec3::zero(), |g| -*g))
                }
            };
            out[..vo].copy_from_slice(&qdd_rest[..vo]);
            for (k, &b) in keep.iter().enumerate() {
                out[vo + b] = qdd_rest[vo + k];
            }
            for (x, r) in branches.iter().zip(&results).filter(|(x, _)| x.kind == Kind::AbaDown) {
                for (b, v) in joint_results(x, r) {
                    out[vo + b] = v;
                }
            }
            // The parents' ω for the first calls, then their accelerations for the second.
            for x in branches.iter().filter(|x| x.kind == Kind::AbaUp) {
                match x.group.parent.and_then(kept) {
                    Some(p) => out.extend(ws.v[p].ang.0),
                    None => out.extend(qd[..3].iter().copied()),
                }
            }
            for x in branches.iter().filter(|x| x.kind == Kind::AbaDown) {
                match x.group.parent.and_then(kept) {
                    Some(p) => out.extend(ws.a[p].to_array()),
                    None => out.extend(a0.to_array()),
                }
            }
        }
    }
    let outputs = if kind == Kind::Crba { nv * nv } else { nv };
    drop(ws);
    let graph = tracer.finish();
    let traced = Traced::new(&f.rust_name(), &graph, &out);
    let mut body = sin_cos_inputs(&traced, n, qo, rewrites).map_err(CodegenError::Internal)?;
    // The branches read their joints' sines and cosines from `s` and `c`.
    for x in &branches {
        for lane in &x.group.lanes {
            for (j, &b) in lane.iter().enumerate() {
                body.angle_scale[b] = x.body.angle_scale[j];
            }
        }
    }
    Ok(Branched { body, outputs, branches })
}

impl Branched {
    /// The FP operations (a fused multiply-add counted once with `fma`) a
    /// call runs, and those written in the module: the rest's, and each
    /// group's body once per branch, or once.
    pub fn fp_ops(&self, fma: bool) -> (usize, usize) {
        let rest = crate::codegen::counted(&self.body.function, fma).fp_ops();
        self.branches.iter().fold((rest, rest), |(run, written), x| {
            let b = x.fp_ops(fma);
            (run + x.group.lanes.len() * b, written + b)
        })
    }

    /// How many times the calls stop the rest: once, or twice for the
    /// articulated-body algorithm (its branches' first parts, then their
    /// second).
    pub fn phases(&self) -> usize {
        self.branches.iter().map(|x| x.phase() + 1).max().unwrap_or(1)
    }

    /// Where the arguments of phase `phase`'s calls start among the rest's
    /// extra outputs.
    pub fn args_before(&self, phase: usize) -> usize {
        self.branches.iter().filter(|x| x.phase() < phase).map(BranchBody::motion).sum()
    }

    /// The function's outputs on numbers, as the emitted body computes them
    /// (unfused): the rest's motions, each branch on its lane's constants,
    /// then the rest with the branches' results. `inputs` are `NAME_sc`'s
    /// (`s`, `c`, `q`, `qd`, …; a floating base's `q` is NQ long).
    pub fn eval(&self, inputs: &[(&str, &[f64])]) -> Result<Vec<f64>, crate::symbolic::MissingInput> {
        let vector = |name: &str| inputs.iter().find(|(n, _)| *n == name).map(|(_, v)| *v);
        let mut all: Vec<(String, Vec<f64>)> = inputs.iter().map(|(n, v)| (n.to_string(), v.to_vec())).collect();
        for (g, x) in self.branches.iter().enumerate() {
            all.push((results_name(g), vec![0.0; x.group.lanes.len() * x.outputs()]));
        }
        let run = |t: &Traced, all: &[(String, Vec<f64>)]| {
            let refs: Vec<(&str, &[f64])> = all.iter().map(|(n, v)| (n.as_str(), v.as_slice())).collect();
            t.eval(&refs)
        };
        // Where the joints' entries start in `q` and in the velocity-side vectors.
        let (q_off, v_off) = (self.body.q_offset, if self.body.q_offset > 0 { 6 } else { 0 });
        for phase in 0..self.phases() {
            let rest = run(&self.body.function, &all)?;
            let mut args = &rest[self.outputs + self.args_before(phase)..];
            for (g, x) in self.branches.iter().enumerate().filter(|(_, x)| x.phase() == phase) {
                let (motion, more) = args.split_at(x.motion());
                args = more;
                let lanes = x.group.lanes.len();
                let mut results = vec![0.0; lanes * x.outputs()];
                for (l, lane) in x.group.lanes.iter().enumerate() {
                    // The lane's joints' entries of a joint-indexed vector, or
                    // of a velocity-side one (past the base's six).
                    let pick = |name: &str, skip: usize| -> Vec<f64> {
                        vector(name).map_or(Vec::new(), |v| lane.iter().map(|&b| v[skip + b]).collect())
                    };
                    // What an articulated-body branch's second part takes from its first.
                    let carried: Vec<f64> = match x.up {
                        Some(u) => {
                            let from = &all.iter().find(|(n, _)| *n == results_name(u)).expect("pushed above").1;
                            lane_entries(from, lanes, l, ABA_UP..ABA_UP + x.carried())
                        }
                        None => Vec::new(),
                    };
                    let lane_inputs: Vec<(String, Vec<f64>)> = vec![
                        (LANE_CONSTANTS.to_string(), x.table[l].clone()),
                        ("m".to_string(), motion.to_vec()),
                        ("x".to_string(), carried),
                        ("s".to_string(), pick("s", 0)),
                        ("c".to_string(), pick("c", 0)),
                        ("q".to_string(), pick("q", q_off)),
                        ("qd".to_string(), pick("qd", v_off)),
                        ("qdd".to_string(), pick("qdd", v_off)),
                        ("tau".to_string(), pick("tau", v_off)),
                    ];
                    for (i, v) in run(&x.body.function, &lane_inputs)?.into_iter().enumerate() {
                        results[result_index(lanes, l, i)] = v;
                    }
                }
                let name = results_name(g);
                all.iter_mut().find(|(n, _)| *n == name).expect("pushed above").1 = results;
            }
        }
        let mut out = run(&self.body.function, &all)?;
        out.truncate(self.outputs);
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codegen::{prepare, CodegenOptions};
    use crate::scene::Scene;
    use approx::assert_relative_eq;

    /// In a lane trace every constant, 0 and ±1 included, is an entry of
    /// `k` of its own, in the order made, and nothing folds: the graph is
    /// the code path, whatever the numbers.
    #[test]
    fn lane_constants_are_inputs() {
        let t = Tracer::start_lanes(Rewrites::default()).unwrap();
        let x = t.input("x", 0);
        let y = x * Expr::from_f64(2.5) + Expr::from_f64(2.5) * x;
        let zero = Expr::from_f64(0.0) * x + x * Expr::from_f64(-1.0);
        let g = t.finish();
        assert_eq!(g.lane_constants(), Some(&[2.5, 2.5, 0.0, -1.0][..]));
        let f = Traced::new("f", &g, &[y, zero]);
        assert!(f.nodes().iter().all(|n| n.constant().is_none()));
        assert_eq!(f.eval(&[("x", &[2.0]), (LANE_CONSTANTS, &[2.5, 2.5, 0.0, -1.0])]).unwrap(), vec![10.0, -2.0]);
        assert_eq!(f.eval(&[("x", &[2.0]), (LANE_CONSTANTS, &[1.5, 3.0, 1.0, 2.0])]).unwrap(), vec![9.0, 6.0]);
    }

    /// A body with loops is never split, so a function whose body with
    /// loops is longer than `split_lets` allows stays unrolled; the default
    /// allows the quadruped's.
    #[test]
    fn a_body_longer_than_the_split_allows_stays_unrolled() {
        let model = robot("quadruped12", true);
        let functions = [Function::InverseDynamics, Function::MassMatrix, Function::BiasForces];
        for (split, looped) in [(None, true), (Some(2500), true), (Some(30), false)] {
            let opts = CodegenOptions::default().functions(functions.clone()).branch_loops(true).split_lets(split);
            let module = crate::codegen::generate(&model, &opts).unwrap();
            for f in &module.functions {
                assert_eq!(f.branched.is_some(), looped, "{:?} with split_lets {split:?}", f.function);
            }
            assert_eq!(module.source.contains("emitted with branches in loops"), looped);
        }
    }

    /// A fixed-base torso turning about z, with two mirrored arms on it
    /// (two revolute joints and a prismatic one each).
    const TWIN_ARMS: &str = r#"<robot name="twin_arms">
      <link name="base"/>
      <joint name="torso" type="revolute"><parent link="base"/><child link="torso_link"/>
        <origin xyz="0 0 0.4"/><axis xyz="0 0 1"/></joint>
      <link name="torso_link"><inertial><origin xyz="0.01 0 0.2"/><mass value="8"/>
        <inertia ixx="0.3" ixy="0.001" ixz="0.02" iyy="0.25" iyz="0" izz="0.1"/></inertial></link>
      ARM(left, 1)
      ARM(right, -1)
    </robot>"#;

    fn arm(side: &str, y: f64) -> String {
        format!(
            r#"<joint name="{side}_1" type="revolute"><parent link="torso_link"/><child link="{side}_1_link"/>
                <origin xyz="0.02 {a} 0.5" rpy="{r} 0 0"/><axis xyz="0 1 0"/></joint>
              <link name="{side}_1_link"><inertial><origin xyz="0.01 {b} -0.1"/><mass value="2"/>
                <inertia ixx="0.02" ixy="{c}" ixz="0.001" iyy="0.018" iyz="{d}" izz="0.01"/></inertial></link>
              <joint name="{side}_2" type="revolute"><parent link="{side}_1_link"/><child link="{side}_2_link"/>
                <origin xyz="0.1 {e} -0.3"/><axis xyz="1 0 0"/></joint>
              <link name="{side}_2_link"><inertial><origin xyz="0 {b} -0.15"/><mass value="1.5"/>
                <inertia ixx="0.012" ixy="{c}" ixz="0" iyy="0.011" iyz="{d}" izz="0.004"/></inertial></link>
              <joint name="{side}_slide" type="prismatic"><parent link="{side}_2_link"/><child link="{side}_3_link"/>
                <origin xyz="0 0 -0.2"/><axis xyz="0 0 1"/><limit lower="-0.1" upper="0.1" effort="50" velocity="1"/></joint>
              <link name="{side}_3_link"><inertial><origin xyz="0.005 {b} -0.05"/><mass value="0.7"/>
                <inertia ixx="0.002" ixy="{c}" ixz="0" iyy="0.002" iyz="0" izz="0.001"/></inertial></link>"#,
            a = 0.25 * y,
            b = 0.02 * y,
            c = 0.0004 * y,
            d = -0.0003 * y,
            e = 0.05 * y,
            r = 0.3 * y,
        )
    }

    /// A bundled robot (or `twin_arms`, `twin_arms_screw`); `humanoid32_alike_wrists` is the
    /// humanoid with its right wrist and force sensor turned as its left
    /// ones are (−270° and 270° for −90° and −90°), so that its arms, which
    /// hang from a body, trace alike too.
    fn robot(name: &str, floating: bool) -> Model {
        if let Some(kind) = name.strip_prefix("twin_arms") {
            let xml =
                TWIN_ARMS.replace("ARM(left, 1)", &arm("left", 1.0)).replace("ARM(right, -1)", &arm("right", -1.0));
            let mut model = Model::from_urdf_str(&xml).unwrap();
            if kind == "_screw" {
                // The right shoulder a screw axis of length 2: its angle is 2q.
                let joint = &mut model.bodies.iter_mut().find(|b| b.joint.name == "right_1").unwrap().joint;
                joint.axis = joint.unit_axis.scale(2.0);
                joint.axis_norm = 2.0;
            }
            return model;
        }
        let file = name.strip_suffix("_alike_wrists").unwrap_or(name);
        let path = format!("{}/robots/{file}.urdf", env!("CARGO_MANIFEST_DIR"));
        let xml = std::fs::read_to_string(path).unwrap();
        let xml = match file == name {
            true => xml,
            false => xml.replace(r#"rpy="0.0 0 -1.57079632679""#, r#"rpy="0.0 0 -4.71238898038""#).replace(
                r#"rpy="0 0 -1.57079632679" xyz="0 0 -0.012725""#,
                r#"rpy="0 0 4.71238898038" xyz="0 0 -0.012725""#,
            ),
        };
        let model = Model::from_urdf_str(&xml).unwrap();
        if floating {
            model.with_floating_base()
        } else {
            model
        }
    }

    /// The humanoid's legs and arms, the quadruped's four legs and the
    /// torso's two arms are found, and they trace alike: the
    /// humanoid's arms though its wrists are turned by −90° and −270° (its
    /// grippers' placements differ by a rotation of π, so their joints take
    /// the general path: `harmonise`), and with its wrists turned alike;
    /// two mirrored arms with a prismatic joint on a fixed base's torso
    /// (branches that hang from a body), but not when one arm's shoulder
    /// turns by twice its coordinate (a screw axis of length 2, which the
    /// lanes do not make alike). The functions with their branches
    /// in a loop give the generic solver's τ, h, M and q̈ (the quadruped's
    /// with armature and friction on its joints).
    #[test]
    fn branches_trace_alike_and_give_the_generic_values() {
        let opts = CodegenOptions::default().branch_loops(true);
        for (name, floating, lanes, alike) in [
            ("humanoid32", true, vec![2, 2], 2),
            ("quadruped12", true, vec![4], 1),
            ("torso_two_arms", false, vec![2], 1),
            ("humanoid32_alike_wrists", true, vec![2, 2], 2),
            ("twin_arms", false, vec![2], 1),
            ("twin_arms_screw", false, vec![2], 0),
        ] {
            let model = robot(name, floating);
            let mut plain = Scene::default().apply(&model).unwrap();
            if name == "quadruped12" {
                // armature and friction of each joint's own: the rest adds
                // them on every joint, but for the forward dynamics, where
                // the branches take their joints' (lanes' constants) and the
                // rest its own
                let n = model.dof();
                plain.armature = (0..n).map(|i| 0.01 * (i + 1) as f64).collect();
                plain.viscous_friction = (0..n).map(|i| 0.2 + 0.1 * i as f64).collect();
                plain.coulomb_friction = vec![0.5; n];
            }
            let (scene, _) = prepare::prepare(&plain, &opts);
            let found: Vec<usize> = groups(&scene.model, MIN_BODIES).iter().map(|g| g.lanes.len()).collect();
            assert_eq!(found, lanes, "{name}: groups");
            let (n, nq, nv) = (model.dof(), model.nq(), model.nv());
            let mut rng = 0x2545_f491_4f6c_dd1du64;
            let mut next = || {
                rng ^= rng << 13;
                rng ^= rng >> 7;
                rng ^= rng << 17;
                (rng >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
            };
            let mut q: Vec<f64> = (0..nq).map(|_| 2.0 * next()).collect();
            if floating {
                let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
                q[3..7].iter_mut().for_each(|x| *x /= norm);
            }
            let qd: Vec<f64> = (0..nv).map(|_| 3.0 * next()).collect();
            let qdd: Vec<f64> = (0..nv).map(|_| 5.0 * next()).collect();
            let tau: Vec<f64> = (0..nv).map(|_| 20.0 * next()).collect();
            let angles = &q[nq - n..];
            let (s, c): (Vec<f64>, Vec<f64>) = angles.iter().map(|a| a.sin_cos()).unzip();
            for f in [Function::InverseDynamics, Function::BiasForces, Function::MassMatrix, Function::ForwardDynamics]
            {
                let b = branched(&scene, &f, opts.rewrites).unwrap();
                let Some(b) = b else {
                    assert_eq!(alike, 0, "{name} {f:?}: no branches trace alike");
                    continue;
                };
                let groups = b.branches.iter().filter(|x| x.kind != Kind::AbaDown).count();
                assert_eq!(groups, alike, "{name} {f:?}");
                let mut inputs: Vec<(&str, &[f64])> = vec![("s", &s), ("c", &c), ("q", &q), ("qd", &qd)];
                match f {
                    Function::InverseDynamics => inputs.push(("qdd", &qdd)),
                    Function::ForwardDynamics => inputs.push(("tau", &tau)),
                    _ => {}
                }
                let got = b.eval(&inputs).unwrap();
                let mut ws = crate::algorithms::Workspace::<f64>::new(&model);
                let mut want = vec![0.0; if f == Function::MassMatrix { nv * nv } else { nv }];
                let g = model.gravity;
                match f {
                    Function::InverseDynamics => {
                        dynamics::inverse_dynamics(&plain, &mut ws, &q, &qd, &qdd, Loads::gravity(&g), &mut want)
                    }
                    Function::BiasForces => dynamics::bias_forces(&plain, &mut ws, &q, &qd, Some(&g), &mut want),
                    Function::ForwardDynamics => {
                        dynamics::forward_dynamics(&plain, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut want)
                    }
                    _ => dynamics::mass_matrix(&plain, &mut ws, &q, &mut want),
                }
                assert_eq!(got.len(), want.len());
                for (a, b) in got.iter().zip(&want) {
                    assert_relative_eq!(*a, *b, epsilon = 1e-11, max_relative = 1e-11);
                }
            }
        }
    }

    /// The forward dynamics' branches take the articulated-body algorithm's
    /// compact arm only in a body too long for the micro-op cache, and
    /// there group by group where it has fewer operations: the humanoid's
    /// arms (eight joints) do, its legs and the quadruped's short legs keep
    /// the distributed arm. (The values are the generic solver's either
    /// way: `branches_trace_alike_and_give_the_generic_values`.)
    #[test]
    fn long_bodies_take_the_arm_with_fewer_operations() {
        let opts = CodegenOptions::default().branch_loops(true);
        let ops = fp_ops_written;
        for (name, compact_groups) in [("humanoid32", vec![false, true]), ("quadruped12", vec![false])] {
            let (scene, _) = prepare::prepare(&Scene::default().apply(&robot(name, true)).unwrap(), &opts);
            let b = branched(&scene, &Function::ForwardDynamics, opts.rewrites).unwrap().unwrap();
            let long = b.fp_ops(true).1 > FRONT_END_FP_OPS;
            assert_eq!(long, name == "humanoid32", "{name}: {} FP ops written", b.fp_ops(true).1);
            let mut taken = Vec::new();
            for (g, pair) in b.branches.chunks(2).enumerate() {
                let arms = [false, true].map(|compact| {
                    branch_body(&scene, pair[0].group.clone(), opts.rewrites, Kind::AbaUp, 2 * g, compact)
                });
                let [distributed, compact] = arms.map(|x| x.unwrap());
                let is = |x: &[BranchBody]| x.iter().zip(pair).all(|(a, b)| a.body == b.body);
                assert!(is(&distributed) != is(&compact), "{name} group {g}: one of the two arms");
                if long {
                    assert_eq!(ops(pair), ops(&distributed).min(ops(&compact)), "{name} group {g}");
                }
                taken.push(is(&compact));
            }
            assert_eq!(taken, compact_groups, "{name}: the groups that take the compact arm");
        }
    }
}
