//! Sphere positions and velocities from the body poses (seed 000):
//! r_ik = r_cm + Aᵀ r_ik^b and v_ik = v_cm + ω × (r_ik − r_cm).

use crate::world::World;
use glam::{DMat3, DVec3};
use rayon::prelude::*;

/// World position and velocity of a sphere with body-frame offset `offset`
/// (m) from the centre of mass of a body at `com` (world, m) with rotation
/// matrix `rot` = R(q) = Aᵀ (body → world), velocity `v` (world, m/s) and
/// angular velocity `w` (world, rad/s): the world-frame arm is `Aᵀ r_b`,
/// x = r_cm + Aᵀ r_b, v = v_cm + ω × Aᵀ r_b. The one formula every stage
/// uses, so that spheres updated in the integration pass and in a rebuild
/// agree bit for bit. The matrix is built once per body
/// (`DMat3::from_quat`) and serves all its spheres.
#[inline(always)]
pub fn sphere_state(com: DVec3, rot: &DMat3, v: DVec3, w: DVec3, offset: DVec3) -> (DVec3, DVec3) {
    let arm = *rot * offset;
    (com + arm, v + w.cross(arm))
}

/// Recomputes every sphere's world position and velocity.
pub fn update_spheres(w: &mut World) {
    let b = &w.bodies;
    let sp = &mut w.spheres;
    let (tf, toff) = (&w.template_first, &w.template_offset);
    sp.state
        .par_iter_mut()
        .zip(sp.index_in_template.par_iter())
        .with_min_len(1024)
        .for_each(|(st, &k)| {
            let bi = st.body as usize;
            let off = toff[(tf[b.template[bi] as usize] + k) as usize];
            (st.position, st.velocity) = sphere_state(
                b.position[bi],
                &DMat3::from_quat(b.orientation[bi]),
                b.velocity[bi],
                b.angular_velocity[bi],
                off,
            );
        });
}
