//! The generated derivatives (`inverse_dynamics_derivatives`,
//! `forward_dynamics_derivatives`, `mass_matrix_inverse`) as traced,
//! simplified and prepared for emission, evaluated by the graph interpreter
//! against the generic derivatives (`Robot`, `SceneRobot`), in f64 and f32;
//! a scene's armature, friction and constant payload entering them with its
//! tip wrench held constant, against double-double finite differences of
//! the scene's dynamics; and the tree's structural zeros as constants.

mod support;

use dynagen::algorithms::{Loads, TipWrench, Workspace};
use dynagen::codegen::{generate, generate_scene, CodegenOptions, Function, GeneratedModule, ScalarType};
use dynagen::scene::{dynamics, Gravity, PayloadInertia, Scene, SceneFile, SceneInputs, SceneRobot};
use dynagen::spatial::{Force, Vec3};
use dynagen::symbolic::Node;
use dynagen::{DoubleDouble, Robot};
use nalgebra::{DMatrix, DVector, Vector6};
use support::{norm_rel_err, Rng};

const DERIVATIVES: [Function; 3] =
    [Function::InverseDynamicsDerivatives, Function::ForwardDynamicsDerivatives, Function::MassMatrixInverse];

fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// Each derivative function of `module` evaluated (f64 or f32 graph
/// evaluation) at `inputs`, against `want`'s generic derivatives.
fn compare(
    module: &GeneratedModule,
    scalar: ScalarType,
    inputs: &[(&str, &[f64])],
    want: impl Fn(&Function) -> Vec<f64>,
    tol: f64,
) -> f64 {
    let mut worst = 0.0_f64;
    for f in &module.functions {
        let got: Vec<f64> = match scalar {
            ScalarType::F32 => f.traced.eval_as::<f32>(inputs).unwrap().into_iter().map(f64::from).collect(),
            ScalarType::F64 => f.traced.eval(inputs).unwrap(),
        };
        let want = want(&f.function);
        let e = norm_rel_err(&got, &want, 1e-300);
        assert!(e <= tol, "{}: {e:e}", f.label());
        worst = worst.max(e);
    }
    worst
}

/// `robot`'s derivatives at (q, q̇, x), x taken as q̈ and as τ, with the
/// inputs `si`: ∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q, ∂q̈/∂q̇, M⁻¹ of the forward dynamics'
/// derivatives, and M⁻¹ alone.
fn scene_derivatives(robot: &mut SceneRobot, [q, qd, x]: [&Vec<f64>; 3], si: &SceneInputs) -> [DMatrix<f64>; 6] {
    let dv = |v: &Vec<f64>| DVector::from_vec(v.clone());
    let (a, b) = robot.inverse_dynamics_derivatives_with(&dv(q), &dv(qd), &dv(x), si).unwrap();
    let (c, d, e) = robot.forward_dynamics_derivatives_with(&dv(q), &dv(qd), &dv(x), si).unwrap();
    [a, b, c, d, e, robot.mass_matrix_inverse_with(&dv(q), si).unwrap()]
}

/// What derivative function `f` returns, row-major, from the matrices of
/// [`scene_derivatives`].
fn rows_of(f: &Function, [a, b, c, d, e, minv]: &[DMatrix<f64>; 6]) -> Vec<f64> {
    match f {
        Function::InverseDynamicsDerivatives => [rows(a), rows(b)].concat(),
        Function::ForwardDynamicsDerivatives => [rows(c), rows(d), rows(e)].concat(),
        _ => rows(minv),
    }
}

#[test]
fn generated_derivatives_match_the_generic_ones_on_the_bundled_robots() {
    for name in ["ur5", "panda", "torso_two_arms", "planar_2link", "iiwa14", "quadruped12"] {
        let model = support::model(name);
        let robot = Robot::new(model.clone());
        let n = model.dof();
        // f32 on two robots (generation in a debug build is what takes time)
        let scalars: &[(ScalarType, f64)] = match name {
            "ur5" | "panda" => &[(ScalarType::F64, 1e-12), (ScalarType::F32, 1e-4)],
            _ => &[(ScalarType::F64, 1e-12)],
        };
        for &(scalar, tol) in scalars {
            let options = CodegenOptions::default().functions(DERIVATIVES).scalar(scalar);
            let module = generate(&model, &options).unwrap();
            // the two ∂τ-based functions traced both ways, each compared below
            assert_eq!(module.functions.len(), 5);
            assert_eq!(module.functions.iter().filter(|f| f.emitted).count(), 3);
            let mut rng = Rng::new(0xd0d0 + n as u64);
            for _ in 0..3 {
                let (q, qd, x) = (rng.vec(n, 2.0), rng.vec(n, 1.5), rng.vec(n, 5.0));
                let dv = |v: &Vec<f64>| DVector::from_vec(v.clone());
                let inputs: [(&str, &[f64]); 4] = [("q", &q), ("qd", &qd), ("qdd", &x), ("tau", &x)];
                let e = compare(
                    &module,
                    scalar,
                    &inputs,
                    |f| match f {
                        Function::InverseDynamicsDerivatives => {
                            let (a, b) =
                                robot.clone().inverse_dynamics_derivatives(&dv(&q), &dv(&qd), &dv(&x)).unwrap();
                            [rows(&a), rows(&b)].concat()
                        }
                        Function::ForwardDynamicsDerivatives => {
                            let (a, b, c) =
                                robot.clone().forward_dynamics_derivatives(&dv(&q), &dv(&qd), &dv(&x)).unwrap();
                            [rows(&a), rows(&b), rows(&c)].concat()
                        }
                        _ => rows(&robot.clone().mass_matrix_inverse(&dv(&q)).unwrap()),
                    },
                    tol,
                );
                println!("{name} {scalar:?}: worst relative error {e:.1e}");
            }
        }
    }
}

/// On a tree, ∂τᵢ/∂qⱼ and ∂τᵢ/∂q̇ⱼ vanish unless joints i and j lie on one
/// path from the base: those outputs are the constant 0 (emitted as a
/// literal), and every other entry is not. M⁻¹ is emitted symmetric.
#[test]
fn structural_zeros_are_constants_and_the_inverse_is_symmetric() {
    let model = support::model("torso_two_arms");
    let n = model.dof();
    let module = generate(&model, &CodegenOptions::default().functions(DERIVATIVES)).unwrap();
    let ancestor = |a: usize, mut b: usize| loop {
        if a == b {
            return true;
        }
        match model.bodies[b].parent {
            Some(p) => b = p,
            None => return false,
        }
    };
    let related = |i: usize, j: usize| ancestor(i, j) || ancestor(j, i);
    // in both formulations
    for f in module.functions.iter().filter(|f| f.function == Function::InverseDynamicsDerivatives) {
        let (nodes, outs) = (f.traced.nodes(), f.traced.outputs());
        let mut zeros = 0;
        for m in 0..2 {
            for i in 0..n {
                for j in 0..n {
                    let node = &nodes[outs[m * n * n + i * n + j] as usize];
                    let is_zero = *node == Node::Const(0f64.to_bits());
                    if !related(i, j) {
                        assert!(is_zero, "{}: dtau[{i}]/d{}[{j}] is {node:?}", f.label(), ["q", "qd"][m]);
                        zeros += 1;
                    }
                }
            }
        }
        assert!(zeros > n * n / 2, "{}: {zeros} structural zeros", f.label());
    }
    let f = module.functions.iter().find(|f| f.function == Function::MassMatrixInverse).unwrap();
    let outs = f.traced.outputs();
    for i in 0..n {
        for j in 0..n {
            assert_eq!(outs[i * n + j], outs[j * n + i], "M⁻¹[{i}][{j}] and [{j}][{i}] are one node");
        }
    }
    // and in the source: literal zeros in the derivative's rows
    assert!(module.source.contains("pub fn inverse_dynamics_derivatives("));
    assert!(module.source.contains("pub type DofMatrix = [[f64; DOF]; DOF];"));
    assert!(module.source.contains("-> (DofMatrix, DofMatrix)"));
    assert!(module.source.contains("-> (DofMatrix, DofMatrix, DofMatrix)"));
}

/// The bundled `ur5_controller` scene (armature, viscous and Coulomb
/// friction, a constant payload, a tip wrench input): the generated
/// derivatives against the generic ones of the scene, and those against
/// double-double central differences of the scene's dynamics with the tip
/// wrench held constant.
#[test]
fn the_ur5_controller_scene_enters_its_derivatives() {
    let model = support::model("ur5");
    let file = SceneFile::from_toml_file(support::scene_path("ur5_controller")).unwrap();
    let applied = file.scene.apply(&model).unwrap();
    let options = CodegenOptions::default().functions(DERIVATIVES);
    let module = generate_scene(&applied, &options).unwrap();
    let mut robot = SceneRobot::new(applied.clone());
    let n = applied.dof();
    let frame = applied.tip_wrench_frame.expect("the scene has a tip wrench");
    let mut rng = Rng::new(0x5ce0e);
    for _ in 0..3 {
        let (q, qd, x) = (rng.vec(n, 2.0), rng.vec(n, 0.5), rng.vec(n, 5.0));
        let f_tip = rng.vec(6, 10.0);
        let inputs: [(&str, &[f64]); 5] = [("q", &q), ("qd", &qd), ("qdd", &x), ("tau", &x), ("f_tip", &f_tip)];
        let si = SceneInputs { tip_wrench: Some(Vector6::from_column_slice(&f_tip)), ..Default::default() };
        let generic = scene_derivatives(&mut robot, [&q, &qd, &x], &si);
        compare(&module, ScalarType::F64, &inputs, |f| rows_of(f, &generic), 1e-12);
        let [a, b, c, d, ..] = generic;
        // Double-double central differences of the scene's dynamics.
        type Dd = DoubleDouble;
        let g = Vec3(applied.model.gravity.0.map(Dd::from));
        let tips = [TipWrench { frame, wrench: Force::from_array([0, 1, 2, 3, 4, 5].map(|k| Dd::from(f_tip[k]))) }];
        let loads = Loads::gravity(&g).with_tips(&tips);
        let mut ws = Workspace::<Dd>::new(&applied.model);
        let h = 1e-7;
        let mut want = [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]];
        for j in 0..n {
            for (k, arg) in [(0, 0), (1, 1), (2, 0), (3, 1)] {
                let mut y = [vec![Dd::ZERO; n], vec![Dd::ZERO; n]];
                for (s, out) in [(1.0, 0), (-1.0, 1)] {
                    let mut v = [q.clone(), qd.clone()].map(|v| v.iter().map(|&t| Dd::from(t)).collect::<Vec<_>>());
                    v[arg][j] += Dd::from(s * h);
                    let xx: Vec<Dd> = x.iter().map(|&t| Dd::from(t)).collect();
                    if k < 2 {
                        dynamics::inverse_dynamics(&applied, &mut ws, &v[0], &v[1], &xx, loads, &mut y[out]);
                    } else {
                        dynamics::forward_dynamics(&applied, &mut ws, &v[0], &v[1], &xx, loads, &mut y[out]);
                    }
                }
                for i in 0..n {
                    want[k][i * n + j] = ((y[0][i] - y[1][i]) / Dd::from(2.0 * h)).to_f64();
                }
            }
        }
        for (got, want, what) in [
            (&a, &want[0], "dtau/dq"),
            (&b, &want[1], "dtau/dqd"),
            (&c, &want[2], "dqdd/dq"),
            (&d, &want[3], "dqdd/dqd"),
        ] {
            let e = norm_rel_err(&rows(got), want, 1e-12);
            println!("ur5_controller {what}: {e:.1e} against double-double differences");
            assert!(e <= 1e-9, "ur5_controller {what}: {e:e}");
        }
    }
}

/// Only on request: the default module does not have the derivatives, and
/// a scene's header does not list them as left out.
#[test]
fn derivatives_only_on_request() {
    let model = support::model("ur5");
    let plain = generate(&model, &CodegenOptions::default()).unwrap();
    assert!(!plain.source.contains("derivatives") && !plain.source.contains("mass_matrix_inverse"));
    let file = SceneFile::from_toml_file(support::scene_path("ur5_controller")).unwrap();
    let scene = generate_scene(&file.scene.apply(&model).unwrap(), &CodegenOptions::default()).unwrap();
    assert!(!scene.source.contains("derivatives"));
    let f: Function = "forward_dynamics_derivatives".parse().unwrap();
    assert_eq!(f, Function::ForwardDynamicsDerivatives);
    assert!("mass_matrix_inverse".parse::<Function>().is_ok());
}

/// A floating base's generated derivatives (NV × NV, the tangent of the
/// base's body twist), both formulations, evaluated as traced against the
/// generic ones (themselves checked against differences on the manifold and
/// Pinocchio's free flyer): the two-armed torso plain, and in a scene with
/// armature, viscous and Coulomb friction, a constant payload on the
/// floating base, a run-time payload on a hand, gravity and a tip wrench as
/// inputs (held constant). The quadruped12's module is compiled and checked
/// in `tests/tests/generated_derivatives.rs`.
#[test]
fn floating_base_derivatives_match_the_generic_ones() {
    let model = support::model("torso_two_arms").with_floating_base();
    let payload = PayloadInertia::new(2.5, [0.05, -0.02, 0.1], [0.02, 0.03, 0.04, 0.002, -0.001, 0.0005]);
    let scene = Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("right_ee")
        .payload("base", payload)
        .payload_input("left_hand")
        .armature("left_shoulder_joint", 0.05)
        .armature("torso_yaw_joint", 0.1)
        .viscous("right_elbow_joint", 0.4)
        .coulomb("left_elbow_joint", 1.5)
        .coulomb_velocity(0.05);
    for (what, applied) in [("plain", Scene::new()), ("scene", scene)].map(|(w, s)| (w, s.apply(&model).unwrap())) {
        let (nq, nv) = (model.nq(), model.nv());
        let module = generate_scene(&applied, &CodegenOptions::default().functions(DERIVATIVES)).unwrap();
        assert_eq!(module.functions.len(), 5, "both formulations of the two ∂τ-based functions");
        assert!(module.source.contains("pub fn forward_dynamics_derivatives(\n    q: &[f64; NQ],"), "NQ-long q");
        assert!(module.source.contains("[[f64; NV]; NV]"), "NV × NV matrices");
        let mut robot = SceneRobot::new(applied.clone());
        let mut rng = Rng::new(0xf1 + nv as u64);
        for _ in 0..2 {
            let mut q = rng.vec(nq, 2.0);
            support::normalize_quaternion(&mut q);
            let (qd, x) = (rng.vec(nv, 1.5), rng.vec(nv, 5.0));
            let (gravity, f_tip) = ([0.8, -0.4, -9.7], rng.vec(6, 10.0));
            let hand = [PayloadInertia::new(0.7, [0.02, 0.01, -0.03], [0.001, 0.002, 0.0015, 0.0, 0.0001, 0.0])];
            let p = &hand[0];
            let payload_arg: Vec<f64> = [p.mass].into_iter().chain(p.com).chain(p.inertia).collect();
            let inputs: [(&str, &[f64]); 7] = [
                ("q", &q),
                ("qd", &qd),
                ("qdd", &x),
                ("tau", &x),
                ("gravity", &gravity),
                ("f_tip", &f_tip),
                ("payload_left_hand", &payload_arg),
            ];
            let si = match what {
                "plain" => SceneInputs::default(),
                _ => SceneInputs {
                    gravity: Some(gravity.into()),
                    tip_wrench: Some(Vector6::from_column_slice(&f_tip)),
                    payloads: &hand,
                },
            };
            let generic = scene_derivatives(&mut robot, [&q, &qd, &x], &si);
            let worst = compare(&module, ScalarType::F64, &inputs, |f| rows_of(f, &generic), 1e-12);
            println!("torso_two_arms (floating, {what}): worst relative error {worst:.1e}");
            let worst = compare_factors(&module, &inputs, &generic);
            println!("torso_two_arms (floating, {what}), factors and products: worst relative error {worst:.1e}");
        }
    }
}

/// The forward dynamics' derivatives of `module` as emitted with their
/// products in a loop (`codegen/emit/products.rs`): the factors' body (∂τ/∂q,
/// ∂τ/∂q̇ at q̈ = FD, M⁻¹) evaluated at `inputs` (its sines and cosines from
/// `q`), then −M⁻¹∂τ, against the generic derivatives (≤ 1e-12); the worst
/// relative error. Panics if the module does not emit them so.
fn compare_factors(module: &GeneratedModule, inputs: &[(&str, &[f64])], generic: &[DMatrix<f64>; 6]) -> f64 {
    let f = module.functions.iter().find(|f| f.emitted && f.function == Function::ForwardDynamicsDerivatives);
    let (sc, _) = f.and_then(|f| f.factors.as_ref()).expect("the forward dynamics' derivatives as factors");
    assert!(module.source.contains("fn derivative_products_on<I: Isa>"), "the products' loop is emitted");
    let q = inputs.iter().find(|(name, _)| *name == "q").expect("q").1;
    let angle = |i: usize| sc.angle_scale[i].map(|k| k * q[sc.q_offset + i]);
    let s: Vec<f64> = (0..sc.angle_scale.len()).map(|i| angle(i).map_or(0.0, f64::sin)).collect();
    let c: Vec<f64> = (0..sc.angle_scale.len()).map(|i| angle(i).map_or(1.0, f64::cos)).collect();
    assert!(sc.extra_angles.is_empty(), "no mimic joint here");
    let all: Vec<(&str, &[f64])> = inputs.iter().copied().chain([("s", &s[..]), ("c", &c[..])]).collect();
    let out = sc.function.eval(&all).unwrap();
    let n = generic[4].nrows();
    let m = |k: usize| DMatrix::from_row_slice(n, n, &out[k * n * n..(k + 1) * n * n]);
    let minv = m(2);
    let got = [-&minv * m(0), -&minv * m(1), minv];
    let want = [&generic[2], &generic[3], &generic[4]];
    let worst = got.iter().zip(want).map(|(g, w)| norm_rel_err(&rows(g), &rows(w), 1e-300)).fold(0.0, f64::max);
    assert!(worst <= 1e-12, "factors and products: {worst:e}");
    worst
}
