//! ∂τ/∂q and ∂τ/∂q̇ of the recursive Newton-Euler algorithm by an
//! analytical recursion (the shape of Carpentier & Mansard, RSS 2018, and of
//! Singh, Russell & Wensing, RA-L 2022), written in body coordinates: one
//! forward pass, one backward pass, and for each joint i a walk up its
//! ancestors j. O(n·d) work for a tree of depth d, where the derivatives
//! have that many non-zero entries.
//!
//! With S_i the joint's motion subspace, v, a the spatial velocity and
//! acceleration (the base's acceleration −g), Ṡ_i = v_λ(i) × S_i,
//! Ψ̈_i = a_λ(i) × S_i + v_λ(i) × Ṡ_i, and over the subtree of i the
//! composite inertia Iᶜ, its rate İᶜ = Σ (v ×* I − I v×) (an inertia of zero
//! mass), momentum hᶜ = Σ I v and net wrench F, the vectors
//!
//! - t₁ = Iᶜ S,  t₄ = İᶜ S − S ×* hᶜ,
//! - t₂ = 2 Iᶜ Ṡ + İᶜ S + S ×* hᶜ,  t₃ = S ×* F + Iᶜ Ψ̈ + İᶜ Ṡ + Ṡ ×* hᶜ
//!
//! give, for j an ancestor of i or i itself (the formulas agree at j = i):
//! ∂τᵢ/∂qⱼ = t₁ᵢ·Ψ̈ⱼ + t₄ᵢ·Ṡⱼ, ∂τᵢ/∂q̇ⱼ = 2 t₁ᵢ·Ṡⱼ + t₄ᵢ·Sⱼ, ∂τⱼ/∂qᵢ = Sⱼ·t₃ᵢ
//! and ∂τⱼ/∂q̇ᵢ = Sⱼ·t₂ᵢ; every other entry is zero. (A perturbation of qⱼ
//! moves the subtree of j rigidly about Sⱼ, except for the parts of v and a
//! that come from above j: those give Ṡⱼ and Ψ̈ⱼ; the rigid part cancels in
//! Sᵢᵀ F. The B(I, v) of Singh et al. is ½(İ + (Iv)×̄*), kept as İ and h:
//! 15 numbers instead of 36.) The four t vectors are carried up the chain
//! by the joints' force transforms, so each dot product is taken in joint
//! j's own frame, where Sⱼ is an axis and Ṡⱼ has four non-zero entries.
//! On the way, t₁ gives the mass matrix's entries Sⱼ·t₁ᵢ (the CRBA's).
//!
//! Tip wrenches fixed in their frames and payloads enter as in the RNEA (a
//! wrench turning with its body, an inertia added to its body's, or to a
//! floating base's), held constant; the armature does not depend on q or q̇.
//! The model's constants are read as the other algorithms read them
//! (`inertia_in`, `placement_in`), exact for a double-double scalar.
//!
//! A floating base is one more ancestor of every joint, with six
//! coordinates: the tangent of the configuration is the base's body twist
//! (q ⊕ δ moves the base to T·exp(δ), as the floating integrator and
//! Pinocchio's free-flyer do), and everything is in the base's frame, so
//! Sᵦ = 1 (six unit twists) and the vectors t above, carried one step more,
//! give the base's rows (t₃, t₂ themselves) and columns. The base's Ψ̇ is
//! zero (the world does not move), its Ψ̈ₖ = (0; eₖ × gᵦ) with gᵦ = Rᵀg
//! (turning the base turns gravity in its frame; moving it changes nothing)
//! and its q̇ column k reads t₁·(vᵦ × eₖ) + t₄·eₖ (Singh et al.'s Ψ̇ + Ṡ of a
//! multi-degree joint); the 6×6 block of the base is Iᶜᵦ Ψ̈ₖ and
//! Iᶜᵦ(vᵦ × eₖ) + İᶜᵦ eₖ + eₖ ×* hᶜᵦ over the whole robot.

use super::floating::{base_inertia, base_motion, quaternion_rotation};
use super::joint::{add_motion, joint_transform, motion, project};
use super::joint::{cross_motion, force_to_parent, inertia_times_subspace, inertia_to_parent, motion_to_child};
use super::Loads;
use crate::model::Model;
use crate::spatial::{Force, Inertia, Motion, Sym3, Transform, Vec3};
use crate::Scalar;

/// Scratch for [`rnea_derivatives`], allocated once per model.
#[derive(Clone, Debug)]
pub struct RneaDerivativeWorkspace<S> {
    /// Pose of each body in its parent's frame.
    x: Vec<Transform<S>>,
    /// Spatial velocity and acceleration of each body, in its frame.
    v: Vec<Motion<S>>,
    a: Vec<Motion<S>>,
    /// Ṡ and Ψ̈ of each joint, in its body's frame.
    sdot: Vec<Motion<S>>,
    psidd: Vec<Motion<S>>,
    /// Over each subtree, in the body's frame: Iᶜ, İᶜ, hᶜ and F.
    ic: Vec<Inertia<S>>,
    idot: Vec<Inertia<S>>,
    hc: Vec<Force<S>>,
    f: Vec<Force<S>>,
    /// A floating base's Iᶜ, İᶜ, hᶜ and F (the whole robot's).
    base: (Inertia<S>, Inertia<S>, Force<S>, Force<S>),
}

impl<S: Scalar> RneaDerivativeWorkspace<S> {
    /// Scratch for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.dof();
        RneaDerivativeWorkspace {
            x: vec![Transform::identity(); n],
            v: vec![Motion::zero(); n],
            a: vec![Motion::zero(); n],
            sdot: vec![Motion::zero(); n],
            psidd: vec![Motion::zero(); n],
            ic: vec![Inertia::zero(); n],
            idot: vec![Inertia::zero(); n],
            hc: vec![Force::zero(); n],
            f: vec![Force::zero(); n],
            base: (Inertia::zero(), Inertia::zero(), Force::zero(), Force::zero()),
        }
    }
}

/// İ = v ×* I − I v×, the rate of change of a rigid body's spatial inertia
/// `i` (in a frame fixed at the instant) as it moves with twist `v`: an
/// inertia of zero mass, ḣ = ω × h + m ν and Ī̇ = [ω×]Ī − Ī[ω×] + 2(h·ν)1 −
/// (ν hᵀ + h νᵀ).
#[inline(always)]
pub(crate) fn inertia_rate<S: Scalar>(i: &Inertia<S>, v: &Motion<S>) -> Inertia<S> {
    let (w, nu) = (&v.ang, &v.lin);
    let m = i.ibar.to_mat();
    // [ω×]Ī column by column; [ω×]Ī − Ī[ω×] is it plus its transpose.
    let c = [w.cross(&m.col(0)), w.cross(&m.col(1)), w.cross(&m.col(2))];
    let x = |r: usize, k: usize| c[k].0[r];
    let rot = Sym3([
        x(0, 0) + x(0, 0),
        x(1, 1) + x(1, 1),
        x(2, 2) + x(2, 2),
        x(0, 1) + x(1, 0),
        x(0, 2) + x(2, 0),
        x(1, 2) + x(2, 1),
    ]);
    Inertia { mass: S::zero(), h: w.cross(&i.h) + nu.scale(i.mass), ibar: rot + Sym3::cross_shift(&i.h, nu) }
}

/// The unit twist `e_k` (angular first).
#[inline(always)]
fn unit<S: Scalar>(k: usize) -> Motion<S> {
    let mut e = [S::zero(); 6];
    e[k] = S::one();
    Motion::from_array(e)
}

/// ∂τ/∂q and ∂τ/∂q̇ (row-major NV×NV, `[i * nv + j] = ∂τᵢ/∂xⱼ`) of
/// [`rnea`](super::rnea::rnea) at `[q, q̇, q̈]` under `loads` (gravity, tip
/// wrenches and payloads held constant), and the mass matrix into `mass`
/// if given (with the armature). On a floating base the configuration's
/// tangent is the base's body twist (see the module documentation).
///
/// # Panics
/// If a slice does not fit the model (q: NQ, the others NV, NV×NV), or the
/// model has mimic joints.
pub fn rnea_derivatives<S: Scalar>(
    model: &Model,
    ws: &mut RneaDerivativeWorkspace<S>,
    [q, qd, qdd]: [&[S]; 3],
    loads: Loads<'_, S>,
    [dtau_dq, dtau_dqd]: [&mut [S]; 2],
    mut mass: Option<&mut [S]>,
) {
    let (n, nv, floating) = (model.dof(), model.nv(), model.is_floating());
    // Joint i's row and column, and its angle's place in q.
    let (off, qoff) = if floating { (6, 7) } else { (0, 0) };
    assert!(
        q.len() == model.nq() && qd.len() == nv && qdd.len() == nv,
        "rnea_derivatives: q must have NQ entries, q̇ and q̈ NV"
    );
    assert!(
        dtau_dq.len() == nv * nv && dtau_dqd.len() == nv * nv && mass.as_ref().is_none_or(|m| m.len() == nv * nv),
        "rnea_derivatives: the matrices must be NV×NV ({nv}×{nv})"
    );
    assert!(
        !model.has_mimic(),
        "rnea_derivatives: a model with mimic joints (derivatives::inverse_dynamics_derivatives takes them)"
    );
    loads.check(n, "rnea_derivatives");
    let bodies = &model.bodies[..n];
    // Gravity in the root's frame, and the root's motion: a fixed base at
    // rest accelerating at −g, a floating one with its twist and its
    // acceleration less g.
    let g = match loads.gravity {
        Some(g) if floating => quaternion_rotation(&q[3..7]).tr_mul_vec(g),
        Some(g) => *g,
        None => Vec3::zero(),
    };
    let world = Motion::new(Vec3::zero(), -g);
    let (v0, a0) = if floating { (base_motion(qd), base_motion(qdd) + world) } else { (Motion::zero(), world) };
    for (i, body) in bodies.iter().enumerate() {
        let joint = &body.joint;
        let x = joint_transform(joint, q[qoff + i]);
        let (vp, ap) = match body.parent {
            Some(p) => (&ws.v[p], &ws.a[p]),
            None => (&v0, &a0),
        };
        let (v_in, a_in) = (motion_to_child(joint, &x, vp), motion_to_child(joint, &x, ap));
        let sdot = cross_motion(joint, &v_in, S::one());
        let psidd = cross_motion(joint, &a_in, S::one()) + v_in.cross_motion(&sdot);
        let mut v = v_in;
        add_motion(joint, &mut v, qd[off + i]);
        let mut a = a_in + sdot.scale(qd[off + i]);
        add_motion(joint, &mut a, qdd[off + i]);
        let mut inertia = body.inertia_in::<S>();
        for p in loads.payloads.iter().filter(|p| p.body == i) {
            inertia = inertia.add(&p.inertia);
        }
        let h = inertia.mul_motion(&v);
        ws.f[i] = inertia.mul_motion(&a) + v.cross_force(&h);
        ws.idot[i] = inertia_rate(&inertia, &v);
        ws.ic[i] = inertia;
        ws.hc[i] = h;
        (ws.x[i], ws.v[i], ws.a[i], ws.sdot[i], ws.psidd[i]) = (x, v, a, sdot, psidd);
    }
    if floating {
        let i0 = base_inertia(model, loads.payloads);
        let h0 = i0.mul_motion(&v0);
        ws.base = (i0, inertia_rate(&i0, &v0), h0, i0.mul_motion(&a0) + v0.cross_force(&h0));
    }
    for tip in loads.tips {
        let frame = &model.frames[tip.frame];
        let w = frame.placement_in::<S>().force_to_parent(&tip.wrench);
        match frame.body {
            Some(b) => ws.f[b] += w,
            None if floating => ws.base.3 += w,
            None => {}
        }
    }
    dtau_dq.fill(S::zero());
    dtau_dqd.fill(S::zero());
    if let Some(m) = mass.as_deref_mut() {
        m.fill(S::zero());
    }
    for i in (0..n).rev() {
        let joint = &bodies[i].joint;
        let r = off + i;
        let s = motion(joint, S::one());
        let (ic, idot, hc, f) = (&ws.ic[i], &ws.idot[i], &ws.hc[i], &ws.f[i]);
        let (sdot, psidd) = (&ws.sdot[i], &ws.psidd[i]);
        let s_hc = s.cross_force(hc);
        let idot_s = inertia_times_subspace(joint, idot);
        let mut t1 = inertia_times_subspace(joint, ic);
        let mut t4 = idot_s - s_hc;
        let ic_sdot = ic.mul_motion(sdot);
        let mut t2 = ic_sdot + ic_sdot + idot_s + s_hc;
        let mut t3 = s.cross_force(f) + ic.mul_motion(psidd) + idot.mul_motion(sdot) + sdot.cross_force(hc);
        dtau_dq[r * nv + r] = project(joint, &t3);
        dtau_dqd[r * nv + r] = project(joint, &t2);
        if let Some(m) = mass.as_deref_mut() {
            m[r * nv + r] = project(joint, &t1);
        }
        let mut k = i;
        // Up the ancestors (and to a floating base's frame).
        while bodies[k].parent.is_some() || floating {
            let (jk, xk) = (&bodies[k].joint, &ws.x[k]);
            [t1, t2, t3, t4] = [t1, t2, t3, t4].map(|t| force_to_parent(jk, xk, &t));
            let Some(j) = bodies[k].parent else { break };
            k = j;
            let (joint_j, c) = (&bodies[j].joint, off + j);
            let sdot_j = &ws.sdot[j];
            let t1_sdot = sdot_j.dot(&t1);
            dtau_dq[r * nv + c] = ws.psidd[j].dot(&t1) + sdot_j.dot(&t4);
            dtau_dqd[r * nv + c] = (t1_sdot + t1_sdot) + project(joint_j, &t4);
            dtau_dq[c * nv + r] = project(joint_j, &t3);
            dtau_dqd[c * nv + r] = project(joint_j, &t2);
            if let Some(m) = mass.as_deref_mut() {
                let mij = project(joint_j, &t1);
                m[r * nv + c] = mij;
                m[c * nv + r] = mij;
            }
        }
        if floating {
            // The t vectors in the base's frame: its columns and rows.
            let (t2a, t3a, t4a, t1a) = (t2.to_array(), t3.to_array(), t4.to_array(), t1.to_array());
            for c in 0..6 {
                let e = unit::<S>(c);
                dtau_dq[r * nv + c] = world.cross_motion(&e).dot(&t1);
                dtau_dqd[r * nv + c] = v0.cross_motion(&e).dot(&t1) + t4a[c];
                dtau_dq[c * nv + r] = t3a[c];
                dtau_dqd[c * nv + r] = t2a[c];
                if let Some(m) = mass.as_deref_mut() {
                    m[r * nv + c] = t1a[c];
                    m[c * nv + r] = t1a[c];
                }
            }
        }
        let x = &ws.x[i];
        let up = (inertia_to_parent(joint, x, &ws.ic[i]), inertia_to_parent(joint, x, &ws.idot[i]));
        let (hc, f) = (force_to_parent(joint, x, &ws.hc[i]), force_to_parent(joint, x, &ws.f[i]));
        let (ic_p, idot_p, hc_p, f_p) = match bodies[i].parent {
            Some(p) => (&mut ws.ic[p], &mut ws.idot[p], &mut ws.hc[p], &mut ws.f[p]),
            None if floating => (&mut ws.base.0, &mut ws.base.1, &mut ws.base.2, &mut ws.base.3),
            None => continue,
        };
        *ic_p = ic_p.add(&up.0);
        *idot_p = idot_p.add(&up.1);
        *hc_p += hc;
        *f_p += f;
    }
    if floating {
        // The base's own 6×6 blocks, over the whole robot.
        let (ic, idot, hc, _) = &ws.base;
        for k in 0..6 {
            let e = unit::<S>(k);
            let dq = ic.mul_motion(&world.cross_motion(&e)).to_array();
            let dqd = (ic.mul_motion(&v0.cross_motion(&e)) + idot.mul_motion(&e) + e.cross_force(hc)).to_array();
            let m = ic.mul_motion(&e).to_array();
            for l in 0..6 {
                dtau_dq[l * nv + k] = dq[l];
                dtau_dqd[l * nv + k] = dqd[l];
                if let Some(mm) = mass.as_deref_mut() {
                    mm[l * nv + k] = m[l];
                }
            }
        }
    }
    if let (Some(m), Some(armature)) = (mass, loads.armature) {
        for (i, &a) in armature.iter().enumerate() {
            if a != 0.0 {
                m[(off + i) * nv + off + i] += S::from_f64(a);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// İ = v ×* I − I v× against the 6×6 products, for a body off its
    /// frame's origin.
    #[test]
    fn the_inertia_rate_is_the_commutator() {
        let i = Inertia::<f64>::from_mass_com_inertia(
            1.7,
            Vec3([0.1, -0.3, 0.25]),
            Sym3([0.3, 0.25, 0.2, 0.01, -0.02, 0.015]),
        );
        let v = Motion::from_array([0.7, -1.3, 0.4, 0.2, 0.9, -0.5]);
        let rate = inertia_rate(&i, &v).to_matrix();
        // column k of v ×* I − I v×, by the spatial products
        for k in 0..6 {
            let mut e = [0.0; 6];
            e[k] = 1.0;
            let ek = Motion::from_array(e);
            let ie = i.mul_motion(&ek);
            let col = (v.cross_force(&ie) - i.mul_motion(&v.cross_motion(&ek))).to_array();
            for r in 0..6 {
                assert!((rate[r][k] - col[r]).abs() < 1e-14, "[{r}][{k}]: {} vs {}", rate[r][k], col[r]);
            }
        }
    }
}
