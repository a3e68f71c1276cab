//! `report`: it is not implemented in this version. They are defined so that the command's shape
//! is settled and scripts get a clear answer. Each will get its own module,
//! with its own `Args`, when it is implemented: replace its `Command`
//! variant's `unavailable::Args` and its arm in `run`.

use crate::error::{CliError, Output, STATUS_UNAVAILABLE};

/// Arguments of a subcommand that is not available yet: anything is
/// accepted, so that the answer is always the message of [`run`] rather than
/// an argument error.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Ignored: this subcommand is not available yet.
    #[arg(value_name = "ARGS", num_args = 0.., trailing_var_arg = true, allow_hyphen_values = true)]
    pub args: Vec<String>,
}

/// Always fails: the subcommand is not available yet.
pub fn run(name: &str) -> Result<Output, CliError> {
    Err(CliError {
        message: format!(
            "`dynagen {name}` is not available yet in this version ({}): \
             `dynagen inspect`, `eval`, `generate` and `ops` are available",
            env!("CARGO_PKG_VERSION")
        ),
        status: STATUS_UNAVAILABLE,
    })
}
