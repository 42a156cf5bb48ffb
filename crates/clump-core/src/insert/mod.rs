//! Inserting bodies: packing a region before a run ([`pack()`]) and
//! streaming bodies in during a run ([`StreamInserter`]).
//!
//! Both draw bodies from a particle [`Mix`] (templates, fractions by number or
//! mass, size distributions), give them orientations uniformly distributed on
//! SO(3) (Shoemake's method) and place them by random sequential addition: a
//! pose is accepted when every sphere lies inside the [`Region`], touches no
//! active wall and overlaps no sphere of any other body (bodies already in
//! the world included, with their periodic images). Overlaps are found with a
//! uniform hash grid over sphere centres (cell = twice the largest radius), so
//! an insertion costs O(1) per attempt after an O(N) set-up.
//!
//! Everything is deterministic for a given seed (ChaCha8). All positions and
//! velocities are in the world frame, SI units.
//!
//! 2D insertion (`plane = Some(z)`, the planar case of docs/theory.md):
//! centres of mass are drawn uniformly from the region's cross-section at
//! `z` (rejection from its bounding rectangle) and orientations uniformly
//! about z only ([`random_planar_orientation`]); the random numbers come
//! from the same seeded stream, in the same order (position, then
//! orientation), as in 3D.
//!
//! Scaled templates (size distributions other than a fixed scale of 1) are
//! added to the world with [`crate::shape::ClumpTemplate::scaled`] and the
//! base template's material, one per distinct scale value. A checkpoint stores
//! only the dynamic [`crate::state::WorldState`]: a run layer that resumes
//! must re-add the world's templates beyond those of its scenario
//! (`world.templates[n..]` with `world.templates.material(n..)`), in order,
//! before restoring the state.

mod error;
pub mod mix;
pub mod pack;
pub mod region;
mod space;
pub mod stream;

pub use error::InsertError;
pub use mix::{FractionBasis, Mix, MixEntry, ResolvedMix, SizeDistribution, TemplateCache};
pub use pack::{pack, Orientation, PackReport, PackSpec, PackTarget, PACKING_LIMIT, RSA_LIMIT};
pub use region::Region;
pub use stream::{StreamInserter, StreamRate, StreamSpec};

use glam::{DQuat, DVec3};
use rand::Rng;

/// A rotation drawn uniformly from SO(3) (Shoemake 1992, "Uniform random
/// rotations"): three uniform numbers give a unit quaternion uniformly
/// distributed on the 3-sphere.
pub fn random_orientation<R: Rng + ?Sized>(rng: &mut R) -> DQuat {
    let u1: f64 = rng.gen();
    let u2: f64 = rng.gen();
    let u3: f64 = rng.gen();
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    let (t2, t3) = (std::f64::consts::TAU * u2, std::f64::consts::TAU * u3);
    DQuat::from_xyzw(a * t2.sin(), a * t2.cos(), b * t3.sin(), b * t3.cos()).normalize()
}

/// A rotation about z by an angle drawn uniformly from [0, 2π) (2D
/// insertion): the quaternion's x and y parts are exactly zero, so the body
/// stays in the planar case (docs/theory.md).
pub fn random_planar_orientation<R: Rng + ?Sized>(rng: &mut R) -> DQuat {
    let half = std::f64::consts::PI * rng.gen::<f64>();
    DQuat::from_xyzw(0.0, 0.0, half.sin(), half.cos())
}

/// Where and how an insert places its bodies: its region, its orientations
/// and, for 2D insertion, the plane z of the centres of mass (m, world).
pub(crate) struct Placement<'a> {
    region: &'a Region,
    orientation: &'a Orientation,
    plane: Option<f64>,
}

impl<'a> Placement<'a> {
    pub(crate) fn of(region: &'a Region, orientation: &'a Orientation, plane: Option<f64>) -> Self {
        Placement {
            region,
            orientation,
            plane,
        }
    }

    /// One candidate pose of a body whose spheres are at least `margin`
    /// (m) from the region's faces: a centre of mass (world, m) and an
    /// orientation (body → world), in 3D or in the plane. `None` when the
    /// region has no room for the margin (another try).
    pub(crate) fn sample<R: Rng + ?Sized>(
        &self,
        rng: &mut R,
        margin: f64,
    ) -> Option<(DVec3, DQuat)> {
        match self.plane {
            None => {
                let x = self.region.sample_eroded(rng, margin)?;
                Some((x, self.orientation.sample(rng)))
            }
            Some(z) => {
                let x = self.region.sample_in_plane(rng, margin, z)?;
                Some((x, self.orientation.sample_planar(rng)))
            }
        }
    }

    /// Checks a 2D insertion (nothing in 3D): a finite plane inside the
    /// region by at least `max_radius` (m, the largest sphere of the mix)
    /// above and below, no `velocity` along z, no `angular_velocity` about
    /// x or y, and a fixed orientation turned about z only.
    pub(crate) fn check_plane(
        &self,
        velocity: DVec3,
        angular_velocity: DVec3,
        max_radius: f64,
    ) -> Result<(), InsertError> {
        let Some(z) = self.plane else {
            return Ok(());
        };
        let bad = |m: String| Err(InsertError::InvalidSpec(format!("2D insertion: {m}")));
        let (lo, hi) = self.region.bounds();
        if !z.is_finite() || z - max_radius < lo.z || z + max_radius > hi.z {
            return bad(format!(
                "the plane z = {z} m must lie inside the region (z from {} to {} m) by the largest sphere radius, {max_radius} m",
                lo.z, hi.z
            ));
        }
        if velocity.z != 0.0 {
            return bad(format!("the velocity {velocity} has a z component"));
        }
        if angular_velocity.x != 0.0 || angular_velocity.y != 0.0 {
            return bad(format!(
                "the angular velocity {angular_velocity} has an x or y component"
            ));
        }
        if let Orientation::Fixed { quaternion } = *self.orientation {
            if quaternion.x != 0.0 || quaternion.y != 0.0 {
                return bad(format!(
                    "the orientation {quaternion} is turned about an axis other than z"
                ));
            }
        }
        Ok(())
    }
}
