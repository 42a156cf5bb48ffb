//! Sphere positions and velocities from the body poses (seed 000):
//! r_ik = r_cm + Aᵀ r_ik^b and v_ik = v_cm + ω × (r_ik − r_cm).

use crate::sphere::{point_velocity, sphere_position};
use crate::world::World;
use rayon::prelude::*;

/// Recomputes every sphere's world position and velocity.
pub fn update_spheres(w: &mut World) {
    let b = &w.bodies;
    let sp = &mut w.spheres;
    let (tf, toff) = (&w.template_first, &w.template_offset);
    sp.position
        .par_iter_mut()
        .zip(sp.velocity.par_iter_mut())
        .zip(sp.body.par_iter().zip(sp.index_in_template.par_iter()))
        .with_min_len(1024)
        .for_each(|((x, v), (&bi, &k))| {
            let bi = bi as usize;
            let off = toff[(tf[b.template[bi] as usize] + k) as usize];
            let com = b.position[bi];
            *x = sphere_position(com, b.orientation[bi], off);
            *v = point_velocity(com, b.velocity[bi], b.angular_velocity[bi], *x);
        });
}
