//! What a step reports about itself: the contact and kinetic statistics of
//! the force evaluation (thermo output, the health check) and the wall-clock
//! time of each stage.

use serde::{Deserialize, Serialize};

/// Aggregates from the last force evaluation (for thermo output).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactStats {
    /// Touching sphere–sphere pairs.
    pub pair_contacts: u64,
    /// Touching sphere–wall contacts.
    pub wall_contacts: u64,
    /// Elastic energy in all contacts, J.
    pub elastic_energy: f64,
    /// Largest overlap divided by the smaller radius of the contact.
    pub max_overlap_ratio: f64,
    /// Global ids of the two bodies of the contact with the largest overlap
    /// ratio (lower storage chunk first on ties); for a sphere–wall contact
    /// the second entry is 0 and [`ContactStats::max_overlap_wall`] names the wall.
    #[serde(default)]
    pub max_overlap_bodies: [u64; 2],
    /// Wall index + 1 of the contact with the largest overlap ratio when it is
    /// a sphere–wall contact, 0 when it is a sphere–sphere contact (or none).
    #[serde(default)]
    pub max_overlap_wall: u32,
    /// Kinetic energy of all bodies at the end of the step, Σ ½ m v·v + ½ ω·L
    /// (after the second half kick, which the gather applies; world frame),
    /// J. Not finite when some body's state is not finite.
    #[serde(default)]
    pub kinetic_energy: f64,
    /// Total mass of the bodies, kg.
    #[serde(default)]
    pub total_mass: f64,
    /// Largest kinetic energy of a single body at the end of the step, J.
    #[serde(default)]
    pub max_body_kinetic_energy: f64,
    /// Global id of the body with the largest kinetic energy (0 = no bodies).
    #[serde(default)]
    pub max_kinetic_body: u64,
    /// Global id of the first body (storage order) whose position, velocity,
    /// angular momentum, force or torque is NaN or infinite; 0 when all are finite.
    #[serde(default)]
    pub non_finite_body: u64,
}

impl ContactStats {
    /// Folds the statistics of the next chunk (in chunk order) into `self`:
    /// counts and energies add up, maxima keep the earlier chunk on ties and
    /// the first non-finite body is kept. Deterministic for a fixed chunking.
    pub fn merge(&mut self, s: &ContactStats) {
        self.pair_contacts += s.pair_contacts;
        self.wall_contacts += s.wall_contacts;
        self.elastic_energy += s.elastic_energy;
        self.kinetic_energy += s.kinetic_energy;
        self.total_mass += s.total_mass;
        if s.max_overlap_ratio > self.max_overlap_ratio {
            self.max_overlap_ratio = s.max_overlap_ratio;
            self.max_overlap_bodies = s.max_overlap_bodies;
            self.max_overlap_wall = s.max_overlap_wall;
        }
        if s.max_body_kinetic_energy > self.max_body_kinetic_energy {
            self.max_body_kinetic_energy = s.max_body_kinetic_energy;
            self.max_kinetic_body = s.max_kinetic_body;
        }
        if self.non_finite_body == 0 {
            self.non_finite_body = s.non_finite_body;
        }
    }
}

/// The bodies' part of a chunk's [`ContactStats`] (kinetic energy, mass,
/// the most energetic body, the first body not finite), summed in local
/// variables over the chunk and stored in the chunk's slot once at its
/// end, not updated there body by body. The same additions and
/// comparisons in the same order, so the same bits.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BodyTally {
    /// Σ ½ m v·v + ½ ω·L of the bodies so far (world frame), J.
    kinetic_energy: f64,
    /// Their mass, kg.
    total_mass: f64,
    /// The largest kinetic energy of one of them, J.
    max_body_kinetic_energy: f64,
    /// Global id of that body (0: none yet).
    max_kinetic_body: u64,
    /// Global id of the first of them not finite (0: none).
    non_finite_body: u64,
}

impl BodyTally {
    /// Counts a body of mass `mass` (kg) and kinetic energy `ke` (J) whose
    /// state is all finite or not (`finite`); `id` gives its global id, read
    /// only when needed.
    #[inline(always)]
    pub(crate) fn add(
        &mut self,
        ke: f64,
        mass: f64,
        finite: impl FnOnce() -> bool,
        id: impl Fn() -> u64,
    ) {
        self.kinetic_energy += ke;
        self.total_mass += mass;
        if ke > self.max_body_kinetic_energy {
            self.max_body_kinetic_energy = ke;
            self.max_kinetic_body = id();
        }
        if self.non_finite_body == 0 && !finite() {
            self.non_finite_body = id();
        }
    }

    /// Stores the tally in `s`, the statistics of a chunk that counted no
    /// body before.
    pub(crate) fn store(&self, s: &mut ContactStats) {
        s.kinetic_energy = self.kinetic_energy;
        s.total_mass = self.total_mass;
        s.max_body_kinetic_energy = self.max_body_kinetic_energy;
        s.max_kinetic_body = self.max_kinetic_body;
        s.non_finite_body = self.non_finite_body;
    }
}

/// Whether `x` and every component of `v` are finite (neither infinite nor
/// NaN), without a branch: `y · 0` is ±0 for a finite `y` and NaN for any
/// other, so the sum of those products is zero exactly when all are finite.
/// Ten tests chained by `&&` cost about 1 % of a step of the settled tetra
/// bed in the gather.
#[inline(always)]
pub(crate) fn all_finite<const N: usize>(x: f64, v: [glam::DVec3; N]) -> bool {
    // summed as a tree (the vectors' products as vectors, then their
    // components and `x`'s by pairs), not as one chain of ten dependent
    // additions: on the settled tetra bed the gather ran 0.2–0.6 ns a
    // sphere-step faster, the step 0.1–1.8 % (one thread, alternated)
    let s = v.iter().fold(glam::DVec3::ZERO, |acc, y| acc + *y * 0.0);
    (s.x + s.y) + (s.z + x * 0.0) == 0.0
}

/// Wall-clock seconds spent in each stage of `World::step`, accumulated
/// over all steps (like LAMMPS' Pair/Neigh/Modify breakdown). Reading the
/// clock costs about 0.1 µs per stage, negligible against a step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimes {
    /// Initial integrate: half kicks, drift and rotation of the bodies, their
    /// spheres' positions with the skin check, walls. Inside `World::run`
    /// only the first step's (and the walls'): every later step's first half
    /// is done by the gather of the step before, and timed there.
    pub initial: f64,
    /// Neighbour-list rebuilds (sorting, pair list, wall lists).
    pub neighbor: f64,
    /// Sphere–sphere pair forces.
    pub pair: f64,
    /// Per-body gather with sphere–wall contacts and gravity, and the final
    /// integrate (second half kick) of each body in the same pass; inside
    /// `World::run` also the first half of the next step (see `initial`).
    pub gather: f64,
}

impl StageTimes {
    /// The stages as (name, seconds), in pipeline order.
    pub fn rows(&self) -> [(&'static str, f64); 4] {
        [
            ("initial integrate", self.initial),
            ("neighbour build", self.neighbor),
            ("pair forces", self.pair),
            (
                "gather, walls, final integrate (+ next initial)",
                self.gather,
            ),
        ]
    }

    /// Sum over the stages, s.
    pub fn total(&self) -> f64 {
        self.rows().iter().map(|r| r.1).sum()
    }
}

impl std::ops::AddAssign for StageTimes {
    /// Adds another span's times, stage by stage.
    fn add_assign(&mut self, o: StageTimes) {
        self.initial += o.initial;
        self.neighbor += o.neighbor;
        self.pair += o.pair;
        self.gather += o.gather;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn all_finite_is_false_for_any_infinity_or_nan() {
        let ok = DVec3::new(1.0, -0.0, f64::MAX);
        assert!(all_finite(f64::MIN_POSITIVE, [ok, -ok, DVec3::ZERO]));
        assert!(all_finite(-f64::MAX, [ok]));
        for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            assert!(!all_finite(bad, [ok, ok, ok]));
            for axis in 0..3 {
                let mut v = ok;
                v[axis] = bad;
                assert!(!all_finite(1.0, [ok, v, ok]), "{bad} in component {axis}");
                assert!(!all_finite(1.0, [ok, ok, v]), "{bad} in component {axis}");
            }
        }
        // infinities of opposite signs cannot cancel into a zero
        let inf = DVec3::new(f64::INFINITY, 0.0, 0.0);
        let ninf = DVec3::new(f64::NEG_INFINITY, 0.0, 0.0);
        assert!(!all_finite(0.0, [inf, ninf]));
    }

    #[test]
    fn body_tally_sums_in_order_and_keeps_the_first_maximum_and_the_first_bad_body() {
        let bodies = [
            (2.0, 1.0, true, 11),
            (5.0, 2.0, true, 12),
            (5.0, 3.0, false, 13),
            (1.0, 4.0, false, 14),
        ];
        let mut t = BodyTally::default();
        for &(ke, m, fin, id) in &bodies {
            t.add(ke, m, || fin, || id);
        }
        let mut s = ContactStats::default();
        t.store(&mut s);
        assert_eq!(s.kinetic_energy, ((2.0 + 5.0) + 5.0) + 1.0);
        assert_eq!(s.total_mass, 10.0);
        assert_eq!(s.max_body_kinetic_energy, 5.0);
        assert_eq!(s.max_kinetic_body, 12, "ties keep the earlier body");
        assert_eq!(s.non_finite_body, 13, "the first body not finite");
    }
}
