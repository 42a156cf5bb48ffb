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

use glam::DQuat;
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
