//! The VTK output is valid: read back with an independent minimal parser of
//! VTK XML PolyData with raw appended data (UInt64 headers).

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::ContactTable;
use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{self, ClumpTemplate};
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use clump_io::vtk::{self, PvdWriter, VtkSeries, CYLINDER_SEGMENTS};
use glam::{DQuat, DVec3};
use std::collections::HashMap;

#[derive(Debug, Clone)]
struct Arr {
    ty: String,
    comps: usize,
    offset: usize,
}

struct Parsed {
    attrs: HashMap<String, String>,
    arrays: HashMap<(String, String), Arr>,
    data: Vec<u8>,
}

fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!("{name}=\"");
    let i = tag.find(&key)? + key.len();
    let j = tag[i..].find('"')?;
    Some(tag[i..i + j].to_string())
}

fn parse(bytes: &[u8]) -> Parsed {
    let marker = b"<AppendedData encoding=\"raw\">";
    let pos = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("AppendedData");
    let under = pos + bytes[pos..].iter().position(|&b| b == b'_').expect("_");
    let header = std::str::from_utf8(&bytes[..pos]).expect("utf8 header");
    assert!(header.contains("header_type=\"UInt64\""));
    assert!(header.contains("byte_order=\"LittleEndian\""));
    assert!(header.contains("type=\"PolyData\""));
    let tail = b"</AppendedData>\n</VTKFile>\n";
    assert!(bytes.ends_with(tail));
    let mut attrs = HashMap::new();
    let mut arrays = HashMap::new();
    let mut section = String::new();
    for tag in header.split('<').skip(1) {
        let tag = tag.split('>').next().unwrap();
        let name = tag.split_whitespace().next().unwrap_or("");
        match name {
            "Piece" => {
                for k in ["NumberOfPoints", "NumberOfVerts", "NumberOfPolys"] {
                    attrs.insert(k.to_string(), attr(tag, k).unwrap());
                }
            }
            "PointData" | "CellData" | "Points" | "Verts" | "Polys" => section = name.to_string(),
            "DataArray" => {
                assert_eq!(attr(tag, "format").as_deref(), Some("appended"));
                let a = Arr {
                    ty: attr(tag, "type").unwrap(),
                    comps: attr(tag, "NumberOfComponents").unwrap().parse().unwrap(),
                    offset: attr(tag, "offset").unwrap().parse().unwrap(),
                };
                arrays.insert((section.clone(), attr(tag, "Name").unwrap()), a);
            }
            _ => {}
        }
    }
    let data = bytes[under + 1..bytes.len() - tail.len()].to_vec();
    Parsed {
        attrs,
        arrays,
        data,
    }
}

impl Parsed {
    fn n(&self, k: &str) -> usize {
        self.attrs[k].parse().unwrap()
    }
    fn raw(&self, section: &str, name: &str) -> (&Arr, &[u8]) {
        let a = &self.arrays[&(section.to_string(), name.to_string())];
        let len =
            u64::from_le_bytes(self.data[a.offset..a.offset + 8].try_into().unwrap()) as usize;
        (a, &self.data[a.offset + 8..a.offset + 8 + len])
    }
    fn f64s(&self, section: &str, name: &str) -> (usize, Vec<f64>) {
        let (a, b) = self.raw(section, name);
        assert_eq!(a.ty, "Float64");
        (
            a.comps,
            b.chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect(),
        )
    }
    fn i64s(&self, section: &str, name: &str) -> Vec<i64> {
        let (a, b) = self.raw(section, name);
        assert!(a.ty == "Int64" || a.ty == "UInt64");
        b.chunks_exact(8)
            .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
    fn i32s(&self, section: &str, name: &str) -> Vec<i32> {
        let (a, b) = self.raw(section, name);
        assert_eq!(a.ty, "Int32");
        b.chunks_exact(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
}

fn world() -> World {
    let mats = vec![Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }];
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(0.1, 0.2, 0.3),
            periodic: [false; 3],
        },
        gravity: DVec3::new(0.0, 0.0, -9.81),
        dt: 1e-5,
        rotation: RotationScheme::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let t =
        ClumpTemplate::from_spheres("tetra", &shape::tetrahedron(1e-3, 1.5e-3), 2500.0).unwrap();
    w.add_template(t, 0).unwrap();
    let s = ClumpTemplate::from_spheres("ball", &shape::single_sphere(2e-3), 2500.0).unwrap();
    w.add_template(s, 0).unwrap();
    for i in 0..5 {
        let x = DVec3::new(0.01 + 0.01 * i as f64, 0.05, 0.05);
        let q = DQuat::from_rotation_y(0.3 * i as f64) * DQuat::from_rotation_x(0.1);
        let init = BodyInit {
            velocity: DVec3::new(0.1 * i as f64, -0.2, 1.0 / 3.0),
            angular_velocity: DVec3::new(1.0, 2.0, 3.0 + i as f64),
            ..BodyInit::at_rest((i % 2) as u32, x, q)
        };
        w.add_body(&init).unwrap();
    }
    let wall = |name: &str, shape| Wall {
        name: name.into(),
        shape,
        material: 0,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    };
    w.add_wall(wall(
        "floor",
        WallShape::Plane {
            point: DVec3::ZERO,
            normal: DVec3::Z,
        },
    ))
    .unwrap();
    w.add_wall(wall(
        "tilted",
        WallShape::Plane {
            point: DVec3::new(0.05, 0.1, 0.15),
            normal: DVec3::new(10.0, 5.0, 10.0 / 3.0).normalize(),
        },
    ))
    .unwrap();
    w.add_wall(wall(
        "drum",
        WallShape::Cylinder {
            point: DVec3::new(0.05, 0.1, 0.0),
            axis: DVec3::Z,
            radius: 0.04,
            inside: true,
        },
    ))
    .unwrap();
    w.add_wall(wall(
        "box",
        WallShape::Box {
            lo: DVec3::splat(0.01),
            hi: DVec3::splat(0.02),
            inside: false,
        },
    ))
    .unwrap();
    let mesh = TriMesh::new(
        vec![
            DVec3::ZERO,
            DVec3::new(0.01, 0.0, 0.0),
            DVec3::new(0.0, 0.01, 0.0),
            DVec3::new(0.01, 0.01, 0.0),
        ],
        vec![[0, 1, 2], [1, 3, 2]],
    )
    .unwrap();
    let m = w.add_mesh(mesh);
    w.add_wall(wall(
        "ramp",
        WallShape::Mesh {
            mesh: m,
            position: DVec3::new(0.0, 0.0, 0.1),
            orientation: DQuat::from_rotation_x(0.2),
        },
    ))
    .unwrap();
    w
}

#[test]
fn spheres_file_round_trips() {
    let w = world();
    let p = parse(&vtk::spheres_vtp(&w));
    let n: usize = w
        .bodies()
        .template
        .iter()
        .map(|&t| w.templates[t as usize].spheres.len())
        .sum();
    assert_eq!(n, 3 * 4 + 2);
    assert_eq!(p.n("NumberOfPoints"), n);
    assert_eq!(p.n("NumberOfVerts"), n);
    let (c, pts) = p.f64s("Points", "Points");
    let (_, rad) = p.f64s("PointData", "radius");
    let (vc, vel) = p.f64s("PointData", "velocity");
    let ids = p.i64s("PointData", "body_id");
    assert_eq!((c, vc), (3, 3));
    assert_eq!(
        (pts.len(), rad.len(), vel.len(), ids.len()),
        (3 * n, n, 3 * n, n)
    );
    let mut k = 0;
    for b in 0..w.bodies().len() {
        let t = &w.templates[w.bodies().template[b] as usize];
        for s in &t.spheres {
            let x = w.bodies().position[b] + w.bodies().orientation[b] * s.center;
            let v = w.bodies().velocity[b]
                + w.bodies().angular_velocity[b].cross(x - w.bodies().position[b]);
            assert_eq!(rad[k], s.radius);
            assert_eq!(ids[k] as u64, w.bodies().id[b]);
            assert_eq!(&pts[3 * k..3 * k + 3], &x.to_array());
            assert_eq!(&vel[3 * k..3 * k + 3], &v.to_array());
            k += 1;
        }
    }
    assert_eq!(p.i64s("Verts", "offsets").last().copied(), Some(n as i64));
}

#[test]
fn bodies_file_round_trips() {
    let w = world();
    let p = parse(&vtk::bodies_vtp(&w));
    let n = w.bodies().len();
    assert_eq!(p.n("NumberOfPoints"), n);
    let (_, pts) = p.f64s("Points", "Points");
    let (qc, q) = p.f64s("PointData", "quaternion");
    let (_, vel) = p.f64s("PointData", "velocity");
    let (_, om) = p.f64s("PointData", "angular_velocity");
    let (_, ex) = p.f64s("PointData", "ex");
    let (_, ez) = p.f64s("PointData", "ez");
    let (_, mass) = p.f64s("PointData", "mass");
    let tpl = p.i32s("PointData", "template");
    assert_eq!(qc, 4);
    for b in 0..n {
        let o = w.bodies().orientation[b];
        assert_eq!(&pts[3 * b..3 * b + 3], &w.bodies().position[b].to_array());
        assert_eq!(&q[4 * b..4 * b + 4], &[o.w, o.x, o.y, o.z]);
        assert_eq!(&vel[3 * b..3 * b + 3], &w.bodies().velocity[b].to_array());
        assert_eq!(
            &om[3 * b..3 * b + 3],
            &w.bodies().angular_velocity[b].to_array()
        );
        assert_eq!(&ex[3 * b..3 * b + 3], &(o * DVec3::X).to_array());
        assert_eq!(&ez[3 * b..3 * b + 3], &(o * DVec3::Z).to_array());
        assert_eq!(mass[b], w.bodies().mass[b]);
        assert_eq!(tpl[b] as u32, w.bodies().template[b]);
    }
}

/// A body of a scaled copy of a template (as a mix's size distribution
/// adds them) reports the scenario's template index and its size factor.
#[test]
fn bodies_of_scaled_templates_report_their_base_template_and_scale() {
    let mut w = world();
    let scaled = w.templates[0].scaled(1.25);
    let t = w.add_template(scaled, 0).unwrap();
    assert_eq!(t, 2);
    w.add_body(&BodyInit::at_rest(
        t,
        DVec3::new(0.05, 0.02, 0.02),
        DQuat::IDENTITY,
    ))
    .unwrap();
    let p = parse(&vtk::bodies_vtp(&w));
    let tpl = p.i32s("PointData", "template");
    let (_, scale) = p.f64s("PointData", "scale");
    let n = w.bodies().len();
    for b in 0..n {
        let (want_t, want_s) = match w.bodies().template[b] {
            2 => (0, 1.25),
            t => (t as i32, 1.0),
        };
        assert_eq!(tpl[b], want_t);
        assert!((scale[b] - want_s).abs() < 1e-12, "{}", scale[b]);
    }
    assert!(tpl.iter().filter(|&&t| t == 0).count() >= 2);
}

#[test]
fn walls_file_has_polygons_on_the_walls() {
    let w = world();
    let p = parse(&vtk::walls_vtp(&w));
    let n_polys = p.n("NumberOfPolys");
    assert_eq!(n_polys, 1 + 1 + CYLINDER_SEGMENTS + 6 + 2);
    let idx = p.i32s("CellData", "wall_index");
    assert_eq!(idx.len(), n_polys);
    let (_, pts) = p.f64s("Points", "Points");
    let conn = p.i64s("Polys", "connectivity");
    let offs = p.i64s("Polys", "offsets");
    assert_eq!(offs.len(), n_polys);
    assert_eq!(*offs.last().unwrap() as usize, conn.len());
    let pt = |i: i64| {
        DVec3::new(
            pts[3 * i as usize],
            pts[3 * i as usize + 1],
            pts[3 * i as usize + 2],
        )
    };
    let mut start = 0usize;
    for (c, &end) in offs.iter().enumerate() {
        let verts: Vec<DVec3> = conn[start..end as usize].iter().map(|&i| pt(i)).collect();
        assert!(verts.len() >= 3);
        match w.walls[idx[c] as usize].shape {
            WallShape::Plane { point, normal } => {
                for v in &verts {
                    assert!((*v - point).dot(normal).abs() < 1e-12);
                    assert!(
                        v.cmpge(DVec3::splat(-1e-12)).all()
                            && v.cmple(DVec3::new(0.1, 0.2, 0.3) + 1e-12).all()
                    );
                }
                if idx[c] == 0 {
                    assert_eq!(verts.len(), 4);
                } else {
                    assert_eq!(
                        verts.len(),
                        6,
                        "the plane x/a + y/b + z/c = 3/2 cuts a hexagon"
                    );
                }
            }
            WallShape::Cylinder {
                point,
                axis,
                radius,
                ..
            } => {
                for v in &verts {
                    let r = *v - point;
                    assert!(((r - axis * r.dot(axis)).length() - radius).abs() < 1e-12);
                    assert!(r.z > -1e-12 && r.z < 0.3 + 1e-12);
                }
            }
            WallShape::Mesh {
                position,
                orientation,
                ..
            } => {
                assert_eq!(verts.len(), 3);
                let n = orientation * DVec3::Z;
                assert!(verts.iter().all(|v| (*v - position).dot(n).abs() < 1e-15));
            }
            WallShape::Box { lo, hi, .. } => {
                assert_eq!(verts.len(), 4);
                assert!(verts.iter().all(|v| v.cmpge(lo).all() && v.cmple(hi).all()));
            }
        }
        start = end as usize;
    }
}

#[test]
fn series_writes_files_and_pvd() {
    let dir = std::env::temp_dir().join(format!("clump_vtk_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut w = world();
    let mut s = VtkSeries::new(&dir).unwrap();
    s.write_frame(&w, 0).unwrap();
    w.run(3).unwrap();
    s.write_frame(&w, 3).unwrap();
    for f in [
        "spheres_000000.vtp",
        "bodies_000003.vtp",
        "walls_000003.vtp",
        "spheres.pvd",
        "bodies.pvd",
        "walls.pvd",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let pvd = std::fs::read_to_string(dir.join("bodies.pvd")).unwrap();
    assert!(
        pvd.contains("file=\"bodies_000000.vtp\"") && pvd.contains("file=\"bodies_000003.vtp\"")
    );
    // parse a written file too
    let p = parse(&std::fs::read(dir.join("spheres_000003.vtp")).unwrap());
    assert_eq!(p.n("NumberOfPoints"), 14);
    // resume drops later entries
    let r = PvdWriter::resume(dir.join("bodies.pvd"), 0.0);
    assert_eq!(r.entries().len(), 1);
    assert_eq!(r.entries()[0].1, "bodies_000000.vtp");
    // no temporary files are left behind
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp."))
        .collect();
    assert!(leftovers.is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}
