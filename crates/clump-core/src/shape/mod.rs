//! Clump templates: rigid bodies made of overlapping spheres (the multi-sphere
//! method), and their exact mass properties.
//!
//! A *template* is a list of [`Sphere`]s (centre and radius, m) given in some
//! *input frame* chosen by the user, plus a density (kg/m³) or a mass (kg).
//! [`mass_properties()`] integrates over the **union** of the spheres, so that
//! overlapping regions are counted once (unlike the naive sums of
//! docs/theory.md T-9, which are also reported for comparison).
//! [`ClumpTemplate`] re-expresses the template in its *principal body frame*:
//! origin at the centre of mass, axes along the principal axes of inertia,
//! right-handed.
//!
//! Method (see [`union_integral`] for details): the union is sliced along the
//! input-frame z axis; each slice is a union of discs whose area and first and
//! second area moments are computed exactly with Green's theorem on the
//! uncovered boundary arcs; the slice moments are integrated over z with
//! adaptive Gauss–Kronrod quadrature on sub-intervals split at every height
//! where the topology of the cross-section changes. The result is deterministic
//! and accurate to about 1e-10 relative; an estimate of the error is reported
//! in [`MassProperties::relative_error_bound`].
//!
//! Submodules:
//! - `sphere` — the [`Sphere`] type;
//! - [`error`] — [`ShapeError`];
//! - [`mass_properties`](mod@mass_properties) — [`MassProperties`] and [`mass_properties()`];
//! - [`template`] — [`ClumpTemplate`] (principal body frame);
//! - [`builtin`] — a few built-in shapes;
//! - [`eigen`] — symmetric 3×3 eigen-solver with a deterministic principal frame;
//! - [`union_integral`] and [`disc_union`] — the exact union integrals.

pub mod builtin;
pub mod disc_union;
pub mod eigen;
pub mod error;
pub mod from_mesh;
pub mod mass_properties;
pub mod mobility;
pub mod planar;
mod progress;
mod set;
mod slabs;
mod sphere_grid;
pub mod template;
pub mod template_sphere;
pub mod union_integral;

pub use builtin::{cube_octet, rod, single_sphere, tetrahedron};
pub use eigen::{principal_frame, symmetric_eigen};
pub use error::ShapeError;
pub use mass_properties::{mass_properties, naive_mass_properties, MassProperties};
pub use set::TemplateSet;
pub use sphere_grid::union_sphere_indices;
pub use template::ClumpTemplate;
pub use template_sphere::Sphere;
