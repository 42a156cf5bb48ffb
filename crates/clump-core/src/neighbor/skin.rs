//! Verlet-skin rebuild trigger.

use glam::DVec3;
use rayon::prelude::*;

/// True when any sphere moved more than `skin / 2` (m) from its position at
/// the last build. Measuring sphere centres (not body centres) counts
/// rotation: a sphere at distance R from the centre of mass of a body that
/// turns by an angle α moves by up to αR.
pub fn needs_rebuild(current: &[DVec3], reference: &[DVec3], skin: f64) -> bool {
    if current.len() != reference.len() {
        return true;
    }
    let lim2 = 0.25 * skin * skin;
    current
        .par_chunks(4096)
        .zip(reference.par_chunks(4096))
        .any(|(c, r)| c.iter().zip(r).any(|(a, b)| a.distance_squared(*b) > lim2))
}
