//! Insertion: random sequential packing and streams, checked independently
//! (brute-force overlap loops over sphere positions recomputed from body poses).

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::ContactTable;
use clump_core::contact::{Material, PairProperties};
use clump_core::insert::{
    pack, FractionBasis, InsertError, Mix, MixEntry, Orientation, PackSpec, PackTarget, Region,
    SizeDistribution, StreamInserter, StreamRate, StreamSpec,
};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{self, ClumpTemplate};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};

fn world_with(domain: Domain, gravity: DVec3) -> World {
    let mats = vec![Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }];
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let config = WorldConfig {
        domain,
        gravity,
        dt: 1e-5,
        rotation: RotationScheme::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    World::new(config, mats, table)
}

fn open_world() -> World {
    world_with(
        Domain {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
            periodic: [false; 3],
        },
        DVec3::ZERO,
    )
}

fn tetra() -> ClumpTemplate {
    ClumpTemplate::from_spheres("tetra", &shape::tetrahedron(1e-3, 1.5e-3), 2500.0).unwrap()
}

fn cube_region() -> Region {
    Region::Box {
        lo: DVec3::splat(0.0),
        hi: DVec3::splat(0.03),
    }
}

fn count_spec(region: Region, n: usize, template: u32) -> PackSpec {
    PackSpec {
        region,
        target: PackTarget::Count(n),
        mix: Mix::single(template),
        velocity: DVec3::ZERO,
        orientation: Orientation::Random,
        max_attempts_per_body: 1000,
        angular_velocity: Default::default(),
        dof: Vec::new(),
        plane: None,
    }
}

/// World-frame spheres (centre, radius, body storage index) recomputed from the body poses.
fn spheres_of(w: &World) -> Vec<(DVec3, f64, usize)> {
    let mut out = Vec::new();
    for b in 0..w.bodies().len() {
        let t = &w.templates[w.bodies().template[b] as usize];
        for s in &t.spheres {
            let c = w.bodies().position[b] + w.bodies().orientation[b] * s.center;
            out.push((c, s.radius, b));
        }
    }
    out
}

/// Brute-force O(N²) check: the worst overlap between spheres of different bodies (m; ≤ 0: none).
fn worst_overlap(s: &[(DVec3, f64, usize)]) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            if s[i].2 != s[j].2 {
                let ov = s[i].1 + s[j].1 - (s[i].0 - s[j].0).length();
                worst = worst.max(ov);
            }
        }
    }
    worst
}

fn inside_box(s: &[(DVec3, f64, usize)], lo: DVec3, hi: DVec3) -> bool {
    s.iter()
        .all(|&(c, r, _)| (c - r).cmpge(lo - 1e-12).all() && (c + r).cmple(hi + 1e-12).all())
}

#[test]
fn pack_300_tetra_no_overlap_inside() {
    let mut w = open_world();
    let t = w.add_template(tetra(), 0).unwrap();
    let region = cube_region();
    let rep = pack(&mut w, &count_spec(region, 300, t), 7).unwrap();
    assert_eq!(rep.placed, 300);
    assert_eq!(w.bodies().len(), 300);
    assert_eq!(rep.ids.len(), 300);
    assert!(
        rep.templates_added.is_empty(),
        "a fixed scale of 1 must reuse the base template"
    );
    let s = spheres_of(&w);
    assert_eq!(s.len(), 1200);
    let ov = worst_overlap(&s);
    assert!(ov <= 1e-15, "overlap {ov} m");
    assert!(inside_box(&s, DVec3::ZERO, DVec3::splat(0.03)));
    let phi = rep.volume_fraction;
    let expect = 300.0 * w.templates[0].volume / region.volume();
    assert!(
        (phi - expect).abs() < 1e-12 * expect.max(1.0),
        "{phi} vs {expect}"
    );
    // the same check on the engine's own sphere positions
    w.prepare().unwrap();
    let sp = w.spheres();
    let es: Vec<_> = (0..sp.len())
        .map(|i| (sp.position(i), sp.radius[i], sp.body[i] as usize))
        .collect();
    assert!(worst_overlap(&es) <= 1e-12);
    assert_eq!(w.stats.pair_contacts, 0);
    // orientations are unit quaternions and not all equal
    assert!(w
        .bodies()
        .orientation
        .iter()
        .all(|q| (q.length() - 1.0).abs() < 1e-12));
    assert!(w.bodies().orientation[0] != w.bodies().orientation[1]);
}

#[test]
fn pack_is_deterministic_per_seed() {
    let run = |seed: u64| {
        let mut w = open_world();
        let t = w.add_template(tetra(), 0).unwrap();
        pack(&mut w, &count_spec(cube_region(), 100, t), seed).unwrap();
        (w.bodies().position.clone(), w.bodies().orientation.clone())
    };
    let a = run(11);
    let b = run(11);
    let c = run(12);
    assert_eq!(a, b);
    assert_ne!(a.0, c.0);
}

#[test]
fn impossible_requests_fail_cleanly() {
    let mut w = open_world();
    let t = w.add_template(tetra(), 0).unwrap();
    let region = Region::Box {
        lo: DVec3::ZERO,
        hi: DVec3::splat(0.01),
    };
    // way above the packing limit: refused at once
    let e = pack(&mut w, &count_spec(region, 5000, t), 1).unwrap_err();
    assert!(matches!(e, InsertError::RegionTooSmall { .. }), "{e}");
    assert!(e.to_string().contains("region cannot hold"), "{e}");
    // below the limit but beyond random sequential addition: gives up, world unchanged
    let vol = w.templates[0].volume;
    let n = (0.55 * region.volume() / vol) as usize;
    let mut spec = count_spec(region, n, t);
    spec.max_attempts_per_body = 200;
    let e = pack(&mut w, &spec, 1).unwrap_err();
    match &e {
        InsertError::TargetNotReached {
            placed,
            volume_fraction,
            ..
        } => {
            assert!(*placed > 0 && *placed < n);
            assert!(*volume_fraction > 0.05 && *volume_fraction < 0.55);
        }
        other => panic!("unexpected {other}"),
    }
    let msg = e.to_string();
    assert!(
        msg.contains("placed") && msg.contains("larger region"),
        "{msg}"
    );
    assert_eq!(
        w.bodies().len(),
        0,
        "a failed pack leaves the world unchanged"
    );
    // bad template
    let e = pack(&mut w, &count_spec(region, 1, 9), 1).unwrap_err();
    assert!(matches!(e, InsertError::InvalidSpec(_)), "{e}");
    // bad region
    let e = pack(
        &mut w,
        &count_spec(
            Region::Box {
                lo: DVec3::ONE,
                hi: DVec3::ZERO,
            },
            1,
            t,
        ),
        1,
    )
    .unwrap_err();
    assert!(matches!(e, InsertError::InvalidSpec(_)), "{e}");
}

#[test]
fn pack_respects_existing_bodies_walls_and_cylinders() {
    let mut w = open_world();
    let t = w.add_template(tetra(), 0).unwrap();
    w.add_wall(Wall {
        name: "floor".into(),
        shape: WallShape::Plane {
            point: DVec3::new(0.0, 0.0, 0.01),
            normal: DVec3::Z,
        },
        material: 0,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    })
    .unwrap();
    pack(&mut w, &count_spec(cube_region(), 60, t), 1).unwrap();
    pack(&mut w, &count_spec(cube_region(), 60, t), 2).unwrap();
    let cyl = Region::Cylinder {
        base: DVec3::new(0.015, 0.015, 0.0),
        axis: DVec3::Z,
        radius: 0.012,
        height: 0.03,
    };
    let rep = pack(&mut w, &count_spec(cyl, 40, t), 3).unwrap();
    assert_eq!(w.bodies().len(), 160);
    let s = spheres_of(&w);
    assert!(worst_overlap(&s) <= 1e-15);
    assert!(
        s.iter().all(|&(c, r, _)| c.z - r >= 0.01 - 1e-12),
        "a sphere crosses the wall"
    );
    for &id in &rep.ids {
        let b = w.body_index(id).unwrap();
        for &(c, r, bb) in &s {
            if bb == b {
                assert!(cyl.contains_sphere(c, r - 1e-12));
            }
        }
    }
}

#[test]
fn pack_periodic_images_do_not_overlap() {
    let mut w = world_with(
        Domain {
            lo: DVec3::ZERO,
            hi: DVec3::splat(0.02),
            periodic: [true; 3],
        },
        DVec3::ZERO,
    );
    let t = w.add_template(tetra(), 0).unwrap();
    let region = Region::Box {
        lo: DVec3::ZERO,
        hi: DVec3::splat(0.02),
    };
    pack(&mut w, &count_spec(region, 80, t), 5).unwrap();
    let s = spheres_of(&w);
    let l = 0.02;
    let mut worst = f64::NEG_INFINITY;
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            if s[i].2 != s[j].2 {
                let mut d = s[i].0 - s[j].0;
                d -= (d / l).round() * l;
                worst = worst.max(s[i].1 + s[j].1 - d.length());
            }
        }
    }
    assert!(worst <= 1e-15, "{worst}");
}

#[test]
fn mix_by_mass_with_sizes() {
    let mut w = open_world();
    let small = w
        .add_template(
            ClumpTemplate::from_spheres("s", &shape::single_sphere(5e-4), 2500.0).unwrap(),
            0,
        )
        .unwrap();
    let big = w.add_template(tetra(), 0).unwrap();
    let mix = Mix {
        basis: FractionBasis::Mass,
        entries: vec![
            MixEntry {
                template: small,
                fraction: 0.5,
                size: SizeDistribution::Uniform { min: 0.8, max: 1.2 },
            },
            MixEntry {
                template: big,
                fraction: 0.5,
                size: SizeDistribution::Fixed { scale: 0.9 },
            },
        ],
    };
    let spec = PackSpec {
        region: Region::Box {
            lo: DVec3::ZERO,
            hi: DVec3::new(0.06, 0.06, 0.03),
        },
        target: PackTarget::VolumeFraction(0.1),
        mix,
        velocity: DVec3::new(0.0, 0.0, -1.0),
        orientation: Orientation::Random,
        max_attempts_per_body: 1000,
        angular_velocity: Default::default(),
        dof: Vec::new(),
        plane: None,
    };
    let rep = pack(&mut w, &spec, 3).unwrap();
    assert!(rep.volume_fraction >= 0.1);
    let (mut m_small, mut m_big) = (0.0, 0.0);
    let big_scaled = w
        .templates
        .iter()
        .position(|t| t.name == "tetra" && (t.max_radius - 0.9e-3).abs() < 1e-15)
        .unwrap();
    for b in 0..w.bodies().len() {
        let tt = w.bodies().template[b] as usize;
        if tt == big_scaled {
            m_big += w.bodies().mass[b];
        } else {
            assert_eq!(w.templates[tt].name, "s");
            m_small += w.bodies().mass[b];
        }
        assert_eq!(w.bodies().velocity[b], DVec3::new(0.0, 0.0, -1.0));
    }
    let frac = m_small / (m_small + m_big);
    assert!(
        (frac - 0.5).abs() < 0.1,
        "mass fraction of small spheres {frac}"
    );
    // one template for the fixed scale, one per distinct uniform scale
    let n_big = w
        .bodies()
        .template
        .iter()
        .filter(|&&t| t as usize == big_scaled)
        .count();
    assert_eq!(w.templates.len(), 2 + 1 + (w.bodies().len() - n_big));
    assert!(worst_overlap(&spheres_of(&w)) <= 1e-15);
}

fn stream_spec(template: u32, rate: StreamRate) -> StreamSpec {
    StreamSpec {
        region: Region::Box {
            lo: DVec3::new(0.0, 0.0, 0.5),
            hi: DVec3::new(0.05, 0.05, 0.52),
        },
        mix: Mix::single(template),
        rate,
        velocity: DVec3::new(0.0, 0.0, -2.0),
        start: 0.0,
        end: None,
        exit_normal: Some(DVec3::new(0.0, 0.0, -1.0)),
        orientation: Orientation::Random,
        max_attempts_per_body: 20,
        angular_velocity: Default::default(),
        dof: Vec::new(),
        start_after: None,
        plane: None,
    }
}

#[test]
fn stream_honours_rate() {
    let mut w = open_world();
    w.config.dt = 1e-4;
    let t = w.add_template(tetra(), 0).unwrap();
    let mut s =
        StreamInserter::new(stream_spec(t, StreamRate::BodiesPerSecond(2000.0)), &w, 9).unwrap();
    let mut total = 0;
    for _ in 0..500 {
        w.step().unwrap();
        total += s.insert_due(&mut w).unwrap();
    }
    // 0.05 s at 2000 /s
    assert_eq!(s.backlog(), 0);
    assert_eq!(total as u64, s.inserted());
    assert!((total as i64 - 100).abs() <= 1, "inserted {total}");
    assert_eq!(w.bodies().len(), total);
    // ballistic until the exit face: start steps lie in the future, by at most 0.02/2/dt steps
    let last = w.bodies().len() - 1;
    let ss = w.bodies().start_step[last];
    assert!(
        ss >= w.step && ss <= w.step + 101,
        "start_step {ss} at step {}",
        w.step
    );
    assert!(worst_overlap(&spheres_of(&w)) <= 1e-15);

    // mass rate with a window
    let mut w = open_world();
    w.config.dt = 1e-4;
    let t = w.add_template(tetra(), 0).unwrap();
    let m = w.templates[0].mass;
    let mut spec = stream_spec(t, StreamRate::MassPerSecond(1000.0 * m));
    spec.start = 0.01;
    spec.end = Some(0.03);
    let mut s = StreamInserter::new(spec, &w, 1).unwrap();
    for _ in 0..500 {
        w.step().unwrap();
        s.insert_due(&mut w).unwrap();
    }
    assert!(
        (w.bodies().len() as i64 - 20).abs() <= 1,
        "{}",
        w.bodies().len()
    );
    assert!((s.inserted_mass() - 20.0 * m).abs() <= 1.01 * m);
    assert!(s.finished(w.time));
}

#[test]
fn stream_postpones_when_full_and_resumes_bit_identically() {
    // a tiny region that holds about one body: the rest is postponed
    let mut w = open_world();
    w.config.dt = 1e-4;
    let t = w.add_template(tetra(), 0).unwrap();
    let mut spec = stream_spec(t, StreamRate::BodiesPerSecond(1e4));
    spec.region = Region::Box {
        lo: DVec3::new(0.0, 0.0, 0.5),
        hi: DVec3::new(0.004, 0.004, 0.504),
    };
    spec.exit_normal = None;
    spec.velocity = DVec3::ZERO;
    let mut s = StreamInserter::new(spec, &w, 2).unwrap();
    for _ in 0..5 {
        w.step().unwrap();
        s.insert_due(&mut w).unwrap();
    }
    assert!(w.bodies().len() <= 2);
    assert!(s.postponed() > 0 && s.backlog() > 0);

    // resume: serialize the inserter and the world state, continue both ways
    let build = || {
        let mut w = open_world();
        w.config.dt = 1e-4;
        let t = w.add_template(tetra(), 0).unwrap();
        (w, t)
    };
    let (mut a, t) = build();
    let mut sa =
        StreamInserter::new(stream_spec(t, StreamRate::BodiesPerSecond(3000.0)), &a, 4).unwrap();
    for _ in 0..200 {
        a.step().unwrap();
        sa.insert_due(&mut a).unwrap();
    }
    let state = a.save_state().unwrap();
    let json = serde_json::to_string(&sa).unwrap();
    let (mut b, _) = build();
    b.restore_state(state).unwrap();
    let mut sb: StreamInserter = serde_json::from_str(&json).unwrap();
    for _ in 0..200 {
        a.step().unwrap();
        sa.insert_due(&mut a).unwrap();
        b.step().unwrap();
        sb.insert_due(&mut b).unwrap();
    }
    assert!(a.bodies().len() > 100);
    assert_eq!(a.bodies().id, b.bodies().id);
    assert_eq!(a.bodies().position, b.bodies().position);
    assert_eq!(a.bodies().orientation, b.bodies().orientation);
    assert_eq!(a.bodies().start_step, b.bodies().start_step);
}

#[test]
fn random_orientations_are_uniform() {
    // mean of the rotated x axis ≈ 0 and <(R e_x)_z²> ≈ 1/3
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
    let n = 20000;
    let (mut mean, mut zz) = (DVec3::ZERO, 0.0);
    for _ in 0..n {
        let q: DQuat = clump_core::insert::random_orientation(&mut rng);
        let v = q * DVec3::X;
        mean += v;
        zz += v.z * v.z;
    }
    mean /= n as f64;
    assert!(mean.length() < 0.03, "{mean}");
    assert!((zz / n as f64 - 1.0 / 3.0).abs() < 0.02);
    let _ = BodyInit::at_rest(0, DVec3::ZERO, DQuat::IDENTITY);
}

/// A stream's user-given `start_after`: each body moves ballistically at
/// its insertion velocity, gravity ignored, for ⌈t/dt⌉ steps after its
/// insertion, then falls under gravity (the seed's `start_step`); the
/// stream's per-template degrees of freedom reach the bodies.
#[test]
fn stream_start_after_and_flags() {
    let mut w = world_with(
        Domain {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
            periodic: [false; 3],
        },
        DVec3::new(0.0, 0.0, -9.81),
    );
    w.config.dt = 1e-4;
    let t = w.add_template(tetra(), 0).unwrap();
    let mut spec = stream_spec(t, StreamRate::BodiesPerSecond(100.0));
    spec.start_after = Some(0.00123);
    spec.dof = vec![clump_core::dof::Dof {
        force_flag: [true, false, true],
        ..Default::default()
    }];
    let mut s = StreamInserter::new(spec, &w, 3).unwrap();
    let mut inserted_at = None;
    while inserted_at.is_none() {
        w.step().unwrap();
        if s.insert_due(&mut w).unwrap() > 0 {
            inserted_at = Some(w.step);
        }
    }
    let s0 = inserted_at.unwrap();
    assert_eq!(w.bodies().start_step[0], s0 + 13);
    assert_eq!(w.bodies().force_flag[0], [true, false, true]);
    let (x0, v0) = (w.bodies().position[0], w.bodies().velocity[0]);
    w.run(13).unwrap();
    // ballistic: the velocity is untouched, the centre moved by v·13 dt
    assert_eq!(w.bodies().velocity[0], v0);
    assert!((w.bodies().position[0] - (x0 + v0 * 13.0 * 1e-4)).length() < 1e-15);
    w.run(100).unwrap();
    // then gravity acts: Δv_z = −g · 100 dt (the first kick of step s0 + 13
    // is already counted: every step from the start step on adds g dt)
    let dv = w.bodies().velocity[0].z - v0.z;
    assert!((dv + 9.81 * 100.0 * 1e-4).abs() < 1e-12, "{dv}");
}

/// 2D packing (`plane = Some(z)`): every centre of mass on the plane, every
/// orientation about z only (x, y parts exactly zero), no overlaps, the
/// angles spread over the circle, the same bodies for the same seed; a
/// plane outside the region by less than a sphere radius, a z velocity and
/// a fixed orientation about x are refused.
#[test]
fn packing_in_a_plane() {
    let disc = || {
        ClumpTemplate::from_spheres("disc", &[shape::Sphere::new(DVec3::ZERO, 1e-3)], 2500.0)
            .unwrap()
    };
    let region = Region::Box {
        lo: DVec3::new(0.0, 0.0, -0.002),
        hi: DVec3::new(0.05, 0.05, 0.002),
    };
    let spec = PackSpec {
        plane: Some(0.0),
        ..count_spec(region, 200, 0)
    };
    let run = || {
        let mut w = open_world();
        w.add_template(disc(), 0).unwrap();
        pack(&mut w, &spec, 7).unwrap();
        w
    };
    let w = run();
    let b = &w.bodies();
    assert_eq!(b.len(), 200);
    let mut quadrants = [0; 4];
    for i in 0..b.len() {
        let q = b.orientation[i];
        assert_eq!((b.position[i].z, q.x, q.y), (0.0, 0.0, 0.0), "body {i}");
        let angle = 2.0 * q.z.atan2(q.w);
        quadrants[(angle.rem_euclid(std::f64::consts::TAU) / std::f64::consts::FRAC_PI_2)
            as usize
            % 4] += 1;
    }
    assert!(
        quadrants.iter().all(|&n| n > 30),
        "angles about z: {quadrants:?}"
    );
    let s = spheres_of(&w);
    for (a, &(ca, ra, _)) in s.iter().enumerate() {
        for &(cb, rb, _) in &s[a + 1..] {
            assert!((ca - cb).length() >= ra + rb, "overlap");
        }
    }
    let again = run();
    assert!(
        again.bodies().position == w.bodies().position
            && again.bodies().orientation == w.bodies().orientation
    );
    for (bad, what) in [
        (
            PackSpec {
                plane: Some(0.0015),
                ..spec.clone()
            },
            "plane",
        ),
        (
            PackSpec {
                velocity: DVec3::new(0.0, 0.0, 0.1),
                ..spec.clone()
            },
            "velocity",
        ),
        (
            PackSpec {
                orientation: Orientation::Fixed {
                    quaternion: DQuat::from_rotation_x(0.3),
                },
                ..spec.clone()
            },
            "orientation",
        ),
    ] {
        let mut w = open_world();
        w.add_template(disc(), 0).unwrap();
        let e = pack(&mut w, &bad, 7).unwrap_err().to_string();
        assert!(e.contains("2D insertion") && e.contains(what), "{e}");
    }
}
