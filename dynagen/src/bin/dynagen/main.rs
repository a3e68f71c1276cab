//! `dynagen`: the command-line face of the dynagen crate.
//!
//! One module per subcommand; each has an `Args` struct (its clap
//! arguments) and a `run(&args) -> Result<Output, CliError>` that returns
//! what goes to stdout and the warnings for stderr. `main` parses, runs, prints, and turns an error into one
//! line on stderr and a non-zero exit status. Adding a subcommand is: a
//! module, a variant of [`Command`], and an arm in [`run`].

mod error;
mod eval;
mod generate;
mod inspect;
mod json;
mod ops;
mod report;
mod robot_source;
mod states;

use clap::{Parser, Subcommand};
use error::{CliError, Output};
use std::io::Write;
use std::process::ExitCode;

/// A dynamics compiler for robots: inspect a robot, evaluate its dynamics,
/// generate specialised Rust for it and count its operations.
///
/// Every subcommand takes a URDF file; without one it uses the bundled
/// UR5 (Universal Robots UR5 with the Modern Robotics inertias).
#[derive(Parser, Debug)]
#[command(name = "dynagen", version, about, long_about, after_help = EXIT_STATUS)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

const EXIT_STATUS: &str = "\
Exit status: 0 success; 1 bad input (file, URDF, state, option value), with one
line on stderr naming the file and the item (for `report`: the workspace, cargo,
or the report's own failure); 2 bad command line.";

#[derive(Subcommand, Debug)]
enum Command {
    /// Show a robot as dynagen sees it: the tree of bodies, the joint order,
    /// masses and centres of mass, the frames, and every validation warning.
    Inspect(inspect::Args),
    /// Run the generic solver on a list of states read from JSON: inverse
    /// dynamics, mass matrix, bias and gravity torques, forward dynamics.
    Eval(eval::Args),
    /// Write specialised Rust for a robot: one module of unrolled dynamics
    /// (to stdout, or to a file with -o); each function's operation count
    /// goes to stderr.
    Generate(generate::Args),
    /// Count the operations of each generated function beside those of the
    /// generic recursion (the same algorithm run on a counting scalar).
    Ops(ops::Args),
    /// Measure every way dynagen computes the dynamics — generic and generated,
    /// f64 and f32, two forward dynamics — for speed and for accuracy against
    /// a double-double reference, on the bundled robots: writes docs/report.md
    /// and its plots (with --quick, a temporary folder). Runs `cargo run --release -p dynagen-report` in the
    /// dynagen workspace this binary was built from (DYNAGEN_WORKSPACE names
    /// another).
    Report(report::Args),
}

fn run(command: Command) -> Result<Output, CliError> {
    match command {
        Command::Inspect(args) => inspect::run(&args),
        Command::Eval(args) => eval::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Ops(args) => ops::run(&args),
        Command::Report(args) => report::run(&args),
    }
}

fn main() -> ExitCode {
    // A panic is a bug in dynagen, never the user's fault: say so on one
    // line, without a backtrace.
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
        eprintln!("error: internal error (a bug in dynagen, please report it): {}{at}", one_line(&msg));
    }));

    let cli = Cli::parse();
    match run(cli.command) {
        Ok(out) => {
            for w in &out.warnings {
                eprintln!("warning: {}", one_line(w));
            }
            for n in &out.notes {
                eprintln!("{n}");
            }
            let mut stdout = std::io::stdout().lock();
            match stdout.write_all(out.stdout.as_bytes()).and_then(|()| stdout.flush()) {
                Ok(()) => ExitCode::SUCCESS,
                // `dynagen inspect | head`: the reader left; not an error.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: cannot write to stdout: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Err(e) => {
            eprintln!("error: {}", one_line(&e.message));
            ExitCode::from(e.status)
        }
    }
}

/// Joins the lines of a message (some parser errors span several).
fn one_line(s: &str) -> String {
    s.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join(" ")
}
