//! The one place the numeric API checks its arguments: every call of
//! [`Robot`](super::Robot) and [`SceneRobot`](crate::SceneRobot) checks
//! lengths, shapes, finiteness and names here, so that a bad argument is an
//! [`InputError`] naming it (and the joint), never a panic or a NaN result.

use crate::model::Model;
use crate::spatial::{Force, Vec3};
use nalgebra::{DMatrix, DVector, Vector3};

/// A bad argument to a numeric call.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// A vector or matrix of the wrong size.
    #[error("{what} has {got} entries, but the robot has {expected} joints")]
    WrongLength {
        /// The argument (`q`, `qd`, …).
        what: &'static str,
        /// Its length.
        got: usize,
        /// The robot's number of joints.
        expected: usize,
    },
    /// A vector of the wrong size for a floating-base robot.
    #[error("{what} has {got} entries, but the floating-base robot's {kind} has {expected} (n = {n} joints)")]
    WrongLengthFloating {
        /// The argument.
        what: &'static str,
        /// Its length.
        got: usize,
        /// NQ (a configuration) or NV (velocity side).
        expected: usize,
        /// "configuration (NQ = n + 7)" or "velocity side (NV = n + 6)".
        kind: &'static str,
        /// The number of joints.
        n: usize,
    },
    /// A floating base's quaternion far from unit norm (or zero).
    #[error("{what}[3..7], the base's quaternion (x, y, z, w), has norm {norm}, but it must be 1 (within 1e-6)")]
    Quaternion {
        /// The argument (`q`, `q0`).
        what: &'static str,
        /// Its norm.
        norm: f64,
    },
    /// A NaN or infinite entry.
    #[error("{what}[{index}] (joint \"{joint}\") is {value}, not a finite number")]
    NonFinite {
        /// The argument.
        what: &'static str,
        /// The entry.
        index: usize,
        /// The joint it belongs to.
        joint: String,
        /// The value.
        value: f64,
    },
    /// A non-finite gravity or tip wrench.
    #[error("{0} is not finite")]
    NonFiniteLoad(&'static str),
    /// An unknown frame name.
    #[error("no frame named \"{0}\"")]
    UnknownFrame(String),
    /// A matrix of the wrong shape (a trajectory's, or a tip wrench history).
    #[error("{what} is {rows}×{cols}, but it must be {expected_rows}×{expected_cols}")]
    WrongShape {
        /// The argument.
        what: &'static str,
        /// Its number of rows.
        rows: usize,
        /// Its number of columns.
        cols: usize,
        /// The rows it must have.
        expected_rows: usize,
        /// The columns it must have.
        expected_cols: usize,
    },
    /// A bad entry in one row of a trajectory.
    #[error("row {row}: {error}")]
    Row {
        /// The row (time step), from 0.
        row: usize,
        /// What is wrong in it.
        error: Box<InputError>,
    },
    /// What a floating-base robot cannot do yet (or a fixed-base one).
    #[error("{0}")]
    Unsupported(&'static str),
    /// Forward dynamics of a model whose joints are dependent (its mass
    /// matrix is singular at every configuration): undefined.
    #[error(
        "forward dynamics is undefined for this robot: joints {} are dependent (together they move without moving any mass, so the mass matrix is singular at every configuration); inverse dynamics, M, h and g are still computed",
        crate::model::quoted_names(joints)
    )]
    DependentJoints {
        /// The dependent joints.
        joints: Vec<String>,
    },
    /// A bad integration parameter (time step, number of sub-steps).
    #[error("{what} is {value}, but it must be {must}")]
    BadParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        must: &'static str,
    },
}

/// The arguments of one call, checked against the model of the robot
/// called.
#[derive(Clone, Copy)]
pub(crate) struct Check<'a>(pub(crate) &'a Model);

impl Check<'_> {
    /// Each joint-space argument `(name, value)` has one finite entry per
    /// joint; the first that does not is the error.
    pub(crate) fn joints(self, args: &[(&'static str, &DVector<f64>)]) -> Result<Self, InputError> {
        for (what, x) in args {
            self.joint_slice(what, x.as_slice())?;
        }
        Ok(self)
    }
    /// A joint-space argument as a slice (a trajectory's row).
    ///
    /// On a floating-base robot a configuration (`q`, `q0`) has NQ = n + 7
    /// entries and a quaternion of unit norm (within 1e-6), the other
    /// arguments NV = n + 6.
    pub(crate) fn joint_slice(self, what: &'static str, x: &[f64]) -> Result<Self, InputError> {
        let model = self.0;
        let n = model.dof();
        let config = matches!(what, "q" | "q0");
        // the base's leading entries, and their names
        let (base, names): (usize, &[&str]) = match (model.is_floating(), config) {
            (false, _) => (0, &[]),
            (true, true) => (7, &["base position"; 3]),
            (true, false) => (6, &["base (angular)", "base (angular)", "base (angular)", "base (linear)"]),
        };
        if x.len() != n + base {
            return Err(match base {
                0 => InputError::WrongLength { what, got: x.len(), expected: n },
                _ => InputError::WrongLengthFloating {
                    what,
                    got: x.len(),
                    expected: n + base,
                    kind: if config { "configuration (NQ = n + 7)" } else { "velocity side (NV = n + 6)" },
                    n,
                },
            });
        }
        if let Some(index) = x.iter().position(|v| !v.is_finite()) {
            let joint = match index.checked_sub(base) {
                Some(i) => model.bodies[model.joint_body(i)].joint.name.clone(),
                None if config && index >= 3 => "base quaternion".to_string(),
                None => names[index.min(names.len() - 1)].to_string(),
            };
            return Err(InputError::NonFinite { what, index, joint, value: x[index] });
        }
        if base == 7 {
            let norm = x[3..7].iter().map(|v| v * v).sum::<f64>().sqrt();
            if (norm - 1.0).abs() > 1e-6 || norm.is_nan() {
                return Err(InputError::Quaternion { what, norm });
            }
        }
        Ok(self)
    }
    /// The model has a forward dynamics: no dependent joints.
    pub(crate) fn forward_dynamics(self) -> Result<Self, InputError> {
        match self.0.dependent_joints().first() {
            Some(joints) => Err(InputError::DependentJoints { joints: joints.to_vec() }),
            None => Ok(self),
        }
    }
    /// An output vector has one entry per joint (NV on a floating base).
    pub(crate) fn output(self, what: &'static str, out: &DVector<f64>) -> Result<Self, InputError> {
        let n = self.0.nv();
        if out.len() != n {
            return Err(InputError::WrongLength { what, got: out.len(), expected: n });
        }
        Ok(self)
    }
    /// An output matrix is n×n (NV×NV on a floating base).
    pub(crate) fn square(self, what: &'static str, m: &DMatrix<f64>) -> Result<Self, InputError> {
        let n = self.0.nv();
        if m.nrows() != n || m.ncols() != n {
            return Err(InputError::WrongLength { what, got: m.len(), expected: n });
        }
        Ok(self)
    }
    /// The index of the frame named `frame`.
    pub(crate) fn frame(self, frame: &str) -> Result<usize, InputError> {
        self.0.frame_index(frame).ok_or_else(|| InputError::UnknownFrame(frame.to_string()))
    }
}

/// Gravity (m/s²), if finite.
pub(crate) fn gravity(g: &Vector3<f64>) -> Result<Vec3<f64>, InputError> {
    finite("gravity", g.as_slice())?;
    Ok(Vec3([g.x, g.y, g.z]))
}

/// A wrench (m; f), six entries, if finite.
pub(crate) fn wrench(w: &[f64]) -> Result<Force<f64>, InputError> {
    finite("tip wrench", w)?;
    Ok(Force::from_array([w[0], w[1], w[2], w[3], w[4], w[5]]))
}

fn finite(what: &'static str, x: &[f64]) -> Result<(), InputError> {
    match x.iter().all(|v| v.is_finite()) {
        true => Ok(()),
        false => Err(InputError::NonFiniteLoad(what)),
    }
}

/// `m` is `rows`×`cols`.
pub(crate) fn shape(what: &'static str, m: &DMatrix<f64>, rows: usize, cols: usize) -> Result<(), InputError> {
    if m.nrows() != rows || m.ncols() != cols {
        return Err(InputError::WrongShape {
            what,
            rows: m.nrows(),
            cols: m.ncols(),
            expected_rows: rows,
            expected_cols: cols,
        });
    }
    Ok(())
}

/// A time step: finite and positive.
pub(crate) fn dt(dt: f64) -> Result<(), InputError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(InputError::BadParameter { what: "dt", value: dt, must: "a finite number of seconds above zero" });
    }
    Ok(())
}
