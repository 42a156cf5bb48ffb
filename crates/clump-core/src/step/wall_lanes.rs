//! The lanes of a batch of sphere–wall touches: one array per quantity, one
//! element per touch (structure of arrays), for the law loop of
//! `super::law_lanes`, which the pair kernel runs over sphere pairs too.
//! The wall pass (`super::wall_contacts`) collects touches with their
//! geometry and contact-point velocities into these lanes; evaluated one
//! at a time, a touch's square roots and divisions were a chain the
//! processor could not overlap with the next touch's. After the loop and
//! [`super::law_lanes::finish_sliding`] every lane holds, bit for bit, what
//! [`SlidingLaw::evaluate`] gives.

use super::law_lanes::LawLanes;
use crate::contact::SlidingLaw;
use crate::par::simd::{get3, set3};
use glam::DVec3;

/// Touches a batch holds.
pub(super) const WALL_BATCH: usize = 16;

/// A 3-vector per lane (x, y and z rows), world frame.
type Rows3 = [[f64; WALL_BATCH]; 3];

/// The inputs and outputs of a batch's touches, lane `k` = touch `k`.
/// World frame, SI units. The body is the contact's `i` side: for a wall
/// `R* = r` (the sphere's radius) and `m* = m` (its body's mass).
#[derive(Clone, Copy)]
pub(super) struct WallLanes {
    // --- inputs
    /// Unit normal from the wall to the sphere centre.
    pub normal: Rows3,
    /// Overlap, m.
    pub overlap: [f64; WALL_BATCH],
    /// Velocity of the body's contact point relative to the wall's, m/s.
    pub vrel: Rows3,
    /// The sphere's radius, m.
    pub radius: [f64; WALL_BATCH],
    /// The body's mass, kg.
    pub mass: [f64; WALL_BATCH],
    /// Tangential spring `ξ`, m: input, and output after the law.
    pub spring: Rows3,
    /// Per-lane law, when the batch mixes models ([`SlidingLaw::store_lane`]).
    pub law: [[f64; WALL_BATCH]; SlidingLaw::LANE_ROWS],
    // --- outputs
    /// Force on the sphere, N.
    pub force: Rows3,
    /// Elastic energy, J.
    pub energy: [f64; WALL_BATCH],
    /// Signed normal force, N.
    pub normal_force: [f64; WALL_BATCH],
    /// 1 where the touch slides (outputs of a sticking touch until
    /// [`super::law_lanes::finish_sliding`]), else 0.
    pub slide: [f64; WALL_BATCH],
}

impl WallLanes {
    /// All lanes zero.
    pub(super) fn zeroed() -> Self {
        let v = [0.0; WALL_BATCH];
        WallLanes {
            normal: [v; 3],
            overlap: v,
            vrel: [v; 3],
            radius: v,
            mass: v,
            spring: [v; 3],
            law: [v; SlidingLaw::LANE_ROWS],
            force: [v; 3],
            energy: v,
            normal_force: v,
            slide: v,
        }
    }
}

impl LawLanes for WallLanes {
    const LANES: usize = WALL_BATCH;

    #[inline(always)]
    fn lane_law(&self, k: usize) -> SlidingLaw {
        SlidingLaw::load_lane(&self.law, k)
    }

    #[inline(always)]
    fn contact_as<const LIMIT: bool>(&mut self, k: usize, law: &SlidingLaw, dt: f64) -> bool {
        let mut xi = get3(&self.spring, k);
        let (out, slide) = law.evaluate_as::<LIMIT>(
            get3(&self.normal, k),
            self.overlap[k],
            get3(&self.vrel, k),
            self.radius[k],
            self.mass[k],
            dt,
            &mut xi,
        );
        set3(&mut self.spring, k, xi);
        set3(&mut self.force, k, out.force);
        self.energy[k] = out.energy;
        self.normal_force[k] = out.normal_force;
        slide
    }

    #[inline(always)]
    fn slide(&self, k: usize) -> f64 {
        self.slide[k]
    }

    #[inline(always)]
    fn set_slide(&mut self, k: usize, slide: f64) {
        self.slide[k] = slide;
    }

    #[inline(always)]
    fn set_spring(&mut self, k: usize, xi: DVec3) {
        set3(&mut self.spring, k, xi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::model::sample_laws;
    use crate::par::simd::{levels, unit_numbers};
    use crate::step::law_lanes::{finish_sliding, run_law};

    /// Touches with overlaps of 0 to 20 % of the radius, random contact
    /// velocities, and springs from far inside the Coulomb cone to far
    /// outside it; `mixed`: every lane its own law.
    fn lanes(seed: u64, laws: &[SlidingLaw], mixed: bool) -> WallLanes {
        let mut u = unit_numbers(seed);
        let v3 =
            |a: f64, u: &mut dyn FnMut() -> f64| DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * a;
        let mut l = WallLanes::zeroed();
        for k in 0..WALL_BATCH {
            let r = 1e-3 * (0.5 + u());
            set3(&mut l.normal, k, v3(2.0, &mut u).normalize());
            l.overlap[k] = 0.2 * r * u();
            set3(&mut l.vrel, k, v3(0.4, &mut u));
            l.radius[k] = r;
            l.mass[k] = 1e-5 * (0.5 + u());
            // log-uniform over 10⁻⁶ to 10⁻³ m
            let a = 10f64.powf(-6.0 + 3.0 * u());
            set3(&mut l.spring, k, v3(a, &mut u));
            if mixed {
                laws[k % laws.len()].store_lane(&mut l.law, k);
            }
        }
        l
    }

    /// The lanes, with the sliding touches evaluated again, hold bit for
    /// bit what the scalar law ([`SlidingLaw::evaluate`], the one the
    /// contact model runs on walls) gives each touch, at every vector
    /// instruction set of this processor, for one law and for mixed laws,
    /// over full and partial batches.
    #[test]
    fn wall_lanes_give_the_scalar_law_bit_for_bit() {
        let (laws, levels) = (sample_laws(), levels());
        let dt = 1e-5;
        for (case, law) in [None, Some(&laws[0]), Some(&laws[3])]
            .into_iter()
            .enumerate()
        {
            for len in [WALL_BATCH, 5] {
                let base = lanes(case as u64 + 3, &laws, law.is_none());
                let mut slid = 0;
                for &level in &levels {
                    let mut l = base;
                    run_law(&mut l, len, law, dt, level);
                    slid = (0..len).filter(|&k| l.slide[k] != 0.0).count();
                    finish_sliding(&mut l, len, law, dt, |k| get3(&base.spring, k));
                    for k in 0..len {
                        let lw = law
                            .copied()
                            .unwrap_or_else(|| SlidingLaw::load_lane(&base.law, k));
                        let mut xi = get3(&base.spring, k);
                        let want = lw.evaluate(
                            get3(&base.normal, k),
                            base.overlap[k],
                            get3(&base.vrel, k),
                            base.radius[k],
                            base.mass[k],
                            dt,
                            &mut xi,
                        );
                        let what = format!("{level:?}, case {case}, len {len}, lane {k}");
                        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
                        assert_eq!(bits(get3(&l.force, k)), bits(want.force), "{what}");
                        assert_eq!(bits(get3(&l.spring, k)), bits(xi), "{what}");
                        assert_eq!(l.energy[k].to_bits(), want.energy.to_bits(), "{what}");
                        assert_eq!(
                            l.normal_force[k].to_bits(),
                            want.normal_force.to_bits(),
                            "{what}"
                        );
                        assert_eq!(l.slide[k], 0.0, "{what}");
                    }
                }
                // the springs span the cone: in a full batch some touches
                // slide and some stick
                if len == WALL_BATCH {
                    assert!(slid > 0 && slid < len, "case {case}: {slid} of {len} slide");
                }
            }
        }
    }
}
