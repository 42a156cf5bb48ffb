//! A run driven step by step from another program (the Python package):
//! the same [`Runner`] as `clump run`, with or without an output folder,
//! advanced to a caller's step instead of to the end. At every boundary it
//! does what `clump run` does there (stage changes, insertions, outputs,
//! the checkpoint schedule) and steps through [`Runner::advance_checked`],
//! so a run cut into pieces gives the bits of one uninterrupted `clump run`.
//!
//! Between calls the world is at a step boundary whose boundary work is
//! done ([`DriverState::pre_step_done`](super::DriverState)): the caller
//! may read and steer it ([`Runner::world_mut`]), and the next step starts
//! from what it leaves, as after a stage's start actions.

use super::outputs::{wall_columns, wall_thermo, Outputs};
use super::{Pace, ProgressClock, RunError, RunStatus, RunSummary, Runner};
use crate::scenario::Scenario;
use crate::thermo_csv::WallColumns;
use clump_core::step::run::Advance;
use clump_core::thermo::Thermo;
use clump_core::world::World;
use std::path::Path;
use std::time::Instant;

/// What a session has done since it began (for `manifest.json`).
#[derive(Debug, Clone, Copy)]
pub struct Tally {
    first_step: u64,
    started: Instant,
    sphere_steps: f64,
}

impl Tally {
    /// A session of `runner` that begins now.
    pub fn start(runner: &Runner) -> Self {
        Tally {
            first_step: runner.world.step,
            started: Instant::now(),
            sphere_steps: 0.0,
        }
    }
}

/// Where [`Runner::step_until`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Until {
    /// At the target step (its boundary work done).
    Reached,
    /// All stages are done (the final outputs are written).
    Completed,
    /// The deadline passed; the world is at an earlier step boundary.
    Paused,
}

impl Runner {
    /// A run of `scenario` without an output folder: nothing is written
    /// unless asked ([`Runner::write_checkpoint_to`]).
    pub fn detached(scenario: Scenario) -> Result<Self, RunError> {
        let world = scenario
            .build_world()
            .map_err(|e| RunError::InputMessage(format!("cannot set up the simulation: {e}")))?;
        let st = super::DriverState::fresh(&scenario);
        Ok(Runner::assemble(scenario, world, st, Outputs::detached()))
    }

    /// The run held by a checkpoint file, without an output folder.
    pub fn detached_resume(checkpoint: &Path) -> Result<Self, RunError> {
        let bytes = std::fs::read(checkpoint).map_err(|e| {
            RunError::InputMessage(format!(
                "cannot read checkpoint {}: {e}",
                checkpoint.display()
            ))
        })?;
        let (scenario, world, driver) = super::load_checkpoint(&bytes, checkpoint)?;
        Ok(Runner::assemble(
            scenario,
            world,
            driver,
            Outputs::detached(),
        ))
    }

    /// The world, to steer between calls of [`Runner::step_until`] (use
    /// the world's steering methods, `clump_core::steer`).
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// True once all stages are done.
    pub fn finished(&self) -> bool {
        self.st.stage >= self.scenario.stages.len()
    }

    /// Index of the current stage (the number of stages once finished).
    pub fn stage(&self) -> usize {
        self.st.stage
    }

    /// The current thermo row as `thermo.csv` has it: the column names
    /// (with units) and the values.
    pub fn thermo_row(&self) -> (Vec<String>, Thermo, Vec<f64>) {
        let cols: Vec<WallColumns> = wall_columns(&self.scenario);
        let header = crate::thermo_csv::ThermoWriter::header_columns(
            &cols,
            self.scenario.heat.is_some(),
            self.scenario.fluid.is_some(),
        );
        let (t, power) = wall_thermo(&self.world, &self.scenario.torque_points);
        let power = cols
            .iter()
            .zip(power)
            .filter(|(c, _)| c.power)
            .map(|(_, p)| p)
            .collect();
        (header.split(',').map(str::to_string).collect(), t, power)
    }

    /// Steps until the world's step is `target`, all stages are done, or
    /// `deadline` passes (then at the next step boundary). The step that
    /// ends at `target` records its contacts when `contacts` is true
    /// ([`World::contacts`]). `tally` counts the session's steps for the
    /// manifest written at the end of the stages. On return the boundary work of the world's
    /// step is done, except after [`Until::Paused`].
    pub fn step_until(
        &mut self,
        target: u64,
        contacts: bool,
        deadline: Option<Instant>,
        tally: &mut Tally,
    ) -> Result<Until, RunError> {
        let mut clock = ProgressClock {
            at: Instant::now(),
            step: self.world.step,
        };
        loop {
            if !self.st.pre_step_done {
                let finished = self.pre_step()?;
                self.st.pre_step_done = true;
                if finished {
                    self.finish(tally)?;
                    return Ok(Until::Completed);
                }
            }
            if self.finished() {
                // the final boundary's work (outputs, final state) is done
                return Ok(Until::Completed);
            }
            if self.world.step >= target {
                return Ok(Until::Reached);
            }
            if deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok(Until::Paused);
            }
            self.periodic_checkpoint()?;
            let mut event = self.next_event(Some(target));
            event.contacts |= contacts && event.step == target;
            let pace = Pace {
                interrupt: None,
                deadline,
                progress: None,
                interval: std::time::Duration::MAX,
                clock: &mut clock,
                end_step: target,
                sphere_steps: &mut tally.sphere_steps,
            };
            let (how, tripped) = self.advance_checked(event, pace)?;
            if let Some(inst) = tripped {
                let partial = self.summary(
                    RunStatus::Completed,
                    tally.first_step,
                    tally.started,
                    tally.sphere_steps,
                );
                return Err(self.unstable(inst, &partial, threads()));
            }
            if how == Advance::Interrupted {
                return Ok(Until::Paused);
            }
        }
    }

    /// At the end of all stages: `final_state.json` and `manifest.json`
    /// in the output folder, as `clump run` writes them.
    fn finish(&mut self, t: &Tally) -> Result<(), RunError> {
        let summary = self.summary(
            RunStatus::Completed,
            t.first_step,
            t.started,
            t.sphere_steps,
        );
        if let Some(f) = &self.out.fields {
            f.finish()
                .map_err(super::error::rt("cannot write the time-averaged fields"))?;
        }
        self.write_final_state()
            .map_err(super::error::rt("cannot write final_state.json"))?;
        self.write_manifest(&summary, threads())
            .map_err(super::error::rt("cannot write manifest.json"))
    }

    pub(super) fn summary(
        &self,
        status: RunStatus,
        first_step: u64,
        t_start: Instant,
        sphere_steps: f64,
    ) -> RunSummary {
        RunSummary {
            status,
            first_step,
            final_step: self.world.step,
            time: self.world.time,
            wall_time: t_start.elapsed().as_secs_f64(),
            sphere_steps,
            bodies: self.world.bodies().len(),
            spheres: self.world.spheres().len(),
            checkpoint: self.out.last_checkpoint.clone(),
        }
    }
}

/// Threads of the pool the engine steps in (for the manifest).
fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |c| c.get())
}
