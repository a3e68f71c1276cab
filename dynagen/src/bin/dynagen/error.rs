//! What a subcommand gives back: its output, or one error line.

/// A subcommand's result: text for stdout, and warnings for stderr (one
/// line each, printed as `warning: …`).
#[derive(Debug, Default)]
pub struct Output {
    /// Everything that goes to stdout.
    pub stdout: String,
    /// Warnings, each naming the file and the item.
    pub warnings: Vec<String>,
    /// Information for stderr, printed as is (after the warnings).
    pub notes: Vec<String>,
}

impl Output {
    /// Output without warnings.
    pub fn text(stdout: String) -> Self {
        Output { stdout, ..Default::default() }
    }
}

/// A failure: printed as `error: {message}` on one line.
#[derive(Debug)]
pub struct CliError {
    /// The message, naming the file and the item (link, joint, JSON field,
    /// state index) it is about.
    pub message: String,
    /// The process exit status.
    pub status: u8,
}

/// The exit status of bad input (a file, a URDF, a state, an option).
pub const STATUS_BAD_INPUT: u8 = 1;

impl CliError {
    /// Bad input: `{source}: {message}`, where `source` is the file (or
    /// option) the problem is in.
    pub fn input(source: impl std::fmt::Display, message: impl std::fmt::Display) -> Self {
        CliError { message: format!("{source}: {message}"), status: STATUS_BAD_INPUT }
    }
}
