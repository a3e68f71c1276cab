//! `dynagen ops`: the operation count of each generated function beside
//! that of the generic recursion ([`dynagen::codegen::generic_op_count`]:
//! the same algorithm run on the [`dynagen::Counting`] scalar, every model
//! constant used as a number at run time).

use crate::error::{CliError, Output};
use crate::generate::cli_error;
use crate::robot_source::RobotSource;
use dynagen::codegen::{generic_op_count, Builder};
use std::fmt::Write;
use std::path::PathBuf;

/// Arguments of `dynagen ops`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The robot's URDF file (default: the bundled UR5).
    #[arg(value_name = "ROBOT.urdf")]
    pub robot: Option<PathBuf>,
}

/// Runs `dynagen ops`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let source = RobotSource::from_arg(args.robot.as_deref());
    let model = source.load()?;
    let module = Builder::new().model(model.clone()).generate_module().map_err(|e| cli_error(e, &source))?;
    let mut o = String::new();
    let _ = writeln!(o, "robot \"{}\" from {source}: {} joints", model.name, model.dof());
    let _ = writeln!(
        o,
        "operations per call (+ - * / sqrt sin_cos; negations apart, in the last two columns): generated vs the generic recursion"
    );
    let _ = writeln!(
        o,
        "{:<32} {:>10} {:>10} {:>7}   {:>13} {:>11}",
        "function", "generated", "generic", "ratio", "generated neg", "generic neg"
    );
    for f in &module.functions {
        let generic = generic_op_count(&model, f.kind);
        let (g, r) = (f.op_count.arithmetic(), generic.arithmetic());
        let _ = writeln!(
            o,
            "{:<32} {:>10} {:>10} {:>6.2}x   {:>13} {:>11}",
            f.kind.label(),
            g,
            r,
            r as f64 / g.max(1) as f64,
            f.op_count.neg,
            generic.neg
        );
    }
    let _ = writeln!(o, "\nbreakdown (generated | generic):");
    for f in &module.functions {
        let _ = writeln!(
            o,
            "  {}:\n    {}\n    {}\n    body with sines and cosines given: {}, {}",
            f.kind.label(),
            f.op_count,
            generic_op_count(&model, f.kind),
            f.sin_cos_inputs.function.op_count(),
            f.sin_cos_inputs.function.critical_path()
        );
    }
    Ok(Output { stdout: o, warnings: source.warnings(&model), notes: Vec::new() })
}
