//! When the run loop stops the step for boundary work: the next event
//! (stage end, insertion, output row or frame, checkpoint, step limit) and
//! whether that event needs the whole world or keeps it split over the
//! ranks.

use super::Runner;
use clump_core::step::run::Event;

impl Runner {
    /// The next event: the end of the current stage, the next insertion of
    /// a stream, the next output row or frame, the next checkpoint, the
    /// step limit; at least one step ahead. The step that ends there
    /// records its contacts when a VTK or contact frame may fall there
    /// (the frame's contact counts and contact file need them).
    pub(super) fn next_event(&self, max_steps: Option<u64>) -> Event {
        let step = self.next_event_step(max_steps);
        let st = &self.st;
        let o = &self.scenario.output;
        let last = step >= self.scenario.total_steps() || max_steps.is_some_and(|m| step >= m);
        let due = |on: bool, next: u64| on && (step >= next || last);
        let vtk = due(o.vtk.is_some() && self.out.vtk.is_some(), st.next_vtk);
        let contacts = due(
            o.contacts.is_some() && self.out.contacts.is_some(),
            st.next_contacts,
        ) || due(
            o.fields.is_some() && self.out.fields.is_some(),
            st.next_fields,
        );
        Event {
            step,
            contacts: vtk || contacts,
        }
    }

    /// The step of the next event (see [`Self::next_event`]).
    fn next_event_step(&self, max_steps: Option<u64>) -> u64 {
        let mut e = max_steps.unwrap_or(u64::MAX).min(self.st.next_checkpoint);
        if self.vtk_in_pieces() {
            e = e.min(self.st.next_vtk);
        }
        if self.thermo_in_pieces() {
            e = e.min(self.st.next_thermo);
        }
        if self.contacts_in_pieces() {
            e = e.min(self.st.next_contacts);
        }
        if self.fields_in_pieces() {
            e = e.min(self.st.next_fields);
        }
        let o = &self.scenario.output;
        if o.trajectory.is_some() && self.out.trajectory.is_some() && self.trajectory_in_pieces() {
            e = e.min(self.st.next_trajectory);
        }
        if self.insert_in_pieces() {
            e = e.min(self.next_insertion_step()).min(self.stage_end_step());
        }
        e.min(self.next_whole_step()).max(self.world.step + 1)
    }

    /// True when this run's thermo rows come from reductions over the ranks
    /// ([`World::thermo_of_ranks`]): a world split over several ranks,
    /// with a thermo output (with heat or a fluid too).
    fn thermo_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1)
            && self.out.thermo.is_some()
            && self.scenario.output.thermo.is_some()
    }

    /// True when this run's insertions and stage changes are done on the
    /// world split over the ranks (`clump_core::step::partition::insert`;
    /// a stage's wall and gravity changes are every rank's, its body
    /// changes the holders'): several ranks, without heat or a fluid
    /// (whose new bodies' temperatures and couplings are set on the whole
    /// world).
    fn insert_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1)
            && self.scenario.heat.is_none()
            && self.scenario.fluid.is_none()
    }

    /// The step at which the current stage ends (`u64::MAX` after the last).
    fn stage_end_step(&self) -> u64 {
        let (st, step) = (&self.st, self.world.step);
        self.scenario
            .stages
            .get(st.stage)
            .map_or(u64::MAX, |stage| {
                step.saturating_add(stage.steps.saturating_sub(st.step_in_stage))
            })
    }

    /// The next step at which a stream has bodies due.
    fn next_insertion_step(&self) -> u64 {
        let (step, dt) = (self.world.step, self.world.config.dt);
        let due = self.st.streams.iter().flatten();
        due.map(|s| s.next_due_step(step, dt))
            .min()
            .unwrap_or(u64::MAX)
    }

    /// The next step whose boundary work needs the whole world: the end of
    /// the current stage, an insertion, an output row or frame (every
    /// event but a checkpoint, the step limit, a VTK or contact frame
    /// written in pieces, fields and thermo rows from reductions,
    /// trajectory rows from the bodies' owners, and an insertion or a stage
    /// change done on the split world).
    pub(super) fn next_whole_step(&self) -> u64 {
        let st = &self.st;
        let o = &self.scenario.output;
        let mut e = u64::MAX;
        if !self.insert_in_pieces() {
            e = e.min(self.next_insertion_step()).min(self.stage_end_step());
        }
        if o.vtk.is_some() && self.out.vtk.is_some() && !self.vtk_in_pieces() {
            e = e.min(st.next_vtk);
        }
        if o.thermo.is_some() && self.out.thermo.is_some() && !self.thermo_in_pieces() {
            e = e.min(st.next_thermo);
        }
        if o.trajectory.is_some() && self.out.trajectory.is_some() && !self.trajectory_in_pieces() {
            e = e.min(st.next_trajectory);
        }
        if o.contacts.is_some() && self.out.contacts.is_some() && !self.contacts_in_pieces() {
            e = e.min(st.next_contacts);
        }
        if o.fields.is_some() && self.out.fields.is_some() && !self.fields_in_pieces() {
            e = e.min(st.next_fields);
        }
        if o.flow.is_some() && self.out.flow.is_some() {
            e = e.min(st.next_flow);
        }
        e
    }
}
