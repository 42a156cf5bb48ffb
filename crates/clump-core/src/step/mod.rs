//! The step pipeline (velocity Verlet, as LIGGGHTS `fix multisphere`).
//! `World::take_step` reads top to bottom as the list of stages:
//!
//! 1. **first half** (`first_half`): half kick of v and L (`kick`),
//!    drift of the centre of mass, the rotation scheme's drift of the
//!    orientation; the body's spheres follow, r = r_cm + Aᵀ r_b
//!    ([`kinematics`]), and are checked against the Verlet skin. Inside a
//!    fused stretch of steps ([`World::run`]) the previous step's gather
//!    already did it, body by body.
//! 2. **walls move** (prescribed motion).
//! 3. **neighbours** (`rebuild`), only when a sphere moved more than half
//!    the skin or bodies were added or removed: wrap, remove lost bodies,
//!    sort by cell, build the pair and wall lists, carry histories.
//! 4. **pair stage** (`pair_stage`, kernel in `pair_kernel`): the
//!    contact force of every touching sphere pair, summed per body.
//! 5. **gather** (`gather`): per body, in a fixed order, its pair load,
//!    body forces (gravity), wall contacts (`wall_contacts`), the second
//!    half kick, the health tally, and inside a fused stretch the next
//!    step's first half. The pair stage and the gather are one parallel
//!    call: each thread takes its run of bodies through both.
//!
//! With heat on (`World::heat`), stage 3½, **heat** (`heat`): the bodies'
//! temperatures take one explicit step from the conduction through the
//! contacts at the sphere centres stage 4 reads.
//!
//! A world split over ranks takes the same stages; the rank exchanges are
//! hooks in them (`ranks`): the skin check or-ed over the ranks, the
//! bodies migrating at a rebuild, the ghosts' state and the statistics
//! exchanged after the gather. Such a step is never fused.
//!
//! Every parallel loop writes disjoint outputs and every reduction runs over
//! fixed-size chunks in a fixed order, so the results are bit-identical for
//! any thread count. Each loop gives every thread one contiguous run of
//! chunks (`par::affinity`), balanced by measured time; the cuts never
//! change the results.

mod body_props;
mod coupling;
mod error;
mod first_half;
mod first_half_lanes;
mod gather;
mod heat;
mod heat_pairs;
mod kick;
pub mod kinematics;
mod law_lanes;
mod pair_kernel;
mod pair_stage;
mod partition;
mod ranks;
pub(crate) mod rebuild;
pub mod run;
mod wall_contacts;
mod wall_lanes;

pub use error::StepError;
pub(crate) use first_half::FirstHalf;

use crate::world::World;
use std::time::Instant;

/// Adds the time since `*t` to `acc` and restarts `t`.
#[inline(always)]
fn lap(acc: &mut f64, t: &mut Instant) {
    let now = Instant::now();
    *acc += (now - *t).as_secs_f64();
    *t = now;
}

impl World {
    /// Computes sphere positions, the neighbour list and the forces at the
    /// current state, so that the first step starts with valid forces. Called
    /// automatically by [`World::step`].
    pub fn prepare(&mut self) -> Result<(), StepError> {
        self.props_changed();
        self.refresh_props();
        // a partitioned world is whole between steps (at an event): every
        // rank prepares it whole, as one process does; the next step splits it
        let part = self.part.take();
        if part.as_ref().is_some_and(|p| p.local) {
            self.part = part;
            partition::join::join(self)?;
            return self.prepare();
        }
        let done = rebuild::rebuild(self, true).map(|()| gather::compute(self));
        self.part = part;
        done?;
        self.phase.forces_evaluated();
        Ok(())
    }

    /// Advances the simulation by one time step.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.props_changed();
        self.take_step(false)
    }

    /// One step, stage by stage (see the module docs). With `fuse_next`,
    /// the gather at its end also takes the first half of the next step,
    /// body by body in the same pass, and the world is left between the
    /// two halves of that step: only another `take_step` may follow (see
    /// [`World::run`]). A world split over ranks takes the same stages with
    /// its exchanges ([`ranks`]), never fused.
    pub(crate) fn take_step(&mut self, fuse_next: bool) -> Result<(), StepError> {
        let mut times = self.stage_times;
        let mut t = Instant::now();
        self.begin_step()?;
        // --- 1. first half (done already where fused into the last gather)
        let moved_out = self.first_half();
        // --- 2. walls move
        let wall_started = self.move_walls();
        lap(&mut times.initial, &mut t);
        // --- 3. neighbours, when a sphere left half the skin or bodies changed
        if self.lists_stale(moved_out) {
            self.rebuild_neighbors()?;
            lap(&mut times.neighbor, &mut t);
        } else if wall_started {
            rebuild::wall_started(self);
            lap(&mut times.neighbor, &mut t);
        }
        // --- 3½. heat: conduction at the sphere centres the forces will
        // see (its time is counted with the gather's)
        if self.heat.is_some() {
            heat::conduct(self);
        }
        // --- 4. + 5. pair stage, then the gather (one parallel call)
        let fuse = fuse_next && self.part.is_none() && !self.phase.topology_dirty();
        // SAFETY: the gather touches each body in one chunk only, and
        // resizes no array.
        let next = fuse.then(|| unsafe { FirstHalf::new(self, self.step + 1, true).lagging() });
        let lags = next.as_ref().is_some_and(FirstHalf::lags);
        let (next_stale, pair_time) = gather::pairs_and_gather(self, next);
        times.pair += pair_time.as_secs_f64();
        times.gather -= pair_time.as_secs_f64();
        self.exchange_after_gather()?;
        lap(&mut times.gather, &mut t);
        self.stage_times = times;
        self.end_step(fuse.then_some((next_stale, lags)));
        Ok(())
    }

    /// Before the stages: the forces of the current state exist, the step
    /// reads the bodies' mass properties from where they are, and a world
    /// split over ranks keeps its part.
    fn begin_step(&mut self) -> Result<(), StepError> {
        if self.part.is_some() {
            // a rank's bodies change at every exchange (and whole at an event)
            self.props_changed();
            self.refresh_props();
            return self.keep_rank_part();
        }
        if !self.phase.forces_ready() {
            self.prepare()?;
        }
        self.refresh_props();
        Ok(())
    }

    /// Stage 1: the first half of the step, unless the last gather took it;
    /// true when a sphere moved more than half the skin. With the topology
    /// changed the spheres are left to the rebuild.
    fn first_half(&mut self) -> bool {
        match self.phase {
            crate::world::StepPhase::FirstHalfDone { moved_out, .. } => moved_out,
            crate::world::StepPhase::Boundary(_) => {
                first_half::initial(self, !self.phase.topology_dirty())
            }
        }
    }

    /// Stage 2: the walls' prescribed motion; true when a wall that stood
    /// starts to move (it may come near any sphere).
    fn move_walls(&mut self) -> bool {
        let dt = self.config.dt;
        for w in &mut self.walls {
            w.advance(dt);
        }
        self.neighbors.wall_cull & !rebuild::static_walls(&self.walls) != 0
    }

    /// Whether the neighbour lists must be rebuilt: bodies changed, or a
    /// sphere (on any rank) moved more than half the skin.
    fn lists_stale(&mut self, moved_out: bool) -> bool {
        let dirty = self.phase.topology_dirty();
        if self.part.is_some() {
            self.any_rank(moved_out) || dirty
        } else {
            dirty || moved_out
        }
    }

    /// Stage 3: the neighbour rebuild; on ranks, the bodies migrate.
    fn rebuild_neighbors(&mut self) -> Result<(), StepError> {
        if self.part.is_some() {
            return self.migrate();
        }
        // the rebuild reads and reorders the body arrays
        self.catch_up_bodies();
        rebuild::rebuild(self, true)
    }

    /// The step count and time after a step, and where the world is: with
    /// `fused`, the next step's first half done (whether a sphere moved
    /// more than half the skin, whether the bodies lag); the contact
    /// records, if this step kept them, are the records of this step.
    fn end_step(&mut self, fused: Option<(bool, bool)>) {
        match fused {
            Some((moved_out, lags)) => self.phase.first_half_fused(moved_out, lags),
            None => {
                self.phase.take_first_half();
            }
        }
        self.step += 1;
        self.time = self.step as f64 * self.config.dt;
        let rec = &mut self.neighbors.records;
        rec.step = rec.recording.then_some(self.step);
        rec.recording = false;
    }

    /// Copies the bodies' centres, velocities and angular velocities from
    /// the pair stage's packed copy back into the body arrays, where a
    /// fused stretch of steps left them there alone
    /// (`StepPhase::FirstHalfDone::bodies_lag`).
    pub(crate) fn catch_up_bodies(&mut self) {
        if !self.phase.bodies_lag() {
            return;
        }
        self.phase.bodies_caught_up();
        let b = &mut self.bodies;
        for (i, pb) in self.neighbors.pairs.body.iter().enumerate() {
            b.position[i] = pb.position;
            b.velocity[i] = pb.velocity;
            b.angular_velocity[i] = pb.angular_velocity;
        }
    }

    /// The bodies may have changed since the step last checked where it
    /// reads their mass properties and degrees of freedom from
    /// ([`body_props`]): a driver may have edited them before a public call,
    /// or a rank's bodies were exchanged.
    pub(crate) fn props_changed(&mut self) {
        self.scratch.props.fresh = false;
    }

    /// Checks where the step reads the bodies' mass properties and degrees
    /// of freedom from ([`body_props`]), unless that still holds for the
    /// bodies as they are.
    pub(crate) fn refresh_props(&mut self) {
        if self.scratch.props.holds(self.config.dt) {
            return;
        }
        self.scratch.props.refresh(
            &self.bodies,
            &self.templates,
            self.config.added_mass,
            self.step,
            (self.config.dt, |dt, mass, fa| {
                kick::HalfKick::new(dt, mass, fa).quotients()
            }),
        );
    }
}
