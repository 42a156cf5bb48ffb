//! `clump validate [--quick] [-o DIR]`: runs the validation suite
//! (`clump-validate`) and writes `report.md` with PNG plots into `DIR`.
//! Exit status 0 when every case passes, 1 when any fails, 2 when the
//! output folder cannot be created or written.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clump_validate::{report, run_suite, Selection};

/// Arguments of `clump validate`.
#[derive(Debug, Clone, clap::Args)]
pub struct ValidateArgs {
    /// Run only the cheap subset (what CI runs, seconds instead of minutes).
    #[arg(long)]
    pub quick: bool,
    /// Output folder for `report.md` and the PNG plots.
    #[arg(short = 'o', long = "out", default_value = "validation")]
    pub out: PathBuf,
}

/// Runs the suite and writes the report.
pub fn run(a: &ValidateArgs) -> ExitCode {
    if let Err(e) = std::fs::create_dir_all(&a.out) {
        errln!("error: cannot create {}: {e}", a.out.display());
        return ExitCode::from(2);
    }
    let t0 = Instant::now();
    let sel = if a.quick {
        Selection::Quick
    } else {
        Selection::Full
    };
    let suite = run_suite(sel, &a.out);
    let secs = t0.elapsed().as_secs_f64();
    let cmd = if a.quick {
        "clump validate --quick"
    } else {
        "clump validate"
    };
    let header = vec![
        format!("Command: `{cmd} -o {}`", a.out.display()),
        format!(
            "Wall time: {secs:.1} s on {} thread(s) (rayon)",
            rayon::current_num_threads()
        ),
        format!("clump {}", env!("CARGO_PKG_VERSION")),
    ];
    if let Err(e) = report::write(&a.out, &suite, &header) {
        errln!(
            "error: cannot write {}: {e}",
            a.out.join("report.md").display()
        );
        return ExitCode::from(2);
    }
    let fails = suite.failures();
    outln!(
        "{} passed, {} failed ({secs:.1} s); report: {}",
        suite.len() - fails,
        fails,
        a.out.join("report.md").display()
    );
    for c in suite
        .groups
        .iter()
        .flat_map(|g| &g.cases)
        .filter(|c| !c.pass)
    {
        outln!(
            "FAIL: {}: expected {}, measured {}",
            c.name,
            c.expected,
            c.measured
        );
    }
    if fails == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
