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
        let quick = if self.quick { " -- --quick" } else { "" };
        let _ = writeln!(
            text,
            "Made by `cargo run --release -p dynagen-report{quick}` (or `dynagen report{}`) in the workspace root, \
             in {:.0} s{}.\n",
            if self.quick { " --quick" } else { "" },
            self.started.elapsed().as_secs_f64(),
            if self.quick { ": a smoke run (--quick), too few samples for conclusions" } else { "" },
        );
        let _ = writeln!(text, "{}\n", machine());
        text.push_str(&self.body);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        self.progress(&format!("wrote {}", path.display()));
        Ok(())
    }
}

/// What the report ran on: CPU, cores, OS, compiler, build profile, and the
/// commit when the workspace is a git checkout.
pub fn machine() -> String {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let cpu = cpuinfo
        .lines()
        .find_map(|l| l.strip_prefix("model name").and_then(|r| r.split_once(':')).map(|(_, v)| v.trim().to_string()))
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let os_release = std::fs::read_to_string("/etc/os-release").unwrap_or_default();
    let distro = os_release
        .lines()
        .find_map(|l| l.strip_prefix("PRETTY_NAME=").map(|v| v.trim_matches('"').to_string()))
        .unwrap_or_else(|| std::env::consts::OS.to_string());
    let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease").map(|k| format!(", Linux {}", k.trim()));
    let avx2 = if cfg!(target_feature = "avx2") { "with AVX2" } else { "baseline target features (no AVX2)" };
    let commit = std::process::Command::new("git")
        .args(["rev-parse", "--short", "HEAD"])
        .current_dir(dynagen_tests::workspace_root())
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|c| {
            format!("; commit {}{}", c.trim(), if uncommitted_changes() { " with uncommitted changes" } else { "" })
        })
        .unwrap_or_default();
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().next().map(|x| format!(" Load average (1 min) when it finished: {x}.")))
        .unwrap_or_default();
    format!(
        "Machine: {cpu}, {cores} logical cores available; {distro}{}; {}, {} profile, {} {avx2}{commit}.{load}",
        kernel.unwrap_or_default(),
        env!("DYNAGEN_REPORT_RUSTC"),
        env!("DYNAGEN_REPORT_PROFILE"),
        std::env::consts::ARCH,
    )
}

/// Whether the workspace's tracked files (docs/, which the report writes,
/// aside) differ from the commit.
fn uncommitted_changes() -> bool {
    std::process::Command::new("git")
        .args(["status", "--porcelain", "--untracked-files=no", "--", ".", ":(exclude)docs"])
        .current_dir(dynagen_tests::workspace_root())
        .output()
        .map(|o| o.status.success() && !o.stdout.is_empty())
        .unwrap_or(false)
}
