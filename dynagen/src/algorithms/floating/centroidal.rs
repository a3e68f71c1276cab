//! Centroidal quantities of a floating-base robot: its total mass, centre
//! of mass, and centroidal momentum matrix A_G(q) (Orin and Goswami), with
//! which `h_G = A_G q̇` is the whole robot's momentum about its centre of
//! mass in axes parallel to the world's — (angular; linear), our order
//! (Pinocchio's `ccrba` has (linear; angular)).

use super::crba::{carry_to_base, composite_inertia};
use super::{check_sizes, quaternion_rotation};
use crate::algorithms::mimic::{body_column, on_tree, times};
use crate::algorithms::Workspace;
use crate::model::Model;
use crate::spatial::{Force, Vec3};
use crate::Scalar;

/// The mass of the whole robot: the base and every body.
pub fn total_mass(model: &Model) -> f64 {
    model.base_inertia.mass + model.total_mass()
}

/// The centre of mass of the whole robot, in the world frame.
pub fn center_of_mass<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S]) -> Vec3<S> {
    check_sizes(model, "center_of_mass", q.len(), &[]);
    let ic = on_tree(model, ws, q, None, |ws, q, _| composite_inertia(model, ws, q, &[]));
    let c_base = ic.h.scale(S::one() / ic.mass);
    quaternion_rotation(&q[3..7]).mul_vec(&c_base) + Vec3([q[0], q[1], q[2]])
}

/// The centroidal momentum matrix A_G (6×NV, row-major): column k is the
/// momentum (angular about the centre of mass; linear), in world axes, per
/// unit velocity coordinate k.
pub fn centroidal_momentum_matrix<S: Scalar>(model: &Model, ws: &mut Workspace<S>, q: &[S], a: &mut [S]) {
    check_sizes(model, "centroidal_momentum_matrix", q.len(), &[]);
    let nv = model.nv();
    assert!(a.len() == 6 * nv, "centroidal_momentum_matrix: a must be 6×{nv}");
    let ic = on_tree(model, ws, q, None, |ws, q, _| composite_inertia(model, ws, q, &[]));
    let c = ic.h.scale(S::one() / ic.mass);
    let r = quaternion_rotation(&q[3..7]);
    // A momentum about the base origin (base axes) moved to the centre of
    // mass and turned into world axes: (R(m − c × f); R f).
    // (a mimic joint's column added to its master's, times its multiplier)
    a.fill(S::zero());
    let mut put = |k: usize, f: &Force<S>, m: f64| {
        let ang = r.mul_vec(&(f.ang - c.cross(&f.lin)));
        let lin = r.mul_vec(&f.lin);
        for (row, x) in ang.0.into_iter().chain(lin.0).enumerate() {
            let e = &mut a[row * nv + k];
            *e = if model.has_mimic() { *e + times(m, x) } else { x };
        }
    };
    // the base's columns: the composite inertia (symmetric), row by row
    for (k, row) in ic.to_matrix().into_iter().enumerate() {
        put(k, &Force::from_array(row), 1.0);
    }
    for i in 0..model.bodies.len() {
        let f = carry_to_base(model, ws, i, |_, _| {});
        let (col, m) = body_column(model, i);
        put(6 + col, &f, m);
    }
}
