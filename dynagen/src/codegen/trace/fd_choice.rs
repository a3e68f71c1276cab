//! Which forward dynamics a module emits when the options leave it to the
//! generator ([`ForwardDynamicsMethod::Auto`]).
//!
//! Both are traced. The articulated-body algorithm (ABA) is the accurate
//! one on long chains (`docs/performance.md` has the errors); on short ones both are accurate and CRBA + LᵀDL is the faster body: its
//! critical path is about half of ABA's, whose inward pass waits on one
//! division per joint and on the articulated inertia that depends on it.
//! So the generator measures instead of guessing:
//!
//! - **accuracy**: each of the two traced functions is evaluated in `f64`
//!   on [`STATES`] fixed pseudo-random states (q in ±π rad, q̇ in ±2 rad/s,
//!   τ in ±20 N·m, a scene's gravity and tip wrench in ±10) and compared
//!   with the ABA evaluated in double-double; the error of a state is the
//!   norm of the difference over the norm of the reference;
//! - **speed**: estimated cycles of the body, the larger of its
//!   [`CriticalPath`](crate::symbolic::CriticalPath) and its operation
//!   count over two (a core that issues two floating-point operations a
//!   cycle). Where the ABA's branches run in loops (`branch_loops`, which
//!   LᵀDL does not have), its count is what a call issues: each group's
//!   body once, in vector lanes (f64), or once a branch (f32).
//!
//! LᵀDL is chosen when it is estimated faster and its worst error is at
//! most twice ABA's plus 2 ε (a difference of an ulp or two, the level of
//! rounding noise); otherwise ABA. The states are fixed, so the choice is
//! deterministic. Each module's header says which was chosen and gives
//! both figures.

use crate::codegen::ForwardDynamicsMethod;
use crate::symbolic::Traced;
use crate::DoubleDouble;

/// How many states the accuracy comparison uses.
pub const STATES: usize = 16;

/// The forward dynamics chosen, and why (for the header).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FdChoice {
    /// ABA or LᵀDL.
    pub method: ForwardDynamicsMethod,
    /// One sentence for the header.
    pub why: String,
}

/// Estimated cycles of a body: see the [module documentation](self).
pub(crate) fn estimated_cycles(body: &Traced) -> usize {
    (body.critical_path().cycles as usize).max(body.op_count().total().div_ceil(2))
}

/// The scale of the pseudo-random values an input of this name gets: q in
/// ±π rad, q̇ in ±2 rad/s, τ in ±20 N·m, anything else (a scene's gravity,
/// tip wrench) in ±10.
fn scale_of(name: &str) -> f64 {
    match name {
        "q" => core::f64::consts::PI,
        "qd" => 2.0,
        "tau" => 20.0,
        _ => 10.0,
    }
}

/// The worst relative errors (ABA, LᵀDL) against the double-double ABA,
/// both functions taking `inputs` (names and lengths, in the order their
/// values are drawn).
fn errors(aba: &Traced, ldlt: &Traced, inputs: &[(String, usize)]) -> (f64, f64) {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move |scale: f64| {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        let x = state.wrapping_mul(0x2545_f491_4f6c_dd1d);
        scale * ((x >> 11) as f64 / (1u64 << 52) as f64 - 1.0)
    };
    let (mut e_aba, mut e_ldlt) = (0.0f64, 0.0f64);
    for _ in 0..STATES {
        let values: Vec<Vec<f64>> =
            inputs.iter().map(|(name, len)| (0..*len).map(|_| next(scale_of(name))).collect()).collect();
        let named: Vec<(&str, &[f64])> =
            inputs.iter().zip(&values).map(|((name, _), v)| (name.as_str(), v.as_slice())).collect();
        let (Ok(reference), Ok(a), Ok(l)) = (aba.eval_as::<DoubleDouble>(&named), aba.eval(&named), ldlt.eval(&named))
        else {
            return (0.0, f64::INFINITY);
        };
        let norm = reference.iter().map(|r| r.to_f64() * r.to_f64()).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
        let err = |x: &[f64]| {
            let d: f64 = x.iter().zip(&reference).map(|(x, r)| (DoubleDouble::from(*x) - *r).to_f64().powi(2)).sum();
            d.sqrt() / norm
        };
        e_aba = e_aba.max(err(&a));
        e_ldlt = e_ldlt.max(err(&l));
    }
    (e_aba, e_ldlt)
}

/// Chooses between a traced ABA and LᵀDL, each given as (the function of
/// `q`, its body with the sines and cosines as inputs), both taking
/// `inputs` (a scene's forward dynamics may take a gravity vector and a tip
/// wrench after q, q̇ and τ). `branched`: the FP operations a call of the
/// ABA issues where its branches run in loops (each group's body once in
/// vector lanes), which replace its operation count in the estimate.
pub(crate) fn choose_between(
    aba: [&Traced; 2],
    ldlt: [&Traced; 2],
    branched: Option<usize>,
    inputs: &[(String, usize)],
) -> FdChoice {
    let ca = match branched {
        Some(ops) => (aba[1].critical_path().cycles as usize).max(ops.div_ceil(2)),
        None => estimated_cycles(aba[1]),
    };
    let cl = estimated_cycles(ldlt[1]);
    let (ea, el) = errors(aba[0], ldlt[0], inputs);
    let accurate = el <= 2.0 * ea + 2.0 * f64::EPSILON;
    let method = if cl < ca && accurate { ForwardDynamicsMethod::Ldlt } else { ForwardDynamicsMethod::Aba };
    let loops = if branched.is_some() { " (its branches in loops)" } else { "" };
    let measured = format!(
        "estimated {cl} cycles for CRBA + LTDL against {ca} for the articulated-body algorithm{loops}; worst \
         relative error on {STATES} states against double-double {el:.1e} against {ea:.1e}"
    );
    let why = match method {
        ForwardDynamicsMethod::Ldlt => format!("CRBA + LTDL, chosen as faster and as accurate ({measured})"),
        _ if !accurate => format!("the articulated-body algorithm, chosen as the more accurate ({measured})"),
        _ => format!("the articulated-body algorithm, chosen as the faster ({measured})"),
    };
    FdChoice { method, why }
}
