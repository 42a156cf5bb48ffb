//! thermo.csv and trajectory files: columns, flushing, resume truncation.

use clump_core::thermo::Thermo;
use clump_core::wall::WallLoad;
use clump_io::atomic::write_atomic;
use clump_io::thermo_csv::ThermoWriter;
use glam::DVec3;

fn dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("clump_logs_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn thermo(step: u64) -> Thermo {
    Thermo {
        time: step as f64 * 1e-5,
        step,
        bodies: 10,
        pair_contacts: 3,
        wall_contacts: 2,
        kinetic_translational: 1.5e-7,
        kinetic_rotational: 0.25,
        elastic: 0.0,
        potential: -3.0,
        max_overlap_ratio: 0.01,
        lost_bodies: 1,
        wall_loads: vec![WallLoad {
            force: DVec3::new(1.0, 2.0, 3.0),
            torque: DVec3::new(-1.0, 0.0, 1e-20),
        }],
        heat: None,
        fluid_force: None,
    }
}

#[test]
fn thermo_rows_and_resume() {
    let d = dir("thermo");
    let p = d.join("thermo.csv");
    let names = vec!["floor plate".to_string()];
    let mut w = ThermoWriter::create(&p, &names).unwrap();
    for s in [0, 100, 200, 300] {
        w.write(&thermo(s)).unwrap();
    }
    // flushed without dropping the writer
    let text = std::fs::read_to_string(&p).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 5);
    assert!(lines[0].starts_with(
        "time[s],step,bodies,contacts,pair_contacts,wall_contacts,ke_translational[J]"
    ));
    assert!(lines[0].ends_with(
        "floor_plate_fx[N],floor_plate_fy[N],floor_plate_fz[N],floor_plate_tx[N*m],floor_plate_ty[N*m],floor_plate_tz[N*m]"
    ));
    let cols: Vec<&str> = lines[2].split(',').collect();
    assert_eq!(cols.len(), 12 + 6);
    assert_eq!(cols[1], "100");
    assert_eq!(cols[3], "5");
    assert_eq!(cols[6].parse::<f64>().unwrap(), 1.5e-7);
    assert_eq!(cols[17].parse::<f64>().unwrap(), 1e-20);
    drop(w);
    // an interrupted partial row is dropped; rows after the resume step too
    let mut t = std::fs::read(&p).unwrap();
    t.extend_from_slice(b"0.004,400,1");
    write_atomic(&p, &t).unwrap();
    let mut w = ThermoWriter::resume(&p, &names, 150).unwrap();
    w.write(&thermo(200)).unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    let steps: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(steps, ["0", "100", "200"]);
    // changed walls are refused
    assert!(ThermoWriter::resume(&p, &["other".to_string()], 150).is_err());
    // a file of an older version (header without units) resumes, with units
    let text = std::fs::read_to_string(&p).unwrap();
    let (head, rows) = text.split_once('\n').unwrap();
    let old = clump_io::thermo_csv::without_units(head);
    assert!(
        old.starts_with("time,step,bodies,") && !old.contains('['),
        "{old}"
    );
    write_atomic(&p, format!("{old}\n{rows}").as_bytes()).unwrap();
    drop(ThermoWriter::resume(&p, &names, 150).unwrap());
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        format!(
            "{head}\n{}",
            rows.lines()
                .take(2)
                .map(|l| format!("{l}\n"))
                .collect::<String>()
        )
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn trajectory_rows() {
    use clump_core::body::BodyInit;
    use clump_core::boundary::Domain;
    use clump_core::contact::ContactTable;
    use clump_core::contact::{Material, PairProperties};
    use clump_core::multi_contact::MultiContact;
    use clump_core::rotation::RotationScheme;
    use clump_core::shape::{self, ClumpTemplate};
    use clump_core::world::{AddedMass, World, WorldConfig};
    use clump_io::trajectory::{TrajectoryWriter, TRAJECTORY_HEADER};
    use glam::DQuat;

    let mats = vec![Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }];
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
            periodic: [false; 3],
        },
        gravity: DVec3::ZERO,
        dt: 1e-4,
        rotation: RotationScheme::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let t = w
        .add_template(
            ClumpTemplate::from_spheres("rod", &shape::rod(3, 1e-3, 1e-3), 2500.0).unwrap(),
            0,
        )
        .unwrap();
    let q = DQuat::from_rotation_z(0.5);
    let id = w
        .add_body(&BodyInit {
            angular_velocity: DVec3::new(0.0, 0.0, 2.0),
            velocity: DVec3::X,
            ..BodyInit::at_rest(t, DVec3::ZERO, q)
        })
        .unwrap();
    let d = dir("traj");
    let mut tw = TrajectoryWriter::create(&d, &[id, 999]).unwrap();
    tw.write(&w).unwrap();
    w.run(10).unwrap();
    tw.write(&w).unwrap();
    let text = std::fs::read_to_string(d.join(format!("traj_{id}.csv"))).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], TRAJECTORY_HEADER);
    assert_eq!(lines.len(), 3);
    let v: Vec<f64> = lines[2].split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(v.len(), 17);
    assert!((v[0] - 1e-3).abs() < 1e-15);
    assert!((v[1] - 1e-3).abs() < 1e-12, "x = {}", v[1]);
    // body-frame ω = q⁻¹ ω
    let wb = DQuat::from_xyzw(v[8], v[9], v[10], v[7]).inverse() * DVec3::new(v[11], v[12], v[13]);
    assert!((wb - DVec3::new(v[14], v[15], v[16])).length() < 1e-12);
    // the absent body has a header only
    let none = std::fs::read_to_string(d.join("traj_999.csv")).unwrap();
    assert_eq!(none.lines().count(), 1);
    // resume keeps rows up to the time
    let _ = TrajectoryWriter::resume(&d, &[id], 0.0).unwrap();
    let text = std::fs::read_to_string(d.join(format!("traj_{id}.csv"))).unwrap();
    assert_eq!(text.lines().count(), 2);
    std::fs::remove_dir_all(&d).unwrap();
}
