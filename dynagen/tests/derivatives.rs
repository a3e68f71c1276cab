//! The derivatives of the dynamics (`Robot::inverse_dynamics_derivatives`,
//! `forward_dynamics_derivatives`, `mass_matrix_inverse`) against central
//! finite differences of the same dynamics computed in double-double (so the
//! differences carry ~1e-15 truncation error and no visible rounding), on
//! every bundled robot and on random trees with prismatic joints, fixed
//! links and non-aligned axes; and the identities ∂τ/∂q̈ = M, M·M⁻¹ = 1,
//! ∂q̈/∂q = −M⁻¹ ∂τ/∂q at q̈ = FD(q, q̇, τ).

mod support;

use dynagen::algorithms::{aba, rnea, Loads, TipWrench, Workspace};
use dynagen::spatial::{Force, Vec3};
use dynagen::{DoubleDouble, InputError, Model, Robot, Scalar};
use nalgebra::{DMatrix, DVector};
use std::fmt::Write;
use support::Rng;

type Dd = DoubleDouble;

/// Which argument a finite difference moves.
#[derive(Clone, Copy, Debug)]
enum Wrt {
    Q,
    Qd,
    Third,
}

/// Row-major n×n central differences (step `h`, in double-double) of
/// `f(q, q̇, x)` (x = q̈ or τ) with respect to `wrt`.
fn central(
    n: usize,
    (q, qd, x): (&[f64], &[f64], &[f64]),
    wrt: Wrt,
    mut f: impl FnMut(&[Dd], &[Dd], &[Dd], &mut [Dd]),
) -> Vec<f64> {
    let h = 1e-7;
    let dd = |v: &[f64]| v.iter().map(|&x| Dd::from(x)).collect::<Vec<_>>();
    let mut out = vec![0.0; n * n];
    let (mut plus, mut minus) = (vec![Dd::ZERO; n], vec![Dd::ZERO; n]);
    for j in 0..n {
        for (sign, y) in [(1.0, &mut plus), (-1.0, &mut minus)] {
            let (mut a, mut b, mut c) = (dd(q), dd(qd), dd(x));
            let v = match wrt {
                Wrt::Q => &mut a,
                Wrt::Qd => &mut b,
                Wrt::Third => &mut c,
            };
            v[j] += Dd::from(sign * h);
            f(&a, &b, &c, y);
        }
        for i in 0..n {
            out[i * n + j] = ((plus[i] - minus[i]) / Dd::from(2.0 * h)).to_f64();
        }
    }
    out
}

/// The tip wrenches of a robot's loads, in double-double.
fn dd_tips(tips: &[(usize, [f64; 6])]) -> Vec<TipWrench<Dd>> {
    tips.iter().map(|(frame, w)| TipWrench { frame: *frame, wrench: Force::from_array(w.map(Dd::from)) }).collect()
}

/// Row-major entries of a matrix.
fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// ‖got − want‖_F / ‖want‖_F (‖want‖ at least 1e-12).
fn err(got: &DMatrix<f64>, want: &[f64]) -> f64 {
    support::norm_rel_err(&rows(got), want, 1e-12)
}

/// Checks every derivative of `robot` (with the tip wrenches `tips`, frame
/// index and wrench, already set on it) at `count` random states.
fn check(name: &str, model: &Model, robot: &mut Robot, tips: &[(usize, [f64; 6])], count: usize, seed: u64) -> f64 {
    let n = model.dof();
    let mut rng = Rng::new(seed);
    let g = Vec3(model.gravity.0.map(Dd::from));
    let tips = dd_tips(tips);
    let mut ws = Workspace::<Dd>::new(model);
    let mut worst = 0.0_f64;
    for k in 0..count {
        let (q, qd, qdd, tau) = (rng.vec(n, 2.0), rng.vec(n, 1.5), rng.vec(n, 3.0), rng.vec(n, 10.0));
        let v = |x: &Vec<f64>| DVector::from_vec(x.clone());
        let (dq, dqd) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&qdd)).unwrap();
        let (fq, fqd, minv) = robot.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&tau)).unwrap();
        let m = robot.mass_matrix(&v(&q)).unwrap();
        let loads = Loads::gravity(&g).with_tips(&tips);
        let mut id =
            |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| rnea::rnea(model, &mut ws, a, Some(b), Some(c), loads, y);
        let e_dq = err(&dq, &central(n, (&q, &qd, &qdd), Wrt::Q, &mut id));
        let e_dqd = err(&dqd, &central(n, (&q, &qd, &qdd), Wrt::Qd, &mut id));
        // ∂τ/∂q̈ = M
        let e_m = err(&m, &central(n, (&q, &qd, &qdd), Wrt::Third, &mut id));
        let mut ws2 = Workspace::<Dd>::new(model);
        let mut fd = |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| aba::aba(model, &mut ws2, a, b, c, loads, y);
        let e_fq = err(&fq, &central(n, (&q, &qd, &tau), Wrt::Q, &mut fd));
        let e_fqd = err(&fqd, &central(n, (&q, &qd, &tau), Wrt::Qd, &mut fd));
        let e_minv = err(&minv, &central(n, (&q, &qd, &tau), Wrt::Third, &mut fd));
        // M·M⁻¹ = 1, and mass_matrix_inverse is forward_dynamics_derivatives' M⁻¹
        let e_eye = (&m * &minv - DMatrix::identity(n, n)).norm();
        let alone = robot.mass_matrix_inverse(&v(&q)).unwrap();
        let e_alone = (&alone - &minv).norm() / minv.norm();
        // ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ)
        let at = robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap();
        let (dq_at, dqd_at) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &at).unwrap();
        let e_chain = ((-&minv * dq_at) - &fq).norm() / fq.norm().max(1e-12)
            + ((-&minv * dqd_at) - &fqd).norm() / fqd.norm().max(1e-12);
        let all = [e_dq, e_dqd, e_m, e_fq, e_fqd, e_minv, e_eye, e_alone, e_chain];
        let mut msg = String::new();
        let _ = write!(msg, "{name} state {k}: dtau/dq {e_dq:.1e}, dtau/dqd {e_dqd:.1e}, dtau/dqdd=M {e_m:.1e}, ");
        let _ = write!(msg, "dqdd/dq {e_fq:.1e}, dqdd/dqd {e_fqd:.1e}, Minv {e_minv:.1e}, M Minv - 1 {e_eye:.1e}, ");
        let _ = write!(msg, "alone {e_alone:.1e}, chain {e_chain:.1e}");
        println!("{msg}");
        assert!(all.iter().all(|e| *e <= 1e-9), "{msg}");
        worst = all.iter().fold(worst, |w, e| w.max(*e));
    }
    worst
}

#[test]
fn bundled_robots_match_double_double_finite_differences() {
    for name in ["ur5", "panda", "torso_two_arms", "planar_2link", "iiwa14", "quadruped12"] {
        let model = support::model(name);
        let mut robot = Robot::new(model.clone());
        check(name, &model, &mut robot, &[], 3, 0x5eed_0001);
    }
}

/// A tip wrench set on the robot enters ∂τ/∂q (through Jᵀ(q)) and the
/// forward dynamics' derivatives, held constant.
#[test]
fn a_tip_wrench_is_differentiated_held_constant() {
    let model = support::model("ur5");
    let mut robot = Robot::new(model.clone());
    let frame = model.frames.iter().rposition(|f| f.body.is_some()).unwrap();
    let w = [0.3, -1.2, 0.7, 15.0, -4.0, 22.0];
    robot.set_tip_wrench(&model.frames[frame].name, nalgebra::Vector6::from_row_slice(&w)).unwrap();
    check("ur5 + tip wrench", &model, &mut robot, &[(frame, w)], 2, 0x5eed_0002);
}

/// A random tree as URDF: `n` moving joints with random parents, one in
/// three prismatic, axes random (not unit, not aligned), random origins and
/// inertias, and fixed links (with mass) on random bodies.
fn random_tree(rng: &mut Rng, n: usize) -> String {
    let mut x = String::from("<robot name=\"random\"><link name=\"base\"/>");
    let inertial = |rng: &mut Rng| {
        let (m, c) = (0.2 + 2.0 * rng.unit(), rng.vec(3, 0.2));
        let d = [0.02 + 0.05 * rng.unit(), 0.02 + 0.05 * rng.unit(), 0.02 + 0.05 * rng.unit()];
        let o = rng.vec(3, 0.005);
        format!(
            "<inertial><origin xyz=\"{} {} {}\" rpy=\"0 0 0\"/><mass value=\"{m}\"/><inertia ixx=\"{}\" iyy=\"{}\" izz=\"{}\" ixy=\"{}\" ixz=\"{}\" iyz=\"{}\"/></inertial>",
            c[0], c[1], c[2], d[0] + d[1], d[1] + d[2], d[0] + d[2], o[0], o[1], o[2]
        )
    };
    let link = |k: usize| if k == 0 { "base".to_string() } else { format!("l{}", k - 1) };
    for k in 0..n {
        let parent = link((rng.bits() % (k as u64 + 1)) as usize);
        let kind = if rng.bits().is_multiple_of(3) { "prismatic" } else { "revolute" };
        let (o, r, a) = (rng.vec(3, 0.4), rng.vec(3, 3.0), rng.vec(3, 1.5));
        let _ = write!(
            x,
            "<link name=\"l{k}\">{}</link><joint name=\"j{k}\" type=\"{kind}\"><parent link=\"{parent}\"/><child link=\"l{k}\"/>\
             <origin xyz=\"{} {} {}\" rpy=\"{} {} {}\"/><axis xyz=\"{} {} {}\"/>\
             <limit lower=\"-100\" upper=\"100\" effort=\"100\" velocity=\"100\"/></joint>",
            inertial(rng), o[0], o[1], o[2], r[0], r[1], r[2], a[0] + 0.1, a[1], a[2]
        );
    }
    for f in 0..2 {
        let parent = link(1 + (rng.bits() % n as u64) as usize);
        let (o, r) = (rng.vec(3, 0.3), rng.vec(3, 3.0));
        let _ = write!(
            x,
            "<link name=\"fixed{f}\">{}</link><joint name=\"fj{f}\" type=\"fixed\"><parent link=\"{parent}\"/><child link=\"fixed{f}\"/>\
             <origin xyz=\"{} {} {}\" rpy=\"{} {} {}\"/></joint>",
            inertial(rng), o[0], o[1], o[2], r[0], r[1], r[2]
        );
    }
    x.push_str("</robot>");
    x
}

#[test]
fn random_trees_match_double_double_finite_differences() {
    let mut rng = Rng::new(0x7ee5_5eed);
    for t in 0..12 {
        let n = 2 + (rng.bits() % 9) as usize;
        let urdf = random_tree(&mut rng, n);
        let model = Model::from_urdf_str(&urdf).unwrap_or_else(|e| panic!("tree {t}: {e}\n{urdf}"));
        let mut robot = Robot::new(model.clone());
        check(&format!("random tree {t} ({n} joints)"), &model, &mut robot, &[], 2, 0x5eed_1000 + t);
    }
}

/// The `_into` forms give the plain forms' values, and a wrong shape or a
/// non-finite input is an `InputError` naming it.
#[test]
fn into_forms_and_bad_input() {
    let mut robot = support::robot("panda");
    let n = robot.dof();
    let mut rng = Rng::new(9);
    let (q, qd, x) =
        (DVector::from_vec(rng.vec(n, 1.0)), DVector::from_vec(rng.vec(n, 1.0)), DVector::from_vec(rng.vec(n, 1.0)));
    let (a, b) = robot.inverse_dynamics_derivatives(&q, &qd, &x).unwrap();
    let (mut a2, mut b2, mut c2) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n), DMatrix::zeros(n, n));
    robot.inverse_dynamics_derivatives_into(&q, &qd, &x, &mut a2, &mut b2).unwrap();
    assert_eq!((a, b), (a2.clone(), b2.clone()));
    let (a, b, c) = robot.forward_dynamics_derivatives(&q, &qd, &x).unwrap();
    robot.forward_dynamics_derivatives_into(&q, &qd, &x, &mut a2, &mut b2, &mut c2).unwrap();
    assert_eq!((a, b, c.clone()), (a2, b2, c2.clone()));
    robot.mass_matrix_inverse_into(&q, &mut c2).unwrap();
    assert_eq!(c, c2);
    let mut small = DMatrix::zeros(n - 1, n);
    let e = robot.mass_matrix_inverse_into(&q, &mut small).unwrap_err();
    assert!(matches!(e, InputError::WrongLength { what: "minv", .. }), "{e}");
    let mut bad = qd.clone();
    bad[2] = f64::NAN;
    let e = robot.forward_dynamics_derivatives(&q, &bad, &x).unwrap_err();
    assert!(matches!(e, InputError::NonFinite { what: "qd", index: 2, .. }), "{e}");
    let e = robot.inverse_dynamics_derivatives(&q, &qd, &DVector::zeros(n + 1)).unwrap_err();
    assert!(matches!(e, InputError::WrongLength { what: "qdd", .. }), "{e}");
}

/// The dual scalar is exact to rounding where a finite difference is not:
/// a check that `Dd` itself is precise enough to be the reference.
#[test]
fn double_double_differences_are_the_reference() {
    let x = Dd::from(0.3);
    let h = Dd::from(1e-7);
    let d = ((x + h).sin() - (x - h).sin()) / (h + h);
    assert!((d.to_f64() - 0.3_f64.cos()).abs() < 1e-14);
}

/// The two formulations of ∂τ/∂(q, q̇) (the analytical recursion, the
/// generic solver's; dual numbers through the RNEA) and the forward
/// dynamics' derivatives built on each, on f64: the same matrices to
/// rounding, on random trees with a viscous and a Coulomb friction on every
/// joint, an armature, a payload and a tip wrench.
#[test]
fn both_formulations_agree() {
    use dynagen::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation, JointTorques};
    use dynagen::algorithms::BodyInertia;
    use dynagen::spatial::{Inertia, Sym3};
    /// b∘q̇ + f∘tanh-like smooth sign, as a scene's friction.
    struct Friction(Vec<f64>);
    impl JointTorques for Friction {
        fn add_to<S: Scalar>(&self, qd: &[S], tau: &mut [S]) {
            for (i, t) in tau.iter_mut().enumerate() {
                let v = qd[i];
                *t += S::from_f64(self.0[i]) * v + S::from_f64(0.3) * (v / (v * v + S::from_f64(0.01)).sqrt());
            }
        }
    }
    let mut rng = Rng::new(0xf0f0);
    for t in 0..8 {
        let n = 2 + (rng.bits() % 9) as usize;
        let model = Model::from_urdf_str(&random_tree(&mut rng, n)).unwrap();
        let friction = Friction(rng.vec(n, 0.5).iter().map(|x| x.abs()).collect());
        let armature: Vec<f64> = rng.vec(n, 0.2).iter().map(|x| x.abs()).collect();
        let g = model.gravity;
        let frame = model.frames.iter().rposition(|f| f.body.is_some()).unwrap();
        let tips = [TipWrench { frame, wrench: Force::from_array([0.3, -1.2, 0.7, 15.0, -4.0, 22.0]) }];
        let payload =
            Inertia::from_mass_com_inertia(0.7, Vec3([0.1, 0.0, -0.05]), Sym3([0.01, 0.02, 0.015, 0.0, 0.001, 0.0]));
        let payloads = [BodyInertia { body: n - 1, inertia: payload }];
        let loads = Loads::gravity(&g).with_tips(&tips).with_payloads(&payloads).with_armature(Some(&armature));
        let dynamics = Dynamics { model: &model, loads, torques: &friction, mass: None };
        let mut dw = DerivativeWorkspace::new(&model);
        let (q, qd, x) = (rng.vec(n, 2.0), rng.vec(n, 1.5), rng.vec(n, 3.0));
        let mut out = [[vec![0.0; n * n], vec![0.0; n * n]], [vec![0.0; n * n], vec![0.0; n * n]]];
        let mut fd = [
            [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]],
            [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]],
        ];
        for (k, formulation) in Formulation::ALL.into_iter().enumerate() {
            let [a, b] = &mut out[k];
            d::inverse_dynamics_derivatives(&dynamics, &mut dw, [&q, &qd, &x], formulation, [a, b], None);
            let [a, b, c] = &mut fd[k];
            d::forward_dynamics_derivatives(&dynamics, &mut dw, [&q, &qd, &x], formulation, [a, b, c]);
        }
        let rel = |a: &[f64], b: &[f64]| support::norm_rel_err(a, b, 1e-12);
        let errs = [
            rel(&out[0][0], &out[1][0]),
            rel(&out[0][1], &out[1][1]),
            rel(&fd[0][0], &fd[1][0]),
            rel(&fd[0][1], &fd[1][1]),
            rel(&fd[0][2], &fd[1][2]),
        ];
        println!("tree {t} ({n} joints): analytical against dual numbers {errs:?}");
        assert!(errs.iter().all(|e| *e <= 1e-12), "tree {t}: {errs:?}");
        // and the friction's derivative is in ∂τ/∂q̇'s diagonal: remove it, the rest changes only there
        let none = Dynamics { model: &model, loads, torques: &d::RigidBodyOnly, mass: None };
        let (mut a, mut b) = (vec![0.0; n * n], vec![0.0; n * n]);
        d::inverse_dynamics_derivatives(&none, &mut dw, [&q, &qd, &x], Formulation::Analytical, [&mut a, &mut b], None);
        for i in 0..n {
            for j in 0..n {
                let diff = out[0][1][i * n + j] - b[i * n + j];
                if i == j {
                    let v = qd[i];
                    let want = friction.0[i] + 0.3 * 0.01 / (v * v + 0.01).powf(1.5);
                    assert!(
                        (diff - want).abs() <= 1e-12 * want.abs().max(1.0),
                        "tree {t} [{i}][{i}]: {diff} vs {want}"
                    );
                } else {
                    assert!(diff.abs() <= 1e-12 * b.iter().fold(1.0_f64, |m, x| m.max(x.abs())), "tree {t} [{i}][{j}]");
                }
            }
        }
    }
}

/// Central differences in double-double on a floating base's manifold:
/// column j of ∂y/∂q moves q to q ⊕ (±h eⱼ) (the base by exp of the body
/// twist, as `floating::integrate`), the others as `central`.
fn central_floating(
    model: &Model,
    (q, qd, x): (&[f64], &[f64], &[f64]),
    wrt: Wrt,
    mut f: impl FnMut(&[Dd], &[Dd], &[Dd], &mut [Dd]),
) -> Vec<f64> {
    let nv = model.nv();
    let h = 1e-7;
    let dd = |v: &[f64]| v.iter().map(|&x| Dd::from(x)).collect::<Vec<_>>();
    let mut out = vec![0.0; nv * nv];
    let (mut plus, mut minus) = (vec![Dd::ZERO; nv], vec![Dd::ZERO; nv]);
    for j in 0..nv {
        for (sign, y) in [(1.0, &mut plus), (-1.0, &mut minus)] {
            let (mut a, mut b, mut c) = (dd(q), dd(qd), dd(x));
            match wrt {
                Wrt::Q => {
                    let mut step = vec![Dd::ZERO; nv];
                    step[j] = Dd::from(sign * h);
                    let from = a.clone();
                    dynagen::algorithms::floating::integrate(model, &from, &step, &mut a);
                }
                Wrt::Qd => b[j] += Dd::from(sign * h),
                Wrt::Third => c[j] += Dd::from(sign * h),
            }
            f(&a, &b, &c, y);
        }
        for i in 0..nv {
            out[i * nv + j] = ((plus[i] - minus[i]) / Dd::from(2.0 * h)).to_f64();
        }
    }
    out
}

/// A floating base (the quadruped12, the two-armed torso, the legged
/// manipulator, the humanoid32, a random tree
/// with prismatic joints and non-aligned axes, with a tip wrench): every
/// derivative against double-double central differences on the manifold,
/// ∂τ/∂q̈ = M, M·M⁻¹ = 1 and the chain rule; and both formulations agree.
#[test]
fn a_floating_base_matches_double_double_differences_on_the_manifold() {
    use dynagen::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation, RigidBodyOnly};
    let mut rng = Rng::new(0xf1_0a7);
    let tree = Model::from_urdf_str(&random_tree(&mut rng, 6)).unwrap();
    for (name, model) in [
        ("quadruped12", support::model("quadruped12")),
        ("torso_two_arms", support::model("torso_two_arms")),
        ("legged_manipulator", support::model("legged_manipulator")),
        ("humanoid32", support::model("humanoid32")),
        ("random tree", tree),
    ] {
        let model = model.with_floating_base();
        let (nq, nv) = (model.nq(), model.nv());
        let mut robot = Robot::new(model.clone());
        let frame = model.frames.iter().rposition(|f| f.body.is_some()).unwrap();
        let w = [0.3, -1.2, 0.7, 15.0, -4.0, 22.0];
        robot.set_tip_wrench(&model.frames[frame].name, nalgebra::Vector6::from_row_slice(&w)).unwrap();
        let tips = dd_tips(&[(frame, w)]);
        let g = Vec3(model.gravity.0.map(Dd::from));
        let loads = Loads::gravity(&g).with_tips(&tips);
        for k in 0..2 {
            let mut q = rng.vec(nq, 2.0);
            support::normalize_quaternion(&mut q);
            let (qd, qdd, tau) = (rng.vec(nv, 1.5), rng.vec(nv, 3.0), rng.vec(nv, 10.0));
            let v = |x: &Vec<f64>| DVector::from_vec(x.clone());
            let (dq, dqd) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &v(&qdd)).unwrap();
            let (fq, fqd, minv) = robot.forward_dynamics_derivatives(&v(&q), &v(&qd), &v(&tau)).unwrap();
            let m = robot.mass_matrix(&v(&q)).unwrap();
            let mut ws = Workspace::<Dd>::new(&model);
            let mut id =
                |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| rnea::rnea(&model, &mut ws, a, Some(b), Some(c), loads, y);
            let e_dq = err(&dq, &central_floating(&model, (&q, &qd, &qdd), Wrt::Q, &mut id));
            let e_dqd = err(&dqd, &central_floating(&model, (&q, &qd, &qdd), Wrt::Qd, &mut id));
            let e_m = err(&m, &central_floating(&model, (&q, &qd, &qdd), Wrt::Third, &mut id));
            let mut ws2 = Workspace::<Dd>::new(&model);
            let mut fd = |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| aba::aba(&model, &mut ws2, a, b, c, loads, y);
            let e_fq = err(&fq, &central_floating(&model, (&q, &qd, &tau), Wrt::Q, &mut fd));
            let e_fqd = err(&fqd, &central_floating(&model, (&q, &qd, &tau), Wrt::Qd, &mut fd));
            let e_minv = err(&minv, &central_floating(&model, (&q, &qd, &tau), Wrt::Third, &mut fd));
            let e_eye = (&m * &minv - DMatrix::identity(nv, nv)).norm();
            let at = robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap();
            let (dq_at, _) = robot.inverse_dynamics_derivatives(&v(&q), &v(&qd), &at).unwrap();
            let e_chain = ((-&minv * dq_at) - &fq).norm() / fq.norm();
            // the dual numbers give the same (tip wrench and gravity held constant)
            let g64 = model.gravity;
            let tips64 = [TipWrench { frame, wrench: Force::from_array(w) }];
            let dynamics = Dynamics {
                model: &model,
                loads: Loads::gravity(&g64).with_tips(&tips64),
                torques: &RigidBodyOnly,
                mass: None,
            };
            let mut dw = DerivativeWorkspace::new(&model);
            let (mut a, mut b) = (vec![0.0; nv * nv], vec![0.0; nv * nv]);
            let state = [q.as_slice(), qd.as_slice(), qdd.as_slice()];
            d::inverse_dynamics_derivatives(
                &dynamics,
                &mut dw,
                state,
                Formulation::DualNumbers,
                [&mut a, &mut b],
                None,
            );
            let e_dual = err(&dq, &a) + err(&dqd, &b);
            let all = [e_dq, e_dqd, e_m, e_fq, e_fqd, e_minv, e_eye, e_chain, e_dual];
            let msg = format!(
                "{name} (floating) state {k}: dtau/dq {e_dq:.1e}, dtau/dqd {e_dqd:.1e}, M {e_m:.1e}, dqdd/dq {e_fq:.1e}, \
                 dqdd/dqd {e_fqd:.1e}, Minv {e_minv:.1e}, M Minv - 1 {e_eye:.1e}, chain {e_chain:.1e}, dual {e_dual:.1e}"
            );
            println!("{msg}");
            assert!(all.iter().all(|e| *e <= 1e-9), "{msg}");
        }
    }
}

/// A floating-base scene (the legged manipulator: armature, viscous and
/// Coulomb friction on the joints, a constant payload on the floating trunk,
/// a run-time payload on the arm, gravity and a foot's wrench as inputs):
/// `SceneRobot`'s derivatives against double-double central differences on
/// the manifold of the scene's own dynamics with the inputs held constant,
/// M·M⁻¹ = 1, and M⁻¹ alone equal to the forward dynamics' third matrix.
#[test]
fn a_floating_scene_enters_its_derivatives() {
    use dynagen::scene::{dynamics, Gravity, PayloadInertia, Scene, SceneInputs, SceneRobot};
    let model = support::model("legged_manipulator").with_floating_base();
    let trunk = PayloadInertia::new(3.0, [0.05, -0.02, 0.06], [0.02, 0.03, 0.04, 0.002, -0.001, 0.0005]);
    let arm = [PayloadInertia::new(0.5, [0.04, 0.0, 0.01], [0.0005, 0.0006, 0.0004, 0.0, 0.0, 0.0])];
    let applied = Scene::new()
        .gravity(Gravity::Input)
        .tip_wrench("RL_foot")
        .payload("trunk", trunk)
        .payload_input("arm_link06")
        .armature("FL_hip_joint", 0.011)
        .armature("arm_joint2", 0.004)
        .viscous("RR_calf_joint", 0.3)
        .coulomb("arm_joint1", 1.2)
        .coulomb_velocity(0.05)
        .apply(&model)
        .unwrap();
    let frame = applied.tip_wrench_frame.unwrap();
    let mut robot = SceneRobot::new(applied);
    let (nq, nv) = (model.nq(), model.nv());
    let (g, w) = ([1.5, -0.7, -9.6], [0.3, -1.2, 0.7, 15.0, -4.0, 22.0]);
    let inputs = SceneInputs {
        gravity: Some(nalgebra::Vector3::from(g)),
        tip_wrench: Some(nalgebra::Vector6::from(w)),
        payloads: &arm,
    };
    let (gd, tips) = (Vec3(g.map(Dd::from)), dd_tips(&[(frame, w)]));
    let loads = Loads::gravity(&gd).with_tips(&tips);
    let mut rng = Rng::new(0x5ce4e);
    for k in 0..2 {
        let mut q = rng.vec(nq, 2.0);
        support::normalize_quaternion(&mut q);
        // the arm's Coulomb joint well inside its smooth sign's slope
        let (mut qd, qdd, tau) = (rng.vec(nv, 1.5), rng.vec(nv, 3.0), rng.vec(nv, 10.0));
        qd[6 + model.bodies.iter().position(|b| b.joint.name == "arm_joint1").unwrap()] = 0.03;
        let v = |x: &Vec<f64>| DVector::from_vec(x.clone());
        let (dq, dqd) = robot.inverse_dynamics_derivatives_with(&v(&q), &v(&qd), &v(&qdd), &inputs).unwrap();
        let (fq, fqd, minv) = robot.forward_dynamics_derivatives_with(&v(&q), &v(&qd), &v(&tau), &inputs).unwrap();
        let m = robot.mass_matrix_with(&v(&q), &inputs).unwrap();
        let minv_alone = robot.mass_matrix_inverse_with(&v(&q), &inputs).unwrap();
        // The scene as the last call left it: the run-time payload in its model.
        let scene = robot.scene().clone();
        let mut ws = Workspace::<Dd>::new(&scene.model);
        let mut id =
            |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| dynamics::inverse_dynamics(&scene, &mut ws, a, b, c, loads, y);
        let at = (&q[..], &qd[..], &qdd[..]);
        let (e_dq, e_dqd, e_m) = (
            err(&dq, &central_floating(&scene.model, at, Wrt::Q, &mut id)),
            err(&dqd, &central_floating(&scene.model, at, Wrt::Qd, &mut id)),
            err(&m, &central_floating(&scene.model, at, Wrt::Third, &mut id)),
        );
        let mut ws = Workspace::<Dd>::new(&scene.model);
        let mut fd =
            |a: &[Dd], b: &[Dd], c: &[Dd], y: &mut [Dd]| dynamics::forward_dynamics(&scene, &mut ws, a, b, c, loads, y);
        let at = (&q[..], &qd[..], &tau[..]);
        let (e_fq, e_fqd, e_minv) = (
            err(&fq, &central_floating(&scene.model, at, Wrt::Q, &mut fd)),
            err(&fqd, &central_floating(&scene.model, at, Wrt::Qd, &mut fd)),
            err(&minv, &central_floating(&scene.model, at, Wrt::Third, &mut fd)),
        );
        let e_eye = (&m * &minv - DMatrix::identity(nv, nv)).norm();
        let e_alone = (&minv_alone - &minv).norm() / minv.norm();
        let all = [e_dq, e_dqd, e_m, e_fq, e_fqd, e_minv, e_eye, e_alone];
        let msg = format!(
            "legged manipulator scene state {k}: dtau/dq {e_dq:.1e}, dtau/dqd {e_dqd:.1e}, M {e_m:.1e}, \
             dqdd/dq {e_fq:.1e}, dqdd/dqd {e_fqd:.1e}, Minv {e_minv:.1e}, M Minv - 1 {e_eye:.1e}, Minv alone {e_alone:.1e}"
        );
        println!("{msg}");
        assert!(all.iter().all(|e| *e <= 1e-9), "{msg}");
    }
}
