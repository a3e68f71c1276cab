//! A user of `dynagen::Builder`: `build.rs` writes the UR5's dynamics into
//! `OUT_DIR`, this crate includes it and runs a computed-torque controller
//! on it, as a robot controller would.

/// The UR5's generated dynamics (mass matrix, bias forces, forward dynamics).
pub mod ur5 {
    include!(concat!(env!("OUT_DIR"), "/ur5.rs"));
}

/// The planar arm's five functions, in a private module of which the crate
/// calls only `gravity_torques`: the workspace's clippy (`-D warnings`)
/// sees no dead code in it.
mod planar {
    include!(concat!(env!("OUT_DIR"), "/planar_2link.rs"));
}

/// The planar arm's gravity torques g(q), the only function of its module
/// this crate uses.
pub fn planar_gravity(q: &[f64; 2]) -> [f64; 2] {
    planar::gravity_torques(q)
}

use ur5::DOF;

/// The computed-torque law τ = M(q)(q̈_des + Kp e + Kd ė) + h(q, q̇), with
/// e = q_des − q: with an exact model, every joint's error obeys
/// ë + Kd ė + Kp e = 0.
#[derive(Clone, Copy, Debug)]
pub struct ComputedTorque {
    /// Position gain (1/s²).
    pub kp: f64,
    /// Velocity gain (1/s).
    pub kd: f64,
}

/// A desired trajectory sample: position, velocity, acceleration.
pub type Desired = ([f64; DOF], [f64; DOF], [f64; DOF]);

impl ComputedTorque {
    /// The joint torques for state (q, q̇) and the desired sample.
    pub fn torque(&self, q: &[f64; DOF], qd: &[f64; DOF], (q_des, qd_des, qdd_des): &Desired) -> [f64; DOF] {
        let m = ur5::mass_matrix(q);
        let h = ur5::bias_forces(q, qd);
        let a: [f64; DOF] =
            core::array::from_fn(|i| qdd_des[i] + self.kp * (q_des[i] - q[i]) + self.kd * (qd_des[i] - qd[i]));
        core::array::from_fn(|i| (0..DOF).map(|j| m[i][j] * a[j]).sum::<f64>() + h[i])
    }
}

/// One RK4 step of the closed loop: the robot (its generated forward
/// dynamics) driven by `controller` tracking `desired(t)`.
pub fn rk4_step(
    controller: &ComputedTorque,
    desired: impl Fn(f64) -> Desired,
    t: f64,
    dt: f64,
    q: &mut [f64; DOF],
    qd: &mut [f64; DOF],
) {
    let f = |t: f64, q: &[f64; DOF], qd: &[f64; DOF]| {
        let tau = controller.torque(q, qd, &desired(t));
        (*qd, ur5::forward_dynamics(q, qd, &tau))
    };
    let add = |x: &[f64; DOF], k: &[f64; DOF], s: f64| -> [f64; DOF] { core::array::from_fn(|i| x[i] + s * k[i]) };
    let (k1q, k1v) = f(t, q, qd);
    let (k2q, k2v) = f(t + dt / 2.0, &add(q, &k1q, dt / 2.0), &add(qd, &k1v, dt / 2.0));
    let (k3q, k3v) = f(t + dt / 2.0, &add(q, &k2q, dt / 2.0), &add(qd, &k2v, dt / 2.0));
    let (k4q, k4v) = f(t + dt, &add(q, &k3q, dt), &add(qd, &k3v, dt));
    for i in 0..DOF {
        q[i] += dt / 6.0 * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + k4q[i]);
        qd[i] += dt / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The planar arm's g(q) against its closed form (written in
    /// `dynagen/robots/planar_2link.urdf`): g1 = -24.525 c1 - 5.886 c12,
    /// g2 = -5.886 c12.
    #[test]
    fn the_planar_gravity_is_the_closed_form() {
        for q in [[0.0, 0.0], [0.3, -1.2], [2.0, 0.7f64]] {
            let (c1, c12) = (q[0].cos(), (q[0] + q[1]).cos());
            let want = [-24.525 * c1 - 5.886 * c12, -5.886 * c12];
            let got = planar_gravity(&q);
            for i in 0..2 {
                assert!((got[i] - want[i]).abs() <= 1e-13 * 30.0, "{q:?}: {got:?} against {want:?}");
            }
        }
    }

    /// A smooth trajectory through the workspace.
    fn desired(t: f64) -> Desired {
        let (a, w) = ([0.8, -0.6, 0.9, 0.5, -0.7, 1.0], [1.0, 1.3, 0.7, 1.7, 1.1, 2.0]);
        let q = core::array::from_fn(|i| 0.2 * i as f64 + a[i] * (w[i] * t).sin());
        let qd = core::array::from_fn(|i| a[i] * w[i] * (w[i] * t).cos());
        let qdd = core::array::from_fn(|i| -a[i] * w[i] * w[i] * (w[i] * t).sin());
        (q, qd, qdd)
    }

    /// With gains Kp = ω², Kd = 2ω the error is critically damped:
    /// e(t) = (e₀ + (ė₀ + ω e₀) t) e^(−ωt). The closed loop runs on the
    /// generated M, h and forward dynamics; it follows that law only if the
    /// forward dynamics is the inverse of τ = M q̈ + h.
    #[test]
    fn computed_torque_tracks_with_the_designed_error_dynamics() {
        let w = 10.0;
        let ctl = ComputedTorque { kp: w * w, kd: 2.0 * w };
        let (q0, qd0, _) = desired(0.0);
        let e0: [f64; DOF] = [0.1, -0.05, 0.08, -0.1, 0.05, 0.02];
        let mut q: [f64; DOF] = core::array::from_fn(|i| q0[i] - e0[i]);
        let mut qd = [0.0; DOF];
        let de0: [f64; DOF] = core::array::from_fn(|i| qd0[i] - qd[i]);
        let dt = 1e-3;
        let mut worst = 0.0f64;
        for k in 0..1500 {
            rk4_step(&ctl, desired, k as f64 * dt, dt, &mut q, &mut qd);
            let t = (k + 1) as f64 * dt;
            let (qdes, _, _) = desired(t);
            for i in 0..DOF {
                let want = (e0[i] + (de0[i] + w * e0[i]) * t) * (-w * t).exp();
                worst = worst.max((qdes[i] - q[i] - want).abs());
            }
        }
        assert!(worst < 1e-8, "error departs from the designed dynamics by {worst:e} rad");
        let (qdes, _, _) = desired(1.5);
        let e = (0..DOF).map(|i| (qdes[i] - q[i]).abs()).fold(0.0, f64::max);
        assert!(e < 1e-4, "tracking error after 1.5 s: {e:e} rad");
    }
}
