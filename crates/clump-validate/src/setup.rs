//! Shared set-up of the engine-level cases: worlds with one particle
//! material and one rigid wall material, simple templates, and an impact
//! recorder.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::ContactTable;
use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};

/// Material index of the particles in worlds built by [`world`].
pub const PARTICLE: u16 = 0;
/// Material index of the rigid walls in worlds built by [`world`].
pub const RIGID: u16 = 1;

/// A world with the particle material (index [`PARTICLE`]) and a rigid wall
/// material (index [`RIGID`], `E = ∞`), `props` for every pair; `gravity`
/// in the world frame (m/s²), `dt` in s.
pub fn world(
    particle: Material,
    props: PairProperties,
    dt: f64,
    domain: Domain,
    gravity: DVec3,
) -> Result<World, String> {
    let rigid = Material {
        youngs_modulus: f64::INFINITY,
        poisson_ratio: particle.poisson_ratio,
        density: 1.0,
    };
    let mats = vec![particle, rigid];
    let table = ContactTable::new(&mats, |_, _| props).map_err(|e| e.to_string())?;
    let config = WorldConfig {
        domain,
        gravity,
        dt,
        rotation: RotationScheme::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    Ok(World::new(config, mats, table))
}

/// A cube `[−half, half]³` (m) with no periodic axis.
pub fn open_box(half: f64) -> Domain {
    Domain {
        lo: DVec3::splat(-half),
        hi: DVec3::splat(half),
        periodic: [false; 3],
    }
}

/// Pair properties with restitution `e` and sliding friction `mu`, Hertz,
/// exact damping, no rolling resistance.
pub fn props(e: f64, mu: f64) -> PairProperties {
    PairProperties {
        restitution: e,
        friction: mu,
        rolling_friction: 0.0,
        ..PairProperties::default()
    }
}

/// A material from Young's modulus (Pa), Poisson ratio and density (kg/m³).
pub fn material(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> Material {
    Material {
        youngs_modulus,
        poisson_ratio,
        density,
    }
}

/// `n` coincident spheres of radius `r` (m) at the body origin.
pub fn coincident_spheres(n: usize, r: f64, density: f64) -> Result<ClumpTemplate, String> {
    let s = vec![
        Sphere {
            center: DVec3::ZERO,
            radius: r
        };
        n
    ];
    ClumpTemplate::from_spheres("coincident", &s, density).map_err(|e| e.to_string())
}

/// Two spheres of radius `r` with centres at `±half_gap` on the input x
/// axis (the template's principal frame puts that axis on body x, the
/// smallest moment).
pub fn dimer(r: f64, half_gap: f64, density: f64) -> Result<ClumpTemplate, String> {
    let s: Vec<Sphere> = [-half_gap, half_gap]
        .iter()
        .map(|&x| Sphere {
            center: DVec3::new(x, 0.0, 0.0),
            radius: r,
        })
        .collect();
    ClumpTemplate::from_spheres("dimer", &s, density).map_err(|e| e.to_string())
}

/// A regular tetrahedron of four spheres of radius `r` (m), centres at
/// distance `edge` (m) from each other.
pub fn tetra(r: f64, edge: f64, density: f64) -> Result<ClumpTemplate, String> {
    let h = edge / (2.0 * 2f64.sqrt());
    let s: Vec<Sphere> = [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]]
        .iter()
        .map(|c| Sphere {
            center: DVec3::from_array(*c) * h,
            radius: r,
        })
        .collect();
    ClumpTemplate::from_spheres("tetra", &s, density).map_err(|e| e.to_string())
}

/// A body of `template` at `x` with orientation `q`, velocity `v` and
/// angular velocity `w` (world frame).
pub fn body(template: u32, x: DVec3, q: DQuat, v: DVec3, w: DVec3) -> BodyInit {
    BodyInit {
        velocity: v,
        angular_velocity: w,
        ..BodyInit::at_rest(template, x, q)
    }
}

/// A fixed wall of the rigid material.
pub fn wall(name: &str, shape: WallShape) -> Wall {
    Wall {
        name: name.into(),
        shape,
        material: RIGID,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    }
}

/// A fixed plane through `point` with unit `normal` (into the particles).
pub fn plane(point: DVec3, normal: DVec3) -> Wall {
    wall("plane", WallShape::Plane { point, normal })
}

/// What an impact did: the largest overlap (m), the largest contact force
/// (N), the contact duration (s) and the sampled history
/// `(time since first contact s, overlap m, force N)`.
#[derive(Debug, Default, Clone)]
pub struct Impact {
    /// Largest overlap, m.
    pub max_overlap: f64,
    /// Largest contact force magnitude on the watched body, N.
    pub max_force: f64,
    /// Steps in contact × dt, s.
    pub duration: f64,
    /// `(t, δ, |F|)` samples while in contact.
    pub history: Vec<[f64; 3]>,
}

/// Steps `w` until a contact has started and ended (or `max_steps` steps),
/// watching body `id` whose smallest sphere radius is `radius` (m): the
/// overlap is the engine's largest overlap ratio × `radius`, the force the
/// body's total force less its weight.
pub fn run_impact(w: &mut World, id: u64, radius: f64, max_steps: usize) -> Result<Impact, String> {
    let mut imp = Impact::default();
    let mut steps_in_contact = 0usize;
    for _ in 0..max_steps {
        // every step's contact count is read: an event at every step
        w.run(1).map_err(|e| e.to_string())?;
        let t = w.thermo();
        if t.pair_contacts + t.wall_contacts == 0 {
            if steps_in_contact > 0 {
                break;
            }
            continue;
        }
        steps_in_contact += 1;
        let b = w.body_index(id).ok_or("body lost")?;
        let overlap = t.max_overlap_ratio * radius;
        let force = (w.bodies().force[b] - w.bodies().mass[b] * w.config.gravity).length();
        imp.max_overlap = imp.max_overlap.max(overlap);
        imp.max_force = imp.max_force.max(force);
        imp.history
            .push([steps_in_contact as f64 * w.config.dt, overlap, force]);
    }
    imp.duration = steps_in_contact as f64 * w.config.dt;
    Ok(imp)
}

/// Velocity and angular velocity (world frame) of body `id`.
pub fn motion(w: &World, id: u64) -> Result<(DVec3, DVec3), String> {
    let b = w.body_index(id).ok_or("body lost")?;
    Ok((w.bodies().velocity[b], w.bodies().angular_velocity[b]))
}

/// Hertz theory for an impact at relative normal speed `v` (m/s):
/// `(δmax m, Fmax N, t_c s)` with `E*` (Pa), `R*` (m), `m*` (kg)
/// (REFERENCE.md §3).
pub fn hertz_impact(e_star: f64, r_star: f64, m_star: f64, v: f64) -> (f64, f64, f64) {
    let dmax = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    let fmax = 4.0 / 3.0 * e_star * r_star.sqrt() * dmax.powf(1.5);
    (dmax, fmax, 2.9432 * dmax / v)
}

/// `E*` of two materials (a rigid one has `E = ∞`), Pa.
pub fn effective_modulus(a: &Material, b: &Material) -> f64 {
    let c = |m: &Material| {
        if m.youngs_modulus.is_infinite() {
            0.0
        } else {
            (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus
        }
    };
    1.0 / (c(a) + c(b))
}

/// Mass of a sphere of radius `r` (m) and density `rho` (kg/m³), kg.
pub fn sphere_mass(r: f64, rho: f64) -> f64 {
    rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)
}
