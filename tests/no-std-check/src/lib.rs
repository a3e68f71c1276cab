//! Generated dynamics compiled inside a `#![no_std]` crate: if a generated
//! module used anything from std, this crate would not build. The modules
//! are written by `build.rs` (dynagen as a build dependency) for the UR5
//! and the Panda with each no_std kind of trigonometry:
//!
//! - [`ur5_libm`], [`ur5_libm_f32`]: `NAME(q, …)` calls `libm::sincos`;
//! - [`ur5_inputs`], [`panda_inputs`]: only `NAME_sc(s, c, [q,] …)`, the
//!   caller passes the sines and cosines (the Panda's prismatic fingers make
//!   it take `q` as well);
//! - [`ur5_batched`] (the default options), [`ur5_batched_f32`]: `NAME(q, …)`
//!   calls the module's own `sin_cos_all`;
//! - [`ur5_controller_libm`], [`ur5_controller_sincos`], [`ur5_tau_sincos`]:
//!   scene modules with the `no_std_libm` and `no_std_sincos` targets;
//! - [`ur5_controller_batched`], [`ur5_controller_batched_f32`]: the
//!   controller scene with the batched sines and cosines (target `std`,
//!   which takes the options' trigonometry).
//!
//! The controller scene has Coulomb friction, smoothed with a square root:
//! `libm::sqrt` in the libm module, the module's own `sqrt` (`sqrtf`) in the
//! others.
//!
//! The tests (which may use std) check every module against the generic
//! solver, `dynagen::Robot`.
#![no_std]

macro_rules! generated {
    ($name:ident, $file:literal, $what:literal) => {
        #[doc = $what]
        #[allow(missing_docs)]
        pub mod $name {
            include!(concat!(env!("OUT_DIR"), "/", $file));
        }
    };
}

generated!(ur5_libm, "ur5_libm.rs", "The UR5, `f64`, sines and cosines by `libm`.");
generated!(ur5_libm_f32, "ur5_libm_f32.rs", "The UR5, `f32`, sines and cosines by `libm`.");
generated!(ur5_inputs, "ur5_inputs.rs", "The UR5, `f64`, sines and cosines as inputs.");
generated!(
    ur5_batched,
    "ur5_batched.rs",
    "The UR5 with the default options: `f64`, sines and cosines by the module's `sin_cos_all`."
);
generated!(ur5_batched_f32, "ur5_batched_f32.rs", "The UR5, `f32`, sines and cosines by the module's `sin_cos_all`.");
generated!(panda_inputs, "panda_inputs.rs", "The Panda (prismatic fingers), `f64`, sines and cosines as inputs.");
generated!(
    ur5_controller_libm,
    "ur5_controller_libm.rs",
    "The UR5 controller scene (`dynagen/scenes/ur5_controller.toml`), target `no_std_libm`."
);
generated!(
    ur5_controller_sincos,
    "ur5_controller_sincos.rs",
    "The UR5 controller scene, target `no_std_sincos`: the sines and cosines as inputs, the module's `sqrt`."
);
generated!(
    ur5_controller_batched,
    "ur5_controller_batched.rs",
    "The UR5 controller scene, `f64`, the module's `sin_cos_all` and `sqrt`."
);
generated!(
    ur5_controller_batched_f32,
    "ur5_controller_batched_f32.rs",
    "The UR5 controller scene, `f32`, the module's `sin_cos_all` and `sqrtf`."
);
generated!(
    ur5_tau_sincos,
    "ur5_tau_sincos.rs",
    "A UR5 torque scene (gravity and tip wrench as arguments), target `no_std_sincos`."
);

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use dynagen::Robot;
    use dynagen_tests::{bundled_model, bundled_robot, bundled_scene, norm_rel_err};
    use nalgebra::DVector;
    use std::vec::Vec;

    /// xorshift64*, uniform in [-1, 1).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
            (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        fn array<const N: usize>(&mut self, scale: f64) -> [f64; N] {
            core::array::from_fn(|_| scale * self.next())
        }
    }

    /// What the generic solver gives at one state: τ, M (row-major), h, g, q̈.
    fn reference(robot: &mut Robot, q: &[f64], qd: &[f64], qdd: &[f64], tau: &[f64]) -> [Vec<f64>; 5] {
        let v = DVector::from_column_slice;
        let m = robot.mass_matrix(&v(q)).unwrap();
        [
            robot.inverse_dynamics(&v(q), &v(qd), &v(qdd)).unwrap().as_slice().to_vec(),
            m.transpose().as_slice().to_vec(),
            robot.bias_forces(&v(q), &v(qd)).unwrap().as_slice().to_vec(),
            robot.gravity_torques(&v(q)).unwrap().as_slice().to_vec(),
            robot.forward_dynamics(&v(q), &v(qd), &v(tau)).unwrap().as_slice().to_vec(),
        ]
    }

    fn flat<const N: usize>(m: [[f64; N]; N]) -> Vec<f64> {
        m.iter().flatten().copied().collect()
    }

    #[test]
    fn ur5_every_no_std_variant_matches_the_generic_solver() {
        let mut robot = bundled_robot("ur5");
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut worst = [0.0f64; 4];
        for _ in 0..200 {
            let (q, qd, qdd, tau): ([f64; 6], [f64; 6], [f64; 6], [f64; 6]) =
                (rng.array(3.0), rng.array(2.0), rng.array(5.0), rng.array(30.0));
            let want = reference(&mut robot, &q, &qd, &qdd, &tau);
            let (s, c) = (q.map(f64::sin), q.map(f64::cos));
            let variants: [[Vec<f64>; 5]; 3] = [
                [
                    ur5_libm::inverse_dynamics(&q, &qd, &qdd).to_vec(),
                    flat(ur5_libm::mass_matrix(&q)),
                    ur5_libm::bias_forces(&q, &qd).to_vec(),
                    ur5_libm::gravity_torques(&q).to_vec(),
                    ur5_libm::forward_dynamics(&q, &qd, &tau).to_vec(),
                ],
                [
                    ur5_inputs::inverse_dynamics_sc(&s, &c, &qd, &qdd).to_vec(),
                    flat(ur5_inputs::mass_matrix_sc(&s, &c)),
                    ur5_inputs::bias_forces_sc(&s, &c, &qd).to_vec(),
                    ur5_inputs::gravity_torques_sc(&s, &c).to_vec(),
                    ur5_inputs::forward_dynamics_sc(&s, &c, &qd, &tau).to_vec(),
                ],
                [
                    ur5_batched::inverse_dynamics(&q, &qd, &qdd).to_vec(),
                    flat(ur5_batched::mass_matrix(&q)),
                    ur5_batched::bias_forces(&q, &qd).to_vec(),
                    ur5_batched::gravity_torques(&q).to_vec(),
                    ur5_batched::forward_dynamics(&q, &qd, &tau).to_vec(),
                ],
            ];
            for (k, got) in variants.iter().enumerate() {
                for (g, w) in got.iter().zip(&want) {
                    worst[k] = worst[k].max(norm_rel_err(g, w, 1.0));
                }
            }
            // f32: the libm and batched f32 modules agree with f64 to f32 precision.
            let qf = q.map(|x| x as f32);
            let (qdf, qddf) = (qd.map(|x| x as f32), qdd.map(|x| x as f32));
            for got in
                [ur5_libm_f32::inverse_dynamics(&qf, &qdf, &qddf), ur5_batched_f32::inverse_dynamics(&qf, &qdf, &qddf)]
            {
                let got: Vec<f64> = got.iter().map(|&x| f64::from(x)).collect();
                worst[3] = worst[3].max(norm_rel_err(&got, &want[0], 1.0));
            }
        }
        std::eprintln!(
            "UR5 no_std variants, worst relative error: libm {:.1e}, inputs {:.1e}, batched {:.1e}, f32 {:.1e}",
            worst[0],
            worst[1],
            worst[2],
            worst[3]
        );
        assert!(worst[..3].iter().all(|&e| e < 1e-12), "{worst:?}");
        assert!(worst[3] < 1e-4, "{worst:?}");
    }

    #[test]
    fn panda_with_sines_and_cosines_as_inputs_matches_the_generic_solver() {
        let mut robot = bundled_robot("panda");
        assert_eq!(panda_inputs::DOF, robot.dof());
        let mut rng = Rng(0x0bad_cafe_f00d_d00d);
        for _ in 0..100 {
            let (q, qd, qdd, tau): ([f64; 9], [f64; 9], [f64; 9], [f64; 9]) =
                (rng.array(2.0), rng.array(2.0), rng.array(5.0), rng.array(20.0));
            // The fingers (prismatic) move by centimetres.
            let mut q = q;
            q[7] = 0.02 * (q[7] + 1.0);
            q[8] = 0.02 * (q[8] + 1.0);
            let want = reference(&mut robot, &q, &qd, &qdd, &tau);
            let (s, c) = panda_inputs::sin_cos_all(&q);
            let got = [
                panda_inputs::inverse_dynamics_sc(&s, &c, &q, &qd, &qdd).to_vec(),
                flat(panda_inputs::mass_matrix_sc(&s, &c, &q)),
                panda_inputs::bias_forces_sc(&s, &c, &q, &qd).to_vec(),
                panda_inputs::gravity_torques_sc(&s, &c, &q).to_vec(),
                panda_inputs::forward_dynamics_sc(&s, &c, &q, &qd, &tau).to_vec(),
            ];
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(norm_rel_err(g, w, 1.0) < 1e-11, "function {k}: {g:?} vs {w:?}");
            }
        }
    }

    #[test]
    fn no_std_scene_modules_match_the_scene_robot() {
        use dynagen::scene::{Gravity, Scene, SceneInputs, SceneRobot};
        use nalgebra::{Vector3, Vector6};
        let ur5 = bundled_model("ur5");
        let mut controller =
            SceneRobot::new(Scene::from_toml_file(bundled_scene("ur5_controller")).unwrap().apply(&ur5).unwrap());
        let tau_scene = Scene::new().gravity(Gravity::Input).tip_wrench("ee_link").viscous("elbow_joint", 0.5);
        let mut tau_robot = SceneRobot::new(tau_scene.apply(&ur5).unwrap());
        let mut rng = Rng(0x0bad_cafe_1234_5678);
        for _ in 0..100 {
            let (q, qd, qdd, tau): ([f64; 6], [f64; 6], [f64; 6], [f64; 6]) =
                (rng.array(3.0), rng.array(2.0), rng.array(5.0), rng.array(30.0));
            let (f, g): ([f64; 6], [f64; 3]) = (rng.array(10.0), [rng.next(), rng.next(), -9.81]);
            let v = DVector::from_column_slice;
            let inputs = SceneInputs { tip_wrench: Some(Vector6::from(f)), ..Default::default() };
            let (s, c) = (q.map(f64::sin), q.map(f64::cos));
            let want_tau =
                controller.inverse_dynamics_with(&v(&q), &v(&qd), &v(&qdd), &inputs).unwrap().as_slice().to_vec();
            let want_h = controller.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec();
            let want_qdd =
                controller.forward_dynamics_with(&v(&q), &v(&qd), &v(&tau), &inputs).unwrap().as_slice().to_vec();
            let checks = [
                (ur5_controller_libm::inverse_dynamics(&q, &qd, &qdd, &f).to_vec(), want_tau.clone()),
                (ur5_controller_libm::forward_dynamics(&q, &qd, &tau, &f).to_vec(), want_qdd.clone()),
                (ur5_controller_sincos::inverse_dynamics_sc(&s, &c, &qd, &qdd, &f).to_vec(), want_tau.clone()),
                (ur5_controller_sincos::bias_forces_sc(&s, &c, &qd).to_vec(), want_h.clone()),
                (ur5_controller_sincos::forward_dynamics_sc(&s, &c, &qd, &tau, &f).to_vec(), want_qdd.clone()),
                (ur5_controller_batched::inverse_dynamics(&q, &qd, &qdd, &f).to_vec(), want_tau.clone()),
                (ur5_controller_batched::bias_forces(&q, &qd).to_vec(), want_h.clone()),
                (ur5_controller_batched::forward_dynamics(&q, &qd, &tau, &f).to_vec(), want_qdd),
                (
                    ur5_tau_sincos::inverse_dynamics_sc(&q.map(f64::sin), &q.map(f64::cos), &qd, &qdd, &g, &f).to_vec(),
                    tau_robot
                        .inverse_dynamics_with(
                            &v(&q),
                            &v(&qd),
                            &v(&qdd),
                            &SceneInputs { gravity: Some(Vector3::from(g)), ..inputs },
                        )
                        .unwrap()
                        .as_slice()
                        .to_vec(),
                ),
            ];
            for (got, want) in &checks {
                let e = norm_rel_err(got, want, 1.0);
                assert!(e < 1e-12, "relative error {e:e}: {got:?} vs {want:?}");
            }
            // f32, against the f64 values (τ and h: the friction's sqrtf).
            let f32s = |x: &[f64; 6]| x.map(|v| v as f32);
            let widen = |x: [f32; 6]| x.map(f64::from).to_vec();
            let (qf, qdf, qddf, ff) = (f32s(&q), f32s(&qd), f32s(&qdd), f32s(&f));
            let e = norm_rel_err(
                &widen(ur5_controller_batched_f32::inverse_dynamics(&qf, &qdf, &qddf, &ff)),
                &want_tau,
                1.0,
            );
            assert!(e < 1e-4, "f32 inverse_dynamics: relative error {e:e}");
            let e = norm_rel_err(&widen(ur5_controller_batched_f32::bias_forces(&qf, &qdf)), &want_h, 1.0);
            assert!(e < 1e-4, "f32 bias_forces: relative error {e:e}");
        }
    }
}
