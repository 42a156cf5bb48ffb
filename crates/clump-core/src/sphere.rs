//! Spheres: the contact elements of the bodies, derived from the body poses.
//!
//! As in Chrono DEM-Engine, a sphere is defined by its owner body and its
//! index in the owner's template; everything else is derived. For the
//! contact kernels the set also keeps, per sphere, its global id, its
//! radius and material (copied from the template at each neighbour build)
//! and its centre (recomputed from the body pose every step; it is the only
//! per-sphere state that changes between builds). A body's spheres are
//! contiguous and in template order: sphere `k` of body `b` is
//! `body_first[b] + k`.

use glam::{DQuat, DVec3};

/// Number of bits of a global sphere id that hold the index in the template:
/// `gid = body_id << SPHERE_ID_BITS | index_in_template`.
pub const SPHERE_ID_BITS: u32 = 16;

/// Global sphere id from the owner's global id and the index in the template.
pub fn sphere_gid(body_id: u64, index_in_template: u32) -> u64 {
    (body_id << SPHERE_ID_BITS) | index_in_template as u64
}

/// The spheres of all bodies, structure of arrays. Topology (owner, index,
/// radius, material) changes only when bodies are added, removed or
/// re-sorted; positions are recomputed every step.
#[derive(Debug, Clone, Default)]
pub struct Spheres {
    /// Storage index of the owner body.
    pub body: Vec<u32>,
    /// Index of this sphere in the owner's template.
    pub index_in_template: Vec<u32>,
    /// Global sphere id (see [`sphere_gid`]).
    pub gid: Vec<u64>,
    /// Radius, m.
    pub radius: Vec<f64>,
    /// Material index.
    pub material: Vec<u16>,
    /// Centre and radius of each sphere, packed ([`SphereState`]).
    pub state: Vec<SphereState>,
    /// The material of every sphere, when they all share one (then the
    /// pair kernel needs no per-pair material lookup).
    pub single_material: Option<u16>,
    /// First sphere of each body; `body_first[n_bodies]` = number of spheres.
    pub body_first: Vec<u32>,
}

/// What the pair kernel's detect pass reads of a sphere, packed into 32
/// bytes (two spheres per cache line): centre and radius. The position
/// lives only here; the radius is a copy of [`Spheres::radius`], written
/// with it whenever the topology is rebuilt. Velocities are not stored per
/// sphere: the contact kernels take them from the owner's velocity and
/// angular velocity (`v + ω × (x − r_cm)`), so the first half step writes
/// only the centres, and the detect pass streams half the bytes it did
/// with the 64-byte state (centre, radius, velocity, owner, material).
#[repr(C, align(32))]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SphereState {
    /// Centre, world frame, m. Not wrapped: it is the owner's centre of mass
    /// plus the rotated body-frame offset, so it may lie outside a periodic box.
    pub position: DVec3,
    /// Radius, m.
    pub radius: f64,
}

#[cfg(test)]
impl SphereState {
    /// The states of spheres at `position` (world, m) with `radius` (m).
    pub(crate) fn of(position: &[DVec3], radius: &[f64]) -> Vec<SphereState> {
        position
            .iter()
            .zip(radius)
            .map(|(&position, &radius)| SphereState { position, radius })
            .collect()
    }
}

impl Spheres {
    /// Centre of sphere `s`, world frame, m (see [`SphereState::position`]).
    #[inline(always)]
    pub fn position(&self, s: usize) -> DVec3 {
        self.state[s].position
    }

    /// Centres of all spheres in storage order, world frame, m.
    pub fn positions(&self) -> impl ExactSizeIterator<Item = DVec3> + '_ {
        self.state.iter().map(|x| x.position)
    }

    /// Number of spheres.
    pub fn len(&self) -> usize {
        self.body.len()
    }

    /// True when there are no spheres.
    pub fn is_empty(&self) -> bool {
        self.body.is_empty()
    }

    /// The spheres of body `b` (storage index), as a range of sphere indices.
    pub fn of_body(&self, b: usize) -> std::ops::Range<usize> {
        self.body_first[b] as usize..self.body_first[b + 1] as usize
    }
}

/// World position of a sphere whose body-frame offset from the centre of mass
/// is `offset_body`, for a body at `com_world` with orientation `q`
/// (body → world): r = r_cm + Aᵀ r_b (docs/theory.md T-7).
#[inline(always)]
pub fn sphere_position(com_world: DVec3, q: DQuat, offset_body: DVec3) -> DVec3 {
    com_world + q * offset_body
}

/// World velocity of a material point at `x_world` of a body with centre of
/// mass `com_world`, velocity `v_world` and angular velocity `w_world`:
/// v = v_cm + ω × (x − r_cm).
#[inline(always)]
pub fn point_velocity(com_world: DVec3, v_world: DVec3, w_world: DVec3, x_world: DVec3) -> DVec3 {
    v_world + w_world.cross(x_world - com_world)
}
