//! The solver's short cuts for joint axes along a coordinate axis and for
//! placements without rotation must not change the dynamics. Here a robot
//! with every kind of aligned joint (±x, ±y, ±z, revolute, continuous and
//! prismatic, unit and non-unit axes, rotated and unrotated placements, a
//! branch) is compared with the same robot whose joint frames are turned
//! about general directions: the physical robot is the same, but every
//! axis is then a general one and every placement is rotated, so the
//! general formulas run. τ, M and q̈ must agree to rounding.

use approx::abs_diff_eq;
use dynagen::algorithms::{aba, crba, rnea, Loads, Workspace};
use dynagen::model::{AxisAlignment, Inertial, JointDescription, RobotDescription};
use dynagen::spatial::{Mat3, Transform, Vec3};
use dynagen::{Model, RobotBuilder};

fn link(b: RobotBuilder, name: &str, k: f64) -> RobotBuilder {
    b.link(
        name,
        Some(Inertial::new(
            1.0 + k,
            [0.05 * k, -0.03 + 0.01 * k, 0.1],
            [0.02 + 0.003 * k, 0.025, 0.018 + 0.001 * k, 0.001, -0.0005 * k, 0.0007],
        )),
    )
}

/// A tree with aligned axes of every class and sign.
fn aligned_robot() -> RobotDescription {
    let mut b = RobotBuilder::new("aligned").link("base", None);
    for (i, name) in ["l1", "l2", "l3", "l4", "l5", "l6", "l7", "l8", "l9"].iter().enumerate() {
        b = link(b, name, i as f64);
    }
    let j = [
        JointDescription::revolute("j1", "base", "l1", [0.0, 0.0, 1.0]).origin([0.0, 0.0, 0.1], [0.0, 0.0, 0.0]),
        JointDescription::revolute("j2", "l1", "l2", [0.0, -1.0, 0.0]).origin([0.1, 0.02, 0.3], [0.3, -0.2, 0.5]),
        JointDescription::continuous("j3", "l2", "l3", [1.0, 0.0, 0.0]).origin([0.0, 0.2, 0.1], [0.0, 0.0, 0.0]),
        JointDescription::prismatic("j4", "l3", "l4", [0.0, 0.0, -1.0]).origin([0.1, 0.0, 0.0], [1.0, 0.2, -0.4]),
        JointDescription::revolute("j5", "l4", "l5", [-1.0, 0.0, 0.0]).origin([0.0, 0.1, 0.2], [-0.7, 1.1, 0.3]),
        JointDescription::prismatic("j6", "l5", "l6", [0.0, 1.0, 0.0]).origin([0.05, 0.0, 0.1], [0.0, 0.0, 0.0]),
        // a non-unit axis: turns by 2q
        JointDescription::revolute("j7", "l6", "l7", [0.0, 0.0, -2.0]).origin([0.0, 0.0, 0.15], [0.0, 0.0, 0.0]),
        // a branch from l2
        JointDescription::revolute("j8", "l2", "l8", [0.0, 1.0, 0.0]).origin([0.0, -0.2, 0.1], [0.4, 0.0, 0.0]),
        JointDescription::prismatic("j9", "l8", "l9", [-1.0, 0.0, 0.0]).origin([0.1, 0.1, 0.0], [0.0, 0.0, 0.0]),
    ];
    for j in j {
        b = b.joint(j.limits(-3.0, 3.0, 2.0, 100.0));
    }
    b.description().clone()
}

/// The same robot with the frame of every joint (and so of its child link)
/// turned by a general rotation `Q`: the joint origin becomes `origin·Q`,
/// the axis `Qᵀ·axis`, and what is given in the child link's frame (its
/// inertial frame, the origins of its child joints) is premultiplied by `Qᵀ`.
fn turned(desc: &RobotDescription) -> RobotDescription {
    let mut d = desc.clone();
    let turn: Vec<Transform<f64>> = (0..d.joints.len())
        .map(|i| {
            let k = i as f64;
            Transform::new(Mat3::from_rpy(0.3 + 0.1 * k, -0.5 + 0.07 * k, 0.8 - 0.2 * k), Vec3::zero())
        })
        .collect();
    for (ji, q) in turn.iter().enumerate() {
        let q_inv = q.inverse();
        let child = d.joints[ji].child.clone();
        let j = &mut d.joints[ji];
        j.origin = j.origin.compose(q);
        j.axis = q.rot.tr_mul_vec(&j.axis);
        let l = d.links.iter_mut().find(|l| l.name == child).unwrap();
        if let Some(inertial) = &mut l.inertial {
            inertial.origin = q_inv.compose(&inertial.origin);
        }
        for j in d.joints.iter_mut().filter(|j| j.parent == child) {
            j.origin = q_inv.compose(&j.origin);
        }
    }
    d
}

/// max |a − b| ≤ tol · max(1, max |a|), by `approx`.
fn close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    let epsilon = tol * a.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    assert!(abs_diff_eq!(a, b, epsilon = epsilon), "{what}: {a:?} vs {b:?} (ε {epsilon:e})");
}

#[test]
fn aligned_and_turned_joint_frames_give_the_same_dynamics() {
    let desc = aligned_robot();
    let fast = Model::from_description(&desc).unwrap();
    let general = Model::from_description(&turned(&desc)).unwrap();

    // The short cuts are really taken on one model and not on the other.
    let alignments: Vec<AxisAlignment> = fast.bodies.iter().map(|b| b.joint.alignment).collect();
    for a in [AxisAlignment::X, AxisAlignment::Y, AxisAlignment::Z] {
        assert!(alignments.contains(&a), "{alignments:?}");
    }
    assert!(!alignments.contains(&AxisAlignment::General));
    assert!(fast.bodies.iter().filter(|b| b.joint.placement_rotation_is_identity).count() >= 4);
    assert!(fast.bodies.iter().any(|b| !b.joint.placement_rotation_is_identity));
    assert!(general.bodies.iter().all(|b| b.joint.alignment == AxisAlignment::General));
    assert!(general.bodies.iter().all(|b| !b.joint.placement_rotation_is_identity));

    let n = fast.dof();
    let g = Vec3([0.0, 0.0, -9.81]);
    let (mut w1, mut w2) = (Workspace::<f64>::new(&fast), Workspace::<f64>::new(&general));
    for s in 0..4 {
        let f = |k: usize, a: f64| ((k as f64 + 1.0) * a + s as f64 * 0.37).sin() * (1.0 + s as f64);
        let q: Vec<f64> = (0..n).map(|k| f(k, 1.3)).collect();
        let qd: Vec<f64> = (0..n).map(|k| f(k, 2.1)).collect();
        let qdd: Vec<f64> = (0..n).map(|k| f(k, 0.7)).collect();

        let (mut t1, mut t2) = (vec![0.0; n], vec![0.0; n]);
        rnea::rnea(&fast, &mut w1, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut t1);
        rnea::rnea(&general, &mut w2, &q, Some(&qd), Some(&qdd), Loads::gravity(&g), &mut t2);
        close(&t1, &t2, 1e-13, "tau");
        assert!(t1.iter().all(|x| x.abs() > 1e-6), "every joint carries load: {t1:?}");

        let (mut m1, mut m2) = (vec![0.0; n * n], vec![0.0; n * n]);
        crba::crba(&fast, &mut w1, &q, Loads::none(), &mut m1);
        crba::crba(&general, &mut w2, &q, Loads::none(), &mut m2);
        close(&m1, &m2, 1e-13, "M");

        let (mut a1, mut a2) = (vec![0.0; n], vec![0.0; n]);
        aba::aba(&fast, &mut w1, &q, &qd, &t1, Loads::gravity(&g), &mut a1);
        aba::aba(&general, &mut w2, &q, &qd, &t1, Loads::gravity(&g), &mut a2);
        close(&a1, &a2, 1e-11, "qdd");
        // and forward dynamics inverts inverse dynamics
        close(&a1, &qdd, 1e-11, "aba(rnea(qdd))");
    }
}
