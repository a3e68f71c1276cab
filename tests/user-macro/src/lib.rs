//! A user of `dynagen-macros`: the Panda's dynamics from `urdf!` and a
//! pendulum from `robot!`, generated at compile time, driven by a
//! computed-torque controller as a robot controller would.

/// The Franka Panda (7 arm joints, 2 finger joints): what a controller needs.
pub mod panda {
    dynagen_macros::urdf!("../../dynagen/robots/panda.urdf", functions = [mass_matrix, bias_forces, forward_dynamics],);
}

/// A pendulum written inline: 2 kg at 0.5 m below a hinge about y.
pub mod pendulum {
    dynagen_macros::robot! {
        name: pendulum,
        link base {},
        link arm { mass: 2.0, com: [0, 0, -0.5], inertia: [0.1, 0.1, 0.01, 0, 0, 0] },
        joint hinge: revolute(base -> arm) { origin: [0, 0, 0.3], rpy: [0, 0, 0], axis: [0, 1, 0] },
    }
}

/// The pendulum's gravity torque in f32, from the same inline robot,
/// without fused multiply-adds.
pub mod pendulum_f32 {
    dynagen_macros::robot! {
        name: pendulum,
        functions: [gravity_torques],
        scalar: f32,
        fma: false,
        link base {},
        link arm { mass: 2.0, com: [0, 0, -0.5], inertia: [0.1, 0.1, 0.01, 0, 0, 0] },
        joint hinge: revolute(base -> arm) { axis: [0, 1, 0] },
    }
}

/// The same Panda functions with the module's own batched sines and
/// cosines (no_std; the default, asked for by name), the CRBA + LᵀDL forward
/// dynamics forced, and bodies over 300 `let`s split into parts.
pub mod panda_batched {
    dynagen_macros::urdf!(
        "../../dynagen/robots/panda.urdf",
        functions = [mass_matrix, bias_forces, forward_dynamics],
        trig = batched,
        forward_dynamics = ldlt,
        split_lets = 300,
    );
}

/// The Panda's mass matrix without run-time dispatch: the build's target
/// features only, the same bits on every x86-64 machine.
pub mod panda_no_dispatch {
    dynagen_macros::urdf!("../../dynagen/robots/panda.urdf", functions = [mass_matrix], dispatch = false);
}

/// A robot whose names try to inject code: they stay names.
pub mod hostile;

/// The Panda as franka_description has it: the second finger follows the
/// first (`<mimic>`), so the module has 8 joints.
pub mod panda_mimic {
    dynagen_macros::urdf!("../../dynagen/tests/data/panda_mimic.urdf");
}

/// The same file with its mimic joint made a joint of its own: 9 joints.
pub mod panda_mimic_independent {
    dynagen_macros::urdf!("../../dynagen/tests/data/panda_mimic.urdf", mimic = independent);
}

/// A parallel gripper written inline: the right finger follows the left,
/// mirrored (the same slide, its axis turned), 1 mm further out.
pub mod gripper {
    dynagen_macros::robot! {
        name: gripper,
        link palm {},
        link left { mass: 0.1, com: [0, 0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        link right { mass: 0.1, com: [0, -0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        joint slide: prismatic(palm -> left) { axis: [0, 1, 0] },
        joint mirror: prismatic(palm -> right) { axis: [0, -1, 0], mimic: slide, multiplier: 1, offset: 0.001 },
    }
}

/// The same gripper with its mimic joint a joint of its own (the `mimic`
/// option of `robot!`): two slides.
pub mod gripper_independent {
    dynagen_macros::robot! {
        name: gripper,
        mimic: independent,
        link palm {},
        link left { mass: 0.1, com: [0, 0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        link right { mass: 0.1, com: [0, -0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        joint slide: prismatic(palm -> left) { axis: [0, 1, 0] },
        joint mirror: prismatic(palm -> right) { axis: [0, -1, 0], mimic: slide, multiplier: 1, offset: 0.001 },
    }
}

use panda::DOF;

/// τ = M(q)(q̈_des + Kp e + Kd ė) + h(q, q̇), e = q_des − q.
pub fn computed_torque(
    kp: f64,
    kd: f64,
    q: &[f64; DOF],
    qd: &[f64; DOF],
    q_des: &[f64; DOF],
    qd_des: &[f64; DOF],
    qdd_des: &[f64; DOF],
) -> [f64; DOF] {
    let m = panda::mass_matrix(q);
    let h = panda::bias_forces(q, qd);
    let a: [f64; DOF] = core::array::from_fn(|i| qdd_des[i] + kp * (q_des[i] - q[i]) + kd * (qd_des[i] - qd[i]));
    core::array::from_fn(|i| (0..DOF).map(|j| m[i][j] * a[j]).sum::<f64>() + h[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pendulum_matches_its_closed_form() {
        // I about the hinge = I_yy + m l² = 0.1 + 2 · 0.25; gravity torque
        // m g l sin q (the arm hangs along −z; q turns it about +y).
        for q in [-2.0, -0.3, 0.0, 0.7, 2.5f64] {
            let m = pendulum::mass_matrix(&[q]);
            assert!((m[0][0] - 0.6).abs() < 1e-15, "{m:?}");
            let g = pendulum::gravity_torques(&[q])[0];
            assert!((g - 2.0 * 9.81 * 0.5 * q.sin()).abs() < 1e-14, "{g}");
            let tau = pendulum::inverse_dynamics(&[q], &[1.5], &[-3.0])[0];
            assert!((tau - (0.6 * -3.0 + 9.81 * q.sin())).abs() < 1e-13, "{tau}");
            let qdd = pendulum::forward_dynamics(&[q], &[1.5], &[1.0])[0];
            assert!((qdd - (1.0 - 9.81 * q.sin()) / 0.6).abs() < 1e-13, "{qdd}");
            let g32 = pendulum_f32::gravity_torques(&[q as f32])[0];
            assert!((f64::from(g32) - g).abs() < 1e-5, "{g32}");
        }
        assert_eq!(pendulum::JOINT_NAMES, ["hinge"]);
    }

    #[test]
    fn mimic_joints_follow_their_masters() {
        assert_eq!(panda_mimic::DOF, 8);
        assert_eq!(panda_mimic::JOINT_NAMES[7], "panda_finger_joint1");
        assert_eq!(panda_mimic_independent::DOF, 9);
        // the fingers together: the independent model's entries summed (G = [1, 1] on them)
        let q8 = [0.3, -1.1, 0.7, -2.0, -0.4, 1.9, 0.8, 0.02];
        let q9 = [0.3, -1.1, 0.7, -2.0, -0.4, 1.9, 0.8, 0.02, 0.02];
        let (g8, g9) = (panda_mimic::gravity_torques(&q8), panda_mimic_independent::gravity_torques(&q9));
        assert!(
            (g8[7] - (g9[7] + g9[8])).abs() < 1e-14 && g8[..7].iter().zip(&g9[..7]).all(|(a, b)| (a - b).abs() < 1e-13)
        );
        let (m8, m9) = (panda_mimic::mass_matrix(&q8), panda_mimic_independent::mass_matrix(&q9));
        assert!((m8[7][7] - (m9[7][7] + 2.0 * m9[7][8] + m9[8][8])).abs() < 1e-15);
        // a 0.2 kg gripper on one slide: M = the two fingers' masses, no gravity along y
        assert_eq!(gripper::JOINT_NAMES, ["slide"]);
        assert!((gripper::mass_matrix(&[0.01])[0][0] - 0.2).abs() < 1e-15);
        assert_eq!(gripper::gravity_torques(&[0.01]), [0.0]);
        assert!((gripper::forward_dynamics(&[0.01], &[0.0], &[1.0])[0] - 5.0).abs() < 1e-13);
        // `mimic: independent` in robot!: both slides are joints, each finger its own 0.1 kg.
        assert_eq!(gripper_independent::JOINT_NAMES, ["slide", "mirror"]);
        assert_eq!(gripper_independent::mass_matrix(&[0.01, 0.011]), [[0.1, 0.0], [0.0, 0.1]]);
    }

    #[test]
    fn dispatch_false_keeps_the_baseline_bits() {
        // A default x86-64 build has no FMA; with dispatch (the default) the Panda's M runs its
        // fused AVX2 and FMA copy where the processor has both, without it the unfused baseline.
        let fused_here = cfg!(target_arch = "x86_64")
            && !cfg!(target_feature = "fma")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma");
        let q = [0.3, -1.1, 0.7, -2.0, -0.4, 1.9, 0.8, 0.01, 0.03];
        let (m, m0) = (panda::mass_matrix(&q).concat(), super::panda_no_dispatch::mass_matrix(&q).concat());
        let differ = m.iter().zip(&m0).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
        assert_eq!(differ > 0, fused_here, "{differ} entries differ");
        for (a, b) in m.iter().zip(&m0) {
            assert!((a - b).abs() <= 1e-14 * (1.0 + a.abs()));
        }
    }

    #[test]
    fn the_default_trigonometry_is_the_modules_own_batched_one() {
        // The macros take the library's default, `trig = batched`: `NAME(q)` is, bit for bit,
        // `NAME_sc` of the module's `sin_cos_array(q)`; with std's `sin_cos` some results differ
        // in the last bits (so the check can tell them apart).
        let (mut x, mut std_differs) = (0x2545_f491_4f6c_dd1du64, 0);
        for _ in 0..200 {
            let q: [f64; DOF] = core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            });
            let (s, c) = panda::sin_cos_array(&q);
            let m = panda::mass_matrix(&q).concat();
            assert_eq!(m, panda::mass_matrix_sc(&s, &c, &q).concat(), "q = {q:?}");
            let (s, c) = (q.map(f64::sin), q.map(f64::cos));
            std_differs += usize::from(m != panda::mass_matrix_sc(&s, &c, &q).concat());
        }
        assert!(std_differs > 0, "std's sin_cos gives the batched bits: the check above proves nothing");
    }

    #[test]
    fn options_batched_trig_ldlt_and_split_bodies_agree_with_the_defaults() {
        use super::panda_batched as b;
        let q = [0.3, -1.1, 0.7, -2.0, -0.4, 1.9, 0.8, 0.01, 0.03];
        let qd = [0.2, -0.1, 0.4, 0.0, 0.3, -0.5, 1.0, 0.02, -0.01];
        let tau = [1.0, -20.0, 3.0, 10.0, -0.5, 0.2, 0.1, 2.0, -1.0];
        // Every module has the kernel's `sin_cos_array`.
        let (s, c) = b::sin_cos_array(&q);
        for i in 0..DOF {
            assert!((s[i] - q[i].sin()).abs() <= 2.3e-16 && (c[i] - q[i].cos()).abs() <= 2.3e-16);
        }
        let (m, mb) = (panda::mass_matrix(&q), b::mass_matrix(&q));
        let (h, hb) = (panda::bias_forces(&q, &qd), b::bias_forces(&q, &qd));
        let (a, ab) = (panda::forward_dynamics(&q, &qd, &tau), b::forward_dynamics(&q, &qd, &tau));
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let m_norm = norm(&m.concat());
        for i in 0..DOF {
            for j in 0..DOF {
                assert!((m[i][j] - mb[i][j]).abs() <= 1e-12 * m_norm, "M[{i}][{j}]");
            }
            assert!((h[i] - hb[i]).abs() <= 1e-12 * norm(&h), "h[{i}]");
            assert!((a[i] - ab[i]).abs() <= 1e-10 * norm(&a), "q̈[{i}]: {} {}", a[i], ab[i]);
        }
    }

    /// Semi-implicit Euler on the generated forward dynamics, with the
    /// computed-torque law holding the Panda on a trajectory: the error
    /// follows ë + Kd ė + Kp e = 0 (critically damped), so it shrinks by
    /// the designed factor; a forward dynamics inconsistent with M and h
    /// would leave a steady error.
    #[test]
    fn computed_torque_holds_the_panda_on_its_trajectory() {
        let (w, dt) = (20.0, 2e-4);
        let desired = |t: f64| -> ([f64; DOF], [f64; DOF], [f64; DOF]) {
            let amp = |i: usize| if i < 7 { 0.5 } else { 0.01 };
            (
                core::array::from_fn(|i| if i < 7 { 0.3 } else { 0.02 } + amp(i) * (1.5 * t + i as f64).sin()),
                core::array::from_fn(|i| 1.5 * amp(i) * (1.5 * t + i as f64).cos()),
                core::array::from_fn(|i| -2.25 * amp(i) * (1.5 * t + i as f64).sin()),
            )
        };
        let (q0, _, _) = desired(0.0);
        let mut q: [f64; DOF] = core::array::from_fn(|i| q0[i] + if i < 7 { 0.1 } else { 0.005 });
        let mut qd = [0.0; DOF];
        let steps = 5000; // 1 s
        for k in 0..steps {
            let (qdes, qddes, qdddes) = desired(k as f64 * dt);
            let tau = computed_torque(w * w, 2.0 * w, &q, &qd, &qdes, &qddes, &qdddes);
            let qdd = panda::forward_dynamics(&q, &qd, &tau);
            for i in 0..DOF {
                qd[i] += dt * qdd[i];
                q[i] += dt * qd[i];
            }
        }
        let (qdes, _, _) = desired(steps as f64 * dt);
        let err = (0..DOF).map(|i| (qdes[i] - q[i]).abs()).fold(0.0, f64::max);
        // Exact error after 1 s: (1 + ωt)e^(−ωt)·0.1 ≈ 4e-9 plus what
        // the trajectory's own velocity error adds; Euler's O(dt) error
        // stays well under 1e-4.
        assert!(err < 1e-4, "tracking error after 1 s: {err:e}");
        assert!(err.is_finite());
    }
}

/// The UR5 under the bundled controller scene (a TOML file): the tip wrench
/// at `ee_link` is an argument, armature, friction and a gripper are folded
/// in, and the tool flange's pose and Jacobian come with it.
pub mod ur5_controller {
    dynagen_macros::urdf!("../../dynagen/robots/ur5.urdf", scene = "../../dynagen/scenes/ur5_controller.toml");
}

/// The same scene file with two inline changes on top: the wrist's
/// armature raised from the file's 0.06 to 0.5 kg·m², and gravity made a
/// run-time argument.
pub mod ur5_controller_heavy_wrist {
    dynagen_macros::urdf!(
        "../../dynagen/robots/ur5.urdf",
        scene = "../../dynagen/scenes/ur5_controller.toml",
        armature = { wrist_3_joint = 0.5 },
        gravity = input
    );
}

#[cfg(test)]
mod scene_tests {
    use super::ur5_controller as c;

    #[test]
    fn inline_keys_change_the_scene_file() {
        use super::ur5_controller_heavy_wrist as h;
        let q = [0.3, -1.1, 0.7, 2.0, -0.4, 0.9];
        let (qd, qdd) = ([0.2, -0.1, 0.4, 0.0, 0.3, -0.5], [1.0, 0.5, -0.3, 0.2, 0.0, 0.1]);
        let f = [0.4, -0.2, 0.1, 3.0, -5.0, 10.0];
        let g = [0.0, 0.0, -9.81];
        let file = c::inverse_dynamics(&q, &qd, &qdd, &f);
        let changed = h::inverse_dynamics(&q, &qd, &qdd, &g, &f);
        // Only the wrist's torque changes, by (0.5 − 0.06)·q̈₆; the rest of
        // the file (friction, payload, tip wrench) is kept.
        for i in 0..5 {
            assert!((changed[i] - file[i]).abs() < 1e-12 * (1.0 + file[i].abs()), "joint {i}");
        }
        assert!((changed[5] - file[5] - 0.44 * qdd[5]).abs() < 1e-12, "{} {}", changed[5], file[5]);
        // Gravity is an argument now: none gives a different τ.
        let weightless = h::inverse_dynamics(&q, &qd, &qdd, &[0.0; 3], &f);
        assert!((weightless[1] - changed[1]).abs() > 1.0);
    }

    #[test]
    fn the_tip_wrench_adds_the_jacobian_transpose_times_the_wrench() {
        let q = [0.3, -1.1, 0.7, 2.0, -0.4, 0.9];
        let (qd, qdd) = ([0.2, -0.1, 0.4, 0.0, 0.3, -0.5], [1.0, 0.5, -0.3, 0.2, 0.0, 0.1]);
        let f = [0.4, -0.2, 0.1, 3.0, -5.0, 10.0];
        let base = c::inverse_dynamics(&q, &qd, &qdd, &[0.0; 6]);
        let with = c::inverse_dynamics(&q, &qd, &qdd, &f);
        let j = c::frame_jacobian_ee_link(&q);
        for i in 0..c::DOF {
            let jt_f: f64 = (0..6).map(|r| j[r][i] * f[r]).sum();
            assert!((with[i] - base[i] - jt_f).abs() < 1e-10, "joint {i}");
        }
        // Forward dynamics undoes inverse dynamics, wrench, armature and friction included.
        let back = c::forward_dynamics(&q, &qd, &with, &f);
        for i in 0..c::DOF {
            assert!((back[i] - qdd[i]).abs() < 1e-10, "joint {i}: {back:?}");
        }
    }
}

/// The quadruped with a floating trunk under inline scene keys: gravity a
/// run-time argument (world frame), armature on a knee, the wrench at the
/// front-right foot an argument, and that foot's body Jacobian and
/// acceleration bias J̇q̇ for a contact constraint.
pub mod quadruped_contact {
    dynagen_macros::urdf!(
        "../../dynagen/robots/quadruped12.urdf",
        floating_base = true,
        functions = [inverse_dynamics, mass_matrix],
        gravity = input,
        armature = { FR_calf_joint = 0.02 },
        tip_wrench = FR_foot,
        frame_jacobian = [FR_foot],
        frame_acceleration_bias = [FR_foot],
    );
}

#[cfg(test)]
mod floating_tests {
    use super::quadruped_contact as quad;

    /// A configuration with the trunk level at the origin.
    fn level() -> [f64; quad::NQ] {
        let mut q = [0.0; quad::NQ];
        q[6] = 1.0;
        q[7..].copy_from_slice(&[0.1, 0.8, -1.5, -0.1, 0.8, -1.5, 0.1, 1.0, -1.6, -0.1, 1.0, -1.6]);
        q
    }

    #[test]
    fn a_floating_module_takes_world_gravity_and_the_foot_wrench() {
        let (q, zero) = (level(), [0.0; quad::NV]);
        // At rest the base's rows hold the whole weight (12.453 kg): the
        // wrench on the base is m·9.81 up, in the (level) base frame.
        let tau = quad::inverse_dynamics(&q, &zero, &zero, &[0.0, 0.0, -9.81], &[0.0; 6]);
        assert!((tau[5] - 12.453 * 9.81).abs() < 1e-9, "{}", tau[5]);
        assert!(tau[3].abs() < 1e-12 && tau[4].abs() < 1e-12);
        // The foot's wrench adds Jᵀ F to every row, the base's included.
        let f = [0.1, -0.2, 0.3, 4.0, -2.0, 30.0];
        let with = quad::inverse_dynamics(&q, &zero, &zero, &[0.0; 3], &f);
        let j = quad::frame_jacobian_fr_foot(&q);
        for (i, w) in with.iter().enumerate() {
            let jt_f: f64 = (0..6).map(|r| j[r][i] * f[r]).sum();
            assert!((w - jt_f).abs() < 1e-10, "row {i}");
        }
        // The knee's armature is on its diagonal only.
        let m = quad::mass_matrix(&q);
        let knee = 6 + 2;
        let without = super::quadruped_plain::mass_matrix(&q);
        assert!((m[knee][knee] - without[knee][knee] - 0.02).abs() < 1e-14);
        assert!((m[5][5] - without[5][5]).abs() < 1e-14 && (m[5][5] - 12.453).abs() < 1e-12);
        // At rest the foot's acceleration bias is zero; moving, it is not.
        assert!(quad::frame_acceleration_bias_fr_foot(&q, &zero).iter().all(|x| *x == 0.0));
        let mut qd = zero;
        qd[2] = 1.0;
        assert!(quad::frame_acceleration_bias_fr_foot(&q, &qd)[3..].iter().any(|x| x.abs() > 0.01));
    }
}

/// The same floating quadruped's plain mass matrix.
pub mod quadruped_plain {
    dynagen_macros::urdf!("../../dynagen/robots/quadruped12.urdf", floating_base = true, functions = [mass_matrix]);
}
