//! The floating base (issue 17): random floating trees (revolute,
//! prismatic and fixed joints, non-aligned axes, rotated placements) with
//! random unit quaternions and |q̇| up to 50, checked against identities
//! that do not share our code: ID(FD(τ)) = τ, two forward dynamics,
//! M by unit accelerations, the whole robot's momentum balance, Newton–
//! Euler of a single rigid body in closed form, Jacobians against finite
//! differences on SE(3), the fixed-base model with the base held, energy
//! and momentum conservation; and the URDF `floating` root and its errors.

mod support;

use approx::abs_diff_eq;
use dynagen::algorithms::floating::{
    self, aba::aba, centroidal, crba::crba, forward_dynamics, kinematics as fk, rnea::rnea,
};
use dynagen::algorithms::{crba as fixed_crba, rnea as fixed_rnea, Loads, Workspace};
use dynagen::spatial::{Force, Motion, Transform, Vec3};
use dynagen::{Model, ModelError};
use nalgebra::{DMatrix, DVector};
use std::fmt::Write;
use support::{norm_rel_err, rel_err, scale, Rng};

const G: [f64; 3] = [0.0, 0.0, -9.81];

/// A random tree of `n` moving joints (and a few fixed ones) below a base
/// with a random inertia, as URDF text; `floating_joint` adds a world link
/// and a `floating` joint above the base.
fn random_urdf(rng: &mut Rng, n: usize, floating_joint: bool) -> String {
    let inertial = |rng: &mut Rng| {
        let m = 0.5 + 3.0 * rng.unit();
        // principal moments that satisfy the triangle inequality, rotated
        let (a, b) = (0.02 + 0.1 * rng.unit(), 0.02 + 0.1 * rng.unit());
        let c = (a - b).abs() + 0.01 + 0.05 * rng.unit();
        format!(
            "<inertial><origin xyz=\"{} {} {}\" rpy=\"{} {} {}\"/><mass value=\"{m}\"/>\
             <inertia ixx=\"{a}\" iyy=\"{b}\" izz=\"{c}\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>",
            0.1 * rng.signed(),
            0.1 * rng.signed(),
            0.1 * rng.signed(),
            rng.signed() * 3.0,
            rng.signed() * 1.5,
            rng.signed() * 3.0
        )
    };
    let mut x = String::from("<robot name=\"random_floating\">");
    if floating_joint {
        x.push_str(
            "<link name=\"world\"/><joint name=\"root\" type=\"floating\"><parent link=\"world\"/>\
             <child link=\"base\"/></joint>",
        );
    }
    let _ = write!(x, "<link name=\"base\">{}</link>", inertial(rng));
    let mut links = vec!["base".to_string()];
    for k in 0..n + n / 3 {
        let parent = links[(rng.bits() as usize) % links.len()].clone();
        let kind = match rng.bits() % 5 {
            _ if k >= n => "fixed",
            0..=2 => "revolute",
            3 => "continuous",
            _ => "prismatic",
        };
        let axis = match rng.bits() % 3 {
            0 => "0 0 1".to_string(),
            1 => "1 0 0".to_string(),
            _ => format!("{} {} {}", rng.signed(), rng.signed(), rng.signed() + 1.5),
        };
        let name = format!("l{k}");
        let _ = write!(
            x,
            "<link name=\"{name}\">{}</link><joint name=\"j{k}\" type=\"{kind}\"><parent link=\"{parent}\"/>\
             <child link=\"{name}\"/><origin xyz=\"{} {} {}\" rpy=\"{} {} {}\"/><axis xyz=\"{axis}\"/>\
             <limit lower=\"-10\" upper=\"10\" effort=\"100\" velocity=\"100\"/></joint>",
            inertial(rng),
            0.3 * rng.signed(),
            0.3 * rng.signed(),
            0.3 * rng.signed(),
            rng.signed(),
            rng.signed(),
            rng.signed()
        );
        links.push(name);
    }
    x.push_str("</robot>");
    x
}

fn random_model(seed: u64, n: usize) -> Model {
    let mut rng = Rng::new(seed);
    Model::from_urdf_str(&random_urdf(&mut rng, n, false)).unwrap().with_floating_base()
}

/// A random configuration with a random unit quaternion, and a velocity of
/// norm up to `speed`.
fn random_state(model: &Model, rng: &mut Rng, speed: f64) -> (Vec<f64>, Vec<f64>) {
    let mut q = rng.vec(model.nq(), 2.0);
    let quat = rng.vec(4, 1.0);
    let norm = quat.iter().map(|x| x * x).sum::<f64>().sqrt();
    for k in 0..4 {
        q[3 + k] = quat[k] / norm;
    }
    let qd = rng.vec(model.nv(), 1.0);
    let s = speed * rng.unit() / qd.iter().map(|x| x * x).sum::<f64>().sqrt();
    (q, qd.iter().map(|x| x * s).collect())
}

fn mass_matrix(model: &Model, ws: &mut Workspace<f64>, q: &[f64]) -> DMatrix<f64> {
    let nv = model.nv();
    let mut m = vec![0.0; nv * nv];
    crba(model, ws, q, Loads::none(), &mut m);
    DMatrix::from_row_slice(nv, nv, &m)
}

fn tau_of(model: &Model, ws: &mut Workspace<f64>, q: &[f64], qd: &[f64], qdd: &[f64], g: &Vec3<f64>) -> Vec<f64> {
    let mut tau = vec![0.0; model.nv()];
    rnea(model, ws, q, Some(qd), Some(qdd), Loads::gravity(g), &mut tau);
    tau
}

fn fd_aba(model: &Model, ws: &mut Workspace<f64>, q: &[f64], qd: &[f64], tau: &[f64], g: &Vec3<f64>) -> Vec<f64> {
    let mut qdd = vec![0.0; model.nv()];
    aba(model, ws, q, qd, tau, Loads::gravity(g), &mut qdd);
    qdd
}

const SEEDS: [u64; 6] = [3, 17, 99, 1234, 777, 4242];

#[test]
fn inverse_of_forward_dynamics_and_two_forward_dynamics_agree() {
    let g = Vec3(G);
    let mut worst = [0.0f64; 2];
    for (s, seed) in SEEDS.into_iter().enumerate() {
        let model = random_model(seed, 3 + 2 * s);
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 1);
        for _ in 0..10 {
            let (q, qd) = random_state(&model, &mut rng, 50.0);
            let tau = rng.vec(model.nv(), 20.0);
            let qdd = fd_aba(&model, &mut ws, &q, &qd, &tau, &g);
            let back = tau_of(&model, &mut ws, &q, &qd, &qdd, &g);
            // τ is compared with the size of the terms that make it
            let h = tau_of(&model, &mut ws, &q, &qd, &vec![0.0; model.nv()], &g);
            let size = scale(&h, scale(&tau, 1.0));
            let epsilon = 1e-10 * size;
            assert!(
                abs_diff_eq!(&back[..], &tau[..], epsilon = epsilon),
                "seed {seed}: ID(FD(τ)) {back:?} against τ {tau:?}"
            );
            worst[0] = worst[0].max(rel_err(&back, &tau, size));
            let mut ldlt = vec![0.0; model.nv()];
            forward_dynamics::forward_dynamics_ldlt(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut ldlt);
            let e = norm_rel_err(&ldlt, &qdd, 1.0);
            worst[1] = worst[1].max(e);
            assert!(e < 1e-9, "seed {seed}: ABA vs LᵀDL {e:e}");
        }
    }
    println!("worst ID(FD) {:e}, ABA vs LDLT {:e}", worst[0], worst[1]);
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_and_equals_unit_accelerations() {
    for (s, seed) in SEEDS.into_iter().enumerate() {
        let model = random_model(seed, 4 + 2 * s);
        let nv = model.nv();
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed * 7 + 1);
        let (q, _) = random_state(&model, &mut rng, 0.0);
        let m = mass_matrix(&model, &mut ws, &q);
        assert_eq!(m, m.transpose(), "M is symmetric exactly");
        assert!(m.clone().cholesky().is_some(), "M is positive definite");
        // column j: the inverse dynamics of q̈ = e_j, at rest, no gravity
        let zero = vec![0.0; nv];
        for j in 0..nv {
            let mut e = zero.clone();
            e[j] = 1.0;
            let mut col = vec![0.0; nv];
            rnea(&model, &mut ws, &q, Some(&zero), Some(&e), Loads::none(), &mut col);
            let want = m.column(j);
            let epsilon = 1e-13 * m.amax();
            assert!(
                abs_diff_eq!(&col[..], want.as_slice(), epsilon = epsilon),
                "seed {seed}: column {j} {col:?} against {want}"
            );
        }
        // the base block is the whole robot's composite inertia: its mass
        for k in 3..6 {
            let mass = centroidal::total_mass(&model);
            assert!((m[(k, k)] - mass).abs() < 1e-12 * mass, "M[{k}][{k}] = {} ≠ m = {mass}", m[(k, k)]);
        }
    }
}

/// The world pose of a configuration.
fn pose(q: &[f64]) -> Transform<f64> {
    floating::base_pose(q)
}

/// The configuration after the velocity-side step `dv`.
fn step(model: &Model, q: &[f64], dv: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; q.len()];
    floating::integrate(model, q, dv, &mut out);
    out
}

/// The whole robot's spatial momentum about the world origin, world axes.
fn world_momentum(model: &Model, ws: &mut Workspace<f64>, q: &[f64], qd: &[f64]) -> Force<f64> {
    let m = mass_matrix(model, ws, q);
    let hb = &m * DVector::from_column_slice(qd);
    let hb = Force::from_array([hb[0], hb[1], hb[2], hb[3], hb[4], hb[5]]);
    pose(q).force_to_parent(&hb)
}

#[test]
fn base_rows_are_the_rate_of_change_of_momentum_minus_the_weight() {
    let g = Vec3(G);
    for (s, seed) in SEEDS.into_iter().enumerate() {
        let model = random_model(seed, 3 + s);
        let nv = model.nv();
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 5);
        let (q, qd) = random_state(&model, &mut rng, 5.0);
        let qdd = rng.vec(nv, 5.0);
        let tau = tau_of(&model, &mut ws, &q, &qd, &qdd, &g);
        // d/dt of the world momentum by central differences along the
        // motion: q(t ± δ) by the exponential map of ±δ q̇ + δ²/2 q̈
        let d = 1e-4;
        let at = |sign: f64, ws: &mut Workspace<f64>| {
            let dv: Vec<f64> = (0..nv).map(|k| sign * d * qd[k] + 0.5 * d * d * qdd[k]).collect();
            let qs = step(&model, &q, &dv);
            let qds: Vec<f64> = (0..nv).map(|k| qd[k] + sign * d * qdd[k]).collect();
            world_momentum(&model, ws, &qs, &qds)
        };
        let rate = (at(1.0, &mut ws) - at(-1.0, &mut ws)).scale(0.5 / d);
        let rate_base = pose(&q).force_to_child(&rate);
        // the weight's wrench on the base: m g at the centre of mass
        let c = centroidal::center_of_mass(&model, &mut ws, &q);
        let mass = centroidal::total_mass(&model);
        let weight_world = Force::new(c.cross(&g.scale(mass)), g.scale(mass));
        let want = rate_base - pose(&q).force_to_child(&weight_world);
        let want = want.to_array();
        let epsilon = 1e-6 * scale(&want, 1.0);
        assert!(
            abs_diff_eq!(&tau[..6], &want[..], epsilon = epsilon),
            "seed {seed}: base rows {:?} against the momentum balance {want:?}",
            &tau[..6]
        );
        // g's base rows hold the weight: minus its wrench
        let mut gv = vec![0.0; nv];
        dynagen::algorithms::bias::gravity_torques(&model, &mut ws, &q, &g, &mut gv);
        let hold = -pose(&q).force_to_child(&weight_world);
        let hold = hold.to_array();
        let epsilon = 1e-13 * scale(&hold, mass * 9.81);
        assert!(
            abs_diff_eq!(&gv[..6], &hold[..], epsilon = epsilon),
            "seed {seed}: g's base rows {:?} against the weight {hold:?}",
            &gv[..6]
        );
    }
}

#[test]
fn locked_joints_make_one_rigid_body() {
    let g = Vec3(G);
    for seed in SEEDS {
        let model = random_model(seed, 6);
        let nv = model.nv();
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 11);
        let (q, mut qd) = random_state(&model, &mut rng, 20.0);
        let mut qdd = rng.vec(nv, 10.0);
        for k in 6..nv {
            qd[k] = 0.0;
            qdd[k] = 0.0;
        }
        // Newton–Euler of one body with the composite inertia I:
        // w = I(a − (0; Rᵀg)) + v ×* I v
        let m = mass_matrix(&model, &mut ws, &q);
        let inertia = m.view((0, 0), (6, 6)).clone_owned();
        let v = Motion::from_array(core::array::from_fn(|k| qd[k]));
        let r = pose(&q).rot;
        let gb = r.tr_mul_vec(&g);
        let a = DVector::from_fn(6, |k, _| qdd[k] - if k >= 3 { gb.0[k - 3] } else { 0.0 });
        let iv = &inertia * DVector::from_column_slice(&qd[..6]);
        let iv = Force::from_array(core::array::from_fn(|k| iv[k]));
        let want = &inertia * a + DVector::from_column_slice(&v.cross_force(&iv).to_array());
        let tau = tau_of(&model, &mut ws, &q, &qd, &qdd, &g);
        let epsilon = 1e-12 * scale(want.as_slice(), 1.0);
        assert!(
            abs_diff_eq!(&tau[..6], want.as_slice(), epsilon = epsilon),
            "seed {seed}: locked robot {:?} against the rigid body {want}",
            &tau[..6]
        );
        // and the robot with every joint fixed in the file, at q = 0
        let mut rng = Rng::new(seed);
        let text = random_urdf(&mut rng, 6, false)
            .replace("type=\"revolute\"", "type=\"fixed\"")
            .replace("type=\"continuous\"", "type=\"fixed\"")
            .replace("type=\"prismatic\"", "type=\"fixed\"");
        let rigid = Model::from_urdf_str(&text).unwrap().with_floating_base();
        assert_eq!(rigid.dof(), 0);
        let mut q0 = q.clone();
        q0[7..].fill(0.0);
        let mut ws_r = Workspace::new(&rigid);
        let t_full = tau_of(&model, &mut ws, &q0, &qd, &qdd, &g);
        let t_rigid = tau_of(&rigid, &mut ws_r, &q0[..7], &qd[..6], &qdd[..6], &g);
        let epsilon = 1e-12 * scale(&t_full[..6], 1.0);
        assert!(
            abs_diff_eq!(&t_rigid[..], &t_full[..6], epsilon = epsilon),
            "seed {seed}: all joints fixed in the file: {t_rigid:?} against {:?}",
            &t_full[..6]
        );
    }
}

#[test]
fn zero_gravity_motion_conserves_momentum_and_energy() {
    let none = Vec3([0.0; 3]);
    let mut report = String::new();
    for seed in [3u64, 17, 99] {
        let model = random_model(seed, 5);
        let nv = model.nv();
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 3);
        let (mut q, mut qd) = random_state(&model, &mut rng, 5.0);
        let tau = vec![0.0; nv];
        let energy = |ws: &mut Workspace<f64>, q: &[f64], qd: &[f64]| {
            let v = DVector::from_column_slice(qd);
            0.5 * v.dot(&(mass_matrix(&model, ws, q) * &v))
        };
        let (e0, p0) = (energy(&mut ws, &q, &qd), world_momentum(&model, &mut ws, &q, &qd));
        // RK4 on SE(3) × Rⁿ (floating::step: Munthe-Kaas stages)
        let mut scratch = dynagen::algorithms::integrators::IntegratorScratch::new(&model);
        let inputs = dynagen::algorithms::integrators::StepInputs { dt: 1e-3, tau: &tau, loads: Loads::gravity(&none) };
        for _ in 0..1000 {
            floating::step::step(dynagen::Integrator::Rk4, &model, &mut ws, &mut scratch, &inputs, &mut q, &mut qd);
        }
        let (e1, p1) = (energy(&mut ws, &q, &qd), world_momentum(&model, &mut ws, &q, &qd));
        let de = (e1 - e0).abs() / e0;
        let dp = norm_rel_err(&p1.to_array(), &p0.to_array(), 1e-12);
        let _ =
            writeln!(report, "seed {seed}: energy drift {de:.1e}, momentum drift {dp:.1e} over 1 s (RK4, dt = 1 ms)");
        assert!(de < 1e-10 && dp < 1e-10, "seed {seed}: energy drift {de:e}, momentum drift {dp:e}");
    }
    println!("{report}");
}

#[test]
fn jacobians_against_finite_differences_on_se3() {
    for seed in SEEDS {
        let model = random_model(seed, 7);
        let (nv, nf) = (model.nv(), model.frames.len());
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 21);
        let (q, _) = random_state(&model, &mut rng, 0.0);
        fk::forward_kinematics(&model, &mut ws, &q);
        let frame = (rng.bits() as usize) % nf;
        let t = fk::frame_pose_world(&model, &ws, &q, frame);
        let (mut jb, mut js, mut jbase) = (vec![0.0; 6 * nv], vec![0.0; 6 * nv], vec![0.0; 6 * nv]);
        fk::body_jacobian(&model, &ws, frame, &mut jb);
        fk::space_jacobian_world(&model, &ws, &q, frame, &mut js);
        fk::space_jacobian_base(&model, &ws, frame, &mut jbase);
        let d = 1e-6;
        for k in 0..nv {
            let mut dv = vec![0.0; nv];
            let mut pose_at = |h: f64, ws: &mut Workspace<f64>| {
                dv.iter_mut().enumerate().for_each(|(i, x)| *x = if i == k { h } else { 0.0 });
                let qs = step(&model, &q, &dv);
                fk::forward_kinematics(&model, ws, &qs);
                fk::frame_pose_world(&model, ws, &qs, frame).to_homogeneous()
            };
            let (p, m) = (pose_at(d, &mut ws), pose_at(-d, &mut ws));
            let dt: [[f64; 4]; 4] = core::array::from_fn(|r| core::array::from_fn(|c| (p[r][c] - m[r][c]) / (2.0 * d)));
            let th = nalgebra::Matrix4::from_fn(|r, c| t.to_homogeneous()[r][c]);
            let dt = nalgebra::Matrix4::from_fn(|r, c| dt[r][c]);
            let twist = |x: nalgebra::Matrix4<f64>| [x[(2, 1)], x[(0, 2)], x[(1, 0)], x[(0, 3)], x[(1, 3)], x[(2, 3)]];
            let body = twist(th.try_inverse().unwrap() * dt);
            let space = twist(dt * th.try_inverse().unwrap());
            let col = |j: &[f64]| (0..6).map(|r| j[r * nv + k]).collect::<Vec<_>>();
            for (name, got, want) in [("body", col(&jb), body), ("space", col(&js), space)] {
                let epsilon = 1e-8 * scale(&want, 1.0);
                assert!(
                    abs_diff_eq!(&got[..], &want[..], epsilon = epsilon),
                    "seed {seed}, frame {frame}, column {k}: {name} Jacobian {got:?} against {want:?}"
                );
            }
            // the base-frame Jacobian is the world one seen from the base
            let world = Motion::from_array(core::array::from_fn(|r| js[r * nv + k]));
            let in_base = pose(&q).motion_to_child(&world).to_array();
            assert!(abs_diff_eq!(&col(&jbase)[..], &in_base[..], epsilon = 1e-13 * scale(&in_base, 1.0)));
        }
    }
}

#[test]
fn fixed_base_model_is_the_floating_one_with_the_base_held() {
    let g = Vec3(G);
    for seed in SEEDS {
        let floating = random_model(seed, 7);
        let mut fixed = floating.clone();
        fixed.root_joint = dynagen::model::RootJoint::Fixed;
        let (n, nv) = (fixed.dof(), floating.nv());
        let (mut wf, mut wx) = (Workspace::new(&floating), Workspace::new(&fixed));
        let mut rng = Rng::new(seed + 31);
        let (q, mut qd) = random_state(&floating, &mut rng, 30.0);
        let mut qdd = rng.vec(nv, 10.0);
        qd[..6].fill(0.0);
        qdd[..6].fill(0.0);
        // gravity in the base frame for the fixed model
        let gb = pose(&q).rot.tr_mul_vec(&g);
        let tf = tau_of(&floating, &mut wf, &q, &qd, &qdd, &g);
        let mut tx = vec![0.0; n];
        fixed_rnea::rnea(&fixed, &mut wx, &q[7..], Some(&qd[6..]), Some(&qdd[6..]), Loads::gravity(&gb), &mut tx);
        let epsilon = 1e-12 * scale(&tx, 1.0);
        assert!(
            abs_diff_eq!(&tf[6..], &tx[..], epsilon = epsilon),
            "seed {seed}: joint rows of τ {:?} against {tx:?}",
            &tf[6..]
        );
        let mf = mass_matrix(&floating, &mut wf, &q);
        let mut mx = vec![0.0; n * n];
        fixed_crba::crba(&fixed, &mut wx, &q[7..], Loads::none(), &mut mx);
        let joints: Vec<f64> =
            (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).map(|(i, j)| mf[(6 + i, 6 + j)]).collect();
        let epsilon = 1e-13 * scale(&mx, 1.0);
        assert!(
            abs_diff_eq!(&joints[..], &mx[..], epsilon = epsilon),
            "seed {seed}: joint block of M {joints:?} against {mx:?}"
        );
    }
}

#[test]
fn urdf_floating_root_joint() {
    let mut rng = Rng::new(5);
    let text = random_urdf(&mut rng, 5, true);
    let model = Model::from_urdf_str(&text).unwrap();
    assert!(model.is_floating());
    assert_eq!(model.root, "base");
    assert_eq!((model.nq(), model.nv()), (model.dof() + 7, model.dof() + 6));
    assert!(model.frame_index("world").is_none());
    let mut rng = Rng::new(5);
    let same = Model::from_urdf_str(&random_urdf(&mut rng, 5, false)).unwrap().with_floating_base();
    assert_eq!(model.bodies, same.bodies);
    assert_eq!(model.base_inertia, same.base_inertia);
    // a fixed-base model keeps NQ = NV = n
    let fixed = support::model("ur5");
    assert_eq!((fixed.nq(), fixed.nv(), fixed.is_floating()), (6, 6, false));
}

#[test]
fn urdf_errors_name_the_item() {
    let link = |n: &str| {
        format!("<link name=\"{n}\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>")
    };
    let joint = |name: &str, kind: &str, p: &str, c: &str| {
        format!("<joint name=\"{name}\" type=\"{kind}\"><parent link=\"{p}\"/><child link=\"{c}\"/><axis xyz=\"0 0 1\"/></joint>")
    };
    let robot = |body: String| format!("<robot name=\"r\">{body}</robot>");
    let err = |x: String| Model::from_urdf_str(&x).unwrap_err();
    // a floating joint below the root
    let e = err(robot(format!(
        "<link name=\"world\"/>{}{}{}{}{}",
        link("base"),
        link("leg"),
        joint("root", "floating", "world", "base"),
        joint("hip", "floating", "base", "leg"),
        ""
    )));
    assert!(matches!(&e, ModelError::Floating { joint, .. } if joint == "hip"), "{e}");
    assert!(e.to_string().contains("hip"), "{e}");
    // a world with mass
    let e = err(robot(format!("{}{}{}", link("world"), link("base"), joint("root", "floating", "world", "base"))));
    assert!(e.to_string().contains("root") && e.to_string().contains("mass"), "{e}");
    // a planar joint
    let e = err(robot(format!("{}{}{}", link("base"), link("slider"), joint("slide", "planar", "base", "slider"))));
    assert!(e.to_string().contains("slide") && e.to_string().contains("planar"), "{e}");
    // two roots
    let e = err(robot(format!("{}{}", link("a"), link("b"))));
    assert!(matches!(&e, ModelError::MultipleRoots(r) if r == &["a", "b"]), "{e}");
    assert!(e.to_string().contains("several root links (a, b)"), "{e}");
    // two roots, one of them floated by a floating joint: still two trees
    let e = err(robot(format!(
        "<link name=\"world\"/>{}{}{}",
        link("base"),
        link("spare"),
        joint("root", "floating", "world", "base")
    )));
    assert!(e.to_string().contains("world") && e.to_string().contains("spare"), "{e}");
}

#[test]
fn robot_checks_floating_inputs_and_names_them() {
    use dynagen::InputError;
    let mut robot = dynagen::Robot::new(support::model("quadruped12").with_floating_base());
    let (nq, nv) = (robot.nq(), robot.nv());
    assert_eq!((nq, nv), (19, 18));
    let mut q = DVector::zeros(nq);
    q[6] = 1.0;
    let v = DVector::zeros(nv);
    assert!(robot.inverse_dynamics(&q, &v, &v).is_ok());
    // a fixed-base length is refused, naming NQ / NV
    let short = DVector::zeros(12);
    let e = robot.inverse_dynamics(&short, &v, &v).unwrap_err();
    assert!(matches!(e, InputError::WrongLengthFloating { what: "q", got: 12, expected: 19, .. }), "{e}");
    assert!(e.to_string().contains("NQ = n + 7"), "{e}");
    let e = robot.inverse_dynamics(&q, &short, &v).unwrap_err();
    assert!(e.to_string().contains("qd") && e.to_string().contains("NV = n + 6"), "{e}");
    // a zero quaternion, and one far from unit norm
    let mut bad = q.clone();
    bad[6] = 0.0;
    let e = robot.mass_matrix(&bad).unwrap_err();
    assert!(matches!(e, InputError::Quaternion { what: "q", norm } if norm == 0.0), "{e}");
    assert!(e.to_string().contains("quaternion"), "{e}");
    bad[6] = 1.001;
    assert!(matches!(robot.forward_dynamics(&bad, &v, &v), Err(InputError::Quaternion { .. })));
    // 1e-9 off unit norm is fine (used as given)
    bad[6] = 1.0 + 1e-9;
    assert!(robot.forward_dynamics(&bad, &v, &v).is_ok());
    // NaN in the base names the base, in a joint the joint
    let mut nan = q.clone();
    nan[4] = f64::NAN;
    let e = robot.gravity_torques(&nan).unwrap_err();
    assert!(matches!(&e, InputError::NonFinite { joint, index: 4, .. } if joint == "base quaternion"), "{e}");
    let mut nan_v = v.clone();
    nan_v[8] = f64::INFINITY;
    let e = robot.bias_forces(&q, &nan_v).unwrap_err();
    assert!(matches!(&e, InputError::NonFinite { joint, .. } if joint == "FR_calf_joint"), "{e}");
    // the compensated forward dynamics checks the same way
    let e = robot.forward_dynamics_compensated(&q.rows(0, 7).into_owned(), &v, &v).unwrap_err();
    assert!(matches!(e, InputError::WrongLengthFloating { what: "q", got: 7, .. }), "{e}");
    // the centroidal quantities need a floating base
    let mut fixed = support::robot("quadruped12");
    assert!(matches!(fixed.center_of_mass(&DVector::zeros(12)), Err(InputError::Unsupported(_))));
}

#[test]
fn robot_steps_the_base_on_se3() {
    use dynagen::{Integrator, Robot, Stepping};
    let mut robot = Robot::new(support::model("quadruped12").with_floating_base());
    robot.set_gravity(nalgebra::Vector3::zeros()).unwrap();
    let (nq, nv) = (robot.nq(), robot.nv());
    let mut rng = Rng::new(8);
    let (q0, qd0) = random_state(robot.model(), &mut rng, 10.0);
    let (q0, qd0) = (DVector::from_vec(q0), DVector::from_vec(qd0));
    let energy =
        |robot: &mut Robot, q: &DVector<f64>, qd: &DVector<f64>| 0.5 * qd.dot(&(robot.mass_matrix(q).unwrap() * qd));
    let e0 = energy(&mut robot, &q0, &qd0);
    let mut report = String::new();
    for (integrator, tol) in [
        (Integrator::Rk4, 1e-6),
        (Integrator::SemiImplicitEuler, 0.05),
        (Integrator::Euler, 0.5),
        (Integrator::ImplicitEuler, 0.5),
    ] {
        let (mut q, mut qd) = (q0.clone(), qd0.clone());
        let tau = DVector::zeros(nv);
        for _ in 0..1000 {
            robot.step(integrator, &mut q, &mut qd, &tau, 1e-3).unwrap();
        }
        let norm = q.rows(3, 4).norm();
        assert!((norm - 1.0).abs() < 1e-14, "{integrator:?}: quaternion norm {norm}");
        let drift = (energy(&mut robot, &q, &qd) - e0) / e0;
        let _ = writeln!(report, "{integrator:?}: energy change {drift:+.1e} over 1 s at dt = 1 ms");
        assert!(drift.abs() < tol, "{integrator:?}: energy drift {drift:e}");
        // the implicit scheme damps, explicit Euler feeds energy in
        match integrator {
            Integrator::ImplicitEuler => assert!(drift < 0.0, "implicit Euler gained energy: {drift:e}"),
            Integrator::Euler => assert!(drift > 0.0, "explicit Euler lost energy: {drift:e}"),
            _ => {}
        }
    }
    println!("{report}");
    // a trajectory: NQ-wide positions, NV-wide velocities
    let tau = DMatrix::zeros(11, nv);
    let (qs, qds) =
        robot.forward_dynamics_trajectory(&q0, &qd0, &tau, None, Stepping::new(0.01, 10, Integrator::Rk4)).unwrap();
    assert_eq!((qs.ncols(), qds.ncols(), qs.nrows()), (nq, nv, 11));
    let qdd = DMatrix::zeros(11, nv);
    let taus = robot.inverse_dynamics_trajectory(&qs, &qds, &qdd, None).unwrap();
    assert_eq!(taus.ncols(), nv);
}

/// The floating algorithms trace on the symbolic scalar unchanged (no
/// branch on the state; the base's rotation a polynomial in the
/// quaternion), and the traces evaluate to the `f64` solver's numbers.
#[test]
fn floating_algorithms_trace_on_the_symbolic_scalar() {
    use dynagen::symbolic::{Expr, Traced, Tracer};
    use dynagen::Scalar;
    for model in [support::model("quadruped12").with_floating_base(), random_model(99, 8)] {
        let (nq, nv) = (model.nq(), model.nv());
        let t = Tracer::start().unwrap();
        let (q, qd, qdd, tau) = (t.inputs("q", nq), t.inputs("qd", nv), t.inputs("qdd", nv), t.inputs("tau", nv));
        let g = Vec3(G.map(Expr::from_f64));
        let mut ws = Workspace::<Expr>::new(&model);
        let mut id = vec![Expr::zero(); nv];
        rnea(&model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut id);
        let mut m = vec![Expr::zero(); nv * nv];
        crba(&model, &mut ws, &q, Loads::none(), &mut m);
        let mut fd = vec![Expr::zero(); nv];
        aba(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut fd);
        let mut fd2 = vec![Expr::zero(); nv];
        forward_dynamics::forward_dynamics_ldlt(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut fd2);
        let graph = t.finish();
        let traced: Vec<Traced> = [("rnea", &id), ("crba", &m), ("aba", &fd), ("ldlt", &fd2)]
            .into_iter()
            .map(|(name, out)| Traced::new(name, &graph, out))
            .collect();
        let mut rng = Rng::new(2);
        let mut ws = Workspace::new(&model);
        for _ in 0..3 {
            let (qv, qdv) = random_state(&model, &mut rng, 50.0);
            let (qddv, tauv) = (rng.vec(nv, 5.0), rng.vec(nv, 10.0));
            let inputs: [(&str, &[f64]); 4] = [("q", &qv), ("qd", &qdv), ("qdd", &qddv), ("tau", &tauv)];
            let want_id = tau_of(&model, &mut ws, &qv, &qdv, &qddv, &Vec3(G));
            let want_m = mass_matrix(&model, &mut ws, &qv);
            let want_fd = fd_aba(&model, &mut ws, &qv, &qdv, &tauv, &Vec3(G));
            let checks: [(&Traced, &[f64]); 4] = [
                (&traced[0], &want_id),
                (&traced[1], want_m.as_slice()),
                (&traced[2], &want_fd),
                (&traced[3], &want_fd),
            ];
            for (f, want) in checks {
                let got = f.eval(&inputs).unwrap();
                let epsilon = 1e-11 * scale(want, 1.0);
                assert!(
                    abs_diff_eq!(&got[..], want, epsilon = epsilon),
                    "{}: {} traced {got:?} against f64 {want:?}",
                    model.name,
                    f.name()
                );
            }
        }
    }
}

/// τ ≈ h at |q̇| = 50: the compensated forward dynamics keeps the digits
/// that τ − h cancels, against the articulated-body algorithm run in
/// double-double arithmetic (the reference).
#[test]
fn compensated_forward_dynamics_on_a_floating_base() {
    use dynagen::{DoubleDouble, Robot, Scalar};
    let model = support::model("quadruped12").with_floating_base();
    let nv = model.nv();
    let mut robot = Robot::new(model.clone());
    let mut ws = Workspace::new(&model);
    let mut wd = Workspace::<DoubleDouble>::new(&model);
    let mut rng = Rng::new(41);
    let (mut plain_worst, mut comp_worst) = (0.0f64, 0.0f64);
    for _ in 0..5 {
        let (q, qd) = random_state(&model, &mut rng, 50.0);
        let qd: Vec<f64> = {
            let s = 50.0 / qd.iter().map(|x| x * x).sum::<f64>().sqrt();
            qd.iter().map(|x| x * s).collect()
        };
        let mut h = vec![0.0; nv];
        dynagen::algorithms::bias::bias_forces(&model, &mut ws, &q, &qd, Some(&Vec3(G)), &mut h);
        let tau: Vec<f64> = h.iter().map(|x| x + 1e-3 * rng.signed()).collect();
        let dd = |x: &[f64]| x.iter().map(|v| DoubleDouble::from_f64(*v)).collect::<Vec<_>>();
        let mut want = vec![DoubleDouble::zero(); nv];
        let g = Vec3(G.map(DoubleDouble::from_f64));
        aba(&model, &mut wd, &dd(&q), &dd(&qd), &dd(&tau), Loads::gravity(&g), &mut want);
        let want: Vec<f64> = want.iter().map(|x| Scalar::to_f64(*x).unwrap()).collect();
        let (qv, qdv, tv) = (DVector::from_vec(q), DVector::from_vec(qd), DVector::from_vec(tau));
        let plain = robot.forward_dynamics(&qv, &qdv, &tv).unwrap();
        let comp = robot.forward_dynamics_compensated(&qv, &qdv, &tv).unwrap();
        plain_worst = plain_worst.max(norm_rel_err(plain.as_slice(), &want, 1e-300));
        comp_worst = comp_worst.max(norm_rel_err(comp.as_slice(), &want, 1e-300));
    }
    println!("τ ≈ h at |q̇| = 50: ABA {plain_worst:.1e}, compensated {comp_worst:.1e} relative to double-double");
    assert!(comp_worst < 1e-9 && comp_worst < plain_worst, "compensated {comp_worst:e}, plain {plain_worst:e}");
}

/// A floating robot that cannot be accelerated in every direction (a point
/// mass) gets a warning naming its root; a real one does not.
#[test]
fn a_singular_floating_base_is_warned_about() {
    use dynagen::ModelWarning;
    let quadruped = support::model("quadruped12").with_floating_base();
    assert!(!quadruped.warnings.iter().any(|w| matches!(w, ModelWarning::FloatingBaseSingular { .. })));
    let point = Model::from_urdf_str(
        "<robot name=\"p\"><link name=\"world\"/><link name=\"ball\"><inertial><mass value=\"1\"/>\
         <inertia ixx=\"0\" iyy=\"0\" izz=\"0\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\
         <joint name=\"free\" type=\"floating\"><parent link=\"world\"/><child link=\"ball\"/></joint></robot>",
    )
    .unwrap();
    assert!(point.is_floating());
    let w = point.warnings.iter().find(|w| matches!(w, ModelWarning::FloatingBaseSingular { .. })).expect("a warning");
    assert!(w.to_string().contains("\"ball\" floats"), "{w}");
}

/// A massless root link set floating moves against its first joint without
/// moving any mass (the UR5's base_link and shoulder_pan_joint): M(q) is
/// singular at every q. The load names both, the checked forward dynamics
/// and code generation refuse with that message, and `singular_joints_at`
/// (NQ-long q) finds the same set; the quadruped's trunk has mass, no
/// warning.
#[test]
fn a_massless_floating_root_makes_its_first_joint_dependent() {
    use dynagen::codegen::{generate, CodegenOptions};
    use dynagen::ModelWarning;
    let quadruped = support::model("quadruped12").with_floating_base();
    assert!(quadruped.dependent_joints().is_empty());
    let ur5 = support::model("ur5").with_floating_base();
    let expected = ["base_link (the floating base)".to_string(), "shoulder_pan_joint".to_string()];
    assert_eq!(ur5.dependent_joints(), [&expected[..]]);
    let w = ur5.warnings.iter().find(|w| matches!(w, ModelWarning::DependentJoints { .. })).expect("a warning");
    assert!(
        w.to_string().contains("\"base_link (the floating base)\" and \"shoulder_pan_joint\" are dependent"),
        "{w}"
    );
    let mut q = vec![0.0; ur5.nq()];
    q[6] = 1.0;
    q[7..].copy_from_slice(&[0.3, -0.7, 1.1, 0.2, -0.4, 0.9]);
    assert_eq!(ur5.singular_joints_at(&q), [expected.to_vec()]);
    let mut robot = dynagen::Robot::new(ur5.clone());
    let (v, nv) = (DVector::from_vec(q), ur5.nv());
    let e = robot.forward_dynamics(&v, &DVector::zeros(nv), &DVector::zeros(nv)).unwrap_err();
    assert!(
        e.to_string().contains("\"base_link (the floating base)\" and \"shoulder_pan_joint\" are dependent"),
        "{e}"
    );
    let e = generate(&ur5, &CodegenOptions::default()).unwrap_err();
    assert!(e.to_string().contains("forward_dynamics cannot be generated"), "{e}");
    assert!(e.to_string().contains("\"shoulder_pan_joint\""), "{e}");
}

/// The derivatives of a floating base are NV×NV in the tangent space (the
/// base's body twist): moving the base changes nothing in its frame, so
/// ∂τ/∂q's three translation columns are zero, and without gravity so are
/// its three rotation columns. (Their values: `tests/derivatives.rs`
/// against double-double differences on the manifold, `tests/pinocchio.rs`
/// against Pinocchio's free-flyer.)
#[test]
fn derivatives_of_a_floating_base_live_in_the_tangent_space() {
    use nalgebra::DVector;
    let model = support::model("quadruped12").with_floating_base();
    let (nq, nv) = (model.nq(), model.nv());
    let mut robot = dynagen::Robot::new(model.clone());
    let mut q = DVector::from_fn(nq, |i, _| 0.1 * i as f64 - 0.4);
    let norm = q.rows(3, 4).norm();
    q.rows_mut(3, 4).iter_mut().for_each(|x| *x /= norm);
    let v = DVector::from_fn(nv, |i, _| 0.2 * (i as f64).sin());
    let (dq, dqd) = robot.inverse_dynamics_derivatives(&q, &v, &v).unwrap();
    assert_eq!((dq.nrows(), dq.ncols(), dqd.ncols()), (nv, nv, nv));
    assert!((3..6).all(|c| dq.column(c).iter().all(|x| *x == 0.0)), "translation columns");
    assert!((0..3).all(|c| dq.column(c).norm() > 0.0), "gravity turns with the base");
    let (fq, _, minv) = robot.forward_dynamics_derivatives(&q, &v, &v).unwrap();
    assert_eq!((fq.nrows(), minv.ncols()), (nv, nv));
    let mut free = dynagen::Robot::new(model.with_gravity([0.0; 3]));
    let (dq, _) = free.inverse_dynamics_derivatives(&q, &v, &v).unwrap();
    assert!((0..6).all(|c| dq.column(c).iter().all(|x| *x == 0.0)), "no gravity: the base's columns vanish");
    assert!(robot.inverse_dynamics_derivatives(&DVector::zeros(nq), &v, &v).is_err(), "a zero quaternion");
}

/// The energies of a floating model: kinetic ½ q̇ᵀ M q̇, and the potential's
/// derivative along each velocity coordinate (a step q ⊕ ε e_k on SE(3)) is
/// g's entry: the base rows included.
#[test]
fn energies_agree_with_m_and_g() {
    use dynagen::algorithms::{bias, energy};
    let g = Vec3(G);
    for seed in SEEDS {
        let model = random_model(seed, 6);
        let nv = model.nv();
        let mut ws = Workspace::new(&model);
        let mut rng = Rng::new(seed + 77);
        let (q, qd) = random_state(&model, &mut rng, 20.0);
        let m = mass_matrix(&model, &mut ws, &q);
        let v = DVector::from_column_slice(&qd);
        let want = 0.5 * v.dot(&(&m * &v));
        let got = energy::kinetic_energy(&model, &mut ws, &q, &qd);
        assert!((got - want).abs() <= 1e-13 * want, "seed {seed}: kinetic energy {got} vs {want}");
        let mut gv = vec![0.0; nv];
        bias::gravity_torques(&model, &mut ws, &q, &g, &mut gv);
        let d = 1e-5;
        for k in 0..nv {
            let mut e = vec![0.0; nv];
            let mut at = |h: f64, ws: &mut Workspace<f64>| {
                e[k] = h;
                energy::potential_energy(&model, ws, &step(&model, &q, &e), &g)
            };
            let slope = (at(d, &mut ws) - at(-d, &mut ws)) / (2.0 * d);
            let scale = gv.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert!((slope - gv[k]).abs() < 1e-7 * scale, "seed {seed}: dV/dq[{k}] = {slope} vs g = {}", gv[k]);
        }
    }
}

/// A payload carried by the floating base ([`BASE_BODY`]) is the base's
/// inertia plus the payload's, in rnea, crba and aba alike.
#[test]
fn a_payload_on_the_base_adds_to_the_base_inertia() {
    use dynagen::algorithms::{BodyInertia, BASE_BODY};
    use dynagen::spatial::{Inertia, Sym3};
    let g = Vec3(G);
    let model = random_model(17, 6);
    let nv = model.nv();
    let payload =
        Inertia::from_mass_com_inertia(2.5, Vec3([0.1, -0.05, 0.2]), Sym3([0.03, 0.04, 0.02, 0.001, 0.0, -0.002]));
    let mut heavier = model.clone();
    heavier.base_inertia = heavier.base_inertia.add(&payload);
    let carried = [BodyInertia { body: BASE_BODY, inertia: payload }];
    let loads = Loads::gravity(&g).with_payloads(&carried);
    let (mut ws, mut wh) = (Workspace::new(&model), Workspace::new(&heavier));
    let mut rng = Rng::new(23);
    for _ in 0..3 {
        let (q, qd) = random_state(&model, &mut rng, 20.0);
        let (qdd, tau) = (rng.vec(nv, 5.0), rng.vec(nv, 20.0));
        let (mut a, mut b) = (vec![0.0; nv], vec![0.0; nv]);
        rnea(&model, &mut ws, &q, Some(&qd), Some(&qdd), loads, &mut a);
        rnea(&heavier, &mut wh, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut b);
        assert!(rel_err(&a, &b, 1.0) < 1e-14, "rnea");
        aba(&model, &mut ws, &q, &qd, &tau, loads, &mut a);
        aba(&heavier, &mut wh, &q, &qd, &tau, Loads::gravity(&g), &mut b);
        assert!(rel_err(&a, &b, 1.0) < 1e-12, "aba");
        let (mut ma, mut mb) = (vec![0.0; nv * nv], vec![0.0; nv * nv]);
        crba(&model, &mut ws, &q, loads, &mut ma);
        crba(&heavier, &mut wh, &q, Loads::none(), &mut mb);
        assert!(rel_err(&ma, &mb, 1.0) < 1e-14, "crba");
    }
    // On a fixed base it moves nothing.
    let mut fixed = model.clone();
    fixed.root_joint = dynagen::model::RootJoint::Fixed;
    let n = fixed.dof();
    let mut wf = Workspace::new(&fixed);
    let (mut ma, mut mb) = (vec![0.0; n * n], vec![0.0; n * n]);
    fixed_crba::crba(&fixed, &mut wf, &vec![0.3; n], Loads::none().with_payloads(&carried), &mut ma);
    fixed_crba::crba(&fixed, &mut wf, &vec![0.3; n], Loads::none(), &mut mb);
    assert_eq!(ma, mb);
}
