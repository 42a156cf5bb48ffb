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
    /// Where the steps run (see `clump run --device`); a checkpoint of
    /// either device resumes on either.
    #[arg(long, value_enum, default_value_t = crate::device::Device::Cpu)]
    pub device: crate::device::Device,
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
    let device = match args.device {
        crate::device::Device::Cpu => None,
        crate::device::Device::Gpu => match device_for(&args.checkpoint, ranks.size()) {
            Ok(d) => Some(d),
            Err(e) => {
                errln!("error: {e}");
                ranks.fail(2);
                return ExitCode::from(2);
            }
        },
    };
    // split over the ranks before the checkpoint's pieces are read: each
    // rank reads and keeps only its share of the world
    let mut runner = match Runner::resume_split(
        &args.checkpoint,
        scratch.as_deref().or(args.outdir.as_deref()),
        opts,
        ranks.comm(),
    ) {
        Ok(r) => r,
        Err(e) => {
            let code = error_exit(&e);
            ranks.fail(2);
            return code;
        }
    };
    if let Some(d) = device {
        tracing::info!("steps between events on the GPU: {}", d.describe());
        runner.set_device(d);
    }
    let code = drive(runner, args.threads, args.steps, &ranks);
    if let Some(d) = &scratch {
        ranks.finish(d);
    }
    code
}

/// The GPU for resuming `checkpoint`, its settings checked first (nothing
/// is written when they are refused).
fn device_for(
    checkpoint: &std::path::Path,
    ranks: usize,
) -> Result<Box<dyn clump_io::run::device::StepDevice>, String> {
    let bytes = std::fs::read(checkpoint)
        .map_err(|e| format!("cannot read checkpoint {}: {e}", checkpoint.display()))?;
    let (sc, world, _, _) =
        clump_io::run::load_checkpoint_with_id(&bytes, checkpoint).map_err(|e| e.to_string())?;
    crate::device::stepper(&sc, &world, ranks)
}
