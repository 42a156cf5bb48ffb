//! thermo.csv with `[fluid]`: the total fluid force columns, checked
//! against Stokes' drag and Archimedes' buoyancy on two held spheres in a
//! uniform upward flow, and in a sheared flow read from a grid file; and
//! the columns survive a resume.

mod support;

use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use std::path::PathBuf;

const R: f64 = 0.0005; // m
const MU: f64 = 1e-3; // Pa s
const RHO_F: f64 = 1000.0; // kg/m^3
const U: f64 = 0.01; // m/s, upward

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_fluid_thermo_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scenario_file(d: &std::path::Path) -> PathBuf {
    scenario_with_velocity(d, &format!("[0.0, 0.0, {U}]"))
}

/// The scenario with `[fluid] velocity = <velocity>`.
fn scenario_with_velocity(d: &std::path::Path, velocity: &str) -> PathBuf {
    std::fs::write(
        d.join("bodies.csv"),
        "template,x,y,z,driven\nball,0.0,0.0,0.01,1\nball,0.004,0.0,0.01,1\n",
    )
    .unwrap();
    let text = format!(
        r#"
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.01, -0.01, 0.0]
hi = [0.01, 0.01, 0.02]

[[material]]
name = "glass"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "ball"
material = "glass"
spheres = [[0.0, 0.0, 0.0, {R}]]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "flow"
steps = 20

[output]
thermo = {{ every_steps = 10 }}
checkpoint = {{ every_steps = 10 }}

[fluid]
density = {RHO_F}
viscosity = {MU}
drag = "stokes"
velocity = {velocity}
"#
    );
    let p = d.join("scenario.toml");
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn thermo_has_the_total_fluid_force() {
    let d = dir("total");
    let sc = scenario::load(&scenario_file(&d)).unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut run = Runner::new(sc, &out).unwrap();
    run.run(RunOptions::default()).unwrap();
    let text = std::fs::read_to_string(out.join("thermo.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[header.len() - 3..],
        ["fluid_fx[N]", "fluid_fy[N]", "fluid_fz[N]"]
    );
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last.len(), header.len());
    // two spheres held at rest: Stokes drag 3 π μ d U and buoyancy ρ_f V g each
    let v = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let each = 3.0 * std::f64::consts::PI * MU * 2.0 * R * U + RHO_F * v * 9.81;
    let n = header.len();
    assert_eq!(last[n - 3], 0.0);
    assert_eq!(last[n - 2], 0.0);
    assert!(
        (last[n - 1] - 2.0 * each).abs() < 1e-12 * each,
        "{} vs {}",
        last[n - 1],
        2.0 * each
    );

    drop(run);
    // resumed from the checkpoint at step 10: the same file, the same rows
    resume_gives_the_same_thermo(&out, &text);
}

#[test]
fn thermo_fluid_force_in_a_grid_velocity_field() {
    // u = (0, 0, U (1 + x/L)), L = 0.01 m, on a grid over the domain; the
    // spheres held at x = 0 and x = 0.004 m see U and 1.4 U (trilinear
    // interpolation is exact for a linear field): the total is
    // 3 π μ d U (1 + 1.4) + 2 ρ_f V g
    let d = dir("grid");
    let mut csv = String::from("x,y,z,ux,uy,uz\n");
    for z in [0.0, 0.02] {
        for y in [-0.01, 0.01] {
            for x in [-0.01, 0.0, 0.01] {
                let uz = U * (1.0 + x / 0.01);
                csv += &format!("{x},{y},{z},0,0,{uz}\n");
            }
        }
    }
    std::fs::write(d.join("flow.csv"), csv).unwrap();
    let sc = scenario::load(&scenario_with_velocity(&d, "\"flow.csv\""))
        .unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut run = Runner::new(sc, &out).unwrap();
    run.run(RunOptions::default()).unwrap();
    let text = std::fs::read_to_string(out.join("thermo.csv")).unwrap();
    let fz = support::last_value(&out.join("thermo.csv"), "fluid_fz[N]");
    let v = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let want = 3.0 * std::f64::consts::PI * MU * 2.0 * R * U * 2.4 + 2.0 * RHO_F * v * 9.81;
    assert!((fz - want).abs() < 1e-12 * want, "{fz} vs {want}");
    drop(run);
    // the resumed run reads the grid from the scenario again: same rows
    resume_gives_the_same_thermo(&out, &text);
}

/// Resumes the run in `out` from its checkpoint at step 10 to its end and
/// checks that thermo.csv is `text` again.
fn resume_gives_the_same_thermo(out: &std::path::Path, text: &str) {
    let ck = out.join("checkpoint_000000010.ckpt");
    let mut again = Runner::resume(&ck, Some(out)).unwrap();
    again.run(RunOptions::default()).unwrap();
    assert_eq!(
        std::fs::read_to_string(out.join("thermo.csv")).unwrap(),
        text
    );
}

/// The nodes `o + (i, j, k) h` of a 5 × 4 × 3 grid over the domain and a
/// field linear in x, y, z on them, x fastest.
fn vti_test_field() -> ([f64; 3], [f64; 3], [usize; 3], Vec<([f64; 3], [f64; 3])>) {
    let (o, h, n) = ([-0.01, -0.01, 0.0], [0.0055, 0.007, 0.011], [5, 4, 3]);
    let mut nodes = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let p = [
                    o[0] + i as f64 * h[0],
                    o[1] + j as f64 * h[1],
                    o[2] + k as f64 * h[2],
                ];
                let u = [0.3 * p[1], 0.2 * p[2], U * (1.0 + p[0] / 0.01) + 0.1 * p[1]];
                nodes.push((p, u));
            }
        }
    }
    (o, h, n, nodes)
}

/// A `.vti` of the field: `data` the `<DataArray>`'s attributes and text.
fn vti_text(o: [f64; 3], h: [f64; 3], n: [usize; 3], header: &str, data: &str) -> String {
    let ext = format!("0 {} 0 {} 0 {}", n[0] - 1, n[1] - 1, n[2] - 1);
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\"{header}>\n  <ImageData WholeExtent=\"{ext}\" Origin=\"{:e} {:e} {:e}\" Spacing=\"{:e} {:e} {:e}\">\n    <Piece Extent=\"{ext}\">\n      <PointData Vectors=\"U\">\n        <DataArray type=\"Float64\" Name=\"p\" NumberOfComponents=\"1\" format=\"ascii\">0</DataArray>\n        {data}\n      </PointData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n",
        o[0], o[1], o[2], h[0], h[1], h[2]
    )
}

#[test]
fn a_vti_field_gives_the_bits_of_the_same_csv_field() {
    use base64::Engine as _;
    let b64 = base64::engine::general_purpose::STANDARD;
    let d = dir("vti");
    let (o, h, n, nodes) = vti_test_field();
    let mut csv = String::from("x,y,z,ux,uy,uz\n");
    let mut ascii = String::new();
    let mut raw = Vec::new();
    for (p, u) in &nodes {
        csv += &format!(
            "{:e},{:e},{:e},{:e},{:e},{:e}\n",
            p[0], p[1], p[2], u[0], u[1], u[2]
        );
        ascii += &format!(" {:e} {:e} {:e}", u[0], u[1], u[2]);
        raw.extend(u.iter().flat_map(|x| x.to_le_bytes()));
    }
    std::fs::write(d.join("flow.csv"), csv).unwrap();
    let array = |format: &str, text: &str| {
        format!("<DataArray type=\"Float64\" Name=\"U\" NumberOfComponents=\"3\" format=\"{format}\">{text}</DataArray>")
    };
    std::fs::write(
        d.join("flow.vti"),
        vti_text(o, h, n, "", &array("ascii", &ascii)),
    )
    .unwrap();
    // binary: a UInt32 byte count and the data in one base64 stream; a
    // UInt64 count encoded on its own, then the data (as VTK writes it)
    let mut one = (raw.len() as u32).to_le_bytes().to_vec();
    one.extend(&raw);
    let bin32 = array("binary", &b64.encode(&one));
    std::fs::write(d.join("flow32.vti"), vti_text(o, h, n, "", &bin32)).unwrap();
    let two = b64.encode((raw.len() as u64).to_le_bytes()) + &b64.encode(&raw);
    let bin64 = array("binary", &two);
    let h64 = " header_type=\"UInt64\"";
    std::fs::write(d.join("flow64.vti"), vti_text(o, h, n, h64, &bin64)).unwrap();
    let run = |file: &str| {
        let sc = scenario::load(&scenario_with_velocity(&d, &format!("\"{file}\"")))
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let grid = sc.fluid_grid.clone().expect("a grid");
        let out = d.join(format!("out_{file}"));
        let mut r = Runner::new(sc, &out).unwrap();
        r.run(RunOptions::default()).unwrap();
        (
            grid,
            std::fs::read_to_string(out.join("thermo.csv")).unwrap(),
        )
    };
    let (g_csv, t_csv) = run("flow.csv");
    // the held spheres (x = 0, 4 mm; y = 0) see U and 1.4 U along z
    let fz = support::last_value(&d.join("out_flow.csv/thermo.csv"), "fluid_fz[N]");
    let v = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let want = 3.0 * std::f64::consts::PI * MU * 2.0 * R * U * 2.4 + 2.0 * RHO_F * v * 9.81;
    assert!((fz - want).abs() < 1e-12 * want, "{fz} vs {want}");
    for file in ["flow.vti", "flow32.vti", "flow64.vti"] {
        let (g, t) = run(file);
        assert!(g == g_csv, "{file}: the grid differs from the CSV's");
        assert_eq!(t, t_csv, "{file}: thermo.csv differs from the CSV run's");
    }
}

#[test]
fn bad_vti_files_are_refused_at_the_key() {
    let d = dir("vti_bad");
    let (o, h, n, nodes) = vti_test_field();
    let vals: String = nodes
        .iter()
        .map(|(_, u)| format!(" {:e} {:e} {:e}", u[0], u[1], u[2]))
        .collect();
    let arr = |attrs: &str, text: &str| {
        format!("<DataArray type=\"Float64\" Name=\"U\" NumberOfComponents=\"3\" {attrs}>{text}</DataArray>")
    };
    let err = |name: &str, text: String| {
        std::fs::write(d.join(name), text).unwrap();
        match scenario::load(&scenario_with_velocity(&d, &format!("\"{name}\""))) {
            Ok(_) => panic!("{name} was accepted"),
            Err(e) => e.to_string(),
        }
    };
    // the grid stops 1 mm short of the domain's upper z
    let short = err(
        "short.vti",
        vti_text(
            o,
            [h[0], h[1], 0.0095],
            n,
            "",
            &arr("format=\"ascii\"", &vals),
        ),
    );
    assert!(short.contains("velocity grid file 'short.vti': grid does not cover the domain: its upper z is 0.019 m, below the domain's 0.02 m"), "{short}");
    assert!(short.contains("scenario.toml:"), "{short}");
    let few = err(
        "few.vti",
        vti_text(o, h, n, "", &arr("format=\"ascii\"", " 1 2 3")),
    );
    assert!(few.contains("velocity grid file 'few.vti', line 7: the array holds 3 values, the 5 x 4 x 3 nodes need 180"), "{few}");
    let zip = err(
        "zip.vti",
        vti_text(
            o,
            h,
            n,
            " compressor=\"vtkZLibDataCompressor\"",
            &arr("format=\"binary\"", "AAAA"),
        ),
    );
    assert!(
        zip.contains("line 2: compressed data (vtkZLibDataCompressor) is not read"),
        "{zip}"
    );
    let bad = err(
        "nan.vti",
        vti_text(o, h, n, "", &arr("format=\"ascii\"", " 1 x 3")),
    );
    assert!(
        bad.contains("line 7: the array has a value that is not a number"),
        "{bad}"
    );
    let xml = err(
        "cut.vti",
        "<VTKFile type=\"ImageData\">\n<ImageData>\n</Piece>\n</VTKFile>\n".into(),
    );
    assert!(
        xml.contains("velocity grid file 'cut.vti', line 3: not valid XML"),
        "{xml}"
    );
}
