//! Forward dynamics by the articulated-body algorithm (Featherstone, *Rigid
//! Body Dynamics Algorithms*, §7.3): q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip)
//! in O(n), without forming M. On long chains it keeps far more digits than
//! a factorisation of M, which is why it is the default forward dynamics.

use super::joint::{
    add_axis, add_motion, cross_axis, force_to_parent, joint_transform, motion, motion_to_child, project,
    with_rotation, Rotation,
};
use super::rnea::{gyroscopic, products, velocity_product_matrix};
use super::{add_tip_wrenches, Loads, Workspace};
use crate::model::{AxisAlignment, Joint, JointKind, Model};
use crate::spatial::{Force, Inertia, Mat3, Motion, Sym3, Vec3};
use crate::Scalar;

/// A symmetric 6×6 articulated-body inertia `[[A, B], [Bᵀ, C]]` in
/// (angular; linear) order: the force `(A ω + B v, Bᵀ ω + C v)` answers the
/// acceleration `(ω, v)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArticulatedInertia<S> {
    a: Sym3<S>,
    b: Mat3<S>,
    c: Sym3<S>,
}

impl<S: Scalar> ArticulatedInertia<S> {
    /// Zero.
    pub fn zero() -> Self {
        ArticulatedInertia { a: Sym3::zero(), b: Mat3::zero(), c: Sym3::zero() }
    }
    /// A rigid body's inertia `[[Ī, [h]], [[h]ᵀ, m·1]]`.
    #[inline(always)]
    pub fn from_rigid(i: &Inertia<S>) -> Self {
        let z = S::zero();
        ArticulatedInertia { a: i.ibar, b: Mat3::skew(&i.h), c: Sym3([i.mass, i.mass, i.mass, z, z, z]) }
    }
    /// `self · m`.
    #[inline(always)]
    pub fn mul_motion(&self, m: &Motion<S>) -> Force<S> {
        Force {
            ang: self.a.mul_vec(&m.ang) + self.b.mul_vec(&m.lin),
            lin: self.b.tr_mul_vec(&m.ang) + self.c.mul_vec(&m.lin),
        }
    }
    /// Its 21 numbers: `A` (xx, yy, zz, xy, xz, yz), `B` row by row, `C`.
    pub(crate) fn to_parts(self) -> [S; 21] {
        let mut x = [S::zero(); 21];
        x[..6].copy_from_slice(&self.a.0);
        for (i, row) in self.b.0.iter().enumerate() {
            x[6 + 3 * i..9 + 3 * i].copy_from_slice(row);
        }
        x[15..].copy_from_slice(&self.c.0);
        x
    }
    /// The inverse of [`to_parts`](Self::to_parts).
    pub(crate) fn from_parts(x: &[S]) -> Self {
        let sym = |y: &[S]| Sym3([y[0], y[1], y[2], y[3], y[4], y[5]]);
        let b = Mat3([[x[6], x[7], x[8]], [x[9], x[10], x[11]], [x[12], x[13], x[14]]]);
        ArticulatedInertia { a: sym(&x[..6]), b, c: sym(&x[15..21]) }
    }
    /// As a 6×6 matrix in (angular; linear) order.
    pub(crate) fn to_matrix(self) -> [[S; 6]; 6] {
        let (a, b, c) = (self.a.to_mat().0, self.b.0, self.c.to_mat().0);
        let mut m = [[S::zero(); 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = a[i][j];
                m[i][3 + j] = b[i][j];
                m[3 + j][i] = b[i][j];
                m[3 + i][3 + j] = c[i][j];
            }
        }
        m
    }
    /// `self · S` for the joint's motion subspace `S` (one column of the
    /// matrix, times the axis component, for an axis-aligned joint).
    #[inline(always)]
    pub(crate) fn mul_subspace(&self, joint: &Joint) -> Force<S> {
        let k = match joint.alignment {
            AxisAlignment::X => 0,
            AxisAlignment::Y => 1,
            AxisAlignment::Z => 2,
            AxisAlignment::General => return self.mul_motion(&motion(joint, S::one())),
        };
        let a = S::from_f64(joint.axis.0[k]);
        let sym_col = |s: &Sym3<S>| {
            let [xx, yy, zz, xy, xz, yz] = s.0;
            Vec3([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]][k]).scale(a)
        };
        match joint.kind {
            // (A e_k a, Bᵀ e_k a)
            JointKind::Revolute | JointKind::Continuous => {
                Force { ang: sym_col(&self.a), lin: Vec3(self.b.0[k]).scale(a) }
            }
            // (B e_k a, C e_k a)
            JointKind::Prismatic => Force { ang: self.b.col(k).scale(a), lin: sym_col(&self.c) },
        }
    }
    /// `self − u uᵀ / d`.
    #[inline(always)]
    pub(crate) fn sub_outer(&self, u: &Force<S>, d_inv: S) -> Self {
        let (ua, ul) = (u.ang.scale(d_inv), u.lin);
        let sym = |s: &Sym3<S>, x: &Vec3<S>, y: &Vec3<S>| {
            let (x, y) = (x.0, y.0);
            Sym3([
                s.0[0] - x[0] * y[0],
                s.0[1] - x[1] * y[1],
                s.0[2] - x[2] * y[2],
                s.0[3] - x[0] * y[1],
                s.0[4] - x[0] * y[2],
                s.0[5] - x[1] * y[2],
            ])
        };
        let mut b = self.b;
        for (r, row) in b.0.iter_mut().enumerate() {
            for (c, e) in row.iter_mut().enumerate() {
                *e -= ua.0[r] * ul.0[c];
            }
        }
        ArticulatedInertia { a: sym(&self.a, &ua, &u.ang), b, c: sym(&self.c, &ul.scale(d_inv), &ul) }
    }
    /// Sets to exact zeros what `self − u uᵀ / d` (with `u = self·S`,
    /// `d = Sᵀu`) has as zeros in exact arithmetic: the row and column of
    /// an axis-aligned joint's direction, since `(I − u uᵀ/d)·S = u − u = 0`.
    /// Computing them would only give rounding errors (and operations).
    #[inline(always)]
    fn clear_subspace(&mut self, joint: &Joint) {
        let k = match joint.alignment {
            AxisAlignment::X => 0,
            AxisAlignment::Y => 1,
            AxisAlignment::Z => 2,
            AxisAlignment::General => return,
        };
        let z = S::zero();
        // Sym3 storage [xx, yy, zz, xy, xz, yz]: the entries of row/column k.
        let sym_entries = [[0, 3, 4], [3, 1, 5], [4, 5, 2]][k];
        match joint.kind {
            JointKind::Revolute | JointKind::Continuous => {
                for e in sym_entries {
                    self.a.0[e] = z;
                }
                self.b.0[k] = [z; 3];
            }
            JointKind::Prismatic => {
                for e in sym_entries {
                    self.c.0[e] = z;
                }
                for row in self.b.0.iter_mut() {
                    row[k] = z;
                }
            }
        }
    }
    /// The same inertia seen from the parent: `Xᵀ · self · X`, where `X`
    /// maps parent motion to this frame and `x` is this frame's pose in
    /// the parent.
    #[inline(always)]
    pub(crate) fn expressed_in_parent<R: Rotation<S>>(&self, r: &R, trans: &Vec3<S>) -> Self {
        // Rotate the blocks into the parent's axes, then shift the origin
        // by r: A' = A₁ − B₁[r] + [r]B₁ᵀ − [r]C₁[r], B' = B₁ + [r]C₁, C' = C₁.
        let a1 = r.rotate_sym(&self.a);
        let b1 = r.rotate_mat(&self.b);
        let c1 = r.rotate_sym(&self.c);
        // The products with the skew matrix [r] are cross products:
        // column c of [r]C₁ is r × (column c of C₁), column c of [r]B₁ᵀ is
        // r × (row c of B₁), and row i of ([r]C₁)[r] is (row i of [r]C₁) × r.
        let c1m = c1.to_mat();
        let rc = [trans.cross(&c1m.col(0)), trans.cross(&c1m.col(1)), trans.cross(&c1m.col(2))]; // columns
        let rb = [trans.cross(&Vec3(b1.0[0])), trans.cross(&Vec3(b1.0[1])), trans.cross(&Vec3(b1.0[2]))]; // columns
        let rc_row = |i: usize| Vec3([rc[0].0[i], rc[1].0[i], rc[2].0[i]]);
        let rcr = [rc_row(0).cross(trans), rc_row(1).cross(trans), rc_row(2).cross(trans)]; // rows
        let mut a = a1.0;
        let idx = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
        for (k, (i, j)) in idx.into_iter().enumerate() {
            // −B₁[r] = ([r]B₁ᵀ)ᵀ
            a[k] = a[k] + rb[i].0[j] + rb[j].0[i] - rcr[i].0[j];
        }
        let mut b = b1;
        for (i, row) in b.0.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e += rc[j].0[i];
            }
        }
        ArticulatedInertia { a: Sym3(a), b, c: c1 }
    }
    /// `self + o`.
    #[inline(always)]
    pub(crate) fn add(&self, o: &Self) -> Self {
        let mut b = self.b;
        for i in 0..3 {
            for j in 0..3 {
                b.0[i][j] += o.b.0[i][j];
            }
        }
        ArticulatedInertia { a: self.a + o.a, b, c: self.c + o.c }
    }
}

/// The index of an axis-aligned joint's axis, `None` for a general axis.
#[inline(always)]
fn axis_index(joint: &Joint) -> Option<usize> {
    match joint.alignment {
        AxisAlignment::X => Some(0),
        AxisAlignment::Y => Some(1),
        AxisAlignment::Z => Some(2),
        AxisAlignment::General => None,
    }
}

/// Forward dynamics by the articulated-body algorithm (a floating model:
/// [`floating::aba`](super::floating::aba::aba), NQ/NV-long slices).
///
/// `tau` are the joint torques/forces; `loads` are gravity in the base
/// frame, the wrenches the robot applies to its environment, the payloads
/// (added to their bodies' inertias) and the armature; the joint
/// accelerations are written to `qdd`.
///
/// A per-joint armature `a` (reflected rotor inertia, kg·m² or kg) gives
/// q̈ = (M(q) + diag(a))⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip). Armature is an inertia
/// felt by the joint coordinate alone, so it enters the recursion exactly
/// where the joint's own inertia does: in `D_i = S_iᵀU_i + a_i` (and so in
/// the articulated inertia passed to the parent, `I_iᴬ − U_i D_i⁻¹ U_iᵀ`).
/// Nothing else changes, so the algorithm keeps its O(n) cost and its
/// accuracy. A joint with `a_i = 0` costs nothing more.
///
/// A model with mimic joints has no articulated-body recursion (a mimic
/// joint has no acceleration of its own to eliminate): its q̈ is the same
/// M(q)⁻¹(τ − h − JᵀF_tip) through M by
/// [`forward_dynamics_ldlt`](super::forward_dynamics::forward_dynamics_ldlt)
/// ([`mimic`](super::mimic)).
///
/// # Panics
/// If a slice's length is not the model's number of joints, or a payload's
/// body is not a body of the model.
pub fn aba<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    if model.has_mimic() {
        return super::forward_dynamics::forward_dynamics_ldlt(model, ws, q, qd, tau, loads, qdd);
    }
    if model.is_floating() {
        return super::floating::aba::aba(model, ws, q, qd, tau, loads, qdd);
    }
    aba_traced_or_compact(model, ws, q, Some(qd), tau, loads, qdd)
}

/// M(q)⁻¹τ: the articulated-body algorithm at rest (q̇ = 0) and without
/// gravity or tip wrenches, which skips every velocity term (the forward
/// pass only places the bodies, and the bias forces are zero). Of `loads`
/// only the inertias (payloads, armature) are read. This is the solve of
/// the compensated forward dynamics
/// ([`forward_dynamics_compensated`](super::compensated::forward_dynamics_compensated)),
/// which has the bias forces already.
///
/// A model with mimic joints: M(q)⁻¹τ by the LᵀDL factorisation of M, as
/// [`aba`].
///
/// # Panics
/// As [`aba`].
pub fn aba_at_rest<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    if model.has_mimic() {
        qdd.copy_from_slice(tau);
        return super::forward_dynamics::solve_with_mass_matrix(model, ws, q, loads.inertias(), qdd);
    }
    if model.is_floating() {
        return super::floating::aba::aba_at_rest(model, ws, q, tau, loads, qdd);
    }
    aba_traced_or_compact(model, ws, q, None, tau, loads.inertias(), qdd)
}

/// [`aba_impl`] in the arm for the scalar: distributed for traced code
/// ([`Scalar::TRACED`]), compact on numbers.
#[inline(always)]
fn aba_traced_or_compact<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    tau: &[S],
    loads: Loads<'_, S>,
    qdd: &mut [S],
) {
    if S::TRACED {
        aba_impl::<S, true>(model, ws, q, qd, tau, loads, &[], qdd)
    } else {
        aba_impl::<S, false>(model, ws, q, qd, tau, loads, &[], qdd)
    }
}

/// The articulated-body algorithm; `qd: None` is at rest (see [`aba_at_rest`]).
///
/// `DISTRIBUTED` (what traced code uses, [`Scalar::TRACED`]) shortens the
/// dependency chain across the joints without changing the result in exact
/// arithmetic. The inward pass passes to the parent
/// `X(Iᴬ − U Uᵀ/D)Xᵀ = X Iᴬ Xᵀ − (XU)(XU)ᵀ/D` and
/// `X(pᴬ + Iᵃc + U u/D) = X(pᴬ + Iᴬc) + XU·(u − Uᵀc)/D` (with
/// `Iᵃ = Iᴬ − U Uᵀ/D`), so everything but one scaling and the rank-one
/// subtraction is computed while the division runs, instead of the whole
/// transform waiting for it. The outward pass uses
/// `Uᵀ(X a_p + c) = (XU)ᵀa_p + Uᵀc`, so q̈ does not wait for the transform
/// of the parent's acceleration. Without armature, along an axis-aligned
/// joint, the exact zeros of `clear_subspace` are kept (the inertia and U
/// are cleared before the transform, and the joint's own force enters as
/// `e_k u/a`). It costs a few operations (U is transformed on its own, and
/// the rank-one update is made on the dense transformed inertia), for a
/// much shorter critical path of the generated ABA (`docs/performance.md`,
/// "Design choices decided by a measurement"). On `f64` the compact arm is
/// kept: there the operation count, not the chain, sets the speed.
///
/// `carried`: what branches computed apart pass to their parents (see
/// [`Carried`]); empty but for `codegen/trace/branches.rs`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn aba_impl<S: Scalar, const DISTRIBUTED: bool>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    tau: &[S],
    loads: Loads<'_, S>,
    carried: &[Carried<S>],
    qdd: &mut [S],
) {
    let n = model.bodies.len();
    assert!(
        q.len() == n && qd.is_none_or(|qd| qd.len() == n) && tau.len() == n && qdd.len() == n && ws.dof() == n,
        "aba: slices must have the model's {n} joints"
    );
    loads.check(n, "aba");
    velocities(model, ws, q, qd, None, loads);
    add_carried(ws, None, carried);
    inward(model, ws, (tau, qd.is_some()), loads.armature, None, DISTRIBUTED);
    // A fixed base is at rest, accelerating at −g.
    let a0 = Motion::new(Vec3::zero(), loads.gravity.map_or(Vec3::zero(), |g| -*g));
    outward(model, ws, &a0, qdd, DISTRIBUTED);
}

/// What a branch computed on its own passes to its parent in [`inward`]
/// (`codegen/trace/branches.rs`): its articulated inertia and bias force in
/// the parent's frame; `parent` a body, or `None` for the moving root.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Carried<S> {
    pub(crate) parent: Option<usize>,
    pub(crate) inertia: ArticulatedInertia<S>,
    pub(crate) bias: Force<S>,
}

/// Adds `carried` to their parents' articulated inertias and bias forces
/// (after [`velocities`], before [`inward`]), as [`pass_on`] adds a child's.
pub(crate) fn add_carried<S: Scalar>(
    ws: &mut Workspace<S>,
    mut root: Option<&mut RootArticulated<S>>,
    carried: &[Carried<S>],
) {
    for c in carried {
        pass_on(ws, root.as_deref_mut(), c.parent, &c.inertia, || c.bias);
    }
}

/// The articulated inertia and bias force that a moving root (a floating
/// base) collects from its children in [`inward`], in its frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RootArticulated<S> {
    pub(crate) inertia: ArticulatedInertia<S>,
    pub(crate) bias: Force<S>,
}

/// The first pass of [`aba_impl`]: poses (`ws.x`), angular velocities ω
/// (`ws.v`), velocity-product accelerations c (`ws.a`), bias forces pᴬ
/// (`ws.f`, with the tip wrenches on bodies), rigid inertias (`ws.art`, the
/// payloads added); `qd: None` at rest. `root_w`: the ω of a moving root,
/// in its frame (`None`: a root at rest).
///
/// The accelerations of this algorithm are "classic": (ω̇; the ordinary
/// acceleration of the frame's origin), as in the RNEA, so the linear
/// velocity is never needed: a body's wrench is I·(ω̇; a) + b with
/// b = (ω × Ī ω; ω × (ω × h)), and the origin of a child at p (in the
/// parent) accelerates by X·(ω̇_p; a_p) + c with c's linear part
/// ω_p × (ω_p × p) (plus the Coriolis 2 ω × ṗ of a prismatic joint) and
/// c's angular part ω_in × S q̇ (revolute). Featherstone's spatial form
/// gives the same q̈ with more operations.
#[inline(always)]
pub(crate) fn velocities<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    q: &[S],
    qd: Option<&[S]>,
    root_w: Option<&Vec3<S>>,
    loads: Loads<'_, S>,
) {
    // [ω×]² of the moving root: the centripetal acceleration of its children's origins.
    let root = root_w.map(|w| (*w, velocity_product_matrix(Some(&products(w)), &Vec3::zero())));
    for (i, body) in model.bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[i]);
        ws.x[i] = x;
        let mut inertia = body.inertia_in::<S>();
        for p in loads.payloads.iter().filter(|p| p.body == i) {
            inertia = inertia.add(&p.inertia);
        }
        ws.art[i] = ArticulatedInertia::from_rigid(&inertia);
        let Some(qd) = qd else {
            // At rest: no velocity, no velocity-product acceleration, no bias force.
            ws.a[i] = Motion::zero();
            ws.f[i] = Force::zero();
            continue;
        };
        let revolute = joint.is_revolute();
        let parent = match body.parent {
            Some(p) => Some((ws.v[p].ang, ws.u[p])),
            None => root,
        };
        let (mut w, mut c) = match parent {
            Some((wp, up)) => with_rotation!(joint, x, |r| {
                let centripetal = up.mul_vec(&x.trans);
                (r.tr_mul(&wp), Motion::new(Vec3::zero(), r.tr_mul(&centripetal)))
            }),
            None => (Vec3::zero(), Motion::zero()),
        };
        if revolute {
            c.ang = cross_axis(joint, &w, qd[i]);
            add_axis(joint, &mut w, qd[i]);
        } else {
            c.lin += cross_axis(joint, &w, qd[i] + qd[i]);
        }
        ws.v[i] = Motion::new(w, Vec3::zero());
        ws.a[i] = c; // c_i, kept until the last pass
                     // [ω×]²: ω × (ω × h) here, the centripetal acceleration of the children
        let p = products(&w);
        let u = velocity_product_matrix(Some(&p), &Vec3::zero());
        ws.u[i] = u;
        let wwh = u.mul_vec(&inertia.h);
        let gyro = if ws.gyro_products[i] { gyroscopic(&inertia.ibar, &p) } else { w.cross(&inertia.ibar.mul_vec(&w)) };
        ws.f[i] = Force::new(gyro, wwh);
    }
    add_tip_wrenches(model, loads.tips, Some(&mut ws.f), None);
}

/// The inward pass of [`aba_impl`] after [`velocities`]: articulated
/// inertias and bias forces from the tips to the root; `(tau, moving)` the
/// joint torques and whether q̇ was given; a moving `root` collects what its
/// children pass it (a fixed one takes nothing); `distributed` the arm (a
/// constant where it is inlined, see [`aba_impl`]).
#[inline(always)]
pub(crate) fn inward<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    (tau, moving): (&[S], bool),
    armature: Option<&[f64]>,
    mut root: Option<&mut RootArticulated<S>>,
    distributed: bool,
) {
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let u = ws.art[i].mul_subspace(&body.joint);
        let d = project(&body.joint, &u);
        let arm = armature.map_or(0.0, |a| a[i]);
        let d = if arm == 0.0 { d } else { d + S::from_f64(arm) };
        let d_inv = S::one() / d;
        let ui = tau[i] - project(&body.joint, &ws.f[i]);
        ws.s1[i] = d_inv;
        // Whether body i passes anything on.
        let passes = body.parent.is_some() || root.is_some();
        if distributed {
            // The transform distributed over the rank-one update (exact
            // algebra, see the function's documentation): what does not
            // wait for 1/d (X Iᴬ Xᵀ, X U, X(pᴬ + Iᴬc), u − Uᵀc) runs
            // beside the division, and only the scaling and the rank-one
            // subtraction follow it.
            let x = ws.x[i];
            // Without armature, along an axis-aligned joint's direction k,
            // Iᴬ − U Uᵀ/d has an exact zero row and column, so it equals
            // Iᴬ₀ − U₀U₀ᵀ/d with row/column k cleared from Iᴬ and entry k
            // from U (fewer operations, and the exact zeros kept). Then
            // pᴬ + Iᵃc + U u/d = pᴬ + Iᴬ₀c + U₀(u − U₀ᵀc)/d + e_k U_k u/d,
            // and U_k/d = 1/a for the axis component a (d = a U_k).
            let cleared = match (axis_index(&body.joint), arm == 0.0) {
                (Some(k), true) => Some(k),
                _ => None,
            };
            let (art0, u0, along) = match cleared {
                Some(k) => {
                    let mut art0 = ws.art[i];
                    art0.clear_subspace(&body.joint);
                    let mut u0 = u;
                    let mut along = Force::zero();
                    let a_inv = S::from_f64(1.0 / body.joint.axis.0[k]);
                    match body.joint.kind {
                        JointKind::Revolute | JointKind::Continuous => {
                            u0.ang.0[k] = S::zero();
                            along.ang.0[k] = ui * a_inv;
                        }
                        JointKind::Prismatic => {
                            u0.lin.0[k] = S::zero();
                            along.lin.0[k] = ui * a_inv;
                        }
                    }
                    (art0, u0, Some((u, along)))
                }
                None => (ws.art[i], u, None),
            };
            let u0_p = force_to_parent(&body.joint, &x, &u0);
            // The outward pass needs the whole U in the parent's frame.
            ws.u6[i] = match along {
                Some((u, _)) => u0_p + force_to_parent(&body.joint, &x, &(u - u0)),
                None => u0_p,
            };
            // u − U₀ᵀc, and the outward pass's u − Uᵀc = u − U₀ᵀc − U_k c_k.
            let s0 = if moving { ui - ws.a[i].dot(&u0) } else { ui };
            ws.s2[i] = match (moving, along) {
                (true, Some((u, _))) => s0 - ws.a[i].dot(&(u - u0)),
                _ => s0,
            };
            if passes {
                let art_p = with_rotation!(&body.joint, x, |r| art0.expressed_in_parent(&r, &x.trans));
                let g = if moving { ws.f[i] + art0.mul_motion(&ws.a[i]) } else { ws.f[i] };
                let g = match along {
                    Some((_, along)) => g + along,
                    None => g,
                };
                let mut ia_p = art_p.sub_outer(&u0_p, d_inv);
                // The entry the parent's d reads (the diagonal along its
                // axis, if aligned) as e − (v_k v_k)·(1/d): the square does
                // not wait for the division, one multiplication less on the
                // chain from this d to the parent's.
                let parent_joint = body.parent.map(|p| &model.bodies[p].joint);
                if let Some((k, parent_joint)) = parent_joint.and_then(|j| Some((axis_index(j)?, j))) {
                    let (block, old, v) = match parent_joint.kind {
                        JointKind::Revolute | JointKind::Continuous => (&mut ia_p.a, &art_p.a, u0_p.ang.0[k]),
                        JointKind::Prismatic => (&mut ia_p.c, &art_p.c, u0_p.lin.0[k]),
                    };
                    block.0[k] = old.0[k] - v * v * d_inv;
                }
                let pa_p = || force_to_parent(&body.joint, &x, &g) + u0_p.scale(s0 * d_inv);
                pass_on(ws, root.as_deref_mut(), body.parent, &ia_p, pa_p);
            }
            continue;
        }
        ws.u6[i] = u;
        ws.s2[i] = ui;
        if passes {
            let mut ia = ws.art[i].sub_outer(&u, d_inv);
            // Without armature (I − u uᵀ/d)·S = 0 exactly; with it, the
            // product is u·a/d, which the parent must see.
            if arm == 0.0 {
                ia.clear_subspace(&body.joint);
            }
            let pa = if moving {
                ws.f[i] + ia.mul_motion(&ws.a[i]) + u.scale(ui * d_inv)
            } else {
                ws.f[i] + u.scale(ui * d_inv) // c_i = 0 at rest
            };
            let x = ws.x[i];
            let ia_p = with_rotation!(&body.joint, x, |r| ia.expressed_in_parent(&r, &x.trans));
            pass_on(ws, root.as_deref_mut(), body.parent, &ia_p, || force_to_parent(&body.joint, &x, &pa));
        }
    }
}

/// Adds a body's articulated inertia and bias force (computed by `pa` after
/// the inertia is added), in its parent's frame, to its parent's (or to the
/// moving root's).
#[inline(always)]
fn pass_on<S: Scalar>(
    ws: &mut Workspace<S>,
    root: Option<&mut RootArticulated<S>>,
    parent: Option<usize>,
    ia: &ArticulatedInertia<S>,
    pa: impl FnOnce() -> Force<S>,
) {
    match (parent, root) {
        (Some(p), _) => {
            ws.art[p] = ws.art[p].add(ia);
            ws.f[p] += pa();
        }
        (None, Some(root)) => {
            root.inertia = root.inertia.add(ia);
            root.bias += pa();
        }
        (None, None) => {}
    }
}

/// The outward pass of [`aba_impl`]: q̈ and the bodies' accelerations from
/// the root's classic acceleration `a0` (ω̇; the acceleration of its origin,
/// gravity as −g); `distributed` as for [`inward`].
#[inline(always)]
pub(crate) fn outward<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    a0: &Motion<S>,
    qdd: &mut [S],
    distributed: bool,
) {
    for (i, body) in model.bodies.iter().enumerate() {
        let a_parent = match body.parent {
            Some(p) => ws.a[p],
            None => *a0,
        };
        let a = motion_to_child(&body.joint, &ws.x[i], &a_parent) + ws.a[i];
        let qddi = if distributed {
            // Uᵀ(X a_p + c) = (XᵀU)ᵀ a_p + Uᵀc, with u − Uᵀc from the
            // inward pass: q̈ no longer waits for the transform of a_p.
            (ws.s2[i] - a_parent.dot(&ws.u6[i])) * ws.s1[i]
        } else {
            (ws.s2[i] - a.dot(&ws.u6[i])) * ws.s1[i]
        };
        qdd[i] = qddi;
        ws.a[i] = a;
        add_motion(&body.joint, &mut ws.a[i], qddi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::TipWrench;
    use crate::model::{Inertial, JointDescription, RobotBuilder};

    /// A tree with every case of the distributed arm: general and
    /// axis-aligned (non-unit) revolute and prismatic joints, turned
    /// placements, two children on one body, a leaf on the root body.
    fn mixed_tree() -> Model {
        let body = |m: f64, c: [f64; 3]| Some(Inertial::new(m, c, [0.03, 0.02, 0.025, 0.004, -0.003, 0.002]));
        RobotBuilder::new("mixed")
            .link("base", None)
            .link("l1", body(2.0, [0.1, 0.0, 0.2]))
            .link("l2", body(1.5, [0.0, 0.3, -0.1]))
            .link("l3", body(0.8, [0.05, -0.02, 0.1]))
            .link("l4", body(0.6, [-0.1, 0.04, 0.0]))
            .link("l5", body(0.4, [0.02, 0.01, 0.03]))
            .link("l6", body(0.3, [0.0, 0.0, 0.05]))
            .joint(JointDescription::revolute("j1", "base", "l1", [0.0, 0.0, 1.0]).origin([0.0, 0.0, 0.3], [0.0; 3]))
            .joint(
                JointDescription::revolute("j2", "l1", "l2", [0.3, -0.5, 0.8])
                    .origin([0.1, 0.2, 0.3], [0.4, -0.2, 1.1]),
            )
            .joint(
                JointDescription::prismatic("j3", "l2", "l3", [0.0, -2.0, 0.0])
                    .origin([0.0, 0.4, 0.0], [1.3, 0.0, 0.3]),
            )
            .joint(
                JointDescription::continuous("j4", "l3", "l4", [2.0, 0.0, 0.0])
                    .origin([0.2, 0.0, 0.1], [0.0, 0.7, 0.0]),
            )
            .joint(
                JointDescription::prismatic("j5", "l2", "l5", [0.6, 0.0, 0.8])
                    .origin([0.0, -0.1, 0.2], [0.2, 0.0, 0.0]),
            )
            .joint(
                JointDescription::revolute("j6", "l1", "l6", [0.0, 1.0, 0.0]).origin([-0.1, 0.0, 0.1], [0.0, 0.0, 0.5]),
            )
            .build()
            .unwrap()
    }

    fn bundled(name: &str) -> Model {
        Model::from_urdf_file(format!("{}/robots/{name}.urdf", env!("CARGO_MANIFEST_DIR"))).unwrap()
    }

    /// The distributed arm (what traced code runs) and the compact one give
    /// the same q̈ on f64, with and without velocities, tip wrenches and
    /// armature, to rounding.
    #[test]
    fn distributed_arm_matches_compact_arm() {
        for model in [mixed_tree(), bundled("panda"), bundled("ur5")] {
            let n = model.dof();
            let mut ws = Workspace::<f64>::new(&model);
            let val = |k: usize, scale: f64| scale * (0.37 * k as f64 + 0.2).sin();
            let q: Vec<f64> = (0..n).map(|k| val(k, 2.0)).collect();
            let qd: Vec<f64> = (0..n).map(|k| val(k + 11, 1.5)).collect();
            let tau: Vec<f64> = (0..n).map(|k| val(k + 23, 10.0)).collect();
            let armature: Vec<f64> = (0..n).map(|k| if k % 2 == 0 { 0.05 * (k + 1) as f64 } else { 0.0 }).collect();
            let g = Vec3([0.0, 0.0, -9.81]);
            let last = model.frames.len() - 1;
            let tips = [TipWrench { frame: last, wrench: Force::new(Vec3([0.3, -0.2, 0.5]), Vec3([4.0, -1.0, 2.5])) }];
            /// (q̇, armature, gravity, tip wrenches)
            type Case<'a> = (Option<&'a [f64]>, Option<&'a [f64]>, Option<&'a Vec3<f64>>, &'a [TipWrench<f64>]);
            let cases: [Case; 3] = [
                (Some(&qd), None, Some(&g), &tips),
                (Some(&qd), Some(&armature), Some(&g), &[]),
                (None, None, None, &[]),
            ];
            for (case, (qd, arm, g, tips)) in cases.into_iter().enumerate() {
                let loads = Loads::new(g, tips, &[]).with_armature(arm);
                let (mut compact, mut distributed) = (vec![0.0; n], vec![0.0; n]);
                aba_impl::<f64, false>(&model, &mut ws, &q, qd, &tau, loads, &[], &mut compact);
                aba_impl::<f64, true>(&model, &mut ws, &q, qd, &tau, loads, &[], &mut distributed);
                let scale = compact.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!(scale > 1e-3, "{} case {case}: q̈ is not trivial", model.name);
                for k in 0..n {
                    assert!(
                        (compact[k] - distributed[k]).abs() <= 1e-12 * scale,
                        "{} case {case} q̈[{k}]: {} vs {}",
                        model.name,
                        compact[k],
                        distributed[k]
                    );
                }
            }
        }
    }
}
