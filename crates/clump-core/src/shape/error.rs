//! Errors of template construction and mass-property computation.

use serde::{Deserialize, Serialize};

/// Why a template or its mass properties could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error, Serialize, Deserialize)]
pub enum ShapeError {
    /// The template has no sphere.
    #[error("empty template: at least one sphere is needed")]
    EmptyTemplate,
    /// A sphere has a zero or negative radius.
    #[error("sphere {index}: radius must be > 0, found {radius} m")]
    NonPositiveRadius {
        /// Index of the sphere in the input list (0-based).
        index: usize,
        /// The offending radius, m.
        radius: f64,
    },
    /// A sphere has a NaN or infinite coordinate or radius.
    #[error(
        "sphere {index}: centre and radius must be finite, found centre {center:?} m, radius {radius} m"
    )]
    NonFiniteSphere {
        /// Index of the sphere in the input list (0-based).
        index: usize,
        /// The offending centre, m (input frame).
        center: [f64; 3],
        /// The radius, m.
        radius: f64,
    },
    /// Density is zero, negative or not finite.
    #[error("density must be finite and > 0, found {density} kg/m³")]
    InvalidDensity {
        /// The offending density, kg/m³.
        density: f64,
    },
    /// An explicit mass is zero, negative or not finite.
    #[error("mass must be finite and > 0, found {mass} kg")]
    InvalidMass {
        /// The offending mass, kg.
        mass: f64,
    },
    /// An explicit inertia tensor is not a valid inertia tensor (not finite,
    /// not symmetric, not positive definite or violating the triangle
    /// inequality I1 + I2 ≥ I3 of principal moments).
    #[error("invalid inertia tensor: {reason}")]
    InvalidInertia {
        /// What is wrong, in words.
        reason: String,
    },
    /// A scale factor is zero, negative or not finite.
    #[error("scale factor must be finite and > 0, found {scale}")]
    InvalidScale {
        /// The offending scale factor (dimensionless).
        scale: f64,
    },
    /// The mass properties came out infinite or NaN: the coordinates are
    /// so large that their squares overflow (|x| above about 1e150 m).
    #[error("the mass properties are not finite ({what}): sphere coordinates or radii too large for f64 (centres up to {extent:e} m from the origin)")]
    NotFinite {
        /// Which quantity, with its value.
        what: String,
        /// Largest distance of a sphere's far side from the origin, m.
        extent: f64,
    },
    /// The adaptive quadrature did not reach the requested accuracy (only for
    /// pathological inputs, e.g. many thousands of spheres).
    #[error(
        "mass-property quadrature did not converge: estimated relative error {relative_error_bound:e} > 1e-6"
    )]
    NotConverged {
        /// The estimated relative error reached.
        relative_error_bound: f64,
    },
}
