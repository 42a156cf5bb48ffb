//! `clump resume CHECKPOINT [-o OUTDIR] [--threads N] [--steps N] [--rewind]`.

use crate::cmd_run::progress::init_logging;
use crate::cmd_run::{drive, error_exit};
use crate::ranks::Ranks;
use clap::Args;
use clump_io::run::{ResumeOptions, Runner};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `clump resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// Checkpoint file (`checkpoint_<step>.ckpt`); it holds the scenario, so
    /// nothing else is needed.
    pub checkpoint: PathBuf,
    /// Output directory (default: the checkpoint's directory, which must
    /// then be a run folder).
    #[arg(short = 'o', long = "out")]
    pub outdir: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Stop when the run reaches this step (total, counted from the start of
    /// the original run).
    #[arg(long)]
    pub steps: Option<u64>,
    /// Continue even when the run folder went past the checkpoint (its later
    /// rows, frames, manifest and final state are replaced).
    #[arg(long)]
    pub rewind: bool,
}

/// Runs `clump resume`.
pub fn run(args: &ResumeArgs) -> ExitCode {
    init_logging();
    let ranks = Ranks::start();
    // rank 0 continues the run's files; the others keep the schedule in a
    // scratch folder
    let scratch = (!ranks.is_root()).then(|| ranks.outdir(std::path::Path::new(".")));
    let opts = ResumeOptions {
        outdir_given: scratch.is_some() || args.outdir.is_some(),
        rewind: args.rewind,
        max_steps: args.steps,
    };
    let mut runner = match Runner::resume_with(
        &args.checkpoint,
        scratch.as_deref().or(args.outdir.as_deref()),
        opts,
    ) {
        Ok(r) => r,
        Err(e) => {
            let code = error_exit(&e);
            ranks.fail(2);
            return code;
        }
    };
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
