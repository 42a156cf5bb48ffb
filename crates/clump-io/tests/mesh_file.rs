//! STL (ASCII, binary) and OBJ loading, with welding and the import transform.

use clump_io::mesh_file::{read_mesh_file, stl_ascii, stl_binary, MeshFileError, MeshTransform};
use glam::{DQuat, DVec3};
use std::path::PathBuf;

/// The path `name` in a fresh directory, which is removed when the returned
/// guard is dropped.
fn tmp(name: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::Builder::new()
        .prefix("clump-mesh-file-")
        .tempdir()
        .unwrap();
    let path = dir.path().join(name);
    (dir, path)
}

/// A closed unit cube `[0, 1]³`, 12 triangles, outward winding.
fn cube() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    clump_core::wall::mesh::primitives::cuboid(DVec3::ZERO, DVec3::ONE)
}

fn check_cube(m: &clump_core::wall::TriMesh, scale: f64, offset: DVec3) {
    assert_eq!(m.triangles().len(), 12);
    assert_eq!(m.vertices().len(), 8, "corners are welded into 8 vertices");
    m.check_closed().expect("closed");
    let (lo, hi) = m.bounds();
    assert!((lo - offset).length() < 1e-6 * scale, "{lo}");
    assert!(
        (hi - (offset + DVec3::splat(scale))).length() < 1e-6 * scale,
        "{hi}"
    );
}

#[test]
fn binary_stl() {
    let (v, t) = cube();
    let (_dir_p, p) = tmp("cube_bin.stl");
    let mut bytes = stl_binary(&v, &t);
    // binary files may begin with "solid" too
    bytes[..5].copy_from_slice(b"solid");
    std::fs::write(&p, &bytes).unwrap();
    let m = read_mesh_file(&p, &MeshTransform::default()).unwrap();
    check_cube(&m, 1.0, DVec3::ZERO);
    let tr = MeshTransform {
        scale: 0.001,
        rotation: DQuat::IDENTITY,
        offset: DVec3::new(1.0, 2.0, 3.0),
    };
    let m = read_mesh_file(&p, &tr).unwrap();
    check_cube(&m, 0.001, DVec3::new(1.0, 2.0, 3.0));
    // truncated binary, not ASCII either
    std::fs::write(&p, &bytes[..bytes.len() - 7]).unwrap();
    let e = read_mesh_file(&p, &MeshTransform::default()).unwrap_err();
    assert!(matches!(e, MeshFileError::Syntax { .. }), "{e}");
}

#[test]
fn ascii_stl() {
    let (v, t) = cube();
    let (_dir_p, p) = tmp("cube_ascii.STL");
    std::fs::write(&p, stl_ascii("cube", &v, &t)).unwrap();
    // rotated 90° about z, then shifted
    let tr = MeshTransform {
        scale: 2.0,
        rotation: DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
        offset: DVec3::new(2.0, 0.0, 0.0),
    };
    let m = read_mesh_file(&p, &tr).unwrap();
    assert_eq!((m.vertices().len(), m.triangles().len()), (8, 12));
    let (lo, hi) = m.bounds();
    assert!((lo - DVec3::new(0.0, 0.0, 0.0)).length() < 1e-12, "{lo}");
    assert!((hi - DVec3::new(2.0, 2.0, 2.0)).length() < 1e-12, "{hi}");
    // a facet with 2 vertices is an error naming the line
    let bad = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n";
    std::fs::write(&p, bad).unwrap();
    let e = read_mesh_file(&p, &MeshTransform::default()).unwrap_err();
    assert!(matches!(e, MeshFileError::Syntax { line: 7, .. }), "{e}");
    assert!(e.to_string().contains("2 vertices"), "{e}");
    // a non-number
    std::fs::write(
        &p,
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n",
    )
    .unwrap();
    let e = read_mesh_file(&p, &MeshTransform::default()).unwrap_err();
    assert!(e.to_string().contains(":4:"), "{e}");
}

#[test]
fn obj() {
    // the cube as six quads, with texture/normal index forms and a negative index
    let text = "# cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nvt 0 0\nvn 0 0 1\n\
                f 1 3 4 2\nf 5/1 6/1 8/1 7/1\nf 1//1 2//1 6//1 5//1\nf 3/1/1 7/1/1 8/1/1 4/1/1\nf 1 5 7 3\nf -7 -5 -1 -3\n";
    let (_dir_p, p) = tmp("cube.obj");
    std::fs::write(&p, text).unwrap();
    let m = read_mesh_file(
        &p,
        &MeshTransform {
            scale: 3.0,
            ..Default::default()
        },
    )
    .unwrap();
    check_cube(&m, 3.0, DVec3::ZERO);
    std::fs::write(&p, "v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap();
    let e = read_mesh_file(&p, &MeshTransform::default()).unwrap_err();
    assert!(
        e.to_string().contains(":3:") && e.to_string().contains("out of range"),
        "{e}"
    );
}

#[test]
fn errors() {
    let (_dir_p, p) = tmp("mesh.ply");
    std::fs::write(&p, "ply").unwrap();
    assert!(matches!(
        read_mesh_file(&p, &MeshTransform::default()),
        Err(MeshFileError::UnknownFormat { .. })
    ));
    let (_dir_missing, missing) = tmp("missing.stl");
    let e = read_mesh_file(missing, &MeshTransform::default()).unwrap_err();
    assert!(matches!(e, MeshFileError::Io { .. }));
    let (v, t) = cube();
    let (_dir_q, q) = tmp("c.stl");
    std::fs::write(&q, stl_binary(&v, &t)).unwrap();
    let e = read_mesh_file(
        &q,
        &MeshTransform {
            scale: 0.0,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(matches!(e, MeshFileError::BadScale { .. }));
    // arbitrary bytes never panic
    std::fs::write(&q, [0xffu8, 0x00, 0x13, 0x37]).unwrap();
    assert!(read_mesh_file(&q, &MeshTransform::default()).is_err());
}
