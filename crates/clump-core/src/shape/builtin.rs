//! Built-in template shapes. Each returns spheres (m) in the shape's own
//! frame, centred on the origin (the centroid of the sphere centres).

use glam::DVec3;

use super::template_sphere::Sphere;

/// One sphere of radius `radius` (m) at the origin.
pub fn single_sphere(radius: f64) -> Vec<Sphere> {
    vec![Sphere::new(DVec3::ZERO, radius)]
}

/// `n` spheres of radius `radius` (m) on the x axis, `spacing` (m) apart
/// centre to centre, centred on the origin.
pub fn rod(n: usize, radius: f64, spacing: f64) -> Vec<Sphere> {
    let half = 0.5 * (n.saturating_sub(1)) as f64;
    (0..n)
        .map(|i| Sphere::new(DVec3::new((i as f64 - half) * spacing, 0.0, 0.0), radius))
        .collect()
}

/// 4 spheres of radius `radius` (m) on the vertices of a regular tetrahedron
/// of edge `edge` (m), centroid at the origin; vertices at
/// (edge / 2√2) · (±1, ±1, ±1) with an even number of minus signs.
pub fn tetrahedron(radius: f64, edge: f64) -> Vec<Sphere> {
    let s = edge / (2.0 * std::f64::consts::SQRT_2);
    [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ]
    .iter()
    .map(|p| Sphere::new(DVec3::from_array(*p) * s, radius))
    .collect()
}

/// 8 spheres of radius `radius` (m) on the corners of an axis-aligned cube of
/// edge `edge` (m) centred on the origin.
pub fn cube_octet(radius: f64, edge: f64) -> Vec<Sphere> {
    let h = 0.5 * edge;
    let mut v = Vec::with_capacity(8);
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                v.push(Sphere::new(DVec3::new(sx * h, sy * h, sz * h), radius));
            }
        }
    }
    v
}
