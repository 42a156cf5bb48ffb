//! Bodies that left the simulation, counted by cause.
//!
//! A body leaves when its centre of mass crosses a non-periodic side of the
//! domain (counted per side), when its position is no longer finite, or when
//! a driver removes it (`crate::World::remove_body`). The counts are part
//! of the checkpointed state, so a resumed run reports the same totals.

use serde::{Deserialize, Serialize};

/// Why a body left the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LossCause {
    /// Its centre of mass crossed a non-periodic side: `axis` 0, 1, 2 for
    /// x, y, z; `high` for the upper side (`hi`), else the lower (`lo`).
    Side {
        /// 0, 1 or 2 for x, y or z.
        axis: usize,
        /// The upper side of the domain along `axis`.
        high: bool,
    },
    /// Its position was NaN or infinite at a neighbour rebuild.
    NotFinite,
    /// A driver removed it through the API.
    Removed,
}

/// Counts of bodies that left the simulation, by cause.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct LostBodies {
    /// Crossed a side, per side: x lo, x hi, y lo, y hi, z lo, z hi.
    pub through_side: [u64; 6],
    /// Position no longer finite.
    pub not_finite: u64,
    /// Removed by a driver.
    pub removed: u64,
}

/// The names of the six sides in the order of [`LostBodies::through_side`].
pub const SIDE_NAMES: [&str; 6] = ["x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi"];

impl LostBodies {
    /// Counts one body lost for `cause`.
    pub fn record(&mut self, cause: LossCause) {
        match cause {
            LossCause::Side { axis, high } => self.through_side[2 * axis + high as usize] += 1,
            LossCause::NotFinite => self.not_finite += 1,
            LossCause::Removed => self.removed += 1,
        }
    }

    /// All bodies lost, whatever the cause.
    pub fn total(&self) -> u64 {
        self.through_side.iter().sum::<u64>() + self.not_finite + self.removed
    }

    /// `(cause name, count)` for every cause with a non-zero count, sides
    /// first in the order of [`SIDE_NAMES`], then `not_finite`, `removed`.
    pub fn by_cause(&self) -> Vec<(&'static str, u64)> {
        SIDE_NAMES
            .iter()
            .zip(self.through_side)
            .map(|(&n, c)| (n, c))
            .chain([("not_finite", self.not_finite), ("removed", self.removed)])
            .filter(|&(_, c)| c > 0)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_cause_lands_in_its_own_count() {
        let mut l = LostBodies::default();
        l.record(LossCause::Side {
            axis: 2,
            high: false,
        });
        l.record(LossCause::Side {
            axis: 2,
            high: false,
        });
        l.record(LossCause::Side {
            axis: 0,
            high: true,
        });
        l.record(LossCause::NotFinite);
        l.record(LossCause::Removed);
        assert_eq!(l.through_side, [0, 1, 0, 0, 2, 0]);
        assert_eq!(l.total(), 5);
        assert_eq!(
            l.by_cause(),
            vec![("x_hi", 1), ("z_lo", 2), ("not_finite", 1), ("removed", 1)]
        );
    }
}
