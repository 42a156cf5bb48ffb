//! Cohesion against values from outside the code: LIGGGHTS' own
//! `cohesion sjkr` run side by side (fixtures `sjkr_wall.*`, `sjkr_pair.*`
//! in `crates/clump-core/tests/fixtures/liggghts`), and JKR against its
//! closed forms (Johnson, Kendall & Roberts 1971; Thornton & Ning 1998).

use crate::liggghts::table;
use crate::setup::{body, coincident_spheres, open_box, plane, world, PARTICLE};
use clump_core::contact::{CohesionLaw, DampingLaw, Material, PairProperties};
use clump_core::world::World;
use glam::{DQuat, DVec3};

/// The material and contact of the SJKR fixtures: E = 10 MPa, ν = 0.3,
/// ρ = 2500 kg/m³; e = 0.5, μ = 0.5, LIGGGHTS damping, `limitForce off`,
/// `cohesionEnergyDensity` 2·10⁵ J/m³.
pub fn sjkr_contact() -> (Material, PairProperties) {
    let mat = Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    };
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.5,
        damping: DampingLaw::Liggghts,
        tensile: true,
        cohesion: CohesionLaw::Sjkr {
            energy_density: 2e5,
        },
        ..PairProperties::default()
    };
    (mat, props)
}

/// A world with the SJKR fixtures' contact, `dt` = 1e-6 s, gravity `g`
/// (m/s², world), no walls.
fn sjkr_world(g: DVec3) -> Result<World, String> {
    let (mat, props) = sjkr_contact();
    world(mat, props, 1e-6, open_box(0.05), g)
}

/// Adds a sphere of radius `r` (m) at `x` (m) moving at `v` (m/s).
fn add_sphere(w: &mut World, r: f64, x: DVec3, v: DVec3) -> Result<u64, String> {
    let t = coincident_spheres(1, r, w.materials[0].density)?;
    let t = w.add_template(t, PARTICLE).map_err(|e| e.to_string())?;
    w.add_body(&body(t, x, DQuat::IDENTITY, v, DVec3::ZERO))
        .map_err(|e| e.to_string())
}

/// Body `id`'s position and velocity (m, m/s, world).
fn motion(w: &World, id: u64) -> (DVec3, DVec3) {
    let b = w.body_index(id).expect("body");
    (w.bodies.position[b], w.bodies.velocity[b])
}

/// `sjkr_wall.in`: a 2 mm sphere dropped at 0.3 m/s onto a plane of its
/// own material, LIGGGHTS' rows `t z vz fz` every 20 steps and Clump's
/// `[z, vz]` at the same steps.
pub fn sjkr_wall() -> Result<(Vec<Vec<f64>>, Vec<[f64; 2]>), String> {
    let rows = table(include_str!(
        "../../clump-core/tests/fixtures/liggghts/sjkr_wall.dat"
    ));
    let mut w = sjkr_world(DVec3::new(0.0, 0.0, -9.81))?;
    let mut floor = plane(DVec3::ZERO, DVec3::Z);
    floor.material = PARTICLE;
    w.add_wall(floor).map_err(|e| e.to_string())?;
    let id = add_sphere(
        &mut w,
        0.002,
        DVec3::new(0.0, 0.0, 0.0021),
        DVec3::new(0.0, 0.0, -0.3),
    )?;
    let mut out = Vec::with_capacity(rows.len());
    for _ in &rows {
        w.run(20).map_err(|e| e.to_string())?;
        let (x, v) = motion(&w, id);
        out.push([x.z, v.z]);
    }
    Ok((rows, out))
}

/// `sjkr_pair.in`: spheres of 2 and 1 mm meeting head-on at 0.2 m/s each,
/// no gravity; LIGGGHTS' rows `t x1 vx1 x2 vx2 fx1` every 20 steps and
/// Clump's `[x1, vx1, x2, vx2]` at the same steps.
pub fn sjkr_pair() -> Result<(Vec<Vec<f64>>, Vec<[f64; 4]>), String> {
    let rows = table(include_str!(
        "../../clump-core/tests/fixtures/liggghts/sjkr_pair.dat"
    ));
    let mut w = sjkr_world(DVec3::ZERO)?;
    let a = add_sphere(
        &mut w,
        0.002,
        DVec3::new(-0.0021, 0.0, 0.0),
        DVec3::new(0.2, 0.0, 0.0),
    )?;
    let b = add_sphere(
        &mut w,
        0.001,
        DVec3::new(0.0011, 0.0, 0.0),
        DVec3::new(-0.2, 0.0, 0.0),
    )?;
    let mut out = Vec::with_capacity(rows.len());
    for _ in &rows {
        w.run(20).map_err(|e| e.to_string())?;
        let ((xa, va), (xb, vb)) = (motion(&w, a), motion(&w, b));
        out.push([xa.x, va.x, xb.x, vb.x]);
    }
    Ok((rows, out))
}

/// Largest deviation of Clump's columns from LIGGGHTS' (`cols[k]` is the
/// LIGGGHTS column of Clump's value `k`), relative to each column's
/// largest magnitude.
pub fn deviation<const N: usize>(rows: &[Vec<f64>], clump: &[[f64; N]], cols: [usize; N]) -> f64 {
    let mut worst = 0.0f64;
    for (k, &c) in cols.iter().enumerate() {
        let scale = rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        for (r, s) in rows.iter().zip(clump) {
            worst = worst.max((s[k] - r[c]).abs() / scale);
        }
    }
    worst
}
