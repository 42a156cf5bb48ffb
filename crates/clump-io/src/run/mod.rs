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

pub mod outdir;
mod report;

pub use report::InsertionCount;

use crate::checkpoint::write_checkpoint;
use crate::scenario::{self, Files, InsertSpec, Scenario, ScenarioError};
use crate::thermo_csv::{ThermoWriter, WallColumns};
use crate::trajectory::TrajectoryWriter;
use crate::vtk::VtkSeries;
use clump_core::health::{HealthMonitor, Instability};
use clump_core::insert::{pack, StreamInserter};
use clump_core::shape::ClumpTemplate;
use clump_core::state::WorldState;
use clump_core::thermo::Thermo;
use clump_core::world::World;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Version string written into manifests and checkpoints.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Why a run failed.
#[derive(Debug)]
pub enum RunError {
    /// Bad input (scenario, checkpoint that does not fit): exit status 2.
    Input(ScenarioError),
    /// Bad input without a scenario location (e.g. an unreadable checkpoint).
    InputMessage(String),
    /// Failure while running (I/O, engine): exit status 1.
    Runtime(String),
    /// The simulation became unstable (NaN/Inf state, excessive overlap,
    /// kinetic-energy blow-up); the message names the step, the bodies, the
    /// likely cause and the last good checkpoint and output. Exit status 1.
    Unstable(Box<UnstableRun>),
}

/// An instability that stopped a run, with what is needed to report it.
#[derive(Debug, Clone)]
pub struct UnstableRun {
    /// What was detected.
    pub instability: Instability,
    /// The likely cause, with a remedy.
    pub cause: String,
    /// Where the time step is set in the scenario (`file:line`, key).
    pub dt_location: String,
    /// The last checkpoint written before the instability (a good state),
    /// with its step.
    pub last_checkpoint: Option<(PathBuf, u64)>,
    /// The output directory.
    pub outdir: PathBuf,
    /// Step of the last thermo row written (a good state).
    pub last_thermo: Option<u64>,
    /// Step of the last VTK frame written (a good state).
    pub last_vtk: Option<u64>,
}

impl fmt::Display for UnstableRun {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.instability;
        writeln!(f, "error: the simulation became unstable {i}")?;
        let ids: Vec<String> = i.bodies().iter().map(|b| b.to_string()).collect();
        if !ids.is_empty() {
            writeln!(f, "  bodies involved: {}", ids.join(", "))?;
        }
        writeln!(f, "  likely cause: {}", self.cause)?;
        writeln!(f, "  time step: {}", self.dt_location)?;
        match &self.last_checkpoint {
            Some((p, step)) => writeln!(
                f,
                "  last good checkpoint: {} (step {step}; `clump resume {}` continues from it)",
                p.display(),
                p.display()
            )?,
            None => writeln!(
                f,
                "  last good checkpoint: none was written (add [output] checkpoint = {{ every_steps = N }})"
            )?,
        }
        let step = |s: Option<u64>| s.map_or_else(|| "none".to_string(), |s| format!("step {s}"));
        writeln!(
            f,
            "  last good output in {}: thermo.csv up to {}, VTK frames up to {}",
            self.outdir.display(),
            step(self.last_thermo),
            step(self.last_vtk)
        )?;
        write!(
            f,
            "  = note: the unstable state was not written: no checkpoint or output was overwritten"
        )
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Input(e) => write!(f, "{e}"),
            RunError::InputMessage(m) => write!(f, "error: {m}"),
            RunError::Runtime(m) => write!(f, "error: {m}"),
            RunError::Unstable(u) => write!(f, "{u}"),
        }
    }
}

impl std::error::Error for RunError {}

impl RunError {
    /// True for bad input (exit status 2).
    pub fn is_input(&self) -> bool {
        !matches!(self, RunError::Runtime(_) | RunError::Unstable(_))
    }
}

fn rt<E: fmt::Display>(what: &str) -> impl FnOnce(E) -> RunError + '_ {
    move |e| RunError::Runtime(format!("{what}: {e}"))
}

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
}

/// Everything in a checkpoint file (stored as JSON inside the binary
/// container of [`crate::checkpoint`], so that tagged enums round-trip; f64
/// values are written in shortest round-trip form and read back exactly).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Checkpoint {
    /// Clump version that wrote it.
    pub version: String,
    /// The scenario file as given when the run started.
    pub scenario_path: String,
    /// The scenario text.
    pub scenario_text: String,
    /// Files the scenario refers to, keyed as written in the scenario.
    pub files: BTreeMap<String, Vec<u8>>,
    /// Output directory of the run.
    pub outdir: String,
    /// Templates added during the run (scaled copies), with their material.
    pub extra_templates: Vec<(ClumpTemplate, u16)>,
    /// The driver state.
    pub driver: DriverState,
    /// The world state.
    pub world: WorldState,
    /// Id of the run (see [`outdir`]; absent in older checkpoints).
    #[serde(default)]
    pub run_id: Option<String>,
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

/// The thermo columns of every wall: a power column for the walls that move
/// at the start or are set moving by a stage.
fn wall_columns(scenario: &Scenario) -> Vec<WallColumns> {
    let moving = |v: DVec3| v != DVec3::ZERO;
    scenario
        .walls
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let staged = scenario.stages.iter().flat_map(|s| &s.walls).any(|c| {
                c.wall == i
                    && (c.velocity.is_some_and(moving) || c.angular_velocity.is_some_and(moving))
            });
            WallColumns {
                name: w.name.clone(),
                power: staged || moving(w.motion.velocity) || moving(w.motion.angular_velocity),
            }
        })
        .collect()
}

/// The world's thermo row with each wall's torque taken about its torque
/// point (`T_P = T_c + (c − P) × F`, world frame), and the power each wall's
/// rigid motion delivers to the particles, `−(F·v + T_c·ω)` (W).
fn wall_thermo(world: &World, torque_points: &[Option<DVec3>]) -> (Thermo, Vec<f64>) {
    let mut t = world.thermo();
    let mut power = Vec::with_capacity(t.wall_loads.len());
    for (i, (l, w)) in t.wall_loads.iter_mut().zip(&world.walls).enumerate() {
        let m = &w.motion;
        power.push(-(l.force.dot(m.velocity) + l.torque.dot(m.angular_velocity)));
        if let Some(p) = torque_points.get(i).copied().flatten() {
            l.torque += (m.center - p).cross(l.force);
        }
    }
    (t, power)
}

struct Outputs {
    dir: PathBuf,
    vtk: Option<VtkSeries>,
    thermo: Option<ThermoWriter>,
    trajectory: Option<TrajectoryWriter>,
    last_checkpoint: Option<PathBuf>,
    run_id: String,
    _lock: outdir::FolderLock,
}

/// A simulation ready to run (fresh or resumed).
pub struct Runner {
    scenario: Scenario,
    world: World,
    st: DriverState,
    out: Outputs,
    n_scenario_templates: usize,
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
        let (lock, run_id) = outdir::prepare_fresh(outdir, overwrite, &scenario.path)?;
        crate::atomic::write_atomic(outdir.join("scenario.toml"), scenario.text.as_bytes())
            .map_err(rt("cannot copy the scenario"))?;
        let o = &scenario.output;
        let wall_columns = wall_columns(&scenario);
        let out = Outputs {
            dir: outdir.to_path_buf(),
            vtk: match o.vtk {
                Some(_) => Some(
                    VtkSeries::new(outdir)
                        .map_err(rt("cannot start VTK output"))?
                        .with_format(o.vtk_format),
                ),
                None => None,
            },
            thermo: match o.thermo {
                Some(_) => Some(
                    ThermoWriter::create_walls(outdir.join("thermo.csv"), &wall_columns)
                        .map_err(rt("cannot create thermo.csv"))?,
                ),
                None => None,
            },
            trajectory: match &o.trajectory {
                Some(t) if !t.bodies.is_empty() => Some(
                    TrajectoryWriter::create(outdir, &t.bodies)
                        .map_err(rt("cannot create trajectory files"))?,
                ),
                _ => None,
            },
            last_checkpoint: None,
            run_id,
            _lock: lock,
        };
        let st = DriverState {
            stage: 0,
            step_in_stage: 0,
            stage_started: false,
            pre_step_done: false,
            streams: vec![None; scenario.inserts.len()],
            next_vtk: 0,
            next_thermo: 0,
            next_trajectory: 0,
            next_checkpoint: o.checkpoint.unwrap_or(u64::MAX),
            last_vtk: None,
            last_thermo: None,
            inserted: vec![0; scenario.inserts.len()],
            health: None,
            last_insert_step: None,
        };
        let n = scenario.templates.len();
        Ok(Runner {
            scenario,
            world,
            st,
            out,
            n_scenario_templates: n,
        })
    }

    /// Resumes from a checkpoint file. Outputs go to `outdir`, by default the
    /// directory of the checkpoint.
    pub fn resume(checkpoint: &Path, outdir: Option<&Path>) -> Result<Self, RunError> {
        let bytes = std::fs::read(checkpoint).map_err(|e| {
            RunError::InputMessage(format!(
                "cannot read checkpoint {}: {e}",
                checkpoint.display()
            ))
        })?;
        let (scenario, world, driver, run_id) = load_checkpoint_with_id(&bytes, checkpoint)?;
        let outdir = match outdir {
            Some(d) => d.to_path_buf(),
            None => checkpoint
                .parent()
                .map(Path::to_path_buf)
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or_else(|| PathBuf::from(".")),
        };
        let (lock, run_id) = outdir::prepare_resume(&outdir, run_id.as_deref(), checkpoint)?;
        crate::atomic::write_atomic(outdir.join("scenario.toml"), scenario.text.as_bytes())
            .map_err(rt("cannot copy the scenario"))?;
        let o = &scenario.output;
        let wall_columns = wall_columns(&scenario);
        let (step, time) = (world.step, world.time);
        let out = Outputs {
            dir: outdir.clone(),
            vtk: match o.vtk {
                Some(_) => Some(
                    VtkSeries::resume(&outdir, time)
                        .map_err(rt("cannot resume VTK output"))?
                        .with_format(o.vtk_format),
                ),
                None => None,
            },
            thermo: match o.thermo {
                Some(_) => Some(
                    ThermoWriter::resume_walls(outdir.join("thermo.csv"), &wall_columns, step)
                        .map_err(rt("cannot resume thermo.csv"))?,
                ),
                None => None,
            },
            trajectory: match &o.trajectory {
                Some(t) if !t.bodies.is_empty() => Some(
                    TrajectoryWriter::resume(&outdir, &t.bodies, time)
                        .map_err(rt("cannot resume trajectory files"))?,
                ),
                _ => None,
            },
            last_checkpoint: Some(checkpoint.to_path_buf()),
            run_id,
            _lock: lock,
        };
        let n = scenario.templates.len();
        tracing::info!(step, time, "resumed from {}", checkpoint.display());
        Ok(Runner {
            scenario,
            world,
            st: driver,
            out,
            n_scenario_templates: n,
        })
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The output directory.
    pub fn outdir(&self) -> &Path {
        &self.out.dir
    }

    /// Runs until all stages are done, the step limit is reached or an
    /// interrupt is requested.
    pub fn run(&mut self, mut opts: RunOptions) -> Result<RunSummary, RunError> {
        let t_start = Instant::now();
        let first_step = self.world.step;
        let total = self.scenario.total_steps();
        let end_step = opts.max_steps.map_or(total, |m| m.min(total));
        let dt = self.world.config.dt;
        let mut sphere_steps = 0.0;
        let mut last_report = Instant::now();
        let mut last_report_step = self.world.step;
        let status = loop {
            if !self.st.pre_step_done {
                let finished = self.pre_step()?;
                self.st.pre_step_done = true;
                if finished {
                    break RunStatus::Completed;
                }
            }
            if let Some(flag) = &opts.interrupt {
                let sig = flag.load(Ordering::Relaxed);
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
            if self.world.step >= self.st.next_checkpoint {
                let every = self.scenario.output.checkpoint.unwrap_or(u64::MAX);
                self.st.next_checkpoint = self.world.step.saturating_add(every);
                self.write_checkpoint()?;
            }
            self.world
                .step()
                .map_err(rt(&format!("step {}", self.world.step)))?;
            let limits = self.scenario.stability;
            let health = self
                .st
                .health
                .get_or_insert_with(|| HealthMonitor::new(limits));
            if let Err(inst) = health.check(&self.world) {
                let partial = RunSummary {
                    status: RunStatus::Completed,
                    first_step,
                    final_step: self.world.step,
                    time: self.world.time,
                    wall_time: t_start.elapsed().as_secs_f64(),
                    sphere_steps,
                    bodies: self.world.bodies.len(),
                    spheres: self.world.spheres().len(),
                    checkpoint: self.out.last_checkpoint.clone(),
                };
                return Err(self.unstable(inst, &partial, opts.threads));
            }
            sphere_steps += self.world.spheres().len() as f64;
            self.st.step_in_stage += 1;
            self.st.pre_step_done = false;
            if let Some(cb) = opts.progress.as_mut() {
                if self.world.step % 16 == 0 || self.world.step == end_step {
                    let now = Instant::now();
                    let el = now.duration_since(last_report);
                    if el >= opts.progress_interval || self.world.step == end_step {
                        let sps = (self.world.step - last_report_step) as f64
                            / el.as_secs_f64().max(1e-9);
                        last_report = now;
                        last_report_step = self.world.step;
                        let p = self.progress(end_step, sps, dt);
                        cb(&p);
                    }
                }
            }
        };
        let wall_time = t_start.elapsed().as_secs_f64();
        self.write_final_state()
            .map_err(rt("cannot write final_state.json"))?;
        let summary = RunSummary {
            status,
            first_step,
            final_step: self.world.step,
            time: self.world.time,
            wall_time,
            sphere_steps,
            bodies: self.world.bodies.len(),
            spheres: self.world.spheres().len(),
            checkpoint: self.out.last_checkpoint.clone(),
        };
        self.write_manifest(&summary, opts.threads)
            .map_err(rt("cannot write manifest.json"))?;
        Ok(summary)
    }

    fn progress(&self, end_step: u64, sps: f64, dt: f64) -> Progress {
        Progress {
            time: self.world.time,
            end_time: end_step as f64 * dt,
            step: self.world.step,
            end_step,
            steps_per_second: sps,
            bodies: self.world.bodies.len(),
            spheres: self.world.spheres().len(),
            contacts: self.world.stats.pair_contacts + self.world.stats.wall_contacts,
            stage: self
                .scenario
                .stages
                .get(self.st.stage)
                .map_or_else(String::new, |s| s.name.clone()),
        }
    }

    /// Stage changes, insertion and output before a step. Returns true when
    /// all stages are done (after writing the final output).
    fn pre_step(&mut self) -> Result<bool, RunError> {
        let stages = &self.scenario.stages;
        while self.st.stage < stages.len() && self.st.step_in_stage >= stages[self.st.stage].steps {
            self.st.stage += 1;
            self.st.step_in_stage = 0;
            self.st.stage_started = false;
        }
        let finished = self.st.stage >= stages.len();
        if !finished {
            if !self.st.stage_started {
                self.begin_stage()?;
                self.st.stage_started = true;
            }
            for (k, s) in self.st.streams.iter_mut().enumerate() {
                if let Some(s) = s {
                    let n = s.insert_due(&mut self.world).map_err(|e| {
                        RunError::Input(self.scenario.insert_error(k, e.to_string()))
                    })?;
                    self.st.inserted[k] += n as u64;
                    if n > 0 {
                        self.st.last_insert_step = Some(self.world.step);
                    }
                }
            }
        }
        self.write_outputs(finished)?;
        Ok(finished)
    }

    fn begin_stage(&mut self) -> Result<(), RunError> {
        let si = self.st.stage;
        let stage = self.scenario.stages[si].clone();
        tracing::info!(stage = %stage.name, step = self.world.step, time = self.world.time, steps = stage.steps, "stage begins");
        if let Some(g) = stage.gravity {
            self.world.config.gravity = g;
        }
        for c in &stage.walls {
            let w = &mut self.world.walls[c.wall];
            if let Some(a) = c.active {
                w.active = a;
            }
            if let Some(v) = c.velocity {
                w.motion.velocity = v;
            }
            if let Some(v) = c.angular_velocity {
                w.motion.angular_velocity = v;
            }
            if let Some(v) = c.center {
                w.motion.center = v;
            }
            if let Some(v) = c.surface_velocity {
                w.motion.surface_velocity = v;
            }
        }
        for k in 0..self.scenario.inserts.len() {
            let ins = &self.scenario.inserts[k];
            if ins.stage != si {
                continue;
            }
            match &ins.kind {
                InsertSpec::File { bodies } => {
                    for b in bodies {
                        self.world.add_body(b).map_err(|e| {
                            RunError::Input(self.scenario.insert_error(k, e.to_string()))
                        })?;
                    }
                    self.st.inserted[k] += bodies.len() as u64;
                    self.st.last_insert_step = Some(self.world.step);
                    tracing::info!(bodies = bodies.len(), "inserted bodies from file");
                }
                InsertSpec::Pack { spec, seed, .. } => {
                    let rep = pack(&mut self.world, spec, *seed).map_err(|e| {
                        RunError::Input(self.scenario.insert_error(k, e.to_string()))
                    })?;
                    self.st.inserted[k] += rep.placed as u64;
                    self.st.last_insert_step = Some(self.world.step);
                    tracing::info!(
                        bodies = rep.placed,
                        volume_fraction = rep.volume_fraction,
                        "packed region"
                    );
                }
                InsertSpec::Stream { spec, seed, .. } => {
                    let s = StreamInserter::new(spec.clone(), &self.world, *seed).map_err(|e| {
                        RunError::Input(self.scenario.insert_error(k, e.to_string()))
                    })?;
                    self.st.streams[k] = Some(s);
                }
            }
        }
        Ok(())
    }

    fn write_outputs(&mut self, finished: bool) -> Result<(), RunError> {
        let step = self.world.step;
        let o = self.scenario.output.clone();
        if let (Some(every), Some(vtk)) = (o.vtk, self.out.vtk.as_mut()) {
            if step >= self.st.next_vtk || (finished && self.st.last_vtk != Some(step)) {
                vtk.write_frame(&self.world, step)
                    .map_err(rt("cannot write VTK output"))?;
                self.st.last_vtk = Some(step);
                self.st.next_vtk = step + every;
            }
        }
        if let (Some(every), Some(th)) = (o.thermo, self.out.thermo.as_mut()) {
            if step >= self.st.next_thermo || (finished && self.st.last_thermo != Some(step)) {
                let (thermo, power) = wall_thermo(&self.world, &self.scenario.torque_points);
                th.write_row(&thermo, &power)
                    .map_err(rt("cannot write thermo.csv"))?;
                self.st.last_thermo = Some(step);
                self.st.next_thermo = step + every;
            }
        }
        if let (Some(t), Some(tw)) = (&o.trajectory, self.out.trajectory.as_mut()) {
            if step >= self.st.next_trajectory {
                tw.write(&self.world)
                    .map_err(rt("cannot write trajectories"))?;
                self.st.next_trajectory = step + t.every;
            }
        }
        Ok(())
    }

    /// Writes a checkpoint of the current state into the output directory
    /// (`checkpoint_<step>.ckpt`); returns its path.
    pub fn write_checkpoint(&mut self) -> Result<PathBuf, RunError> {
        let world = self
            .world
            .save_state()
            .map_err(rt("cannot capture the state"))?;
        let extra: Vec<(ClumpTemplate, u16)> = (self.n_scenario_templates
            ..self.world.templates.len())
            .map(|i| {
                (
                    self.world.templates[i].clone(),
                    self.world.template_material[i],
                )
            })
            .collect();
        let ck = Checkpoint {
            version: VERSION.to_string(),
            scenario_path: self.scenario.path.display().to_string(),
            scenario_text: self.scenario.text.clone(),
            files: self.scenario.files.clone(),
            outdir: self.out.dir.display().to_string(),
            extra_templates: extra,
            driver: self.st.clone(),
            world,
            run_id: Some(self.out.run_id.clone()),
        };
        let json = serde_json::to_string(&ck).map_err(rt("cannot encode the checkpoint"))?;
        let path = self
            .out
            .dir
            .join(format!("checkpoint_{:09}.ckpt", self.world.step));
        write_checkpoint(&path, &json, self.scenario.fingerprint())
            .map_err(rt("cannot write the checkpoint"))?;
        tracing::info!(
            step = self.world.step,
            "checkpoint written to {}",
            path.display()
        );
        self.out.last_checkpoint = Some(path.clone());
        Ok(path)
    }

    /// Stops a run at an instability: keeps every output and checkpoint as
    /// they are (the thermo and trajectory files are flushed row by row; the
    /// bad state is not written anywhere), records the status in the
    /// manifest and returns the report.
    fn unstable(&mut self, inst: Instability, summary: &RunSummary, threads: usize) -> RunError {
        use crate::scenario::Seg::K;
        let since = self
            .st
            .last_insert_step
            .map(|s| self.world.step.saturating_sub(s));
        let cause = self.world.diagnose(&inst, since);
        tracing::error!(step = inst.step, "unstable: {inst}");
        let src = crate::scenario::Source::new(&self.scenario.path, self.scenario.text.clone());
        let path = self.scenario.path.display();
        let dt = self.world.config.dt;
        let at = |k: &str| {
            let p = [K("simulation"), K(k)];
            src.has(&p).then(|| src.error_at(&p, "").line()).flatten()
        };
        let dt_location = match (at("dt"), at("dt_fraction")) {
            (Some(l), _) => format!("dt = {dt:e} s is set at {path}:{l} ([simulation] dt)"),
            (None, Some(l)) => {
                format!("dt = {dt:e} s follows from {path}:{l} ([simulation] dt_fraction)")
            }
            _ => format!("dt = {dt:e} s (dt = \"auto\"; set [simulation] dt in {path})"),
        };
        let last_checkpoint = self.out.last_checkpoint.clone().map(|p| {
            let step = p
                .file_stem()
                .and_then(|s| s.to_str())
                .and_then(|s| s.strip_prefix("checkpoint_"))
                .and_then(|s| s.parse::<u64>().ok())
                .unwrap_or(0);
            (p, step)
        });
        let report = UnstableRun {
            instability: inst,
            cause,
            dt_location,
            last_checkpoint,
            outdir: self.out.dir.clone(),
            last_thermo: self.st.last_thermo,
            last_vtk: self.st.last_vtk,
        };
        let status = format!("unstable at step {}", report.instability.step);
        if let Err(e) = self.write_manifest_status(summary, threads, &status) {
            tracing::warn!("cannot write manifest.json: {e}");
        }
        RunError::Unstable(Box::new(report))
    }

    fn write_final_state(&self) -> std::io::Result<()> {
        let json = final_state_json(&self.world);
        crate::atomic::write_atomic(self.out.dir.join("final_state.json"), json.as_bytes())
    }

    fn write_manifest(&self, s: &RunSummary, threads: usize) -> std::io::Result<()> {
        let status = match s.status {
            RunStatus::Completed => "completed".to_string(),
            RunStatus::StepLimit => "step_limit".to_string(),
            RunStatus::Interrupted(sig) => format!("interrupted (signal {sig})"),
        };
        self.write_manifest_status(s, threads, &status)
    }

    fn write_manifest_status(
        &self,
        s: &RunSummary,
        threads: usize,
        status: &str,
    ) -> std::io::Result<()> {
        let m = serde_json::json!({
            "program": "clump",
            "version": VERSION,
            "scenario": self.scenario.path.display().to_string(),
            "fingerprint": format!("{:016x}", self.scenario.fingerprint()),
            "threads": threads,
            "status": status,
            "dt": self.world.config.dt,
            "first_step": s.first_step,
            "final_step": s.final_step,
            "steps": s.steps(),
            "total_steps": self.scenario.total_steps(),
            "simulated_time": s.time,
            "wall_time_s": s.wall_time,
            "bodies": s.bodies,
            "spheres": s.spheres,
            "lost_bodies": self.world.lost_bodies,
            "insertions": self.insertions(),
            "templates": self.scenario.templates.iter().map(|t| t.name.as_str()).collect::<Vec<_>>(),
            "sphere_steps": s.sphere_steps,
            "sphere_steps_per_s": s.throughput(),
            "steps_per_s": if s.wall_time > 0.0 { s.steps() as f64 / s.wall_time } else { 0.0 },
            "checkpoint": s.checkpoint.as_ref().map(|p| p.display().to_string()),
        });
        let text = serde_json::to_string_pretty(&m).map_err(std::io::Error::other)?;
        crate::atomic::write_atomic(self.out.dir.join("manifest.json"), text.as_bytes())
    }
}

/// Decodes checkpoint file bytes (`path` for messages) and rebuilds the
/// simulation they hold: the scenario (from the stored text and files), the
/// world with its restored state, and the driver state. Never panics on
/// bad bytes: every problem is an input error.
pub fn load_checkpoint(
    bytes: &[u8],
    checkpoint: &Path,
) -> Result<(Scenario, World, DriverState), RunError> {
    load_checkpoint_with_id(bytes, checkpoint).map(|(s, w, d, _)| (s, w, d))
}

/// [`load_checkpoint`], also returning the run id stored in the checkpoint.
pub fn load_checkpoint_with_id(
    bytes: &[u8],
    checkpoint: &Path,
) -> Result<(Scenario, World, DriverState, Option<String>), RunError> {
    let (json, fingerprint): (String, u64) =
        crate::checkpoint::decode_checkpoint(bytes, checkpoint)
            .map_err(|e| RunError::InputMessage(e.to_string()))?;
    let ck: Checkpoint = serde_json::from_str(&json).map_err(|e| {
        RunError::InputMessage(format!(
            "checkpoint {}: cannot decode the state: {e}",
            checkpoint.display()
        ))
    })?;
    let scenario = scenario::parse(
        Path::new(&ck.scenario_path),
        ck.scenario_text.clone(),
        Files::embedded(ck.files.clone()),
    )
    .map_err(RunError::Input)?;
    if scenario.fingerprint() != fingerprint {
        return Err(RunError::InputMessage(format!(
                "checkpoint {}: its scenario fingerprint {fingerprint:016x} does not match the stored scenario ({:016x})",
                checkpoint.display(),
                scenario.fingerprint()
            )));
    }
    let mut world = scenario
        .build_world()
        .map_err(|e| RunError::InputMessage(format!("cannot set up the simulation: {e}")))?;
    for (t, m) in &ck.extra_templates {
        world
            .add_template(t.clone(), *m)
            .map_err(|e| RunError::InputMessage(e.to_string()))?;
    }
    let n_ins = scenario.inserts.len();
    let d = &ck.driver;
    if d.streams.len() != n_ins || d.inserted.len() != n_ins || d.stage > scenario.stages.len() {
        return Err(RunError::InputMessage(format!(
            "checkpoint {}: its driver state does not fit its scenario ({n_ins} insertions, {} stages)",
            checkpoint.display(),
            scenario.stages.len()
        )));
    }
    world.restore_state(ck.world).map_err(|e| {
        RunError::InputMessage(format!(
            "checkpoint {} does not fit its scenario: {e}",
            checkpoint.display()
        ))
    })?;
    Ok((scenario, world, ck.driver, ck.run_id))
}

fn hex3(v: glam::DVec3) -> [String; 3] {
    [
        format!("{:016x}", v.x.to_bits()),
        format!("{:016x}", v.y.to_bits()),
        format!("{:016x}", v.z.to_bits()),
    ]
}

/// Every body's state (sorted by global id) with the exact bit patterns of
/// position, velocity, orientation and angular momentum in hex, as JSON.
pub fn final_state_json(world: &World) -> String {
    let b = &world.bodies;
    let mut idx: Vec<usize> = (0..b.len()).collect();
    idx.sort_by_key(|&i| b.id[i]);
    let bodies: Vec<serde_json::Value> = idx
        .iter()
        .map(|&i| {
            let q = b.orientation[i];
            serde_json::json!({
                "id": b.id[i],
                "template": b.template[i],
                "position": [b.position[i].x, b.position[i].y, b.position[i].z],
                "position_bits": hex3(b.position[i]),
                "velocity_bits": hex3(b.velocity[i]),
                "orientation_bits": [format!("{:016x}", q.w.to_bits()), format!("{:016x}", q.x.to_bits()), format!("{:016x}", q.y.to_bits()), format!("{:016x}", q.z.to_bits())],
                "angular_momentum_bits": hex3(b.angular_momentum[i]),
            })
        })
        .collect();
    let v = serde_json::json!({
        "step": world.step,
        "time_bits": format!("{:016x}", world.time.to_bits()),
        "lost_bodies": world.lost_bodies,
        "bodies": bodies,
    });
    serde_json::to_string_pretty(&v).unwrap_or_default()
}
