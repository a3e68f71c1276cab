//! Scene modules ([`generate_scene`]) against the generic solver under the
//! same scene ([`SceneRobot`]): every function of every option, evaluated by
//! the graph interpreter on random states (what the emitted code computes,
//! `tests/tests/generated_scene.rs` compiles two of them), and the
//! operation count of each option against the full scene's.

mod support;

use dynagen::codegen::{generate_scene, CodegenError, CodegenOptions, Function, GeneratedModule, ScalarType, Trig};
use dynagen::scene::{
    Gravity, PayloadInertia, ResolvedGravity, Scene, SceneError, SceneFile, SceneInputs, SceneModel, SceneRobot,
};
use dynagen::Model;
use nalgebra::{DVector, Vector3, Vector6};
use std::sync::OnceLock;
use support::{norm_rel_err, Rng};

/// A physical payload: mass in [0.5, 1.5] kg, centre of mass within
/// 10 cm, a positive diagonal inertia with a small product.
fn payload(rng: &mut Rng) -> PayloadInertia {
    let d = [2e-3 + 2e-4 * rng.signed(), 2e-3 + 2e-4 * rng.signed(), 1.5e-3 + 2e-4 * rng.signed()];
    PayloadInertia::new(
        1.0 + 0.5 * rng.signed(),
        [0.1 * rng.signed(), 0.1 * rng.signed(), 0.1 * rng.signed()],
        [d[0], d[1], d[2], 1e-5 * rng.signed(), 0.0, 0.0],
    )
}

/// Row-major entries of an nalgebra matrix.
fn rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Vec<f64> {
    (0..m.nrows()).flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)])).collect()
}

/// Generates `scene` for `model` with the full options ([`full_options`]),
/// and checks every traced function (both forward dynamics where both were
/// traced) against [`SceneRobot`] on `states` random states (f64 graph
/// evaluation within `tol`, or f32 evaluation within `tol` when the options
/// are f32).
fn check(model: &Model, scene: &Scene, states: usize, tol: f64) -> (SceneModel, GeneratedModule) {
    check_with(model, scene, &full_options(), states, tol)
}

/// [`check`] with `options`.
fn check_with(
    model: &Model,
    scene: &Scene,
    options: &CodegenOptions,
    states: usize,
    tol: f64,
) -> (SceneModel, GeneratedModule) {
    let applied = scene.apply(model).unwrap();
    let module = generate_scene(&applied, options).unwrap();
    let mut robot = SceneRobot::new(applied.clone());
    // n joints, or a floating base's NQ-long q (a unit quaternion) and NV-long rest
    let (nq, nv) = (applied.model.nq(), applied.model.nv());
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let f32 = options.scalar == ScalarType::F32;
    for _ in 0..states {
        let (mut q, qd, qdd, tau) = (rng.vec(nq, 3.0), rng.vec(nv, 2.0), rng.vec(nv, 5.0), rng.vec(nv, 20.0));
        if applied.model.is_floating() {
            support::normalize_quaternion(&mut q);
        }
        let gravity = [rng.signed(), rng.signed(), -9.81 + rng.signed()];
        let f_tip = rng.vec(6, 10.0);
        let payloads: Vec<PayloadInertia> = applied.input_payloads.iter().map(|_| payload(&mut rng)).collect();
        let mut named: Vec<(String, Vec<f64>)> = vec![
            ("q".into(), q.clone()),
            ("qd".into(), qd.clone()),
            ("qdd".into(), qdd.clone()),
            ("tau".into(), tau.clone()),
            ("gravity".into(), gravity.to_vec()),
            ("f_tip".into(), f_tip.clone()),
        ];
        for (p, v) in applied.input_payloads.iter().zip(&payloads) {
            let mut x = vec![v.mass];
            x.extend(v.com);
            x.extend(v.inertia);
            named.push((dynagen::codegen::payload_argument(&p.link), x));
        }
        let inputs: Vec<(&str, &[f64])> = named.iter().map(|(k, v)| (k.as_str(), v.as_slice())).collect();
        let scene_inputs = SceneInputs {
            gravity: (applied.gravity == ResolvedGravity::Input).then(|| Vector3::from(gravity)),
            tip_wrench: applied.tip_wrench_frame.map(|_| Vector6::from_column_slice(&f_tip)),
            payloads: &payloads,
        };
        let dv = |v: &Vec<f64>| DVector::from_column_slice(v);
        for f in &module.functions {
            let got: Vec<f64> = if f32 {
                f.traced.eval_as::<f32>(&inputs).unwrap().into_iter().map(f64::from).collect()
            } else {
                f.traced.eval(&inputs).unwrap()
            };
            let i = &scene_inputs;
            let want: Vec<f64> = match &f.function {
                Function::InverseDynamics => {
                    robot.inverse_dynamics_with(&dv(&q), &dv(&qd), &dv(&qdd), i).unwrap().as_slice().to_vec()
                }
                Function::MassMatrix => rows(&robot.mass_matrix_with(&dv(&q), i).unwrap()),
                Function::BiasForces => robot.bias_forces_with(&dv(&q), &dv(&qd), i).unwrap().as_slice().to_vec(),
                Function::GravityTorques => robot.gravity_torques_with(&dv(&q), i).unwrap().as_slice().to_vec(),
                Function::Coriolis => robot.coriolis_with(&dv(&q), &dv(&qd), i).unwrap().as_slice().to_vec(),
                Function::ForwardDynamics => {
                    robot.forward_dynamics_with(&dv(&q), &dv(&qd), &dv(&tau), i).unwrap().as_slice().to_vec()
                }
                Function::InverseDynamicsDerivatives => {
                    let (a, b) = robot.inverse_dynamics_derivatives_with(&dv(&q), &dv(&qd), &dv(&qdd), i).unwrap();
                    [rows(&a), rows(&b)].concat()
                }
                Function::ForwardDynamicsDerivatives => {
                    let (a, b, c) = robot.forward_dynamics_derivatives_with(&dv(&q), &dv(&qd), &dv(&tau), i).unwrap();
                    [rows(&a), rows(&b), rows(&c)].concat()
                }
                Function::MassMatrixInverse => rows(&robot.mass_matrix_inverse_with(&dv(&q), i).unwrap()),
                Function::FramePose(frame) => rows(&robot.frame_pose(frame, &dv(&q)).unwrap()),
                Function::FrameJacobian(frame) => rows(&robot.frame_jacobian(frame, &dv(&q)).unwrap()),
                Function::FrameWorldJacobian(frame) => rows(&robot.frame_world_jacobian(frame, &dv(&q)).unwrap()),
                Function::FrameAccelerationBias(frame) => {
                    robot.frame_acceleration_bias(frame, &dv(&q), &dv(&qd)).unwrap().as_slice().to_vec()
                }
            };
            assert_eq!(got.len(), want.len(), "{}", f.label());
            let e = norm_rel_err(&got, &want, 1e-300);
            // g(q) = 0 without gravity: compare absolutely.
            let e = if want.iter().all(|x| *x == 0.0) { got.iter().fold(0.0f64, |m, x| m.max(x.abs())) } else { e };
            assert!(e < tol, "{}: relative error {e:e}\n got {got:?}\nwant {want:?}", f.label());
        }
    }
    (applied, module)
}

fn ops(module: &GeneratedModule, name: &str) -> usize {
    module.function(name).unwrap_or_else(|| panic!("no function {name}")).op_count.total()
}

/// The full scene: the whole robot, with the full options.
fn full_scene() -> Scene {
    Scene::new()
}

/// The full options: the five functions plus coriolis and the
/// end-effector's pose and Jacobian.
fn full_options() -> CodegenOptions {
    CodegenOptions::default()
        .function(Function::Coriolis)
        .function(Function::FramePose("ee_link".into()))
        .function(Function::FrameJacobian("ee_link".into()))
}

/// The sum of the operation counts of the functions `module` emits.
fn emitted_total(module: &GeneratedModule) -> usize {
    module.functions.iter().filter(|f| f.emitted).map(|f| f.op_count.total()).sum()
}

/// [`full_options`] with the code keys of a scene file whose text is
/// `toml` applied (`target = ...`, `scalar = ...`).
fn with_keys(toml: &str) -> CodegenOptions {
    SceneFile::from_toml_str(toml).unwrap().code.apply(full_options())
}

/// The full scene's module, generated once and checked against SceneRobot.
fn full() -> &'static GeneratedModule {
    static FULL: OnceLock<GeneratedModule> = OnceLock::new();
    FULL.get_or_init(|| check(&support::model("ur5"), &full_scene(), 5, 1e-12).1)
}

const ALL: [&str; 8] = [
    "inverse_dynamics",
    "mass_matrix",
    "bias_forces",
    "gravity_torques",
    "coriolis",
    "forward_dynamics",
    "frame_pose_ee_link",
    "frame_jacobian_ee_link",
];

/// Each function's count minus the full scene's, printed for the report.
fn deltas(label: &str, module: &GeneratedModule) -> Vec<(&'static str, i64)> {
    let d: Vec<(&str, i64)> = ALL
        .iter()
        .filter(|f| module.function(f).is_some())
        .map(|f| (*f, ops(module, f) as i64 - ops(full(), f) as i64))
        .collect();
    let text: Vec<String> = d.iter().map(|(f, x)| format!("{f} {} ({x:+})", ops(module, f))).collect();
    println!("UR5 {label}: {}", text.join(", "));
    d
}

fn delta(d: &[(&str, i64)], f: &str) -> i64 {
    d.iter().find(|(g, _)| *g == f).unwrap_or_else(|| panic!("{f} not generated")).1
}

#[test]
fn the_full_scene_is_the_plain_module() {
    // The full scene's contract functions count what generate(&Model) does:
    // the scene path adds nothing when the scene asks for nothing.
    // The forward dynamics is chosen between ABA and CRBA + LᵀDL as the
    // plain module's is (the UR5 gets LᵀDL, with the same sentence why).
    let plain = dynagen::codegen::generate(&support::model("ur5"), &CodegenOptions::default()).unwrap();
    for name in ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"] {
        let p = plain.function(name).unwrap();
        let s = full().function(name).unwrap();
        assert_eq!((s.op_count, s.method), (p.op_count, p.method), "{name}");
    }
    // Both forward dynamics are traced and counted in both, one emitted.
    for m in [&plain, full()] {
        let fd: Vec<_> = m.functions.iter().filter(|f| f.function == Function::ForwardDynamics).collect();
        assert_eq!(fd.len(), 2);
        assert_eq!(fd.iter().filter(|f| f.emitted).count(), 1);
    }
    let why = |source: &str| source.lines().find(|l| l.starts_with("// Forward dynamics: ")).map(str::to_string);
    assert!(why(&plain.source).unwrap().contains("CRBA + LTDL, chosen as faster and as accurate"));
    // The same choice for the same estimated cycles and the same errors:
    // both modules are traced by one pipeline (codegen/trace/mod.rs). (When
    // scenes were traced by another path, the errors could differ in their
    // last digit: plain 3.8e-16 and scene 3.7e-16 for LᵀDL.)
    assert_eq!(why(&full().source), why(&plain.source));
    assert!(why(&full().source).unwrap().contains("; worst relative error on 16 states against double-double"));
    deltas("full scene", full());
}

#[test]
fn a_function_subset_emits_only_those() {
    let options = CodegenOptions::default().functions([Function::InverseDynamics, Function::Coriolis]);
    let (_, m) = check_with(&support::model("ur5"), &Scene::new(), &options, 5, 1e-12);
    let d = deltas("functions = [inverse_dynamics, coriolis]", &m);
    assert_eq!((delta(&d, "inverse_dynamics"), delta(&d, "coriolis")), (0, 0));
    for f in ["mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics", "frame_pose"] {
        assert!(!m.source.contains(&format!("fn {f}")), "{f} emitted");
    }
    // The default scene with fewer functions: the plain header's list of
    // the contract functions left out (alphabetical).
    assert!(m.source.contains("\n// Left out: bias_forces, forward_dynamics, gravity_torques, mass_matrix.\n"));
    let total = emitted_total(&m);
    let full_total = emitted_total(full());
    assert!(total < full_total / 3, "{total} vs {full_total}");
}

#[test]
fn torque_only_without_gravity_has_fewer_operations_and_no_mass_matrix() {
    let scene = Scene::new().gravity(Gravity::None);
    let options = CodegenOptions::default().functions([Function::InverseDynamics]);
    let (_, m) = check_with(&support::model("ur5"), &scene, &options, 5, 1e-12);
    let d = deltas("tau only, gravity none", &m);
    assert!(delta(&d, "inverse_dynamics") < 0);
    assert!(!m.source.contains("fn mass_matrix") && m.source.contains("pub fn inverse_dynamics("));
    assert!(m.source.contains("//   gravity: none"));
    // A scene other than the default one lists the functions it leaves out
    // in its own section, in the module's order.
    assert!(m.source.contains(
        "\n//   functions not generated: mass_matrix, bias_forces, gravity_torques, coriolis, forward_dynamics\n"
    ));
}

#[test]
fn gravity_none_removes_every_gravity_term() {
    let (_, m) = check(&support::model("ur5"), &full_scene().gravity(Gravity::None), 5, 1e-12);
    let d = deltas("gravity none", &m);
    assert_eq!(ops(&m, "gravity_torques"), 0);
    for f in ["inverse_dynamics", "bias_forces", "forward_dynamics"] {
        assert!(delta(&d, f) < 0, "{f}");
    }
    for f in ["mass_matrix", "coriolis", "frame_pose_ee_link", "frame_jacobian_ee_link"] {
        assert_eq!(delta(&d, f), 0, "{f}");
    }
}

#[test]
fn constant_gravity_is_folded_and_costs_no_more_than_an_input() {
    // The model's own vector given as a constant: the same module.
    let (_, same) =
        check(&support::model("ur5"), &full_scene().gravity(Gravity::Constant([0.0, 0.0, -9.81])), 3, 1e-12);
    assert!(deltas("gravity constant (0, 0, -9.81)", &same).iter().all(|(_, x)| *x == 0));
    // A tilted vector: three components instead of one to propagate.
    let (_, tilted) =
        check(&support::model("ur5"), &full_scene().gravity(Gravity::Constant([1.0, -2.0, -9.0])), 5, 1e-12);
    let dt = deltas("gravity constant (1, -2, -9)", &tilted);
    let (_, input) = check(&support::model("ur5"), &full_scene().gravity(Gravity::Input), 5, 1e-12);
    let di = deltas("gravity input", &input);
    assert!(input.source.contains("gravity: &[f64; 3]"));
    for f in ["inverse_dynamics", "bias_forces", "gravity_torques", "forward_dynamics"] {
        // An input costs what a general direction costs, plus a few
        // products a constant would have folded.
        assert!(delta(&dt, f) > 0 && delta(&di, f) >= delta(&dt, f), "{f}");
        assert!(delta(&di, f) - delta(&dt, f) <= 5, "{f}: input {} vs constant {}", delta(&di, f), delta(&dt, f));
    }
    for f in ["mass_matrix", "coriolis"] {
        assert_eq!((delta(&dt, f), delta(&di, f)), (0, 0), "{f}");
    }
}

#[test]
fn a_tip_wrench_input_costs_less_than_its_jacobian_transpose() {
    let (_, m) = check(&support::model("ur5"), &full_scene().tip_wrench("ee_link"), 5, 1e-12);
    let d = deltas("tip wrench input at ee_link", &m);
    assert!(m.source.contains("f_tip: &[f64; 6]"));
    // What J_bᵀF would cost on its own: the Jacobian plus 6n products and
    // 5n sums.
    let separate = (ops(full(), "frame_jacobian_ee_link") + 11 * 6) as i64;
    for f in ["inverse_dynamics", "forward_dynamics"] {
        assert!(delta(&d, f) > 0 && delta(&d, f) < separate, "{f}: {}", delta(&d, f));
    }
    // h, g and M have no tip wrench.
    for f in ["mass_matrix", "bias_forces", "gravity_torques", "coriolis"] {
        assert_eq!(delta(&d, f), 0, "{f}");
    }
}

#[test]
fn a_subtree_drops_joints_and_operations() {
    let scene = full_scene().subtree("base_link", &["wrist_1_link"]);
    let options = CodegenOptions::default().functions(Function::DEFAULT);
    let (applied, m) = check_with(&support::model("ur5"), &scene, &options, 5, 1e-12);
    assert_eq!(applied.dof(), 4);
    let d = deltas("subtree base_link -> wrist_1_link", &m);
    // g of the regrouped UR5 reads only the shoulder, elbow and wrist-1
    // angles, which the sub-tree keeps: it cannot drop; everything else must.
    assert!(d.iter().all(|(f, x)| *x < 0 || (*f == "gravity_torques" && *x == 0)), "{d:?}");
    assert!(m
        .source
        .contains("//   joints merged rigidly below a sub-tree tip: wrist_2_joint at 0, wrist_3_joint at 0"));
}

#[test]
fn a_locked_joint_folds_and_drops_operations() {
    let (applied, m) = check(
        &support::model("ur5"),
        &full_scene().lock("wrist_3_joint", 0.3).lock("shoulder_pan_joint", -1.0),
        5,
        1e-12,
    );
    assert_eq!(applied.dof(), 4);
    let d = deltas("lock wrist_3_joint, shoulder_pan_joint", &m);
    // g does not depend on either joint (the pan axis is vertical, wrist 3
    // turns a body that regrouping leaves without mass): it stays; everything
    // else must drop.
    assert!(d.iter().all(|(f, x)| *x < 0 || (*f == "gravity_torques" && *x == 0)), "{d:?}");
    assert!(m.source.contains("//   locked joints (fixed, folded): shoulder_pan_joint at -1, wrist_3_joint at 0.3"));
}

#[test]
fn constant_and_input_payloads() {
    let p = PayloadInertia::new(1.2, [0.0, 0.0, 0.06], [0.0018, 0.0018, 0.0012, 0.0, 0.0, 0.0]);
    let (_, constant) = check(&support::model("ur5"), &full_scene().payload("ee_link", p), 5, 1e-12);
    let dc = deltas("constant payload on ee_link", &constant);
    let (_, input) = check(&support::model("ur5"), &full_scene().payload_input("ee_link"), 5, 1e-12);
    let di = deltas("input payload on ee_link", &input);
    assert!(input.source.contains("payload_ee_link: &[f64; 10]"));
    // With a payload input the forward dynamics can only be CRBA + LᵀDL (ABA
    // has no payload form); a constant payload is folded in and both are
    // compared as for a plain module.
    assert!(input.source.contains("// Forward dynamics: CRBA with the input payloads' inertias"));
    assert!(constant.source.contains("chosen as"));
    let n = 6;
    // As an input, the payload is one more inertia on its link's body
    // (`rnea` and `crba` with it in their `Loads`): its ten parameters moved
    // into the body's frame, then m·a + U·h, Ī·ω̇ + ω×(Ī·ω) + h×a in the
    // RNEA, or one more addition to a composite inertia in the CRBA, whose
    // sum has no zero entry left to exploit up the chain. That is less than
    // a second inverse dynamics for τ, h, g and C(q, q̇)q̇, and for M less
    // than J_bᵀ I J_b, which an earlier version used (the frame's Jacobian,
    // I times each column, ≤ 40 operations, and n(n+1)/2 dot products of 11:
    // +753 operations on the UR5; now +197).
    let id = ops(full(), "inverse_dynamics") as i64;
    let bound_m = 40 * n + 11 * n * (n + 1) / 2;
    for f in ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "coriolis", "forward_dynamics"] {
        // Folded, a payload costs the sparsity its body's inertia loses: the
        // regrouping had left the UR5's wrist bodies without mass, and a
        // payload whose centre of mass is off the flange's axis gives the
        // last body mass and first moments again, which every joint then
        // carries (g: 19 → 46). That is bounded by a second full body on
        // the chain, under half of the function (M: +57 on 131 since the
        // mass matrix is planned, codegen/trace/mass_matrix.rs; it was under 2/5
        // of the 171 before).
        let full_ops = ops(full(), f) as i64;
        assert!(delta(&dc, f) > 0 && delta(&dc, f) <= full_ops.max(100) / 2, "{f}: {}", delta(&dc, f));
        assert!(delta(&di, f) > delta(&dc, f), "{f}");
        let bound = match f {
            "mass_matrix" => bound_m,
            "forward_dynamics" => id + bound_m,
            _ => id,
        };
        assert!(delta(&di, f) <= bound, "{f}: {} > {bound}", delta(&di, f));
    }
    for f in ["frame_pose_ee_link", "frame_jacobian_ee_link"] {
        assert_eq!((delta(&dc, f), delta(&di, f)), (0, 0), "{f}");
    }
}

#[test]
fn armature_adds_one_product_and_sum_per_joint() {
    let scene = full_scene().armature("elbow_joint", 0.3).armature("wrist_1_joint", 0.05);
    let (_, m) = check(&support::model("ur5"), &scene, 5, 1e-12);
    let d = deltas("armature on 2 joints", &m);
    // τ: a·q̈ and its sum; M: a on the diagonal.
    assert_eq!(delta(&d, "inverse_dynamics"), 4);
    assert_eq!(delta(&d, "mass_matrix"), 2);
    // ABA: a in D_i (one addition), and the articulated inertia the joint
    // passes to its parent, I − u uᵀ/(d + a), no longer has exact zeros along
    // the joint's axis (it maps S to u·a/(d + a)): its row and column of 6
    // entries and their transform to the parent come back, at most 36
    // operations per joint.
    let fd = delta(&d, "forward_dynamics");
    assert!((2..=2 * 36).contains(&fd), "forward_dynamics: {fd}");
    for f in ["bias_forces", "gravity_torques", "coriolis"] {
        assert_eq!(delta(&d, f), 0, "{f}");
    }
}

#[test]
fn viscous_and_coulomb_friction_cost_what_their_formulas_do() {
    let (_, viscous) = check(&support::model("ur5"), &full_scene().viscous("elbow_joint", 0.8), 5, 1e-12);
    let dv = deltas("viscous friction on 1 joint", &viscous);
    let (_, coulomb) =
        check(&support::model("ur5"), &full_scene().coulomb("elbow_joint", 2.0).coulomb_velocity(0.05), 5, 1e-12);
    let dc = deltas("Coulomb friction on 1 joint", &coulomb);
    for f in ["inverse_dynamics", "bias_forces", "forward_dynamics"] {
        // b·q̇ and its sum; f·q̇/√(q̇² + v²): ², +, √, /, ·, sum.
        assert_eq!(delta(&dv, f), 2, "{f}");
        assert_eq!(delta(&dc, f), 6, "{f}");
    }
    for f in ["mass_matrix", "gravity_torques", "coriolis"] {
        assert_eq!((delta(&dv, f), delta(&dc, f)), (0, 0), "{f}");
    }
}

#[test]
fn f32_scenes_match_in_f32() {
    let scene = full_scene().tip_wrench("ee_link").gravity(Gravity::Input);
    let (_, m) = check_with(&support::model("ur5"), &scene, &full_options().scalar(ScalarType::F32), 10, 1e-5);
    // A scene file's `scalar = "f32"` is the same options.
    assert_eq!(with_keys("scalar = \"f32\""), full_options().scalar(ScalarType::F32));
    assert!(m.source.contains("pub fn inverse_dynamics(\n    q: &[f32; DOF],") || m.source.contains("q: &[f32; DOF]"));
    assert!(m.source.contains("gravity: &[f32; 3]") && !m.source.contains("f64; DOF"));
    let (_, f64_module) =
        check(&support::model("ur5"), &full_scene().tip_wrench("ee_link").gravity(Gravity::Input), 1, 1e-12);
    for f in ALL {
        assert_eq!(ops(&m, f), ops(&f64_module, f), "{f}");
    }
}

#[test]
fn no_std_targets() {
    // A scene file's target is the options' trigonometry.
    let libm = full_scene().coulomb("elbow_joint", 1.0);
    let options = with_keys("target = \"no_std_libm\"");
    assert_eq!(options, full_options().trig(Trig::Libm));
    let (_, m) = check_with(&support::model("ur5"), &libm, &options, 2, 1e-12);
    assert!(m.source.contains("libm::sincos(") && m.source.contains("libm::sqrt("));
    assert!(!m.source.contains(".sin_cos()") && !m.source.contains(".sqrt()"));
    let inputs = full_scene().tip_wrench("ee_link");
    let options = with_keys("target = \"no_std_sincos\"");
    assert_eq!(options, full_options().trig(Trig::Inputs));
    let (_, m) = check_with(&support::model("ur5"), &inputs, &options, 2, 1e-12);
    assert!(m.source.contains("pub fn inverse_dynamics_sc(") && !m.source.contains("pub fn inverse_dynamics("));
    assert!(deltas("no_std_sincos, tip wrench", &m).iter().all(|(f, x)| *x == 0 || f.contains("dynamics")));
}

/// Coulomb friction's square root without std and without libm: the
/// module's own `sqrt` (`sqrtf` in f32), one call in each body that has the
/// friction (τ, h, forward dynamics), for the batched trigonometry and for
/// target `no_std_sincos` (the sines and cosines as inputs). The compiled
/// modules are checked in `tests/no-std-check` (inside `#![no_std]`) and
/// `tests/tests/generated_scene.rs`.
#[test]
fn coulomb_friction_without_std_uses_the_module_sqrt() {
    let friction = || full_scene().coulomb("elbow_joint", 1.0).viscous("wrist_1_joint", 0.5);
    let batched = full_options().trig(Trig::Batched);
    let cases = [
        ("batched", friction(), batched.clone(), "sqrt"),
        ("no_std_sincos", friction(), with_keys("target = \"no_std_sincos\""), "sqrt"),
        ("batched f32", friction(), batched.scalar(ScalarType::F32), "sqrtf"),
    ];
    for (label, scene, options, sqrt) in cases {
        let tol = if sqrt == "sqrtf" { 1e-5 } else { 1e-12 };
        let (_, m) = check_with(&support::model("ur5"), &scene, &options, 2, tol);
        let src = &m.source;
        assert!(!src.contains(".sqrt()") && !src.contains("libm") && !src.contains(".sin_cos()"), "{label}");
        // One square root per body with friction: τ, h and the forward dynamics.
        let calls = src.lines().filter(|l| l.trim_start().starts_with("let t") && l.contains(&format!(" = {sqrt}(")));
        assert_eq!(calls.count(), 3, "{label}");
        assert!(src.contains(&format!("\nfn {sqrt}(")), "{label}: the kernel text's {sqrt}");
        for f in ["inverse_dynamics", "bias_forces", "forward_dynamics"] {
            assert_eq!(m.function(f).unwrap().op_count.sqrt, 1, "{label}: {f}");
        }
    }
    // With std's trigonometry, std's square root.
    let (_, m) = check_with(&support::model("ur5"), &friction(), &full_options().trig(Trig::Std), 1, 1e-12);
    assert_eq!(m.source.matches(".sqrt()").count(), 3);
}

#[test]
fn branched_and_prismatic_robots() {
    let panda = support::model("panda");
    // Prismatic fingers: the _sc functions also take q, then the inputs.
    let options =
        CodegenOptions::default().function(Function::Coriolis).function(Function::FrameJacobian("panda_hand".into()));
    let scene = Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("panda_hand")
        .payload_input("panda_hand")
        .lock("panda_joint7", 0.3)
        .armature("panda_joint2", 0.2)
        .viscous("panda_finger_joint1", 3.0);
    let (applied, _) = check_with(&panda, &scene, &options, 3, 1e-12);
    assert_eq!(applied.dof(), 8);
    // A finger's frame, a wrench and a payload on it: code generation moves
    // the finger's frame to its centre of mass (`center_prismatic_leaves`),
    // the frame keeps its pose and the payload its place; with a payload the
    // second finger's column of M is no longer the first's mirror image.
    let options = CodegenOptions::default()
        .function(Function::FramePose("panda_leftfinger".into()))
        .function(Function::FrameJacobian("panda_rightfinger".into()));
    let scene = Scene::new().tip_wrench("panda_leftfinger").payload_input("panda_rightfinger");
    let (applied, _) = check_with(&panda, &scene, &options, 3, 1e-12);
    assert_eq!(applied.dof(), 9);
    let torso = support::model("torso_two_arms");
    let options = CodegenOptions::default().function(Function::FramePose("left_hand".into()));
    let scene = Scene::new().subtree("torso", &["left_hand"]).tip_wrench("left_hand").coulomb("left_elbow_joint", 1.0);
    let (applied, m) = check_with(&torso, &scene, &options, 3, 1e-12);
    assert!(!applied.dropped_links.is_empty());
    assert!(m.source.contains("//   bodies dropped: right_"), "{}", &m.source[..2000]);
}

#[test]
fn codegen_errors_name_the_item() {
    // Two frames whose names differ only in characters Rust names cannot hold.
    let model = dynagen::model::RobotBuilder::new("r")
        .link("base", None)
        .link("a-b", Some(dynagen::model::Inertial::point_mass(1.0, [0.0, 0.0, -1.0])))
        .link("a_b", None)
        .joint(dynagen::model::JointDescription::revolute("j", "base", "a-b", [0.0, 1.0, 0.0]))
        .joint(dynagen::model::JointDescription::fixed("f", "a-b", "a_b"))
        .build()
        .unwrap();
    let applied = Scene::new().apply(&model).unwrap();
    let options = CodegenOptions::default()
        .function(Function::FramePose("a-b".into()))
        .function(Function::FramePose("a_b".into()));
    let e = generate_scene(&applied, &options).unwrap_err();
    assert!(matches!(e, CodegenError::DuplicateName(_)), "{e}");
    assert!(e.to_string().contains("frame_pose_a_b"), "{e}");
    // No functions: options without any, and a scene file whose lists are
    // empty.
    let e = generate_scene(&applied, &CodegenOptions::default().functions([])).unwrap_err();
    assert!(matches!(e, CodegenError::NoFunctions), "{e}");
    assert!(e.to_string().contains("no function"), "{e}");
    let e = SceneFile::from_toml_str("functions = []").unwrap_err();
    assert!(matches!(e, SceneError::NoFunctions), "{e}");
    assert!(e.to_string().contains("no function"), "{e}");
}

/// The legged manipulator (18 joints: Go1 legs, a Z1 arm) with a floating
/// trunk.
fn legged_manipulator() -> Model {
    support::model("legged_manipulator").with_floating_base()
}

/// The five functions, coriolis, and every frame function of a foot and of
/// the arm's tool.
fn floating_options() -> CodegenOptions {
    let mut options = CodegenOptions::default().function(Function::Coriolis);
    for frame in ["FL_foot", "arm_ee"] {
        for kind in Function::FRAME_KINDS {
            options = options.function(Function::frame_function(kind, frame).unwrap());
        }
    }
    options
}

/// Every scene option on a floating base, generated and checked against
/// [`SceneRobot`] (which `tests/floating_scene.rs` and
/// `tests/floating_pinocchio.rs` check against independent computations):
/// run-time gravity (world frame), a tip wrench at a foot, run-time payloads
/// on the floating trunk and on the arm, armature, friction and a lock; a
/// constant payload and a tip wrench on the base; a sub-tree of the legs
/// that keeps the floating base; one rooted on the arm's mount, a
/// fixed-base arm.
#[test]
fn every_scene_option_on_a_floating_base_matches_the_scene_robot() {
    let model = legged_manipulator();
    let everything = Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("FL_foot")
        .payload_input("trunk")
        .payload_input("arm_link06")
        .armature("FL_calf_joint", 0.03)
        .armature("arm_joint2", 0.01)
        .viscous("RR_thigh_joint", 0.2)
        .coulomb("arm_joint1", 1.5)
        .lock("arm_joint6", 0.3);
    let (applied, m) = check_with(&model, &everything, &floating_options(), 3, 1e-12);
    assert!(applied.model.is_floating() && applied.dof() == 17, "{}", applied.dof());
    // the signatures, whitespace aside
    let flat: String = m.source.split_whitespace().collect();
    for signature in [
        "pub fn inverse_dynamics(q: &[f64; NQ], qd: &[f64; NV], qdd: &[f64; NV], gravity: &[f64; 3], f_tip: &[f64; 6], \
         payload_trunk: &[f64; 10], payload_arm_link06: &[f64; 10],) -> [f64; NV]",
        "pub fn frame_acceleration_bias_fl_foot(q: &[f64; NQ], qd: &[f64; NV]) -> [f64; 6]",
        "pub fn frame_world_jacobian_arm_ee(q: &[f64; NQ]) -> [[f64; NV]; 6]",
    ] {
        let want: String = signature.split_whitespace().collect();
        assert!(flat.contains(&want), "missing: {signature}");
    }
    assert!(m.source.contains("// Gravity: a run-time input, m/s^2 in the world frame."));
    assert!(m.source.contains("`gravity`: m/s², in the world frame."));
    let on_base = Scene::new()
        .gravity(Gravity::Constant([0.5, -0.3, -9.7]))
        .payload("trunk", PayloadInertia::new(2.0, [0.05, 0.0, 0.03], [0.01, 0.02, 0.02, 0.001, 0.0, 0.0]))
        .tip_wrench("trunk")
        .lock("FL_calf_joint", -1.2);
    let (applied, _) = check_with(&model, &on_base, &floating_options(), 3, 1e-12);
    assert!(applied.warnings.is_empty(), "{:?}", applied.warnings);
    let legs = Scene::new().gravity(Gravity::None).subtree("trunk", &["FL_foot", "FR_foot", "RL_foot", "RR_foot"]);
    let options = CodegenOptions::default().function(Function::FrameAccelerationBias("RR_foot".into()));
    let (applied, _) = check_with(&model, &legs, &options, 3, 1e-12);
    assert!(applied.model.is_floating() && applied.dof() == 12);
    let arm = Scene::new().subtree("arm_link00", &["arm_ee"]).armature("arm_joint3", 0.02);
    let options = CodegenOptions::default().function(Function::FrameAccelerationBias("arm_ee".into()));
    let (applied, m) = check_with(&model, &arm, &options, 3, 1e-12);
    assert!(!applied.model.is_floating() && applied.dof() == 6);
    assert!(m.source.contains("pub const NQ: usize = DOF;"));
}
