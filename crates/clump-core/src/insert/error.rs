//! Errors of the insertion module.

use crate::world::WorldError;
use thiserror::Error;

/// Why bodies could not be inserted.
#[derive(Debug, Error)]
pub enum InsertError {
    /// The insertion specification is invalid (bad region, empty mix, …).
    #[error("invalid insertion: {0}")]
    InvalidSpec(String),
    /// The requested solid volume exceeds what the region can possibly hold.
    #[error(
        "region cannot hold the requested bodies: they need a solid volume of {requested_volume:.6e} m³, \
         {ratio:.3} of the region volume {region_volume:.6e} m³, above the packing limit {limit:.2} \
         (random sequential addition realistically reaches about 0.38); use a larger region or fewer bodies"
    )]
    RegionTooSmall {
        /// Requested (expected) solid volume, m³.
        requested_volume: f64,
        /// Region volume, m³.
        region_volume: f64,
        /// requested_volume / region_volume.
        ratio: f64,
        /// The limit that was exceeded (dimensionless volume fraction).
        limit: f64,
    },
    /// Random sequential addition gave up before reaching the target.
    #[error(
        "could not reach the packing target ({target}): placed {placed} bodies (achieved solid volume \
         fraction {volume_fraction:.4}) before a body failed to fit after {attempts} attempts; \
         use a larger region, a lower count or volume fraction, or more attempts per body"
    )]
    TargetNotReached {
        /// Human-readable target ("300 bodies", "volume fraction 0.3").
        target: String,
        /// Bodies placed before giving up.
        placed: usize,
        /// Solid volume fraction of the placed bodies in the region (dimensionless).
        volume_fraction: f64,
        /// Attempts made for the body that did not fit.
        attempts: u32,
    },
    /// The world rejected a template or body.
    #[error("{0}")]
    World(#[from] WorldError),
}
