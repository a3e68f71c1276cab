//! Floating-base modules: the traced functions (what the generated code
//! computes, fused and unfused) against the floating-base algorithms in
//! f64 and in double-double, on the quadruped and the two-armed torso with
//! a floating root, at random unit quaternions and |q̇| up to 50; the
//! module's signatures follow the contract (NQ, NV); what is not generated
//! for a floating base yet is an error naming it.

mod support;

use dynagen::algorithms::floating::{aba, crba, rnea};
use dynagen::algorithms::{Loads, Workspace};
use dynagen::codegen::{generate, CodegenOptions, ForwardDynamicsMethod, Function};
use dynagen::spatial::Vec3;
use dynagen::{DoubleDouble, Model, Scalar};
use support::{norm_rel_err, Rng};

/// `q` with a random unit quaternion and random joints, and a velocity-side
/// vector of the given scale.
fn state(model: &Model, rng: &mut Rng, speed: f64) -> (Vec<f64>, Vec<f64>) {
    let mut q = rng.vec(model.nq(), 1.0);
    let quat = rng.vec(4, 1.0);
    let norm = quat.iter().map(|x| x * x).sum::<f64>().sqrt();
    for k in 0..4 {
        q[3 + k] = quat[k] / norm;
    }
    (q, rng.vec(model.nv(), speed))
}

/// The floating-base algorithm behind `f` on the scalar `S`.
fn generic<S: Scalar>(
    model: &Model,
    f: &Function,
    method: Option<ForwardDynamicsMethod>,
    args: &[Vec<f64>],
) -> Vec<f64> {
    let a: Vec<Vec<S>> = args.iter().map(|v| v.iter().map(|&x| S::from_f64(x)).collect()).collect();
    let mut ws = Workspace::<S>::new(model);
    let g = Vec3::<S>::from_f64(&model.gravity);
    let nv = model.nv();
    let mut out = vec![S::zero(); if *f == Function::MassMatrix { nv * nv } else { nv }];
    let loads = Loads::gravity(&g);
    match (f, method) {
        (Function::InverseDynamics, _) => rnea::rnea(model, &mut ws, &a[0], Some(&a[1]), Some(&a[2]), loads, &mut out),
        (Function::MassMatrix, _) => crba::crba(model, &mut ws, &a[0], Loads::none(), &mut out),
        (Function::BiasForces, _) => rnea::rnea(model, &mut ws, &a[0], Some(&a[1]), None, loads, &mut out),
        (Function::GravityTorques, _) => rnea::rnea(model, &mut ws, &a[0], None, None, loads, &mut out),
        (Function::Coriolis, _) => rnea::rnea(model, &mut ws, &a[0], Some(&a[1]), None, Loads::none(), &mut out),
        (Function::ForwardDynamics, _) => aba::aba(model, &mut ws, &a[0], &a[1], &a[2], loads, &mut out),
        _ => unreachable!("not a floating-base function"),
    }
    out.iter().map(|x| x.to_f64().unwrap()).collect()
}

#[test]
fn floating_base_functions_match_the_floating_algorithms() {
    for name in ["quadruped12", "torso_two_arms"] {
        let model = support::model(name).with_floating_base();
        let module = generate(&model, &CodegenOptions::default().function(Function::Coriolis)).unwrap();
        // Both forward dynamics are traced, each checked.
        assert_eq!(module.functions.len(), 7, "{name}");
        let mut rng = Rng::new(17);
        let mut worst = 0.0f64;
        for k in 0..20 {
            let speed = if k % 2 == 0 { 2.0 } else { 50.0 };
            let (q, qd) = state(&model, &mut rng, speed);
            let (qdd, tau) = (rng.vec(model.nv(), 5.0), rng.vec(model.nv(), 20.0));
            for f in &module.functions {
                let args: Vec<Vec<f64>> = f
                    .function
                    .vectors()
                    .iter()
                    .map(|v| match *v {
                        "q" => q.clone(),
                        "qd" => qd.clone(),
                        "qdd" => qdd.clone(),
                        _ => tau.clone(),
                    })
                    .collect();
                let inputs: Vec<(&str, &[f64])> =
                    f.function.vectors().iter().zip(&args).map(|(n, v)| (*n, v.as_slice())).collect();
                let want = generic::<DoubleDouble>(&model, &f.function, f.method, &args);
                for (got, how) in [
                    (f.traced.eval(&inputs).unwrap(), "unfused"),
                    (f.traced.eval_fused(&f.traced.fusion(), &inputs).unwrap(), "fused"),
                ] {
                    let e = norm_rel_err(&got, &want, 1e-300);
                    assert!(e < 1e-12, "{name} {} {how}, state {k}: relative error {e:e}", f.label());
                    worst = worst.max(e);
                }
                // The generic f64 solver is as close to double-double.
                let f64_err = norm_rel_err(&generic::<f64>(&model, &f.function, f.method, &args), &want, 1e-300);
                assert!(f64_err < 1e-12, "{name} {}: generic f64 {f64_err:e}", f.label());
            }
        }
        println!("{name}: worst relative error of the traced functions {worst:.1e}");
    }
}

#[test]
fn a_floating_module_follows_the_contract() {
    let model = support::model("quadruped12").with_floating_base();
    let src = generate(&model, &CodegenOptions::default()).unwrap().source;
    for item in [
        "pub const DOF: usize = 12;",
        "pub const NQ: usize = 19;",
        "pub const NV: usize = 18;",
        "pub fn inverse_dynamics(q: &[f64; NQ], qd: &[f64; NV], qdd: &[f64; NV]) -> [f64; NV]",
        "pub fn mass_matrix(q: &[f64; NQ]) -> [[f64; NV]; NV]",
        "pub fn bias_forces(q: &[f64; NQ], qd: &[f64; NV]) -> [f64; NV]",
        "pub fn gravity_torques(q: &[f64; NQ]) -> [f64; NV]",
        "pub fn forward_dynamics(q: &[f64; NQ], qd: &[f64; NV], tau: &[f64; NV]) -> [f64; NV]",
        "// Gravity: [0.0, 0.0, -9.81] m/s^2 in the world frame, folded in.",
    ] {
        assert!(src.contains(item), "missing: {item}");
    }
    // A fixed-base module names the same lengths.
    let fixed = generate(&support::model("ur5"), &CodegenOptions::default()).unwrap().source;
    assert!(fixed.contains("pub const NQ: usize = DOF;") && fixed.contains("pub const NV: usize = DOF;"));
}

/// The derivatives, which a floating module lacked before, are generated on
/// request (their values: tests/codegen_derivatives.rs and the tests crate).
#[test]
fn a_floating_module_has_the_derivatives_on_request() {
    let model = support::model("quadruped12").with_floating_base();
    let options = CodegenOptions::default().functions([Function::InverseDynamicsDerivatives]);
    let src = generate(&model, &options).unwrap().source;
    assert!(src.contains("pub fn inverse_dynamics_derivatives(\n    q: &[f64; NQ],"), "NQ-long q");
    assert!(src.contains("pub type NvMatrix = [[f64; NV]; NV];"), "NV × NV matrices");
    assert!(src.contains("-> (NvMatrix, NvMatrix)"), "returned as the module's alias");
}
