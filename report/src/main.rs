//! `dynagen-report`: measures every way dynagen computes the dynamics — how
//! fast and how accurate against the double-double reference — and writes
//! docs/report.md with its SVG plots. `dynagen report` runs this.
//!
//! ```text
//! cargo run --release -p dynagen-report [-- --out DIR] [--quick]
//! ```

mod plot;
mod report;
mod work_precision;

mod error_vs_time;

use report::Report;

fn main() {
    let mut args = std::env::args().skip(1);
    let mut out = dynagen_tests::workspace_root().join("docs");
    let mut quick = false;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--out" => match args.next() {
                Some(dir) => out = dir.into(),
                None => fail("--out needs a directory"),
            },
            "--quick" => quick = true,
            "-h" | "--help" => {
                println!("usage: dynagen-report [--out DIR] [--quick]\n  writes DIR/report.md and DIR/report/*.svg (DIR defaults to the workspace's docs/)");
                return;
            }
            other => fail(&format!("unknown argument `{other}` (try --help)")),
        }
    }
    let mut report = match Report::new(&out, quick) {
        Ok(r) => r,
        Err(e) => fail(&e),
    };
    // The sections, in the order the report shows them.
    error_vs_time::run(&mut report);
    work_precision::run(&mut report);
    if let Err(e) = report.finish() {
        fail(&e);
    }
}

fn fail(message: &str) -> ! {
    eprintln!("dynagen-report: {message}");
    std::process::exit(1);
}
