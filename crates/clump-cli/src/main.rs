//! The `clump` command-line program.
//!
//! Exit status: 0 success, 2 bad input (scenario, checkpoint, arguments),
//! 1 failure while running (also when stdout cannot be written, e.g. a full
//! disk), 130 after SIGINT, 143 after SIGTERM (a checkpoint is written
//! first), 141 when the reader of stdout closed it (`| head`; see [`term`]).

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[macro_use]
mod term;

mod bench;
mod check_words;
mod cmd_check;
mod cmd_post;
mod cmd_resume;
mod cmd_run;
mod cmd_template;
mod cmd_validate;
mod core_latency;
mod device;
mod huge_pages;
mod memory;
mod rank_work;
mod ranks;

/// Large arrays on huge pages (`huge_pages`).
#[global_allocator]
static ALLOCATOR: huge_pages::HugePages = huge_pages::HugePages;

/// Clump: a DEM simulator for rigid clumps of overlapping spheres.
#[derive(Parser)]
#[command(name = "clump", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Commands,
}

#[derive(Subcommand)]
enum Commands {
    /// Run a scenario (TOML): write VTK, thermo, trajectories and checkpoints.
    Run(cmd_run::RunArgs),
    /// Validate a scenario without running it and print derived quantities.
    Check(cmd_check::CheckArgs),
    /// Continue a run from a checkpoint (bit-identically).
    Resume(cmd_resume::ResumeArgs),
    /// Mass properties of a multi-sphere template file (`x y z r` per line).
    Template(cmd_template::TemplateArgs),
    /// Benchmarks (the shared tetra bed; `--case stone-pile`, `stone-bed`), optionally side by side with LIGGGHTS.
    Bench(bench::BenchArgs),
    /// Run the validation suite and write report.md with PNG plots.
    Validate(cmd_validate::ValidateArgs),
    /// Plots, coarse-grained fields and force chains from a run's folder.
    Post(cmd_post::PostArgs),
}

fn main() -> ExitCode {
    huge_pages::init();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match cli.command {
        Commands::Run(a) => cmd_run::run(&a),
        Commands::Check(a) => cmd_check::run(&a),
        Commands::Resume(a) => cmd_resume::run(&a),
        Commands::Validate(a) => cmd_validate::run(&a),
        Commands::Post(a) => cmd_post::run(&a),
        Commands::Bench(a) => match bench::run(&a) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                errln!("error: {e:#}");
                ExitCode::from(1)
            }
        },
        Commands::Template(a) => match cmd_template::run(&a) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                errln!("error: {e:#}");
                ExitCode::from(1)
            }
        },
    }
}
