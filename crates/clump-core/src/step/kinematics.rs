//! Sphere positions from the body poses (docs/theory.md T-7): r_ik = r_cm + Aᵀ r_ik^b.
//! A sphere's velocity, v_ik = v_cm + ω × (r_ik − r_cm), is not stored: the
//! contact kernels evaluate it at the contact point from the owner's
//! velocity and angular velocity.

use crate::world::World;
use glam::{DMat3, DVec3};
use rayon::prelude::*;

/// World position of a sphere with body-frame offset `offset` (m) from the
/// centre of mass of a body at `com` (world, m) with rotation matrix `rot` =
/// R(q) = Aᵀ (body → world): x = r_cm + Aᵀ r_b. The one formula every stage
/// uses, so that spheres updated in the integration pass and in a rebuild
/// agree bit for bit. The matrix is built once per body
/// (`DMat3::from_quat`) and serves all its spheres.
#[inline(always)]
pub fn sphere_position(com: DVec3, rot: &DMat3, offset: DVec3) -> DVec3 {
    com + *rot * offset
}

/// Recomputes every sphere's world position.
pub fn update_spheres(w: &mut World) {
    let b = &w.bodies;
    let sp = &mut w.spheres;
    let (tf, toff) = (&w.templates.first, &w.templates.offset);
    sp.state
        .par_iter_mut()
        .zip(sp.index_in_template.par_iter())
        .zip(sp.body.par_iter())
        .with_min_len(1024)
        .for_each(|((st, &k), &bi)| {
            let bi = bi as usize;
            let off = toff[(tf[b.template[bi] as usize] + k) as usize];
            st.position =
                sphere_position(b.position[bi], &DMat3::from_quat(b.orientation[bi]), off);
        });
}
