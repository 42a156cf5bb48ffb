//! The simulation domain and periodic boundaries.

use crate::lost::LossCause;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// An axis-aligned simulation domain, world frame, m.
///
/// Along a periodic axis, bodies' centres of mass wrap into `[lo, hi)` and
/// spheres interact with the nearest image of each other. Along a non-periodic
/// axis, a body whose centre of mass leaves `[lo, hi]` is removed (counted as
/// lost in the thermo output).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Domain {
    /// Lower corner, world frame, m.
    pub lo: DVec3,
    /// Upper corner, world frame, m.
    pub hi: DVec3,
    /// Which axes (x, y, z) are periodic.
    pub periodic: [bool; 3],
}

impl Domain {
    /// Edge lengths, m.
    pub fn size(&self) -> DVec3 {
        self.hi - self.lo
    }

    /// Wraps a world position into the box along periodic axes; returns the
    /// wrapped position. Non-periodic axes are left unchanged.
    pub fn wrap(&self, mut x: DVec3) -> DVec3 {
        let l = self.size();
        for a in 0..3 {
            if self.periodic[a] {
                let f = ((x[a] - self.lo[a]) / l[a]).floor();
                if f != 0.0 {
                    x[a] -= f * l[a];
                }
                // guard against round-off placing x exactly at hi
                if x[a] >= self.hi[a] {
                    x[a] = self.lo[a];
                }
            }
        }
        x
    }

    /// True when a centre of mass at `x` lies outside the domain along a
    /// non-periodic axis (such a body is removed).
    pub fn is_outside(&self, x: DVec3) -> bool {
        self.exit_cause(x).is_some()
    }

    /// Why a centre of mass at `x` is outside the domain: the first
    /// non-periodic side it lies beyond (x, then y, then z), or a
    /// non-finite position; `None` inside.
    pub fn exit_cause(&self, x: DVec3) -> Option<LossCause> {
        if !x.is_finite() {
            return Some(LossCause::NotFinite);
        }
        (0..3).find_map(|axis| {
            if self.periodic[axis] {
                None
            } else if x[axis] < self.lo[axis] {
                Some(LossCause::Side { axis, high: false })
            } else if x[axis] > self.hi[axis] {
                Some(LossCause::Side { axis, high: true })
            } else {
                None
            }
        })
    }

    /// Integer image shift `s` (per axis) such that `d + s·L` is the minimum
    /// image of the separation `d` (world frame, m).
    pub fn minimum_image_shift(&self, d: DVec3) -> [i8; 3] {
        let l = self.size();
        let mut s = [0i8; 3];
        for a in 0..3 {
            if self.periodic[a] {
                s[a] = -(d[a] / l[a]).round() as i8;
            }
        }
        s
    }

    /// The world-frame offset (m) of an integer image shift.
    pub fn shift_vector(&self, s: [i8; 3]) -> DVec3 {
        DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64) * self.size()
    }
}
