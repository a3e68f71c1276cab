//! The derivatives of the dynamics on [`Robot`]: ∂τ/∂(q, q̇), ∂q̈/∂(q, q̇)
//! and M⁻¹, by [`algorithms::derivatives`](crate::algorithms::derivatives)
//! (the analytical recursion), checked and allocation-free in their `_into`
//! forms. Matrices are `[output][input]`: entry (i, j) is ∂yᵢ/∂xⱼ, NV × NV.
//! On a floating base the configuration's columns are in its tangent space:
//! column k < 6 moves the base by exp of the body twist eₖ (angular first),
//! as [`integrate`](crate::algorithms::floating::integrate) does; the
//! translation columns are zero (`docs/architecture.md`, "Derivatives:
//! conventions").

use super::{matrix, Robot};
use crate::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation, RigidBodyOnly};
use crate::algorithms::{crba, Loads};
use crate::model::Model;
use crate::InputError;
use nalgebra::{DMatrix, DVector};

/// A [`Robot`]'s scratch for its derivatives, allocated with it.
#[derive(Clone, Debug)]
pub(crate) struct DerivativeScratch {
    pub(super) dw: DerivativeWorkspace<f64>,
    /// Three row-major n×n results.
    pub(super) rows: [Vec<f64>; 3],
}

impl DerivativeScratch {
    pub(crate) fn new(model: &Model) -> Self {
        let n = model.nv();
        DerivativeScratch {
            dw: DerivativeWorkspace::new(model),
            rows: [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]],
        }
    }
}

/// Copies the row-major `rows` into `m`.
pub(super) fn copy_rows(rows: &[f64], m: &mut DMatrix<f64>) {
    let n = m.nrows();
    for i in 0..n {
        for j in 0..n {
            m[(i, j)] = rows[i * n + j];
        }
    }
}

impl Robot {
    /// (∂τ/∂q, ∂τ/∂q̇) of the inverse dynamics
    /// ([`inverse_dynamics`](Self::inverse_dynamics), tip wrenches held
    /// constant) at (q, q̇, q̈); ∂τ/∂q̈ is the [`mass_matrix`](Self::mass_matrix).
    pub fn inverse_dynamics_derivatives(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>), InputError> {
        let nv = self.model.nv();
        let mut dqd = DMatrix::zeros(nv, nv);
        let dq = matrix(nv, |dq| self.inverse_dynamics_derivatives_into(q, qd, qdd, dq, &mut dqd))?;
        Ok((dq, dqd))
    }
    /// [`inverse_dynamics_derivatives`](Self::inverse_dynamics_derivatives)
    /// into `dtau_dq` and `dtau_dqd` (n×n), allocating nothing.
    pub fn inverse_dynamics_derivatives_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        dtau_dq: &mut DMatrix<f64>,
        dtau_dqd: &mut DMatrix<f64>,
    ) -> Result<(), InputError> {
        self.check()
            .joints(&[("q", q), ("qd", qd), ("qdd", qdd)])?
            .square("dtau_dq", dtau_dq)?
            .square("dtau_dqd", dtau_dqd)?;
        let g = self.model.gravity;
        let DerivativeScratch { dw, rows } = &mut self.deriv;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let d = Dynamics { model: &self.model, loads, torques: &RigidBodyOnly, mass: None };
        let [a, b, _] = rows;
        let state = [q.as_slice(), qd.as_slice(), qdd.as_slice()];
        d::inverse_dynamics_derivatives(&d, dw, state, Formulation::Analytical, [a, b], None);
        copy_rows(a, dtau_dq);
        copy_rows(b, dtau_dqd);
        Ok(())
    }

    /// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) of the forward dynamics
    /// ([`forward_dynamics`](Self::forward_dynamics), tip wrenches held
    /// constant) at (q, q̇, τ); M⁻¹ = ∂q̈/∂τ.
    #[allow(clippy::type_complexity)]
    pub fn forward_dynamics_derivatives(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>), InputError> {
        let n = self.model.nv();
        let (mut dqd, mut minv) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        let dq = matrix(n, |dq| self.forward_dynamics_derivatives_into(q, qd, tau, dq, &mut dqd, &mut minv))?;
        Ok((dq, dqd, minv))
    }
    /// [`forward_dynamics_derivatives`](Self::forward_dynamics_derivatives)
    /// into `dqdd_dq`, `dqdd_dqd` and `minv` (n×n), allocating nothing.
    pub fn forward_dynamics_derivatives_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        dqdd_dq: &mut DMatrix<f64>,
        dqdd_dqd: &mut DMatrix<f64>,
        minv: &mut DMatrix<f64>,
    ) -> Result<(), InputError> {
        self.check()
            .joints(&[("q", q), ("qd", qd), ("tau", tau)])?
            .forward_dynamics()?
            .square("dqdd_dq", dqdd_dq)?
            .square("dqdd_dqd", dqdd_dqd)?
            .square("minv", minv)?;
        let g = self.model.gravity;
        let DerivativeScratch { dw, rows } = &mut self.deriv;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let d = Dynamics { model: &self.model, loads, torques: &RigidBodyOnly, mass: None };
        let [a, b, c] = rows;
        let state = [q.as_slice(), qd.as_slice(), tau.as_slice()];
        d::forward_dynamics_derivatives(&d, dw, state, Formulation::Analytical, [a, b, c]);
        copy_rows(a, dqdd_dq);
        copy_rows(b, dqdd_dqd);
        copy_rows(c, minv);
        Ok(())
    }

    /// M(q)⁻¹, from the sparse LᵀDL factors of the mass matrix (no dense
    /// inversion).
    pub fn mass_matrix_inverse(&mut self, q: &DVector<f64>) -> Result<DMatrix<f64>, InputError> {
        matrix(self.model.nv(), |m| self.mass_matrix_inverse_into(q, m))
    }
    /// [`mass_matrix_inverse`](Self::mass_matrix_inverse) into `minv` (n×n),
    /// allocating nothing.
    pub fn mass_matrix_inverse_into(&mut self, q: &DVector<f64>, minv: &mut DMatrix<f64>) -> Result<(), InputError> {
        self.check().joints(&[("q", q)])?.forward_dynamics()?.square("minv", minv)?;
        let [m, linv, _] = &mut self.deriv.rows;
        crba::crba(&self.model, &mut self.ws, q.as_slice(), Loads::none(), m);
        // M⁻¹ is symmetric: row-major and column-major agree.
        d::mass_matrix_inverse(&self.model, m, linv, minv.as_mut_slice());
        Ok(())
    }
}
