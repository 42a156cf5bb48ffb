//! Mass properties of unions of spheres against the closed forms of
//! `validation/REFERENCE.md` §2 (not against the code's own output).

use std::f64::consts::PI;

use clump_core::shape::{
    cube_octet, mass_properties, rod, single_sphere, tetrahedron, ClumpTemplate, MassProperties,
    ShapeError, Sphere,
};
use glam::{DMat3, DQuat, DVec3};
use proptest::prelude::*;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn sphere(x: f64, y: f64, z: f64, r: f64) -> Sphere {
    Sphere::new(DVec3::new(x, y, z), r)
}

/// Two unit spheres at ±a on the x axis (REFERENCE.md §2), ρ = 1.
fn pair(a: f64) -> Vec<Sphere> {
    vec![sphere(-a, 0.0, 0.0, 1.0), sphere(a, 0.0, 0.0, 1.0)]
}

fn ref_volume(a: f64) -> f64 {
    2.0 * PI / 3.0 * (2.0 - a) * (1.0 + a).powi(2)
}
fn ref_axis(a: f64) -> f64 {
    PI * (8.0 / 15.0 + a - 2.0 / 3.0 * a.powi(3) + a.powi(5) / 5.0)
}
fn ref_trans(a: f64) -> f64 {
    PI * (8.0 / 15.0 + 1.5 * a + 4.0 / 3.0 * a * a + a.powi(3) / 3.0 + a.powi(5) / 30.0)
}

fn mat_max_abs(m: &DMat3) -> f64 {
    m.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

fn max_offdiag(m: &DMat3) -> f64 {
    m.x_axis.y.abs().max(m.x_axis.z.abs()).max(m.y_axis.z.abs())
}

#[test]
fn reference_table_two_spheres() {
    // d, V, I_axis, I_trans, naive V, naive I_axis, naive I_trans
    let table = [
        (
            0.5, 5.726862, 2.428803, 3.131877, 8.377580, 3.351032, 3.874631,
        ),
        (
            1.0, 7.068583, 3.004148, 5.213080, 8.377580, 3.351032, 5.445427,
        ),
        (
            1.5, 8.017606, 3.297241, 8.032639, 8.377580, 3.351032, 8.063421,
        ),
    ];
    for (d, v, ia, it, nv, nia, nit) in table {
        let a = d / 2.0;
        let p = mass_properties(&pair(a), 1.0).unwrap();
        eprintln!(
            "REFERENCE §2 d={d}: rel. error vs closed form V {:.1e}, I_axis {:.1e}, I_trans {:.1e}/{:.1e}; vs table V {:.1e} I_axis {:.1e} I_trans {:.1e}; reported bound {:.1e}; naive V error {:+.1} %",
            rel(p.volume, ref_volume(a)),
            rel(p.principal_moments.x, ref_axis(a)),
            rel(p.principal_moments.y, ref_trans(a)),
            rel(p.principal_moments.z, ref_trans(a)),
            rel(p.volume, v),
            rel(p.principal_moments.x, ia),
            rel(p.principal_moments.y, it),
            p.relative_error_bound,
            100.0 * (p.naive_volume / p.volume - 1.0)
        );
        // Closed forms, tight.
        assert!(rel(p.volume, ref_volume(a)) < 1e-9, "d={d}: V {}", p.volume);
        assert!(rel(p.principal_moments.x, ref_axis(a)) < 1e-9, "d={d}");
        assert!(rel(p.principal_moments.y, ref_trans(a)) < 1e-9, "d={d}");
        assert!(rel(p.principal_moments.z, ref_trans(a)) < 1e-9, "d={d}");
        assert!(rel(p.inertia.x_axis.x, ref_axis(a)) < 1e-9);
        assert!(rel(p.inertia.y_axis.y, ref_trans(a)) < 1e-9);
        assert!(rel(p.inertia.z_axis.z, ref_trans(a)) < 1e-9);
        assert!(max_offdiag(&p.inertia) < 1e-12);
        assert!(p.center_of_mass.length() < 1e-12);
        // The table (6 decimals).
        assert!(rel(p.volume, v) < 1e-6, "d={d}");
        assert!(rel(p.mass, v) < 1e-6, "d={d}");
        assert!(rel(p.principal_moments.x, ia) < 1e-6, "d={d}");
        assert!(rel(p.principal_moments.y, it) < 1e-6, "d={d}");
        assert!(rel(p.naive_volume, nv) < 1e-6, "d={d}");
        assert!(rel(p.naive_principal_moments.x, nia) < 1e-6, "d={d}");
        assert!(rel(p.naive_principal_moments.y, nit) < 1e-6, "d={d}");
        assert!(rel(p.naive_principal_moments.z, nit) < 1e-6, "d={d}");
        // The axis of the smallest moment is x.
        assert!((p.principal_axis(0) - DVec3::X).length() < 1e-9);
        assert!(p.relative_error_bound <= 1e-6);
        assert!(p.relative_error_bound > 0.0);
    }
}

#[test]
fn reference_pair_in_other_orientations() {
    // The same pair along z (horizontal intersection circle: coaxial discs in
    // every slice) and along a diagonal, off the origin.
    for d in [0.5, 1.0, 1.5] {
        let a: f64 = d / 2.0;
        for dir in [
            DVec3::Z,
            DVec3::new(1.0, 1.0, 1.0).normalize(),
            DVec3::new(0.3, -0.2, 0.9).normalize(),
        ] {
            let o = DVec3::new(3.0, -1.0, 2.0);
            let s = [Sphere::new(o - a * dir, 1.0), Sphere::new(o + a * dir, 1.0)];
            let p = mass_properties(&s, 1.0).unwrap();
            assert!(rel(p.volume, ref_volume(a)) < 1e-9, "d={d} dir={dir}");
            assert!(
                rel(p.principal_moments.x, ref_axis(a)) < 1e-9,
                "d={d} dir={dir}"
            );
            assert!(
                rel(p.principal_moments.y, ref_trans(a)) < 1e-9,
                "d={d} dir={dir}"
            );
            assert!(
                rel(p.principal_moments.z, ref_trans(a)) < 1e-9,
                "d={d} dir={dir}"
            );
            assert!((p.center_of_mass - o).length() < 1e-12);
            assert!(p.principal_axis(0).dot(dir).abs() > 1.0 - 1e-12);
            assert!(p.relative_error_bound <= 1e-6);
        }
    }
}

#[test]
fn snowman_along_z() {
    // Unequal coaxial spheres along z: V = V1 + V2 − lens (REFERENCE.md §2 lens formula).
    let (r1, r2, d): (f64, f64, f64) = (1.0, 0.5, 1.0);
    let s = [sphere(0.5, 0.5, 0.0, r1), sphere(0.5, 0.5, d, r2)];
    let p = mass_properties(&s, 1.0).unwrap();
    let lens = PI * (r1 + r2 - d).powi(2) * (d * d + 2.0 * d * (r1 + r2) - 3.0 * (r1 - r2).powi(2))
        / (12.0 * d);
    assert!(rel(p.volume, 4.0 / 3.0 * PI * (r1.powi(3) + r2.powi(3)) - lens) < 1e-9);
    assert!(p.relative_error_bound <= 1e-6);
}

#[test]
fn density_scales_mass_and_inertia() {
    let p1 = mass_properties(&pair(0.4), 1.0).unwrap();
    let p2 = mass_properties(&pair(0.4), 2500.0).unwrap();
    assert_eq!(p1.volume, p2.volume);
    assert!(rel(p2.mass, 2500.0 * p1.volume) < 1e-15);
    assert!(rel(p2.principal_moments.z, 2500.0 * p1.principal_moments.z) < 1e-14);
}

#[test]
fn lens_volume() {
    // R1 = 1, R2 = 0.5, d = 1: lens 0.212712 (REFERENCE.md §2).
    let s = [sphere(0.0, 0.0, 0.0, 1.0), sphere(0.0, 0.6, 0.8, 0.5)];
    let p = mass_properties(&s, 1.0).unwrap();
    let lens_exact = PI * (1.5f64 - 1.0).powi(2) * (1.0 + 2.0 * 1.5 - 3.0 * 0.25) / 12.0;
    assert!(rel(lens_exact, 0.212712) < 2e-6);
    let union = 4.0 / 3.0 * PI * (1.0 + 0.125);
    assert!(rel(p.volume, union - lens_exact) < 1e-9);
    assert!(rel(p.volume, union - 0.212712) < 1e-6);
}

fn single_sphere_inertia(r: f64, rho: f64) -> f64 {
    let m = rho * 4.0 / 3.0 * PI * r.powi(3);
    0.4 * m * r * r
}

#[test]
fn coincident_spheres_count_once() {
    let r = 0.7;
    let c = DVec3::new(0.1, -2.0, 3.0);
    let one = mass_properties(&[Sphere::new(c, r)], 3.0).unwrap();
    let four = mass_properties(&[Sphere::new(c, r); 4], 3.0).unwrap();
    let m = 3.0 * 4.0 / 3.0 * PI * r.powi(3);
    assert_eq!(
        one,
        MassProperties {
            naive_volume: one.naive_volume,
            naive_principal_moments: one.naive_principal_moments,
            ..four
        }
    );
    assert!(rel(four.mass, m) < 1e-14);
    for k in 0..3 {
        assert!(rel(four.principal_moments[k], single_sphere_inertia(r, 3.0)) < 1e-13);
    }
    assert!((four.center_of_mass - c).length() < 1e-14);
    assert_eq!(four.principal_axes, DMat3::IDENTITY);
    // The naive sum counts them four times.
    assert!(rel(four.naive_volume, 4.0 * 4.0 / 3.0 * PI * r.powi(3)) < 1e-14);
}

#[test]
fn sphere_inside_another() {
    let big = sphere(1.0, 1.0, 1.0, 2.0);
    let small = sphere(1.5, 0.5, 1.2, 0.8);
    let tangent_inside = sphere(1.0, 1.0, 2.0, 1.0); // touches from inside
    let p = mass_properties(&[small, big, tangent_inside], 1.0).unwrap();
    let v = 4.0 / 3.0 * PI * 8.0;
    assert!(rel(p.volume, v) < 1e-14);
    assert!(rel(p.principal_moments.x, single_sphere_inertia(2.0, 1.0)) < 1e-13);
    assert!((p.center_of_mass - big.center).length() < 1e-14);
}

#[test]
fn tangent_and_disjoint_spheres() {
    // Externally tangent and disjoint spheres: volume is the plain sum.
    let s = [
        sphere(0.0, 0.0, 0.0, 1.0),
        sphere(2.0, 0.0, 0.0, 1.0),
        sphere(0.0, 5.0, 1.0, 0.5),
    ];
    let p = mass_properties(&s, 1.0).unwrap();
    assert!(rel(p.volume, p.naive_volume) < 1e-12);
    for k in 0..3 {
        assert!(rel(p.principal_moments[k], p.naive_principal_moments[k]) < 1e-10);
    }
}

fn l_trimer() -> Vec<Sphere> {
    vec![
        sphere(0.2, -0.1, 0.3, 1.0),
        sphere(1.6, -0.1, 0.5, 0.7),
        sphere(0.2, 1.1, 0.1, 0.5),
    ]
}

#[test]
fn l_trimer_body_frame_is_principal() {
    let t = ClumpTemplate::from_spheres("L", &l_trimer(), 1200.0).unwrap();
    let p = &t.properties;
    assert!(
        max_offdiag(&p.inertia) > 1e-3 * p.principal_moments.z,
        "input tensor should not be diagonal"
    );
    assert!(
        p.principal_moments.x < p.principal_moments.y
            && p.principal_moments.y < p.principal_moments.z
    );
    // Right-handed, orthonormal rows.
    let r = p.principal_axes;
    assert!(mat_max_abs(&(r * r.transpose() - DMat3::IDENTITY)) < 1e-13);
    assert!((r.determinant() - 1.0).abs() < 1e-13);
    assert!(
        (p.principal_axis(0).cross(p.principal_axis(1)) - p.principal_axis(2)).length() < 1e-13
    );
    // Each axis is an eigenvector.
    for k in 0..3 {
        let a = p.principal_axis(k);
        assert!(
            (p.inertia * a - p.principal_moments[k] * a).length() < 1e-12 * p.principal_moments.z
        );
    }
    // Body-frame spheres: COM at the origin, diagonal inertia = principal_inertia.
    let b = mass_properties(&t.spheres, 1200.0).unwrap();
    let scale = b.principal_moments.z;
    assert!(b.center_of_mass.length() < 1e-9 * t.bounding_radius);
    assert!(max_offdiag(&b.inertia) < 1e-9 * scale);
    for k in 0..3 {
        assert!(rel(b.inertia.col(k)[k], t.principal_inertia[k]) < 1e-9);
    }
    assert!(mat_max_abs(&(b.principal_axes - DMat3::IDENTITY)) < 1e-6);
    assert!(rel(b.volume, t.volume) < 1e-9);
    // input_to_body maps input-frame offsets to body-frame centres.
    for (s_in, s_b) in l_trimer().iter().zip(&t.spheres) {
        let c = t.input_to_body * (s_in.center - t.input_center_of_mass);
        assert!((c - s_b.center).length() < 1e-13);
        assert!(
            (t.body_to_input() * s_b.center + t.input_center_of_mass - s_in.center).length()
                < 1e-13
        );
    }
    let br = t
        .spheres
        .iter()
        .map(|s| s.center.length() + s.radius)
        .fold(0.0, f64::max);
    assert_eq!(t.bounding_radius, br);
    assert_eq!((t.min_radius, t.max_radius), (0.5, 1.0));
    assert!(rel(t.mass, 1200.0 * t.volume) < 1e-15);
}

#[test]
fn scaled_is_exact() {
    let t = ClumpTemplate::from_spheres("L", &l_trimer(), 2.0).unwrap();
    let s = 0.001;
    let ts = t.scaled(s);
    let spheres: Vec<Sphere> = l_trimer()
        .iter()
        .map(|x| Sphere::new(x.center * s, x.radius * s))
        .collect();
    let direct = ClumpTemplate::from_spheres("L", &spheres, 2.0).unwrap();
    assert!(rel(ts.mass, direct.mass) < 1e-10);
    assert!(rel(ts.mass, t.mass * 1e-9) < 1e-15);
    for k in 0..3 {
        assert!(rel(ts.principal_inertia[k], direct.principal_inertia[k]) < 1e-9);
        assert!(rel(ts.principal_inertia[k], t.principal_inertia[k] * 1e-15) < 1e-14);
    }
    for (a, b) in ts.spheres.iter().zip(&direct.spheres) {
        assert!((a.center - b.center).length() < 1e-12);
    }
    assert!(rel(ts.bounding_radius, direct.bounding_radius) < 1e-12);
}

#[test]
fn with_mass_and_override() {
    let spheres = l_trimer();
    let t = ClumpTemplate::from_spheres("L", &spheres, 1000.0).unwrap();
    let tm = ClumpTemplate::with_mass("L", &spheres, 2.0 * t.mass).unwrap();
    assert!(rel(tm.density, 2000.0) < 1e-14);
    assert!(rel(tm.principal_inertia.z, 2.0 * t.principal_inertia.z) < 1e-14);

    let inertia = DMat3::from_cols(
        DVec3::new(2.0, 0.5, 0.0),
        DVec3::new(0.5, 3.0, 0.0),
        DVec3::new(0.0, 0.0, 4.0),
    );
    let to = ClumpTemplate::with_override("L", &spheres, 1000.0, 7.0, inertia).unwrap();
    assert_eq!(to.mass, 7.0);
    assert_eq!(to.properties.inertia, inertia);
    let disc = ((1.0f64).powi(2) * 0.25 + 0.25).sqrt();
    assert!((to.principal_inertia.x - (2.5 - disc)).abs() < 1e-14);
    assert!((to.principal_inertia.y - (2.5 + disc)).abs() < 1e-14);
    assert!((to.principal_inertia.z - 4.0).abs() < 1e-14);
    assert_eq!(to.principal_inertia, to.properties.principal_moments);
    assert!((to.properties.principal_axis(2) - DVec3::Z).length() < 1e-14);
    assert_eq!(to.input_center_of_mass, t.input_center_of_mass);
    // Bad overrides.
    assert!(matches!(
        ClumpTemplate::with_override("L", &spheres, 1000.0, -1.0, inertia),
        Err(ShapeError::InvalidMass { .. })
    ));
    assert!(matches!(
        ClumpTemplate::with_override(
            "L",
            &spheres,
            1000.0,
            1.0,
            DMat3::from_diagonal(DVec3::new(1.0, 1.0, 3.0))
        ),
        Err(ShapeError::InvalidInertia { .. })
    ));
    assert!(matches!(
        ClumpTemplate::with_override(
            "L",
            &spheres,
            1000.0,
            1.0,
            DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0))
        ),
        Err(ShapeError::InvalidInertia { .. })
    ));
}

#[test]
fn degenerate_inputs_are_errors() {
    let ok = sphere(0.0, 0.0, 0.0, 1.0);
    assert_eq!(mass_properties(&[], 1.0), Err(ShapeError::EmptyTemplate));
    assert!(matches!(
        mass_properties(&[ok, sphere(1.0, 0.0, 0.0, 0.0)], 1.0),
        Err(ShapeError::NonPositiveRadius { index: 1, .. })
    ));
    assert!(matches!(
        mass_properties(&[sphere(1.0, 0.0, 0.0, -2.0)], 1.0),
        Err(ShapeError::NonPositiveRadius { index: 0, .. })
    ));
    assert!(matches!(
        mass_properties(&[ok, sphere(f64::NAN, 0.0, 0.0, 1.0)], 1.0),
        Err(ShapeError::NonFiniteSphere { index: 1, .. })
    ));
    assert!(matches!(
        mass_properties(&[sphere(0.0, f64::INFINITY, 0.0, 1.0)], 1.0),
        Err(ShapeError::NonFiniteSphere { index: 0, .. })
    ));
    assert!(matches!(
        mass_properties(&[sphere(0.0, 0.0, 0.0, f64::NAN)], 1.0),
        Err(ShapeError::NonFiniteSphere { index: 0, .. })
    ));
    for rho in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            mass_properties(&[ok], rho),
            Err(ShapeError::InvalidDensity { .. })
        ));
    }
    assert!(matches!(
        ClumpTemplate::with_mass("x", &[ok], 0.0),
        Err(ShapeError::InvalidMass { .. })
    ));
    // Messages are readable.
    let e = mass_properties(&[ok, sphere(1.0, 0.0, 0.0, 0.0)], 1.0).unwrap_err();
    assert!(e.to_string().contains("radius must be > 0"), "{e}");
}

/// The tetra-bed template (REFERENCE: bench/tetra-bed/README.md): r = 1 mm,
/// edge 1.2 mm, ρ = 2500; Monte-Carlo values agree to ~1e-3.
#[test]
fn tetra_bed_template() {
    let check = |spheres: &[Sphere]| {
        let t = ClumpTemplate::from_spheres("tetra", spheres, 2500.0).unwrap();
        assert!(rel(t.mass, 3.166825e-05) < 1e-3, "mass {}", t.mass);
        for k in 0..3 {
            assert!(
                rel(t.principal_inertia[k], 2.84709e-11) < 1e-3,
                "I {}",
                t.principal_inertia[k]
            );
        }
        // Isotropic (tetrahedral symmetry): identity principal frame.
        assert!(rel(t.principal_inertia.x, t.principal_inertia.z) < 1e-9);
        assert_eq!(t.properties.principal_axes, DMat3::IDENTITY);
        assert!(t.properties.relative_error_bound <= 1e-6);
        t
    };
    let builtin = check(&tetrahedron(1e-3, 1.2e-3));
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/bench/tetra-bed/tetra.xyzr"
    );
    if let Ok(text) = std::fs::read_to_string(path) {
        let spheres: Vec<Sphere> = text
            .lines()
            .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .map(|l| {
                let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                sphere(v[0], v[1], v[2], v[3])
            })
            .collect();
        let file = check(&spheres);
        assert!(rel(file.mass, builtin.mass) < 1e-12);
    }
}

#[test]
fn builtins() {
    let s = mass_properties(&single_sphere(0.5), 1.0).unwrap();
    assert!(rel(s.volume, 4.0 / 3.0 * PI * 0.125) < 1e-15);

    let r = rod(5, 0.5, 0.6);
    assert_eq!(r.len(), 5);
    assert!((r[0].center.x + 1.2).abs() < 1e-15 && (r[4].center.x - 1.2).abs() < 1e-15);
    let p = mass_properties(&r, 1.0).unwrap();
    assert!(p.center_of_mass.length() < 1e-12);
    assert!(mat_max_abs(&(p.principal_axes - DMat3::IDENTITY)) < 1e-12);
    assert!(p.volume < p.naive_volume);

    // The same rod along z (coaxial discs in every slice) and along a diagonal.
    let q = DQuat::from_rotation_arc(DVec3::X, DVec3::Z);
    let rz: Vec<Sphere> = r
        .iter()
        .map(|s| Sphere::new(q * s.center, s.radius))
        .collect();
    let pz = mass_properties(&rz, 1.0).unwrap();
    assert!(rel(pz.volume, p.volume) < 1e-9);
    assert!((pz.principal_axis(0) - DVec3::Z).length() < 1e-9);
    let qd = DQuat::from_rotation_arc(DVec3::X, DVec3::new(1.0, -2.0, 0.5).normalize());
    let rd: Vec<Sphere> = r
        .iter()
        .map(|s| Sphere::new(qd * s.center, s.radius))
        .collect();
    let pd = mass_properties(&rd, 1.0).unwrap();
    for k in 0..3 {
        assert!(rel(pz.principal_moments[k], p.principal_moments[k]) < 1e-9);
        assert!(rel(pd.principal_moments[k], p.principal_moments[k]) < 1e-9);
    }

    let c = cube_octet(0.6, 1.0);
    assert_eq!(c.len(), 8);
    let p = mass_properties(&c, 1.0).unwrap();
    assert_eq!(p.principal_axes, DMat3::IDENTITY);
    assert!(rel(p.principal_moments.x, p.principal_moments.z) < 1e-9);

    let t = tetrahedron(0.1, 1.0);
    for i in 0..4 {
        for j in i + 1..4 {
            assert!(rel((t[i].center - t[j].center).length(), 1.0) < 1e-15);
        }
    }
    assert!(t.iter().map(|s| s.center).sum::<DVec3>().length() < 1e-15);
}

#[test]
fn fifty_sphere_cluster_is_accurate() {
    // A deterministic pseudo-random "stone" of 50 overlapping spheres.
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let spheres: Vec<Sphere> = (0..50)
        .map(|_| sphere(4.0 * rnd(), 3.0 * rnd(), 2.0 * rnd(), 0.5 + rnd()))
        .collect();
    let p = mass_properties(&spheres, 1.0).unwrap();
    assert!(p.relative_error_bound <= 1e-8, "{}", p.relative_error_bound);
    assert!(p.volume < p.naive_volume);
}

fn arb_cluster() -> impl Strategy<Value = Vec<Sphere>> {
    prop::collection::vec(
        ((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 0.3f64..1.2),
        1..7,
    )
    .prop_map(|v| {
        v.into_iter()
            .map(|((x, y, z), r)| sphere(x, y, z, r))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn rigid_motion_invariance(
        spheres in arb_cluster(),
        axis in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        angle in 0.0f64..6.3,
        shift in (-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0),
    ) {
        let axis = DVec3::new(axis.0, axis.1, axis.2);
        prop_assume!(axis.length() > 0.1);
        let q = DQuat::from_axis_angle(axis.normalize(), angle);
        let t = DVec3::new(shift.0, shift.1, shift.2);
        let moved: Vec<Sphere> = spheres.iter().map(|s| Sphere::new(q * s.center + t, s.radius)).collect();
        let a = mass_properties(&spheres, 1.0).unwrap();
        let b = mass_properties(&moved, 1.0).unwrap();
        prop_assert!(rel(b.volume, a.volume) < 1e-9, "{} {}", a.volume, b.volume);
        let scale = a.principal_moments.z;
        for k in 0..3 {
            prop_assert!((a.principal_moments[k] - b.principal_moments[k]).abs() < 1e-9 * scale,
                "{:?} {:?}", a.principal_moments, b.principal_moments);
        }
        prop_assert!((q * a.center_of_mass + t - b.center_of_mass).length() < 1e-9 * (1.0 + t.length()));
        prop_assert!(a.relative_error_bound <= 1e-6 && b.relative_error_bound <= 1e-6);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// The asymmetric L-shaped trimer with unequal radii, rotated and
    /// translated arbitrarily: the same principal moments (compared with the
    /// unmoved template), and its body-frame tensor is diagonal.
    #[test]
    fn l_trimer_rigid_motion_invariance(
        axis in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        angle in 0.0f64..6.3,
        shift in (-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0),
    ) {
        let axis = DVec3::new(axis.0, axis.1, axis.2);
        prop_assume!(axis.length() > 0.1);
        let q = DQuat::from_axis_angle(axis.normalize(), angle);
        let t = DVec3::new(shift.0, shift.1, shift.2);
        let base = ClumpTemplate::from_spheres("L", &l_trimer(), 1200.0).unwrap();
        let moved: Vec<Sphere> = l_trimer().iter().map(|s| Sphere::new(q * s.center + t, s.radius)).collect();
        let m = ClumpTemplate::from_spheres("L moved", &moved, 1200.0).unwrap();
        let scale = base.principal_inertia.z;
        for k in 0..3 {
            prop_assert!((m.principal_inertia[k] - base.principal_inertia[k]).abs() < 1e-9 * scale);
        }
        let b = mass_properties(&m.spheres, 1200.0).unwrap();
        prop_assert!(max_offdiag(&b.inertia) < 1e-9 * scale);
        prop_assert!(b.center_of_mass.length() < 1e-9 * m.bounding_radius);
    }
}
