//! The functions of a generated module, traced from the generic algorithms.

use super::{leaves, mass_matrix};
use crate::algorithms::{aba, bias, crba, forward_dynamics, ldlt, rnea, BodyInertia, Loads, TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::Vec3;
use crate::symbolic::{balance, factor, Expr, Function, Graph, Latency, Node, NodeId, Rewrites, TraceActive, Tracer};
use crate::Scalar;

/// The functions of the generated-code contract (DESIGN.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FunctionKind {
    /// `inverse_dynamics(q, qd, qdd) -> τ`, by the recursive Newton-Euler algorithm.
    InverseDynamics,
    /// `mass_matrix(q) -> M`, by the composite-rigid-body algorithm.
    MassMatrix,
    /// `bias_forces(q, qd) -> h = C(q, q̇)q̇ + g(q)`.
    BiasForces,
    /// `gravity_torques(q) -> g(q)`.
    GravityTorques,
    /// `forward_dynamics(q, qd, tau) -> q̈` by the articulated-body algorithm.
    ForwardDynamicsAba,
    /// `forward_dynamics(q, qd, tau) -> q̈` by CRBA, RNEA and a sparse LᵀDL solve.
    ForwardDynamicsLdlt,
}

impl FunctionKind {
    /// Every kind, in the order a module lists them.
    pub const ALL: [FunctionKind; 6] = [
        FunctionKind::InverseDynamics,
        FunctionKind::MassMatrix,
        FunctionKind::BiasForces,
        FunctionKind::GravityTorques,
        FunctionKind::ForwardDynamicsAba,
        FunctionKind::ForwardDynamicsLdlt,
    ];
    /// The name of the generated function.
    pub fn fn_name(self) -> &'static str {
        match self {
            FunctionKind::InverseDynamics => "inverse_dynamics",
            FunctionKind::MassMatrix => "mass_matrix",
            FunctionKind::BiasForces => "bias_forces",
            FunctionKind::GravityTorques => "gravity_torques",
            FunctionKind::ForwardDynamicsAba | FunctionKind::ForwardDynamicsLdlt => "forward_dynamics",
        }
    }
    /// A label that tells the two forward dynamics apart.
    pub fn label(self) -> &'static str {
        match self {
            FunctionKind::ForwardDynamicsAba => "forward_dynamics (ABA)",
            FunctionKind::ForwardDynamicsLdlt => "forward_dynamics (CRBA + LTDL)",
            k => k.fn_name(),
        }
    }
    /// The input vectors, in argument order.
    pub fn inputs(self) -> &'static [&'static str] {
        match self {
            FunctionKind::InverseDynamics => &["q", "qd", "qdd"],
            FunctionKind::MassMatrix | FunctionKind::GravityTorques => &["q"],
            FunctionKind::BiasForces => &["q", "qd"],
            FunctionKind::ForwardDynamicsAba | FunctionKind::ForwardDynamicsLdlt => &["q", "qd", "tau"],
        }
    }
    /// Whether the output is the n×n matrix (row-major) rather than an n-vector.
    pub fn is_matrix(self) -> bool {
        self == FunctionKind::MassMatrix
    }
    /// Runs the generic algorithm behind this function on any scalar:
    /// `args` in the order of [`inputs`](Self::inputs), `gravity` in the
    /// base frame, the result into `out` (n, or n×n row-major). Tracing and
    /// the generic operation count both go through here.
    pub fn run<S: Scalar>(
        self,
        model: &Model,
        ws: &mut Workspace<S>,
        args: &[Vec<S>],
        gravity: &Vec3<S>,
        out: &mut [S],
    ) {
        let g = Some(gravity);
        match self {
            FunctionKind::InverseDynamics => {
                rnea::rnea(model, ws, &args[0], Some(&args[1]), Some(&args[2]), Loads::new(g, &[], &[]), out)
            }
            FunctionKind::MassMatrix => crba::crba(model, ws, &args[0], Loads::none(), out),
            FunctionKind::BiasForces => bias::bias_forces(model, ws, &args[0], &args[1], g, out),
            FunctionKind::GravityTorques => bias::gravity_torques(model, ws, &args[0], gravity, out),
            FunctionKind::ForwardDynamicsAba => {
                aba::aba(model, ws, &args[0], &args[1], &args[2], Loads::new(g, &[], &[]), out)
            }
            FunctionKind::ForwardDynamicsLdlt => forward_dynamics::forward_dynamics_ldlt(
                model,
                ws,
                &args[0],
                &args[1],
                &args[2],
                Loads::new(g, &[], &[]),
                out,
            ),
        }
    }
}

/// Runs the generic algorithm behind `kind` on symbolic inputs and keeps
/// what its outputs reach, factored. Gravity is the model's, folded in as
/// constants.
pub fn trace(model: &Model, kind: FunctionKind, rewrites: Rewrites) -> Result<Function, TraceActive> {
    Ok(factor(&trace_unfactored(model, kind, rewrites)?, rewrites))
}

/// The mass matrix, in `MassMatrix` and the LᵀDL forward dynamics, is
/// traced from the codegen variant of CRBA ([`mass_matrix`](super::mass_matrix)),
/// with the choices [`plan`](super::mass_matrix::plan) makes for this model;
/// every other function from the generic algorithm ([`FunctionKind::run`]).
fn trace_unfactored(model: &Model, kind: FunctionKind, rewrites: Rewrites) -> Result<Function, TraceActive> {
    match kind {
        FunctionKind::MassMatrix => {
            let plan = mass_matrix::plan(model, rewrites)?;
            trace_run(model, kind, rewrites, |ws, args, _, out| {
                mass_matrix::mass_matrix(model, ws, &args[0], &[], &plan, out)
            })
        }
        FunctionKind::ForwardDynamicsLdlt => {
            let plan = mass_matrix::plan(model, rewrites)?;
            trace_run(model, kind, rewrites, |ws, args, g, out| {
                let steps = LdltSteps { gravity: Some(g), tips: &[], payloads: &[], plan: &plan };
                ldlt_forward_dynamics(model, ws, &args[0], &args[1], &args[2], &steps, |_| {}, out)
            })
        }
        FunctionKind::GravityTorques => match leaves::fold_for_gravity(model) {
            // Point masses on prismatic leaves folded into their parents
            // (codegen/leaves.rs); the model's own workspace does not fit.
            Some((folded, list)) => trace_run(&folded, kind, rewrites, |ws, args, g, out| {
                leaves::gravity_torques(&folded, &list, ws, &args[0], g, out)
            }),
            None => trace_run(model, kind, rewrites, |ws, args, g, out| kind.run(model, ws, args, g, out)),
        },
        _ => trace_run(model, kind, rewrites, |ws, args, g, out| kind.run(model, ws, args, g, out)),
    }
}

/// What [`ldlt_forward_dynamics`] takes besides the state: gravity, tip
/// wrenches, run-time payloads, and the mass-matrix plan.
pub(crate) struct LdltSteps<'a> {
    pub gravity: Option<&'a Vec3<Expr>>,
    pub tips: &'a [TipWrench<Expr>],
    pub payloads: &'a [BodyInertia<Expr>],
    pub plan: &'a mass_matrix::Plan,
}

/// q̈ = M⁻¹(rhs − h − JᵀF_tip) as the generated CRBA + LᵀDL computes it:
/// the steps of `forward_dynamics::forward_dynamics_ldlt`, with M from
/// the planned [`mass_matrix`](mass_matrix::mass_matrix) (that function is
/// left as it is: passing it the mass matrix cost the f64 solver
/// instructions), and `add_to_m` applied to M before it is factorised (a
/// scene's armature). Plain modules and scenes trace it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn ldlt_forward_dynamics(
    model: &Model,
    ws: &mut Workspace<Expr>,
    q: &[Expr],
    qd: &[Expr],
    rhs: &[Expr],
    steps: &LdltSteps,
    add_to_m: impl FnOnce(&mut [Expr]),
    out: &mut [Expr],
) {
    let n = model.dof();
    rnea::rnea(model, ws, q, Some(qd), None, Loads::new(steps.gravity, steps.tips, steps.payloads), out);
    for i in 0..n {
        out[i] = rhs[i] - out[i];
    }
    let mut m = vec![Expr::zero(); n * n];
    mass_matrix::mass_matrix(model, ws, q, steps.payloads, steps.plan, &mut m);
    add_to_m(&mut m);
    ldlt::factorise(model, &mut m);
    ldlt::solve(model, &m, out);
}

/// Traces `run` (an algorithm computing `kind`'s outputs, with `kind`'s
/// inputs) on symbolic inputs, unfactored.
fn trace_run(
    model: &Model,
    kind: FunctionKind,
    rewrites: Rewrites,
    run: impl FnOnce(&mut Workspace<Expr>, &[Vec<Expr>], &Vec3<Expr>, &mut [Expr]),
) -> Result<Function, TraceActive> {
    let n = model.dof();
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> = kind.inputs().iter().map(|name| tracer.inputs(name, n)).collect();
    let mut ws = Workspace::<Expr>::new(model);
    let g = Vec3::<Expr>::from_f64(&model.gravity);
    let zero = tracer.constant(0.0);
    let mut out = vec![zero; if kind.is_matrix() { n * n } else { n }];
    run(&mut ws, &args, &g, &mut out);
    drop(ws);
    let graph = tracer.finish();
    Ok(Function::new(kind.fn_name(), &graph, &out))
}

/// A function traced with the sines and cosines of the joint angles as
/// inputs: `s[i]` and `c[i]` are the sine and cosine of joint `i`'s angle
/// θᵢ = `angle_scale[i]`·`q[i]` (the scale is `|axis|`, 1 for a unit axis;
/// `None` for a joint whose angle the function does not read).
#[derive(Clone, Debug, PartialEq)]
pub struct SinCosTrace {
    /// The function, reading `s` and `c` instead of computing sines and
    /// cosines (and `q` only where a prismatic joint needs it).
    pub function: Function,
    /// For each joint, the factor of `q[i]` in its angle, if it is read.
    pub angle_scale: Vec<Option<f64>>,
}

/// [`trace`], with every sine and cosine of a joint angle read from the
/// inputs `s` and `c` instead (see [`SinCosTrace`]). `Err` names a sine of
/// anything other than a joint angle (which the algorithms never take).
pub fn trace_sin_cos_inputs(model: &Model, kind: FunctionKind, rewrites: Rewrites) -> Result<SinCosTrace, String> {
    let f = trace_unfactored(model, kind, rewrites).map_err(|e| e.to_string())?;
    sin_cos_inputs(&f, model.dof(), rewrites)
}

/// A traced (unfactored) function of `q` with the sines and cosines of the
/// `n` joint angles made inputs, then factored; see [`trace_sin_cos_inputs`].
pub fn sin_cos_inputs(f: &Function, n: usize, rewrites: Rewrites) -> Result<SinCosTrace, String> {
    let nodes = f.nodes();
    let q = f.input_names().iter().position(|s| s == "q").map(|k| k as u32);
    let joint_of = |id: NodeId| match nodes[id as usize] {
        Node::Input { name, index } if Some(name) == q => Some(index as usize),
        _ => None,
    };
    let mut g = Graph::with_rewrites(rewrites);
    // Keep the input vectors' order (q, qd, …) and add s, c after them.
    for name in f.input_names() {
        g.input(name, 0);
    }
    let mut angle_scale: Vec<Option<f64>> = vec![None; n];
    let mut new: Vec<NodeId> = Vec::with_capacity(nodes.len());
    // For each SinCos node: its joint.
    let mut sc_joint: Vec<usize> = vec![usize::MAX; nodes.len()];
    for (id, node) in nodes.iter().enumerate() {
        let m = |x: NodeId| new[x as usize];
        let mapped = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => g.input(&f.input_names()[name as usize], index as usize),
            Node::Add(a, b) => g.add(m(a), m(b)),
            Node::Sub(a, b) => g.sub(m(a), m(b)),
            Node::Mul(a, b) => g.mul(m(a), m(b)),
            Node::Div(a, b) => g.div(m(a), m(b)),
            Node::Neg(a) => g.neg(m(a)),
            Node::Sqrt(a) => g.sqrt(m(a)),
            Node::SinCos(a) => {
                let (joint, scale) = match (joint_of(a), nodes[a as usize]) {
                    (Some(i), _) => (i, 1.0),
                    (None, Node::Mul(x, y)) => match (joint_of(x), joint_of(y), nodes[x as usize], nodes[y as usize]) {
                        (Some(i), None, _, k) | (None, Some(i), k, _) => match k.constant() {
                            Some(k) => (i, k),
                            None => return Err(format!("{}: the sine of a non-angle", f.name())),
                        },
                        _ => return Err(format!("{}: the sine of a non-angle", f.name())),
                    },
                    _ => return Err(format!("{}: the sine of a non-angle", f.name())),
                };
                if angle_scale[joint].is_some_and(|k| k != scale) {
                    return Err(format!("{}: joint {joint} turns by two different angles", f.name()));
                }
                angle_scale[joint] = Some(scale);
                sc_joint[id] = joint;
                // Not read by anything but Sin and Cos, which map to inputs.
                g.constant(0.0)
            }
            Node::Sin(sc) => g.input("s", sc_joint[sc as usize]),
            Node::Cos(sc) => g.input("c", sc_joint[sc as usize]),
        };
        new.push(mapped);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut names = f.input_names().to_vec();
    for extra in ["s", "c"] {
        if !names.iter().any(|x| x == extra) {
            names.push(extra.to_string());
        }
    }
    let mut function = Function::from_ids(f.name(), &g, &outputs);
    function.set_input_names(&names);
    let mut function = factor(&function, rewrites);
    if rewrites.reassociate {
        function = balance(&function, &Latency::default(), rewrites);
    }
    Ok(SinCosTrace { function, angle_scale })
}

/// The inverse of [`trace_sin_cos_inputs`]: `s[i]` and `c[i]` replaced by the
/// sine and cosine of `angle_scale[i]·q[i]`, giving a function of `q` again
/// (for evaluation and operation counts of the `q` variant).
pub fn sin_cos_from_q(sc: &SinCosTrace, rewrites: Rewrites) -> Function {
    let f = &sc.function;
    let mut g = Graph::with_rewrites(rewrites);
    for name in f.input_names() {
        if name != "s" && name != "c" {
            g.input(name, 0);
        }
    }
    let mut new: Vec<NodeId> = Vec::with_capacity(f.nodes().len());
    for node in f.nodes() {
        let m = |x: NodeId| new[x as usize];
        let mapped = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => {
                let name = &f.input_names()[name as usize];
                if name == "s" || name == "c" {
                    let i = index as usize;
                    let q = g.input("q", i);
                    let scale = sc.angle_scale[i].unwrap_or(1.0);
                    let angle = if scale == 1.0 {
                        q
                    } else {
                        let k = g.constant(scale);
                        g.mul(q, k)
                    };
                    let (s, c) = g.sin_cos(angle);
                    if name == "s" {
                        s
                    } else {
                        c
                    }
                } else {
                    g.input(name, index as usize)
                }
            }
            Node::Add(a, b) => g.add(m(a), m(b)),
            Node::Sub(a, b) => g.sub(m(a), m(b)),
            Node::Mul(a, b) => g.mul(m(a), m(b)),
            Node::Div(a, b) => g.div(m(a), m(b)),
            Node::Neg(a) => g.neg(m(a)),
            Node::Sqrt(a) => g.sqrt(m(a)),
            Node::SinCos(_) | Node::Sin(_) | Node::Cos(_) => unreachable!("an _sc function has no sines"),
        };
        new.push(mapped);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut out = Function::from_ids(f.name(), &g, &outputs);
    let names: Vec<String> = f.input_names().iter().filter(|n| *n != "s" && *n != "c").cloned().collect();
    out.set_input_names(&names);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codegen::{prepare_model, CodegenOptions};

    /// The codegen variant of CRBA never needs more operations than the
    /// generic one it replaces in the trace.
    #[test]
    fn the_planned_mass_matrix_is_no_costlier_than_the_generic_crba() {
        let opts = CodegenOptions::default();
        for name in ["ur5", "panda", "torso_two_arms", "planar_2link"] {
            let path = format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"));
            let (model, _) = prepare_model(&Model::from_urdf_file(path).unwrap(), &opts);
            for kind in [FunctionKind::MassMatrix, FunctionKind::ForwardDynamicsLdlt] {
                let count = |f: Function| sin_cos_inputs(&f, model.dof(), opts.rewrites).unwrap().function.op_count();
                let generic = count(
                    trace_run(&model, kind, opts.rewrites, |ws, args, g, out| kind.run(&model, ws, args, g, out))
                        .unwrap(),
                );
                let planned = count(trace_unfactored(&model, kind, opts.rewrites).unwrap());
                println!("{name} {kind:?}: generic CRBA {generic}, planned {planned}");
                assert!(planned.total() <= generic.total(), "{name} {kind:?}: {planned} vs {generic}");
            }
        }
    }
}
