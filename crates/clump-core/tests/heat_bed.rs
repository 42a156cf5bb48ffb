//! The effective conductivity of random beds (docs/theory.md T-58): a bed
//! of tetrahedral clumps and a bed of spheres of the same volume settle
//! under gravity onto a floor, are frozen, and conduct from the floor at
//! 400 K to the top layer held at 300 K. At steady state the conductivity
//! measured from the floor's heat flow and the interior gradient is
//! compared with Batchelor & O'Brien's mean field evaluated on the bed's own
//! contacts, `k_aff = Σ_c H_c (l_c·z)² / V` (affine body temperatures; for
//! a monodisperse sphere bed this is `Z φ H d² / (8 π r³)`), which bounds
//! it from above (the exact steady state minimises the dissipation over
//! all temperature fields, the affine one among them). Measured: the ratio
//! for each shape, i.e. the clump shape's effect.

use clump_core::heat::{Conductance, HeatModel, ThermalMaterial};
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::testbed::{lattice_bed, tetra_template};
use clump_core::world::World;
use glam::DVec3;

const K: f64 = 1.0;

/// Body temperatures at or above this height (m) are held at 300 K.
fn top_layer(w: &World) -> f64 {
    let top = w.bodies().position.iter().map(|p| p.z).fold(0.0, f64::max);
    top - 2.0e-3
}

/// Batchelor–O'Brien's conductance of each touching sphere pair (T-53),
/// with the branch between the bodies' centres (minimum image in the
/// periodic x and y): `(H, l)` per contact, and the body indices.
fn contacts(w: &World) -> Vec<(f64, DVec3, usize, usize)> {
    let sp = w.spheres();
    let d = &w.config.domain;
    let size = d.size();
    let image = |mut v: DVec3| {
        for a in 0..2 {
            v[a] -= size[a] * (v[a] / size[a]).round();
        }
        v
    };
    let mut out = Vec::new();
    for i in 0..sp.len() {
        for j in i + 1..sp.len() {
            let (bi, bj) = (sp.body[i] as usize, sp.body[j] as usize);
            if bi == bj {
                continue;
            }
            let (ri, rj) = (sp.radius[i], sp.radius[j]);
            let dist = image(sp.position(i) - sp.position(j)).length();
            let delta = ri + rj - dist;
            if delta > 0.0 {
                let h = 2.0 * K * (ri * rj / (ri + rj) * delta).sqrt();
                let l = image(w.bodies().position[bj] - w.bodies().position[bi]);
                out.push((h, l, bi, bj));
            }
        }
    }
    out
}

/// Settles a jittered 6×6×8 lattice of `template` bodies, freezes it and returns
/// (measured k_e, affine k_aff, coordination number, solid fraction of
/// the interior), W/(m K).
fn bed_conductivity(template: ClumpTemplate) -> (f64, f64, f64, f64) {
    let mut w = lattice_bed(&[template], 6, 6, 8, None);
    // a fixed lateral jitter (±0.4 mm), so that spheres do not fall in
    // columns
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut jitter = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 0.4e-3
    };
    for b in 0..w.bodies().len() {
        let p = w.bodies().position[b] + DVec3::new(jitter(), jitter(), 0.0);
        let q = w.bodies().orientation[b];
        w.set_body_pose_at(b, p, q).unwrap();
    }
    w.run(30_000).unwrap();
    let t = w.thermo();
    eprintln!(
        "settled: KE {:.3e} J, PE {:.3e} J, top {:.4} m",
        t.kinetic_translational + t.kinetic_rotational,
        t.potential,
        top_layer(&w)
    );
    // freeze: no force or torque acts any more, nothing moves
    w.config.gravity = DVec3::ZERO;
    for b in 0..w.bodies().len() {
        w.set_body_velocity_at(b, DVec3::ZERO).unwrap();
        w.set_body_angular_velocity_at(b, DVec3::ZERO).unwrap();
        w.set_body_dof_at(b, [false; 3], [false; 3]).unwrap();
    }
    w.step().unwrap();
    let c = contacts(&w);
    let zs: Vec<f64> = w.bodies().position.iter().map(|p| p.z).collect();
    eprintln!(
        "contacts: engine {} pair + {} wall, found {}; bodies {}, z from {:.4} to {:.4} m, sphere r {:.4e}",
        w.stats.pair_contacts,
        w.stats.wall_contacts,
        c.len(),
        zs.len(),
        zs.iter().cloned().fold(f64::INFINITY, f64::min),
        zs.iter().cloned().fold(0.0, f64::max),
        w.spheres().radius[0]
    );
    // c_p such that the explicit step is stable with margin (T-57)
    let mut sum_h = vec![0.0; w.bodies().len()];
    for &(h, _, i, j) in &c {
        sum_h[i] += h;
        sum_h[j] += h;
    }
    let m_min = w
        .bodies()
        .mass
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    let h_max = sum_h.iter().cloned().fold(0.0, f64::max) + 4.0 * 2.0 * K * 1e-4;
    let cp = 4.0 * w.config.dt * h_max / m_min;
    let thermal = Some(ThermalMaterial {
        conductivity: K,
        specific_heat: cp,
    });
    w.enable_heat(HeatModel {
        conductance: Conductance::BatchelorObrien,
        materials: vec![thermal; w.materials.len()],
        wall_temperature: vec![Some(400.0)],
        template_temperature: vec![350.0; w.templates.len()],
        template_source: vec![0.0; w.templates.len()],
    })
    .unwrap();
    let z_top = top_layer(&w);
    let hold = |w: &mut World| {
        for b in 0..w.bodies().len() {
            if w.bodies().position[b].z >= z_top {
                w.set_body_temperature_at(b, 300.0).unwrap();
            }
        }
    };
    let mut last = 0.0;
    for round in 0..400 {
        for _ in 0..250 {
            hold(&mut w);
            w.step().unwrap();
        }
        let q = w.thermo().heat.unwrap().wall_flow[0];
        if round > 4 && ((q - last) / q).abs() < 1e-7 {
            break;
        }
        last = q;
    }
    hold(&mut w);
    let th = w.thermo().heat.unwrap();
    let size = w.config.domain.size();
    let area = size.x * size.y;
    let flux = th.wall_flow[0] / area;
    // the interior: 3 mm above the floor to 3 mm below the held layer
    let (z1, z2) = (3e-3, z_top - 3e-3);
    let inside: Vec<usize> = (0..w.bodies().len())
        .filter(|&b| (z1..z2).contains(&w.bodies().position[b].z))
        .collect();
    // least-squares slope of T against z over the interior bodies
    let n = inside.len() as f64;
    let (mut sz, mut st, mut szz, mut szt) = (0.0, 0.0, 0.0, 0.0);
    for &b in &inside {
        let (z, t) = (w.bodies().position[b].z, w.bodies().temperature[b]);
        sz += z;
        st += t;
        szz += z * z;
        szt += z * t;
    }
    let slope = (n * szt - sz * st) / (n * szz - sz * sz);
    let k_e = -flux / slope;
    eprintln!(
        "interior: {} bodies, z {z1:.4}..{z2:.4} m, floor flow {:.4e} W, slope {slope:.4e} K/m",
        inside.len(),
        th.wall_flow[0]
    );
    // the affine estimate from the contacts whose branch midpoint is inside
    let volume = area * (z2 - z1);
    let mut k_aff = 0.0;
    let mut z_sum = 0.0;
    for &(h, l, i, _) in &c {
        // the part of the branch inside the slab (a contact conducts the
        // slab's heat in proportion to it)
        let (za, zb) = (w.bodies().position[i].z, w.bodies().position[i].z + l.z);
        let (lo, hi) = (za.min(zb).max(z1), za.max(zb).min(z2));
        if hi > lo {
            k_aff += h * l.z.abs() * (hi - lo) / volume;
        }
        let mid = za + 0.5 * l.z;
        if (z1..z2).contains(&mid) {
            z_sum += 2.0;
        }
    }
    let solid: f64 = inside
        .iter()
        .map(|&b| w.templates[w.bodies().template[b] as usize].volume)
        .sum();
    (k_e, k_aff, z_sum / n, solid / volume)
}

#[test]
#[ignore = "slow (two beds settle, about 3 min): cargo test --profile ci -p clump-core --test heat_bed -- --ignored --nocapture"]
fn random_beds_conduct_below_the_batchelor_obrien_mean_field_and_shape_matters() {
    let tetra = tetra_template();
    let r = (0.75 * tetra.volume / std::f64::consts::PI).cbrt();
    let sphere = ClumpTemplate::from_spheres(
        "sphere",
        &[Sphere {
            center: DVec3::ZERO,
            radius: r,
        }],
        clump_core::testbed::tetra_material().density,
    )
    .unwrap();
    let mut rows = Vec::new();
    for (name, t) in [("spheres", sphere), ("tetra clumps", tetra)] {
        let (k_e, k_aff, z, phi) = bed_conductivity(t);
        println!(
            "{name}: k_e = {k_e:.4e} W/(m K), Batchelor–O'Brien on its contacts {k_aff:.4e}, ratio {:.3}; Z = {z:.2}, φ = {phi:.3}",
            k_e / k_aff
        );
        // the mean field bounds the steady state from above
        assert!(k_e > 0.0 && k_e <= k_aff * (1.0 + 1e-9), "{k_e} {k_aff}");
        rows.push((k_e, k_aff));
    }
    println!(
        "shape effect: k_e(tetra) / k_e(spheres) = {:.3}",
        rows[1].0 / rows[0].0
    );
}
