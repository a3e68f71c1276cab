//! The numerical sections of the report: simulation work-precision (each
//! integrator on an ordinary and a stiff scene), the compensated forward
//! dynamics (digits won, time), and the stiff and extreme suite's bounds.

mod compensated;
mod simulation;
mod stiff_suite;

use crate::report::Report;

/// Writes the sections.
pub fn run(report: &mut Report) {
    simulation::run(report);
    compensated::run(report);
    stiff_suite::run(report);
}
