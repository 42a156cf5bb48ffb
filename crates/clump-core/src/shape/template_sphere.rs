//! The [`Sphere`] of a template, and helpers on lists of spheres.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::error::ShapeError;

/// One sphere of a clump template.
///
/// The frame of `center` depends on context and is stated where a `Sphere`
/// is used: the user's *input frame* for the arguments of
/// [`mass_properties`](super::mass_properties()) and
/// [`ClumpTemplate::from_spheres`](super::ClumpTemplate::from_spheres), the
/// principal *body frame* in [`ClumpTemplate::spheres`](super::ClumpTemplate::spheres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sphere {
    /// Centre of the sphere, m (frame: see the type's documentation).
    pub center: DVec3,
    /// Radius, m (> 0).
    pub radius: f64,
}

impl Sphere {
    /// A sphere with centre `center` (m) and radius `radius` (m).
    pub fn new(center: DVec3, radius: f64) -> Self {
        Self { center, radius }
    }

    /// Volume of the sphere alone, m³: (4/3)πr³.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }
}

/// Checks that a list of spheres describes a valid template: non-empty,
/// finite centres and radii, radii > 0.
pub fn validate_spheres(spheres: &[Sphere]) -> Result<(), ShapeError> {
    if spheres.is_empty() {
        return Err(ShapeError::EmptyTemplate);
    }
    for (index, s) in spheres.iter().enumerate() {
        if !s.center.is_finite() || !s.radius.is_finite() {
            return Err(ShapeError::NonFiniteSphere {
                index,
                center: [s.center.x, s.center.y, s.center.z],
                radius: s.radius,
            });
        }
        if s.radius <= 0.0 {
            return Err(ShapeError::NonPositiveRadius {
                index,
                radius: s.radius,
            });
        }
    }
    Ok(())
}
