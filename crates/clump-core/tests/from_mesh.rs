//! Templates generated from a closed mesh (CLUMP Euclidean-map method), the
//! polyhedron mass properties, and the closed-mesh checks.

use clump_core::shape::from_mesh::{
    fidelity, generate, polyhedron_properties, FromMeshError, FromMeshOptions,
};
use clump_core::wall::{MeshError, TriMesh};
use glam::{DQuat, DVec3};

use clump_core::wall::mesh::primitives::{cuboid, icosphere};

#[test]
fn polyhedron_properties_of_a_box() {
    // a 2 × 1 × 0.5 box, with the winding of half its triangles flipped
    let lo = DVec3::new(5.0, -3.0, 1.0);
    let (v, mut t) = cuboid(lo, lo + DVec3::new(2.0, 1.0, 0.5));
    // flip the winding of every other face (two triangles per face)
    for (k, tri) in t.iter_mut().enumerate() {
        if (k / 2) % 2 == 1 {
            tri.swap(1, 2);
        }
    }
    let m = TriMesh::new(v, t).unwrap();
    let p = polyhedron_properties(&m).unwrap();
    assert!((p.volume - 1.0).abs() < 1e-12);
    assert!((p.center_of_mass - DVec3::new(6.0, -2.5, 1.25)).length() < 1e-12);
    let i = |a: f64, b: f64| (a * a + b * b) / 12.0;
    let exact = DVec3::new(i(1.0, 2.0), i(0.5, 2.0), i(0.5, 1.0));
    let mut sorted = exact.to_array();
    sorted.sort_by(f64::total_cmp);
    assert!(
        (p.principal_moments - DVec3::from_array(sorted)).length() < 1e-12,
        "{:?}",
        p.principal_moments
    );
}

#[test]
fn ellipsoid_template() {
    let (v, t) = icosphere(4);
    let axes = DVec3::new(3.0, 2.0, 1.0);
    let q = DQuat::from_euler(glam::EulerRot::ZYX, 0.4, -0.3, 0.7);
    let shift = DVec3::new(0.3, -1.0, 2.0);
    let m = TriMesh::new(v.iter().map(|&p| shift + q * (p * axes)).collect(), t).unwrap();
    let opt = FromMeshOptions {
        max_spheres: 50,
        resolution: 40,
        ..Default::default()
    };
    let t0 = std::time::Instant::now();
    let spheres = generate(&m, &opt).unwrap();
    let f = fidelity(&m, &spheres, 20_000).unwrap();
    eprintln!(
        "{} spheres in {:.2} s: volume error {:+.3} %, moments {:+.3?} %, axes {:.3?} deg, surface deviation mean {:.4} max {:.4}",
        spheres.len(),
        t0.elapsed().as_secs_f64(),
        100.0 * f.volume_error,
        (100.0 * f.moment_errors).to_array(),
        f.axis_errors_deg.to_array(),
        f.mean_surface_deviation,
        f.max_surface_deviation
    );
    assert!(spheres.len() <= 50);
    assert!(
        f.moment_errors.abs().max_element() < 0.03,
        "{:?}",
        f.moment_errors
    );
    assert!(f.mean_surface_deviation < 0.1);
    let v_exact = 4.0 / 3.0 * std::f64::consts::PI * 6.0;
    assert!(
        ((f.clump.volume - v_exact) / v_exact).abs() < 0.02,
        "volume {} vs {v_exact}",
        f.clump.volume
    );
    // principal axes of the ellipsoid: the rotated x (smallest moment), y, z
    for (k, e) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        let angle = f
            .clump
            .principal_axis(k)
            .dot(q * e)
            .abs()
            .min(1.0)
            .acos()
            .to_degrees();
        assert!(angle < 2.0, "axis {k}: {angle}°");
    }
    assert!(f.axis_errors_deg.max_element() < 2.0);
    // the polyhedron itself is close to the ellipsoid
    assert!(((f.mesh.volume - v_exact) / v_exact).abs() < 0.01);
    assert!((f.mesh.center_of_mass - shift).length() < 1e-9);
}

#[test]
fn tolerance_stops_early() {
    let (v, t) = icosphere(3);
    let m = TriMesh::new(
        v.iter().map(|&p| p * DVec3::new(2.0, 1.0, 1.0)).collect(),
        t,
    )
    .unwrap();
    let few = generate(
        &m,
        &FromMeshOptions {
            max_spheres: 200,
            tolerance: Some(0.2),
            resolution: 20,
            ..Default::default()
        },
    )
    .unwrap();
    let many = generate(
        &m,
        &FromMeshOptions {
            max_spheres: 200,
            tolerance: Some(0.02),
            resolution: 20,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(few.len() < many.len(), "{} vs {}", few.len(), many.len());
    // without refinement every sphere lies inside the mesh (inscribed)
    let inscribed = generate(
        &m,
        &FromMeshOptions {
            max_spheres: 200,
            tolerance: Some(0.02),
            resolution: 20,
            refine_iterations: 0,
            ..Default::default()
        },
    )
    .unwrap();
    for s in &inscribed {
        assert!(m.contains(s.center));
        assert!(m.closest_point(s.center).2 >= s.radius * (1.0 - 1e-12));
    }
}

#[test]
fn open_or_non_manifold_mesh_is_an_error() {
    let (v, mut t) = icosphere(1);
    let removed = t.pop().unwrap();
    let m = TriMesh::new(v.clone(), t.clone()).unwrap();
    let e = generate(&m, &FromMeshOptions::default()).unwrap_err();
    assert!(
        matches!(e, FromMeshError::Mesh(MeshError::OpenEdge { .. })),
        "{e}"
    );
    let msg = e.to_string();
    assert!(msg.contains("open boundary edge between vertices"), "{msg}");
    // a fin: a third triangle on an existing edge
    t.push(removed);
    let mut v2 = v.clone();
    v2.push(DVec3::new(5.0, 5.0, 5.0));
    t.push([t[0][0], t[0][1], v2.len() as u32 - 1]);
    let m = TriMesh::new(v2, t).unwrap();
    let e = generate(&m, &FromMeshOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.starts_with("non-manifold edge between vertices"),
        "{msg}"
    );
    assert!(polyhedron_properties(&m).is_err());
    // bad options
    let (v, t) = icosphere(1);
    let m = TriMesh::new(v, t).unwrap();
    assert!(matches!(
        generate(
            &m,
            &FromMeshOptions {
                overlap: 1.0,
                ..Default::default()
            }
        ),
        Err(FromMeshError::Option(_))
    ));
    assert!(matches!(
        generate(
            &m,
            &FromMeshOptions {
                max_spheres: 0,
                ..Default::default()
            }
        ),
        Err(FromMeshError::Option(_))
    ));
}
