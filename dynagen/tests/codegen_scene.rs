//! Scene modules ([`generate_scene`]) against the generic solver under the
//! same scene ([`SceneRobot`]): every function of every option, evaluated by
//! the graph interpreter on random states (what the emitted code computes,
//! `tests/tests/generated_scene.rs` compiles two of them), and the
//! operation count of each option against the full scene's.

use dynagen::codegen::{generate_scene, CodegenOptions, GeneratedModule};
use dynagen::scene::{
    Function, Gravity, PayloadInertia, ResolvedGravity, ScalarType, Scene, SceneInputs, SceneModel, SceneRobot, Target,
};
use dynagen::Model;
use nalgebra::{DVector, Vector3, Vector6};

/// A small deterministic generator (xorshift64*), uniform in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vec(&mut self, n: usize, scale: f64) -> Vec<f64> {
        (0..n).map(|_| scale * self.next()).collect()
    }
    /// A physical payload: mass in [0.5, 1.5] kg, centre of mass within
    /// 10 cm, a positive diagonal inertia with a small product.
    fn payload(&mut self) -> PayloadInertia {
        let d = [2e-3 + 2e-4 * self.next(), 2e-3 + 2e-4 * self.next(), 1.5e-3 + 2e-4 * self.next()];
        PayloadInertia::new(
            1.0 + 0.5 * self.next(),
            [0.1 * self.next(), 0.1 * self.next(), 0.1 * self.next()],
            [d[0], d[1], d[2], 1e-5 * self.next(), 0.0, 0.0],
        )
    }
}

fn ur5() -> Model {
    Model::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf")).unwrap()
}

fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    let norm = want.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
    let diff = got.iter().zip(want).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
    diff / norm
}

/// Row-major entries of an nalgebra matrix.
fn rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Vec<f64> {
    (0..m.nrows()).flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)])).collect()
}

/// Generates `scene` for `model`, and checks every function against
/// [`SceneRobot`] on `states` random states (f64 graph evaluation within
/// `tol`, or f32 evaluation within `tol` when the scene is f32).
fn check(model: &Model, scene: &Scene, states: usize, tol: f64) -> (SceneModel, GeneratedModule) {
    let applied = scene.apply(model).unwrap();
    let module = generate_scene(&applied, &CodegenOptions::default()).unwrap();
    let mut robot = SceneRobot::new(applied.clone());
    let n = applied.dof();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let f32 = applied.scalar == ScalarType::F32;
    for _ in 0..states {
        let (q, qd, qdd, tau) = (rng.vec(n, 3.0), rng.vec(n, 2.0), rng.vec(n, 5.0), rng.vec(n, 20.0));
        let gravity = [rng.next(), rng.next(), -9.81 + rng.next()];
        let f_tip = rng.vec(6, 10.0);
        let payloads: Vec<PayloadInertia> = applied.input_payloads.iter().map(|_| rng.payload()).collect();
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
        for f in &module.scene_functions {
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
                Function::FramePose(frame) => rows(&robot.frame_pose(frame, &dv(&q)).unwrap()),
                Function::FrameJacobian(frame) => rows(&robot.frame_jacobian(frame, &dv(&q)).unwrap()),
            };
            assert_eq!(got.len(), want.len(), "{}", f.name);
            let e = rel_err(&got, &want);
            // g(q) = 0 without gravity: compare absolutely.
            let e = if want.iter().all(|x| *x == 0.0) { got.iter().fold(0.0f64, |m, x| m.max(x.abs())) } else { e };
            assert!(e < tol, "{}: relative error {e:e}\n got {got:?}\nwant {want:?}", f.name);
        }
    }
    (applied, module)
}

fn ops(module: &GeneratedModule, name: &str) -> usize {
    module.scene_function(name).unwrap_or_else(|| panic!("no function {name}")).op_count.total()
}

const CONTRACT: [&str; 5] = ["inverse_dynamics", "mass_matrix", "bias_forces", "gravity_torques", "forward_dynamics"];

/// The full scene: the five functions plus coriolis and the end-effector's
/// pose and Jacobian.
fn full_scene() -> Scene {
    Scene::new()
        .function(Function::Coriolis)
        .function(Function::FramePose("ee_link".into()))
        .function(Function::FrameJacobian("ee_link".into()))
}

fn full_module() -> GeneratedModule {
    check(&ur5(), &full_scene(), 5, 1e-12).1
}

fn print(label: &str, module: &GeneratedModule) {
    let counts: Vec<String> =
        module.scene_functions.iter().map(|f| format!("{} {}", f.name, f.op_count.total())).collect();
    println!("{label:28} {}", counts.join(", "));
}

#[test]
fn measure() {
    let model = ur5();
    let full = full_module();
    print("full", &full);
    for (label, scene) in [
        ("gravity none", full_scene().gravity(Gravity::None)),
        ("gravity input", full_scene().gravity(Gravity::Input)),
        ("gravity tilted", full_scene().gravity(Gravity::Constant([1.0, -2.0, -9.0]))),
        ("tip wrench", full_scene().tip_wrench("ee_link")),
        ("subtree", full_scene().subtree("base_link", &["wrist_1_link"]).functions(Function::DEFAULT)),
        ("lock", full_scene().lock("wrist_3_joint", 0.3)),
        (
            "payload const",
            full_scene().payload(
                "ee_link",
                PayloadInertia::new(1.2, [0.0, 0.0, 0.06], [0.0018, 0.0018, 0.0012, 0.0, 0.0, 0.0]),
            ),
        ),
        ("payload input", full_scene().payload_input("ee_link")),
        ("armature", full_scene().armature("elbow_joint", 0.3)),
        ("viscous", full_scene().viscous("elbow_joint", 0.3)),
        ("coulomb", full_scene().coulomb("elbow_joint", 0.3)),
        ("f32", full_scene().scalar(ScalarType::F32)),
    ] {
        let tol = if label == "f32" { 1e-5 } else { 1e-12 };
        let (_, m) = check(&model, &scene, 5, tol);
        print(label, &m);
    }
    let _ = (CONTRACT, Target::Std);
}
