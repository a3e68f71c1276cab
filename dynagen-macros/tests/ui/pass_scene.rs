// A scene given inline: gravity none, a lock, armature, only τ, C(q, q̇)q̇
// and a frame pose. Without gravity τ(q, q̇, 0) is C(q, q̇)q̇, τ(q, 0, 0) = 0,
// the armature adds a·q̈ to its joint's torque alone at q̇ = 0 (beside M q̈),
// and the frame pose is a rigid transform.
mod arm {
    dynagen_macros::robot! {
        name: arm3,
        functions: [inverse_dynamics, coriolis],
        gravity: none,
        lock: { wrist: 0.4 },
        armature: { elbow: 0.25 },
        frame_pose: [hand],
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link fore { mass: 1.5, com: [0.4, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link hand { mass: 0.5, com: [0.05, 0, 0], inertia: [0.001, 0.001, 0.001, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
        joint elbow: revolute(upper -> fore) { origin: [1.0, 0, 0], axis: [0, 1, 0] },
        joint wrist: revolute(fore -> hand) { origin: [0.8, 0, 0], axis: [1, 0, 0] },
    }
}

mod plain {
    dynagen_macros::robot! {
        name: arm3,
        functions: [inverse_dynamics],
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link fore { mass: 1.5, com: [0.4, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link hand { mass: 0.5, com: [0.05, 0, 0], inertia: [0.001, 0.001, 0.001, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
        joint elbow: revolute(upper -> fore) { origin: [1.0, 0, 0], axis: [0, 1, 0] },
        joint wrist: revolute(fore -> hand) { origin: [0.8, 0, 0], axis: [1, 0, 0] },
    }
}

fn main() {
    assert_eq!(arm::DOF, 2);
    assert_eq!(arm::JOINT_NAMES, ["shoulder", "elbow"]);
    let q = [0.3, -1.1];
    let qd = [0.5, -0.9];
    let tau = arm::inverse_dynamics(&q, &qd, &[0.0; 2]);
    let c = arm::coriolis(&q, &qd);
    for i in 0..2 {
        assert!((tau[i] - c[i]).abs() <= 1e-12 * (1.0 + c[i].abs()), "{tau:?} {c:?}");
    }
    assert_eq!(arm::inverse_dynamics(&q, &[0.0; 2], &[0.0; 2]), [0.0; 2]);
    // M q̈ with and without the armature (column 2 of M by q̈ = e2).
    let m2 = arm::inverse_dynamics(&q, &[0.0; 2], &[0.0, 1.0]);
    let m2_plain = plain::inverse_dynamics(&[q[0], q[1], 0.4], &[0.0; 3], &[0.0, 1.0, 0.0]);
    let g = plain::inverse_dynamics(&[q[0], q[1], 0.4], &[0.0; 3], &[0.0; 3]);
    assert!((m2[0] - (m2_plain[0] - g[0])).abs() < 1e-12, "{m2:?} {m2_plain:?}");
    assert!((m2[1] - (m2_plain[1] - g[1]) - 0.25).abs() < 1e-12, "{m2:?} {m2_plain:?}");
    let t = arm::frame_pose_hand(&q);
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| t[k][i] * t[k][j]).sum();
            assert!((dot - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
        }
    }
    assert_eq!(t[3], [0.0, 0.0, 0.0, 1.0]);
}
