//! Code generation for a scene: [`generate_scene`].
//!
//! Each function a scene asks for is traced from the functions of
//! [`scene::dynamics`](crate::scene::dynamics), the ones
//! [`SceneRobot`](crate::scene::SceneRobot) runs, on the reduced model of the
//! [`SceneModel`]: locks, sub-tree, constant payloads, armature, friction and
//! a constant (or no) gravity are folded in as constants, and what the scene
//! does not ask for is never traced. The run-time inputs become arguments
//! after the contract's (`q`, `qd`, `qdd` or `tau`), in this order:
//!
//! | argument | when | meaning |
//! | --- | --- | --- |
//! | `gravity: &[T; 3]` | gravity `input` | m/s², in the reduced model's base frame (the sub-tree root's) |
//! | `f_tip: &[T; 6]` | a tip wrench | (m; f) the tip frame applies to its environment, in that frame (MR's `Ftip`) |
//! | `payload_LINK: &[T; 10]` | an input payload on LINK | `[mass, cx, cy, cz, ixx, iyy, izz, ixy, ixz, iyz]`: kg, centre of mass (m) and inertia about it (kg·m²), in LINK's frame |
//!
//! `inverse_dynamics` and `forward_dynamics` take the gravity, the tip
//! wrench and the payloads; `bias_forces` and `gravity_torques` gravity and
//! payloads (h has no tip wrench); `mass_matrix` and `coriolis` only
//! payloads; `frame_pose_FRAME(q) -> [[T; 4]; 4]` (the homogeneous pose in
//! the base frame) and `frame_jacobian_FRAME(q) -> [[T; DOF]; 6]` (the body
//! Jacobian, rows (ω; v), in the frame) nothing.
//!
//! **Input payloads.** The algorithms read a body's inertia as a model
//! constant, so a payload given at run time enters them as one more body
//! inertia on its link's body, from the arguments moved into the body's
//! frame: τ, h, g and C(q, q̇)q̇ by `rnea_with_payloads`, M by the planned
//! mass matrix (`codegen/mass_matrix.rs`) with the payloads in its
//! composite inertias. Forward dynamics with an input payload solves
//! (M + diag(armature)) q̈ = τ − friction − h − JᵀF_tip by the sparse LᵀDL
//! factorisation (the articulated-body algorithm would need the payload in
//! its articulated inertias).
//!
//! **Forward dynamics.** Without input payloads and with
//! [`ForwardDynamicsMethod::Auto`] (the default), both the articulated-body
//! algorithm and CRBA + LᵀDL are traced and one is kept by the rule of a
//! plain module ([`fd_choice`](super::fd_choice)): LᵀDL where it is
//! estimated faster and as accurate. The header says which and why.

use super::emit::{self, Dim, Param, Shape};
use super::trace::{ldlt_forward_dynamics, sin_cos_from_q, sin_cos_inputs, LdltSteps, SinCosTrace};
use super::{
    fd_choice, module_name, parse_item, prepare_model, sin_cos, trig_source, wrapper, CodegenError, CodegenOptions,
    ForwardDynamicsMethod, GeneratedModule, ScalarType, SnappedConstant, Trig, GENERATOR_VERSION,
};
use crate::algorithms::{kinematics, rnea, BodyInertia, Loads, TipWrench, Workspace};
use crate::model::{JointKind, Model};
use crate::scene::{dynamics, Function as SceneFn, ResolvedGravity, SceneModel};
use crate::spatial::{Force, Inertia, Sym3, Transform, Vec3};
use crate::symbolic::{factor, Expr, Function, OpCount, Rewrites, TraceActive, Tracer};
use quote::quote;
use std::fmt::Write;

/// One function of a scene module.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneFunction {
    /// What the scene asked for.
    pub function: SceneFn,
    /// Its name in the module (`frame_pose_ee_link` for a frame function).
    pub name: String,
    /// Its arguments in order, with their lengths (the `_sc` variant takes
    /// `s` and `c` instead of `q`, and `q` too if a joint is prismatic).
    pub inputs: Vec<(String, usize)>,
    /// The traced, dead-code-eliminated function (evaluate it with
    /// [`Function::eval`], inputs by the names of [`inputs`](Self::inputs)).
    pub traced: Function,
    /// The same with the sines and cosines as inputs: the body of `NAME_sc`.
    pub sin_cos_inputs: SinCosTrace,
    /// Its operation count.
    pub op_count: OpCount,
}

/// The run-time arguments of a scene function after the contract's.
struct Extras {
    gravity: bool,
    tip: bool,
    payloads: bool,
}

fn extras(f: &SceneFn) -> Extras {
    let (gravity, tip, payloads) = match f {
        SceneFn::InverseDynamics | SceneFn::ForwardDynamics => (true, true, true),
        SceneFn::BiasForces | SceneFn::GravityTorques => (true, false, true),
        SceneFn::MassMatrix | SceneFn::Coriolis => (false, false, true),
        SceneFn::FramePose(_) | SceneFn::FrameJacobian(_) => (false, false, false),
    };
    Extras { gravity, tip, payloads }
}

/// The contract's vector arguments of a scene function.
fn vectors(f: &SceneFn) -> &'static [&'static str] {
    match f {
        SceneFn::InverseDynamics => &["q", "qd", "qdd"],
        SceneFn::BiasForces | SceneFn::Coriolis => &["q", "qd"],
        SceneFn::ForwardDynamics => &["q", "qd", "tau"],
        _ => &["q"],
    }
}

/// The name of a payload's argument.
pub fn payload_argument(link: &str) -> String {
    format!("payload_{}", module_name(link).trim_start_matches('_'))
}

/// The Rust name of a scene function.
pub fn scene_function_name(f: &SceneFn) -> String {
    match f {
        SceneFn::FramePose(frame) => format!("frame_pose_{}", module_name(frame).trim_start_matches('_')),
        SceneFn::FrameJacobian(frame) => format!("frame_jacobian_{}", module_name(frame).trim_start_matches('_')),
        f => f.name().to_string(),
    }
}

/// The arguments of `f` in `scene`, with their lengths.
fn params(scene: &SceneModel, f: &SceneFn) -> Vec<Param> {
    let mut p: Vec<Param> = vectors(f).iter().map(|v| Param::dof(v)).collect();
    let x = extras(f);
    if x.gravity && scene.gravity == ResolvedGravity::Input {
        p.push(Param::fixed("gravity", 3));
    }
    if x.tip && scene.tip_wrench_frame.is_some() {
        p.push(Param::fixed("f_tip", 6));
    }
    if x.payloads {
        for pl in &scene.input_payloads {
            p.push(Param::fixed(&payload_argument(&pl.link), 10));
        }
    }
    p
}

fn shape(f: &SceneFn) -> Shape {
    match f {
        SceneFn::MassMatrix => Shape::Matrix(Dim::Dof, Dim::Dof),
        SceneFn::FramePose(_) => Shape::Matrix(Dim::Fixed(4), Dim::Fixed(4)),
        SceneFn::FrameJacobian(_) => Shape::Matrix(Dim::Fixed(6), Dim::Dof),
        _ => Shape::Vector(Dim::Dof),
    }
}

/// Traces `f` of `scene` (with `model`, the snapped reduced model) without
/// factoring.
fn trace_unfactored(
    scene: &SceneModel,
    model: &Model,
    f: &SceneFn,
    method: ForwardDynamicsMethod,
    rewrites: Rewrites,
) -> Result<Function, TraceActive> {
    let n = model.dof();
    // M by the codegen variant of CRBA, as the plain module's (planned
    // before this trace starts), in the mass matrix and in the LᵀDL forward
    // dynamics (always taken with input payloads: ABA has no payload form).
    let use_ldlt =
        f == &SceneFn::ForwardDynamics && (method == ForwardDynamicsMethod::Ldlt || !scene.input_payloads.is_empty());
    let plan = match f {
        SceneFn::MassMatrix => Some(super::mass_matrix::plan(model, rewrites)?),
        _ if use_ldlt => Some(super::mass_matrix::plan(model, rewrites)?),
        _ => None,
    };
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> = vectors(f).iter().map(|name| tracer.inputs(name, n)).collect();
    let x = extras(f);
    let gravity: Option<Vec3<Expr>> = match scene.gravity {
        _ if !x.gravity => None,
        ResolvedGravity::None => None,
        ResolvedGravity::Constant(_) => Some(Vec3::from_f64(&model.gravity)),
        ResolvedGravity::Input => {
            let g = tracer.inputs("gravity", 3);
            Some(Vec3([g[0], g[1], g[2]]))
        }
    };
    let tips: Vec<TipWrench<Expr>> = match scene.tip_wrench_frame {
        Some(frame) if x.tip => {
            let w = tracer.inputs("f_tip", 6);
            vec![TipWrench { frame, wrench: Force::from_array([w[0], w[1], w[2], w[3], w[4], w[5]]) }]
        }
        _ => Vec::new(),
    };
    let mut payloads = Vec::new();
    if x.payloads {
        for p in &scene.input_payloads {
            let v = tracer.inputs(&payload_argument(&p.link), 10);
            if model.frames[p.frame].body.is_none() {
                continue; // on the base: moves nothing
            }
            let inertia = Inertia::from_mass_com_inertia(
                v[0],
                Vec3([v[1], v[2], v[3]]),
                Sym3([v[4], v[5], v[6], v[7], v[8], v[9]]),
            );
            // In the frame of the link's body (frames move with the bodies
            // the regrouping slides, so this is exact in the snapped model).
            let place = Transform::<Expr>::from_f64(&model.frames[p.frame].placement);
            payloads.push(BodyInertia {
                body: model.frames[p.frame].body.expect("checked above"),
                inertia: place.inertia_to_parent(&inertia),
            });
        }
    }
    let mut s = scene.clone();
    s.model = model.clone();
    let scene = &s;
    let mut ws = Workspace::<Expr>::new(model);
    let zero = tracer.constant(0.0);
    let g = gravity.as_ref();
    let out_len = match shape(f) {
        Shape::Vector(_) => n,
        Shape::Matrix(Dim::Fixed(4), _) => 16,
        Shape::Matrix(Dim::Fixed(6), _) => 6 * n,
        Shape::Matrix(..) => n * n,
    };
    let mut out = vec![zero; out_len];
    let p = !payloads.is_empty();
    // The input payloads enter the recursions as extra body inertias
    // (rnea_with_payloads, and in M codegen/mass_matrix.rs as crba_with_payloads
    // does): the same dynamics as
    // SceneRobot's, which adds their values to the model's inertias.
    let (q, pl) = (&args[0], &payloads[..]);
    match f {
        SceneFn::InverseDynamics => {
            dynamics::inverse_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, &tips, pl), &mut out);
        }
        SceneFn::MassMatrix => {
            let plan = plan.as_ref().expect("planned above");
            super::mass_matrix::mass_matrix(model, &mut ws, q, pl, plan, &mut out);
            dynamics::add_armature_diagonal(scene, &mut out);
        }
        SceneFn::BiasForces if p => {
            rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(g, &[], pl), &mut out);
            dynamics::add_friction(scene, &args[1], &mut out);
        }
        SceneFn::BiasForces => dynamics::bias_forces(scene, &mut ws, q, &args[1], g, &mut out),
        SceneFn::GravityTorques if p && g.is_some() => {
            rnea::rnea(model, &mut ws, q, None, None, Loads::new(g, &[], pl), &mut out);
        }
        SceneFn::GravityTorques => dynamics::gravity_torques(scene, &mut ws, q, g, &mut out),
        SceneFn::Coriolis if p => {
            rnea::rnea(model, &mut ws, q, Some(&args[1]), None, Loads::new(None, &[], pl), &mut out);
        }
        SceneFn::Coriolis => dynamics::coriolis(scene, &mut ws, q, &args[1], &mut out),
        SceneFn::ForwardDynamics if use_ldlt => {
            // As the plain module's LᵀDL, on τ − friction, with the armature on M's diagonal.
            let plan = plan.as_ref().expect("planned above");
            let mut rhs = args[2].clone();
            dynamics::sub_friction(scene, &args[1], &mut rhs);
            let steps = LdltSteps { gravity: g, tips: &tips, payloads: pl, plan };
            let armature = |m: &mut [Expr]| dynamics::add_armature_diagonal(scene, m);
            ldlt_forward_dynamics(model, &mut ws, q, &args[1], &rhs, &steps, armature, &mut out);
        }
        SceneFn::ForwardDynamics => {
            dynamics::forward_dynamics(scene, &mut ws, q, &args[1], &args[2], Loads::new(g, &tips, &[]), &mut out)
        }
        SceneFn::FramePose(name) | SceneFn::FrameJacobian(name) => {
            let frame = model.frame_index(name).expect("checked by Scene::apply");
            kinematics::forward_kinematics(model, &mut ws, &args[0]);
            if matches!(f, SceneFn::FramePose(_)) {
                let t = kinematics::frame_pose(model, &ws, frame).to_homogeneous();
                for (o, x) in out.iter_mut().zip(t.iter().flatten()) {
                    *o = *x;
                }
            } else {
                kinematics::body_jacobian(model, &ws, frame, &mut out);
            }
        }
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(Function::new(&scene_function_name(f), &graph, &out))
}

/// Traces `f` of `scene` as the generated module computes it, factored (no
/// rounding snap; [`generate_scene`] snaps the model first when asked).
pub fn trace_scene(scene: &SceneModel, f: &SceneFn, rewrites: Rewrites) -> Result<Function, TraceActive> {
    let t = trace_unfactored(scene, &scene.model, f, ForwardDynamicsMethod::Aba, rewrites)?;
    Ok(factor(&t, rewrites))
}

fn doc_of(scene: &SceneModel, f: &SceneFn, count: &OpCount) -> String {
    let what = match f {
        SceneFn::InverseDynamics => {
            "Inverse dynamics τ = (M(q) + diag(armature))q̈ + C(q, q̇)q̇ + g(q) + friction + J(q)ᵀF_tip, by the recursive Newton-Euler algorithm.".to_string()
        }
        SceneFn::MassMatrix => {
            "The mass matrix M(q) + diag(armature) by the composite-rigid-body algorithm (symmetric, `[row][col]`).".to_string()
        }
        SceneFn::BiasForces => "The bias forces h(q, q̇) = C(q, q̇)q̇ + g(q) + friction.".to_string(),
        SceneFn::GravityTorques => "The gravity torques g(q).".to_string(),
        SceneFn::Coriolis => "The Coriolis and centripetal torques C(q, q̇)q̇.".to_string(),
        SceneFn::ForwardDynamics => {
            "Forward dynamics q̈ = (M(q) + diag(armature))⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip).".to_string()
        }
        SceneFn::FramePose(frame) => {
            format!("The pose of frame `{frame}` in the base frame, as a homogeneous matrix `[row][col]`.")
        }
        SceneFn::FrameJacobian(frame) => format!(
            "The body Jacobian of frame `{frame}` (6 × DOF, rows (ω; v), in the frame): its twist is `J q̇`, and `Jᵀ F` is the joint torque of a wrench `F` given in the frame."
        ),
    };
    let mut args = String::new();
    for p in params(scene, f) {
        let what = match p.name.as_str() {
            "gravity" => "`gravity`: m/s², in the base frame.".to_string(),
            "f_tip" => {
                let frame = scene.tip_wrench_frame.map(|i| scene.model.frames[i].name.as_str()).unwrap_or("");
                format!("`f_tip`: the wrench (m; f) frame `{frame}` applies to its environment, in that frame (N·m; N).")
            }
            name if name.starts_with("payload_") => format!(
                "`{name}`: [mass, cx, cy, cz, ixx, iyy, izz, ixy, ixz, iyz], kg, m and kg·m² about the centre of mass, in the link's frame."
            ),
            _ => continue,
        };
        let _ = write!(args, "\n {what}");
    }
    format!(" {what}\n\n Joint order: [`JOINT_NAMES`]; rad, m, s, N·m, N.{args}\n {count}.")
}

/// Generates the module of an applied scene: only the functions it asks
/// for, everything it fixes folded in, its run-time inputs as arguments (see
/// [`crate::scene`] for the options, and the comments of `codegen/scene.rs`). From `options`: the rounding snap,
/// the rewrites, the source for the header, the forward-dynamics method
/// (without input payloads), and the trigonometry when the scene's target
/// is std. The scalar is `f32` if the scene or `options` ask for it; a
/// no_std target sets the trigonometry (libm, or the sines and cosines as
/// inputs).
///
/// ```
/// use dynagen::codegen::{generate_scene, CodegenOptions};
/// use dynagen::scene::{Function, Gravity, Scene};
/// let ur5 = dynagen::Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap();
/// let scene = Scene::new().functions([Function::InverseDynamics]).gravity(Gravity::None).tip_wrench("ee_link");
/// let module = generate_scene(&scene.apply(&ur5).unwrap(), &CodegenOptions::default()).unwrap();
/// assert!(module.source.contains("f_tip: &[f64; 6]"));
/// assert!(!module.source.contains("fn mass_matrix"));
/// assert!(module.source.contains("//   functions not generated: mass_matrix, bias_forces"));
/// ```
pub fn generate_scene(scene: &SceneModel, options: &CodegenOptions) -> Result<GeneratedModule, CodegenError> {
    // As `generate` (the regrouping is exact for every function of a scene:
    // frames move with the slid bodies; armature, friction and run-time
    // payloads do not depend on the bodies' own inertias).
    let (model, snapped) = prepare_model(&scene.model, options);
    let n = model.dof();
    let scalar = if scene.scalar == ScalarType::F32 { ScalarType::F32 } else { options.scalar };
    let trig = Trig::for_target(scene.target, options.trig);
    let mut names = std::collections::HashSet::new();
    for f in &scene.functions {
        let name = scene_function_name(f);
        if !names.insert(name.clone()) {
            return Err(CodegenError::DuplicateName(name));
        }
    }
    let mut items: Vec<syn::Item> = Vec::new();
    let joint_names = model.joint_names();
    let n_lit = proc_macro2::Literal::usize_unsuffixed(n);
    let consts = quote! {
        #[doc = " The number of degrees of freedom (joints)."]
        pub const DOF: usize = #n_lit;
        #[doc = " The joint names, in the order of every index of the functions below."]
        pub const JOINT_NAMES: [&str; DOF] = [#(#joint_names),*];
    };
    let consts: syn::File = syn::parse2(consts).map_err(|e| CodegenError::Internal(e.to_string()))?;
    items.extend(consts.items);
    items.push(parse_item(sin_cos::sin_cos_all_item(scalar))?);
    let has_prismatic = model.bodies.iter().any(|b| b.joint.kind == JointKind::Prismatic);
    let mut functions = Vec::new();
    let mut split_functions = Vec::new();
    let mut fd_why = String::new();
    for f in &scene.functions {
        let name = scene_function_name(f);
        let ps = params(scene, f);
        let traced_as = |method| -> Result<(SinCosTrace, Function), CodegenError> {
            let traced = trace_unfactored(scene, &model, f, method, options.rewrites)?;
            let sc = sin_cos_inputs(&traced, n, options.rewrites).map_err(CodegenError::Internal)?;
            let function = sin_cos_from_q(&sc, options.rewrites);
            Ok((sc, function))
        };
        let (sc, function) = match options.forward_dynamics {
            // Both traced and compared, as for a plain module (fd_choice.rs);
            // with input payloads only LᵀDL exists.
            ForwardDynamicsMethod::Auto if f == &SceneFn::ForwardDynamics && scene.input_payloads.is_empty() => {
                let aba = traced_as(ForwardDynamicsMethod::Aba)?;
                let ldlt = traced_as(ForwardDynamicsMethod::Ldlt)?;
                let inputs: Vec<(String, usize)> = ps.iter().map(|p| (p.name.clone(), p.len_value(n))).collect();
                let choice = fd_choice::choose_between([&aba.1, &aba.0.function], [&ldlt.1, &ldlt.0.function], &inputs);
                fd_why = choice.why;
                if choice.method == ForwardDynamicsMethod::Ldlt {
                    ldlt
                } else {
                    aba
                }
            }
            method => traced_as(method)?,
        };
        let op_count = super::counted(&function, options.fma);
        let inputs = ps.iter().map(|p| (p.name.clone(), p.len_value(n))).collect();
        functions.push(SceneFunction {
            function: f.clone(),
            name,
            inputs,
            traced: function,
            sin_cos_inputs: sc,
            op_count,
        });
    }
    // Large modules keep the build's target features only, as plain ones (DISPATCH_MAX_OPS).
    let emitted_ops = functions.iter().map(|f| f.op_count.total()).sum();
    let (effective, dropped_note) = super::within_dispatch_limit(options, emitted_ops);
    let options = &effective;
    let opts = CodegenOptions { scalar, trig, ..options.clone() };
    for sf in &functions {
        let (f, name, sc, op_count) = (&sf.function, &sf.name, &sf.sin_cos_inputs, sf.op_count);
        let ps = params(scene, f);
        let mut sc_params = vec![Param::dof("s"), Param::dof("c")];
        if has_prismatic {
            sc_params.push(Param::dof("q"));
        }
        sc_params.extend(ps[1..].iter().cloned());
        let sc_name = format!("{name}_sc");
        let signature = emit::Signature { name: sc_name.clone(), params: sc_params, output: shape(f) };
        let sc_count = super::counted(&sc.function, options.fma);
        let doc = format!("{}\n\n{}", doc_of(scene, f, &sc_count), super::sc_doc(has_prismatic));
        let style = emit::BodyStyle::of(options);
        let emitted = emit::emit_function(&sc.function, &signature, scalar, trig, n, &doc, style)?;
        let sc_split = super::split::parts_of(&emitted);
        if let Some(parts) = sc_split {
            split_functions.push((sc_name.clone(), parts));
        }
        items.extend(emitted);
        if trig != Trig::Inputs {
            let doc = format!(
                "{}\n\n The sines and cosines of the joint angles by {}, then [`{sc_name}`].",
                doc_of(scene, f, &op_count),
                trig_source(trig, scalar)
            );
            let ret = shape(f).tokens(scalar);
            let body = super::ScBody { trace: sc, has_prismatic, split: sc_split.is_some() };
            items.extend(super::parse_items(wrapper(name, &ps, ret, body, &opts, &doc))?);
        }
    }
    let file = syn::File { shebang: None, frontmatter: None, attrs: vec![], items };
    let body = emit::tidy_dispatch(&prettyplease::unparse(&file));
    let model_hash = super::model_hash(&scene.model);
    let mut header = header(scene, &opts, &fd_why, &functions, &snapped, model_hash)
        + &super::split::header_note(options.split_lets, &split_functions);
    header.push_str(&dropped_note);
    let kernel = sin_cos::kernel_source(scalar, options.runtime_dispatch);
    Ok(GeneratedModule {
        source: format!("{header}\n{body}\n{kernel}"),
        functions: Vec::new(),
        scene_functions: functions,
        snapped,
        model_hash,
    })
}

fn list(items: &[String]) -> String {
    if items.is_empty() {
        "none".to_string()
    } else {
        items.join(", ")
    }
}

fn header(
    scene: &SceneModel,
    options: &CodegenOptions,
    fd_why: &str,
    functions: &[SceneFunction],
    snapped: &[SnappedConstant],
    hash: u64,
) -> String {
    let model = &scene.model;
    let mut h = String::new();
    let scene_name = scene.name.as_deref().map(|s| format!(" in the scene \"{s}\"")).unwrap_or_default();
    let _ = writeln!(
        h,
        "// Dynamics of the robot \"{}\"{scene_name} ({} joints), generated by dynagen {GENERATOR_VERSION}.",
        model.name,
        model.dof()
    );
    let _ = writeln!(h, "// Do not edit: regenerate from the model and the scene instead.");
    let _ = writeln!(h, "//");
    let source = options.source.as_deref().unwrap_or("(not given)");
    let _ = writeln!(h, "// Model source: {source}");
    let _ = writeln!(h, "// Reduced model content hash (FNV-1a 64 of its canonical text): {hash:016x}");
    let scalar = match options.scalar {
        ScalarType::F64 => "f64",
        ScalarType::F32 => "f32",
    };
    let _ = writeln!(
        h,
        "// Options: scalar {scalar}; rounding snap {} ({} constants); trigonometry: {}.",
        if options.snap_rounding { "on" } else { "off" },
        snapped.len(),
        match options.trig {
            Trig::Std => "std's sin_cos",
            Trig::Batched => "sin_cos_all (no_std)",
            Trig::Libm => "libm (no_std)",
            Trig::Inputs => "only NAME_sc(s, c, ...), the caller passes the sines and cosines (no_std)",
        }
    );
    h.push_str(&super::fma_note(options));
    if scene.functions.contains(&SceneFn::ForwardDynamics) {
        let fd = if !scene.input_payloads.is_empty() {
            "CRBA with the input payloads' inertias and the armature on M's diagonal, RNEA, and a sparse LTDL solve"
        } else if !fd_why.is_empty() {
            fd_why
        } else if options.forward_dynamics == ForwardDynamicsMethod::Ldlt {
            "CRBA with the armature on M's diagonal, RNEA, and a sparse LTDL solve, as asked"
        } else {
            "the articulated-body algorithm, armature in D_i = S_i^T U_i + a_i, as asked"
        };
        let _ = writeln!(h, "// Forward dynamics: {fd}.");
    }
    // What the scene left out.
    let _ = writeln!(h, "//");
    let _ = writeln!(h, "// Left out by the scene:");
    let all = [
        SceneFn::InverseDynamics,
        SceneFn::MassMatrix,
        SceneFn::BiasForces,
        SceneFn::GravityTorques,
        SceneFn::Coriolis,
        SceneFn::ForwardDynamics,
    ];
    let not_emitted: Vec<String> =
        all.iter().filter(|f| !scene.functions.contains(f)).map(|f| f.name().to_string()).collect();
    let _ = writeln!(h, "//   functions not generated: {}", list(&not_emitted));
    if scene.gravity == ResolvedGravity::None {
        let _ = writeln!(h, "//   gravity: none (every gravity term is gone; g(q) = 0)");
    }
    if scene.tip_wrench_frame.is_none() {
        let _ = writeln!(h, "//   tip wrench: none (no J^T F_tip term)");
    }
    let locked: Vec<String> = scene
        .fixed_joints
        .iter()
        .filter(|(j, _)| scene.scene.locks.iter().any(|(l, _)| l == j))
        .map(|(j, q)| format!("{j} at {q}"))
        .collect();
    let merged: Vec<String> = scene
        .fixed_joints
        .iter()
        .filter(|(j, _)| !scene.scene.locks.iter().any(|(l, _)| l == j))
        .map(|(j, q)| format!("{j} at {q}"))
        .collect();
    let _ = writeln!(h, "//   locked joints (fixed, folded): {}", list(&locked));
    let _ = writeln!(h, "//   joints merged rigidly below a sub-tree tip: {}", list(&merged));
    let _ = writeln!(h, "//   joints removed (above the root or off the sub-tree): {}", list(&scene.removed_joints));
    let _ = writeln!(h, "//   bodies dropped: {}", list(&scene.dropped_links));
    // What it folded in.
    let names = scene.joint_names();
    let per_joint = |v: &[f64]| -> Vec<String> {
        v.iter().zip(&names).filter(|(x, _)| **x != 0.0).map(|(x, j)| format!("{j} {x}")).collect()
    };
    let _ = writeln!(h, "// Folded in:");
    if let ResolvedGravity::Constant(_) = scene.gravity {
        let _ = writeln!(h, "//   gravity: {:?} m/s^2 in the base frame", model.gravity.0);
    }
    let _ = writeln!(h, "//   armature: {}", list(&per_joint(&scene.armature)));
    let _ = writeln!(h, "//   viscous friction: {}", list(&per_joint(&scene.viscous_friction)));
    let coulomb = per_joint(&scene.coulomb_friction);
    let _ = writeln!(
        h,
        "//   Coulomb friction: {}{}",
        list(&coulomb),
        if coulomb.is_empty() { String::new() } else { format!(" (smoothed, v_eps = {})", scene.coulomb_velocity) }
    );
    let constant_payloads: Vec<String> = scene
        .scene
        .payloads
        .iter()
        .filter_map(|p| match &p.value {
            crate::scene::PayloadValue::Constant(c) => Some(format!("{} ({} kg)", p.link, c.mass)),
            crate::scene::PayloadValue::Input => None,
        })
        .collect();
    let _ = writeln!(h, "//   constant payloads: {}", list(&constant_payloads));
    let mut inputs = Vec::new();
    if scene.gravity == ResolvedGravity::Input {
        inputs.push("gravity: &[T; 3] (m/s^2, base frame)".to_string());
    }
    if let Some(i) = scene.tip_wrench_frame {
        inputs.push(format!("f_tip: &[T; 6] (m; f) at frame \"{}\", in that frame", model.frames[i].name));
    }
    for p in &scene.input_payloads {
        inputs.push(format!(
            "{}: &[T; 10] = [mass, com xyz, ixx iyy izz ixy ixz iyz] on \"{}\"",
            payload_argument(&p.link),
            p.link
        ));
    }
    let _ = writeln!(h, "// Run-time inputs: {}", list(&inputs));
    let _ = writeln!(h, "// Operation counts:");
    for f in functions {
        let _ = writeln!(h, "//   {}: {}", f.name, f.op_count);
    }
    if let Ok(toml) = scene.scene.to_toml_string() {
        let _ = writeln!(h, "//");
        let _ = writeln!(h, "// The scene:");
        for line in toml.lines() {
            let _ = writeln!(h, "//   {line}");
        }
        h = h.replace("//   \n", "//\n");
    }
    h
}
