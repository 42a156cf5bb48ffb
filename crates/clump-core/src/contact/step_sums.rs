//! Exact contact sums of one force evaluation, made when a driver asks for
//! them (the step that ends at an event, whose statistics a thermo row
//! reports): the elastic energy of the counted contacts and each wall's
//! load, as exact sums of the per-contact terms ([`crate::exact_sum`]).
//! Their values do not depend on the order of the contacts, on the
//! threads, or on how the contacts are shared among ranks, so one process
//! and any number of ranks report the same bits (a rank adds the contacts
//! it counts in its statistics: those of its owned bodies' rows and its
//! owned bodies' wall contacts). Written by the pair kernel and the gather.

use crate::exact_sum::{AtomicExactSum, ExactSum};
use crate::wall::WallLoad;
use glam::DVec3;

/// A wall's load as exact sums: force x, y, z, torque x, y, z.
pub type WallSums = [ExactSum; 6];

/// The exact sums of the evaluation that ends at a requested step.
#[derive(Debug, Default)]
pub struct StepSums {
    /// The world step whose evaluation makes them (see
    /// [`StepSums::request`]).
    at: Option<u64>,
    /// The world step the sums describe; `None`: the last evaluation made
    /// none.
    made: Option<u64>,
    elastic: AtomicExactSum,
    wall: Vec<[AtomicExactSum; 6]>,
}

impl Clone for StepSums {
    /// The request only (the sums belong to the world's last evaluation).
    fn clone(&self) -> Self {
        StepSums {
            at: self.at,
            ..StepSums::default()
        }
    }
}

impl StepSums {
    /// Asks the force evaluation that leaves the world at step `at` to make
    /// the sums (`None`: none).
    pub fn request(&mut self, at: Option<u64>) {
        self.at = at;
    }

    /// At the start of an evaluation whose statistics describe world step
    /// `step`, with `walls` walls: whether it makes the sums (then they
    /// start from zero). Any evaluation forgets the sums of the last one.
    pub(crate) fn begin(&mut self, step: u64, walls: usize) -> bool {
        self.made = None;
        let on = self.at == Some(step);
        if on {
            self.elastic.clear();
            self.wall.resize_with(walls, Default::default);
            self.wall.truncate(walls);
            self.wall
                .iter_mut()
                .flatten()
                .for_each(AtomicExactSum::clear);
        }
        on
    }

    /// At the end of an evaluation that [`StepSums::begin`] started with
    /// sums on.
    pub(crate) fn end(&mut self, step: u64) {
        self.made = Some(step);
    }

    /// Adds a contact's elastic energy, J.
    #[inline]
    pub(crate) fn add_elastic(&self, e: f64) {
        self.elastic.add(e);
    }

    /// Adds a contact's load on wall `w`: force (N) and torque (N m),
    /// world frame.
    #[inline]
    pub(crate) fn add_wall(&self, w: usize, force: DVec3, torque: DVec3) {
        let s = &self.wall[w];
        for k in 0..3 {
            s[k].add(force[k]);
            s[3 + k].add(torque[k]);
        }
    }

    /// The sums of the last evaluation when it made them and describes
    /// world step `step`: the elastic energy and each wall's load.
    pub fn at_step(&self, step: u64) -> Option<(ExactSum, Vec<WallSums>)> {
        (self.made == Some(step)).then(|| {
            let walls = self
                .wall
                .iter()
                .map(|w| w.each_ref().map(AtomicExactSum::load));
            (self.elastic.load(), walls.collect())
        })
    }
}

/// Each wall's load, rounded from its sums.
pub fn wall_loads(sums: &[WallSums]) -> Vec<WallLoad> {
    sums.iter()
        .map(|s| WallLoad {
            force: DVec3::new(s[0].value(), s[1].value(), s[2].value()),
            torque: DVec3::new(s[3].value(), s[4].value(), s[5].value()),
        })
        .collect()
}
