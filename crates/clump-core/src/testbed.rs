//! Ready-made worlds for benchmarks, profiling and scaling studies.
//!
//! [`tetra_lattice_bed`] builds the material of the shared tetra-bed
//! benchmark (4-sphere tetrahedral clumps, r = 1 mm, edge 1.2 mm, ρ = 2500,
//! Hertz–Mindlin with LIGGGHTS damping and no tensile clamp, as LIGGGHTS'
//! default `limitForce off`, E = 5 MPa, ν = 0.3, e = 0.5, μ = 0.5, dt = 1e-5 s) as a bed of any size: clumps on a cubic lattice of pitch
//! [`LATTICE_PITCH`], periodic in x and y, above a floor at z = 0, at rest.
//! Because the box is periodic sideways, beds of different areas but the
//! same number of layers have the same local structure, which is what a
//! cost-per-sphere scaling study needs. [`tile_xy`] replicates a settled
//! periodic bed side by side, so a dense bed of a million spheres costs one
//! small settling run.

use crate::body::BodyInit;
use crate::boundary::Domain;
use crate::contact::ContactTable;
use crate::contact::{DampingLaw, Material, PairProperties};
use crate::multi_contact::MultiContact;
use crate::shape::{ClumpTemplate, Sphere};
use crate::wall::{Wall, WallMotion, WallShape};
use crate::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};

/// Lattice pitch, m: just above the clump's bounding diameter (3.47 mm), so
/// the clumps start apart.
pub const LATTICE_PITCH: f64 = 3.6e-3;

/// The benchmark's grain material.
pub fn tetra_material() -> Material {
    Material {
        youngs_modulus: 5e6,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

/// The benchmark's contact properties (LIGGGHTS damping, tensile normal
/// force allowed as with LIGGGHTS' default `limitForce off`, for comparisons).
pub fn tetra_contact() -> PairProperties {
    PairProperties {
        restitution: 0.5,
        friction: 0.5,
        damping: DampingLaw::Liggghts,
        tensile: true,
        ..PairProperties::default()
    }
}

/// The benchmark's template: 4 spheres of radius 1 mm on the vertices of a
/// regular tetrahedron with edge 1.2 mm.
pub fn tetra_template() -> ClumpTemplate {
    let h = 1.2e-3 / (2.0 * 2f64.sqrt());
    let s: Vec<Sphere> = [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]]
        .iter()
        .map(|c| Sphere {
            center: DVec3::from_array(*c) * h,
            radius: 1e-3,
        })
        .collect();
    ClumpTemplate::from_spheres("tetra", &s, tetra_material().density)
        .expect("the tetra template is valid")
}

/// `nx × ny × nz` tetra clumps at rest on a lattice (deterministic
/// orientations), periodic in x and y, with a floor at z = 0 and gravity
/// −9.81 m/s² along z. `skin`: the Verlet skin (m), `None` for the engine's
/// default. Run a few thousand steps to let it settle into a dense bed.
pub fn tetra_lattice_bed(nx: usize, ny: usize, nz: usize, skin: Option<f64>) -> World {
    lattice_bed(&[tetra_template()], nx, ny, nz, skin)
}

/// [`tetra_lattice_bed`] with the bodies of `templates` (body `k` of the
/// lattice, counted x first, has template `k mod templates.len()`), each
/// template no wider than the lattice pitch, of the tetra's material.
pub fn lattice_bed(
    templates: &[ClumpTemplate],
    nx: usize,
    ny: usize,
    nz: usize,
    skin: Option<f64>,
) -> World {
    let m = tetra_material();
    let mats = vec![m];
    let table = ContactTable::new(&mats, |_, _| tetra_contact()).expect("valid contact model");
    let (lx, ly) = (nx as f64 * LATTICE_PITCH, ny as f64 * LATTICE_PITCH);
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::new(0.0, 0.0, -0.001),
            hi: DVec3::new(lx, ly, (nz as f64 + 2.0) * LATTICE_PITCH),
            periodic: [true, true, false],
        },
        gravity: DVec3::new(0.0, 0.0, -9.81),
        dt: 1e-5,
        rotation: Default::default(),
        added_mass: AddedMass::default(),
        skin,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let ids: Vec<_> = templates
        .iter()
        .map(|t| w.add_template(t.clone(), 0).expect("material 0 exists"))
        .collect();
    w.add_wall(Wall {
        name: "floor".into(),
        shape: WallShape::Plane {
            point: DVec3::ZERO,
            normal: DVec3::Z,
        },
        material: 0,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    })
    .expect("one wall");
    let mut k = 0u64;
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let t = ids[k as usize % ids.len()];
                k += 1;
                let q = DQuat::from_euler(
                    glam::EulerRot::ZXZ,
                    k as f64 * 0.7,
                    k as f64 * 1.3,
                    k as f64 * 0.4,
                );
                let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.6) * LATTICE_PITCH;
                w.add_body(&BodyInit::at_rest(t, p, q))
                    .expect("template exists");
            }
        }
    }
    w
}

/// A world made of `kx × ky` copies of the periodic world `w` side by side
/// in x and y (world frame): the domain grows to `kx·L_x × ky·L_y`, and every
/// body is copied with its pose and velocities, shifted by whole periods.
/// Because `w` is periodic in x and y, the copies join seamlessly: every
/// contact of the tiled bed is a contact of `w` (contact histories start
/// afresh). Walls, templates, materials and settings are those of `w`.
///
/// # Panics
/// If `w` is not periodic in x and y, or `kx` or `ky` is zero.
pub fn tile_xy(w: &World, kx: usize, ky: usize) -> World {
    let dom = w.config.domain;
    assert!(
        dom.periodic[0] && dom.periodic[1],
        "tile_xy needs a bed periodic in x and y"
    );
    assert!(kx > 0 && ky > 0, "tile_xy needs at least one tile each way");
    let period = dom.hi - dom.lo;
    let mut config = w.config;
    config.domain.hi.x = dom.lo.x + kx as f64 * period.x;
    config.domain.hi.y = dom.lo.y + ky as f64 * period.y;
    let mut out = World::new(config, w.materials.clone(), w.contact_table.clone());
    for (t, m) in w.templates.iter().zip(w.templates.materials()) {
        out.add_template(t.clone(), *m)
            .expect("the template's material exists");
    }
    for wall in &w.walls {
        out.add_wall(wall.clone())
            .expect("the source world's walls are valid");
    }
    let b = &w.bodies;
    for ty in 0..ky {
        for tx in 0..kx {
            let shift = DVec3::new(tx as f64 * period.x, ty as f64 * period.y, 0.0);
            for i in 0..b.len() {
                let init = BodyInit {
                    template: b.template[i],
                    position: b.position[i] + shift,
                    orientation: b.orientation[i],
                    velocity: b.velocity[i],
                    angular_velocity: b.angular_velocity[i],
                    force_flag: b.force_flag[i],
                    torque_flag: b.torque_flag[i],
                    start_step: 0,
                };
                out.add_body(&init).expect("the template exists");
            }
        }
    }
    out
}

/// Every body's id and state (centre, velocity, angular momentum, angular
/// velocity, force, torque, orientation) as bits, in storage order: equal
/// vectors mean the same state bit for bit.
pub fn state_bits(w: &World) -> Vec<u64> {
    let b = &w.bodies;
    let mut out = Vec::with_capacity(b.len() * 23);
    for i in 0..b.len() {
        out.push(b.id[i]);
        for v in [
            b.position[i],
            b.velocity[i],
            b.angular_momentum[i],
            b.angular_velocity[i],
            b.force[i],
            b.torque[i],
        ] {
            out.extend(v.to_array().map(f64::to_bits));
        }
        out.extend(b.orientation[i].to_array().map(f64::to_bits));
    }
    out
}

/// Turns heat on in a testbed world (Batchelor & O'Brien conductance):
/// every material of conductivity `k` (W/(m K)) and specific heat `cp`
/// (J/(kg K)), every wall at `wall_t` (K), the bodies of every template at
/// `body_t` (K) with the volumetric source `q` (W/m³).
pub fn heat_on(w: &mut World, k: f64, cp: f64, wall_t: f64, body_t: f64, q: f64) {
    use crate::heat::{Conductance, HeatModel, ThermalMaterial};
    let thermal = Some(ThermalMaterial {
        conductivity: k,
        specific_heat: cp,
    });
    w.enable_heat(HeatModel {
        conductance: Conductance::BatchelorObrien,
        materials: vec![thermal; w.materials.len()],
        wall_temperature: vec![Some(wall_t); w.walls.len()],
        template_temperature: vec![body_t; w.templates.len()],
        template_source: vec![q; w.templates.len()],
    })
    .expect("valid heat settings");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tiling a periodic bed 2 × 3 gives six times its contacts: every copy
    /// sees the same neighbours across the seams as the original across
    /// its periodic boundaries.
    #[test]
    fn tiled_bed_has_the_tile_contacts_times_the_tile_count() {
        let mut w = tetra_lattice_bed(4, 4, 3, None);
        w.run(3000).unwrap();
        let mut tiled = tile_xy(&w, 2, 3);
        assert_eq!(tiled.bodies.len(), 6 * w.bodies.len());
        w.prepare().unwrap();
        tiled.prepare().unwrap();
        let (a, b) = (w.thermo(), tiled.thermo());
        assert!(a.pair_contacts > 0);
        assert_eq!(b.pair_contacts, 6 * a.pair_contacts);
        assert_eq!(b.wall_contacts, 6 * a.wall_contacts);
    }
}

/// Fault injection for tests: sets body `i`'s velocity (m/s, world frame)
/// past the steering methods' checks, so that a test can plant a value no
/// driver could (a NaN) and watch the health check find it.
pub fn inject_body_velocity(w: &mut World, i: usize, v: DVec3) {
    w.bodies.velocity[i] = v;
}

/// Runs `f` on `ranks` in-process ranks (one thread each, with its
/// [`crate::partition::ThreadComm`]) on `make()`'s world split over them;
/// returns each rank's result, in rank order.
pub fn on_thread_ranks<T: Send + 'static>(
    ranks: usize,
    make: fn() -> World,
    f: fn(&mut World) -> T,
) -> Vec<T> {
    let handles: Vec<_> = crate::partition::ThreadComm::group(ranks)
        .into_iter()
        .map(|comm| {
            std::thread::spawn(move || {
                let mut w = make();
                w.partition(Box::new(comm));
                f(&mut w)
            })
        })
        .collect();
    handles.into_iter().map(|h| h.join().unwrap()).collect()
}
