//! A bounded period-two oscillation, seen in one number the step already
//! sums: the elastic energy of the contacts. When a damped contact's time
//! step is above its stability limit (docs/theory.md T-52) but the motion
//! stays bounded (the contact opens, the Hertz stiffness changes), the
//! contact forces flip sign every step at many times the bodies' weight
//! and the bed never comes to rest, while neither the overlap nor the
//! kinetic energy trips the health check. The overlaps then go up and
//! down in turn, and so does the elastic energy: [`ZigZag`] counts the
//! steps in a row at which its change alternates in sign by more than a
//! set fraction of it. A settling or flowing bed changes its elastic
//! energy smoothly at the time scale of contacts (tens of steps), so it
//! does not alternate for long; a period-two oscillation does at every
//! step.

use serde::{Deserialize, Serialize};

/// Steps in a row at which the elastic energy must alternate for a
/// period-two oscillation.
pub const ZIGZAG_STEPS: u64 = 200;
/// Smallest change of the elastic energy, relative to it, that counts.
pub const ZIGZAG_RELATIVE: f64 = 1e-3;

/// The run of alternating elastic-energy changes (serializable: it goes
/// into checkpoints with the health check).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ZigZag {
    /// The elastic energy of the last step, J (`None` before the first).
    pub last_energy: Option<f64>,
    /// Its change at the last step, J.
    pub last_change: f64,
    /// Steps in a row with an alternating change of at least
    /// [`ZIGZAG_RELATIVE`].
    pub run: u64,
    /// The smallest relative change in that run.
    pub smallest: f64,
}

impl ZigZag {
    /// Adds a step's elastic energy `e` (J); returns the length of the run
    /// and its smallest relative change once the run reaches
    /// [`ZIGZAG_STEPS`].
    pub fn add(&mut self, e: f64) -> Option<(u64, f64)> {
        let prev = self.last_energy.replace(e)?;
        let change = e - prev;
        let relative = change.abs() / e.abs().max(prev.abs());
        if relative >= ZIGZAG_RELATIVE && change * self.last_change < 0.0 {
            self.smallest = if self.run == 0 {
                relative
            } else {
                self.smallest.min(relative)
            };
            self.run += 1;
        } else {
            self.run = 0;
        }
        self.last_change = change;
        (self.run >= ZIGZAG_STEPS).then_some((self.run, self.smallest))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alternation_is_found_and_smooth_change_is_not() {
        let mut z = ZigZag::default();
        // a period-two oscillation of 1 % about 1 J
        let hit = (0..1000).find_map(|n| z.add(1.0 + 0.01 * (-1f64).powi(n)));
        assert_eq!(hit.map(|h| h.0), Some(ZIGZAG_STEPS));
        // a decaying oscillation at 20 steps a period, and round-off
        // alternation of a settled bed, are not
        let mut z = ZigZag::default();
        for n in 0..5000 {
            let t = n as f64;
            let e = 1.0
                + 0.5 * (-t / 800.0).exp() * (t * std::f64::consts::PI / 10.0).sin()
                + 1e-12 * (-1f64).powi(n);
            assert_eq!(z.add(e), None, "step {n}");
        }
    }
}
