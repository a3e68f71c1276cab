//! The mass matrix as code generation traces it: the composite-rigid-body
//! algorithm, with each entry computed where it costs the fewest operations.
//!
//! The generic [`crba`](crate::algorithms::crba::crba) gets the entry
//! `M[i][j]` of a joint `i` and its descendant `j` by carrying the column
//! `F_j = Iᶜ_j S_j` up the chain to `i` and projecting it on `S_i`. The same
//! number is `S_i⁽ᵏ⁾ · F_j⁽ᵏ⁾` in the frame of *any* body `k` on the path
//! from `i` to `j`: `F_j` carried up to `k`, and joint `i`'s motion axis
//! `S_i` carried down to `k` (the power of a wrench on a twist does not
//! depend on the frame both are written in).
//!
//! Likewise the diagonal `M[i][i] = S_iᵀ Iᶜ_i S_i` can expand the composite
//! inertia `d` levels deep: `Iᶜ_i` is body `i`'s own inertia plus its
//! children's composites, so `M[i][i]` is the sum of `S_i⁽ᵏ⁾ᵀ I_k S_i⁽ᵏ⁾` over
//! the bodies `k` less than `d` levels below `i` and of `S_i⁽ᵏ⁾ᵀ Iᶜ_k S_i⁽ᵏ⁾`
//! over those exactly `d` below. A regrouped body inertia (see
//! `grouping.rs`) is sparse and constant where a composite is neither, so
//! each term can be far cheaper than rotating the composite into the
//! ancestor's frame.
//!
//! Carried axes are shared by every entry of their row, carried columns by
//! every entry of their column, and which choice is cheapest depends on the
//! robot. [`plan`] traces every choice once and picks one per entry,
//! greedily, by the operations the chosen entries need together;
//! [`mass_matrix`] then computes `M` with those choices. Every choice gives
//! `M` up to rounding (tested against the generic solver); the choice with
//! index 0 everywhere ([`Plan::crba`]) is the generic algorithm's.

use crate::algorithms::joint::{
    force_to_parent, inertia_times_subspace, inertia_to_parent, motion, motion_to_child, project,
};
use crate::algorithms::rnea::update_joint_transforms;
use crate::algorithms::{mimic, BodyInertia, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Motion, Transform, Vec3};
use crate::symbolic::{Expr, Node, Rewrites, TraceActive, Traced, Tracer};
use crate::Scalar;

/// Above this many joints [`plan`] keeps the generic algorithm's choices:
/// tracing every choice grows as n³, and on long chains it saves a few per
/// cent of M's operations for seconds of planning (`docs/performance.md`).
pub(crate) const MAX_PLANNED_DOF: usize = 24;

/// For each entry `(i, j)` with `i ≤ j` (row-major index `i·n + j`), which
/// of its ways to compute it [`mass_matrix`] takes:
///
/// - diagonal: `d`, the depth to which the composite inertia is expanded
///   (0: `S_iᵀ F_i`, the generic algorithm);
/// - `i` an ancestor of `j`: `c`, the meeting body is `c` levels below `i`
///   on the path to `j` (0: project at `i`, the generic algorithm).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Plan {
    choice: Vec<usize>,
}

impl Plan {
    /// The generic algorithm's choices (every entry's choice 0).
    pub(crate) fn crba(n: usize) -> Plan {
        Plan { choice: vec![0; n * n] }
    }
    /// How deep below a joint any choice reaches.
    fn reach(&self) -> usize {
        self.choice.iter().copied().max().unwrap_or(0)
    }
}

/// `Sᵀ I S` for a motion `S = (ω, v)`: `ω·Īω + 2 h·(v × ω) + m v·v`.
#[inline(always)]
fn quadratic_form<S: Scalar>(i: &Inertia<S>, s: &Motion<S>) -> S {
    let (w, v) = (&s.ang, &s.lin);
    w.dot(&i.ibar.mul_vec(w)) + i.h.dot(&v.cross(w)) * S::from_f64(2.0) + v.dot(v) * i.mass
}

/// Every way of computing each entry that reaches at most `reach` levels
/// below the entry's upper joint, in the order of the [`Plan`]'s choices;
/// empty lists for joints on different branches. Leaves the composite
/// inertias in `ws`.
fn candidates<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    payloads: &[BodyInertia<S>],
    reach: usize,
) -> Vec<Vec<S>> {
    let n = model.bodies.len();
    assert!(q.len() == n && ws.dof() == n, "mass_matrix: q must have the model's {n} bodies");
    update_joint_transforms(model, ws, q);
    let mut own: Vec<Inertia<S>> = model.bodies.iter().map(|b| Inertia::from_f64(&b.inertia)).collect();
    for p in payloads {
        own[p.body] = own[p.body].add(&p.inertia);
    }
    ws.inertia[..n].copy_from_slice(&own);
    for i in (0..n).rev() {
        if let Some(p) = model.bodies[i].parent {
            let ic = inertia_to_parent(&model.bodies[i].joint, &ws.x[i], &ws.inertia[i]);
            ws.inertia[p] = ws.inertia[p].add(&ic);
        }
    }
    // Levels below each joint (None: not a descendant, or out of reach)
    // and each joint's motion axis carried down to those bodies.
    let mut level: Vec<Vec<Option<usize>>> = vec![vec![None; n]; n];
    let mut down: Vec<Vec<Option<Motion<S>>>> = vec![vec![None; n]; n];
    for i in 0..n {
        level[i][i] = Some(0);
        down[i][i] = Some(motion(&model.bodies[i].joint, S::one()));
        // Bodies are in topological order: a parent comes first.
        for k in i + 1..n {
            let Some(p) = model.bodies[k].parent else { continue };
            match level[i][p] {
                Some(l) if l < reach => {
                    level[i][k] = Some(l + 1);
                    let s = down[i][p].expect("carried with its level");
                    down[i][k] = Some(motion_to_child(&model.bodies[k].joint, &ws.x[k], &s));
                }
                _ => {}
            }
        }
    }
    let mut out: Vec<Vec<S>> = vec![Vec::new(); n * n];
    for j in 0..n {
        let body = &model.bodies[j];
        let mut f: Force<S> = inertia_times_subspace(&body.joint, &ws.inertia[j]);
        // The diagonal: expanded 0, 1, … levels, as long as bodies remain.
        let diag = &mut out[j * n + j];
        diag.push(project(&body.joint, &f));
        let mut own_sum: Option<S> = None;
        for d in 1..=reach {
            let lj = &level[j];
            let at = |l: usize| (j..n).filter(move |&k| lj[k] == Some(l));
            for k in at(d - 1) {
                let t = quadratic_form(&own[k], &down[j][k].expect("in reach"));
                own_sum = Some(own_sum.map_or(t, |s| s + t));
            }
            let mut e = own_sum.expect("body j is at level 0");
            let mut deeper = false;
            for k in at(d) {
                e += quadratic_form(&ws.inertia[k], &down[j][k].expect("in reach"));
                deeper = true;
            }
            diag.push(e);
            if !deeper {
                break;
            }
        }
        // A mirror image of an earlier column (the second finger of a
        // gripper): every entry above the parent is that column's, negated.
        if let Some(k) = mirrored_column(model, payloads, j) {
            let mut b = k;
            while let Some(p) = model.bodies[b].parent {
                let negated: Vec<S> = out[p * n + k].iter().map(|&x| -x).collect();
                out[p * n + j] = negated;
                b = p;
            }
            continue;
        }
        // Up the path to the root: the column carried, and each ancestor's
        // entry formed at the bodies on the way.
        let mut path = vec![j];
        let mut cols = vec![f];
        let mut k = j;
        while let Some(p) = model.bodies[k].parent {
            let joint = &model.bodies[k].joint;
            f = if k == j && !joint.is_revolute() {
                // A prismatic joint's own column `Iᶜ S = (h × s; m s)` has its
                // force along the axis `s`, so the translation `s·q` of the
                // joint adds `q s × m s = 0` to its moment: only the
                // placement carries it to the parent (no product with q).
                let place = Transform { rot: ws.x[k].rot, trans: Vec3::from_f64(&joint.placement.trans) };
                force_to_parent(joint, &place, &f)
            } else {
                force_to_parent(joint, &ws.x[k], &f)
            };
            k = p;
            path.push(k);
            cols.push(f);
            let list = &mut out[k * n + j];
            list.push(project(&model.bodies[k].joint, &f));
            for t in (0..path.len() - 1).rev() {
                let Some(s) = down[k][path[t]] else { break };
                list.push(s.dot(&cols[t]));
            }
        }
    }
    out
}

/// The column `Iᶜ_j S_j` of a prismatic joint `j` without children (and
/// without payloads), carried to its parent: a model constant, since the
/// joint's translation along `S_j` does not change it (see [`candidates`]).
fn leaf_column_at_parent(model: &Model, payloads: &[BodyInertia<impl Scalar>], j: usize) -> Option<Force<f64>> {
    let body = &model.bodies[j];
    let leaf = !body.joint.is_revolute()
        && body.parent.is_some()
        && !model.bodies.iter().any(|b| b.parent == Some(j))
        && !payloads.iter().any(|p| p.body == j);
    leaf.then(|| {
        let place = Transform::<f64>::from_f64(&body.joint.placement);
        force_to_parent(&body.joint, &place, &inertia_times_subspace(&body.joint, &body.inertia))
    })
}

/// An earlier joint `k` whose column is exactly the negation of joint `j`'s
/// at their common parent ([`leaf_column_at_parent`]): the two fingers of
/// a gripper, mirror images of each other. Every entry of `j`'s column
/// above the parent is then `k`'s negated, to the bit (each operation that
/// carries and projects a column is odd, and IEEE rounding is symmetric).
fn mirrored_column(model: &Model, payloads: &[BodyInertia<impl Scalar>], j: usize) -> Option<usize> {
    let fj = leaf_column_at_parent(model, payloads, j)?.to_array();
    (0..j).find(|&k| {
        model.bodies[k].parent == model.bodies[j].parent
            && leaf_column_at_parent(model, payloads, k)
                .is_some_and(|fk| fk.to_array().iter().zip(&fj).all(|(a, b)| *a == -*b))
    })
}

/// M(q), row-major into `m` (n×n, both triangles), each entry computed as
/// `plan` says, with extra body inertias `payloads` added to their bodies'
/// as [`crba`](crate::algorithms::crba::crba)
/// does (every plan is exact whatever the inertias). With mimic joints the
/// plan is the bodies' (M_tree), projected: `Gᵀ M_tree G`
/// ([`mimic`](crate::algorithms::mimic)).
///
/// # Panics
/// If the slices do not fit the model, or `plan` is not one of its.
pub(crate) fn mass_matrix<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    payloads: &[BodyInertia<S>],
    plan: &Plan,
    m: &mut [S],
) {
    if model.has_mimic() {
        let nt = model.bodies.len();
        let (mut tq, mut mt) = (vec![S::zero(); nt], vec![S::zero(); nt * nt]);
        mimic::tree_positions(model, q, &mut tq);
        tree_mass_matrix(model, ws, &tq, (payloads, plan), &mut mt);
        return mimic::project_matrix(model, &mt, m);
    }
    tree_mass_matrix(model, ws, q, (payloads, plan), m)
}

/// [`mass_matrix`] of the bodies' coordinates: M_tree.
fn tree_mass_matrix<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    (payloads, plan): (&[BodyInertia<S>], &Plan),
    m: &mut [S],
) {
    let n = model.bodies.len();
    assert!(m.len() == n * n && plan.choice.len() == n * n, "mass_matrix: m and the plan must be {n}×{n}");
    assert!(payloads.iter().all(|p| p.body < n), "mass_matrix: a payload's body is not one of the model's {n}");
    let all = candidates(model, ws, q, payloads, plan.reach());
    m.fill(S::zero());
    for i in 0..n {
        for j in i..n {
            if let Some(&x) = all[i * n + j].get(plan.choice[i * n + j]) {
                m[i * n + j] = x;
                m[j * n + i] = x;
            }
        }
    }
}

/// The choices for `model`: every way of computing each entry is traced
/// once, and starting from the generic algorithm's, each entry in turn takes
/// the way that lowers the operation count of all chosen entries together
/// (operations shared between entries counted once), until none does.
/// Models of more than [`MAX_PLANNED_DOF`] joints keep the generic choices.
pub(crate) fn plan(model: &Model, rewrites: Rewrites) -> Result<Plan, TraceActive> {
    let n = model.bodies.len();
    if n > MAX_PLANNED_DOF {
        return Ok(Plan::crba(n));
    }
    let tracer = Tracer::start_with(rewrites)?;
    let q = tracer.inputs("q", n);
    let mut ws = Workspace::<Expr>::new(model);
    let all = candidates(model, &mut ws, &q, &[], n);
    drop(ws);
    let graph = tracer.finish();
    let flat: Vec<Expr> = all.iter().flatten().copied().collect();
    let f = Traced::new("mass_matrix", &graph, &flat);
    let nodes = f.nodes();
    let is_op = |node: &Node| !matches!(node, Node::Const(_) | Node::Input { .. } | Node::Sin(_) | Node::Cos(_));
    // The operations each candidate reaches.
    let mut seen = vec![u32::MAX; nodes.len()];
    let cone = |root: u32, mark: u32, seen: &mut Vec<u32>| -> Vec<u32> {
        let mut stack = vec![root];
        let mut ops = Vec::new();
        while let Some(x) = stack.pop() {
            if seen[x as usize] == mark {
                continue;
            }
            seen[x as usize] = mark;
            let node = &nodes[x as usize];
            if is_op(node) {
                ops.push(x);
            }
            stack.extend(node.operands());
        }
        ops
    };
    let mut outputs = f.outputs().iter();
    let mut cones: Vec<Vec<Vec<u32>>> = Vec::with_capacity(n * n);
    let mut mark = 0;
    for list in &all {
        let mut c = Vec::with_capacity(list.len());
        for _ in list {
            let root = *outputs.next().expect("one output per candidate");
            c.push(cone(root, mark, &mut seen));
            mark += 1;
        }
        cones.push(c);
    }
    let mut plan = Plan::crba(n);
    let mut uses = vec![0u32; nodes.len()];
    for c in &cones {
        for &x in c.first().into_iter().flatten() {
            uses[x as usize] += 1;
        }
    }
    // Moves: one entry to another choice, or a whole row's off-diagonal
    // entries to the same level below their joint (carrying the row's axis
    // pays only when several entries share it). Diagonal entries first
    // (their choices decide which axes are carried), then the rest.
    let mut moves: Vec<Vec<(usize, usize)>> = Vec::new();
    let singles = |e: usize| (1..cones[e].len()).map(move |alt| vec![(e, alt)]);
    for i in 0..n {
        moves.extend(singles(i * n + i));
    }
    for i in 0..n {
        for level in 1..n {
            let row: Vec<(usize, usize)> = (i + 1..n)
                .map(|j| i * n + j)
                .filter(|&e| cones[e].len() > 1)
                .map(|e| (e, level.min(cones[e].len() - 1)))
                .collect();
            if row.len() > 1 {
                moves.push(row);
            }
        }
        for j in i + 1..n {
            moves.extend(singles(i * n + j));
        }
    }
    for _sweep in 0..4 {
        let mut improved = false;
        for m in &moves {
            let m: Vec<(usize, usize)> = m.iter().copied().filter(|&(e, alt)| plan.choice[e] != alt).collect();
            if m.is_empty() {
                continue;
            }
            // Operations freed by dropping the current choices, and added by
            // taking the others.
            let mut freed = 0i64;
            for &(e, _) in &m {
                for &x in &cones[e][plan.choice[e]] {
                    uses[x as usize] -= 1;
                    freed += i64::from(uses[x as usize] == 0);
                }
            }
            let mut added = 0i64;
            for &(e, alt) in &m {
                for &x in &cones[e][alt] {
                    added += i64::from(uses[x as usize] == 0);
                    uses[x as usize] += 1;
                }
            }
            if added < freed {
                for &(e, alt) in &m {
                    plan.choice[e] = alt;
                }
                improved = true;
            } else {
                for &(e, alt) in &m {
                    for &x in &cones[e][alt] {
                        uses[x as usize] -= 1;
                    }
                    for &x in &cones[e][plan.choice[e]] {
                        uses[x as usize] += 1;
                    }
                }
            }
        }
        if !improved {
            break;
        }
    }
    Ok(plan)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::crba::crba;
    use crate::algorithms::Loads;
    use crate::codegen::{prepare::prepare_model, CodegenOptions};

    fn bundled(name: &str) -> Model {
        Model::from_urdf_file(format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"))).unwrap()
    }

    /// Every choice of every entry, on chains and a tree, regrouped or not,
    /// equals the generic CRBA.
    #[test]
    fn every_choice_equals_the_generic_crba() {
        let opts = CodegenOptions::default();
        for name in ["ur5", "panda", "torso_two_arms"] {
            let original = bundled(name);
            for model in [prepare_model(&original, &opts).0, original.clone()] {
                let n = model.dof();
                let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.7 * i as f64 - 0.11 * (i * i) as f64).collect();
                let mut want = vec![0.0; n * n];
                crba(&model, &mut Workspace::new(&model), &q, Loads::none(), &mut want);
                let all = candidates(&model, &mut Workspace::new(&model), &q, &[], n);
                let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                let mut checked = 0;
                for i in 0..n {
                    for j in i..n {
                        let list = &all[i * n + j];
                        let mut k = Some(j);
                        while k.is_some_and(|k| k > i) {
                            k = model.bodies[k.unwrap()].parent;
                        }
                        assert_eq!(list.is_empty(), k != Some(i), "{name} ({i}, {j})");
                        for (c, x) in list.iter().enumerate() {
                            let err = (x - want[i * n + j]).abs();
                            assert!(err <= 1e-13 * scale, "{name} M[{i}][{j}] choice {c}: {x} vs {}", want[i * n + j]);
                            checked += 1;
                        }
                    }
                }
                assert!(checked > n * (n + 1) / 2, "{name}: more than one choice somewhere");
                // the Panda's second finger mirrors the first
                let mirrors: Vec<Option<usize>> =
                    (0..n).map(|j| mirrored_column(&model, &[] as &[BodyInertia<f64>], j)).collect();
                let want_mirrors = if name == "panda" { vec![(8, 7)] } else { vec![] };
                let got_mirrors: Vec<(usize, usize)> =
                    mirrors.iter().enumerate().filter_map(|(j, k)| k.map(|k| (j, k))).collect();
                assert_eq!(got_mirrors, want_mirrors, "{name}");
                // and through a plan
                let p = plan(&model, opts.rewrites).unwrap();
                let mut got = vec![0.0; n * n];
                mass_matrix(&model, &mut Workspace::new(&model), &q, &[], &p, &mut got);
                for (x, y) in got.iter().zip(&want) {
                    assert!((x - y).abs() <= 1e-13 * scale, "{name}: {x} vs {y}");
                }
                // with payloads on two bodies
                let payloads: Vec<BodyInertia<f64>> = [(n - 1, 0.7), (n / 2, 1.9)]
                    .iter()
                    .map(|&(body, mass)| BodyInertia {
                        body,
                        inertia: Inertia::from_mass_com_inertia(
                            mass,
                            crate::spatial::Vec3([0.05, -0.1, 0.2]),
                            crate::spatial::Sym3([0.02, 0.03, 0.01, 0.001, -0.002, 0.0005]),
                        ),
                    })
                    .collect();
                crate::algorithms::crba::crba(
                    &model,
                    &mut Workspace::new(&model),
                    &q,
                    Loads::none().with_payloads(&payloads),
                    &mut want,
                );
                mass_matrix(&model, &mut Workspace::new(&model), &q, &payloads, &p, &mut got);
                let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                for (x, y) in got.iter().zip(&want) {
                    assert!((x - y).abs() <= 1e-13 * scale, "{name} with payloads: {x} vs {y}");
                }
            }
        }
    }
}
