//! How several simultaneous contact points between the same two bodies (or a
//! body and a wall) combine (docs/theory.md T-34).
//!
//! - [`MultiContact::Sum`]: every sphere-pair force adds up, as in LIGGGHTS,
//!   Yade, MercuryDPM and DEM-Engine. With `n` simultaneous equal contacts the
//!   body pair feels an `n`-times stiffer spring and an `n`-times larger
//!   dashpot. Each dashpot was sized for one contact carrying the whole body
//!   mass, so the damping ratio `ζ = −β` grows by √n (`n` × dashpot against
//!   `√n` × `√(k m)`) and the restitution **drops below** the input `e`:
//!   with the tensile clamp (default) `e_n = exp(−2ζ_n A(ζ_n))`,
//!   `ζ_n = √n ζ` ([`crate::contact::damping::clamped_restitution`]); for a
//!   `tensile` pair `e_n = exp(−√n ζ π/√(1 − n ζ²))` with
//!   `ζ = −ln e/√(ln²e + π²)` (no rebound once `n ζ² ≥ 1`). This holds for the
//!   linear law and, by the phase-plane mapping in [`crate::contact::damping`],
//!   also for Hertz with the δ^¼ dashpot. For `n = 2`, `e = 0.5` gives
//!   `e_2 ≈ 0.394` (clamped) or `0.366` (tensile). The contact time
//!   shrinks by `√n` (linear) or `n^{2/5}` (Hertz). An elastic contact
//!   (`e = 1`) stays elastic. The test `dimer_dropped_flat_sum_and_average`
//!   checks this on a dimer dropped flat.
//! - [`MultiContact::Average`]: f_ij = (1/NCP_ij) Σ f_ik,jl. The
//!   forces of the `NCP` touching sphere pairs are each divided by `NCP`, so
//!   `n` equal simultaneous contacts act like a single contact: stiffness,
//!   damping, restitution and contact time are those of one sphere pair. The
//!   cost: when a contact appears or disappears the force jumps (NCP changes),
//!   so the pair force is not derivable from a potential and energy is not
//!   conserved exactly.

use serde::{Deserialize, Serialize};

/// Several-contact treatment, chosen per interaction type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MultiContact {
    /// Forces of all touching sphere pairs add up.
    #[default]
    Sum,
    /// Forces are divided by the number of touching sphere pairs.
    Average,
}

/// A small, allocation-free counter of touching contacts per partner
/// (another body's global id, or a wall index). Used while gathering the
/// forces of one body. Partners beyond the capacity fall back to a linear
/// scan of the overflow, which is still correct but slower.
pub struct PartnerCounts {
    keys: [u64; 32],
    counts: [u32; 32],
    len: usize,
    overflow: Vec<(u64, u32)>,
}

impl Default for PartnerCounts {
    fn default() -> Self {
        Self {
            keys: [0; 32],
            counts: [0; 32],
            len: 0,
            overflow: Vec::new(),
        }
    }
}

impl PartnerCounts {
    /// Forget all counts.
    pub fn clear(&mut self) {
        self.len = 0;
        self.overflow.clear();
    }

    /// Count one more touching contact with `partner`.
    pub fn add(&mut self, partner: u64) {
        for k in 0..self.len {
            if self.keys[k] == partner {
                self.counts[k] += 1;
                return;
            }
        }
        if self.len < self.keys.len() {
            self.keys[self.len] = partner;
            self.counts[self.len] = 1;
            self.len += 1;
            return;
        }
        match self.overflow.iter_mut().find(|e| e.0 == partner) {
            Some(e) => e.1 += 1,
            None => self.overflow.push((partner, 1)),
        }
    }

    /// Number of touching contacts with `partner` (0 if none).
    pub fn get(&self, partner: u64) -> u32 {
        for k in 0..self.len {
            if self.keys[k] == partner {
                return self.counts[k];
            }
        }
        self.overflow
            .iter()
            .find(|e| e.0 == partner)
            .map_or(0, |e| e.1)
    }
}
