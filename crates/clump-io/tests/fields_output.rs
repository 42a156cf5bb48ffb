//! `[output.fields]` during a run, and the same fields from the saved
//! frames afterwards (`clump post`'s path): the saved frames hold what the
//! coarse-graining needs, so both agree bit for bit; the `.vti` and the
//! 1D CSV read back (the `.vti` by the `vtk` package, skipped with a note
//! when it is missing) equal the engine's fields.

mod post;

use clump_io::post::fields::coarse_grain;
use clump_io::post::frame::Frame;
use clump_io::post::read::{contact_frames, read_frame};
use clump_io::post::write::csv_1d;

#[test]
fn run_time_fields_equal_post_processed_saved_frames_and_read_back() {
    let d = post::dir("fields");
    let out = r#"thermo = { every = 0.05 }
contacts = { every = 0.1 }
fields = { every = 0.1, axes = ["z"], cells = [60], lo = [-0.004], hi = [0.026], width = 0.001, average = true }"#;
    let r = post::run(&post::bed_text(120, 7, out), &d);
    let run = d.join("run");
    let spec = r.scenario().output.fields.clone().unwrap().1;
    let live = Frame::capture(r.world());
    let grid = spec.grid(&live.domain);
    let engine = coarse_grain(&live, &grid);
    let step = live.step;
    // the saved frames give the same frame and the same fields
    let frames = contact_frames(&run).unwrap();
    assert!(frames.len() >= 3, "{frames:?}");
    let &(s, t) = frames.last().unwrap();
    assert_eq!(s, step);
    let saved = read_frame(&run, s, t).unwrap();
    assert_eq!(saved.bodies.len(), live.bodies.len());
    let mut a = saved.bodies.clone();
    let mut b = live.bodies.clone();
    a.sort_by_key(|x| x.id);
    b.sort_by_key(|x| x.id);
    assert_eq!(a, b);
    assert_eq!(saved.contacts, live.contacts);
    let post = coarse_grain(&saved, &grid);
    assert_eq!(csv_1d(&grid, &post), csv_1d(&grid, &engine));
    let csv = std::fs::read_to_string(run.join(format!("fields_{step:06}.csv"))).unwrap();
    assert_eq!(csv, csv_1d(&grid, &engine));
    assert!(run.join("fields_mean.csv").exists());
    // one solid density (2500 kg/m³, mass = ρ_p × union volume): the void
    // fraction column is 1 − ρ/ρ_p of the density column
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let col = |name: &str| rows[0].iter().position(|c| c.starts_with(name)).unwrap();
    let (kr, ke) = (col("density["), col("void_fraction"));
    for r in &rows[1..] {
        let (rho, eps): (f64, f64) = (r[kr].parse().unwrap(), r[ke].parse().unwrap());
        assert!((eps - (1.0 - rho / 2500.0)).abs() < 1e-12, "{r:?}");
    }
    assert!(rows[1..]
        .iter()
        .any(|r| r[ke].parse::<f64>().unwrap() < 0.9));
    // the .vti, read by vtk
    let vti = run.join(format!("fields_{step:06}.vti"));
    let Some(j) = post::read_vtk(&[vti.clone()]) else {
        return;
    };
    let v = &j[vti.to_str().unwrap()];
    assert_eq!(v["dimensions"], serde_json::json!([1, 1, 60]));
    let rho: Vec<f64> = v["point_data"]["density"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(rho, engine.density);
    let s: Vec<Vec<f64>> = v["point_data"]["stress"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            x.as_array()
                .unwrap()
                .iter()
                .map(|y| y.as_f64().unwrap())
                .collect()
        })
        .collect();
    let es = engine.stress();
    for (k, row) in s.iter().enumerate() {
        assert_eq!(row[8], es[k].z_axis.z);
        assert_eq!(row[1], es[k].y_axis.x);
    }
    let z0 = v["origin"][2].as_f64().unwrap();
    assert!((z0 - grid.centre(0, 0)).abs() < 1e-15);
    let _ = std::fs::remove_dir_all(&d);
}
