// A two-link planar arm written inline; its mass matrix checked against the
// textbook closed form (point masses at the link ends, Lynch & Park 8.1).
mod arm {
    dynagen_macros::robot! {
        name: two_link,
        functions: [mass_matrix, gravity_torques],
        link base {},
        link upper { mass: 2.0, com: [1.0, 0, 0], inertia: [0, 0, 0, 0, 0, 0] },
        link fore { mass: 3.0, com: [0.5, 0, 0], inertia: [0, 0, 0, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
        joint elbow: continuous(upper -> fore) { origin: [1.0, 0, 0], axis: [0, 0, 1] }
    }
}

fn main() {
    let (m1, m2, l1, l2) = (2.0, 3.0, 1.0, 0.5);
    for q2 in [-1.0f64, 0.0, 0.4, 2.0] {
        let m = arm::mass_matrix(&[0.3, q2]);
        let m11 = m1 * l1 * l1 + m2 * (l1 * l1 + 2.0 * l1 * l2 * q2.cos() + l2 * l2);
        let m12 = m2 * (l1 * l2 * q2.cos() + l2 * l2);
        let m22 = m2 * l2 * l2;
        for (got, want) in [(m[0][0], m11), (m[0][1], m12), (m[1][0], m12), (m[1][1], m22)] {
            assert!((got - want).abs() < 1e-12, "{m:?}");
        }
        // Gravity along −z, joints about z: no gravity torque.
        assert_eq!(arm::gravity_torques(&[0.3, q2]), [0.0, 0.0]);
    }
    assert_eq!(arm::JOINT_NAMES, ["shoulder", "elbow"]);
}
