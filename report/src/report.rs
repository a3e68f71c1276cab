//! The report being written: its sections, plots and progress messages.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The report under construction.
pub struct Report {
    /// Where report.md goes; plots go into `dir/report/`.
    pub dir: PathBuf,
    /// Fewer states and repetitions (a smoke run; its numbers are not for publication).
    pub quick: bool,
    started: Instant,
    body: String,
}

impl Report {
    /// A report to be written into `dir`.
    pub fn new(dir: &Path, quick: bool) -> Result<Self, String> {
        std::fs::create_dir_all(dir.join("report")).map_err(|e| format!("{}: {e}", dir.join("report").display()))?;
        Ok(Report { dir: dir.to_path_buf(), quick, started: Instant::now(), body: String::new() })
    }

    /// Prints a progress line to stderr, with the time since the start.
    pub fn progress(&self, message: &str) {
        eprintln!("[{:7.1} s] {message}", self.started.elapsed().as_secs_f64());
    }

    /// Appends a section (`## title` and its Markdown body).
    pub fn section(&mut self, title: &str, body: &str) {
        let _ = write!(self.body, "## {title}\n\n{}\n\n", body.trim_end());
    }

    /// The path of a plot file `name` (e.g. `ur5_error_vs_time.svg`), and the
    /// link to it relative to report.md.
    pub fn plot_path(&self, name: &str) -> (PathBuf, String) {
        (self.dir.join("report").join(name), format!("report/{name}"))
    }

    /// Writes report.md.
    pub fn finish(&mut self) -> Result<(), String> {
        let path = self.dir.join("report.md");
        let mut text = String::from("# dynagen: error versus run time\n\n");
        let _ = writeln!(
            text,
            "Made by `cargo run --release -p dynagen-report` (or `dynagen report`){} in {:.0} s.\n",
            if self.quick { " with --quick: a smoke run, too few samples for conclusions" } else { "" },
            self.started.elapsed().as_secs_f64()
        );
        text.push_str(&self.body);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        self.progress(&format!("wrote {}", path.display()));
        Ok(())
    }
}
