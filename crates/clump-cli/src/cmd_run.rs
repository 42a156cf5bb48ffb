//! `clump run SCENARIO [-o OUTDIR] [--threads N] [--steps N]`.

use crate::ranks::Ranks;
use clap::Args;
use clump_io::run::{RunError, RunOptions, RunStatus, Runner};
use clump_io::scenario;
use progress::{init_logging, Display};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize};
use std::sync::Arc;

/// Arguments of `clump run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scenario file (TOML, SI units; see docs/scenario.md).
    pub scenario: PathBuf,
    /// Output directory (default: [output] directory of the scenario, else out/<scenario name>).
    #[arg(short = 'o', long = "out")]
    pub outdir: Option<PathBuf>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Stop when the run reaches this step (counted from the start of the
    /// run), writing a checkpoint; for tests and quick looks.
    #[arg(long)]
    pub steps: Option<u64>,
    /// Delete the files of an earlier run in the output directory first
    /// (without it, such a directory is refused).
    #[arg(long)]
    pub overwrite: bool,
    /// Where the steps run: `gpu` hands the steps between events to the
    /// GPU path (built with the `gpu` feature; `clump check --device gpu`
    /// lists what it runs). Outputs and checkpoints are the CPU path's.
    #[arg(long, value_enum, default_value_t = crate::device::Device::Cpu)]
    pub device: crate::device::Device,
}

/// Exit status for a run error.
pub fn error_exit(e: &RunError) -> ExitCode {
    err!("{e}");
    if !e.to_string().ends_with('\n') {
        errln!();
    }
    ExitCode::from(if e.is_input() { 2 } else { 1 })
}

/// `n`, or the number of cores when `n` is larger (with a warning): more
/// threads than cores only slow a run down (results do not depend on it).
pub fn capped_threads(n: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    if n > cores {
        errln!(
            "warning: --threads {n} is more than the {cores} cores of this machine; using {cores}"
        );
        cores
    } else {
        n
    }
}

/// Registers SIGINT, SIGTERM and SIGHUP (a closed terminal): the first sets
/// the returned flag to the signal number (the run then checkpoints and
/// stops, exit status 128 + the signal); a second one terminates at once.
pub fn install_signals() -> Arc<AtomicUsize> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let flag = Arc::new(AtomicUsize::new(0));
    let seen = Arc::new(AtomicBool::new(false));
    for sig in [SIGINT, SIGTERM, SIGHUP] {
        let _ = signal_hook::flag::register_conditional_shutdown(sig, 128 + sig, Arc::clone(&seen));
        let _ = signal_hook::flag::register(sig, Arc::clone(&seen));
        let _ = signal_hook::flag::register_usize(sig, Arc::clone(&flag), sig as usize);
    }
    flag
}

/// Runs `runner` to the end (or the step limit / a signal) in a pool of
/// `threads`, with progress display and summary; returns the exit status.
pub fn drive(
    mut runner: Runner,
    threads: Option<usize>,
    max_steps: Option<u64>,
    ranks: &Ranks,
) -> ExitCode {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if n == 0 {
            errln!("error: --threads must be at least 1");
            return ExitCode::from(2);
        }
        b = b.num_threads(capped_threads(n));
    }
    let pool = match b.build() {
        Ok(p) => p,
        Err(e) => {
            errln!("error: cannot start {threads:?} threads: {e}");
            return ExitCode::from(1);
        }
    };
    let flag = install_signals();
    let total = runner.scenario().total_steps();
    let end_step = max_steps.map_or(total, |m| m.min(total));
    let mut display = Display::new(end_step, runner.world().step, ranks.is_root());
    let interval = display.interval();
    let nthreads = pool.current_num_threads();
    tracing::info!(
        threads = nthreads,
        dt = runner.world().config.dt,
        steps = total,
        "running {} into {}",
        runner.scenario().path.display(),
        runner.outdir().display()
    );
    let result = pool.install(|| {
        let mut cb = |p: &clump_io::run::Progress| display.update(p);
        let opts = RunOptions {
            max_steps,
            interrupt: Some(flag.clone()),
            progress: Some(&mut cb),
            progress_interval: interval,
            threads: nthreads,
        };
        runner.run(opts)
    });
    display.finish();
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            if ranks.size() > 1 {
                err!("rank {} of {}: ", ranks.rank(), ranks.size());
            }
            let code = error_exit(&e);
            ranks.fail(if e.is_input() { 2 } else { 1 });
            return code;
        }
    };
    let rank_lines = crate::rank_work::rank_lines(&mut runner);
    if !ranks.is_root() {
        return match s.status {
            RunStatus::Interrupted(sig) => ExitCode::from((128 + sig).clamp(0, 255) as u8),
            _ => ExitCode::SUCCESS,
        };
    }
    let status = match s.status {
        RunStatus::Completed => "completed",
        RunStatus::StepLimit => "stopped at the --steps limit",
        RunStatus::Interrupted(_) => "interrupted",
    };
    outln!(
        "{status}: steps {} → {} ({} steps, t = {:.6} s), {} bodies, {} spheres, wall time {:.2} s, {:.3e} sphere-steps/s on {} threads",
        s.first_step,
        s.final_step,
        s.steps(),
        s.time,
        s.bodies,
        s.spheres,
        s.wall_time,
        s.throughput(),
        nthreads
    );
    if let Some(p) = runner.world().part_info() {
        let t = p.traffic;
        let steps = t.steps.max(1) as f64;
        let owned = t.local_body_steps.saturating_sub(t.ghost_body_steps).max(1) as f64;
        outln!(
            "ranks: {} (regions by recursive coordinate bisection; halo {:.3e} m); rank 0: halo fraction {:.3} (ghost bodies per owned body), ghost states {:.0} B and {:.2} messages per step, {} neighbour rebuilds ({:.0} B and {:.2} messages each), {} whole-world gathers ({:.0} B each)",
            p.size,
            p.halo,
            t.ghost_body_steps as f64 / owned,
            t.ghost_bytes as f64 / steps,
            t.ghost_messages as f64 / steps,
            t.rebuilds,
            t.migrate_bytes as f64 / t.rebuilds.max(1) as f64,
            t.migrate_messages as f64 / t.rebuilds.max(1) as f64,
            t.gathers,
            t.gather_bytes as f64 / t.gathers.max(1) as f64,
        );
        for line in &rank_lines {
            outln!("{line}");
        }
    }
    report_bodies(&runner);
    outln!("output: {}", runner.outdir().display());
    if let Some(c) = &s.checkpoint {
        if s.status != RunStatus::Completed {
            outln!(
                "checkpoint: {} (continue with `clump resume {}`)",
                c.display(),
                c.display()
            );
        }
    }
    match s.status {
        RunStatus::Interrupted(sig) => ExitCode::from((128 + sig).clamp(0, 255) as u8),
        _ => ExitCode::SUCCESS,
    }
}

/// Prints what became of the bodies asked for (stdout), with a warning on
/// stderr for every insertion that could not place them all.
fn report_bodies(runner: &Runner) {
    for c in runner.insertions() {
        outln!(
            "insert #{} ({}): asked {}, placed {}{}",
            c.insert,
            c.kind,
            c.asked,
            c.placed,
            if c.waiting > 0 {
                format!(", {} not placed (no room in the region)", c.waiting)
            } else {
                String::new()
            }
        );
        if c.waiting > 0 {
            errln!(
                "warning: insert #{} ({}) placed {} of the {} bodies asked for; {} found no room in its region (a larger region, a lower rate or a longer stage helps)",
                c.insert, c.kind, c.placed, c.asked, c.waiting
            );
        }
    }
    let lost = runner.lost_bodies();
    if lost.total() > 0 {
        let causes: Vec<String> = lost
            .by_cause()
            .into_iter()
            .map(|(cause, n)| match cause {
                "not_finite" => format!("{n} with a non-finite position"),
                "removed" => format!("{n} removed by a driver"),
                side => format!("{n} through the {side} side"),
            })
            .collect();
        outln!(
            "lost: {} bodies: {} (a body is lost when its centre crosses a non-periodic side of the domain)",
            lost.total(),
            causes.join(", ")
        );
    }
}

/// Default output directory: the scenario's `[output] directory`, else
/// `out/<scenario file stem>`.
pub fn default_outdir(sc: &scenario::Scenario, path: &Path) -> PathBuf {
    match &sc.output.directory {
        Some(d) => PathBuf::from(d),
        None => Path::new("out").join(path.file_stem().unwrap_or_default()),
    }
}

/// Runs `clump run`.
pub fn run(args: &RunArgs) -> ExitCode {
    init_logging();
    let sc = match scenario::load(&args.scenario) {
        Ok(s) => s,
        Err(e) => {
            err!("{e}");
            return ExitCode::from(2);
        }
    };
    for w in &sc.warnings {
        err!("{w}");
    }
    if !crate::memory::fits(&sc) {
        return ExitCode::from(2);
    }
    let outdir = args
        .outdir
        .clone()
        .unwrap_or_else(|| default_outdir(&sc, &args.scenario));
    let ranks = Ranks::start();
    let device = match args.device {
        crate::device::Device::Cpu => None,
        crate::device::Device::Gpu => match sc
            .build_world()
            .map_err(|e| format!("cannot set up the simulation: {e}"))
            .and_then(|w| crate::device::stepper(&sc, &w, ranks.size()))
        {
            Ok(d) => Some(d),
            Err(e) => {
                errln!("error: {e}");
                ranks.fail(2);
                return ExitCode::from(2);
            }
        },
    };
    let mine = ranks.outdir(&outdir);
    let mut runner = match Runner::new_in(sc, &mine, args.overwrite || !ranks.is_root()) {
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
    if let Some(d) = device {
        tracing::info!("steps between events on the GPU: {}", d.describe());
        runner.set_device(d);
    }
    let code = drive(runner, args.threads, args.steps, &ranks);
    ranks.finish(&mine);
    code
}

/// Logging (tracing) and progress display shared by `run` and `resume`.
pub mod progress {

    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    use std::io::{IsTerminal, Write};
    use std::sync::OnceLock;
    use std::time::{Duration, Instant};

    static BAR: OnceLock<ProgressBar> = OnceLock::new();

    /// A writer that prints log lines above the progress bar (if any).
    struct LogWriter;

    /// Failures to write are ignored: a closed or full stderr must not stop
    /// a run.
    impl Write for LogWriter {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            match BAR.get() {
                Some(pb) if !pb.is_hidden() => {
                    let _ = pb.suspend(|| std::io::stderr().write_all(buf));
                }
                _ => {
                    let _ = std::io::stderr().write_all(buf);
                }
            }
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            let _ = std::io::stderr().flush();
            Ok(())
        }
    }

    /// Installs the tracing subscriber (`RUST_LOG` overrides the default
    /// `info` level for Clump's own messages).
    pub fn init_logging() {
        use tracing_subscriber::EnvFilter;
        let filter = EnvFilter::try_from_default_env()
            .unwrap_or_else(|_| EnvFilter::new("warn,clump_io=info,clump=info,clump_core=info"));
        let _ = tracing_subscriber::fmt()
            .with_env_filter(filter)
            .with_target(false)
            .with_ansi(std::io::stderr().is_terminal())
            .with_writer(|| LogWriter)
            .log_internal_errors(false)
            .try_init();
    }

    /// Progress display: an indicatif bar on a terminal, plain lines otherwise.
    /// The ETA follows the recent rate (see [`RecentRate`]).
    pub struct Display {
        bar: Option<ProgressBar>,
        shown: bool,
        last_line: Instant,
        line_every: Duration,
        rate: RecentRate,
    }

    /// Steps per second over the last few seconds: an exponential average
    /// of the rates between progress reports with a time constant of
    /// [`RecentRate::TAU`], so that the ETA follows a run that slows down
    /// (e.g. while bodies pour in) within seconds.
    #[derive(Debug, Default)]
    pub struct RecentRate {
        rate: Option<f64>,
        last: Option<Instant>,
    }

    impl RecentRate {
        /// Time constant of the average, s.
        pub const TAU: f64 = 1.0;

        /// Adds a rate measured now (steps/s); returns the average.
        pub fn update(&mut self, steps_per_second: f64, now: Instant) -> f64 {
            let r = match (self.rate, self.last) {
                (Some(r), Some(t)) => {
                    let a = 1.0 - (-now.duration_since(t).as_secs_f64() / Self::TAU).exp();
                    r + a * (steps_per_second - r)
                }
                _ => steps_per_second,
            };
            self.rate = Some(r);
            self.last = Some(now);
            r
        }
    }

    /// `left` steps at `rate` steps/s, as `1h02m`, `3m05s` or `12 s`.
    pub fn eta(left: u64, rate: f64) -> String {
        if !(rate > 0.0) {
            return "?".to_string();
        }
        let s = (left as f64 / rate).round();
        if !(s < 1e9) {
            return "?".to_string();
        }
        let s = s as u64;
        match s {
            0..=99 => format!("{s} s"),
            100..=3599 => format!("{}m{:02}s", s / 60, s % 60),
            _ => format!("{}h{:02}m", s / 3600, s / 60 % 60),
        }
    }

    impl Display {
        /// A display for a run ending at `end_step`.
        /// A display; `shown = false` (an MPI rank other than 0) shows nothing.
        pub fn new(end_step: u64, start_step: u64, shown: bool) -> Self {
            if shown && std::io::stderr().is_terminal() {
                let pb = ProgressBar::with_draw_target(
                    Some(end_step),
                    ProgressDrawTarget::stderr_with_hz(4),
                );
                pb.set_style(
                    ProgressStyle::with_template(
                        "{spinner} [{elapsed_precise}] {bar:30.cyan/blue} {msg}",
                    )
                    .unwrap_or_else(|_| ProgressStyle::default_bar())
                    .progress_chars("=> "),
                );
                pb.set_position(start_step);
                pb.reset_eta();
                let _ = BAR.set(pb.clone());
                Display {
                    bar: Some(pb),
                    shown,
                    last_line: Instant::now(),
                    line_every: Duration::from_secs(5),
                    rate: RecentRate::default(),
                }
            } else {
                Display {
                    bar: None,
                    shown,
                    last_line: Instant::now(),
                    line_every: Duration::from_secs(5),
                    rate: RecentRate::default(),
                }
            }
        }

        /// Wall time between progress callbacks the display wants.
        pub fn interval(&self) -> Duration {
            if self.bar.is_some() {
                Duration::from_millis(250)
            } else {
                Duration::from_secs(1)
            }
        }

        /// Shows one progress report.
        pub fn update(&mut self, p: &clump_io::run::Progress) {
            if !self.shown {
                return;
            }
            let rate = self.rate.update(p.steps_per_second, Instant::now());
            let eta = eta(p.end_step.saturating_sub(p.step), rate);
            let msg = format!(
                "t = {:.4}/{:.4} s  step {}/{}  {:.0} steps/s  {} bodies  {} contacts  [{}]",
                p.time,
                p.end_time,
                p.step,
                p.end_step,
                p.steps_per_second,
                p.bodies,
                p.contacts,
                p.stage
            );
            match &self.bar {
                Some(pb) => {
                    pb.set_position(p.step);
                    pb.set_message(format!("{msg} ETA {eta}"));
                }
                None => {
                    if self.last_line.elapsed() >= self.line_every || p.step == p.end_step {
                        self.last_line = Instant::now();
                        let pct = 100.0 * p.step as f64 / p.end_step.max(1) as f64;
                        errln!("progress {pct:5.1}%  {msg}  ETA {eta}");
                    }
                }
            }
        }

        /// Removes the bar.
        pub fn finish(&self) {
            if let Some(pb) = &self.bar {
                pb.finish_and_clear();
            }
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        /// A run slowing from 1000 to 100 steps/s: the excess of the ETA's
        /// rate decays as e^(−t/τ), τ = 1 s, whatever the report interval
        /// (here 0.25 s): after 4 s it is 100 + 900 e^(−4) ≈ 116 steps/s.
        #[test]
        fn eta_follows_a_falling_rate() {
            let t0 = Instant::now();
            let mut r = RecentRate::default();
            let mut k = 0u32;
            let mut at = |r: &mut RecentRate, sps: f64| {
                k += 1;
                r.update(sps, t0 + Duration::from_millis(250 * k as u64))
            };
            for _ in 0..40 {
                at(&mut r, 1000.0);
            }
            let mut last = 0.0;
            for _ in 0..16 {
                last = at(&mut r, 100.0);
            }
            let want = 100.0 + 900.0 * (-4.0f64).exp();
            assert!((last - want).abs() < 1e-9 * want, "{last} vs {want}");
            assert_eq!(eta(1000, 100.0), "10 s");
            assert_eq!(eta(18_500, 100.0), "3m05s");
            assert_eq!(eta(372_000, 100.0), "1h02m");
            assert_eq!(eta(10, 0.0), "?");
        }
    }
}
