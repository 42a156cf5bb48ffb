//! `clump resume CHECKPOINT [-o OUTDIR] [--threads N] [--steps N]`.

use crate::cmd_run::progress::init_logging;
use crate::cmd_run::{drive, error_exit};
use crate::ranks::Ranks;
use clap::Args;
use clump_io::run::Runner;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `clump resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// Checkpoint file (`checkpoint_<step>.ckpt`); it holds the scenario, so
    /// nothing else is needed.
    pub checkpoint: PathBuf,
    /// Output directory (default: the checkpoint's directory).
    #[arg(short = 'o', long = "out")]
    pub outdir: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Stop when the run reaches this step (total, counted from the start of
    /// the original run).
    #[arg(long)]
    pub steps: Option<u64>,
}

/// Runs `clump resume`.
pub fn run(args: &ResumeArgs) -> ExitCode {
    init_logging();
    let ranks = Ranks::start();
    // rank 0 continues the run's files; the others keep the schedule in a
    // scratch folder
    let scratch = (!ranks.is_root()).then(|| ranks.outdir(std::path::Path::new(".")));
    let mut runner = match Runner::resume(
        &args.checkpoint,
        scratch.as_deref().or(args.outdir.as_deref()),
    ) {
        Ok(r) => r,
        Err(e) => {
            let code = error_exit(&e);
            ranks.fail(2);
            return code;
        }
    };
    let at = runner.world().step;
    if let Some(n) = args.steps.filter(|&n| n <= at) {
        errln!("error: --steps {n} is not after the checkpoint's step {at}; nothing would be run\n  = help: --steps counts from the start of the original run: give a step above {at}");
        return ExitCode::from(2);
    }
    if let Err(e) = ranks.split(&mut runner) {
        errln!("error: {e}");
        ranks.fail(2);
        return ExitCode::from(2);
    }
    let code = drive(runner, args.threads, args.steps, &ranks);
    if let Some(d) = &scratch {
        ranks.finish(d);
    }
    code
}
