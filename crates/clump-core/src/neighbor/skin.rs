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
/// Thickest adapted skin, fraction of the largest sphere radius (LIGGGHTS'
/// tetra-bed input uses 0.5), further limited so that a periodic axis keeps
/// three neighbour cells ([`crate::world::World::max_adapted_skin`]).
pub const SKIN_MAX: f64 = 0.5;
/// `2 R / c` of the cost model in [`adapted_skin`] for clumps of `k`
/// spheres, in units of the smallest radius: a rebuild costs `R` steps, and
/// the candidate pairs of a skin one radius thick cost `c` steps' work.
///
/// Both depend on the shape. A sphere's neighbour search scans every sphere
/// in the 27 cells around it, and a clump of many overlapping spheres
/// packs many of them there (its own, mostly), so `R` grows with `k`;
/// those spheres are mostly buried inside their clump, with no partner
/// across a gap, so `c` does not. Measured with `clump bench` in phase B,
/// from the stage shares and rebuild counts at two skins each (one thread):
///
/// | bed | k | R, steps | c, steps per r_min of skin | 2R/c |
/// |---|---|---|---|---|
/// | settled tetra bed, 2 000 clumps | 4 | 13 | 0.66 | 39 |
/// | stone pile, 200 stones | 50 | 36 | 0.25 | 288 |
///
/// The line through the two points, `2R/c = 17.3 + 5.41 k`, is used for
/// every `k`; a bed of single spheres gets 23. Only the speed depends on
/// it: any skin gives the same contacts.
fn skin_cost(k: usize) -> f64 {
    17.3 + 5.41 * k as f64
}

/// The skin (m) for the next neighbour list, from the motion since the last
/// build: the largest sphere displacement `d_max` (m) over `steps` steps,
/// for clumps of up to `k` spheres.
///
/// With the spheres moving at up to `u = d_max/steps` per step, a list of
/// skin `s` lasts `s/(2u)` steps; per step it costs a rebuild share
/// `2uR/s` plus candidate pairs `c s`. The sum is least at
/// `s = √(2Ru/c)` (`skin_cost`), clamped to [`SKIN_MIN`] times the
/// smallest radius `r_min` (m) below and to `s_max` (m) above. Depends only
/// on the state and the templates, so every thread count, every rank count
/// and a restarted run choose the same skin.
pub fn adapted_skin(r_min: f64, s_max: f64, d_max: f64, steps: u64, k: usize) -> f64 {
    let u = d_max / steps.max(1) as f64;
    let s = (skin_cost(k) * u * r_min).sqrt();
    s.min(s_max).max(SKIN_MIN * r_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The optimum of the cost model, and its clamps: a settled bed gets
    /// the thinnest skin, a fast one the thickest, and in between the skin
    /// grows with the square root of the speed, thicker for clumps of many
    /// spheres (whose rebuilds cost more steps).
    #[test]
    fn skin_follows_the_motion() {
        let (r, top) = (1e-3, 2e-3);
        assert_eq!(adapted_skin(r, top, 1e-9, 1000, 4), SKIN_MIN * r);
        assert_eq!(adapted_skin(r, top, 1e-2, 10, 4), top);
        // u = 1e-7 m per step, k = 4: s = √((17.3 + 21.64) · 1e-7 · 1e-3)
        let s = adapted_skin(r, top, 1e-5, 100, 4);
        assert!((s - (38.94f64 * 1e-10).sqrt()).abs() < 1e-12, "{s}");
        let s4 = adapted_skin(r, top, 4e-5, 100, 4);
        assert!((s4 / s - 2.0).abs() < 1e-12);
        let stone = adapted_skin(r, top, 1e-5, 100, 50);
        assert!((stone / s - (287.8f64 / 38.94).sqrt()).abs() < 1e-12);
    }
}
