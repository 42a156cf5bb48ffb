//! Verlet-skin rebuild trigger.
//!
//! The list must be rebuilt when any sphere moved more than `skin / 2` (m)
//! from its position at the last build. Measuring sphere centres (not body
//! centres) counts rotation: a sphere at distance R from the centre of mass
//! of a body that turns by an angle α moves by up to αR. The check runs in
//! the integration pass that moves the spheres
//! ([`crate::step::integrate::initial`]).
//!
//! Unless the scenario fixes it, the skin follows the motion
//! ([`adapted_skin`]): a thick skin while the bed moves fast (fewer
//! rebuilds), a thin one once it has settled (fewer candidate pairs).

use glam::DVec3;

/// `(skin/2)²`, m², the squared displacement that triggers a rebuild.
#[inline(always)]
pub fn trigger_distance2(skin: f64) -> f64 {
    0.25 * skin * skin
}

/// True when a sphere now at `x` (world, m) moved farther than allowed from
/// its position `x_ref` at the last build; `limit2` from [`trigger_distance2`].
#[inline(always)]
pub fn moved_too_far(x: DVec3, x_ref: DVec3, limit2: f64) -> bool {
    x.distance_squared(x_ref) > limit2
}

/// Default skin as a fraction of the smallest sphere radius: the skin of
/// the first neighbour build.
pub const SKIN_DEFAULT: f64 = 0.2;
/// Thinnest adapted skin, fraction of the smallest sphere radius.
pub const SKIN_MIN: f64 = 0.05;
/// Thickest adapted skin, fraction of the smallest sphere radius (LIGGGHTS'
/// tetra-bed input uses 0.5).
pub const SKIN_MAX: f64 = 0.5;
/// `2 R / c` of the cost model in [`adapted_skin`]: a rebuild costs about
/// `R` = 13 steps, and every `0.1 r` of skin adds about 0.4 candidate pairs
/// per sphere, each about a sixth of a step's cost per sphere, so
/// `c ≈ 0.66` steps per radius of skin (measured on the settled 2 000-clump
/// tetra bed: 1.74, 1.35 and 1.13 candidates per sphere at skins of 0.2,
/// 0.1 and 0.05 r).
const SKIN_COST: f64 = 39.0;

/// The skin (m) for the next neighbour list, from the motion since the last
/// build: the largest sphere displacement `d_max` (m) over `steps` steps.
///
/// With the spheres moving at up to `u = d_max/steps` per step, a list of
/// skin `s` lasts `s/(2u)` steps; per step it costs a rebuild share
/// `2uR/s` plus candidate pairs `c s`. The sum is least at
/// `s = √(2Ru/c)`, clamped to [`SKIN_MIN`]..[`SKIN_MAX`] times the smallest
/// radius `r_min` (m). Depends only on the state, so every thread count
/// and a restarted run choose the same skin.
pub fn adapted_skin(r_min: f64, d_max: f64, steps: u64) -> f64 {
    let u = d_max / steps.max(1) as f64;
    let s = (SKIN_COST * u * r_min).sqrt();
    s.clamp(SKIN_MIN * r_min, SKIN_MAX * r_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The optimum of the cost model, and its clamps: a settled bed gets
    /// the thinnest skin, a fast one the thickest, and in between the skin
    /// grows with the square root of the speed.
    #[test]
    fn skin_follows_the_motion() {
        let r = 1e-3;
        assert_eq!(adapted_skin(r, 1e-9, 1000), SKIN_MIN * r);
        assert_eq!(adapted_skin(r, 1e-3, 10), SKIN_MAX * r);
        // u = 1e-7 m per step: s = √(39 · 1e-7 · 1e-3) ≈ 6.2e-5 m
        let s = adapted_skin(r, 1e-5, 100);
        assert!((s - (39.0f64 * 1e-10).sqrt()).abs() < 1e-12, "{s}");
        let s4 = adapted_skin(r, 4e-5, 100);
        assert!((s4 / s - 2.0).abs() < 1e-12);
    }
}
