//! The step pipeline, in order (velocity Verlet, as LIGGGHTS `fix multisphere`):
//!
//! 1. [`integrate::initial`]: half kick of v and L, drift of the centre of
//!    mass, free-rotation drift of the orientation (the chosen rotation scheme);
//!    walls move.
//! 2. Sphere kinematics ([`kinematics`]), in the same pass over each body:
//!    sphere positions from the body pose, r = r_cm + Aᵀ r_b, and the
//!    Verlet-skin check (a sphere's velocity, v = v_cm + ω × (r − r_cm), is
//!    evaluated where a contact needs it, from its body's).
//! 3. Neighbour search ([`rebuild`]), only when a sphere moved more than half
//!    the skin. Bodies are wrapped, lost bodies removed and the rest sorted
//!    by cell (slabs across the longest axis, `neighbor::sort`) here; a world
//!    split over ranks exchanges its bodies at this stage.
//! 4. [`force`]: per-pair forces (sphere pairs of different bodies, the
//!    batched `pair_kernel`), which also sums each body's pair force and
//!    torque as soon as all its pairs are evaluated; then a per-body gather
//!    in a fixed order with sphere–wall contacts and gravity (and the pair
//!    sums of the bodies on the seam between two threads' runs).
//!    F = Σ f, M = Σ (x_c − r_cm) × f (docs/theory.md T-11).
//! 5. Final integrate (`integrate::FinalKick`): second half kick, applied by
//!    the gather to each body as soon as its force and torque are summed
//!    (same pass).
//!
//! Inside [`World::run`], the gather of every step but the last also applies
//! stage 1 and 2 of the next step to each body shortly after its final kick
//! (`integrate::FirstHalf`; to a block of 8 bodies after their kicks, so
//! that the processor overlaps their independent chains), while the
//! bodies' state is in the cache: one sweep over the bodies per step
//! instead of two, which counts in beds larger than the caches. The order of operations on each body is
//! unchanged, so are the results; between public calls the world is always
//! at a step boundary.
//!
//! Inside [`World::run`], stages 4 and 5 are also one parallel call
//! (`force::pairs_and_gather`): each thread evaluates the rows of its run
//! of bodies and then gathers the same bodies, from its last chunk down,
//! waiting for the earlier threads' rows only before the bodies on the
//! seam with them; the threads wait for each other once a step.
//!
//! Every parallel loop writes disjoint outputs and every reduction runs over
//! fixed-size chunks in a fixed order, so the results are bit-identical for
//! any thread count. Each loop gives every thread one contiguous run of
//! chunks (`affinity`), balanced by measured time; the cuts never change
//! the results.

pub(crate) mod body_props;
mod first_half_lanes;
pub mod force;
pub mod integrate;
pub mod kinematics;
mod law_lanes;
mod pair_kernel;
mod partition;
pub mod rebuild;
pub mod run;
mod wall_contacts;
mod wall_lanes;

use crate::world::World;
use std::time::Instant;
use thiserror::Error;

/// Adds the time since `*t` to `acc` and restarts `t`.
#[inline(always)]
fn lap(acc: &mut f64, t: &mut Instant) {
    let now = Instant::now();
    *acc += (now - *t).as_secs_f64();
    *t = now;
}

/// Why a step could not be taken.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum StepError {
    /// The neighbour grid could not be built (e.g. a periodic box too small).
    #[error("neighbour search: {0}")]
    Neighbor(String),
    /// A driver of [`World::run_driven`] named an event that is not ahead.
    #[error("the driver's next event (step {event}) is not after the current step {step}")]
    Event {
        /// The world's step.
        step: u64,
        /// The event's step.
        event: u64,
    },
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
        let done = rebuild::rebuild(self, true).map(|()| force::compute(self));
        self.part = part;
        done?;
        self.phase.forces_ready = true;
        Ok(())
    }

    /// Advances the simulation by one time step.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.props_changed();
        self.step_fused(false)
    }

    /// Copies the bodies' centres, velocities and angular velocities from
    /// the pair stage's packed copy back into the body arrays, where a
    /// fused stretch of steps left them there alone
    /// (`StepPhase::bodies_lag`).
    pub(crate) fn catch_up_bodies(&mut self) {
        if !std::mem::take(&mut self.phase.bodies_lag) {
            return;
        }
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
                integrate::HalfKick::new(dt, mass, fa).quotients()
            }),
        );
    }

    /// One step; with `fuse_next`, the gather at its end also takes the
    /// first half of the next step ([`integrate::FirstHalf`]), body by body
    /// in the same pass, and the world is left between the two halves of
    /// that step: only another `step_fused` may follow (see [`World::run`]).
    pub(crate) fn step_fused(&mut self, fuse_next: bool) -> Result<(), StepError> {
        if !self.phase.forces_ready {
            self.prepare()?;
        }
        self.refresh_props();
        let dt = self.config.dt;
        let mut times = self.stage_times;
        let mut t = Instant::now();
        // the spheres move with their bodies in the same pass unless the
        // topology changed (then the rebuild below recomputes them); the
        // gather of the step before may have done it already
        debug_assert!(!self.phase.bodies_lag || self.phase.first_half_done.is_some());
        let moved_out = match self.phase.first_half_done.take() {
            Some(stale) => stale,
            None => integrate::initial(self, !self.phase.topology_dirty),
        };
        for w in &mut self.walls {
            w.advance(dt);
        }
        // a wall that starts to move may come near any sphere
        let wall_started = self.neighbors.wall_cull & !rebuild::static_walls(&self.walls) != 0;
        lap(&mut times.initial, &mut t);
        let stale = self.phase.topology_dirty || moved_out;
        if stale {
            // the rebuild reads and reorders the body arrays
            self.catch_up_bodies();
            rebuild::rebuild(self, true)?;
            lap(&mut times.neighbor, &mut t);
        } else if wall_started {
            rebuild::wall_started(self);
            lap(&mut times.neighbor, &mut t);
        }
        let fuse = fuse_next && !self.phase.topology_dirty;
        // SAFETY: the gather touches each body in one chunk only, and
        // resizes no array.
        let next =
            fuse.then(|| unsafe { integrate::FirstHalf::new(self, self.step + 1, true).lagging() });
        // the pair stage and the gather in one parallel call; the calling
        // thread's time in the pair stage is the pair stage's time
        let (next_stale, pair_time) = force::pairs_and_gather(self, next);
        times.pair += pair_time.as_secs_f64();
        times.gather -= pair_time.as_secs_f64();
        if fuse {
            self.phase.first_half_done = Some(next_stale);
        }
        lap(&mut times.gather, &mut t);
        self.stage_times = times;
        self.end_step();
        Ok(())
    }

    /// The step count and time after a step; the contact records, if this
    /// step kept them, are the records of this step.
    fn end_step(&mut self) {
        self.step += 1;
        self.time = self.step as f64 * self.config.dt;
        let rec = &mut self.neighbors.records;
        rec.step = rec.recording.then_some(self.step);
        rec.recording = false;
    }

    /// One step of a world split over ranks ([`crate::partition`]), never
    /// fused. The same stages as [`World::step_fused`] on this rank's part,
    /// plus what the ranks exchange: whether any sphere moved past half the
    /// skin (then every rank rebuilds: the whole world is gathered,
    /// reorganised and split again), after the gather the ghosts' new state
    /// from their owners, and the statistics and wall loads summed over
    /// the ranks.
    pub(crate) fn step_partitioned(&mut self) -> Result<(), StepError> {
        use partition::ghosts;
        let dt = self.config.dt;
        let mut times = self.stage_times;
        let mut t = Instant::now();
        // a rank's bodies change at every exchange (and whole at an event)
        self.props_changed();
        self.refresh_props();
        let local = self.part.as_ref().is_some_and(|p| p.local);
        let dirty = self.phase.topology_dirty;
        if !local && !dirty {
            // at an event the world is whole: keep this rank's part (a
            // restart's rebuild from the build poses, bit for bit)
            if !self.neighbors.history_pending {
                self.neighbors.pairs.save_history(
                    &self.spheres.gid,
                    self.contact_table.any_reach(),
                    &mut self.neighbors.history_map,
                );
                self.neighbors
                    .pairs
                    .save_slip(&self.spheres.gid, &mut self.neighbors.slip_map);
            }
            rebuild::rebuild(self, false)?;
            self.rebuilds = self.rebuilds.saturating_sub(1);
        }
        // a whole world with new bodies takes its first half whole, as one
        // process does, and is split at the rebuild that follows
        let moved_out = integrate::initial(self, !dirty);
        for w in &mut self.walls {
            w.advance(dt);
        }
        let wall_started = self.neighbors.wall_cull & !rebuild::static_walls(&self.walls) != 0;
        lap(&mut times.initial, &mut t);
        let stale = self.any_rank(moved_out) || dirty;
        if stale {
            if self.part.as_ref().is_some_and(|p| p.local) {
                // bodies move to their new ranks, neighbours only
                partition::migrate::rebuild(self)?;
            } else {
                // the whole world (new bodies): rebuilt whole, then split
                rebuild::rebuild(self, true)?;
            }
            // the gather kicks this rank's bodies as they are now
            self.props_changed();
            self.refresh_props();
            lap(&mut times.neighbor, &mut t);
        } else if wall_started {
            rebuild::wall_started(self);
            lap(&mut times.neighbor, &mut t);
        }
        force::pair_forces(self);
        lap(&mut times.pair, &mut t);
        force::gather(self, true, None);
        ghosts::refresh(self);
        ghosts::reduce(self);
        lap(&mut times.gather, &mut t);
        self.stage_times = times;
        self.end_step();
        Ok(())
    }
}
