//! The run loop every driver uses (`clump run`, `clump resume`, `clump
//! bench`, the validation cases, Python, MPI): it advances a world from one
//! *event* to the next and hands the world to the driver at those step
//! boundaries, like LAMMPS' fixed hook order (`initial_integrate` …
//! `end_of_step`).
//!
//! Between two events the steps run fused (each step's gather also takes
//! the next step's first half, body by body; see [`World::run`]), so a
//! driver pays for the fusion's gain only where it needs the world: a stage
//! change, output due, a checkpoint due, a steering action. After *every*
//! step the driver also sees the step's statistics ([`StepReport`]), cheap
//! enough for a health check or a progress line, but not the world itself:
//! inside a fused stretch the bodies are already half a step further.
//!
//! The hook points, in the order the loop calls them:
//! 1. [`Driver::at_boundary`]: the world at a step boundary, with its
//!    forces and statistics of the last step. Observe anything (bodies,
//!    walls, [`World::contacts`] when the event asked for them) and steer
//!    through the world's methods (velocities, poses, wall motion, gravity,
//!    adding and removing bodies). Runs at the start and at every event.
//! 2. [`Driver::next_event`]: the step of the next event.
//! 3. Steps up to that event: initial integrate → neighbours → pair forces →
//!    gather with walls, gravity and final integrate (see [`crate::step`]).
//! 4. [`StepHook::end_of_step`] after each of them: the step's statistics
//!    ([`StepHook::stop_requested`] is polled before each).
//!
//! A driver that keeps the world itself (as `clump run` does) calls
//! [`World::advance`] from its own loop instead: the same steps, hooks and
//! fusion, with the boundary work written inline.

use super::StepError;
use crate::stats::ContactStats;
use crate::world::World;

/// Whether the run goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// End the run (the loop returns [`RunEnd::Driver`] from a boundary,
    /// [`RunEnd::Tripped`] after a step).
    Stop,
}

/// The next step boundary at which a driver needs the world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Event {
    /// The world's step number at that boundary (greater than the current
    /// one; `u64::MAX`: none).
    pub step: u64,
    /// Record every contact's force in the step that ends there, for
    /// [`World::contacts`] (costs a store per contact in that step only).
    pub contacts: bool,
}

impl Event {
    /// An event at `step`, without contact records.
    pub fn at(step: u64) -> Self {
        Event {
            step,
            contacts: false,
        }
    }
}

/// What one completed step reports to `Driver::end_of_step`.
#[derive(Debug, Clone, Copy)]
pub struct StepReport<'a> {
    /// The world's step number after the step.
    pub step: u64,
    /// Simulated time after the step, s.
    pub time: f64,
    /// Bodies.
    pub bodies: usize,
    /// Spheres stepped.
    pub spheres: usize,
    /// Statistics of the step's force evaluation and kinetic energy (the
    /// health check's input).
    pub stats: &'a ContactStats,
}

/// Where [`World::advance`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Advance {
    /// At the event's step boundary.
    Reached,
    /// [`StepHook::end_of_step`] asked to stop (e.g. a health trip). When
    /// that step was fused, the next step's first half is already applied
    /// (stepping on finishes that step correctly).
    Tripped,
    /// [`StepHook::stop_requested`] was true; the world is at a step
    /// boundary before the event.
    Interrupted,
}

/// How [`World::run_driven`] ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunEnd {
    /// [`Driver::at_boundary`] asked to stop; the world is at a step boundary.
    Driver,
    /// See [`Advance::Tripped`].
    Tripped,
    /// See [`Advance::Interrupted`].
    Interrupted,
}

/// What the loop asks after and before every step.
pub trait StepHook {
    /// After every step (fused or not), with its statistics.
    fn end_of_step(&mut self, _report: &StepReport) -> Flow {
        Flow::Continue
    }

    /// Polled before every step: when true, the loop stops at the next step
    /// boundary (at once when the world is at one).
    fn stop_requested(&self) -> bool {
        false
    }
}

/// No per-step hook.
impl StepHook for () {}

/// A driver of the run loop: the hooks at step boundaries, and after steps.
pub trait Driver: StepHook {
    /// Called at the start and at every event, with the world at a step
    /// boundary: observe and steer.
    fn at_boundary(&mut self, world: &mut World) -> Flow;

    /// The next event, after [`Self::at_boundary`]. Its step must be greater
    /// than the world's (else the loop ends with [`StepError::Event`]).
    fn next_event(&mut self, world: &World) -> Event;
}

/// The driver of a plain `n`-step run: no events but the end.
pub struct Steps {
    end: u64,
}

impl Steps {
    /// Runs until the world's step is `end`.
    pub fn until(end: u64) -> Self {
        Steps { end }
    }
}

impl StepHook for Steps {}

impl Driver for Steps {
    fn at_boundary(&mut self, world: &mut World) -> Flow {
        if world.step >= self.end {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }

    fn next_event(&mut self, _world: &World) -> Event {
        Event::at(self.end)
    }
}

impl World {
    /// Steps up to `event` (fused between boundaries), calling `hook` after
    /// every step; the inner loop of [`Self::run_driven`], for drivers that
    /// keep the world themselves (`clump run`).
    pub fn advance<H: StepHook + ?Sized>(
        &mut self,
        event: Event,
        hook: &mut H,
    ) -> Result<Advance, StepError> {
        if event.step <= self.step {
            return Err(StepError::Event {
                step: self.step,
                event: event.step,
            });
        }
        if self.part.is_some() {
            return self.advance_partitioned(event, hook);
        }
        // the bodies may have been edited since the last call, even when
        // the world stopped inside a fused step (Advance::Tripped)
        self.props_changed();
        let end = self.advance_fused(event, hook);
        // the world handed back has its body arrays current, also when the
        // stretch ended inside a fused step (a trip, an error)
        self.catch_up_bodies();
        end
    }

    /// The fused steps of [`Self::advance`] on a whole world.
    fn advance_fused<H: StepHook + ?Sized>(
        &mut self,
        event: Event,
        hook: &mut H,
    ) -> Result<Advance, StepError> {
        while self.step < event.step {
            let interrupt = hook.stop_requested();
            if interrupt && !self.phase.first_half_done() {
                return Ok(Advance::Interrupted);
            }
            let last = self.step + 1 == event.step;
            self.neighbors.records.set_recording(last && event.contacts);
            self.take_step(!last && !interrupt)?;
            let report = self.report();
            if hook.end_of_step(&report) == Flow::Stop {
                return Ok(Advance::Tripped);
            }
        }
        Ok(Advance::Reached)
    }

    /// [`Self::advance`] of a world split over ranks: unfused steps of this
    /// rank's part, a stop request honoured when any rank has one, and the
    /// whole world gathered on every rank at the end (the driver's boundary
    /// work sees it whole). Every rank takes the same decisions: the hook
    /// sees the statistics summed over the ranks.
    fn advance_partitioned<H: StepHook + ?Sized>(
        &mut self,
        event: Event,
        hook: &mut H,
    ) -> Result<Advance, StepError> {
        let mut end = Advance::Reached;
        if !self.phase.forces_ready() {
            if self.is_split() {
                // new bodies or settings in a split world: the parts rebuilt
                // and their forces, as one process's prepare
                self.prepare_split()?;
            } else {
                // the whole world's first forces (or after new bodies), as
                // one process takes them; the rebuild splits it
                self.prepare()?;
            }
        }
        // a stop asked by the hook after a step is or-ed over the ranks with
        // the stop requests before the next (one reduction per step)
        let mut tripped = false;
        // an event whose boundary work needs only each rank's part keeps
        // the world split: no whole step before it, no gather after it
        let split_event = self
            .part
            .as_mut()
            .is_some_and(|p| std::mem::take(&mut p.stay_split));
        if let Some(p) = self.part.as_mut() {
            p.stop.1 = None;
        }
        loop {
            let flags = [tripped, hook.stop_requested()];
            let [trip, interrupt] = self.or_stop_flags(flags);
            if trip {
                end = Advance::Tripped;
                break;
            }
            if self.step >= event.step {
                break;
            }
            if interrupt {
                end = Advance::Interrupted;
                break;
            }
            let last = self.step + 1 == event.step;
            if last && !split_event {
                // the step before an event runs whole on every rank, as one
                // process takes it: its statistics, wall loads and contact
                // records (for output) are then one process's, bit for bit
                self.neighbors.records.set_recording(event.contacts);
                super::partition::join::whole_step(self)?;
            } else {
                // a split event's last step records its part's contacts
                // (the frame's contact counts of the owned bodies)
                self.neighbors.records.set_recording(last && event.contacts);
                self.take_step(false)?;
            }
            let report = self.report();
            tripped = hook.end_of_step(&report) == Flow::Stop;
        }
        // a tripped run is diagnosed on the whole world
        let whole = !split_event || end == Advance::Tripped;
        if whole && self.part.as_ref().is_some_and(|p| p.local) {
            super::partition::join::join(self)?;
        }
        Ok(end)
    }

    /// The trip and stop flags of a rank's loop, or-ed over the ranks.
    /// After a rank's step, the stop requests came with its statistics
    /// (sent before the step: a request made since goes with the next
    /// step's) and the trip is every rank's, the hook having read the same
    /// summed statistics; otherwise (the first step, after a whole step)
    /// one reduction. This rank's request then goes with the next step's
    /// statistics.
    fn or_stop_flags(&mut self, [tripped, stop]: [bool; 2]) -> [bool; 2] {
        let Some(p) = self.part.as_mut() else {
            return [tripped, stop];
        };
        p.stop.0 = stop;
        match p.stop.1.take() {
            Some(any) => [tripped, any],
            None => self.any_ranks([tripped, stop]),
        }
    }

    /// What the step just taken reports to the hook.
    fn report(&self) -> StepReport<'_> {
        StepReport {
            step: self.step,
            time: self.time,
            bodies: self.bodies.len(),
            spheres: self.spheres.len(),
            stats: &self.stats,
        }
    }

    /// Runs the world under `driver` until a hook or a stop request ends
    /// it (see the module docs for the order of the hooks).
    pub fn run_driven<D: Driver + ?Sized>(&mut self, driver: &mut D) -> Result<RunEnd, StepError> {
        loop {
            if driver.at_boundary(self) == Flow::Stop {
                return Ok(RunEnd::Driver);
            }
            let event = driver.next_event(self);
            match self.advance(event, driver)? {
                Advance::Reached => {}
                Advance::Tripped => return Ok(RunEnd::Tripped),
                Advance::Interrupted => return Ok(RunEnd::Interrupted),
            }
        }
    }

    /// Advances by `n` steps (fused: see [`crate::step`]); the world ends at
    /// a step boundary.
    pub fn run(&mut self, n: u64) -> Result<(), StepError> {
        let end = self.step.saturating_add(n);
        self.run_driven(&mut Steps::until(end)).map(|_| ())
    }
}
