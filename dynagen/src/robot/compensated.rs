//! Compensated forward dynamics in the numeric API: for states where the
//! torques nearly balance the bias forces at high speed (see
//! [`algorithms::compensated`](crate::algorithms::compensated)).

use super::{vector, InputError, Robot};
use crate::algorithms::Loads;
use nalgebra::DVector;

impl Robot {
    /// Forward dynamics q̈ = M(q)⁻¹(τ − h(q, q̇) − J(q)ᵀF_tip) with h and
    /// τ − h in compensated (double-`f64`) arithmetic, then the
    /// articulated-body algorithm on τ − h rounded once: as accurate as
    /// [`forward_dynamics`](Self::forward_dynamics) in general, and by as
    /// many digits more accurate as τ − h cancels (‖h‖/‖τ − h‖), for a few
    /// times its run time. Under the robot's gravity and tip wrenches.
    ///
    /// ```
    /// use dynagen::Robot;
    /// use nalgebra::dvector;
    /// let urdf = r#"<robot name="r"><link name="base"/>
    ///   <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
    ///     <inertia ixx="0.01" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    ///   <joint name="j" type="continuous"><parent link="base"/><child link="arm"/>
    ///     <axis xyz="0 0 1"/></joint></robot>"#;
    /// let mut robot = Robot::from_urdf_str(urdf).unwrap();
    /// let (q, qd, tau) = (dvector![0.3], dvector![100.0], dvector![1.0]);
    /// let a = robot.forward_dynamics_compensated(&q, &qd, &tau).unwrap();
    /// let b = robot.forward_dynamics(&q, &qd, &tau).unwrap();
    /// // One body about a vertical axis: q̈ = τ / (Izz + m·0.5²) = 1 / 0.6.
    /// assert!((a[0] - 1.0 / 0.6).abs() < 1e-14 && (b[0] - 1.0 / 0.6).abs() < 1e-14);
    /// ```
    pub fn forward_dynamics_compensated(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Result<DVector<f64>, InputError> {
        vector(self.model.nv(), |qdd| self.forward_dynamics_compensated_into(q, qd, tau, qdd))
    }
    /// Makes [`forward_dynamics_compensated`](Self::forward_dynamics_compensated)
    /// take `steps` steps of iterative refinement (0, the default: none):
    /// each computes the residual τ − RNEA(q, q̇, q̈) in compensated
    /// arithmetic and adds the articulated-body algorithm's correction, for
    /// about the time of the first pass again. It pays where M(q) is
    /// ill-conditioned (nearly dependent joints), where the `f64` solve
    /// loses about ε·cond(M) of q̈; measurements in `docs/performance.md`.
    pub fn set_compensated_refinement(&mut self, steps: usize) {
        self.comp.set_refinement(steps);
    }
    /// [`forward_dynamics_compensated`](Self::forward_dynamics_compensated)
    /// into `qdd`, allocating nothing.
    pub fn forward_dynamics_compensated_into(
        &mut self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
        qdd: &mut DVector<f64>,
    ) -> Result<(), InputError> {
        self.check().joints(&[("q", q), ("qd", qd), ("tau", tau)])?.forward_dynamics()?.output("qdd", qdd)?;
        let g = self.model.gravity;
        let loads = Loads::gravity(&g).with_tips(&self.tips);
        let (q, qd, tau) = (q.as_slice(), qd.as_slice(), tau.as_slice());
        self.comp.solve(&self.model, q, qd, tau, loads, qdd.as_mut_slice());
        Ok(())
    }
}
