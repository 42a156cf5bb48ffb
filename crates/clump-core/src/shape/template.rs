//! [`ClumpTemplate`]: a template re-expressed in its principal body frame.

use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

use super::error::ShapeError;
use super::mass_properties::{mass_properties, MassProperties};
use super::template_sphere::Sphere;

/// A clump template in its principal body frame: centre of mass at the origin,
/// axes along the principal axes of inertia (ascending moments along body
/// x, y, z), right-handed. SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClumpTemplate {
    /// Name of the template (free text, e.g. the file it came from).
    pub name: String,
    /// The spheres, **body frame** (centres relative to the centre of mass,
    /// along the principal axes), m, in input order. Every input sphere is
    /// kept (also duplicates and spheres inside others, which the mass
    /// properties count once); see
    /// [`union_sphere_indices`](super::union_sphere_indices) to drop them.
    pub spheres: Vec<Sphere>,
    /// Mass, kg.
    pub mass: f64,
    /// Volume of the union of the spheres, m³.
    pub volume: f64,
    /// Density, kg/m³ (given, or mass / volume for [`ClumpTemplate::with_mass`]).
    pub density: f64,
    /// Principal moments of inertia, kg m², body frame (diagonal of the
    /// body-frame inertia tensor), ascending.
    pub principal_inertia: DVec3,
    /// Bounding radius about the centre of mass: max over spheres of
    /// |centre| + radius, m.
    pub bounding_radius: f64,
    /// Smallest sphere radius, m.
    pub min_radius: f64,
    /// Largest sphere radius, m.
    pub max_radius: f64,
    /// Centre of mass in the input frame, m.
    pub input_center_of_mass: DVec3,
    /// Rotation taking input-frame vectors to body-frame vectors:
    /// `c_body = input_to_body * (c_input − input_center_of_mass)`.
    pub input_to_body: DQuat,
    /// Full mass properties, input frame.
    pub properties: MassProperties,
}

impl ClumpTemplate {
    /// Template from spheres (m, input frame) at uniform `density` (kg/m³).
    pub fn from_spheres(name: &str, spheres: &[Sphere], density: f64) -> Result<Self, ShapeError> {
        let props = mass_properties(spheres, density)?;
        Ok(Self::from_properties(name, spheres, density, props))
    }

    /// Template from spheres (m, input frame) with a given total `mass` (kg);
    /// the density is derived as mass / volume of the union.
    pub fn with_mass(name: &str, spheres: &[Sphere], mass: f64) -> Result<Self, ShapeError> {
        if !mass.is_finite() || mass <= 0.0 {
            return Err(ShapeError::InvalidMass { mass });
        }
        let unit = mass_properties(spheres, 1.0)?;
        let density = mass / unit.volume;
        let mut props = unit;
        props.mass = mass;
        props.inertia *= density;
        props.principal_moments *= density;
        props.naive_principal_moments *= density;
        Ok(Self::from_properties(name, spheres, density, props))
    }

    /// Template with explicit mass (kg) and inertia tensor (kg m², about the
    /// centre of mass, **input frame**) overriding the computed ones; the
    /// centre of mass and volume are computed from the spheres, the principal
    /// frame from `inertia_input`. `density` (kg/m³) is stored as given.
    pub fn with_override(
        name: &str,
        spheres: &[Sphere],
        density: f64,
        mass: f64,
        inertia_input: DMat3,
    ) -> Result<Self, ShapeError> {
        let props = mass_properties(spheres, density)?.with_override(mass, inertia_input)?;
        Ok(Self::from_properties(name, spheres, density, props))
    }

    /// [`Self::with_override`] with a given centre of mass `com` (m, input
    /// frame) as well: `inertia_input` is taken about `com`, and the body
    /// frame's origin is `com` (LIGGGHTS templates that state their own
    /// centre of mass). The volume is still that of the spheres' union.
    pub fn with_override_about(
        name: &str,
        spheres: &[Sphere],
        density: f64,
        mass: f64,
        inertia_input: DMat3,
        com: DVec3,
    ) -> Result<Self, ShapeError> {
        let mut props = mass_properties(spheres, density)?.with_override(mass, inertia_input)?;
        props.center_of_mass = com;
        Ok(Self::from_properties(name, spheres, density, props))
    }

    /// Builds the body-frame template from already computed properties.
    pub(super) fn from_properties(
        name: &str,
        spheres: &[Sphere],
        density: f64,
        props: MassProperties,
    ) -> Self {
        let rot = props.principal_axes; // rows = axes: input → body
        let input_to_body = DQuat::from_mat3(&rot).normalize();
        let com = props.center_of_mass;
        let body: Vec<Sphere> = spheres
            .iter()
            .map(|s| Sphere::new(rot * (s.center - com), s.radius))
            .collect();
        let bounding_radius = body
            .iter()
            .map(|s| s.center.length() + s.radius)
            .fold(0.0, f64::max);
        let min_radius = body.iter().map(|s| s.radius).fold(f64::INFINITY, f64::min);
        let max_radius = body.iter().map(|s| s.radius).fold(0.0, f64::max);
        Self {
            name: name.to_string(),
            spheres: body,
            mass: props.mass,
            volume: props.volume,
            density,
            principal_inertia: props.principal_moments,
            bounding_radius,
            min_radius,
            max_radius,
            input_center_of_mass: com,
            input_to_body,
            properties: props,
        }
    }

    /// The template with all lengths multiplied by `s` (> 0) at the same
    /// density: volume and mass × s³, inertia × s⁵, frames unchanged. Exact
    /// (no re-integration).
    ///
    /// # Panics
    /// If `s` is not finite and > 0.
    pub fn scaled(&self, s: f64) -> Self {
        assert!(
            s.is_finite() && s > 0.0,
            "scale factor must be finite and > 0, got {s}"
        );
        let (s3, s5) = (s * s * s, s.powi(5));
        let mut p = self.properties;
        p.volume *= s3;
        p.mass *= s3;
        p.center_of_mass *= s;
        p.inertia *= s5;
        p.principal_moments *= s5;
        p.naive_volume *= s3;
        p.naive_principal_moments *= s5;
        Self {
            name: self.name.clone(),
            spheres: self
                .spheres
                .iter()
                .map(|sp| Sphere::new(sp.center * s, sp.radius * s))
                .collect(),
            mass: self.mass * s3,
            volume: self.volume * s3,
            density: self.density,
            principal_inertia: self.principal_inertia * s5,
            bounding_radius: self.bounding_radius * s,
            min_radius: self.min_radius * s,
            max_radius: self.max_radius * s,
            input_center_of_mass: self.input_center_of_mass * s,
            input_to_body: self.input_to_body,
            properties: p,
        }
    }

    /// Rotation taking body-frame vectors to input-frame vectors (inverse of
    /// [`ClumpTemplate::input_to_body`]).
    pub fn body_to_input(&self) -> DQuat {
        self.input_to_body.conjugate()
    }
}
