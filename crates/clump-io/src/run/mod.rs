//! The run driver: builds the [`World`] from a [`Scenario`], runs its stages,
//! performs the insertions and writes the outputs into an output directory.
//!
//! # Output directory
//! - `spheres.pvd`, `bodies.pvd`, `walls.pvd` and their `*_<step>.vtp` frames
//!   ([`crate::vtk`]);
//! - `thermo.csv` ([`crate::thermo_csv`], with the force and torque on each wall);
//! - `traj_<id>.csv` for `[output.trajectory]` bodies ([`crate::trajectory`]);
//! - `scenario.toml`: a copy of the scenario;
//! - `checkpoint_<step>.ckpt`: periodic checkpoints, one when the run is
//!   interrupted (SIGINT/SIGTERM) and one when a `--steps` limit stops it;
//! - `final_state.json`: every body's state at the end, with the exact f64 bit
//!   patterns (hex), for bit-for-bit comparisons;
//! - `manifest.json`: version, threads, wall time, steps, throughput;
//! - `.clump.lock` and `.clump-run`: the folder lock and the run's id
//!   ([`outdir`]: folders are never shared or mixed).
//!
//! # Determinism and resume
//! The loop has a fixed order per step: stage changes and insertions, then
//! outputs, then (the *checkpoint point*) the engine step. A checkpoint
//! holds the world's dynamic state ([`clump_core::state::WorldState`]), the
//! driver's state ([`DriverState`]: stage, step within the stage, stream
//! inserters with their random generators, next output steps), scaled
//! templates added by insertion, and the scenario text with every file it
//! refers to. Resuming rebuilds the world from that text, restores both
//! states and re-enters the loop at the checkpoint point, so the resumed run
//! repeats the uninterrupted one bit for bit.
#![allow(clippy::manual_is_multiple_of, clippy::result_large_err)]

mod checkpoint;
mod contact_ranks;
pub mod device;
mod error;
mod events;
mod fields_ranks;
mod manifest;
pub mod outdir;
mod outputs;
mod pieces;
mod report;
mod session;
mod stages;
mod traj_ranks;
mod vtk_ranks;

pub use checkpoint::{load_checkpoint, load_checkpoint_with_id, Checkpoint};
pub use error::{RunError, UnstableRun};
pub use manifest::final_state_json;
pub use pieces::PieceRef;
pub use report::InsertionCount;
pub use session::{Tally, Until};

use crate::post;
use crate::scenario::Scenario;
use clump_core::health::{HealthMonitor, Instability};
use clump_core::insert::StreamInserter;
use clump_core::step::run::{Advance, Event, Flow, StepHook, StepReport};
use clump_core::world::World;
use error::rt;
use outputs::{Outputs, Start};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Version string written into manifests and checkpoints.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The driver's own state, saved in checkpoints.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DriverState {
    /// Index of the current stage.
    pub stage: usize,
    /// Steps taken in the current stage.
    pub step_in_stage: u64,
    /// Whether the current stage's start actions (wall changes, packs) ran.
    pub stage_started: bool,
    /// Whether this step's pre-step work (insertion, output) is done.
    pub pre_step_done: bool,
    /// One entry per `[[insert]]`: the stream inserter once its stage began.
    pub streams: Vec<Option<StreamInserter>>,
    /// Next step with VTK output.
    pub next_vtk: u64,
    /// Next step with a thermo row.
    pub next_thermo: u64,
    /// Next step with trajectory rows.
    pub next_trajectory: u64,
    /// Next step with a periodic checkpoint.
    pub next_checkpoint: u64,
    /// Step of the last VTK frame written (for the final frame).
    pub last_vtk: Option<u64>,
    /// Step of the last thermo row written.
    pub last_thermo: Option<u64>,
    /// Bodies inserted so far by each `[[insert]]`.
    pub inserted: Vec<u64>,
    /// The instability check with its kinetic-energy reference (`None`
    /// until the first step; checkpoints of older versions lack it).
    #[serde(default)]
    pub health: Option<HealthMonitor>,
    /// Step at which bodies were last inserted.
    #[serde(default)]
    pub last_insert_step: Option<u64>,
    /// Next step with a contact frame.
    #[serde(default)]
    pub next_contacts: u64,
    /// Step of the last contact frame written.
    #[serde(default)]
    pub last_contacts: Option<u64>,
    /// Next step with coarse-grained fields.
    #[serde(default)]
    pub next_fields: u64,
    /// Step of the last fields written.
    #[serde(default)]
    pub last_fields: Option<u64>,
    /// Next step with a flow.csv row.
    #[serde(default)]
    pub next_flow: u64,
    /// The flow measurement's state.
    #[serde(default)]
    pub flow: crate::post::flow::FlowState,
}
impl DriverState {
    /// The state before the first step of `scenario`.
    pub(crate) fn fresh(scenario: &Scenario) -> Self {
        DriverState {
            stage: 0,
            step_in_stage: 0,
            stage_started: false,
            pre_step_done: false,
            streams: vec![None; scenario.inserts.len()],
            next_vtk: 0,
            next_thermo: 0,
            next_trajectory: 0,
            next_checkpoint: scenario.output.checkpoint.unwrap_or(u64::MAX),
            last_vtk: None,
            last_thermo: None,
            inserted: vec![0; scenario.inserts.len()],
            health: None,
            last_insert_step: None,
            next_contacts: 0,
            last_contacts: None,
            next_fields: 0,
            last_fields: None,
            next_flow: 0,
            flow: Default::default(),
        }
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunStatus {
    /// All stages done.
    Completed,
    /// Stopped at the `--steps` limit (a checkpoint was written).
    StepLimit,
    /// Stopped by a signal (a checkpoint was written); the signal number.
    Interrupted(i32),
}

/// Live progress, passed to the progress callback.
#[derive(Debug, Clone)]
pub struct Progress {
    /// Simulated time, s.
    pub time: f64,
    /// Simulated time at the end of the run (or of the step limit), s.
    pub end_time: f64,
    /// Current step.
    pub step: u64,
    /// Step at which the run will stop.
    pub end_step: u64,
    /// Steps per second of wall time since the last report.
    pub steps_per_second: f64,
    /// Bodies.
    pub bodies: usize,
    /// Spheres.
    pub spheres: usize,
    /// Touching contacts (sphere–sphere + sphere–wall).
    pub contacts: u64,
    /// Current stage name.
    pub stage: String,
}

/// What a resume may do besides continuing the run in its own folder.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ResumeOptions {
    /// The output folder was named by the user (`-o`), so it need not be a
    /// run folder already. Without it, the checkpoint's folder must be one
    /// (`clump resume` never fills an arbitrary folder with a run's files).
    pub outdir_given: bool,
    /// Continue even when the folder's run went past the checkpoint: its
    /// later thermo and trajectory rows, frames and final state are replaced.
    /// Without it, such a resume is refused (nothing is lost silently).
    pub rewind: bool,
    /// The step the resumed run stops at (checked before anything is written).
    pub max_steps: Option<u64>,
}

/// Options of one run.
pub struct RunOptions<'a> {
    /// Stop when the world reaches this step (total, counted from 0).
    pub max_steps: Option<u64>,
    /// Set to a signal number (non-zero) to stop at the next step.
    pub interrupt: Option<Arc<AtomicUsize>>,
    /// Called about every `progress_interval` of wall time.
    pub progress: Option<&'a mut dyn FnMut(&Progress)>,
    /// Wall time between progress reports.
    pub progress_interval: Duration,
    /// Threads in use (for the manifest).
    pub threads: usize,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions {
            max_steps: None,
            interrupt: None,
            progress: None,
            progress_interval: Duration::from_millis(500),
            threads: 1,
        }
    }
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// How it ended.
    pub status: RunStatus,
    /// Step when this invocation started.
    pub first_step: u64,
    /// Step at the end.
    pub final_step: u64,
    /// Simulated time at the end, s.
    pub time: f64,
    /// Wall time, s.
    pub wall_time: f64,
    /// Σ over steps of the number of spheres.
    pub sphere_steps: f64,
    /// Bodies at the end.
    pub bodies: usize,
    /// Spheres at the end.
    pub spheres: usize,
    /// The last checkpoint written, if any.
    pub checkpoint: Option<PathBuf>,
}

impl RunSummary {
    /// Steps taken in this invocation.
    pub fn steps(&self) -> u64 {
        self.final_step - self.first_step
    }

    /// Throughput, sphere-steps per wall second.
    pub fn throughput(&self) -> f64 {
        if self.wall_time > 0.0 {
            self.sphere_steps / self.wall_time
        } else {
            0.0
        }
    }
}
/// When the last progress line was reported.
struct ProgressClock {
    at: Instant,
    step: u64,
}

/// What the runner checks after every step, fused or not: the health of
/// the state (from the step's statistics), the stage's step count, the
/// progress line and the interrupt flag.
struct StepChecks<'a, 'p> {
    health: &'a mut HealthMonitor,
    step_in_stage: &'a mut u64,
    pre_step_done: &'a mut bool,
    stage: &'a str,
    dt: f64,
    /// The caller's side: interrupt, deadline, progress, counters.
    pace: Pace<'a, 'p>,
    /// The instability found, which ended the steps.
    tripped: Option<Instability>,
}

impl StepHook for StepChecks<'_, '_> {
    fn end_of_step(&mut self, r: &StepReport) -> Flow {
        if let Err(inst) = self.health.check_step(r.step, r.time, r.stats) {
            self.tripped = Some(inst);
            return Flow::Stop;
        }
        *self.pace.sphere_steps += r.spheres as f64;
        *self.step_in_stage += 1;
        *self.pre_step_done = false;
        if let Some(cb) = self.pace.progress.as_mut() {
            if r.step % 16 == 0 || r.step == self.pace.end_step {
                let now = Instant::now();
                let el = now.duration_since(self.pace.clock.at);
                if el >= self.pace.interval || r.step == self.pace.end_step {
                    let sps = (r.step - self.pace.clock.step) as f64 / el.as_secs_f64().max(1e-9);
                    self.pace.clock.at = now;
                    self.pace.clock.step = r.step;
                    cb(&Progress {
                        time: r.time,
                        end_time: self.pace.end_step as f64 * self.dt,
                        step: r.step,
                        end_step: self.pace.end_step,
                        steps_per_second: sps,
                        bodies: r.bodies,
                        spheres: r.spheres,
                        contacts: r.stats.pair_contacts + r.stats.wall_contacts,
                        stage: self.stage.to_string(),
                    });
                }
            }
        }
        Flow::Continue
    }

    fn stop_requested(&self) -> bool {
        self.pace
            .interrupt
            .is_some_and(|f| f.load(Ordering::Relaxed) != 0)
            || self.pace.deadline.is_some_and(|d| Instant::now() >= d)
    }
}

/// The signal a step boundary stops for, the same on every rank of a world
/// split over ranks: a signal reaches the ranks one by one, and a rank that
/// stopped on its own flag while another stepped on would leave that one
/// waiting in the step's reduction for ever. `mine` is this process's
/// flag (0: none); a rank without a signal of its own takes SIGTERM when
/// some rank has one, else SIGINT. Without a partition, `mine`.
fn rank_consistent_signal(w: &mut World, mine: usize) -> usize {
    const SIGINT: usize = libc::SIGINT as usize;
    const SIGTERM: usize = libc::SIGTERM as usize;
    let [int, other] = w.any_ranks([mine == SIGINT, mine != 0 && mine != SIGINT]);
    match (mine, other, int) {
        (0, true, _) => SIGTERM,
        (0, false, true) => SIGINT,
        _ => mine,
    }
}

/// What [`Runner::advance_checked`] takes from its caller besides the event.
struct Pace<'a, 'p> {
    interrupt: Option<&'a AtomicUsize>,
    deadline: Option<Instant>,
    progress: Option<&'a mut (dyn FnMut(&Progress) + 'p)>,
    interval: Duration,
    clock: &'a mut ProgressClock,
    end_step: u64,
    sphere_steps: &'a mut f64,
}

/// A simulation ready to run (fresh or resumed).
pub struct Runner {
    scenario: Scenario,
    world: World,
    st: DriverState,
    out: Outputs,
    n_scenario_templates: usize,
    /// The world at this boundary, with the contacts of the step that ended
    /// here, taken before any stage change or insertion (which would make
    /// the records stale); `None` where no contacts were recorded.
    snap: Option<post::frame::Frame>,
    /// The device that takes the steps between events, if any
    /// ([`device::StepDevice`]); `None`: the CPU path takes them all.
    device: Option<Box<dyn device::StepDevice>>,
}

impl Runner {
    /// A fresh run of `scenario` writing into `outdir` (created if missing;
    /// refused when it holds another run's files, see [`outdir`]).
    pub fn new(scenario: Scenario, outdir: &Path) -> Result<Self, RunError> {
        Self::new_in(scenario, outdir, false)
    }

    /// [`Runner::new`]; with `overwrite`, another run's files in `outdir`
    /// are deleted first.
    pub fn new_in(scenario: Scenario, outdir: &Path, overwrite: bool) -> Result<Self, RunError> {
        let world = scenario
            .build_world()
            .map_err(|e| RunError::InputMessage(format!("cannot set up the simulation: {e}")))?;
        let out = Outputs::open(&scenario, outdir, Start::Fresh { overwrite })?;
        let st = DriverState::fresh(&scenario);
        Ok(Runner::assemble(scenario, world, st, out))
    }

    /// Resumes from a checkpoint file. Outputs go to `outdir`, by default the
    /// directory of the checkpoint, which may lie past the checkpoint (its
    /// later rows and frames are then replaced); `clump resume` uses
    /// [`Self::resume_with`], which refuses that unless asked.
    pub fn resume(checkpoint: &Path, outdir: Option<&Path>) -> Result<Self, RunError> {
        let opts = ResumeOptions {
            outdir_given: true,
            rewind: true,
            max_steps: None,
        };
        Self::resume_with(checkpoint, outdir, opts)
    }

    /// [`Self::resume`] with the checks of `clump resume` (`opts`), all made
    /// before any file is written.
    pub fn resume_with(
        checkpoint: &Path,
        outdir: Option<&Path>,
        opts: ResumeOptions,
    ) -> Result<Self, RunError> {
        Self::resume_split(checkpoint, outdir, opts, None)
    }

    /// [`Self::resume_with`] with the world split over the ranks of `comm`
    /// (every rank calls it): of a checkpoint in pieces, each rank reads
    /// only the pieces that hold its share of the world and keeps only that
    /// share (`pieces::read_share`).
    pub fn resume_split(
        checkpoint: &Path,
        outdir: Option<&Path>,
        opts: ResumeOptions,
        comm: Option<Box<dyn clump_core::partition::Comm>>,
    ) -> Result<Self, RunError> {
        let bytes = std::fs::read(checkpoint).map_err(|e| {
            RunError::InputMessage(format!(
                "cannot read checkpoint {}: {e}",
                checkpoint.display()
            ))
        })?;
        let (scenario, mut world, driver, run_id, pending) =
            checkpoint::load_manifest(&bytes, checkpoint)?;
        drop(bytes);
        if let Some(c) = comm {
            world.partition(c);
        }
        if let Some(p) = pending {
            pieces::read_share(&mut world, &p)?;
        }
        let at = world.step;
        if let Some(n) = opts.max_steps.filter(|&n| n <= at) {
            return Err(RunError::InputMessage(format!(
                "--steps {n} is not after the checkpoint's step {at}; nothing would be run (no file was touched)\n  = help: --steps counts from the start of the original run: give a step above {at}"
            )));
        }
        let opts = ResumeOptions {
            outdir_given: opts.outdir_given || outdir.is_some(),
            ..opts
        };
        let outdir = match outdir {
            Some(d) => d.to_path_buf(),
            None => checkpoint
                .parent()
                .map(Path::to_path_buf)
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or_else(|| PathBuf::from(".")),
        };
        let (step, time) = (world.step, world.time);
        let start = Start::Resume {
            checkpoint,
            step,
            time,
            run_id: run_id.as_deref(),
            opts,
        };
        let out = Outputs::open(&scenario, &outdir, start)?;
        tracing::info!(step, time, "resumed from {}", checkpoint.display());
        Ok(Runner::assemble(scenario, world, driver, out))
    }

    /// The runner of `scenario` in `world`, at driver state `st`, writing to `out`.
    fn assemble(scenario: Scenario, world: World, st: DriverState, out: Outputs) -> Self {
        let n = scenario.templates.len();
        Runner {
            scenario,
            world,
            st,
            out,
            n_scenario_templates: n,
            snap: None,
            device: None,
        }
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Splits the world over the ranks of `comm` (every rank runs the same
    /// scenario; see `clump_core::partition`).
    pub fn partition(&mut self, comm: Box<dyn clump_core::partition::Comm>) {
        self.world.partition(comm);
    }

    /// Hands the steps between events, but the last before each event,
    /// to `device` ([`device::StepDevice`]).
    pub fn set_device(&mut self, device: Box<dyn device::StepDevice>) {
        self.device = Some(device);
    }

    /// The output directory.
    pub fn outdir(&self) -> &Path {
        &self.out.dir
    }

    /// Runs until all stages are done, the step limit is reached or an
    /// interrupt is requested. The steps between two events (a stage
    /// change, an insertion, output or a checkpoint due, the step limit) run
    /// fused in the engine's run loop ([`World::advance`]); the health check
    /// and the progress line see every step's statistics.
    pub fn run(&mut self, mut opts: RunOptions) -> Result<RunSummary, RunError> {
        let t_start = Instant::now();
        let first_step = self.world.step;
        let total = self.scenario.total_steps();
        let end_step = opts.max_steps.map_or(total, |m| m.min(total));
        let mut sphere_steps = 0.0;
        let mut clock = ProgressClock {
            at: Instant::now(),
            step: self.world.step,
        };
        let status = loop {
            // --- at a step boundary
            if !self.st.pre_step_done {
                let finished = match self.pre_step() {
                    Ok(f) => f,
                    Err(RunError::Runtime(m)) => return Err(self.output_failed(m)),
                    Err(e) => return Err(e),
                };
                self.st.pre_step_done = true;
                if finished {
                    break RunStatus::Completed;
                }
            }
            if let Some(flag) = &opts.interrupt {
                let sig = rank_consistent_signal(&mut self.world, flag.load(Ordering::Relaxed));
                if sig != 0 {
                    tracing::warn!(
                        signal = sig,
                        step = self.world.step,
                        "interrupted; writing a checkpoint"
                    );
                    self.write_checkpoint()?;
                    break RunStatus::Interrupted(sig as i32);
                }
            }
            if opts.max_steps.is_some_and(|m| self.world.step >= m) {
                self.write_checkpoint()?;
                break RunStatus::StepLimit;
            }
            self.periodic_checkpoint()?;
            // --- the steps to the next event
            let event = self.next_event(opts.max_steps);
            // over MPI ranks, an event with no boundary work but a
            // checkpoint or a VTK frame (written in pieces) keeps the world
            // split
            let split = event.step < self.next_whole_step();
            self.world.keep_split_at_next_event(split);
            let pace = Pace {
                interrupt: opts.interrupt.as_deref(),
                deadline: None,
                progress: opts.progress.as_deref_mut(),
                interval: opts.progress_interval,
                clock: &mut clock,
                end_step,
                sphere_steps: &mut sphere_steps,
            };
            if let Some(inst) = self.advance_checked(event, pace)?.1 {
                let partial = self.summary(RunStatus::Completed, first_step, t_start, sphere_steps);
                return Err(self.unstable(inst, &partial, opts.threads));
            }
        };
        let wall_time = t_start.elapsed().as_secs_f64();
        // over MPI ranks the world stays split at the end (each rank holds
        // its part): final_state.json is gathered to rank 0 only
        let (bodies, spheres) = manifest::whole_counts(&mut self.world);
        if let Some(f) = &self.out.fields {
            f.finish()
                .map_err(rt("cannot write the time-averaged fields"))?;
        }
        self.write_final_state()
            .map_err(rt("cannot write final_state.json"))?;
        let summary = RunSummary {
            status,
            first_step,
            final_step: self.world.step,
            time: self.world.time,
            wall_time,
            sphere_steps,
            bodies,
            spheres,
            checkpoint: self.out.last_checkpoint.clone(),
        };
        self.write_manifest(&summary, opts.threads)
            .map_err(rt("cannot write manifest.json"))?;
        Ok(summary)
    }

    /// An output of this step could not be written (e.g. a full disk): the
    /// stage changes and insertions of the step are done (outputs come
    /// last), so the state is whole. A checkpoint is written if there is
    /// room, and the message says whether, and how to continue.
    fn output_failed(&mut self, message: String) -> RunError {
        self.st.pre_step_done = true;
        let step = self.world.step;
        let next = match self.write_checkpoint() {
            Ok(p) => format!(
                "a checkpoint of step {step} was written: {} (after freeing space, `clump resume {}` continues; outputs of step {step} may be missing)",
                p.display(),
                p.display()
            ),
            Err(e) => format!("there was no room for a checkpoint of step {step} either ({e})"),
        };
        RunError::Runtime(format!("{message}\n  {next}"))
    }

    /// The periodic checkpoint, when one is due at this boundary (a run
    /// without an output folder keeps the schedule and writes nothing).
    fn periodic_checkpoint(&mut self) -> Result<(), RunError> {
        if self.world.step >= self.st.next_checkpoint {
            let every = self.scenario.output.checkpoint.unwrap_or(u64::MAX);
            self.st.next_checkpoint = self.world.step.saturating_add(every);
            if !self.out.is_detached() {
                self.write_checkpoint()?;
            }
        }
        Ok(())
    }

    /// Steps up to `event` in the engine's run loop ([`World::advance`])
    /// under the runner's per-step checks (health, stage step count,
    /// progress, interrupt); returns where it stopped and the instability
    /// that ended it, if any.
    fn advance_checked(
        &mut self,
        event: Event,
        pace: Pace,
    ) -> Result<(Advance, Option<Instability>), RunError> {
        let limits = self.scenario.stability;
        let mut hook = StepChecks {
            health: self
                .st
                .health
                .get_or_insert_with(|| HealthMonitor::new(limits)),
            step_in_stage: &mut self.st.step_in_stage,
            pre_step_done: &mut self.st.pre_step_done,
            stage: self
                .scenario
                .stages
                .get(self.st.stage)
                .map_or("", |s| s.name.as_str()),
            dt: self.world.config.dt,
            pace,
            tripped: None,
        };
        let at = self.world.step;
        // the step before every event makes the exact sums of its thermo row
        self.world.request_exact_sums(Some(event.step));
        if let Some(dev) = self.device.as_mut() {
            // the steps before the event's last on the device
            let to = event.step - 1;
            if to > at {
                let done = dev
                    .advance(&mut self.world, to, &mut || hook.stop_requested())
                    .map_err(|e| RunError::Runtime(format!("step {at}: device: {e}")))?;
                *hook.step_in_stage += done;
                *hook.pace.sphere_steps += done as f64 * self.world.spheres().len() as f64;
                if done > 0 {
                    *hook.pre_step_done = false;
                }
                if self.world.step < to {
                    return Ok((Advance::Interrupted, None));
                }
            }
        }
        let at = self.world.step;
        let how = self
            .world
            .advance(event, &mut hook)
            .map_err(rt(&format!("step {at}")))?;
        Ok((how, hook.tripped.take()))
    }
}
