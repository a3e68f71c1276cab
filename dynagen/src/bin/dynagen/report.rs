//! `dynagen report`: the error-versus-run-time report (docs/report.md and
//! its plots; a `--quick` run writes into a temporary folder unless `--out`
//! says where). The report measures code generated for the bundled robots,
//! which has to be compiled into it, so it is its own program in the
//! workspace (`report/`, package `dynagen-report`); this subcommand runs it
//! with cargo in the dynagen workspace this binary was built from, its
//! output streamed as it runs.

use crate::error::{CliError, Output, STATUS_BAD_INPUT};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable that names another dynagen workspace to run the
/// report in (default: the one this binary was built from).
pub const WORKSPACE_VAR: &str = "DYNAGEN_WORKSPACE";

/// Arguments of `dynagen report`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Fewer states and repetitions: a smoke run (well under a minute once
    /// built), too few samples for conclusions.
    #[arg(long)]
    pub quick: bool,
    /// Where to write report.md and report/*.svg (default: the workspace's
    /// docs/ for a full run; a temporary folder with --quick, so that a smoke
    /// run does not replace the committed report).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// The command a user can run by hand in the workspace.
fn by_hand(args: &Args) -> String {
    let mut extra = String::new();
    if let Some(out) = &args.out {
        extra.push_str(&format!(" --out {}", out.display()));
    }
    if args.quick {
        extra.push_str(" --quick");
    }
    let extra = if extra.is_empty() { String::new() } else { format!(" --{extra}") };
    format!("cargo run --release -p dynagen-report{extra}")
}

/// Runs `dynagen report`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let workspace = std::env::var_os(WORKSPACE_VAR)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join(".."));
    let manifest = workspace.join("report").join("Cargo.toml");
    if !manifest.is_file() {
        return Err(CliError::input(
            workspace.display(),
            format!(
                "no dynagen workspace here (no report/Cargo.toml): the report compiles generated code, so it runs \
                 from dynagen's source; in a checkout of dynagen run `{}`",
                by_hand(args)
            ),
        ));
    }
    let mut report_args: Vec<std::ffi::OsString> = Vec::new();
    if let Some(out) = &args.out {
        // The report runs in the workspace: make DIR the caller's.
        let out = std::env::current_dir().map(|d| d.join(out)).unwrap_or_else(|_| out.clone());
        report_args.push("--out".into());
        report_args.push(out.into());
    }
    if args.quick {
        report_args.push("--quick".into());
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(&cargo)
        .current_dir(&workspace)
        .args(["run", "--release", "-p", "dynagen-report", "--"])
        .args(&report_args)
        .status()
        .map_err(|e| {
            CliError::input(
                Path::new(&cargo).display(),
                format!(
                    "cannot run cargo ({e}): the report needs it; in {} run `{}`",
                    workspace.display(),
                    by_hand(args)
                ),
            )
        })?;
    if !status.success() {
        return Err(CliError {
            message: format!(
                "the report failed ({status}); its messages are above; by hand, in {}: `{}`",
                workspace.display(),
                by_hand(args)
            ),
            status: STATUS_BAD_INPUT,
        });
    }
    Ok(Output::default())
}
