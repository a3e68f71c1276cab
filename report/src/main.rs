//! `dynagen-report`: measures every way dynagen computes the dynamics — how
//! fast and how accurate against the double-double reference — and writes
//! docs/report.md with its SVG plots. `dynagen report` runs this.
//!
//! ```text
//! cargo run --release -p dynagen-report [-- --out DIR] [--quick]
//! ```
//!
//! A full run writes into the workspace's `docs/`; a quick run (a smoke test,
//! too few samples to publish) writes into a temporary folder unless `--out`
//! names one, so that it never replaces the committed report.

mod plot;
mod report;
mod work_precision;

mod derivatives;
mod error_vs_time;

use report::Report;
use std::path::{Path, PathBuf};

fn main() {
    let mut args = std::env::args().skip(1);
    let mut out: Option<PathBuf> = None;
    let mut quick = false;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--out" => match args.next() {
                Some(dir) => out = Some(dir.into()),
                None => fail("--out needs a directory"),
            },
            "--quick" => quick = true,
            "-h" | "--help" => {
                println!("usage: dynagen-report [--out DIR] [--quick]\n  writes DIR/report.md and DIR/report/*.svg (DIR defaults to the workspace's docs/,\n  and with --quick to {})", quick_dir(&std::env::temp_dir()).display());
                return;
            }
            other => fail(&format!("unknown argument `{other}` (try --help)")),
        }
    }
    let out = out_dir(out, quick, &dynagen_tests::workspace_root().join("docs"), &std::env::temp_dir());
    let mut report = match Report::new(&out, quick) {
        Ok(r) => r,
        Err(e) => fail(&e),
    };
    // The sections, in the order the report shows them.
    error_vs_time::run(&mut report);
    derivatives::run(&mut report);
    work_precision::run(&mut report);
    if let Err(e) = report.finish() {
        fail(&e);
    }
}

/// Where the report goes: `--out DIR` when given; otherwise `docs` (the
/// workspace's docs/, the committed report) for a full run, and a folder in
/// `temp` for a quick one, whose numbers are not for publication.
fn out_dir(out: Option<PathBuf>, quick: bool, docs: &Path, temp: &Path) -> PathBuf {
    match out {
        Some(dir) => dir,
        None if quick => quick_dir(temp),
        None => docs.to_path_buf(),
    }
}

/// The folder of a quick run without `--out`.
fn quick_dir(temp: &Path) -> PathBuf {
    temp.join("dynagen-report-quick")
}

fn fail(message: &str) -> ! {
    eprintln!("dynagen-report: {message}");
    std::process::exit(1);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quick_run_does_not_write_the_committed_report_unless_asked() {
        let (docs, temp) = (Path::new("/ws/docs"), Path::new("/tmp"));
        assert_eq!(out_dir(None, false, docs, temp), docs);
        let quick = out_dir(None, true, docs, temp);
        assert!(quick.starts_with(temp) && !quick.starts_with(docs), "{}", quick.display());
        // Asked for by name, any folder (docs/ too) is used as given.
        assert_eq!(out_dir(Some(docs.to_path_buf()), true, docs, temp), docs);
        assert_eq!(out_dir(Some("mine".into()), false, docs, temp), Path::new("mine"));
    }
}
