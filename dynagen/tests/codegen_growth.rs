//! Operation counts over serial chains of 2 to 64 joints: linear in the
//! number of joints for τ (RNEA is O(n)), quadratic for M (n(n+1)/2
//! entries, each a projection of a force carried up the chain).

mod support;

use dynagen::codegen::{trace, ForwardDynamicsMethod, Function};
use dynagen::scene::Scene;
use dynagen::symbolic::Rewrites;
use support::skewed_chain::skewed_chain as chain;

#[test]
fn op_counts_grow_linearly_for_tau_and_quadratically_for_m() {
    let sizes = [2usize, 4, 8, 16, 32, 64];
    let mut rows = Vec::new();
    println!("{:>6} {:>10} {:>10} {:>10} {:>10}", "joints", "tau", "tau/n", "M", "M/n^2");
    for &n in &sizes {
        let scene = Scene::default().apply(&chain(n)).unwrap();
        let count = |f: Function| {
            trace(&scene, &f, ForwardDynamicsMethod::Aba, Rewrites::default()).unwrap().op_count().total()
        };
        let (tau, m) = (count(Function::InverseDynamics), count(Function::MassMatrix));
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
/// Panda functions (the bundled URDFs, default options), and on the
/// critical paths of their bodies (`NAME_sc`, latency-weighted: add, sub,
/// mul 4 cycles, div 14): they may fall, not rise (negations included).
/// The numbers are those reached with the regrouped inertial parameters,
/// body frames slid along their axes, Khalil's U matrix and the gyroscopic
/// moment from `ω ωᵀ` in the RNEA, classic accelerations and exact zeros
/// along S in the ABA, each mass-matrix entry formed where it is cheapest
/// (`codegen/trace/mass_matrix.rs`; UR5 M was 171, LTDL 542; Panda M 654, LTDL
/// 1826), inertias turned about the joint axis before a quarter-turn
/// placement when traced (`joint::Permuted`; ABA UR5 620, Panda 1872), the
/// traced RNEA's moment grouped by the entries of `Ī` (`rnea::inertial_moment`;
/// τ UR5 289, Panda 831; h 257, 804), the Panda's fingers (prismatic
/// leaves) as point masses at their origins placed without rotation
/// (`grouping::center_prismatic_leaves`; Panda τ 785, M 616, h 758, g 222,
/// ABA 1779, LTDL 1742; M's critical path rose from 96 to 104 cycles, the
/// others fell), the second finger's column of M the first's negated
/// (`mass_matrix::mirrored_column`; Panda M 564, LTDL 1592), the fingers'
/// weights in g split into masses fixed to the hand, regrouped, and first
/// moments `m d q` (`codegen/trace/gravity_fold.rs`; Panda g 189, 108 cycles), and sums
/// reassociated for a shorter
/// critical path (see `benches/README.md`), and the traced ABA's transform
/// to the parent distributed over the rank-one update (`aba::aba_impl`,
/// `distributed`: ABA critical path UR5 310 → 208, Panda 514 → 330 cycles,
/// for 31 and 16 more operations; ABA was UR5 610, Panda 1639; then the
/// parent's axis entry as e − (v_k v_k)/d: 202 and 324 cycles, 3 and 6
/// more operations). Before (commit 6587eda): UR5 τ
/// 422, M 206, h 389, g 118, ABA 1256; before reassociation (commit
/// 32b1f50), critical paths UR5 τ 140, M 76, h 129, ABA 354, LTDL 222 and
/// Panda τ 212, M 152, h 205, ABA 670, LTDL 362 cycles. For scale, a CasADi
/// graph of Pinocchio's algorithms takes 579 (τ), 301 (M) and 134 (g) on
/// the UR5.
#[test]
fn bundled_op_counts_do_not_grow() {
    use dynagen::codegen::{generate, CodegenOptions};
    use ForwardDynamicsMethod::{Aba, Ldlt};
    /// (function, forward-dynamics method, operations, critical path of the body in cycles)
    type Limit = (Function, Option<ForwardDynamicsMethod>, usize, u32);
    let limits: [(&str, [Limit; 6]); 2] = [
        (
            "ur5",
            [
                (Function::InverseDynamics, None, 282, 108),
                (Function::MassMatrix, None, 131, 44),
                (Function::BiasForces, None, 253, 105),
                (Function::GravityTorques, None, 19, 32),
                (Function::ForwardDynamics, Some(Aba), 644, 202),
                (Function::ForwardDynamics, Some(Ldlt), 498, 162),
            ],
        ),
        (
            "panda",
            [
                (Function::InverseDynamics, None, 692, 160),
                (Function::MassMatrix, None, 515, 104),
                (Function::BiasForces, None, 661, 161),
                (Function::GravityTorques, None, 122, 96),
                (Function::ForwardDynamics, Some(Aba), 1661, 324),
                (Function::ForwardDynamics, Some(Ldlt), 1508, 242),
            ],
        ),
    ];
    for (robot, limits) in limits {
        let module = generate(&support::model(robot), &CodegenOptions::default()).unwrap();
        for (kind, method, limit, path_limit) in limits {
            let f = module.functions.iter().find(|f| f.function == kind && f.method == method).unwrap();
            let (count, path) = (f.op_count, f.sin_cos_inputs.function.critical_path());
            println!("{robot} {}: {count}; body {path}", f.label());
            assert!(count.total() <= limit, "{robot} {}: {} operations, more than {limit}", f.label(), count.total());
            assert!(
                path.cycles <= path_limit,
                "{robot} {}: critical path {} cycles, more than {path_limit}",
                f.label(),
                path.cycles
            );
        }
    }
}

/// The forward dynamics a default module emits: CRBA + LTDL on the UR5
/// (shorter critical path, as accurate), the articulated-body algorithm on
/// a long chain (where LTDL loses digits); the header says which and why.
#[test]
fn forward_dynamics_is_chosen_by_speed_and_accuracy() {
    use dynagen::codegen::{generate, CodegenOptions};
    use ForwardDynamicsMethod::{Aba, Ldlt};
    let only_fd = [Function::ForwardDynamics];
    let robot = support::model;
    // The UR5: LTDL as accurate and faster. The Panda: LTDL faster but
    // 4.5 times ABA's error (1.8e-15 against 4.0e-16). A 40-joint chain: ABA
    // faster and far more accurate.
    for (name, model, want) in [("ur5", robot("ur5"), Ldlt), ("panda", robot("panda"), Aba), ("chain", chain(40), Aba)]
    {
        let module = generate(&model, &CodegenOptions::default().functions(only_fd.clone())).unwrap();
        let emitted: Vec<(Function, Option<ForwardDynamicsMethod>)> =
            module.functions.iter().filter(|f| f.emitted).map(|f| (f.function.clone(), f.method)).collect();
        let line = module.source.lines().find(|l| l.starts_with("// Forward dynamics:")).unwrap();
        println!("{name}: {line}");
        assert_eq!(emitted, [(Function::ForwardDynamics, Some(want))], "{name}: {line}");
        assert!(line.contains("chosen as"), "{name}: {line}");
    }
}

/// Every module keeps its run-time dispatch, however long its bodies (the
/// AVX2 + FMA copies compile in time linear in their length since the
/// fused multiply-add helpers are compiled with the `fma` feature; compile
/// times in `docs/performance.md`), plain or scene; off, it has none.
#[test]
fn the_dispatch_is_kept_in_large_modules() {
    use dynagen::codegen::{generate, CodegenOptions};
    for n in [4, 8] {
        let module = generate(&chain(n), &CodegenOptions::default()).unwrap();
        assert!(module.source.contains("fn inverse_dynamics_sc_avx2_fma("), "{n} joints");
        assert!(module.source.contains("unsafe fn fma_x86(") && !module.source.contains("but left out"), "{n} joints");
        let off = generate(&chain(n), &CodegenOptions::default().runtime_dispatch(false)).unwrap();
        assert!(!off.source.contains("fn inverse_dynamics_sc_avx2_fma("));
        let scene = dynagen::scene::Scene::new().apply(&chain(n)).unwrap();
        let module = dynagen::codegen::generate_scene(&scene, &CodegenOptions::default()).unwrap();
        assert!(module.source.contains("fn inverse_dynamics_sc_avx2_fma("), "scene, {n} joints");
    }
}
