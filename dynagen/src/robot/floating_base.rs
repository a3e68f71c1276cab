//! What only a floating-base [`Robot`] has: its whole-body (centroidal)
//! quantities, for whole-body controllers.

use super::check::InputError;
use super::Robot;
use crate::algorithms::floating::centroidal;
use nalgebra::{DVector, Matrix6xX, Vector3};

impl Robot {
    fn floating_only(&self) -> Result<(), InputError> {
        match self.model.is_floating() {
            true => Ok(()),
            false => Err(InputError::Unsupported("centroidal quantities are computed for a floating-base robot only")),
        }
    }
    /// The whole robot's mass (kg): the floating base and every body.
    pub fn total_mass(&self) -> Result<f64, InputError> {
        self.floating_only()?;
        Ok(centroidal::total_mass(&self.model))
    }
    /// The whole robot's centre of mass in the world frame (m) at `q` (NQ).
    pub fn center_of_mass(&mut self, q: &DVector<f64>) -> Result<Vector3<f64>, InputError> {
        self.floating_only()?;
        self.check().joints(&[("q", q)])?;
        Ok(Vector3::from(centroidal::center_of_mass(&self.model, &mut self.ws, q.as_slice()).0))
    }
    /// The centroidal momentum matrix A_G(q) (6×NV): `A_G q̇` is the whole
    /// robot's momentum (angular about its centre of mass; linear) in world
    /// axes.
    pub fn centroidal_momentum_matrix(&mut self, q: &DVector<f64>) -> Result<Matrix6xX<f64>, InputError> {
        self.floating_only()?;
        self.check().joints(&[("q", q)])?;
        let mut a = vec![0.0; 6 * self.model.nv()];
        centroidal::centroidal_momentum_matrix(&self.model, &mut self.ws, q.as_slice(), &mut a);
        Ok(Matrix6xX::from_row_slice(&a))
    }
}
