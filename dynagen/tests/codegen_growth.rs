//! Operation counts over serial chains of 2 to 64 joints: linear in the
//! number of joints for τ (RNEA is O(n)), quadratic for M (n(n+1)/2
//! entries, each a projection of a force carried up the chain).

#[path = "support/skewed_chain.rs"]
mod skewed_chain;

use dynagen::codegen::{trace, FunctionKind};
use dynagen::symbolic::Rewrites;
use dynagen::Model;
use skewed_chain::skewed_chain as chain;

#[test]
fn op_counts_grow_linearly_for_tau_and_quadratically_for_m() {
    let sizes = [2usize, 4, 8, 16, 32, 64];
    let mut rows = Vec::new();
    println!("{:>6} {:>10} {:>10} {:>10} {:>10}", "joints", "tau", "tau/n", "M", "M/n^2");
    for &n in &sizes {
        let model = chain(n);
        let tau = trace(&model, FunctionKind::InverseDynamics, Rewrites::default()).unwrap().op_count().total();
        let m = trace(&model, FunctionKind::MassMatrix, Rewrites::default()).unwrap().op_count().total();
        println!("{n:>6} {tau:>10} {:>10.1} {m:>10} {:>10.1}", tau as f64 / n as f64, m as f64 / (n * n) as f64);
        rows.push((n, tau, m));
    }
    // Doubling the joints from 16 on: τ doubles, M quadruples (within the
    // first rows' fixed costs).
    for w in rows.windows(2).skip(3) {
        let ((n0, t0, m0), (n1, t1, m1)) = (w[0], w[1]);
        let (rt, rm) = (t1 as f64 / t0 as f64, m1 as f64 / m0 as f64);
        assert!((1.9..=2.1).contains(&rt), "τ from {n0} to {n1} joints grew {rt:.2}×");
        assert!((3.6..=4.2).contains(&rm), "M from {n0} to {n1} joints grew {rm:.2}×");
    }
}

/// A regression guard on the operation counts of the generated UR5 and
/// Panda functions (the bundled URDFs, default options): they may fall, not
/// rise (negations included). The numbers are those reached with the
/// regrouped inertial parameters, body frames slid along their axes,
/// Khalil's U matrix and the gyroscopic moment from `ω ωᵀ` in the RNEA,
/// classic accelerations and exact zeros along S in the ABA (see
/// `benches/README.md`). Before (commit 6587eda): UR5 τ 422, M 206, h 389,
/// g 118, ABA 1256. For scale, a CasADi graph of Pinocchio's algorithms
/// takes 579 (τ), 301 (M) and 134 (g) on the UR5.
#[test]
fn bundled_op_counts_do_not_grow() {
    use dynagen::codegen::{generate, CodegenOptions};
    let limits: [(&str, [(FunctionKind, usize); 5]); 2] = [
        (
            "ur5",
            [
                (FunctionKind::InverseDynamics, 289),
                (FunctionKind::MassMatrix, 173),
                (FunctionKind::BiasForces, 257),
                (FunctionKind::GravityTorques, 19),
                (FunctionKind::ForwardDynamicsAba, 620),
            ],
        ),
        (
            "panda",
            [
                (FunctionKind::InverseDynamics, 831),
                (FunctionKind::MassMatrix, 655),
                (FunctionKind::BiasForces, 804),
                (FunctionKind::GravityTorques, 225),
                (FunctionKind::ForwardDynamicsAba, 1874),
            ],
        ),
    ];
    for (robot, limits) in limits {
        let path = format!("{}/robots/{robot}.urdf", env!("CARGO_MANIFEST_DIR"));
        let module = generate(&Model::from_urdf_file(&path).unwrap(), &CodegenOptions::default()).unwrap();
        for (kind, limit) in limits {
            let count = module.functions.iter().find(|f| f.kind == kind).unwrap().op_count;
            println!("{robot} {}: {count}", kind.label());
            assert!(
                count.total() <= limit,
                "{robot} {}: {} operations, more than {limit}",
                kind.label(),
                count.total()
            );
        }
    }
}
