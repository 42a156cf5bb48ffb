//! Packing a region before a run by random sequential addition.

use super::mix::{Mix, TemplateCache};
use super::region::Region;
use super::space::{body_spheres, fits, Occupancy};
use super::{random_orientation, random_planar_orientation, InsertError, Placement};
use crate::body::BodyInit;
use crate::world::World;
use glam::{DQuat, DVec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Requested solid volume fractions above this (random close packing of
/// equal spheres) are refused at once.
pub const PACKING_LIMIT: f64 = 0.64;

/// Solid volume fraction that random sequential addition of spheres
/// realistically reaches (the jamming limit is about 0.38).
pub const RSA_LIMIT: f64 = 0.38;

/// How many bodies to place.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PackTarget {
    /// Exactly this many bodies.
    Count(usize),
    /// Bodies until their solid volume reaches this fraction of the region
    /// volume (dimensionless, in (0, 0.64]).
    VolumeFraction(f64),
}

/// Orientation of inserted bodies (body → world).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Orientation {
    /// Uniformly random on SO(3).
    #[default]
    Random,
    /// Every body gets this orientation (normalised).
    Fixed {
        /// Body → world rotation.
        quaternion: DQuat,
    },
}

impl Orientation {
    /// Draws an orientation (consumes random numbers only for `Random`).
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> DQuat {
        match *self {
            Orientation::Random => random_orientation(rng),
            Orientation::Fixed { quaternion } => quaternion.normalize(),
        }
    }

    /// Draws an orientation turned about z only (2D insertion): a uniform
    /// angle for `Random`, the fixed rotation (checked to be about z) for
    /// `Fixed`.
    pub fn sample_planar<R: Rng + ?Sized>(&self, rng: &mut R) -> DQuat {
        match *self {
            Orientation::Random => random_planar_orientation(rng),
            Orientation::Fixed { quaternion } => quaternion.normalize(),
        }
    }

    fn validate(&self) -> Result<(), InsertError> {
        if let Orientation::Fixed { quaternion } = *self {
            if !quaternion.is_finite() || quaternion.length() < 1e-12 {
                return Err(InsertError::InvalidSpec(format!(
                    "fixed orientation must be a finite, non-zero quaternion, got {quaternion}"
                )));
            }
        }
        Ok(())
    }
}

fn default_attempts() -> u32 {
    1000
}

/// What [`pack()`] should do.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PackSpec {
    /// Where to place the bodies (every sphere fully inside).
    pub region: Region,
    /// How many bodies.
    pub target: PackTarget,
    /// Which bodies.
    pub mix: Mix,
    /// Initial centre-of-mass velocity of every body, world frame, m/s.
    #[serde(default)]
    pub velocity: DVec3,
    /// Orientations (default: uniformly random).
    #[serde(default)]
    pub orientation: Orientation,
    /// Random poses tried for one body before giving up (default 1000).
    #[serde(default = "default_attempts")]
    pub max_attempts_per_body: u32,
    /// Initial angular velocity of every body, world frame, rad/s.
    #[serde(default)]
    pub angular_velocity: DVec3,
    /// Degrees of freedom of the bodies by the index of their (unscaled)
    /// template in the mix; a template past the end is free.
    #[serde(default)]
    pub dof: Vec<crate::dof::Dof>,
    /// 2D insertion (`[domain] dimension = 2`): every centre of mass on the
    /// plane z = this (world frame, m), every body turned about z only
    /// (see the [module docs](super)); `None`: 3D.
    #[serde(default)]
    pub plane: Option<f64>,
}

/// What [`pack()`] did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PackReport {
    /// Number of bodies placed.
    pub placed: usize,
    /// Global ids of the placed bodies, in placement order.
    pub ids: Vec<u64>,
    /// Solid volume of the placed bodies, m³.
    pub solid_volume: f64,
    /// `solid_volume` / region volume (dimensionless).
    pub volume_fraction: f64,
    /// Poses tried in total.
    pub attempts: u64,
    /// Indices of scaled templates added to the world, in order.
    pub templates_added: Vec<u32>,
}

/// Places bodies in `spec.region` by random sequential addition (see the
/// [module docs](super)), deterministically for `seed`.
///
/// On success the bodies (and any scaled templates) are added to `world`;
/// on error the world is left unchanged. Errors: an invalid spec, a request
/// above [`PACKING_LIMIT`] of the region volume
/// ([`InsertError::RegionTooSmall`]), or a body that found no free pose in
/// `max_attempts_per_body` tries ([`InsertError::TargetNotReached`]).
pub fn pack(world: &mut World, spec: &PackSpec, seed: u64) -> Result<PackReport, InsertError> {
    spec.region.validate()?;
    spec.orientation.validate()?;
    if !spec.velocity.is_finite() {
        return Err(InsertError::InvalidSpec(format!(
            "velocity must be finite, got {}",
            spec.velocity
        )));
    }
    if spec.max_attempts_per_body == 0 {
        return Err(InsertError::InvalidSpec(
            "max_attempts_per_body must be at least 1".into(),
        ));
    }
    let mix = spec.mix.resolve(world)?;
    let place = Placement::of(&spec.region, &spec.orientation, spec.plane);
    place.check_plane(spec.velocity, spec.angular_velocity, mix.max_radius)?;
    let region_volume = spec.region.volume();
    let (requested_volume, target_desc) = match spec.target {
        PackTarget::Count(n) => (n as f64 * mix.mean_volume, format!("{n} bodies")),
        PackTarget::VolumeFraction(phi) => {
            if !(phi.is_finite() && phi > 0.0) {
                return Err(InsertError::InvalidSpec(format!(
                    "volume fraction must be > 0, got {phi}"
                )));
            }
            (phi * region_volume, format!("solid volume fraction {phi}"))
        }
    };
    if requested_volume > PACKING_LIMIT * region_volume {
        return Err(InsertError::RegionTooSmall {
            requested_volume,
            region_volume,
            ratio: requested_volume / region_volume,
            limit: PACKING_LIMIT,
        });
    }

    let mut occ = Occupancy::from_world(world, &spec.region, mix.max_radius);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut placed: Vec<(u32, f64, DVec3, DQuat)> = Vec::new();
    let mut solid_volume = 0.0;
    let mut attempts_total = 0u64;
    let mut buf = Vec::new();
    let done = |n: usize, v: f64| match spec.target {
        PackTarget::Count(c) => n >= c,
        PackTarget::VolumeFraction(phi) => v >= phi * region_volume,
    };
    while !done(placed.len(), solid_volume) {
        let (k, scale) = mix.sample(&mut rng);
        let base = mix.entries[k].template;
        let t = &world.templates[base as usize];
        let margin = t.min_radius * scale;
        let mut ok = false;
        for _ in 0..spec.max_attempts_per_body {
            attempts_total += 1;
            let Some((x, q)) = place.sample(&mut rng, margin) else {
                continue;
            };
            body_spheres(t, scale, x, q, &mut buf);
            if fits(&buf, &spec.region, world, &occ) {
                for &(c, r) in &buf {
                    occ.insert(c, r);
                }
                placed.push((base, scale, x, q));
                solid_volume += t.volume * scale.powi(3);
                ok = true;
                break;
            }
        }
        if !ok {
            return Err(InsertError::TargetNotReached {
                target: target_desc,
                placed: placed.len(),
                volume_fraction: solid_volume / region_volume,
                attempts: spec.max_attempts_per_body,
            });
        }
    }

    let mut cache = TemplateCache::default();
    let mut ids = Vec::with_capacity(placed.len());
    for &(base, scale, x, q) in &placed {
        let template = cache.resolve(world, base, scale)?;
        let mut init = BodyInit {
            velocity: spec.velocity,
            angular_velocity: spec.angular_velocity,
            ..BodyInit::at_rest(template, x, q)
        };
        spec.dof
            .get(base as usize)
            .copied()
            .unwrap_or_default()
            .apply(&mut init);
        ids.push(world.add_body(&init)?);
    }
    Ok(PackReport {
        placed: placed.len(),
        ids,
        solid_volume,
        volume_fraction: solid_volume / region_volume,
        attempts: attempts_total,
        templates_added: cache.entries.iter().map(|e| e.2).collect(),
    })
}
