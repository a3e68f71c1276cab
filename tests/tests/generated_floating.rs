//! The compiled floating-base module of the quadruped (written by
//! `build.rs`) against the floating-base algorithms, at random unit
//! quaternions and |q̇| up to 50: the generated code computes what the
//! generic solver computes, with the contract's NQ/NV signatures.

use dynagen::algorithms::floating::{aba, crba, rnea};
use dynagen::algorithms::{Loads, Workspace};
use dynagen::spatial::Vec3;
use dynagen::Model;
use dynagen_tests::{norm_rel_err, workspace_root, Rng};

#[allow(dead_code)] // the module's helpers this test does not call
mod quad {
    include!(concat!(env!("OUT_DIR"), "/quadruped12_floating.rs"));
}

#[test]
fn the_compiled_floating_quadruped_matches_the_generic_solver() {
    let model =
        Model::from_urdf_file(workspace_root().join("dynagen/robots/quadruped12.urdf")).unwrap().with_floating_base();
    assert_eq!((quad::DOF, quad::NQ, quad::NV), (model.dof(), model.nq(), model.nv()));
    let names: Vec<&str> = model.joint_names();
    assert_eq!(quad::JOINT_NAMES.to_vec(), names);
    let g = Vec3::from_f64(&model.gravity);
    let mut ws = Workspace::<f64>::new(&model);
    let mut rng = Rng::new(5);
    let mut worst = 0.0f64;
    for k in 0..50 {
        let speed = if k % 2 == 0 { 2.0 } else { 50.0 };
        let mut q: [f64; quad::NQ] = core::array::from_fn(|_| rng.range(-1.0, 1.0));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let mut v = |s: f64| -> [f64; quad::NV] { core::array::from_fn(|_| rng.range(-s, s)) };
        let (qd, qdd, tau) = (v(speed), v(5.0), v(20.0));
        let nv = quad::NV;
        let mut want = vec![0.0; nv];
        let mut check = |got: &[f64], want: &[f64], what: &str| {
            let e = norm_rel_err(got, want, 1e-300);
            assert!(e < 1e-12, "{what} at state {k}: relative error {e:e}");
            worst = worst.max(e);
        };
        rnea::rnea(&model, &mut ws, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut want);
        check(&quad::inverse_dynamics(&q, &qd, &qdd), &want, "tau");
        rnea::rnea(&model, &mut ws, &q, Some(&qd), None, Loads::gravity(&g), &mut want);
        check(&quad::bias_forces(&q, &qd), &want, "h");
        rnea::rnea(&model, &mut ws, &q, None, None, Loads::gravity(&g), &mut want);
        check(&quad::gravity_torques(&q), &want, "g");
        aba::aba(&model, &mut ws, &q, &qd, &tau, Loads::gravity(&g), &mut want);
        check(&quad::forward_dynamics(&q, &qd, &tau), &want, "qdd");
        let mut m = vec![0.0; nv * nv];
        crba::crba(&model, &mut ws, &q, Loads::none(), &mut m);
        check(quad::mass_matrix(&q).as_flattened(), &m, "M");
    }
    println!("floating quadruped, compiled: worst relative error {worst:.1e}");
}
