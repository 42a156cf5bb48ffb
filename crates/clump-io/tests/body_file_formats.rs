//! `[[insert]] kind = "file"` with `format = "xyzq"` and
//! `orientation_frame = "input"`: the shared tetra-bed initial-condition
//! layout. The sphere world positions must be `x + q · (c_input − com)`,
//! computed here independently from the template's input coordinates.

use clump_io::scenario::{self, Files, InsertSpec};
use glam::{DQuat, DVec3};
use std::collections::BTreeMap;
use std::path::Path;

/// An asymmetric trimer (input frame, m), so that the principal frame differs
/// from the input frame and a wrong composition of frames shows.
const SPHERES: [([f64; 3], f64); 3] = [
    ([0.010, 0.002, -0.001], 0.004),
    ([0.014, 0.002, -0.001], 0.003),
    ([0.010, 0.007, 0.001], 0.0025),
];

fn scenario(insert_extra: &str, body_file: &str) -> Result<scenario::Scenario, String> {
    let text = format!(
        r#"
[simulation]
dt = 1e-5
[domain]
lo = [-1.0, -1.0, -1.0]
hi = [1.0, 1.0, 1.0]
[[material]]
name = "m"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2000
[[template]]
name = "trimer"
material = "m"
spheres = [{}]
[[insert]]
kind = "file"
file = "bodies.txt"
{insert_extra}
[[stage]]
steps = 1
"#,
        SPHERES
            .iter()
            .map(|(c, r)| format!("[{}, {}, {}, {r}]", c[0], c[1], c[2]))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut files = BTreeMap::new();
    files.insert("bodies.txt".to_string(), body_file.as_bytes().to_vec());
    scenario::parse(Path::new("t.toml"), text, Files::embedded(files)).map_err(|e| e.to_string())
}

#[test]
fn xyzq_in_input_frame_places_spheres_as_the_file_says() {
    let q1 = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 1.1);
    let q2 = DQuat::from_axis_angle(DVec3::new(-0.3, 0.1, 1.0).normalize(), -2.4);
    let x1 = DVec3::new(0.1, -0.2, 0.3);
    let x2 = DVec3::new(-0.4, 0.25, 0.0);
    let file = format!(
        "# id x y z qw qx qy qz\n1 {} {} {} {} {} {} {}\n\n2 {} {} {} {} {} {} {}\n",
        x1.x, x1.y, x1.z, q1.w, q1.x, q1.y, q1.z, x2.x, x2.y, x2.z, q2.w, q2.x, q2.y, q2.z
    );
    let sc = scenario(
        "format = \"xyzq\"\ntemplate = \"trimer\"\norientation_frame = \"input\"",
        &file,
    )
    .unwrap();
    let mut w = sc.build_world().unwrap();
    let InsertSpec::File { bodies } = &sc.inserts[0].kind else {
        panic!("expected a file insertion")
    };
    assert_eq!(bodies.len(), 2);
    for b in bodies {
        w.add_body(b).unwrap();
    }
    w.prepare().unwrap();
    // The absolute check needs the union's centre of mass in the input frame
    // (validated on its own in clump-core's mass-property tests); the
    // frame-free check below does not.
    let com = sc.templates[0].template.input_center_of_mass;
    let sp = w.spheres();
    for (x, q) in [(x1, q1), (x2, q2)] {
        for (c, r) in SPHERES {
            let expect = x + q * (DVec3::from_array(c) - com);
            let found = (0..sp.len()).any(|k| {
                (sp.position(k) - expect).length() < 1e-12 && (sp.radius[k] - r).abs() < 1e-15
            });
            assert!(found, "no sphere of radius {r} at {expect}");
        }
        // frame-free: the vector between the first two spheres is q (c1 − c0)
        let d_expect = q * (DVec3::from_array(SPHERES[1].0) - DVec3::from_array(SPHERES[0].0));
        let near = |p: DVec3| {
            (0..sp.len())
                .find(|&k| (sp.position(k) - p).length() < 1e-9)
                .unwrap()
        };
        let k0 = near(x + q * (DVec3::from_array(SPHERES[0].0) - com));
        let k1 = near(x + q * (DVec3::from_array(SPHERES[1].0) - com));
        assert!((sp.position(k1) - sp.position(k0) - d_expect).length() < 1e-12);
    }
}

#[test]
fn csv_with_default_template_and_body_frame() {
    let sc = scenario(
        "template = \"trimer\"",
        "x,y,z,qw,qx,qy,qz\n0.1,0.2,0.3,1,0,0,0\n",
    )
    .unwrap();
    let InsertSpec::File { bodies } = &sc.inserts[0].kind else {
        panic!("expected a file insertion")
    };
    assert_eq!(bodies[0].orientation, DQuat::IDENTITY);
    assert_eq!(bodies[0].position, DVec3::new(0.1, 0.2, 0.3));
}

#[test]
fn bad_body_files_are_named_errors() {
    let e = scenario("format = \"xyzq\"", "1 0 0 0 1 0 0 0\n").unwrap_err();
    assert!(e.contains("name the template"), "{e}");
    let e = scenario(
        "format = \"xyzq\"\ntemplate = \"trimer\"",
        "1 0 0 0 1 0 0\n",
    )
    .unwrap_err();
    assert!(
        e.contains("bodies.txt:1") && e.contains("expected 8 fields"),
        "{e}"
    );
    let e = scenario(
        "format = \"xyzq\"\ntemplate = \"trimer\"",
        "# c\n1 0 0 x 1 0 0 0\n",
    )
    .unwrap_err();
    assert!(
        e.contains("bodies.txt:2") && e.contains("column 'z'"),
        "{e}"
    );
    let e = scenario(
        "format = \"xyzq\"\ntemplate = \"trimer\"",
        "1 0 0 0 0 0 0 0\n",
    )
    .unwrap_err();
    assert!(e.contains("quaternion") && e.contains("zero"), "{e}");
    let e = scenario("format = \"tsv\"\ntemplate = \"trimer\"", "").unwrap_err();
    assert!(e.contains("format"), "{e}");
    let e = scenario("template = \"trimmer\"", "x,y,z\n0,0,0\n").unwrap_err();
    assert!(e.contains("trimmer") && e.contains("trimer"), "{e}");
}

fn file_bodies(sc: &scenario::Scenario) -> &[clump_core::body::BodyInit] {
    let InsertSpec::File { bodies } = &sc.inserts[0].kind else {
        panic!("expected a file insertion")
    };
    bodies
}

/// A byte-order mark (as spreadsheet programs write it) before the header
/// is not part of the first column name.
#[test]
fn csv_with_a_byte_order_mark_is_accepted() {
    let sc = scenario("", "\u{feff}template,x,y,z\ntrimer,0.1,0.2,0.3\n").unwrap();
    assert_eq!(file_bodies(&sc)[0].position, DVec3::new(0.1, 0.2, 0.3));
}

/// Quaternions are normalised without overflow or underflow: (1e200,
/// 1e200, 0, 0) and (1e-200, 0, 0, 1e-200) are the rotations by 90° about
/// x and z; the zero quaternion is refused, naming the row.
#[test]
fn quaternions_are_normalised_safely() {
    let sc = scenario(
        "template = \"trimer\"",
        "x,y,z,qw,qx,qy,qz\n0,0,0,1e200,1e200,0,0\n0.5,0,0,1e-200,0,0,1e-200\n",
    )
    .unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let want = [
        DQuat::from_xyzw(h, 0.0, 0.0, h),
        DQuat::from_xyzw(0.0, 0.0, h, h),
    ];
    for (b, w) in file_bodies(&sc).iter().zip(want) {
        assert!((b.orientation - w).length() < 1e-15, "{:?}", b.orientation);
    }
    let e = scenario(
        "template = \"trimer\"",
        "x,y,z,qw,qx,qy,qz\n0,0,0,1,0,0,0\n0.5,0,0,0,0,0,0\n",
    )
    .unwrap_err();
    assert!(
        e.contains("bodies.txt:3: the quaternion (qw, qx, qy, qz) is zero"),
        "{e}"
    );
}

/// Invalid UTF-8 is reported with its line and column; a 50 kB token is
/// not echoed whole.
#[test]
fn invalid_bytes_and_huge_tokens_are_located_and_shortened() {
    let mut file = b"template,x,y,z\ntrimer,0.1,0".to_vec();
    file.push(0xff);
    file.extend_from_slice(b",0.3\n");
    let mut files = BTreeMap::new();
    files.insert("bodies.txt".to_string(), file);
    let sc = "[simulation]\ndt = 1e-5\n[domain]\nlo = [-1.0, -1.0, -1.0]\nhi = [1.0, 1.0, 1.0]\n[[material]]\nname = \"m\"\nyoungs_modulus = 1e7\npoisson_ratio = 0.3\ndensity = 2000\n[[template]]\nname = \"trimer\"\nmaterial = \"m\"\nspheres = [[0.0, 0.0, 0.0, 0.01]]\n[[insert]]\nkind = \"file\"\nfile = \"bodies.txt\"\n[[stage]]\nsteps = 1\n";
    let e = scenario::parse(Path::new("t.toml"), sc.to_string(), Files::embedded(files))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bodies.txt:2: not UTF-8 text: invalid byte at column 13"),
        "{e}"
    );
    let huge = "9".repeat(50_000) + "x";
    let e = scenario("template = \"trimer\"", &format!("x,y,z\n{huge},0,0\n")).unwrap_err();
    assert!(e.len() < 2_000, "message of {} bytes", e.len());
    assert!(e.contains("(50001 characters)"), "{e}");
}
