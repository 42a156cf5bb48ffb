//! Heat transfer (docs/theory.md T-53 … T-57) against closed forms: two
//! bodies relaxing to a common temperature, a chain of spheres between a
//! hot and a cold wall at steady state (series conductances), and the
//! effective conductivity of sphere lattices against Batchelor & O'Brien's
//! packed-bed relation; conservation of heat; thread-count independence.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{ContactTable, Material, PairProperties};
use clump_core::heat::{Conductance, HeatModel, ThermalMaterial};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

/// Particle materials 0 and 1, rigid wall material 2.
const K: [f64; 3] = [2.0, 30.0, 50.0];
const CP: [f64; 3] = [800.0, 500.0, 1.0];
const RHO: [f64; 2] = [2500.0, 7800.0];

fn world(dt: f64, domain: Domain) -> World {
    let mats = vec![
        Material {
            youngs_modulus: 1e8,
            poisson_ratio: 0.3,
            density: RHO[0],
        },
        Material {
            youngs_modulus: 2e8,
            poisson_ratio: 0.25,
            density: RHO[1],
        },
        Material::rigid(),
    ];
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let config = WorldConfig {
        domain,
        gravity: DVec3::ZERO,
        dt,
        rotation: Default::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    World::new(config, mats, table)
}

fn open(half: f64) -> Domain {
    Domain {
        lo: DVec3::splat(-half),
        hi: DVec3::splat(half),
        periodic: [false; 3],
    }
}

fn model(conductance: Conductance, temps: Vec<f64>, walls: Vec<Option<f64>>) -> HeatModel {
    let n = temps.len();
    HeatModel {
        conductance,
        materials: (0..3)
            .map(|m| {
                Some(ThermalMaterial {
                    conductivity: K[m],
                    specific_heat: CP[m],
                })
            })
            .collect(),
        wall_temperature: walls,
        template_temperature: temps,
        template_source: vec![0.0; n],
    }
}

/// A body held in place: no force or torque component acts.
fn held(template: u32, x: DVec3) -> BodyInit {
    BodyInit {
        force_flag: [false; 3],
        torque_flag: [false; 3],
        ..BodyInit::at_rest(template, x, DQuat::IDENTITY)
    }
}

fn sphere(r: f64, rho: f64) -> ClumpTemplate {
    let s = [Sphere {
        center: DVec3::ZERO,
        radius: r,
    }];
    ClumpTemplate::from_spheres("sphere", &s, rho).unwrap()
}

fn plane(name: &str, point: DVec3, normal: DVec3) -> Wall {
    Wall {
        name: name.into(),
        shape: WallShape::Plane { point, normal },
        material: 2,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    }
}

/// Temperature of body `id`, K.
fn temp(w: &World, id: u64) -> f64 {
    w.bodies().temperature[w.body_index(id).unwrap()]
}

/// Two spheres of different materials and radii, overlapping by `delta`:
/// T₁ − T₂ decays as exp(−H (1/C₁ + 1/C₂) t) with H from the contact
/// radius (T-53 or T-54 from outside the code), and Σ C T stays.
fn two_bodies(conductance: Conductance) {
    let (r1, r2, delta): (f64, f64, f64) = (1e-3, 1.5e-3, 2e-5);
    let k_star = 2.0 * K[0] * K[1] / (K[0] + K[1]);
    let h = match conductance {
        Conductance::BatchelorObrien => 2.0 * k_star * (r1 * r2 / (r1 + r2) * delta).sqrt(),
        Conductance::Geometric => {
            // the circle in which the spheres intersect: d² = (r1+r2−δ)²
            let d = r1 + r2 - delta;
            let x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
            2.0 * k_star * (PI * (r1 * r1 - x * x)).sqrt()
        }
    };
    let c1 = RHO[0] * 4.0 / 3.0 * PI * r1.powi(3) * CP[0];
    let c2 = RHO[1] * 4.0 / 3.0 * PI * r2.powi(3) * CP[1];
    let lambda = h * (1.0 / c1 + 1.0 / c2);
    let dt = 1e-3 / lambda;
    let mut w = world(dt, open(0.1));
    let t1 = w.add_template(sphere(r1, RHO[0]), 0).unwrap();
    let t2 = w.add_template(sphere(r2, RHO[1]), 1).unwrap();
    w.enable_heat(model(conductance, vec![400.0, 300.0], vec![]))
        .unwrap();
    let a = w.add_body(&held(t1, DVec3::ZERO)).unwrap();
    let b = w
        .add_body(&held(t2, DVec3::new(r1 + r2 - delta, 0.0, 0.0)))
        .unwrap();
    let content0 = c1 * 400.0 + c2 * 300.0;
    let steps = 3000;
    let mut worst = 0.0f64;
    for n in 1..=steps {
        w.run(1).unwrap();
        let t = n as f64 * dt;
        let diff = temp(&w, a) - temp(&w, b);
        let expect = 100.0 * (-lambda * t).exp();
        worst = worst.max(((diff - expect) / expect).abs());
        let content = c1 * temp(&w, a) + c2 * temp(&w, b);
        assert!(
            ((content - content0) / content0).abs() < 1e-14,
            "step {n}: heat {content} J, at the start {content0} J"
        );
    }
    println!("{conductance:?}: H = {h:.6e} W/K, worst relative error of T1 - T2 over λt ≤ 3: {worst:.3e}");
    assert!(worst < 0.01, "{worst}");
    // the thermo reports the same content, and the stability ratio
    let th = w.thermo().heat.unwrap();
    assert!(((th.heat_content - content0) / content0).abs() < 1e-14);
    let ratio = dt * h * (1.0 / c1).max(1.0 / c2);
    assert!(
        (th.stability - ratio).abs() < 1e-12 * ratio,
        "{} {ratio}",
        th.stability
    );
}

#[test]
fn two_bodies_relax_at_the_batchelor_obrien_rate() {
    two_bodies(Conductance::BatchelorObrien);
}

#[test]
fn two_bodies_relax_at_the_geometric_area_rate() {
    two_bodies(Conductance::Geometric);
}

/// Two parallel rods of two spheres each, side by side: two sphere
/// contacts between the bodies, twice the conductance of one, and one
/// temperature per body.
#[test]
fn clumps_conduct_through_each_sphere_contact() {
    let (r, delta, spacing): (f64, f64, f64) = (1e-3, 1e-5, 1.8e-3);
    let rod = ClumpTemplate::from_spheres(
        "rod",
        &[
            Sphere {
                center: DVec3::new(0.0, -spacing / 2.0, 0.0),
                radius: r,
            },
            Sphere {
                center: DVec3::new(0.0, spacing / 2.0, 0.0),
                radius: r,
            },
        ],
        RHO[0],
    )
    .unwrap();
    let c = rod.mass * CP[0];
    // per contact H = 2 k a, two contacts, λ = 2 H (1/C + 1/C)
    let h = 2.0 * K[0] * (r / 2.0 * delta).sqrt();
    let lambda = 4.0 * h / c;
    let dt = 1e-3 / lambda;
    let mut w = world(dt, open(0.1));
    // the body frame is the principal frame: turn it back to the input's
    let q = rod.body_to_input();
    let t = w.add_template(rod, 0).unwrap();
    w.enable_heat(model(Conductance::BatchelorObrien, vec![350.0], vec![]))
        .unwrap();
    let at = |x| BodyInit {
        orientation: q,
        ..held(t, x)
    };
    let a = w.add_body(&at(DVec3::ZERO)).unwrap();
    let b = w
        .add_body(&at(DVec3::new(2.0 * r - delta, 0.0, 0.0)))
        .unwrap();
    w.set_body_temperature(a, 360.0).unwrap();
    w.set_body_temperature(b, 340.0).unwrap();
    let steps = 2000;
    w.run(steps).unwrap();
    let diff = temp(&w, a) - temp(&w, b);
    let expect = 20.0 * (1.0 - lambda * dt).powi(steps as i32);
    assert!(
        ((diff - expect) / expect).abs() < 1e-9,
        "{diff} K, explicit Euler of two contacts {expect} K"
    );
    assert_eq!(w.stats.pair_contacts, 2);
}

/// N spheres in a row between a wall at 400 K and one at 300 K: at steady
/// state the heat flow is ΔT over the series resistances, and each sphere
/// sits at the hot wall's temperature minus the flow times the resistance
/// before it.
#[test]
fn a_chain_between_walls_reaches_the_series_conductance_solution() {
    let (r, ds, dw, n): (f64, f64, f64, usize) = (1e-3, 2e-5, 1e-5, 8);
    let hs = 2.0 * K[0] * (r / 2.0 * ds).sqrt();
    let kw = 2.0 * K[0] * K[2] / (K[0] + K[2]);
    let hw = 2.0 * kw * (r * dw).sqrt();
    let c = RHO[0] * 4.0 / 3.0 * PI * r.powi(3) * CP[0];
    let dt = 0.4 * c / (hs + hw.max(hs));
    let mut w = world(dt, open(0.1));
    let t = w.add_template(sphere(r, RHO[0]), 0).unwrap();
    let x0 = -(n as f64 - 1.0) / 2.0 * (2.0 * r - ds);
    let lo = x0 - r + dw;
    let hi = -x0 + r - dw;
    w.add_wall(plane("hot", DVec3::new(lo, 0.0, 0.0), DVec3::X))
        .unwrap();
    w.add_wall(plane("cold", DVec3::new(hi, 0.0, 0.0), -DVec3::X))
        .unwrap();
    w.enable_heat(model(
        Conductance::BatchelorObrien,
        vec![300.0],
        vec![Some(400.0), Some(300.0)],
    ))
    .unwrap();
    let ids: Vec<u64> = (0..n)
        .map(|k| {
            let x = x0 + k as f64 * (2.0 * r - ds);
            w.add_body(&held(t, DVec3::new(x, 0.0, 0.0))).unwrap()
        })
        .collect();
    w.run(20_000).unwrap();
    let resistance = 2.0 / hw + (n - 1) as f64 / hs;
    let q = 100.0 / resistance;
    for (k, &id) in ids.iter().enumerate() {
        let expect = 400.0 - q * (1.0 / hw + k as f64 / hs);
        let got = temp(&w, id);
        assert!(
            (got - expect).abs() < 1e-9 * expect,
            "sphere {k}: {got} K, series solution {expect} K"
        );
    }
    let th = w.thermo().heat.unwrap();
    assert!(
        (th.wall_flow[0] - q).abs() < 1e-9 * q,
        "{} {q}",
        th.wall_flow[0]
    );
    assert!(
        (th.wall_flow[1] + q).abs() < 1e-9 * q,
        "{} {q}",
        th.wall_flow[1]
    );
    println!("chain of {n}: Q = {q:.6e} W, walls {:?}", th.wall_flow);
}

/// A lattice of spheres (period `cell` in x and y, periodic there) between
/// a hot wall below and a cold one above, held in place. Returns the
/// effective conductivity (W/(m K)) from the wall flow and the mean
/// temperature gradient between the layers away from the walls.
fn lattice_conductivity(sites: &[DVec3], cell: f64, cells: usize, r: f64, dw: f64) -> f64 {
    let side = cell * cells as f64;
    let z_lo = sites.iter().map(|p| p.z).fold(f64::INFINITY, f64::min) - r + dw;
    let z_hi = sites.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max) + r - dw;
    let domain = Domain {
        lo: DVec3::new(0.0, 0.0, z_lo - 4.0 * r),
        hi: DVec3::new(side, side, z_hi + 4.0 * r),
        periodic: [true, true, false],
    };
    let c = RHO[0] * 4.0 / 3.0 * PI * r.powi(3) * CP[0];
    // each sphere: at most 12 contacts of H ≤ 2 k √(r/2 · 0.03 r)
    let dt = 0.5 * c / (12.0 * 2.0 * K[0] * (0.015 * r * r).sqrt());
    let mut w = world(dt, domain);
    let t = w.add_template(sphere(r, RHO[0]), 0).unwrap();
    w.add_wall(plane("hot", DVec3::new(0.0, 0.0, z_lo), DVec3::Z))
        .unwrap();
    w.add_wall(plane("cold", DVec3::new(0.0, 0.0, z_hi), -DVec3::Z))
        .unwrap();
    w.enable_heat(model(
        Conductance::BatchelorObrien,
        vec![350.0],
        vec![Some(400.0), Some(300.0)],
    ))
    .unwrap();
    for i in 0..cells {
        for j in 0..cells {
            for s in sites {
                let p = *s + DVec3::new(i as f64 * cell, j as f64 * cell, 0.0);
                w.add_body(&held(t, p)).unwrap();
            }
        }
    }
    let mut last = 0.0;
    for _ in 0..200 {
        w.run(500).unwrap();
        let q = w.thermo().heat.unwrap().wall_flow[0];
        if ((q - last) / q).abs() < 1e-12 {
            break;
        }
        last = q;
    }
    let th = w.thermo().heat.unwrap();
    assert!(
        ((th.wall_flow[0] + th.wall_flow[1]) / th.wall_flow[0]).abs() < 1e-9,
        "not steady: {:?}",
        th.wall_flow
    );
    // layers by height, their mean temperatures
    let mut layers: Vec<(f64, f64, usize)> = Vec::new();
    for b in 0..w.bodies().len() {
        let z = w.bodies().position[b].z;
        match layers.iter_mut().find(|l| (l.0 - z).abs() < 1e-3 * r) {
            Some(l) => {
                l.1 += w.bodies().temperature[b];
                l.2 += 1;
            }
            None => layers.push((z, w.bodies().temperature[b], 1)),
        }
    }
    layers.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (z1, t1) = (layers[1].0, layers[1].1 / layers[1].2 as f64);
    let l2 = &layers[layers.len() - 2];
    let (z2, t2) = (l2.0, l2.1 / l2.2 as f64);
    let gradient = (t2 - t1) / (z2 - z1);
    let flux = th.wall_flow[0] / (side * side);
    -flux / gradient
}

/// Batchelor & O'Brien's (1977) packed-bed conductivity of the contacts
/// alone under a uniform gradient, k_e = Z φ H d² / (8 π r³): the sum of
/// H l_x² over the contacts per volume, with Z contacts a sphere, solid
/// fraction φ (undeformed spheres of radius r), contact conductance H and
/// centre distance d (for d = 2r and H = 2 k a: k_e / k = Z φ a / (π r)).
fn batchelor_obrien(z: f64, phi: f64, h: f64, d: f64, r: f64) -> f64 {
    z * phi * h * d * d / (8.0 * PI * r.powi(3))
}

/// The relation is exact for a lattice with one sphere per primitive cell
/// (each sphere's neighbours are symmetric about it, so a uniform gradient
/// balances): a simple cubic and a face-centred cubic lattice of
/// overlapping spheres, measured between walls.
#[test]
fn lattice_conductivity_matches_batchelor_obrien() {
    let (r, delta, dw): (f64, f64, f64) = (1e-3, 2e-5, 1e-5);
    let d = 2.0 * r - delta;
    let h = 2.0 * K[0] * (r / 2.0 * delta).sqrt();
    let sphere_volume = 4.0 / 3.0 * PI * r.powi(3);
    // simple cubic, six layers
    let sc: Vec<DVec3> = (0..6)
        .map(|k| DVec3::new(0.5 * d, 0.5 * d, k as f64 * d))
        .collect();
    let k_sc = lattice_conductivity(&sc, d, 4, r, dw);
    let bo_sc = batchelor_obrien(6.0, sphere_volume / d.powi(3), h, d, r);
    println!("simple cubic: k_e = {k_sc:.9e} W/(m K), Batchelor–O'Brien {bo_sc:.9e}");
    assert!((k_sc - bo_sc).abs() < 1e-6 * bo_sc);
    // face-centred cubic, cubic cell a = √2 d (four spheres), eight layers
    // a/2 apart
    let a = 2f64.sqrt() * d;
    let mut fcc = Vec::new();
    for k in 0..8 {
        let z = k as f64 * a / 2.0;
        let (u, v) = if k % 2 == 0 {
            (0.25, 0.75)
        } else {
            (0.75, 0.25)
        };
        fcc.push(DVec3::new(u * a, 0.25 * a, z));
        fcc.push(DVec3::new(v * a, 0.75 * a, z));
    }
    let k_fcc = lattice_conductivity(&fcc, a, 3, r, dw);
    let bo_fcc = batchelor_obrien(12.0, 4.0 * sphere_volume / a.powi(3), h, d, r);
    println!("fcc: k_e = {k_fcc:.9e} W/(m K), Batchelor–O'Brien {bo_fcc:.9e}");
    assert!((k_fcc - bo_fcc).abs() < 1e-6 * bo_fcc);
}

/// A bed of tetrahedral clumps falls onto a floor at 400 K and packs while
/// conducting (every contact, rebuilds, periodic sides): the temperatures
/// have the same bits on 1 and 3 threads, and the heat the bodies gained
/// is the heat the floor gave, to round-off.
#[test]
fn a_settling_bed_conducts_the_same_bits_on_any_thread_count_and_conserves_heat() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut w = clump_core::testbed::tetra_lattice_bed(5, 5, 4, None);
            clump_core::testbed::heat_on(&mut w, 5.0, 1.0, 400.0, 300.0, 0.0);
            let content = |w: &World| w.thermo().heat.unwrap().heat_content;
            let c0 = content(&w);
            w.run(6000).unwrap();
            let th = w.thermo().heat.unwrap();
            let gained = content(&w) - c0;
            let ids = w.bodies().id.clone();
            let mut t: Vec<(u64, u64)> = ids
                .iter()
                .zip(&w.bodies().temperature)
                .map(|(&i, &t)| (i, t.to_bits()))
                .collect();
            t.sort();
            (t, gained, th.wall_heat[0], th.max_temperature, th.stability)
        })
    };
    let (a, gained, wall, hottest, stability) = run(1);
    let (b, ..) = run(3);
    println!(
        "tetra bed: heat from the floor {wall:.6e} J, gained by the bodies {gained:.6e} J, hottest {hottest:.3} K, stability ratio {stability:.3e}"
    );
    assert!(hottest > 300.1, "no heat reached the bed: {hottest}");
    assert!(wall > 0.0);
    assert!(
        ((gained - wall) / wall).abs() < 1e-9,
        "{gained} J gained, {wall} J from the floor"
    );
    assert!(a == b, "temperatures differ between 1 and 3 threads");
}
