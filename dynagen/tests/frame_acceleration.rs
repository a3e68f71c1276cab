//! The frame functions (pose, body and world Jacobians, classical
//! acceleration bias J̇q̇) on fixed and floating bases, against finite
//! differences that share no code with them: along the motion q(t) = q ⊕
//! t·q̇ (the base by the exponential map of its body twist, so q̈ = 0), the
//! body Jacobian's rate times q̇ is the spatial part of J̇q̇, and the frame
//! origin's second derivative in the world is its rotation times J̇q̇'s
//! linear part. The generated frame functions (their traces as emitted)
//! against the generic solver. Pinocchio's values for the legged
//! manipulator's contact frames are in `tests/floating_pinocchio.rs`.

mod support;

use dynagen::algorithms::floating;
use dynagen::codegen::{generate, CodegenOptions, Function};
use dynagen::{Model, Robot};
use nalgebra::{DVector, Vector3, Vector6};
use support::{rel_err, Rng};

/// q ⊕ dv: the base by the exponential map, joints by addition.
fn step(model: &Model, q: &DVector<f64>, dv: &DVector<f64>) -> DVector<f64> {
    if !model.is_floating() {
        return q + dv;
    }
    let mut out = vec![0.0; q.len()];
    floating::integrate(model, q.as_slice(), dv.as_slice(), &mut out);
    DVector::from_vec(out)
}

/// A random state: q (a unit quaternion on a floating base), q̇ of norm
/// `speed`.
fn state(model: &Model, rng: &mut Rng, speed: f64) -> (DVector<f64>, DVector<f64>) {
    let mut q = DVector::from_vec(rng.vec(model.nq(), 2.0));
    if model.is_floating() {
        let norm = q.rows(3, 4).norm();
        q.rows_mut(3, 4).iter_mut().for_each(|x| *x /= norm);
    }
    let qd = DVector::from_vec(rng.vec(model.nv(), 1.0));
    let norm = qd.norm();
    (q, qd * (speed / norm))
}

fn models() -> Vec<Model> {
    vec![
        support::model("legged_manipulator").with_floating_base(),
        support::model("torso_two_arms").with_floating_base(),
        support::model("ur5"),
        support::model("panda"),
    ]
}

/// J̇q̇ of every frame against central differences of the body Jacobian
/// and of the frame's world position along q ⊕ t·q̇.
#[test]
fn acceleration_bias_is_the_rate_of_the_jacobian_and_the_points_acceleration() {
    let mut worst = [0.0f64; 2];
    for model in models() {
        let mut robot = Robot::new(model.clone());
        let mut rng = Rng::new(13);
        for _ in 0..3 {
            let (q, qd) = state(&model, &mut rng, 3.0);
            for frame in model.frames.iter().map(|f| f.name.clone()) {
                let bias = robot.frame_acceleration_bias(&frame, &q, &qd).unwrap();
                let twist = robot.body_jacobian(&frame, &q).unwrap() * &qd;
                let (w, v) = (twist.fixed_rows::<3>(0), twist.fixed_rows::<3>(3));
                // the spatial part: the classical one less (0; ω × v)
                let mut spatial = bias;
                let wv = w.cross(&v);
                for k in 0..3 {
                    spatial[3 + k] -= wv[k];
                }
                let h = 1e-5;
                let mut at = |t: f64| {
                    let qt = step(&model, &q, &(&qd * t));
                    let jqd: Vector6<f64> = robot.body_jacobian(&frame, &qt).unwrap() * &qd;
                    let p = robot.frame_pose(&frame, &qt).unwrap();
                    (jqd, Vector3::new(p[(0, 3)], p[(1, 3)], p[(2, 3)]))
                };
                let ((jp, pp), (j0, p0), (jm, pm)) = (at(h), at(0.0), at(-h));
                let rate = (jp - jm) / (2.0 * h);
                let e = rel_err(spatial.as_slice(), rate.as_slice(), 1.0);
                assert!(e < 1e-7, "{} {frame}: J̇q̇ against d/dt (J q̇): {e:e}", model.name);
                assert!(rel_err(j0.as_slice(), twist.as_slice(), 1.0) < 1e-14);
                let accel = (pp - 2.0 * p0 + pm) / (h * h);
                let r = robot.frame_pose(&frame, &q).unwrap().fixed_view::<3, 3>(0, 0).clone_owned();
                let want = r * bias.fixed_rows::<3>(3);
                let e2 = rel_err(accel.as_slice(), want.as_slice(), 1.0);
                assert!(e2 < 1e-4, "{} {frame}: the origin's acceleration {e2:e}", model.name);
                worst = [worst[0].max(e), worst[1].max(e2)];
            }
        }
    }
    println!("J̇q̇ against central differences: of J q̇ {:.1e}, of the origin's position {:.1e}", worst[0], worst[1]);
}

/// The base-frame pose and Jacobian of a floating robot are the world ones
/// seen from the base; on a fixed base all three coincide.
#[test]
fn base_frame_pose_and_jacobian_are_the_world_ones_seen_from_the_base() {
    for model in models() {
        let mut robot = Robot::new(model.clone());
        let mut rng = Rng::new(17);
        let (q, _) = state(&model, &mut rng, 0.0);
        let base = robot.frame_pose(&model.root, &q).unwrap();
        let inv = base.try_inverse().unwrap();
        for frame in ["arm_ee", "RR_foot", "right_ee", "ee_link", "panda_hand"] {
            if model.frame_index(frame).is_none() {
                continue;
            }
            let world = robot.frame_pose(frame, &q).unwrap();
            let in_base = robot.frame_pose_in_base(frame, &q).unwrap();
            assert!(rel_err((inv * world).as_slice(), in_base.as_slice(), 1.0) < 1e-13, "{frame}");
            // the world Jacobian's twist at the world origin, moved to the base origin in base axes
            let js = robot.space_jacobian(frame, &q).unwrap();
            let jb = robot.base_jacobian(frame, &q).unwrap();
            let (r, p) = (base.fixed_view::<3, 3>(0, 0), base.fixed_view::<3, 1>(0, 3));
            for k in 0..model.nv() {
                let (w, v) = (js.fixed_view::<3, 1>(0, k), js.fixed_view::<3, 1>(3, k));
                let (wb, vb) = (r.transpose() * w, r.transpose() * (v + w.cross(&p)));
                let got: Vec<f64> = jb.column(k).iter().copied().collect();
                let want: Vec<f64> = wb.iter().chain(vb.iter()).copied().collect();
                assert!(rel_err(&got, &want, 1.0) < 1e-13, "{} {frame} column {k}", model.name);
            }
        }
    }
}

/// Every frame function of a fixed-base and a floating-base module, as
/// emitted (fused and not), against the generic solver.
#[test]
fn generated_frame_functions_match_the_generic_solver() {
    for (model, frames) in
        [(models().remove(0), ["FL_foot", "arm_ee"]), (models().remove(2), ["ee_link", "wrist_2_link"])]
    {
        let functions: Vec<Function> = frames
            .iter()
            .flat_map(|f| Function::FRAME_KINDS.iter().map(|k| Function::frame_function(k, f).unwrap()))
            .collect();
        let module = generate(&model, &CodegenOptions::default().functions(functions)).unwrap();
        let mut robot = Robot::new(model.clone());
        let mut rng = Rng::new(19);
        for _ in 0..5 {
            let (q, qd) = state(&model, &mut rng, 20.0);
            let rows = |m: nalgebra::Matrix6xX<f64>| m.transpose().as_slice().to_vec();
            for f in &module.functions {
                let frame = f.function.frame().unwrap();
                let want: Vec<f64> = match &f.function {
                    Function::FramePose(_) => robot.frame_pose(frame, &q).unwrap().transpose().as_slice().to_vec(),
                    Function::FrameJacobian(_) => rows(robot.body_jacobian(frame, &q).unwrap()),
                    Function::FrameWorldJacobian(_) => rows(robot.space_jacobian(frame, &q).unwrap()),
                    _ => robot.frame_acceleration_bias(frame, &q, &qd).unwrap().as_slice().to_vec(),
                };
                let inputs: Vec<(&str, &[f64])> = vec![("q", q.as_slice()), ("qd", qd.as_slice())];
                for got in [f.traced.eval(&inputs).unwrap(), f.traced.eval_fused(&f.traced.fusion(), &inputs).unwrap()]
                {
                    let e = rel_err(&got, &want, 1.0);
                    assert!(e < 1e-13, "{} {}: {e:e}", model.name, f.name);
                }
            }
        }
    }
}

/// The frame functions' spellings: `KIND:FRAME` in a list of functions
/// (the command line, the Builder, the macros), one TOML key a kind; the
/// Rust names; an unknown kind's error lists every spelling.
#[test]
fn frame_function_names_parse_and_round_trip() {
    use dynagen::scene::SceneFile;
    let f: Function = "frame_acceleration_bias: FL_foot".parse().unwrap();
    assert_eq!(f, Function::FrameAccelerationBias("FL_foot".into()));
    assert_eq!(f.rust_name(), "frame_acceleration_bias_fl_foot");
    assert_eq!(f.vectors(), ["q", "qd"]);
    let w: Function = "frame_world_jacobian:arm_ee".parse().unwrap();
    assert_eq!((w.rust_name().as_str(), w.frame()), ("frame_world_jacobian_arm_ee", Some("arm_ee")));
    let e = "frame_velocity:arm_ee".parse::<Function>().unwrap_err();
    assert!(e.contains("frame_world_jacobian:FRAME, frame_acceleration_bias:FRAME"), "{e}");
    let text = "frame_world_jacobian = [\"arm_ee\"]\nframe_acceleration_bias = [\"FL_foot\", \"RR_foot\"]\n";
    let file = SceneFile::from_toml_str(text).unwrap();
    let functions = file.code.functions.clone().unwrap();
    assert_eq!(&functions[..5], &Function::DEFAULT);
    assert_eq!(functions[5..], [w.clone(), f, Function::FrameAccelerationBias("RR_foot".into())]);
    assert_eq!(SceneFile::from_toml_str(&file.to_toml_string().unwrap()).unwrap(), file);
    let model = support::model("ur5");
    let built = dynagen::Builder::new()
        .model(model)
        .functions(&["frame_acceleration_bias:ee_link", "frame_world_jacobian:ee_link"])
        .generate_module()
        .unwrap()
        .source;
    assert!(built.contains("pub fn frame_acceleration_bias_ee_link(q: &[f64; DOF], qd: &[f64; DOF]) -> [f64; 6]"));
    assert!(built.contains("pub fn frame_world_jacobian_ee_link(q: &[f64; DOF]) -> [[f64; DOF]; 6]"));
}
