//! Verlet-skin rebuild trigger.
//!
//! The list must be rebuilt when any sphere moved more than `skin / 2` (m)
//! from its position at the last build. Measuring sphere centres (not body
//! centres) counts rotation: a sphere at distance R from the centre of mass
//! of a body that turns by an angle α moves by up to αR. The check runs in
//! the integration pass that moves the spheres
//! ([`crate::step::integrate::initial`]).

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
