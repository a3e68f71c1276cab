//! A planar two-link arm against its closed-form dynamics.
//!
//! The arm: joint 1 (shoulder) at the base origin and joint 2 (elbow) at
//! (l₁, 0, 0) in link 1's frame, both revolute about y. Each link is a
//! uniform solid cylinder of mass mᵢ, length lᵢ and radius r along its x
//! axis, starting at its joint: centre of mass at (lᵢ/2, 0, 0), inertia
//! about it diag(mᵢr²/2, mᵢ(3r² + lᵢ²)/12, mᵢ(3r² + lᵢ²)/12). Gravity is
//! (0, 0, −g₀), g₀ = 9.81 m/s².
//!
//! Derivation. A rotation by θ about y takes (x, 0, 0) to (x cos θ, 0,
//! −x sin θ), so with cᵢ = cos qᵢ, sᵢ = sin qᵢ, c₁₂ = cos(q₁ + q₂),
//! s₁₂ = sin(q₁ + q₂) and lcᵢ = lᵢ/2 the centres of mass are
//!   p₁ = lc₁ (c₁, 0, −s₁),  p₂ = l₁ (c₁, 0, −s₁) + lc₂ (c₁₂, 0, −s₁₂),
//! and the links turn about y at ω₁ = q̇₁ and ω₂ = q̇₁ + q̇₂. With
//! Iᵢ = mᵢ(3r² + lᵢ²)/12 (the inertia about the y axis through the centre of
//! mass),
//!   |ṗ₁|² = lc₁² q̇₁²,
//!   |ṗ₂|² = l₁² q̇₁² + lc₂² (q̇₁ + q̇₂)² + 2 l₁ lc₂ c₂ q̇₁ (q̇₁ + q̇₂),
//!   T = ½ m₁|ṗ₁|² + ½ I₁ q̇₁² + ½ m₂|ṗ₂|² + ½ I₂ (q̇₁ + q̇₂)² = ½ q̇ᵀ M(q) q̇,
//! so
//!   M₁₁ = I₁ + I₂ + m₁ lc₁² + m₂ (l₁² + lc₂² + 2 l₁ lc₂ c₂),
//!   M₁₂ = M₂₁ = I₂ + m₂ (lc₂² + l₁ lc₂ c₂),
//!   M₂₂ = I₂ + m₂ lc₂².
//! Only M₁₁ and M₁₂ depend on q, through q₂: with b = m₂ l₁ lc₂ s₂,
//! ∂M₁₁/∂q₂ = −2b, ∂M₁₂/∂q₂ = −b. The Christoffel form
//! (C q̇)ᵢ = Σⱼₖ (∂Mᵢⱼ/∂qₖ − ½ ∂Mⱼₖ/∂qᵢ) q̇ⱼ q̇ₖ gives
//!   (C q̇)₁ = −2b q̇₁q̇₂ − b q̇₂² = −b (2 q̇₁ q̇₂ + q̇₂²),
//!   (C q̇)₂ = −b q̇₁q̇₂ + ½ (2b q̇₁² + 2b q̇₁q̇₂) = b q̇₁².
//! The potential energy is V = −Σ mᵢ g·pᵢ = g₀ Σ mᵢ zᵢ with z₁ = −lc₁ s₁,
//! z₂ = −l₁ s₁ − lc₂ s₁₂, so g(q) = ∂V/∂q:
//!   g₁ = −g₀ ((m₁ lc₁ + m₂ l₁) c₁ + m₂ lc₂ c₁₂),
//!   g₂ = −g₀ m₂ lc₂ c₁₂.
//! The radius enters only through Iᵢ; the inertia about the link's own axis
//! (mᵢr²/2) never moves, since both joints turn about y.

use approx::abs_diff_eq;
use dynagen::model::{Inertial, JointDescription};
use dynagen::{Robot, RobotBuilder};
use nalgebra::{DVector, Matrix2, Vector2};

const L1: f64 = 0.7;
const L2: f64 = 0.45;
const M1: f64 = 2.3;
const M2: f64 = 1.1;
const R: f64 = 0.03;
const G0: f64 = 9.81;

fn rod(m: f64, l: f64) -> Inertial {
    let across = m * (3.0 * R * R + l * l) / 12.0;
    Inertial::new(m, [l / 2.0, 0.0, 0.0], [m * R * R / 2.0, across, across, 0.0, 0.0, 0.0])
}

fn arm() -> Robot {
    let model = RobotBuilder::new("planar_2link")
        .link("base", None)
        .link("upper", Some(rod(M1, L1)))
        .link("fore", Some(rod(M2, L2)))
        .joint(JointDescription::revolute("shoulder", "base", "upper", [0.0, 1.0, 0.0]))
        .joint(JointDescription::revolute("elbow", "upper", "fore", [0.0, 1.0, 0.0]).origin([L1, 0.0, 0.0], [0.0; 3]))
        .build()
        .unwrap();
    Robot::new(model)
}

struct ClosedForm {
    m: Matrix2<f64>,
    c: Vector2<f64>,
    g: Vector2<f64>,
}

fn closed_form(q: [f64; 2], qd: [f64; 2]) -> ClosedForm {
    let (lc1, lc2) = (L1 / 2.0, L2 / 2.0);
    let i1 = M1 * (3.0 * R * R + L1 * L1) / 12.0;
    let i2 = M2 * (3.0 * R * R + L2 * L2) / 12.0;
    let (c1, c2, c12, s2) = (q[0].cos(), q[1].cos(), (q[0] + q[1]).cos(), q[1].sin());
    let m11 = i1 + i2 + M1 * lc1 * lc1 + M2 * (L1 * L1 + lc2 * lc2 + 2.0 * L1 * lc2 * c2);
    let m12 = i2 + M2 * (lc2 * lc2 + L1 * lc2 * c2);
    let m22 = i2 + M2 * lc2 * lc2;
    let b = M2 * L1 * lc2 * s2;
    ClosedForm {
        m: Matrix2::new(m11, m12, m12, m22),
        c: Vector2::new(-b * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]), b * qd[0] * qd[0]),
        g: Vector2::new(-G0 * ((M1 * lc1 + M2 * L1) * c1 + M2 * lc2 * c12), -G0 * M2 * lc2 * c12),
    }
}

const STATES: [([f64; 2], [f64; 2], [f64; 2]); 6] = [
    ([0.0, 0.0], [0.0, 0.0], [0.0, 0.0]),
    ([0.3, -0.8], [1.2, -0.4], [0.5, 2.0]),
    ([-1.9, 2.4], [-3.0, 2.5], [-1.0, 0.25]),
    ([std::f64::consts::FRAC_PI_2, 0.0], [0.0, 7.0], [3.0, -3.0]),
    ([2.8, -3.1], [0.01, -5.5], [0.0, 0.0]),
    ([40.0, -17.5], [9.0, 11.0], [-20.0, 13.0]),
];

/// |got − want| ≤ 1e-12 (1 + max |want|), entrywise (column-major slices),
/// by `approx`.
fn close(what: &str, got: &[f64], want: &[f64]) {
    let epsilon = 1e-12 * (1.0 + want.iter().fold(0.0f64, |a, x| a.max(x.abs())));
    assert!(abs_diff_eq!(got, want, epsilon = epsilon), "{what}: {got:?} vs {want:?} (ε {epsilon:e})");
}

#[test]
fn mass_matrix_coriolis_gravity_and_inverse_dynamics() {
    let mut r = arm();
    assert_eq!(r.joint_names(), ["shoulder", "elbow"]);
    for (q, qd, qdd) in STATES {
        let cf = closed_form(q, qd);
        let (qv, qdv, qddv) =
            (DVector::from_row_slice(&q), DVector::from_row_slice(&qd), DVector::from_row_slice(&qdd));
        let m = r.mass_matrix(&qv).unwrap();
        close("M", m.as_slice(), cf.m.as_slice());
        let c = r.coriolis_torques(&qv, &qdv).unwrap();
        close("C q̇", c.as_slice(), cf.c.as_slice());
        let g = r.gravity_torques(&qv).unwrap();
        close("g", g.as_slice(), cf.g.as_slice());
        let tau = r.inverse_dynamics(&qv, &qdv, &qddv).unwrap();
        let want = cf.m * Vector2::from(qdd) + cf.c + cf.g;
        close("τ", tau.as_slice(), want.as_slice());
        // and back: the closed-form solve of M q̈ = τ − C q̇ − g
        let qdd_fd = r.forward_dynamics(&qv, &qdv, &tau).unwrap();
        let want = cf.m.try_inverse().unwrap() * (Vector2::new(tau[0], tau[1]) - cf.c - cf.g);
        close("q̈", qdd_fd.as_slice(), want.as_slice());
    }
}
