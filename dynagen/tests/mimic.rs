//! Mimic joints (URDF `<mimic>`): a joint that follows its master,
//! q = multiplier·q_master + offset, has no coordinate of its own.
//!
//! `tests/data/panda_mimic.urdf` is the bundled Panda with the `<mimic>`
//! element franka_description gives its second finger;
//! `tests/data/gripper_mimic.urdf` a gripper linkage with multipliers of
//! −0.75, 1, −1 and 0.02 m/rad, offsets, a mimic joint below its revolute
//! master, two on a sibling branch and a prismatic one. Pinocchio's values
//! with its URDF parser's mimic option (`pinocchio_mimic_*.json`,
//! scripts/reference/make_pinocchio_mimic.py) are the reference: τ, M, h,
//! g and q̈ within 1e-12, from the generic solver and from the traced
//! generated functions (the compiled modules: tests/tests/generated_mimic.rs).

mod support;

use dynagen::codegen::{generate, CodegenOptions, Function};
use dynagen::model::{JointDescription, MimicJoints, ModelError};
use dynagen::{Model, Robot};
use nalgebra::{DMatrix, DVector};
use serde_json::Value;
use std::path::Path;
use support::rel_err;

fn data_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn vector(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn reference(robot: &str) -> Value {
    let path = data_path(&format!("pinocchio_mimic_{robot}.json"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn mimic_model(robot: &str) -> Model {
    Model::from_urdf_file(data_path(&format!("{robot}_mimic.urdf"))).unwrap()
}

/// The five quantities of one state: (name, ours, Pinocchio's).
fn compare(robot: &mut Robot, s: &Value) -> Vec<(&'static str, Vec<f64>, Vec<f64>)> {
    let v = |k: &str| DVector::from_vec(vector(&s[k]));
    let (q, qd, qdd, tau_in) = (v("q"), v("qd"), v("qdd"), v("tau_in"));
    let m = robot.mass_matrix(&q).unwrap();
    let m_rows: Vec<f64> = m.row_iter().flat_map(|r| r.iter().copied().collect::<Vec<_>>()).collect();
    let pin_m: Vec<f64> = s["M"].as_array().unwrap().iter().flat_map(vector).collect();
    vec![
        ("tau", robot.inverse_dynamics(&q, &qd, &qdd).unwrap().as_slice().to_vec(), vector(&s["tau"])),
        ("M", m_rows, pin_m),
        ("h", robot.bias_forces(&q, &qd).unwrap().as_slice().to_vec(), vector(&s["h"])),
        ("g", robot.gravity_torques(&q).unwrap().as_slice().to_vec(), vector(&s["g"])),
        ("qdd", robot.forward_dynamics(&q, &qd, &tau_in).unwrap().as_slice().to_vec(), vector(&s["qdd_fd"])),
    ]
}

#[test]
fn the_panda_with_its_mimic_finger_loads_unedited_with_eight_joints() {
    let model = mimic_model("panda");
    let data = reference("panda");
    assert_eq!(model.bodies.len(), 9);
    assert_eq!(model.dof(), 8);
    let names: Vec<&str> = data["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
    assert_eq!(model.joint_names(), names);
    let finger2 = model.joint_body_index("panda_finger_joint2").unwrap();
    let m = model.mimic(finger2).expect("the second finger follows the first");
    assert_eq!((model.bodies[m.master].joint.name.as_str(), m.multiplier, m.offset), ("panda_finger_joint1", 1.0, 0.0));
    assert_eq!(model.column(finger2), 7);
    assert_eq!(model.joint_index("panda_finger_joint2"), None);
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn generic_solver_matches_pinocchio_with_mimic_joints() {
    for robot in ["panda", "gripper"] {
        let data = reference(robot);
        let mut ours = Robot::new(mimic_model(robot));
        let names: Vec<&str> = data["joint_names"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
        assert_eq!(ours.joint_names(), names, "{robot}");
        let mut worst = [0.0f64; 5];
        for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
            for (i, (what, got, want)) in compare(&mut ours, s).into_iter().enumerate() {
                let e = rel_err(&got, &want, 1e-9);
                assert!(e <= 1e-12, "{robot} state {k}: {what} relative error {e:e}\n{got:?}\n{want:?}");
                worst[i] = worst[i].max(e);
            }
        }
        println!("{robot}: largest relative error against Pinocchio (tau, M, h, g, qdd): {worst:?}");
    }
}

#[test]
fn traced_generated_functions_match_pinocchio_with_mimic_joints() {
    for robot in ["panda", "gripper"] {
        let data = reference(robot);
        let module = generate(&mimic_model(robot), &CodegenOptions::default()).unwrap();
        for (k, s) in data["states"].as_array().unwrap().iter().enumerate() {
            let (q, qd, qdd, tau_in) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]), vector(&s["tau_in"]));
            for f in module.functions.iter().filter(|f| f.emitted) {
                let (third, want) = match f.function {
                    Function::InverseDynamics => (("qdd", &qdd[..]), vector(&s["tau"])),
                    Function::MassMatrix => {
                        (("tau", &[][..]), s["M"].as_array().unwrap().iter().flat_map(vector).collect())
                    }
                    Function::BiasForces => (("tau", &[][..]), vector(&s["h"])),
                    Function::GravityTorques => (("tau", &[][..]), vector(&s["g"])),
                    Function::ForwardDynamics => (("tau", &tau_in[..]), vector(&s["qdd_fd"])),
                    _ => continue,
                };
                let got = f.traced.eval(&[("q", &q), ("qd", &qd), third]).unwrap();
                let e = rel_err(&got, &want, 1e-9);
                assert!(e <= 1e-12, "{robot} state {k}: generated {} relative error {e:e}", f.label());
            }
        }
    }
}

#[test]
fn mimic_joints_can_be_independent_joints_as_before() {
    let path = data_path("panda_mimic.urdf");
    let opts = dynagen::model::BuildOptions::default().mimic_joints(MimicJoints::Independent);
    let independent = Model::from_urdf_file_with(&path, &opts).unwrap();
    let bundled = support::model("panda");
    assert_eq!(independent.dof(), 9);
    assert!(!independent.has_mimic());
    assert_eq!(independent.bodies, bundled.bodies);
}

/// The Builder's option: the same file read with its mimic joint as a
/// joint of its own generates the bundled Panda's 9-joint dynamics, and by
/// default the 8 joints of the mimic model.
#[test]
fn the_builder_reads_mimic_joints_either_way() {
    let path = data_path("panda_mimic.urdf");
    let module = |mimic: MimicJoints| {
        let module = dynagen::Builder::new().urdf(&path).mimic_joints(mimic).generate_module().unwrap();
        module.functions.into_iter().find(|f| f.function == Function::InverseDynamics).unwrap()
    };
    let (follow, independent) = (module(MimicJoints::Follow), module(MimicJoints::Independent));
    let mut bundled = Robot::new(support::model("panda"));
    let state = |n: usize, k: usize| -> Vec<f64> { (0..n).map(|j| (0.3 * (j + 7 * k) as f64 + 0.1).sin()).collect() };
    let (q, qd, qdd) = (state(9, 0), state(9, 1), state(9, 2));
    let v = |x: &[f64]| DVector::from_column_slice(x);
    let want = bundled.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap();
    let got = independent.traced.eval(&[("q", &q), ("qd", &qd), ("qdd", &qdd)]).unwrap();
    assert!(rel_err(&got, want.as_slice(), 1e-9) <= 1e-13, "{got:?}\n{want:?}");
    let mut mimic = Robot::new(mimic_model("panda"));
    let want = mimic.inverse_dynamics(&v(&q[..8]), &v(&qd[..8]), &v(&qdd[..8])).unwrap();
    let got = follow.traced.eval(&[("q", &q[..8]), ("qd", &qd[..8]), ("qdd", &qdd[..8])]).unwrap();
    assert!(rel_err(&got, want.as_slice(), 1e-9) <= 1e-13, "{got:?}\n{want:?}");
}

/// A robot of the joint `m` from `base` to `a` and the joints `x` and `y`
/// among the links `a`, `b` and `c`.
fn three_joints(x: JointDescription, y: JointDescription) -> Result<Model, ModelError> {
    let body = Some(dynagen::model::Inertial::new(0.5, [0.0, 0.0, 0.1], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0]));
    dynagen::RobotBuilder::new("r")
        .link("base", None)
        .link("a", body)
        .link("b", body)
        .link("c", body)
        .joint(JointDescription::revolute("m", "base", "a", [0.0, 0.0, 1.0]))
        .joint(x)
        .joint(y)
        .build()
}

/// A robot with a master `m`, a fixed joint `fix` and the joint `f`, which
/// follows one of them as written.
fn follower(f: JointDescription) -> Result<Model, ModelError> {
    three_joints(JointDescription::fixed("fix", "a", "b"), f)
}

#[test]
fn a_bad_mimic_is_an_error_naming_the_joint() {
    let rev = |master: &str| JointDescription::revolute("f", "a", "c", [1.0, 0.0, 0.0]).mimic(master, 2.0, 0.1);
    let msg = |r: Result<Model, ModelError>| r.unwrap_err().to_string();
    assert_eq!(msg(follower(rev("nope"))), "joint \"f\" (mimic): its master joint \"nope\" does not exist");
    assert_eq!(msg(follower(rev("f"))), "joint \"f\" (mimic): it mimics itself");
    assert_eq!(
        msg(follower(rev("fix"))),
        "joint \"f\" (mimic): its master joint \"fix\" is fixed: a mimic joint follows a revolute, continuous or \
         prismatic joint"
    );
    assert_eq!(
        msg(follower(JointDescription::revolute("f", "a", "c", [1.0, 0.0, 0.0]).mimic("m", f64::NAN, 0.0))),
        "joint \"f\": mimic multiplier is not finite"
    );
    assert_eq!(
        msg(follower(JointDescription::revolute("f", "a", "c", [1.0, 0.0, 0.0]).mimic("m", 1.0, f64::INFINITY))),
        "joint \"f\": mimic offset is not finite"
    );
    assert_eq!(
        msg(follower(JointDescription::fixed("f", "a", "c").mimic("m", 1.0, 0.0))),
        "joint \"f\" (mimic): a fixed joint cannot follow another (only revolute, continuous and prismatic joints \
         mimic): remove its <mimic>, or read mimic joints as independent joints (the option mimic = independent), \
         which ignores it"
    );
    // a chain of mimics, and a cycle of them
    let two = three_joints;
    let x = JointDescription::revolute("x", "a", "b", [0.0, 1.0, 0.0]).mimic("y", 2.0, 0.5);
    let y = JointDescription::revolute("y", "b", "c", [0.0, 1.0, 0.0]);
    assert_eq!(
        msg(two(x.clone(), y.clone().mimic("m", 3.0, 0.25))),
        "joint \"x\" (mimic): its master joint \"y\" follows \"m\" itself: mimic joints cannot be chained; make \"x\" \
         follow \"m\" directly (multiplier 6 and offset 1)"
    );
    assert_eq!(
        msg(two(x, y.mimic("x", 3.0, 0.0))),
        "joint \"x\" (mimic): its master joint \"y\" follows it in turn: mimic joints cannot form a cycle"
    );
}

/// The model of `robot`'s file with every joint independent (the full
/// tree, floating or not), and the coupling of the mimic model's joints:
/// the bodies' coordinates are `g·q_joints + o`.
struct FullTree {
    full: Model,
    g: DMatrix<f64>,
    o: DVector<f64>,
    /// A floating base's leading entries of q and of q̇ (0, 0 when fixed).
    base: (usize, usize),
}

impl FullTree {
    fn new(model: &Model, robot: &str) -> Self {
        let path = data_path(&format!("{robot}_mimic.urdf"));
        let opts = dynagen::model::BuildOptions::default().mimic_joints(MimicJoints::Independent);
        let mut full = Model::from_urdf_file_with(&path, &opts).unwrap();
        if model.is_floating() {
            full = floating(full);
        }
        let nb = model.bodies.len();
        let (mut g, mut o) = (DMatrix::zeros(nb, model.dof()), DVector::zeros(nb));
        for i in 0..nb {
            let m = model.mimic(i);
            g[(i, model.column(i))] = m.map_or(1.0, |m| m.multiplier);
            o[i] = m.map_or(0.0, |m| m.offset);
        }
        let base = if model.is_floating() { (7, 6) } else { (0, 0) };
        FullTree { full, g, o, base }
    }
    /// The full model's configuration of the mimic model's `q`.
    fn q(&self, q: &DVector<f64>) -> DVector<f64> {
        let b = self.base.0;
        let joints = &self.g * q.rows(b, q.len() - b) + &self.o;
        DVector::from_iterator(b + joints.len(), q.rows(0, b).iter().chain(joints.iter()).copied())
    }
    /// The velocity-side coupling: G with a floating base's identity block.
    fn gv(&self) -> DMatrix<f64> {
        let b = self.base.1;
        let mut gv = DMatrix::zeros(b + self.g.nrows(), b + self.g.ncols());
        for k in 0..b {
            gv[(k, k)] = 1.0;
        }
        gv.view_mut((b, b), self.g.shape()).copy_from(&self.g);
        gv
    }
}

/// `model` with a floating base of 5 kg (the files' base links have no
/// mass, which would make the base's yaw and a first joint about z
/// dependent).
fn floating(mut model: Model) -> Model {
    use dynagen::spatial::{Inertia, Sym3, Vec3};
    // before floating it, so that the load's checks see the base's mass
    model.base_inertia =
        Inertia::from_mass_com_inertia(5.0, Vec3([0.0, 0.0, 0.05]), Sym3([0.1, 0.12, 0.08, 0.0, 0.0, 0.0]));
    model.with_floating_base()
}

/// max |a − b| / max(max |b|, 1e-9).
fn max_diff(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    let scale = b.iter().fold(1e-9f64, |m, x| m.max(x.abs()));
    a.iter().zip(b.iter()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

/// Every quantity of the generic solver on a model with mimic joints
/// equals the full tree's projected by the coupling: τ = Gᵀτ_full,
/// M = GᵀM_full G, h, g, J = J_full G, the derivatives by the chain rule,
/// the same frame poses, ½ q̇ᵀMq̇ as kinetic energy; forward dynamics
/// solves M q̈ = τ − h whichever way it is asked (ABA's name, LᵀDL,
/// compensated), and the integrators keep the energy.
#[test]
fn every_generic_function_is_the_full_trees_projected() {
    use dynagen::algorithms::{energy, Workspace};
    for floating_base in [false, true] {
        for robot in ["gripper", "panda"] {
            let model = if floating_base { floating(mimic_model(robot)) } else { mimic_model(robot) };
            let ft = FullTree::new(&model, robot);
            let (mut ours, mut full) = (Robot::new(model.clone()), Robot::new(ft.full.clone()));
            let gv = ft.gv();
            let mut rng = support::Rng::new(0x51ed);
            let frame = model.frames.last().unwrap().name.clone();
            for _ in 0..5 {
                let mut q = DVector::from_vec(rng.vec(model.nq(), 1.5));
                if floating_base {
                    let norm = q.rows(3, 4).norm();
                    q.rows_mut(3, 4).unscale_mut(norm);
                }
                let (qd, qdd) =
                    (DVector::from_vec(rng.vec(model.nv(), 2.0)), DVector::from_vec(rng.vec(model.nv(), 5.0)));
                let qf = ft.q(&q);
                let (qdf, qddf) = (&gv * &qd, &gv * &qdd);
                let col = |v: DVector<f64>| DMatrix::from_column_slice(v.len(), 1, v.as_slice());
                let tag = format!("{robot} floating {floating_base}");
                let checks = [
                    (
                        "tau",
                        col(ours.inverse_dynamics(&q, &qd, &qdd).unwrap()),
                        gv.transpose() * col(full.inverse_dynamics(&qf, &qdf, &qddf).unwrap()),
                    ),
                    ("M", ours.mass_matrix(&q).unwrap(), gv.transpose() * full.mass_matrix(&qf).unwrap() * &gv),
                    (
                        "h",
                        col(ours.bias_forces(&q, &qd).unwrap()),
                        gv.transpose() * col(full.bias_forces(&qf, &qdf).unwrap()),
                    ),
                    (
                        "g",
                        col(ours.gravity_torques(&q).unwrap()),
                        gv.transpose() * col(full.gravity_torques(&qf).unwrap()),
                    ),
                    (
                        "pose",
                        ours.frame_pose(&frame, &q).unwrap().resize(4, 4, 0.0),
                        full.frame_pose(&frame, &qf).unwrap().resize(4, 4, 0.0),
                    ),
                    (
                        "J_s",
                        ours.space_jacobian(&frame, &q).unwrap().resize(6, model.nv(), 0.0),
                        (full.space_jacobian(&frame, &qf).unwrap() * &gv).resize(6, model.nv(), 0.0),
                    ),
                    (
                        "J_b",
                        ours.body_jacobian(&frame, &q).unwrap().resize(6, model.nv(), 0.0),
                        (full.body_jacobian(&frame, &qf).unwrap() * &gv).resize(6, model.nv(), 0.0),
                    ),
                    (
                        "J_base",
                        ours.base_jacobian(&frame, &q).unwrap().resize(6, model.nv(), 0.0),
                        (full.base_jacobian(&frame, &qf).unwrap() * &gv).resize(6, model.nv(), 0.0),
                    ),
                    (
                        "Jdot qd",
                        col(ours.frame_acceleration_bias(&frame, &q, &qd).unwrap().resize_vertically(6, 0.0)),
                        col(full.frame_acceleration_bias(&frame, &qf, &qdf).unwrap().resize_vertically(6, 0.0)),
                    ),
                ];
                for (what, got, want) in checks {
                    let e = max_diff(&got, &want);
                    assert!(e <= 1e-13, "{tag}: {what} differs by {e:e}");
                }
                // forward dynamics, whichever way
                let m = ours.mass_matrix(&q).unwrap();
                let tau = DVector::from_vec(rng.vec(model.nv(), 10.0));
                let qdd1 = ours.forward_dynamics(&q, &qd, &tau).unwrap();
                let rhs = &tau - ours.bias_forces(&q, &qd).unwrap();
                assert!(max_diff(&col(&m * &qdd1), &col(rhs.clone())) <= 1e-12, "{tag}: M q̈ = τ − h");
                let compensated = ours.forward_dynamics_compensated(&q, &qd, &tau).unwrap();
                // (with a step of refinement: the residual by the projected RNEA)
                ours.set_compensated_refinement(1);
                let refined = ours.forward_dynamics_compensated(&q, &qd, &tau).unwrap();
                ours.set_compensated_refinement(0);
                for other in [ours.forward_dynamics_ldlt(&q, &qd, &tau).unwrap(), compensated, refined] {
                    assert!(max_diff(&col(other), &col(qdd1.clone())) <= 1e-12, "{tag}: forward dynamics variants");
                }
                // kinetic energy
                let mut ws = Workspace::<f64>::new(&model);
                let t = energy::kinetic_energy(&model, &mut ws, q.as_slice(), qd.as_slice());
                let want = 0.5 * qd.dot(&(&m * &qd));
                assert!((t - want).abs() <= 1e-13 * want.abs().max(1.0), "{tag}: kinetic energy {t} against {want}");
                if floating_base {
                    let a = ours.centroidal_momentum_matrix(&q).unwrap();
                    let af = full.centroidal_momentum_matrix(&qf).unwrap() * &gv;
                    assert!(
                        max_diff(&a.resize(6, model.nv(), 0.0), &af.resize(6, model.nv(), 0.0)) <= 1e-13,
                        "{tag}: A_G"
                    );
                    let c = ours.center_of_mass(&q).unwrap() - full.center_of_mass(&qf).unwrap();
                    assert!(c.norm() <= 1e-14, "{tag}: centre of mass");
                }
                {
                    // the derivatives, by the chain rule (a floating base's
                    // columns in the tangent space of its body twist on both)
                    let (dq, dqd) = ours.inverse_dynamics_derivatives(&q, &qd, &qdd).unwrap();
                    let (fq, fqd) = full.inverse_dynamics_derivatives(&qf, &qdf, &qddf).unwrap();
                    assert!(max_diff(&dq, &(gv.transpose() * fq * &gv)) <= 1e-12, "{tag}: dtau/dq");
                    assert!(max_diff(&dqd, &(gv.transpose() * fqd * &gv)) <= 1e-12, "{tag}: dtau/dqd");
                    let minv = ours.mass_matrix_inverse(&q).unwrap();
                    let eye = DMatrix::<f64>::identity(model.nv(), model.nv());
                    assert!(max_diff(&(&minv * &m), &eye) <= 1e-10, "{tag}: M⁻¹ M");
                    let (aq, aqd, ainv) = ours.forward_dynamics_derivatives(&q, &qd, &tau).unwrap();
                    let (tq, tqd) = ours.inverse_dynamics_derivatives(&q, &qd, &qdd1).unwrap();
                    assert!(max_diff(&ainv, &minv) <= 1e-12, "{tag}: M⁻¹ of the forward derivatives");
                    assert!(max_diff(&aq, &-(&minv * tq)) <= 1e-10, "{tag}: dqdd/dq = −M⁻¹ dtau/dq");
                    assert!(max_diff(&aqd, &-(&minv * tqd)) <= 1e-10, "{tag}: dqdd/dqd = −M⁻¹ dtau/dqd");
                }
            }
        }
    }
}

/// The integrators on a model with mimic joints: without torques, an RK4
/// second of the gripper keeps T + V within 1e-6 of its start, and every
/// integrator steps.
#[test]
fn integrators_step_a_model_with_mimic_joints() {
    use dynagen::algorithms::{energy, Workspace};
    use dynagen::{Integrator, Stepping};
    let model = mimic_model("gripper");
    let mut robot = Robot::new(model.clone());
    let (q0, qd0) = (DVector::from_vec(vec![0.2, -0.4, 0.3, 0.1]), DVector::from_vec(vec![0.5, -0.3, 1.0, 0.2]));
    let energy = |q: &[f64], qd: &[f64]| {
        let mut ws = Workspace::<f64>::new(&model);
        energy::kinetic_energy(&model, &mut ws, q, qd) + energy::potential_energy(&model, &mut ws, q, &model.gravity)
    };
    let tau = DMatrix::zeros(101, 4);
    let (q, qd) =
        robot.forward_dynamics_trajectory(&q0, &qd0, &tau, None, Stepping::new(0.01, 4, Integrator::Rk4)).unwrap();
    let (q1, qd1) = (q.row(100).transpose(), qd.row(100).transpose());
    let (e0, e1) = (energy(q0.as_slice(), qd0.as_slice()), energy(q1.as_slice(), qd1.as_slice()));
    assert!((e1 - e0).abs() <= 1e-6 * e0.abs().max(1.0), "energy {e0} → {e1}");
    for integrator in [Integrator::Euler, Integrator::SemiImplicitEuler, Integrator::Rk4, Integrator::ImplicitEuler] {
        let (mut q, mut qd) = (q0.clone(), qd0.clone());
        robot.step(integrator, &mut q, &mut qd, &DVector::zeros(4), 1e-3).unwrap();
        assert!(q.iter().chain(qd.iter()).all(|x| x.is_finite()) && q != q0, "{integrator:?}");
    }
}

/// Scenes: locking a master locks the joints that follow it where they
/// are then (the scene is the full tree's with all of them locked there);
/// armature and friction go to the master's column; a mimic joint has no
/// lock, armature or friction of its own, and a sub-tree that would keep a
/// mimic joint without its master, or merge it rigidly while its master
/// moves, is refused naming both.
#[test]
fn scenes_lock_masters_with_their_mimic_joints() {
    use dynagen::scene::{Scene, SceneError, SceneRobot};
    let model = mimic_model("gripper");
    let full = FullTree::new(&model, "gripper").full;
    let locked = Scene::new().lock("c_finger", 0.3).apply(&model).unwrap();
    assert_eq!(locked.joint_names(), ["a_shoulder", "b_elbow", "h_cam"]);
    assert!(!locked.model.has_mimic());
    let at = |j: &str| locked.fixed_joints.iter().find(|(n, _)| n == j).map(|(_, q)| *q);
    assert_eq!(at("c_finger"), Some(0.3));
    assert_eq!(at("d_tip_l"), Some(-0.75 * 0.3 + 0.2));
    assert_eq!(at("e_knuckle_r"), Some(0.3 - 0.1));
    assert_eq!(at("f_tip_r"), Some(-0.3));
    assert_eq!(at("g_slide"), Some(0.02 * 0.3 + 0.01));
    let mut by_hand = Scene::new();
    for (j, q) in &locked.fixed_joints {
        by_hand = by_hand.lock(j, *q);
    }
    let (mut a, mut b) = (SceneRobot::new(locked.clone()), SceneRobot::new(by_hand.apply(&full).unwrap()));
    let (q, qd, qdd) = (
        DVector::from_vec(vec![0.4, -0.7, 1.1]),
        DVector::from_vec(vec![0.3, 1.2, -0.5]),
        DVector::from_vec(vec![2.0, -1.0, 0.5]),
    );
    let (ta, tb) = (a.inverse_dynamics(&q, &qd, &qdd).unwrap(), b.inverse_dynamics(&q, &qd, &qdd).unwrap());
    assert!(rel_err(ta.as_slice(), tb.as_slice(), 1e-9) <= 1e-14, "{ta} against {tb}");

    // armature and friction on a master: its column's
    let scene = Scene::new().armature("c_finger", 0.05).viscous("c_finger", 0.2).apply(&model).unwrap();
    let (mut s, mut plain) = (SceneRobot::new(scene), Robot::new(model.clone()));
    let q = DVector::from_vec(vec![0.4, -0.7, 1.1, 0.2]);
    let (qd, qdd) = (DVector::from_vec(vec![0.3, 1.2, -0.5, 0.1]), DVector::from_vec(vec![2.0, -1.0, 0.5, 1.5]));
    let mut want = plain.inverse_dynamics(&q, &qd, &qdd).unwrap();
    want[2] += 0.05 * qdd[2] + 0.2 * qd[2];
    let got = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
    assert!(rel_err(got.as_slice(), want.as_slice(), 1e-9) <= 1e-14, "{got} against {want}");
    let back = s.forward_dynamics(&q, &qd, &got).unwrap();
    assert!(rel_err(back.as_slice(), qdd.as_slice(), 1e-9) <= 1e-12, "{back} against {qdd}");

    let msg = |scene: Scene| match scene.apply(&model) {
        Err(e @ SceneError::MimicJoint { .. }) => e.to_string(),
        other => panic!("{other:?}"),
    };
    assert_eq!(
        msg(Scene::new().lock("d_tip_l", 0.1)),
        "joint \"d_tip_l\" follows joint \"c_finger\" (mimic): it has no lock of its own; give the lock to its master"
    );
    assert_eq!(
        msg(Scene::new().armature("g_slide", 0.1)),
        "joint \"g_slide\" follows joint \"c_finger\" (mimic): it has no armature of its own; give the armature to \
         its master"
    );
    assert_eq!(
        msg(Scene::new().subtree("palm", &["tip_r"])),
        "joint \"e_knuckle_r\" follows joint \"c_finger\" (mimic): the sub-tree keeps it but not its master (which is \
         on a branch the sub-tree drops): lock the master, or keep it by listing a tip below it"
    );
    assert_eq!(
        msg(Scene::new().subtree("base", &["knuckle_l"])),
        "joint \"d_tip_l\" follows joint \"c_finger\" (mimic): the sub-tree merges it rigidly below a tip, but its \
         master moves: lock the master, or list a tip below the mimic joint"
    );
    // a locked master lets the sub-tree merge its mimic joints, where they are
    let merged = Scene::new().subtree("base", &["knuckle_l"]).lock("c_finger", 0.3).apply(&model).unwrap();
    assert_eq!(merged.joint_names(), ["a_shoulder", "b_elbow"]);
    let at = |j: &str| merged.fixed_joints.iter().find(|(n, _)| n == j).map(|(_, q)| *q);
    assert_eq!(at("d_tip_l"), Some(-0.75 * 0.3 + 0.2));
}

/// Every function code generation makes of a model with mimic joints, as
/// traced (the emitted arithmetic, evaluated), against the generic solver:
/// the contract's five, coriolis, the derivatives, a frame's pose and
/// Jacobian, in f64 and f32; a scene's; a floating base's. Sines and cosines given by the caller cannot hold a mimic
/// joint's own angle: refused, naming the option.
#[test]
fn every_generated_function_of_a_mimic_model_is_the_generic_one() {
    use dynagen::codegen::{generate_scene, ForwardDynamicsMethod, ScalarType, Trig};
    use dynagen::scene::{Scene, SceneRobot};
    let rows = |m: DMatrix<f64>| m.transpose().as_slice().to_vec();
    let mut all = vec![
        Function::InverseDynamics,
        Function::MassMatrix,
        Function::BiasForces,
        Function::GravityTorques,
        Function::ForwardDynamics,
        Function::Coriolis,
        Function::InverseDynamicsDerivatives,
        Function::ForwardDynamicsDerivatives,
        Function::MassMatrixInverse,
    ];
    for robot in ["gripper", "panda"] {
        let model = mimic_model(robot);
        let frame = model.frames.last().unwrap().name.clone();
        all.truncate(9);
        all.extend([
            Function::FramePose(frame.clone()),
            Function::FrameJacobian(frame.clone()),
            Function::FrameWorldJacobian(frame.clone()),
            Function::FrameAccelerationBias(frame.clone()),
        ]);
        let mut generic = Robot::new(model.clone());
        let n = model.dof();
        let mut rng = support::Rng::new(0x6e6e);
        let (q, qd, x) = (rng.vec(n, 2.0), rng.vec(n, 1.5), rng.vec(n, 5.0));
        let v = |a: &Vec<f64>| DVector::from_vec(a.clone());
        let mut want = |f: &Function| -> Vec<f64> {
            let r = &mut generic;
            match f {
                Function::InverseDynamics => r.inverse_dynamics(&v(&q), &v(&qd), &v(&x)).unwrap().as_slice().to_vec(),
                Function::MassMatrix => rows(r.mass_matrix(&v(&q)).unwrap()),
                Function::BiasForces => r.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
                Function::GravityTorques => r.gravity_torques(&v(&q)).unwrap().as_slice().to_vec(),
                Function::ForwardDynamics => r.forward_dynamics(&v(&q), &v(&qd), &v(&x)).unwrap().as_slice().to_vec(),
                Function::Coriolis => r.coriolis_torques(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
                Function::InverseDynamicsDerivatives => {
                    let (a, b) = r.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
                    [rows(a), rows(b)].concat()
                }
                Function::ForwardDynamicsDerivatives => {
                    let (a, b, c) = r.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&x)).unwrap();
                    [rows(a), rows(b), rows(c)].concat()
                }
                Function::MassMatrixInverse => rows(r.mass_matrix_inverse(&v(&q)).unwrap()),
                Function::FramePose(name) => r.frame_pose(name, &v(&q)).unwrap().transpose().as_slice().to_vec(),
                Function::FrameJacobian(name) => r.body_jacobian(name, &v(&q)).unwrap().transpose().as_slice().to_vec(),
                Function::FrameWorldJacobian(name) => {
                    r.space_jacobian(name, &v(&q)).unwrap().transpose().as_slice().to_vec()
                }
                Function::FrameAccelerationBias(name) => {
                    r.frame_acceleration_bias(name, &v(&q), &v(&qd)).unwrap().as_slice().to_vec()
                }
            }
        };
        let inputs: [(&str, &[f64]); 4] = [("q", &q), ("qd", &qd), ("qdd", &x), ("tau", &x)];
        // (the trace is the same whatever the trigonometry: tests/tests/generated_mimic.rs
        // compiles the batched and std's)
        for (scalar, tol) in [(ScalarType::F64, 1e-12), (ScalarType::F32, 1e-4)] {
            let options = CodegenOptions::default().functions(all.clone()).scalar(scalar);
            let module = generate(&model, &options).unwrap();
            for f in module.functions.iter().filter(|f| f.emitted) {
                let got: Vec<f64> = match scalar {
                    ScalarType::F32 => f.traced.eval_as::<f32>(&inputs).unwrap().into_iter().map(f64::from).collect(),
                    ScalarType::F64 => f.traced.eval(&inputs).unwrap(),
                };
                let e = support::norm_rel_err(&got, &want(&f.function), 1e-300);
                assert!(e <= tol, "{robot} {scalar:?}: {} relative error {e:e}", f.label());
            }
        }
        // the caller's sines and cosines: the Panda's mimic finger is prismatic, the gripper's joints turn
        let inputs = generate(&model, &CodegenOptions::default().trig(Trig::Inputs));
        match robot {
            "panda" => assert!(inputs.is_ok()),
            _ => assert!(inputs.unwrap_err().to_string().contains("trig inputs"), "the gripper with trig inputs"),
        }
        // ABA asked for by name
        let aba = generate(&model, &CodegenOptions::default().forward_dynamics(ForwardDynamicsMethod::Aba));
        assert!(aba.unwrap_err().to_string().contains("articulated-body algorithm (aba)"));
    }
    // a scene: armature and friction on the gripper's master, a lock
    let model = mimic_model("gripper");
    let scene =
        Scene::new().armature("c_finger", 0.05).coulomb("c_finger", 0.3).lock("h_cam", 0.2).apply(&model).unwrap();
    let module = generate_scene(&scene, &CodegenOptions::default()).unwrap();
    let mut generic = SceneRobot::new(scene);
    let state = [vec![0.3, -0.4, 0.8], vec![1.0, 0.5, -2.0], vec![3.0, -1.0, 2.0]];
    traced_five(&module, &state, "gripper scene", |f, [q, qd, x]| five!(generic, f, q, qd, x));
    // a floating base
    for robot in ["panda", "gripper"] {
        let model = floating(mimic_model(robot));
        let module = generate(&model, &CodegenOptions::default()).unwrap();
        let mut generic = Robot::new(model.clone());
        let mut rng = support::Rng::new(0xf10a);
        let mut q = rng.vec(model.nq(), 1.0);
        support::normalize_quaternion(&mut q);
        let state = [q, rng.vec(model.nv(), 1.5), rng.vec(model.nv(), 5.0)];
        traced_five(&module, &state, &format!("floating {robot}"), |f, [q, qd, x]| five!(generic, f, q, qd, x));
    }
}

/// The contract's five functions of a `Robot` or `SceneRobot` at (q, q̇, x),
/// x being q̈ or τ, M row-major.
macro_rules! five {
    ($robot:expr, $f:expr, $q:expr, $qd:expr, $x:expr) => {{
        let v = |a: &[f64]| DVector::from_column_slice(a);
        match $f {
            Function::InverseDynamics => $robot.inverse_dynamics(&v($q), &v($qd), &v($x)).unwrap(),
            Function::BiasForces => $robot.bias_forces(&v($q), &v($qd)).unwrap(),
            Function::GravityTorques => $robot.gravity_torques(&v($q)).unwrap(),
            Function::ForwardDynamics => $robot.forward_dynamics(&v($q), &v($qd), &v($x)).unwrap(),
            _ => DVector::from_column_slice($robot.mass_matrix(&v($q)).unwrap().transpose().as_slice()),
        }
    }};
}
use five;

/// Each emitted function of `module` as traced, at `state` = (q, q̇, x),
/// against `want` within 1e-12.
fn traced_five(
    module: &dynagen::codegen::GeneratedModule,
    state: &[Vec<f64>; 3],
    tag: &str,
    mut want: impl FnMut(&Function, [&[f64]; 3]) -> DVector<f64>,
) {
    let [q, qd, x] = state;
    for f in module.functions.iter().filter(|f| f.emitted) {
        let got = f.traced.eval(&[("q", q), ("qd", qd), ("qdd", x), ("tau", x)]).unwrap();
        let e = support::norm_rel_err(&got, want(&f.function, [q, qd, x]).as_slice(), 1e-300);
        assert!(e <= 1e-12, "{tag}: {} relative error {e:e}", f.label());
    }
}

/// The `<mimic>` element as the raw-XML check reads it: the master's name
/// required, multiplier and offset whole finite numbers (urdf-rs would keep
/// what parses of "2x"), one element per joint; errors name the joint.
#[test]
fn the_mimic_element_is_checked_in_the_xml() {
    let inertial = r#"<inertial><mass value="1"/><origin xyz="0 0 0.1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>"#;
    let xml = |mimic: &str| {
        format!(
            r#"<robot name="r"><link name="base"/><link name="a">{inertial}</link><link name="b">{inertial}</link>
            <joint name="lead" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
            <joint name="follow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>{mimic}</joint></robot>"#
        )
    };
    let err = |mimic: &str| Model::from_urdf_str(&xml(mimic)).unwrap_err().to_string();
    assert_eq!(
        err(r#"<mimic joint="lead" multiplier="2x"/>"#),
        "joint \"follow\": cannot read mimic multiplier from \"2x\""
    );
    assert_eq!(err(r#"<mimic joint="lead" offset="nan"/>"#), "joint \"follow\": cannot read mimic offset from \"nan\"");
    assert_eq!(err(r#"<mimic multiplier="2"/>"#), "malformed URDF: joint \"follow\": <mimic> has no joint attribute");
    assert_eq!(err(r#"<mimic joint=""/>"#), "malformed URDF: joint \"follow\": <mimic> has an empty joint attribute");
    assert_eq!(
        err(r#"<mimic joint="lead"/><mimic joint="lead"/>"#),
        "malformed URDF: joint \"follow\" has more than one <mimic>"
    );
    assert_eq!(err(r#"<mimic joint="leed"/>"#), "joint \"follow\" (mimic): its master joint \"leed\" does not exist");
    // URDF's defaults: multiplier 1, offset 0
    let m = Model::from_urdf_str(&xml(r#"<mimic joint="lead"/>"#)).unwrap();
    assert_eq!(m.mimic(1).map(|c| (c.master, c.multiplier, c.offset)), Some((0, 1.0, 0.0)));
    let m = Model::from_urdf_str(&xml(r#"<mimic joint="lead" multiplier="-0.5" offset="0.25"/>"#)).unwrap();
    assert_eq!(m.mimic(1).map(|c| (c.multiplier, c.offset)), Some((-0.5, 0.25)));
    // a master and follower that move nothing together are refused, naming both
    let massless = r#"<robot name="r"><link name="base"/><link name="a"/><link name="b"/>
        <joint name="lead" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
        <joint name="follow" type="continuous"><parent link="base"/><child link="b"/><axis xyz="0 1 0"/><mimic joint="lead"/></joint></robot>"#;
    let e = Model::from_urdf_str(massless).unwrap_err().to_string();
    assert!(e.contains("joint \"lead\"") && e.contains("\"follow\"") && e.contains("<inertial>"), "{e}");
}

/// The names of a master and of its mimic joint reach the header's list of
/// couplings escaped, like every name from a robot file: a newline, a
/// carriage return or a line separator in them ends no comment.
#[test]
fn mimic_names_in_the_header_are_escaped() {
    let body = Some(dynagen::model::Inertial::new(0.5, [0.0, 0.0, 0.1], [0.01, 0.01, 0.01, 0.0, 0.0, 0.0]));
    let (master, follower) = ("m\npub fn injected() -> u32 { 42 }\n//", "f\r\u{2028}*/\"\\");
    let model = dynagen::RobotBuilder::new("r")
        .link("base", None)
        .link("a", body)
        .link("b", body)
        .joint(JointDescription::revolute(master, "base", "a", [0.0, 0.0, 1.0]))
        .joint(JointDescription::revolute(follower, "base", "b", [0.0, 1.0, 0.0]).mimic(master, 2.0, 0.5))
        .build()
        .unwrap();
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    let header: Vec<&str> = module.source.lines().take_while(|l| l.starts_with("//")).collect();
    let line = header.iter().find(|l| l.contains("= 2.0 *")).expect("the coupling's line");
    assert!(line.contains(r"\u{a}") && line.contains(r"\u{d}") && line.contains(r"\u{2028}"), "{line}");
    assert!(!module.source.contains("\npub fn injected"));
}

/// A master below the joint that follows it, and a master on one branch
/// followed on another: τ and M are the full tree's projected, and forward
/// dynamics (LᵀDL along M's elimination tree, which these patterns fill in)
/// inverts them.
#[test]
fn masters_below_and_beside_their_followers() {
    use dynagen::model::{Inertial, RobotBuilder};
    let body = |m: f64| Some(Inertial::new(m, [0.05, 0.02, 0.1], [0.01, 0.02, 0.015, 0.001, 0.0, 0.002]));
    let robot = |mimic: MimicJoints| {
        RobotBuilder::new("r")
            .link("base", None)
            .link("a", body(1.0))
            .link("b", body(0.7))
            .link("c", body(0.5))
            .link("d", body(0.3))
            .joint(JointDescription::revolute("up", "base", "a", [0.0, 0.0, 1.0]).mimic("low", -0.5, 0.3))
            .joint(JointDescription::revolute("low", "a", "b", [0.0, 1.0, 0.0]).origin([0.0, 0.0, 0.3], [0.0; 3]))
            .joint(JointDescription::revolute("side", "base", "c", [1.0, 0.0, 0.0]).origin([0.2, 0.0, 0.0], [0.0; 3]))
            .joint(JointDescription::prismatic("far", "c", "d", [0.0, 0.6, 0.8]).mimic("low", 0.1, 0.0))
            .mimic_joints(mimic)
            .build()
            .unwrap()
    };
    let (model, full) = (robot(MimicJoints::Follow), robot(MimicJoints::Independent));
    assert_eq!(model.joint_names(), ["low", "side"]);
    let (mut ours, mut theirs) = (Robot::new(model), Robot::new(full));
    let g = DMatrix::from_row_slice(4, 2, &[-0.5, 0.0, 1.0, 0.0, 0.0, 1.0, 0.1, 0.0]);
    let o = DVector::from_vec(vec![0.3, 0.0, 0.0, 0.0]);
    let (q, qd, qdd) =
        (DVector::from_vec(vec![0.7, -0.4]), DVector::from_vec(vec![1.1, 0.6]), DVector::from_vec(vec![-2.0, 3.0]));
    let qf = &g * &q + &o;
    let col = |v: DVector<f64>| DMatrix::from_column_slice(v.len(), 1, v.as_slice());
    let tau = ours.inverse_dynamics(&q, &qd, &qdd).unwrap();
    let want = g.transpose() * col(theirs.inverse_dynamics(&qf, &(&g * &qd), &(&g * &qdd)).unwrap());
    assert!(max_diff(&col(tau.clone()), &want) <= 1e-14);
    let m = ours.mass_matrix(&q).unwrap();
    assert!(max_diff(&m, &(g.transpose() * theirs.mass_matrix(&qf).unwrap() * &g)) <= 1e-14);
    assert!(m[(0, 1)] != 0.0, "the branches share an entry through the mimic joints");
    let back = ours.forward_dynamics(&q, &qd, &tau).unwrap();
    assert!(max_diff(&col(back), &col(qdd)) <= 1e-12);
}

/// A scene on a floating base with mimic joints: armature on the master
/// finger and a locked wrist. Its τ is the plain floating robot's (the
/// wrist held where it is locked) plus the armature term, and its forward
/// dynamics inverts it.
#[test]
fn a_floating_scene_with_mimic_joints() {
    use dynagen::scene::{Scene, SceneRobot};
    let model = floating(mimic_model("panda"));
    let scene = Scene::new().armature("panda_finger_joint1", 0.1).lock("panda_joint7", 0.2).apply(&model).unwrap();
    assert!(scene.model.is_floating() && scene.model.has_mimic());
    assert_eq!(scene.model.nv(), 6 + 7);
    let (mut s, mut plain) = (SceneRobot::new(scene), Robot::new(model.clone()));
    let mut rng = support::Rng::new(0x5ce4e);
    let mut q = DVector::from_vec(rng.vec(7 + 7, 1.0));
    let norm = q.rows(3, 4).norm();
    q.rows_mut(3, 4).unscale_mut(norm);
    q[13] = 0.02; // the finger, in its range
    let (qd, qdd) = (DVector::from_vec(rng.vec(13, 1.0)), DVector::from_vec(rng.vec(13, 3.0)));
    let tau = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
    // the plain robot with the wrist at 0.2, still
    let ins = |v: &DVector<f64>, at: usize, x: f64| {
        DVector::from_iterator(v.len() + 1, v.iter().take(at).chain([x].iter()).chain(v.iter().skip(at)).copied())
    };
    let (pq, pqd, pqdd) = (ins(&q, 13, 0.2), ins(&qd, 12, 0.0), ins(&qdd, 12, 0.0));
    let full = plain.inverse_dynamics(&pq, &pqd, &pqdd).unwrap();
    let mut want = DVector::from_iterator(13, full.iter().take(12).chain(full.iter().skip(13)).copied());
    want[12] += 0.1 * qdd[12];
    assert!(rel_err(tau.as_slice(), want.as_slice(), 1e-9) <= 1e-13, "{tau} against {want}");
    let back = s.forward_dynamics(&q, &qd, &tau).unwrap();
    assert!(rel_err(back.as_slice(), qdd.as_slice(), 1e-9) <= 1e-10, "{back} against {qdd}");
}
