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
use super::{Loads, Workspace};
use crate::model::Model;
use crate::spatial::{Force, Inertia, Mat3, Motion, Sym3, Vec3};
use crate::Scalar;

/// The products `ω ωᵀ` as `[xx, yy, zz, xy, xz, yz]`, shared by
/// [`velocity_product_matrix`] and [`gyroscopic`].
#[inline(always)]
pub(crate) fn products<S: Scalar>(w: &Vec3<S>) -> Sym3<S> {
    let [x, y, z] = w.0;
    Sym3([x * x, y * y, z * z, x * y, x * z, y * z])
}

/// `U = [ω̇×] + [ω×][ω×]` (Khalil's matrix), so that `U·v = ω̇ × v + ω × (ω × v)`:
/// the acceleration of a point at `v` of a body turning with ω, ω̇ relative
/// to the body's origin; `p` = [`products`] of ω (`None`: ω = 0, only `[ω̇×]`).
#[inline(always)]
pub(crate) fn velocity_product_matrix<S: Scalar>(p: Option<&Sym3<S>>, wd: &Vec3<S>) -> Mat3<S> {
    let mut u = Mat3::skew(wd);
    if let Some(p) = p {
        let [xx, yy, zz, xy, xz, yz] = p.0;
        let m = &mut u.0;
        m[0][0] = -(yy + zz);
        m[1][1] = -(xx + zz);
        m[2][2] = -(xx + yy);
        m[0][1] += xy;
        m[1][0] += xy;
        m[0][2] += xz;
        m[2][0] += xz;
        m[1][2] += yz;
        m[2][1] += yz;
    }
    u
}

/// Whether [`gyroscopic`] is the cheaper form of `ω × (Ī ω)` for this body's
/// (constant) `Ī`, counting the operations of both forms on its non-zero
/// entries (not counting the products `ω ωᵀ`, which `U` needs anyway): a
/// sparse `Ī`, as regrouping leaves, takes fewer operations from the
/// products, a dense one as `Ī ω` then a cross product.
#[inline(always)]
pub(crate) fn use_products_for_gyroscopic(ibar: &Sym3<f64>) -> bool {
    let [xx, yy, zz, xy, xz, yz] = ibar.0;
    let nz = |x: f64| usize::from(x != 0.0);
    let sum = |terms: &[usize]| {
        let n: usize = terms.iter().sum();
        (2 * n).saturating_sub(1)
    };
    // Ī ω row by row, then ω × (Ī ω): a component of the cross product has
    // a term for each non-zero entry of Ī ω it reads.
    let rows = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]].map(|r| r.iter().map(|x| nz(*x)).sum::<usize>());
    let direct = rows.iter().map(|n| (2 * n).saturating_sub(1)).sum::<usize>()
        + sum(&[usize::from(rows[2] > 0), usize::from(rows[1] > 0)])
        + sum(&[usize::from(rows[0] > 0), usize::from(rows[2] > 0)])
        + sum(&[usize::from(rows[1] > 0), usize::from(rows[0] > 0)]);
    // the three components of `gyroscopic`, a difference of products each
    let products = sum(&[nz(xz), nz(xy), nz(yz), nz(zz - yy)])
        + sum(&[nz(xy), nz(yz), nz(xz), nz(xx - zz)])
        + sum(&[nz(yz), nz(xz), nz(xy), nz(yy - xx)])
        + nz(yz)
        + nz(xz)
        + nz(xy);
    products < direct
}

/// The gyroscopic moment `ω × (Ī ω)` from the products `p = ω ωᵀ` (see
/// [`products`]): each component is a combination of the products with
/// constant coefficients, e.g. `x: Ī_xz p_xy − Ī_xy p_xz + Ī_yz (p_yy − p_zz)
/// + (Ī_zz − Ī_yy) p_yz`, so the products of ω that `U` needs serve here too.
#[inline(always)]
pub(crate) fn gyroscopic<S: Scalar>(i: &Sym3<S>, p: &Sym3<S>) -> Vec3<S> {
    let [ixx, iyy, izz, ixy, ixz, iyz] = i.0;
    let [pxx, pyy, pzz, pxy, pxz, pyz] = p.0;
    Vec3([
        ixz * pxy - ixy * pxz + iyz * (pyy - pzz) + (izz - iyy) * pyz,
        ixy * pyz - iyz * pxy + ixz * (pzz - pxx) + (ixx - izz) * pxz,
        iyz * pxz - ixz * pyz + ixy * (pxx - pyy) + (iyy - ixx) * pxy,
    ])
}

/// `Ī·ω̇ + ω × (Ī·ω)` from `U` ([`velocity_product_matrix`], whose
/// off-diagonal entries are `ω̇_k ± ω_i ω_j`) and the products `p = ω ωᵀ`:
/// grouped by the entries of `Ī` (as Khalil and Kleinfinger write the
/// Newton-Euler moment), each off-diagonal entry of `Ī` multiplies three
/// terms instead of five, e.g. `x: Ī_xx ω̇_x + Ī_xz U_yx − Ī_xy U_zx +
/// Ī_yz (p_yy − p_zz) + (Ī_zz − Ī_yy) p_yz`. The sum of `Ī·ω̇` and
/// [`gyroscopic`], up to rounding.
#[inline(always)]
pub(crate) fn inertial_moment<S: Scalar>(i: &Sym3<S>, wd: &Vec3<S>, p: &Sym3<S>, u: &Mat3<S>) -> Vec3<S> {
    let [ixx, iyy, izz, ixy, ixz, iyz] = i.0;
    let [pxx, pyy, pzz, pxy, pxz, pyz] = p.0;
    let [wx, wy, wz] = wd.0;
    let u = &u.0;
    Vec3([
        ixx * wx + ixz * u[1][0] - ixy * u[2][0] + iyz * (pyy - pzz) + (izz - iyy) * pyz,
        iyy * wy + ixy * u[2][1] - iyz * u[0][1] + ixz * (pzz - pxx) + (ixx - izz) * pxz,
        izz * wz + iyz * u[0][2] - ixz * u[1][2] + ixy * (pxx - pyy) + (iyy - ixx) * pxy,
    ])
}

/// Computes the pose of every body in its parent's frame into `ws.x`, from
/// the bodies' coordinates (one per body).
#[inline(always)]
pub(crate) fn update_joint_transforms<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) {
    for (i, b) in model.bodies.iter().enumerate() {
        ws.x[i] = joint_transform(&b.joint, q[i]);
    }
}

/// The motion of the body the tree's first joints hang from, in its own
/// frame: ω, ω̇, the ordinary acceleration of its origin with gravity folded
/// in (`a − Rᵀg`), and `U` ([`velocity_product_matrix`]) of ω and ω̇. A
/// floating base moves so; a fixed base is at rest and accelerates at −g.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RootMotion<S> {
    pub(crate) w: Vec3<S>,
    pub(crate) wd: Vec3<S>,
    pub(crate) a: Vec3<S>,
    pub(crate) u: Mat3<S>,
}

/// The root of [`rnea_tree`]: a fixed base accelerating at −g (base frame;
/// `None`: no gravity), or a moving one.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Root<'a, S> {
    Fixed(Option<&'a Vec3<S>>),
    Moving(&'a RootMotion<S>),
}

/// The wrench `(n; f)` about a body's origin that produces its motion
/// (ω, ω̇, origin acceleration `a`): `f = m·a + U·h`, `n = Ī·ω̇ + ω × (Ī·ω)
/// + h × a`, and `U` ([`velocity_product_matrix`]). `spinning`: whether ω
/// may be non-zero (q̇ given), `moving`: whether ω or ω̇ may be (`U` is
/// `None` otherwise); `gyro` the body's choice of form for `ω × (Ī·ω)` on
/// numbers (see [`use_products_for_gyroscopic`]).
#[inline(always)]
pub(crate) fn body_wrench<S: Scalar>(
    inertia: &Inertia<S>,
    [w, wd, a]: [&Vec3<S>; 3],
    (spinning, moving): (bool, bool),
    gyro: bool,
) -> (Force<S>, Option<Mat3<S>>) {
    let (h, ibar) = (&inertia.h, &inertia.ibar);
    let mut f = a.scale(inertia.mass);
    let mut m = h.cross(a);
    let p = spinning.then(|| products(w));
    let mut u = None;
    if moving {
        // U = [ω̇×] + [ω×][ω×]: U·v = ω̇ × v + ω × (ω × v), shared by this
        // body's force (v = h) and its children's origins (v = p)
        let uu = velocity_product_matrix(p.as_ref(), wd);
        f += uu.mul_vec(h);
        // Traced: Ī·ω̇ + ω × (Ī·ω) grouped by the entries of Ī, fewer
        // products than Ī·ω̇ plus either form of the gyroscopic moment. On
        // f64 it made `bias_forces` 1.5–2 % slower in instructions, so
        // there it is compiled out (Scalar::TRACED).
        match &p {
            Some(p) if S::TRACED => m += inertial_moment(ibar, wd, p, &uu),
            _ => m += ibar.mul_vec(wd),
        }
        u = Some(uu);
    }
    if let Some(p) = &p {
        if !S::TRACED {
            m += if gyro { gyroscopic(ibar, p) } else { w.cross(&ibar.mul_vec(w)) };
        }
    }
    (Force::new(m, f), u)
}

/// Inverse dynamics by the recursive Newton-Euler algorithm. A floating
/// model goes to [`floating::rnea`](super::floating::rnea::rnea) (NQ/NV-long
/// slices, gravity in the world frame).
///
/// - `q`, `qd`, `qdd`: joint positions, velocities and accelerations in joint
///   order (rad, m; per second; per second²). `None` for `qd` or `qdd` means
///   zero, and the terms that would multiply it are not computed.
/// - `loads`: gravity in the base frame (m/s²), wrenches the robot applies
///   to its environment at named frames (the Modern Robotics `Ftip`), extra
///   inertias carried by bodies (payloads: each adds the wrench that
///   produces its motion, m·a + U·h and Ī·ω̇ + ω × (Ī·ω) + h × a, to its
///   body's, exactly as if the body's own inertia were the sum) and the
///   armature (armature∘q̈ added last).
/// - `tau`: the joint torques (N·m) or forces (N) are written here.
///
/// A model with mimic joints takes one entry per joint with a coordinate of
/// its own, and the recursion runs on the bodies' coordinates
/// ([`mimic`](super::mimic)).
///
/// # Panics
/// If a slice's length is not the model's number of joints, or a payload's
/// body is not a body of the model.
// Inlined into its callers so that a caller compiled with extra CPU features
// (the FMA form of the compensated forward dynamics) compiles it with them.
#[inline(always)]
pub fn rnea<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    qdd: Option<&[S]>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    if model.has_mimic() {
        return super::mimic::rnea(model, ws, (q, qd, qdd), loads, tau);
    }
    rnea_bodies(model, ws, (q, qd, qdd), loads, tau)
}

/// The state an inverse dynamics reads: q, and q̇ and q̈ unless zero.
pub(crate) type State<'a, S> = (&'a [S], Option<&'a [S]>, Option<&'a [S]>);

/// [`rnea`] on the bodies' coordinates, one per body ([`Model::tree_nq`]).
#[inline(always)]
pub(crate) fn rnea_bodies<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    (q, qd, qdd): State<'_, S>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) {
    if model.is_floating() {
        return super::floating::rnea::rnea(model, ws, q, qd, qdd, loads, tau);
    }
    let n = model.bodies.len();
    loads.check(n, "rnea");
    assert!(q.len() == n && tau.len() == n && ws.dof() == n, "rnea: slices must have the model's {n} joints");
    assert!(
        qd.is_none_or(|x| x.len() == n) && qdd.is_none_or(|x| x.len() == n),
        "rnea: slices must have the model's {n} joints"
    );
    rnea_tree(model, ws, q, (qd, qdd), Root::Fixed(loads.gravity), loads, tau);
    add_armature(loads.armature, qdd, tau);
}

/// `τ += armature∘q̈` (joints only: `tau` and `qdd` are the joints' slices).
#[inline(always)]
pub(crate) fn add_armature<S: Scalar>(armature: Option<&[f64]>, qdd: Option<&[S]>, tau: &mut [S]) {
    if let (Some(armature), Some(qdd)) = (armature, qdd) {
        for (i, &a) in armature.iter().enumerate() {
            if a != 0.0 {
                tau[i] += S::from_f64(a) * qdd[i];
            }
        }
    }
}

/// The two passes of [`rnea`] over the bodies, hanging from `root`, without
/// the armature: `q`, `(qd, qdd)` and `tau` are the joints' slices (n long,
/// checked by the caller). Of `loads` the tips on bodies and the payloads are
/// read (gravity comes with the root). Returns the wrench the root's
/// children exert on it, in its frame (zero for a fixed root, which is not
/// summed).
#[inline(always)]
pub(crate) fn rnea_tree<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    (qd, qdd): (Option<&[S]>, Option<&[S]>),
    root: Root<'_, S>,
    loads: Loads<'_, S>,
    tau: &mut [S],
) -> Force<S> {
    let n = model.bodies.len();
    let Loads { tips, payloads, .. } = loads;
    // Slices of the known length, so that indexing by body needs no checks.
    let (bodies, q, tau) = (&model.bodies[..n], &q[..n], &mut tau[..n]);
    let (qd, qdd) = (qd.map(|x| &x[..n]), qdd.map(|x| &x[..n]));
    // ws.v[i].ang holds ω (ws.v[i].lin is not used); ws.a[i] holds (ω̇; a).
    let (xs, vs, accs, fs) = (&mut ws.x[..n], &mut ws.v[..n], &mut ws.a[..n], &mut ws.f[..n]);
    let (us, gyro) = (&mut ws.u[..n], &ws.gyro_products[..n]);
    // Without q̇ and q̈ every ω̇ is zero (and without q̇ every ω).
    let moving = qd.is_some() || qdd.is_some();
    for (i, body) in bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[i]);
        xs[i] = x;
        // The parent's ω, ω̇, origin acceleration and U, in its frame.
        let parent = match body.parent {
            Some(p) => Some((vs[p].ang, accs[p], us[p])),
            None => match root {
                Root::Moving(r) => Some((r.w, Motion::new(r.wd, r.a), r.u)),
                Root::Fixed(_) => None,
            },
        };
        // The parent's ω and ω̇, and the acceleration of this body's origin,
        // all in this body's frame. A fixed base is at rest, accelerating at −g.
        let (w_in, wd_in, mut a) = match (parent, root) {
            (Some((wp, ap, up)), _) => with_rotation!(joint, x, |r| {
                // a_origin = a_parent + ω̇ × p + ω × (ω × p) = a_parent + U·p,
                // in the parent's frame
                let mut ao = ap.lin;
                let (mut w_in, mut wd_in) = (Vec3::zero(), Vec3::zero());
                if moving {
                    ao += up.mul_vec(&x.trans);
                    wd_in = r.tr_mul(&ap.ang);
                }
                if qd.is_some() {
                    w_in = r.tr_mul(&wp);
                }
                (w_in, wd_in, r.tr_mul(&ao))
            }),
            (None, Root::Fixed(gravity)) => {
                let a = gravity.map_or(Vec3::zero(), |g| with_rotation!(joint, x, |r| r.tr_mul(&-*g)));
                (Vec3::zero(), Vec3::zero(), a)
            }
            (None, Root::Moving(_)) => unreachable!("a moving root is every root body's parent"),
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
        let inertia = body.inertia_in::<S>();
        let (mut f, u) = body_wrench(&inertia, [&w, &wd, &a], (qd.is_some(), moving), gyro[i]);
        for extra in payloads.iter().filter(|x| x.body == i) {
            // the dense forms, with the payload's inertia an input
            let Inertia { mass, h, ibar } = &extra.inertia;
            f.lin += a.scale(*mass);
            f.ang += h.cross(&a);
            if let Some(u) = &u {
                f.lin += u.mul_vec(h);
                f.ang += ibar.mul_vec(&wd);
            }
            if qd.is_some() {
                f.ang += w.cross(&ibar.mul_vec(&w));
            }
        }
        if let Some(u) = u {
            us[i] = u;
        }
        vs[i].ang = w;
        accs[i] = Motion::new(wd, a);
        fs[i] = f;
    }
    for tip in tips {
        let frame = &model.frames[tip.frame];
        if let Some(b) = frame.body {
            let place = frame.placement_in::<S>();
            fs[b] += place.force_to_parent(&tip.wrench);
        }
    }
    let mut at_root = Force::zero();
    for (i, body) in bodies.iter().enumerate().rev() {
        tau[i] = project(&body.joint, &fs[i]);
        match (body.parent, root) {
            (Some(p), _) => {
                let fp = force_to_parent(&body.joint, &xs[i], &fs[i]);
                fs[p] += fp;
            }
            (None, Root::Moving(_)) => at_root += force_to_parent(&body.joint, &xs[i], &fs[i]),
            (None, Root::Fixed(_)) => {}
        }
    }
    at_root
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `U·v = ω̇ × v + ω × (ω × v)`, the gyroscopic moment from the
    /// products equals `ω × (Ī ω)`, and the moment grouped by `Ī`'s entries
    /// `Ī ω̇ + ω × (Ī ω)`, for a dense and a sparse `Ī`.
    #[test]
    fn velocity_products_and_gyroscopic_moment() {
        let (w, wd, v): (Vec3<f64>, Vec3<f64>, Vec3<f64>) =
            (Vec3([0.7, -1.3, 0.4]), Vec3([2.1, 0.3, -0.9]), Vec3([-0.2, 0.5, 1.1]));
        let u = velocity_product_matrix(Some(&products(&w)), &wd).mul_vec(&v);
        let want = wd.cross(&v) + w.cross(&w.cross(&v));
        for k in 0..3 {
            assert!((u.0[k] - want.0[k]).abs() < 1e-14, "U·v[{k}]");
        }
        let only_wd = velocity_product_matrix(None, &wd).mul_vec(&v);
        assert_eq!(only_wd.0, wd.cross(&v).0);
        for ibar in [Sym3::<f64>([0.3, 0.25, 0.2, 0.01, -0.02, 0.015]), Sym3([0.0, 1.77, -1.755, 0.0, 0.0, 0.075])] {
            let g = gyroscopic(&ibar, &products(&w));
            let want = w.cross(&ibar.mul_vec(&w));
            for k in 0..3 {
                assert!((g.0[k] - want.0[k]).abs() < 1e-14, "gyroscopic[{k}]");
            }
            // and the moment grouped by Ī's entries, with Ī·ω̇
            let u = velocity_product_matrix(Some(&products(&w)), &wd);
            let moment = inertial_moment(&ibar, &wd, &products(&w), &u);
            let want = want + ibar.mul_vec(&wd);
            for k in 0..3 {
                assert!((moment.0[k] - want.0[k]).abs() < 1e-14, "inertial_moment[{k}]");
            }
        }
        // the regrouped UR5 upper arm's Ī is cheaper from the products, a dense one is not
        assert!(use_products_for_gyroscopic(&Sym3([0.0, 1.77, -1.755, 0.0, 0.0, 0.075])));
        assert!(!use_products_for_gyroscopic(&Sym3([0.3, 0.25, 0.2, 0.01, -0.02, 0.015])));
    }
}
