//! The derivatives of a scene's dynamics on [`SceneRobot`]: its armature,
//! friction, constant payloads and gravity enter them; its run-time inputs
//! (gravity, tip wrench, payloads) are held constant. The same algorithm
//! ([`algorithms::derivatives`](crate::algorithms::derivatives)) on the
//! scene's dynamics as the generated functions are traced from. On a
//! floating base the matrices are NV × NV, the configuration's columns in
//! the tangent space of the base's body twist (as [`Robot`](crate::Robot)'s).

use super::{SceneInputError, SceneInputs, SceneRobot, Uses};
use crate::algorithms::derivatives::{self as d, DerivativeWorkspace, Dynamics, Formulation};
use crate::algorithms::Loads;
use crate::robot::derivatives::DerivativeScratch;
use crate::scene::{dynamics, SceneModel};
use nalgebra::{DMatrix, DVector};

impl SceneRobot {
    /// (∂τ/∂q, ∂τ/∂q̇) of [`inverse_dynamics_with`](Self::inverse_dynamics_with)
    /// at (q, q̇, q̈), the inputs held constant; `[output][input]`.
    pub fn inverse_dynamics_derivatives_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>), SceneInputError> {
        self.derivatives([("q", q), ("qd", qd), ("qdd", qdd)], inputs, |d, dw, state, [a, b, _]| {
            d::inverse_dynamics_derivatives(d, dw, state, Formulation::Analytical, [a, b], None)
        })?;
        let (n, [a, b, _]) = (self.nv(), &self.deriv.rows);
        Ok((DMatrix::from_row_slice(n, n, a), DMatrix::from_row_slice(n, n, b)))
    }

    /// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) of [`forward_dynamics_with`](Self::forward_dynamics_with)
    /// at (q, q̇, τ), the inputs held constant; `[output][input]`.
    #[allow(clippy::type_complexity)]
    pub fn forward_dynamics_derivatives_with(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>), SceneInputError> {
        self.derivatives([("q", q), ("qd", qd), ("tau", tau)], inputs, |d, dw, state, [a, b, c]| {
            d::forward_dynamics_derivatives(d, dw, state, Formulation::Analytical, [a, b, c])
        })?;
        let (n, [a, b, c]) = (self.nv(), &self.deriv.rows);
        Ok((DMatrix::from_row_slice(n, n, a), DMatrix::from_row_slice(n, n, b), DMatrix::from_row_slice(n, n, c)))
    }

    /// Runs `run` on the scene's dynamics (armature, friction, the gravity
    /// and tip wrench of `inputs` held constant) at the checked state
    /// `named`, into the three row-major n×n scratch matrices.
    fn derivatives(
        &mut self,
        named: [(&'static str, &DVector<f64>); 3],
        inputs: &SceneInputs<'_>,
        run: impl FnOnce(&Dynamics<'_, f64, SceneModel>, &mut DerivativeWorkspace<f64>, [&[f64]; 3], [&mut [f64]; 3]),
    ) -> Result<(), SceneInputError> {
        self.check().joints(&named)?;
        let g = self.prepare(inputs, Uses { gravity: true, tip: true })?;
        let DerivativeScratch { dw, rows } = &mut self.deriv;
        let scene = &self.scene;
        let loads = dynamics::with_armature(scene, Loads::new(g.as_ref(), &self.tips, &[]));
        let d = Dynamics { model: &scene.model, loads, torques: scene, mass: None };
        let [a, b, c] = rows;
        run(&d, dw, named.map(|(_, v)| v.as_slice()), [a, b, c]);
        Ok(())
    }

    /// (M(q) + diag(armature))⁻¹ with the input payloads of `inputs`, from
    /// the sparse LᵀDL factors.
    pub fn mass_matrix_inverse_with(
        &mut self,
        q: &DVector<f64>,
        inputs: &SceneInputs<'_>,
    ) -> Result<DMatrix<f64>, SceneInputError> {
        self.check().joints(&[("q", q)])?;
        let n = self.nv();
        self.prepare(inputs, Uses { gravity: false, tip: false })?;
        let [m, linv, _] = &mut self.deriv.rows;
        dynamics::mass_matrix(&self.scene, &mut self.ws, q.as_slice(), m);
        let mut minv = DMatrix::zeros(n, n);
        d::mass_matrix_inverse(&self.scene.model, m, linv, minv.as_mut_slice());
        Ok(minv)
    }
}
