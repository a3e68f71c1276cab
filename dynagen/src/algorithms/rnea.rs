//! The recursive Newton-Euler algorithm: inverse dynamics
//! τ = M(q)q̈ + C(q, q̇)q̇ + g(q) + J(q)ᵀF_tip.
//!
//! The classical (Luh-Walker-Paul) form of the recursion that *Modern
//! Robotics* §8.3 writes with twists: going forward from the base, each body
//! gets its angular velocity ω, its angular acceleration ω̇ and the
//! acceleration a of its frame's origin (the ordinary, not the spatial,
//! linear acceleration), with the base accelerating at −g so that gravity
//! appears as an inertial force; the linear velocity is never needed. Going
//! backward from the tips, each joint transmits the force f and the moment n
//! about its body's origin, and its torque is the projection onto its axis.
//! Every quantity is kept in the body's own frame.
//!
//! With the body's mass m, first moment h = m·c and rotational inertia Ī
//! about its origin, the wrench that produces its motion is
//! f = m·a + ω̇ × h + ω × (ω × h) and n = Ī·ω̇ + ω × (Ī·ω) + h × a: the
//! spatial I·A + V ×* I·V written without the linear velocity, which costs
//! fewer operations (and fewer in the generated code).

use super::joint::{add_axis, cross_axis, force_to_parent, joint_transform, project, with_rotation, Rotation};
use super::{TipWrench, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Motion, Transform, Vec3};
use crate::Scalar;

/// Computes the pose of every body in its parent's frame into `ws.x`.
#[inline(always)]
pub(crate) fn update_joint_transforms<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    for (i, b) in model.bodies.iter().enumerate() {
        ws.x[i] = joint_transform(&b.joint, q[i]);
    }
}

/// Inverse dynamics by the recursive Newton-Euler algorithm.
///
/// - `q`, `qd`, `qdd`: joint positions, velocities and accelerations in joint
///   order (rad, m; per second; per second²). `None` for `qd` or `qdd` means
///   zero, and the terms that would multiply it are not computed.
/// - `gravity`: in the base frame (m/s²); `None` for no gravity.
/// - `tips`: wrenches the robot applies to its environment at named frames
///   (the Modern Robotics `Ftip`).
/// - `tau`: the joint torques (N·m) or forces (N) are written here.
///
/// # Panics
/// If a slice's length is not the model's number of joints.
// Inlined into its callers so that a caller compiled with extra CPU features
// (the FMA form of the compensated forward dynamics) compiles it with them.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    gravity: Option<&Vec3<S>>,
    tips: &[TipWrench<S>],
    tau: &mut [S],
) {
    let n = model.dof();
    assert!(q.len() == n && tau.len() == n && ws.dof() == n, "rnea: slices must have the model's {n} joints");
    assert!(
        qd.is_none_or(|x| x.len() == n) && qdd.is_none_or(|x| x.len() == n),
        "rnea: slices must have the model's {n} joints"
    );

    // Slices of the known length, so that indexing by body needs no checks.
    let (bodies, q, tau) = (&model.bodies[..n], &q[..n], &mut tau[..n]);
    let (qd, qdd) = (qd.map(|x| &x[..n]), qdd.map(|x| &x[..n]));
    // ws.v[i].ang holds ω (ws.v[i].lin is not used); ws.a[i] holds (ω̇; a).
    let (xs, vs, accs, fs) = (&mut ws.x[..n], &mut ws.v[..n], &mut ws.a[..n], &mut ws.f[..n]);
    // Without q̇ and q̈ every ω̇ is zero (and without q̇ every ω).
    let moving = qd.is_some() || qdd.is_some();
    for (i, body) in bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[i]);
        xs[i] = x;
        // The parent's ω and ω̇, and the acceleration of this body's origin,
        // all in this body's frame. The base is at rest, accelerating at −g.
        let (w_in, wd_in, mut a) = match body.parent {
            Some(p) => with_rotation!(joint, x, |r| {
                // a_origin = a_parent + ω̇ × p + ω × (ω × p), in the parent's frame
                let mut ao = accs[p].lin;
                let (mut w_in, mut wd_in) = (Vec3::zero(), Vec3::zero());
                if moving {
                    let wdp = accs[p].ang;
                    ao += wdp.cross(&x.trans);
                    wd_in = r.tr_mul(&wdp);
                }
                if qd.is_some() {
                    let wp = vs[p].ang;
                    ao += wp.cross(&wp.cross(&x.trans));
                    w_in = r.tr_mul(&wp);
                }
                (w_in, wd_in, r.tr_mul(&ao))
            }),
            None => {
                let a = gravity.map_or(Vec3::zero(), |g| with_rotation!(joint, x, |r| r.tr_mul(&-*g)));
                (Vec3::zero(), Vec3::zero(), a)
            }
        };
        let (mut w, mut wd) = (w_in, wd_in);
        let revolute = joint.is_revolute();
        if let Some(qd) = qd {
            if revolute {
                // ω = ω_in + s·q̇, ω̇ = ω̇_in + ω_in × s·q̇ (+ s·q̈ below)
                add_axis(joint, &mut w, qd[i]);
                wd += cross_axis(joint, &w_in, qd[i]);
            } else {
                // the Coriolis acceleration 2·ω × s·q̇ (+ s·q̈ below)
                a += cross_axis(joint, &w_in, qd[i] + qd[i]);
            }
        }
        if let Some(qdd) = qdd {
            add_axis(joint, if revolute { &mut wd } else { &mut a }, qdd[i]);
        }
        let inertia = Inertia::<S>::from_f64(&body.inertia);
        let (h, ibar) = (&inertia.h, &inertia.ibar);
        let mut f = a.scale(inertia.mass);
        let mut m = h.cross(&a);
        if moving {
            f += wd.cross(h);
            m += ibar.mul_vec(&wd);
        }
        if qd.is_some() {
            f += w.cross(&w.cross(h));
            m += w.cross(&ibar.mul_vec(&w));
        }
        vs[i].ang = w;
        accs[i] = Motion::new(wd, a);
        fs[i] = Force::new(m, f);
    }
    for tip in tips {
        let frame = &model.frames[tip.frame];
        if let Some(b) = frame.body {
            let place = Transform::<S>::from_f64(&frame.placement);
            fs[b] += place.force_to_parent(&tip.wrench);
        }
    }
    for (i, body) in bodies.iter().enumerate().rev() {
        tau[i] = project(&body.joint, &fs[i]);
        if let Some(p) = body.parent {
            let fp = force_to_parent(&body.joint, &xs[i], &fs[i]);
            fs[p] += fp;
        }
    }
}
