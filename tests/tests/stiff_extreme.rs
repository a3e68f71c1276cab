//! Stiff and extreme robots: the generic solver in f64 against the same
//! algorithms in double-double (≈32 digits), which serves as the reference.
//!
//! Every output must be finite, M symmetric positive definite, and the f64
//! errors within the bounds stated (and justified) at each check. The large
//! sweeps belong to the report; these cases are quick.

use dynagen::algorithms::{aba, bias, crba, forward_dynamics, rnea, Workspace};
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, Model, Scalar};
use dynagen_tests::{chain, rel_err, LinkSpec, Rng};
use nalgebra::{DMatrix, DVector};

const EPS: f64 = f64::EPSILON;

/// Every output of the solver at one state, as f64.
#[derive(Debug)]
struct Outputs {
    tau: Vec<f64>,
    m: Vec<f64>,
    h: Vec<f64>,
    g: Vec<f64>,
    qdd_aba: Vec<f64>,
    qdd_ldlt: Vec<f64>,
}

fn eval<S: Scalar>(model: &Model, q: &[f64], qd: &[f64], qdd: &[f64], tau: &[f64]) -> Outputs {
    let n = model.dof();
    let c = |x: &[f64]| x.iter().map(|&v| S::from_f64(v)).collect::<Vec<S>>();
    let back = |x: &[S]| x.iter().map(|v| v.to_f64().unwrap()).collect::<Vec<f64>>();
    let (q, qd, qdd, tau) = (c(q), c(qd), c(qdd), c(tau));
    let grav = Vec3::<S>::from_f64(&model.gravity);
    let mut ws = Workspace::<S>::new(model);
    let mut out = vec![S::zero(); n];
    rnea::rnea(model, &mut ws, &q, Some(&qd), Some(&qdd), Some(&grav), &[], &mut out);
    let tau_out = back(&out);
    let mut m = vec![S::zero(); n * n];
    crba::crba(model, &mut ws, &q, &mut m);
    bias::bias_forces(model, &mut ws, &q, &qd, Some(&grav), &mut out);
    let h = back(&out);
    bias::gravity_torques(model, &mut ws, &q, &grav, &mut out);
    let g = back(&out);
    aba::aba(model, &mut ws, &q, &qd, &tau, Some(&grav), &[], &mut out);
    let qdd_aba = back(&out);
    forward_dynamics::forward_dynamics_ldlt(model, &mut ws, &q, &qd, &tau, Some(&grav), &[], &mut out);
    Outputs { tau: tau_out, m: back(&m), h, g, qdd_aba, qdd_ldlt: back(&out) }
}

/// The 2-norm condition number of a symmetric matrix and whether it is
/// positive definite (eigenvalues from nalgebra, in f64: enough to print an
/// order of magnitude and to see the sign).
fn spd_condition(n: usize, m: &[f64]) -> (f64, bool) {
    let mat = DMatrix::from_row_slice(n, n, m);
    let symmetric = (0..n).all(|i| (0..n).all(|j| m[i * n + j] == m[j * n + i]));
    let ev = mat.symmetric_eigenvalues();
    let (lo, hi) = (ev.min(), ev.max());
    (hi / lo, symmetric && lo > 0.0)
}

struct Case {
    name: &'static str,
    model: Model,
    q_scale: f64,
    qd_scale: f64,
}

/// Worst errors over a case's states.
struct Worst {
    id: f64,
    aba: f64,
    ldlt: f64,
    cond: f64,
}

/// Checks one robot at a few random states and returns the worst errors.
fn check(case: &Case, states: usize, fd_bound_factor: f64) -> Worst {
    let n = case.model.dof();
    let mut rng = Rng::new(0x5eed ^ n as u64);
    let mut w = Worst { id: 0.0, aba: 0.0, ldlt: 0.0, cond: 0.0 };
    for k in 0..states {
        let q = rng.vec(n, case.q_scale);
        let qd = rng.vec(n, case.qd_scale);
        let qdd = rng.vec(n, 10.0);
        let tau = rng.vec(n, 10.0);
        let f = eval::<f64>(&case.model, &q, &qd, &qdd, &tau);
        let r = eval::<DoubleDouble>(&case.model, &q, &qd, &qdd, &tau);
        let ctx = format!("{} (n = {n}), state {k}", case.name);
        for (what, x) in
            [("tau", &f.tau), ("M", &f.m), ("h", &f.h), ("g", &f.g), ("ABA", &f.qdd_aba), ("LTDL", &f.qdd_ldlt)]
        {
            assert!(x.iter().all(|v| v.is_finite()), "{ctx}: {what} has a non-finite entry: {x:?}");
        }
        let (cond, spd) = spd_condition(n, &f.m);
        assert!(spd, "{ctx}: M is not symmetric positive definite (cond {cond:e})");
        w.cond = w.cond.max(cond);
        // τ, M, h and g: each entry is a sum of O(n) products along the
        // tree, so its rounding error is O(n)·ε relative to the largest
        // term; bounded by 100·n·ε relative to the output's largest entry.
        let id_bound = 100.0 * n as f64 * EPS;
        for (what, a, b) in [("tau", &f.tau, &r.tau), ("M", &f.m, &r.m), ("h", &f.h, &r.h), ("g", &f.g, &r.g)] {
            let e = rel_err(a, b, 0.0);
            assert!(e <= id_bound, "{ctx}: {what} relative error {e:e} > {id_bound:e}");
            w.id = w.id.max(e);
        }
        // Forward dynamics solves M q̈ = τ − h. A backward-stable method's
        // error is bounded by cond(M)·ε relative to the solution the
        // right-hand side's size stands for: ‖τ‖ + ‖h‖ can be far larger
        // than ‖M q̈‖ when they cancel.
        let rhs_scale: f64 = r.h.iter().chain(&tau).fold(0.0, |m, x| m.max(x.abs()));
        let m_norm = DMatrix::from_row_slice(n, n, &r.m).norm();
        let qdd_scale = r.qdd_aba.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let implied = rhs_scale / m_norm;
        let fd_bound = fd_bound_factor * cond * EPS * (1.0 + implied / qdd_scale.max(f64::MIN_POSITIVE));
        let e_aba = rel_err(&f.qdd_aba, &r.qdd_aba, 0.0);
        let e_ldlt = rel_err(&f.qdd_ldlt, &r.qdd_aba, 0.0);
        assert!(e_aba <= fd_bound, "{ctx}: ABA relative error {e_aba:e} > {fd_bound:e} (cond {cond:e})");
        assert!(e_ldlt <= fd_bound, "{ctx}: LTDL relative error {e_ldlt:e} > {fd_bound:e} (cond {cond:e})");
        // The two double-double forward dynamics agree with each other.
        let e_ref = rel_err(&r.qdd_ldlt, &r.qdd_aba, 0.0);
        assert!(e_ref <= 1e-20 * cond.max(1.0), "{ctx}: double-double ABA and LTDL differ by {e_ref:e}");
        w.aba = w.aba.max(e_aba);
        w.ldlt = w.ldlt.max(e_ldlt);
    }
    eprintln!(
        "{:<24} n={n:<3} cond(M) ≤ {:9.2e}  τ/M/h/g err ≤ {:9.2e}  ABA err ≤ {:9.2e}  LTDL err ≤ {:9.2e}",
        case.name, w.cond, w.id, w.aba, w.ldlt
    );
    w
}

fn spec(mass: f64, length: f64, axis: [f64; 3]) -> LinkSpec {
    LinkSpec { mass, length, axis, prismatic: false }
}

fn random_axes(rng: &mut Rng, n: usize, mass: impl Fn(usize) -> f64, length: impl Fn(usize) -> f64) -> Vec<LinkSpec> {
    (0..n)
        .map(|i| LinkSpec { mass: mass(i), length: length(i), axis: rng.unit_vector(), prismatic: i % 5 == 4 })
        .collect()
}

#[test]
fn ordinary_chain_is_accurate() {
    let mut rng = Rng::new(1);
    let links = random_axes(&mut rng, 7, |_| 2.0, |_| 0.3);
    let case = Case { name: "ordinary 7-link chain", model: chain("ordinary", &links), q_scale: 3.0, qd_scale: 2.0 };
    check(&case, 20, 10.0);
}

#[test]
fn mass_ratios_of_a_million_between_neighbours() {
    // Heavy to light: 1e6 kg down to 1e-6 kg, a ratio of 1e6 each step, then
    // alternating 1e-3 / 1e3 (a ratio of 1e6 the other way too).
    let mut rng = Rng::new(2);
    let masses = [1e6, 1.0, 1e-6, 1e-3, 1e3, 1e-3, 1e3];
    let links = random_axes(&mut rng, masses.len(), |i| masses[i], |_| 0.5);
    let case = Case { name: "mass ratios 1e-6..1e6", model: chain("mass_ratios", &links), q_scale: 3.0, qd_scale: 2.0 };
    check(&case, 20, 10.0);
}

#[test]
fn link_lengths_from_a_millimetre_to_a_hundred_metres() {
    let mut rng = Rng::new(3);
    let lengths = [1e2, 1e-3, 1.0, 1e-3, 1e2, 0.1, 1e-3];
    let links = random_axes(&mut rng, lengths.len(), |_| 1.0, |i| lengths[i]);
    let case = Case { name: "lengths 1e-3..1e2 m", model: chain("lengths", &links), q_scale: 3.0, qd_scale: 2.0 };
    check(&case, 20, 10.0);
}

#[test]
fn fast_joints_and_huge_angles() {
    let mut rng = Rng::new(4);
    let links = random_axes(&mut rng, 6, |_| 1.5, |_| 0.4);
    let model = chain("fast", &links);
    let fast = Case { name: "|qd| up to 1e3 rad/s", model: model.clone(), q_scale: 3.0, qd_scale: 1e3 };
    check(&fast, 20, 10.0);
    let wound = Case { name: "|q| up to 1e4 rad", model, q_scale: 1e4, qd_scale: 2.0 };
    check(&wound, 20, 10.0);
}

#[test]
fn sixty_four_joint_chain() {
    let mut rng = Rng::new(5);
    let links = random_axes(&mut rng, 64, |_| 1.0, |_| 0.1);
    let case = Case { name: "64-joint chain", model: chain("long", &links), q_scale: 3.0, qd_scale: 2.0 };
    let w = check(&case, 3, 10.0);
    // The articulated-body algorithm is the accurate one on long chains.
    assert!(w.aba <= w.ldlt * 10.0, "ABA {:e} is much worse than LTDL {:e}", w.aba, w.ldlt);
}

#[test]
fn nearly_dependent_joint_axes() {
    // Two joints at the same point with axes 1e-5 rad apart: M is nearly
    // singular (cond ≈ 1e10) and every method loses ε·cond(M).
    let eps = 1e-5;
    let links = vec![
        spec(1.0, 0.0, [0.0, 0.0, 1.0]),
        spec(1.0, 0.5, [eps.sin(), 0.0, eps.cos()]),
        spec(1.0, 0.5, [0.0, 1.0, 0.0]),
        spec(1.0, 0.5, [1.0, 0.0, 0.0]),
    ];
    let case = Case { name: "axes 1e-5 rad apart", model: chain("dependent", &links), q_scale: 3.0, qd_scale: 2.0 };
    let w = check(&case, 20, 10.0);
    assert!(w.cond > 1e8, "the case should be ill-conditioned, cond(M) = {:e}", w.cond);
}

#[test]
fn non_finite_input_is_an_error_naming_the_joint() {
    let mut rng = Rng::new(6);
    let links = random_axes(&mut rng, 3, |_| 1.0, |_| 0.3);
    let mut robot = dynagen::Robot::new(chain("nan", &links));
    let ok = DVector::from_vec(vec![0.1, 0.2, 0.3]);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let q = DVector::from_vec(vec![0.1, bad, 0.3]);
        let err = robot.inverse_dynamics(&q, &ok, &ok).unwrap_err().to_string();
        assert!(err.contains("q[1]") && err.contains("joint1"), "{err}");
        let err = robot.forward_dynamics(&ok, &ok, &q).unwrap_err().to_string();
        assert!(err.contains("tau[1]") && err.contains("joint1"), "{err}");
        let err = robot.mass_matrix(&q).unwrap_err().to_string();
        assert!(err.contains("q[1]"), "{err}");
    }
    let short = DVector::from_vec(vec![0.1, 0.2]);
    let err = robot.bias_forces(&ok, &short).unwrap_err().to_string();
    assert!(err.contains("qd") && err.contains('2') && err.contains('3'), "{err}");
}

/// Worst relative errors of ABA f64 and of the compensated forward dynamics
/// over `states` states from `gen`, against the double-double reference.
fn compensated_vs_aba(
    model: &Model,
    states: usize,
    mut gen: impl FnMut(&mut Rng) -> (Vec<f64>, Vec<f64>, Vec<f64>),
) -> (f64, f64) {
    let mut robot = dynagen::Robot::new(model.clone());
    let mut rng = Rng::new(0xc0 ^ model.dof() as u64);
    let (mut worst_aba, mut worst_comp) = (0.0f64, 0.0f64);
    for k in 0..states {
        let (q, qd, tau) = gen(&mut rng);
        let reference = dynagen_tests::reference_forward_dynamics(model, &q, &qd, &tau);
        let v = |x: &[f64]| DVector::from_column_slice(x);
        let a = robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap();
        let c = robot.forward_dynamics_compensated(&v(&q), &v(&qd), &v(&tau)).unwrap();
        let (ea, ec) = (rel_err(a.as_slice(), &reference, 0.0), rel_err(c.as_slice(), &reference, 0.0));
        eprintln!("{} state {k}: ABA {ea:e} compensated {ec:e}", model.name);
        worst_aba = worst_aba.max(ea);
        worst_comp = worst_comp.max(ec);
    }
    (worst_aba, worst_comp)
}

#[test]
fn compensated_forward_dynamics_wins_digits_on_cancelling_states() {
    let mut rng = Rng::new(9);
    let stiff = chain(
        "stiff",
        &random_axes(
            &mut rng,
            8,
            |i| [1e3, 1e-3, 1.0, 1e2, 1e-2, 1.0, 1e-1, 10.0][i],
            |i| [1.0, 0.01, 0.3, 2.0, 0.05, 0.5, 0.1, 1.0][i],
        ),
    );
    for model in [dynagen_tests::bundled_model("ur5"), dynagen_tests::bundled_model("panda"), stiff] {
        let n = model.dof();
        let (aba, comp) =
            compensated_vs_aba(&model, 10, |rng| dynagen_tests::cancelling_state(&model, rng, 3.0, 100.0, 1e-2));
        eprintln!("{}: ABA {aba:e} compensated {comp:e}", model.name);
        let (aba, comp) = compensated_vs_aba(&model, 10, |rng| (rng.vec(n, 3.0), rng.vec(n, 2.0), rng.vec(n, 10.0)));
        eprintln!("{} ordinary: ABA {aba:e} compensated {comp:e}", model.name);
    }
}
