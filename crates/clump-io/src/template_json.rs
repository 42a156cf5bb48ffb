//! The JSON objects `clump template --json` prints (shared with the Python
//! package, whose `Template.mass_properties()` returns the same keys and
//! values): the mass properties of a template, and the fidelity of one
//! generated from a mesh.

use clump_core::shape::from_mesh::Fidelity;
use clump_core::shape::MassProperties;

fn rows(m: &glam::DMat3) -> [[f64; 3]; 3] {
    [
        m.row(0).to_array(),
        m.row(1).to_array(),
        m.row(2).to_array(),
    ]
}

/// The mass properties as JSON (exactly the documented keys; SI units,
/// input frame, matrices as arrays of rows).
pub fn mass_properties_json(p: &MassProperties) -> serde_json::Value {
    serde_json::json!({
        "volume": p.volume,
        "mass": p.mass,
        "center_of_mass": p.center_of_mass.to_array(),
        "inertia": rows(&p.inertia),
        "principal_moments": p.principal_moments.to_array(),
        "principal_axes": rows(&p.principal_axes),
        "naive_volume": p.naive_volume,
        "naive_principal_moments": p.naive_principal_moments.to_array(),
        "relative_error_bound": p.relative_error_bound,
    })
}

/// The fidelity report of a template of `n` spheres generated from a mesh
/// in `seconds`, as JSON (SI units, mesh frame, unit density).
pub fn fidelity_json(f: &Fidelity, n: usize, seconds: f64) -> serde_json::Value {
    serde_json::json!({
        "spheres": n,
        "seconds": seconds,
        "mesh_volume": f.mesh.volume,
        "mesh_center_of_mass": f.mesh.center_of_mass.to_array(),
        "mesh_principal_moments": f.mesh.principal_moments.to_array(),
        "clump_volume": f.clump.volume,
        "clump_center_of_mass": f.clump.center_of_mass.to_array(),
        "clump_principal_moments": f.clump.principal_moments.to_array(),
        "volume_error": f.volume_error,
        "centroid_error": f.centroid_error,
        "moment_errors": f.moment_errors.to_array(),
        "axis_errors_deg": f.axis_errors_deg.to_array(),
        "mean_surface_deviation": f.mean_surface_deviation,
        "max_surface_deviation": f.max_surface_deviation,
        "surface_samples": f.samples,
    })
}
