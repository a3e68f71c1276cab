//! Tracing: each function a module asks for, run on the symbolic scalar
//! ([`Expr`]) through the same algorithms the generic solver runs, gives an
//! expression graph of the model's constants and the function's inputs.
//!
//! A few functions are traced from a variant of their algorithm that is
//! cheaper to unroll and computes the same quantity: the mass matrix (here,
//! and in the LᵀDL forward dynamics) from the planned CRBA of
//! [`mass_matrix`], the gravity torques of a model with point masses on
//! prismatic leaves from [`gravity_fold`]. Forward dynamics is traced both
//! ways, by the articulated-body algorithm and by CRBA + LᵀDL, and
//! [`fd_choice`] keeps one. [`sin_cos`] then turns the sines and cosines of
//! the joint angles into inputs: the body every emitted function has.

pub(crate) mod branches;
pub mod fd_choice;
mod frames;
mod generic_count;
mod gravity_fold;
mod mass_matrix;
mod sin_cos;

pub use generic_count::generic_op_count;
pub use sin_cos::{sin_cos_from_q, sin_cos_inputs, Angle, SinCosTrace};

use super::emit::{loop_ops, payload_argument, Sizes};
use super::{counted, CodegenError, CodegenOptions, ForwardDynamicsMethod, Function, GeneratedFunction, ScalarType};
use crate::algorithms::derivatives::{self, DerivativeWorkspace, Dynamics, Formulation, MassMatrixFn};
use crate::algorithms::{crba, ldlt, rnea, BodyInertia, Loads, TipWrench, Workspace};
use crate::scene::{dynamics, ResolvedGravity, SceneModel};
use crate::spatial::{Force, Inertia, Sym3, Transform, Vec3};
use crate::symbolic::{factor, Expr, OpCount, Rewrites, Traced, Tracer};

/// Traces `f` of `scene` as the generated module computes it, factored (on
/// `scene.model` as it is: [`generate`](super::generate) prepares the model
/// first). `method` picks the forward-dynamics algorithm (`Auto` is the
/// articulated-body algorithm here); a scene with run-time payloads always
/// takes LᵀDL.
pub fn trace(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    let mut best: Option<(usize, Traced)> = None;
    for &formulation in formulations(f, &scene.model) {
        let traced = trace_unfactored(scene, f, method, formulation, rewrites)?;
        let cost = body_cost(&traced, scene, rewrites, true)?.fp_ops();
        if best.as_ref().is_none_or(|(c, _)| cost < *c) {
            best = Some((cost, traced));
        }
    }
    Ok(factor(&best.expect("one formulation at least").1, rewrites))
}

/// The formulations `f` is traced in: both for the derivatives of the
/// dynamics (the one with fewer operations is emitted), else one; a model
/// with mimic joints has the dual numbers alone (the analytical recursion
/// runs over the bodies, [`derivatives::inverse_dynamics_derivatives`]).
fn formulations(f: &Function, model: &crate::model::Model) -> &'static [Formulation] {
    match f {
        Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives if model.has_mimic() => {
            &[Formulation::DualNumbers]
        }
        Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives => &Formulation::ALL,
        _ => &[Formulation::Analytical],
    }
}

/// The operation count of the `NAME_sc` body of a traced function.
fn body_cost(traced: &Traced, scene: &SceneModel, rewrites: Rewrites, fma: bool) -> Result<OpCount, CodegenError> {
    let offset = scene.model.nq() - scene.dof();
    let sc = sin_cos_inputs(traced, scene.dof(), offset, rewrites).map_err(CodegenError::Internal)?;
    Ok(counted(&sin_cos_from_q(&sc, rewrites), fma))
}

/// Every function `options` ask for, traced on the prepared `scene`, each
/// with its `NAME_sc` body and operation count, and the forward dynamics
/// chosen. With [`ForwardDynamicsMethod::Auto`] both forward dynamics are
/// traced and [`fd_choice`] marks one emitted (a scene with run-time
/// payloads has LᵀDL alone).
pub(crate) fn trace_module(
    scene: &SceneModel,
    options: &CodegenOptions,
) -> Result<(Vec<GeneratedFunction>, fd_choice::FdChoice), CodegenError> {
    let n = scene.dof();
    let sizes = Sizes::of(&scene.model);
    // Where joint i's angle is in q: q[i], or q[7 + i] after a floating base's position and quaternion.
    let offset = scene.model.nq() - scene.dof();
    let payloads = !scene.input_payloads.is_empty();
    // The articulated-body recursion cannot take mimic joints (see algorithms::mimic).
    let mimic = scene.model.has_mimic();
    if mimic
        && options.forward_dynamics == ForwardDynamicsMethod::Aba
        && options.functions.contains(&Function::ForwardDynamics)
    {
        return Err(CodegenError::Unsupported(format!(
            "forward dynamics by the articulated-body algorithm (aba): {}; its q̈ comes from M by LTDL (ldlt, or \
             the default)",
            mimic_note(&scene.model)
        )));
    }
    // Both forward dynamics are traced and counted, whichever is emitted.
    let methods: &[ForwardDynamicsMethod] = match options.forward_dynamics {
        _ if payloads || mimic => &[ForwardDynamicsMethod::Ldlt],
        _ => &[ForwardDynamicsMethod::Aba, ForwardDynamicsMethod::Ldlt],
    };
    let mut functions = Vec::new();
    for f in &options.functions {
        let inputs: Vec<(String, usize)> =
            f.params(scene).iter().map(|p| (p.name.clone(), p.len_value(sizes))).collect();
        let variants: Vec<Option<ForwardDynamicsMethod>> =
            if *f == Function::ForwardDynamics { methods.iter().map(|&m| Some(m)).collect() } else { vec![None] };
        let first = functions.len();
        for method in variants {
            for &formulation in formulations(f, &scene.model) {
                let m = method.unwrap_or(ForwardDynamicsMethod::Aba);
                let traced = trace_unfactored(scene, f, m, formulation, options.rewrites)?;
                let sc = sin_cos_inputs(&traced, n, offset, options.rewrites).map_err(CodegenError::Internal)?;
                let traced = sin_cos_from_q(&sc, options.rewrites);
                let op_count = counted(&traced, options.fma);
                functions.push(GeneratedFunction {
                    function: f.clone(),
                    method,
                    formulation: (formulations(f, &scene.model).len() > 1).then_some(formulation),
                    name: f.rust_name(),
                    emitted: true,
                    inputs: inputs.clone(),
                    traced,
                    sin_cos_inputs: sc,
                    op_count,
                    factors: None,
                    branched: None,
                });
            }
        }
        // Of the derivatives traced both ways, the one with fewer operations.
        if formulations(f, &scene.model).len() > 1 {
            let traced = &mut functions[first..];
            let best = (0..traced.len()).min_by_key(|&k| traced[k].op_count.fp_ops()).expect("traced");
            for (k, g) in traced.iter_mut().enumerate() {
                g.emitted = k == best;
            }
        }
        if options.branch_loops {
            for g in &mut functions[first..] {
                // A body with loops is never split (its parts would carry the
                // loops' results): one longer than the split allows stays unrolled.
                let lets = |b: &branches::Branched| counted(&b.body.function, options.fma).fp_ops();
                let fits = |b: &branches::Branched| options.split_lets.is_none_or(|max| lets(b) <= max);
                // (the forward dynamics' branches are the articulated-body algorithm's)
                if g.method != Some(ForwardDynamicsMethod::Ldlt) {
                    g.branched = branches::branched(scene, f, options.rewrites)?.filter(fits);
                }
            }
        }
        // The forward dynamics' derivatives as their factors and a loop, where
        // that counts fewer operations (codegen/emit/products.rs).
        if *f == Function::ForwardDynamicsDerivatives {
            if let Some(g) = functions[first..].iter_mut().find(|g| g.emitted) {
                let formulation = g.formulation.unwrap_or(formulations(f, &scene.model)[0]);
                let m = ForwardDynamicsMethod::Aba;
                let traced = trace_unfactored_as(scene, f, m, formulation, Products::Factors, options.rewrites)?;
                let sc = sin_cos_inputs(&traced, n, offset, options.rewrites).map_err(CodegenError::Internal)?;
                let count = counted(&sin_cos_from_q(&sc, options.rewrites), options.fma);
                if count.fp_ops() + loop_ops(sizes.nv) < g.op_count.fp_ops() {
                    g.factors = Some((sc, count));
                }
            }
        }
    }
    let fd = |method| fd_choice::FdChoice { method, why: String::new() };
    let find = |m| functions.iter().find(|g| g.method == Some(m));
    let choice = match (find(ForwardDynamicsMethod::Aba), find(ForwardDynamicsMethod::Ldlt)) {
        (Some(aba), Some(ldlt)) if options.forward_dynamics == ForwardDynamicsMethod::Auto => {
            // The ABA with branches runs each group's body once in vector
            // lanes (f64) or once a branch (a scalar loop in f32); its
            // operations counted as `estimated_cycles` counts them (unfused).
            let branched = aba.branched.as_ref().map(|b| {
                let (run, written) = b.fp_ops(false);
                if options.scalar == ScalarType::F64 {
                    written
                } else {
                    run
                }
            });
            fd_choice::choose_between(
                [&aba.traced, &aba.sin_cos_inputs.function],
                [&ldlt.traced, &ldlt.sin_cos_inputs.function],
                branched,
                &aba.inputs,
            )
        }
        _ if payloads => fd_choice::FdChoice {
            method: ForwardDynamicsMethod::Ldlt,
            why: "CRBA with the input payloads' inertias and the armature on M's diagonal, RNEA, and a sparse \
                  LTDL solve"
                .to_string(),
        },
        _ if mimic => fd_choice::FdChoice {
            method: ForwardDynamicsMethod::Ldlt,
            why: "CRBA projected on the independent joints (mimic joints follow their masters), RNEA, and a sparse \
                  LTDL solve: the articulated-body recursion cannot take mimic joints"
                .to_string(),
        },
        _ if options.forward_dynamics == ForwardDynamicsMethod::Ldlt => fd(ForwardDynamicsMethod::Ldlt),
        _ => fd(ForwardDynamicsMethod::Aba),
    };
    for g in &mut functions {
        if let Some(m) = g.method {
            g.emitted = m == choice.method;
        }
    }
    Ok((functions, choice))
}

/// `joint "a" follows "b"` for the first mimic joint of `model` (which has one).
fn mimic_note(model: &crate::model::Model) -> String {
    let follower = (0..model.bodies.len()).find_map(|i| model.mimic(i).map(|m| (i, m.master)));
    match follower {
        Some((i, master)) => {
            format!("joint \"{}\" follows \"{}\" (mimic)", model.bodies[i].joint.name, model.bodies[master].joint.name)
        }
        None => "the model has mimic joints".to_string(),
    }
}

/// The run-time loads a function of a scene reads, as symbolic inputs (or
/// folded constants): gravity, the tip wrench, the payloads.
struct SceneLoads {
    gravity: Option<Vec3<Expr>>,
    tips: Vec<TipWrench<Expr>>,
    payloads: Vec<BodyInertia<Expr>>,
}

impl SceneLoads {
    /// The loads of `f` in `scene`, the inputs declared on `tracer` in
    /// argument order (after the state vectors).
    fn of(scene: &SceneModel, f: &Function, tracer: &Tracer) -> SceneLoads {
        let model = &scene.model;
        let (gravity, tip, payloads) = f.loads();
        let gravity = match scene.gravity {
            _ if !gravity => None,
            ResolvedGravity::None => None,
            ResolvedGravity::Constant(_) => Some(Vec3::from_f64(&model.gravity)),
            ResolvedGravity::Input => {
                let g = tracer.inputs("gravity", 3);
                Some(Vec3([g[0], g[1], g[2]]))
            }
        };
        let tips = match scene.tip_wrench_frame {
            Some(frame) if tip => {
                let w = tracer.inputs("f_tip", 6);
                vec![TipWrench { frame, wrench: Force::from_array([w[0], w[1], w[2], w[3], w[4], w[5]]) }]
            }
            _ => Vec::new(),
        };
        let mut list = Vec::new();
        for p in scene.input_payloads.iter().filter(|_| payloads) {
            let v = tracer.inputs(&payload_argument(&p.link), 10);
            // On a fixed base a payload moves nothing; on a body (or a
            // floating base) it enters the recursions as one more body
            // inertia, moved into the body's frame (frames move with the
            // bodies the preparation slides, so this is exact in the prepared
            // model).
            let body = match model.frames[p.frame].body {
                Some(b) => b,
                None if model.is_floating() => crate::algorithms::BASE_BODY,
                None => continue,
            };
            let inertia = Inertia::from_mass_com_inertia(
                v[0],
                Vec3([v[1], v[2], v[3]]),
                Sym3([v[4], v[5], v[6], v[7], v[8], v[9]]),
            );
            let place = Transform::<Expr>::from_f64(&model.frames[p.frame].placement);
            list.push(BodyInertia { body, inertia: place.inertia_to_parent(&inertia) });
        }
        SceneLoads { gravity, tips, payloads: list }
    }
}

/// Traces `f` of `scene` without factoring; see [`trace`].
///
/// A floating-base model goes through the same arms: its `q` has NQ
/// entries and the velocity-side vectors NV, `rnea`, `crba` and `aba` are
/// the floating ones (`algorithms/floating/`, gravity in the world frame,
/// payloads on the base too), the scene's armature and friction act on the
/// joints after the base's six, and the fixed-base variants (the planned
/// mass matrix, the gravity fold) are left out.
pub(crate) fn trace_unfactored(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
    formulation: Formulation,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    trace_unfactored_as(scene, f, method, formulation, Products::Traced, rewrites)
}

/// Whether the forward dynamics' derivatives are traced whole, or as their
/// factors ∂τ/∂q, ∂τ/∂q̇ (at q̈ = FD) and M⁻¹, the products −M⁻¹∂τ left to
/// a loop in the emitted code (`codegen/emit/products.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Products {
    /// ∂q̈/∂q, ∂q̈/∂q̇, M⁻¹, every product traced.
    Traced,
    /// ∂τ/∂q, ∂τ/∂q̇ at q̈ = FD(q, q̇, τ), and M⁻¹.
    Factors,
}

/// [`trace_unfactored`], the forward dynamics' derivatives as `products` says.
pub(crate) fn trace_unfactored_as(
    scene: &SceneModel,
    f: &Function,
    method: ForwardDynamicsMethod,
    formulation: Formulation,
    products: Products,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    if let Some(name) = f.frame() {
        return frames::trace_unfactored(scene, f, name, rewrites);
    }
    let model = &scene.model;
    let floating = model.is_floating();
    let n = model.dof();
    let sizes = Sizes::of(model);
    let use_ldlt = *f == Function::ForwardDynamics
        && (method == ForwardDynamicsMethod::Ldlt || !scene.input_payloads.is_empty() || model.has_mimic());
    // The mass-matrix plan is made (traced) before this trace starts; a
    // floating model has none (the generic CRBA instead).
    let needs_plan =
        matches!(f, Function::MassMatrix | Function::ForwardDynamicsDerivatives | Function::MassMatrixInverse)
            || use_ldlt;
    let plan = if needs_plan && !floating { Some(mass_matrix::plan(model, rewrites)?) } else { None };
    let tracer = Tracer::start_with(rewrites)?;
    let length = |name: &&str| if *name == "q" { model.nq() } else { model.nv() };
    let args: Vec<Vec<Expr>> = f.vectors().iter().map(|name| tracer.inputs(name, length(name))).collect();
    let loads = SceneLoads::of(scene, f, &tracer);
    let mut ws = Workspace::<Expr>::new(model);
    let zero = tracer.constant(0.0);
    let mut out = vec![zero; f.output_len(sizes)];
    let (q, g, pl, tips) = (&args[0], loads.gravity.as_ref(), &loads.payloads[..], &loads.tips[..]);
    match f {
        Function::InverseDynamics => {
            dynamics::inverse_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, pl), &mut out)
        }
        Function::MassMatrix => {
            match &plan {
                Some(plan) => mass_matrix::mass_matrix(model, &mut ws, q, pl, plan, &mut out),
                // A floating base: the generic CRBA.
                None => crba::crba(model, &mut ws, q, Loads::new(None, &[], pl), &mut out),
            }
            dynamics::add_armature_diagonal(scene, &mut out);
        }
        Function::BiasForces if pl.is_empty() => dynamics::bias_forces(scene, &mut ws, q, &args[1], g, &mut out),
        Function::BiasForces => {
            rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(g, &[], pl), &mut out);
            dynamics::add_friction(scene, &args[1], &mut out);
        }
        Function::GravityTorques => match (g, gravity_fold::fold_for_gravity(model)) {
            // Point masses on prismatic leaves folded into their parents; the
            // model's own workspace does not fit the folded model.
            (Some(g), Some((folded, leaves))) if pl.is_empty() => {
                let mut ws = Workspace::<Expr>::new(&folded);
                gravity_fold::gravity_torques(&folded, &leaves, &mut ws, q, g, &mut out);
            }
            (Some(_), _) if !pl.is_empty() => {
                rnea::rnea(model, &mut ws, q, None, None, Loads::new(g, &[], pl), &mut out)
            }
            _ => dynamics::gravity_torques(scene, &mut ws, q, g, &mut out),
        },
        Function::Coriolis if pl.is_empty() => dynamics::coriolis(scene, &mut ws, q, &args[1], &mut out),
        Function::Coriolis => rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(None, &[], pl), &mut out),
        Function::ForwardDynamics if use_ldlt && floating => {
            dynamics::forward_dynamics_ldlt(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, pl), &mut out)
        }
        Function::ForwardDynamics if use_ldlt => {
            // M by the planned CRBA with the armature on its diagonal, h by
            // RNEA, on τ − friction, then the sparse LᵀDL solve.
            let plan = plan.as_ref().expect("planned above");
            let mut rhs = args[2].clone();
            dynamics::sub_friction(scene, &args[1], &mut rhs);
            rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(g, tips, pl), &mut out);
            for i in 0..n {
                out[i] = rhs[i] - out[i];
            }
            let mut m = vec![zero; n * n];
            mass_matrix::mass_matrix(model, &mut ws, q, pl, plan, &mut m);
            dynamics::add_armature_diagonal(scene, &mut m);
            ldlt::factorise(model, &mut m);
            ldlt::solve(model, &m, &mut out);
        }
        Function::ForwardDynamics => {
            dynamics::forward_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, tips, &[]), &mut out)
        }
        Function::InverseDynamicsDerivatives | Function::ForwardDynamicsDerivatives | Function::MassMatrixInverse => {
            // The scene's inverse dynamics (armature, friction), its
            // run-time loads held constant; M by the planned CRBA with the
            // armature on its diagonal where the formulation asks for M (a
            // floating base: the generic CRBA, in the tangent space of the
            // base's body twist).
            let plan = plan.as_ref();
            let mass = |ws: &mut Workspace<Expr>, q: &[Expr], m: &mut [Expr]| {
                mass_matrix::mass_matrix(model, ws, q, pl, plan.expect("planned above"), m);
                dynamics::add_armature_diagonal(scene, m);
            };
            let loads = dynamics::with_armature(scene, Loads::new(g, tips, pl));
            let d = Dynamics { model, loads, torques: scene, mass: plan.map(|_| &mass as MassMatrixFn<Expr>) };
            let mut dw = DerivativeWorkspace::<Expr>::new(model);
            let nv = sizes.nv;
            let (a, rest) = out.split_at_mut(nv * nv);
            // (q, q̇, q̈ or τ; the mass matrix's inverse has q alone)
            let state = || [q.as_slice(), &args[1], &args[2]];
            match f {
                Function::InverseDynamicsDerivatives => {
                    derivatives::inverse_dynamics_derivatives(&d, &mut dw, state(), formulation, [a, rest], None)
                }
                Function::ForwardDynamicsDerivatives => {
                    let (b, c) = rest.split_at_mut(nv * nv);
                    match products {
                        Products::Traced => {
                            derivatives::forward_dynamics_derivatives(&d, &mut dw, state(), formulation, [a, b, c])
                        }
                        Products::Factors => derivatives::forward_dynamics_derivative_factors(
                            &d,
                            &mut dw,
                            state(),
                            formulation,
                            [a, b, c],
                        ),
                    }
                }
                _ => {
                    let mut m = vec![zero; nv * nv];
                    let mut linv = vec![zero; nv * nv];
                    match plan {
                        Some(_) => mass(&mut dw.ws, q, &mut m),
                        None => crba::crba(model, &mut ws, q, loads.inertias(), &mut m),
                    }
                    derivatives::mass_matrix_inverse(model, &mut m, &mut linv, a);
                }
            }
        }
        Function::FramePose(_)
        | Function::FrameJacobian(_)
        | Function::FrameWorldJacobian(_)
        | Function::FrameAccelerationBias(_) => unreachable!("traced in frames.rs"),
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(Traced::new(&f.rust_name(), &graph, &out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::forward_dynamics;
    use crate::codegen::{prepare, CodegenOptions};
    use crate::scene::Scene;
    use crate::Scalar;

    /// The codegen variant of CRBA never needs more operations than the
    /// generic one it replaces in the trace.
    #[test]
    fn the_planned_mass_matrix_is_no_costlier_than_the_generic_crba() {
        let opts = CodegenOptions::default();
        for name in ["ur5", "panda", "torso_two_arms", "planar_2link"] {
            let path = format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"));
            let model = crate::Model::from_urdf_file(path).unwrap();
            let (scene, _) = prepare::prepare(&Scene::default().apply(&model).unwrap(), &opts);
            let (model, n) = (&scene.model, scene.dof());
            let count = |f: Traced| sin_cos_inputs(&f, n, 0, opts.rewrites).unwrap().function.op_count();
            // The same two functions with the generic CRBA: M, and the LᵀDL forward dynamics.
            let generic = |f: &Function| {
                let tracer = Tracer::start_with(opts.rewrites).unwrap();
                let args: Vec<Vec<Expr>> = f.vectors().iter().map(|v| tracer.inputs(v, n)).collect();
                let mut ws = Workspace::<Expr>::new(model);
                let mut out = vec![Expr::zero(); f.output_len(Sizes::of(model))];
                let g = Vec3::from_f64(&model.gravity);
                match f {
                    Function::MassMatrix => crba::crba(model, &mut ws, &args[0], Loads::none(), &mut out),
                    _ => forward_dynamics::forward_dynamics_ldlt(
                        model,
                        &mut ws,
                        &args[0],
                        &args[1],
                        &args[2],
                        Loads::gravity(&g),
                        &mut out,
                    ),
                }
                drop(ws);
                count(Traced::new(&f.rust_name(), &tracer.finish(), &out))
            };
            for f in [Function::MassMatrix, Function::ForwardDynamics] {
                let generic = generic(&f);
                let planned = count(
                    trace_unfactored(&scene, &f, ForwardDynamicsMethod::Ldlt, Formulation::Analytical, opts.rewrites)
                        .unwrap(),
                );
                println!("{name} {f:?}: generic CRBA {generic}, planned {planned}");
                assert!(planned.total() <= generic.total(), "{name} {f:?}: {planned} vs {generic}");
            }
        }
    }
}
