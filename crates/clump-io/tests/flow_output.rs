//! `[[output.flow]]` in a small version of the hopper example: the mass
//! flow.csv counts through the outlet plane equals the bin's loss of mass
//! at every row, and at least the bodies the engine removed below the
//! domain (thermo.csv `lost_bodies`) crossed the outlet.

mod post;

const PROBES: &str = r#"
[[output.flow]]
name = "outlet"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, -1.0]
every = 0.002

[[output.flow]]
name = "bin"
type = "region"
lo = [-0.07, -0.04, 0.0]
hi = [0.07, 0.04, 0.2]
bins = [0.0, 0.0052, 0.0058, 0.01]
"#;

#[test]
fn outlet_mass_equals_the_bins_loss() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("../../examples/hopper.toml")).unwrap();
    let text = text
        .replace("count = 1200", "count = 200")
        .replace("duration = 0.3 ", "duration = 0.12")
        .replace("duration = 0.6", "duration = 0.25")
        .replace("vtk = { every = 0.01 }", "vtk = { every = 1.0 }")
        .replace("checkpoint = { every = 0.3 }", "");
    let text = match text.find("\n[[output.flow]]") {
        Some(i) => text[..i].to_string(),
        None => text,
    } + PROBES;
    let d = post::dir("flow");
    let _r = post::run(&text, &d);
    let csv = std::fs::read_to_string(d.join("run/flow.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| {
        header
            .iter()
            .position(|h| *h == n)
            .unwrap_or_else(|| panic!("{n}"))
    };
    let (mp, mn, net, bin, cp, cn, count) = (
        col("outlet_mass_pos[kg]"),
        col("outlet_mass_neg[kg]"),
        col("outlet_net_mass_total[kg]"),
        col("bin_mass[kg]"),
        col("outlet_count_pos"),
        col("outlet_count_neg"),
        col("bin_count"),
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let m0 = rows[0][bin];
    assert!(m0 > 0.0);
    let (mut through, mut crossed) = (0.0, 0.0);
    for r in &rows {
        through += r[mp] - r[mn];
        crossed += r[cp] - r[cn];
        assert!((through - r[net]).abs() <= 1e-12 * m0);
        assert!(
            (m0 - r[bin] - through).abs() <= 1e-12 * m0,
            "t = {}: bin lost {} kg, outlet counted {through} kg",
            r[0],
            m0 - r[bin]
        );
        // the size distribution counts every body of the bin
        let hist: f64 = (count + 1..count + 4).map(|k| r[k]).sum();
        assert_eq!(hist, r[count]);
    }
    let lost = post::last_column(&d.join("run/thermo.csv"), "lost_bodies");
    eprintln!(
        "{} rows, {through:e} kg through the outlet of {m0:e} kg, {crossed} bodies, {lost} lost",
        rows.len()
    );
    assert!(
        through > 0.1 * m0,
        "the hopper drained: {through} of {m0} kg"
    );
    assert!(
        crossed >= lost && lost > 0.0,
        "{crossed} crossed, {lost} lost"
    );
    let _ = std::fs::remove_dir_all(&d);
}
