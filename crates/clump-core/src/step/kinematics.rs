//! Sphere positions from the body poses (docs/theory.md T-7): r_ik = r_cm + Aᵀ r_ik^b,
//! and the spheres of the bodies (their topology arrays, in storage order).
//! A sphere's velocity, v_ik = v_cm + ω × (r_ik − r_cm), is not stored: the
//! contact kernels evaluate it at the contact point from the owner's
//! velocity and angular velocity.

use crate::sphere::sphere_gid;
use crate::world::World;
use glam::{DMat3, DQuat, DVec3};
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

/// Recomputes every sphere's world position from its body's current pose.
pub(crate) fn update_spheres(w: &mut World) {
    let b = &w.bodies;
    place_spheres(&mut w.spheres, b, &w.templates, |bi| {
        (b.position[bi], b.orientation[bi])
    });
}

/// Puts every sphere where its body's pose at the last neighbour build
/// (`NeighborState::reference_pose`) puts it: the positions the neighbour
/// lists are built at and the skin check measures from. These are not
/// stored; a rebuild that needs them places the spheres there, builds, and
/// then calls [`update_spheres`]. The same formula as every other stage, so
/// the same bits as the spheres had at the build.
pub(crate) fn spheres_at_reference_poses(w: &mut World) {
    let poses = &w.neighbors.reference_pose;
    place_spheres(&mut w.spheres, &w.bodies, &w.templates, |bi| poses[bi]);
}

/// Sets every sphere's position from the pose `pose(body)` (centre of mass,
/// orientation) of its body.
fn place_spheres(
    sp: &mut crate::sphere::Spheres,
    b: &crate::body::Bodies,
    templates: &crate::shape::TemplateSet,
    pose: impl Fn(usize) -> (DVec3, DQuat) + Sync,
) {
    let (tf, toff) = (&templates.first, &templates.offset);
    sp.state
        .par_iter_mut()
        .zip(sp.index_in_template.par_iter())
        .zip(sp.body.par_iter())
        .with_min_len(1024)
        .for_each(|((st, &k), &bi)| {
            let bi = bi as usize;
            let off = toff[(tf[b.template[bi] as usize] + k) as usize];
            let (x, q) = pose(bi);
            st.position = sphere_position(x, &DMat3::from_quat(q), off);
        });
}

/// Recomputes the per-sphere topology arrays from the bodies (storage order).
pub(crate) fn rebuild_sphere_topology(w: &mut World) {
    let sp = &mut w.spheres;
    sp.body.clear();
    sp.index_in_template.clear();
    sp.gid.clear();
    sp.radius.clear();
    sp.material.clear();
    sp.body_first.clear();
    // exactly the spheres' number: grown by doubling, the tables would
    // hold up to twice the memory they use
    let total: usize = w
        .bodies
        .template
        .iter()
        .map(|&t| (w.templates.first[t as usize + 1] - w.templates.first[t as usize]) as usize)
        .sum();
    sp.body.reserve_exact(total);
    sp.index_in_template.reserve_exact(total);
    sp.gid.reserve_exact(total);
    sp.radius.reserve_exact(total);
    sp.material.reserve_exact(total);
    sp.body_first.reserve_exact(w.bodies.len() + 1);
    for (b, (&t, &id)) in w.bodies.template.iter().zip(&w.bodies.id).enumerate() {
        sp.body_first.push(sp.body.len() as u32);
        let (s0, s1) = (
            w.templates.first[t as usize],
            w.templates.first[t as usize + 1],
        );
        for k in 0..(s1 - s0) {
            sp.body.push(b as u32);
            sp.index_in_template.push(k);
            sp.gid.push(sphere_gid(id, k));
            sp.radius.push(w.templates.radius[(s0 + k) as usize]);
            sp.material.push(w.templates.material(t as usize));
        }
    }
    sp.body_first.push(sp.body.len() as u32);
    let n = sp.body.len();
    sp.state.resize(n, Default::default());
    for (s, st) in sp.state.iter_mut().enumerate() {
        st.radius = sp.radius[s];
    }
    sp.single_material = match sp.material.first() {
        Some(&m) if sp.material.iter().all(|&x| x == m) => Some(m),
        _ => None,
    };
}
