//! Stage changes and insertion at step boundaries: the stage's start
//! actions (gravity, wall changes, file and pack insertions, stream set-up)
//! and the streams' due insertions.

use super::{RunError, Runner};
use crate::scenario::InsertSpec;
use clump_core::insert::{pack, StreamInserter};

impl Runner {
    /// Stage changes, insertion and output before a step. Returns true when
    /// all stages are done (after writing the final output).
    pub(super) fn pre_step(&mut self) -> Result<bool, RunError> {
        self.snap = self
            .world
            .contacts()
            .is_ok()
            .then(|| crate::post::frame::Frame::capture(&self.world));
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
                    let from = self.world.bodies().len();
                    let n = s.insert_due(&mut self.world).map_err(|e| {
                        RunError::Input(self.scenario.insert_error(k, e.to_string()))
                    })?;
                    insert_temperature(&self.scenario, &mut self.world, k, from);
                    self.st.inserted[k] += n as u64;
                    if n > 0 {
                        self.st.last_insert_step = Some(self.world.step);
                    }
                }
            }
            // a world split over ranks: the new bodies' spheres on their ranks
            self.world.settle_inserted();
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
        for (j, c) in stage.bodies.iter().enumerate() {
            let bad = |e: clump_core::world::WorldError| {
                RunError::Input(self.scenario.stage_body_error(si, j, e.to_string()))
            };
            // a world split over ranks: the ranks that hold the body (its
            // owner, and its ghosts, whose first half reads it) change it;
            // no rank holding it is the error of one process
            let held = self.world.body_index(c.id).is_some();
            let elsewhere = self.world.is_split() && self.world.any_rank(held) && !held;
            if elsewhere {
                continue;
            }
            if let Some(v) = c.velocity {
                self.world.set_body_velocity(c.id, v).map_err(bad)?;
            }
            if let Some(v) = c.angular_velocity {
                self.world.set_body_angular_velocity(c.id, v).map_err(bad)?;
            }
        }
        for k in 0..self.scenario.inserts.len() {
            let ins = &self.scenario.inserts[k];
            if ins.stage != si {
                continue;
            }
            let from = self.world.bodies().len();
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
            insert_temperature(&self.scenario, &mut self.world, k, from);
        }
        Ok(())
    }
}

/// Gives the bodies insert `k` just appended (storage indices from `from`
/// on) the insert's `temperature`, and then its body file's `temperature`
/// column, where it has them.
fn insert_temperature(
    scenario: &crate::scenario::Scenario,
    world: &mut clump_core::world::World,
    k: usize,
    from: usize,
) {
    let Some(h) = scenario.heat.as_ref() else {
        return;
    };
    if let Some(t) = h.insert_temperature[k] {
        for b in from..world.bodies().len() {
            // the temperature was checked at its key (> 0 K, finite)
            world
                .set_body_temperature_at(b, t)
                .expect("a temperature checked at its key");
        }
    }
    if let Some(ts) = &h.file_temperature[k] {
        for (b, &t) in (from..world.bodies().len()).zip(ts) {
            // the body file's column was checked as it was read (> 0 K, finite)
            world
                .set_body_temperature_at(b, t)
                .expect("a temperature checked in its body file");
        }
    }
}
