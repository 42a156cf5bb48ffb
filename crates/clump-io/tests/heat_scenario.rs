//! Heat through the scenario file: the keys reach the engine (a chain of
//! spheres between a hot and a cold wall reaches the series-conductance
//! solution), the outputs carry the temperatures (thermo.csv, bodies
//! frames, trajectories), a run stopped and resumed from its checkpoint
//! ends with the same temperatures bit for bit, and bad input is refused
//! at its key with file and line.

use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use std::path::{Path, PathBuf};

const R: f64 = 1e-3;
const DS: f64 = 2e-5;
const DW: f64 = 1e-5;
const K: f64 = 1e4;
const N: usize = 5;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump-heat-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    for sub in ["a", "b", "c"] {
        std::fs::create_dir_all(d.join(sub)).unwrap();
    }
    d
}

/// x of sphere k of the chain, m.
fn x(k: usize) -> f64 {
    (k as f64 - (N as f64 - 1.0) / 2.0) * (2.0 * R - DS)
}

/// The chain scenario, with `extra` appended to `[heat]`-free text (and
/// `patch` applied as (from, to) replacements).
fn chain(d: &Path, steps: u64, patch: &[(&str, &str)]) -> PathBuf {
    let mut csv = String::from("template,x,y,z\n");
    for k in 0..N {
        csv.push_str(&format!("sphere,{:?},0,0\n", x(k)));
    }
    std::fs::write(d.join("chain.csv"), csv).unwrap();
    let lo = x(0) - R + DW;
    let hi = x(N - 1) + R - DW;
    let mut text = format!(
        r#"[simulation]
dt = 5e-5
gravity = [0.0, 0.0, 0.0]
steps = {steps}

[domain]
lo = [-0.01, -0.01, -0.01]
hi = [0.01, 0.01, 0.01]

[[material]]
name = "grain"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500
thermal_conductivity = {K:?}
specific_heat = 800.0

[[material]]
name = "plate"
youngs_modulus = inf
poisson_ratio = 0.3
density = 0
thermal_conductivity = {K:?}

[[template]]
name = "sphere"
material = "grain"
shape = "sphere"
radius = {R:?}
temperature = 300.0

[[wall]]
name = "hot"
material = "plate"
type = "plane"
point = [{lo:?}, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
temperature = 400.0

[[wall]]
name = "cold"
material = "plate"
type = "plane"
point = [{hi:?}, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
temperature = 300.0

[[insert]]
kind = "file"
file = "chain.csv"
fixed = true

[heat]
conductance = "batchelor_obrien"

[output]
thermo = {{ every_steps = 1000 }}
vtk = {{ every_steps = {steps} }}
trajectory = {{ bodies = [1, {N}], every_steps = 1000 }}
checkpoint = {{ every_steps = 1000000 }}
"#
    );
    for (from, to) in patch {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let p = d.join("chain.toml");
    std::fs::write(&p, text).unwrap();
    p
}

/// The column of `name` in a CSV header line.
fn column(header: &str, name: &str) -> usize {
    header
        .split(',')
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {header}"))
}

fn last_row(csv: &str) -> (String, Vec<f64>) {
    let mut lines = csv.lines();
    let header = lines.next().unwrap().to_string();
    let row = lines
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    (header, row)
}

#[test]
fn a_chain_scenario_reaches_the_series_solution_and_writes_its_temperatures() {
    let d = dir("chain");
    let path = chain(&d, 6000, &[]);
    let sc = scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let h = sc.heat.as_ref().unwrap();
    // T-57's bound: m c_p over 12 wall-form conductances at the guard's overlap
    let mass = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let ratio = sc.stability.max_overlap_ratio;
    let bound = mass * 800.0 / (12.0 * 2.0 * K * (R * ratio * R).sqrt());
    assert!(
        (h.stability_limit - bound).abs() < 1e-12 * bound,
        "{} {bound}",
        h.stability_limit
    );
    assert!(sc.config.dt < h.stability_limit, "{}", h.stability_limit);
    let out = d.join("out");
    let mut r = Runner::new(sc, &out).unwrap();
    r.run(RunOptions::default()).unwrap();
    // series conductances, from outside the code (T-53)
    let hs = 2.0 * K * (R / 2.0 * DS).sqrt();
    let hw = 2.0 * K * (R * DW).sqrt();
    let q = 100.0 / (2.0 / hw + (N - 1) as f64 / hs);
    let expect = |k: usize| 400.0 - q * (1.0 / hw + k as f64 / hs);
    // thermo.csv: the wall flows and the temperature range
    let (header, row) = last_row(&std::fs::read_to_string(out.join("thermo.csv")).unwrap());
    let at = |c: &str| row[column(&header, c)];
    assert!(
        (at("hot_heat_flow[W]") - q).abs() < 1e-6 * q,
        "{} {q}",
        at("hot_heat_flow[W]")
    );
    assert!((at("cold_heat_flow[W]") + q).abs() < 1e-6 * q);
    assert!((at("max_temperature[K]") - expect(0)).abs() < 1e-6 * 400.0);
    assert!((at("min_temperature[K]") - expect(N - 1)).abs() < 1e-6 * 400.0);
    assert!(at("heat_stability") > 0.0 && at("heat_stability") <= 1.0);
    // trajectories: the temperature column of the first and last sphere
    for (id, k) in [(1, 0), (N, N - 1)] {
        let (h, row) =
            last_row(&std::fs::read_to_string(out.join(format!("traj_{id}.csv"))).unwrap());
        let t = row[column(&h, "temperature")];
        assert!(
            (t - expect(k)).abs() < 1e-6 * 400.0,
            "body {id}: {t} K, series {}",
            expect(k)
        );
    }
    // the bodies frame has the temperature array
    let frame = String::from_utf8_lossy(&std::fs::read(out.join("bodies_006000.vtp")).unwrap())
        .into_owned();
    assert!(
        frame.contains("Name=\"temperature\""),
        "no temperature array"
    );
    println!(
        "chain of {N} through the scenario: Q = {q:.6e} W, thermo {:.6e} W",
        at("hot_heat_flow[W]")
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_resumed_run_ends_with_the_same_temperatures() {
    let d = dir("resume");
    let path = chain(&d, 3000, &[]);
    let whole = d.join("whole");
    let mut r = Runner::new(scenario::load(&path).unwrap(), &whole).unwrap();
    r.run(RunOptions::default()).unwrap();
    let a = r.world().bodies().temperature.clone();
    let wa = r.world().heat.as_ref().unwrap().wall_heat.clone();
    drop(r);
    let split = d.join("split");
    let mut r = Runner::new(scenario::load(&path).unwrap(), &split).unwrap();
    let s = r
        .run(RunOptions {
            max_steps: Some(1234),
            ..Default::default()
        })
        .unwrap();
    let ck = s.checkpoint.unwrap();
    drop(r);
    let mut r = Runner::resume(&ck, None).unwrap();
    r.run(RunOptions::default()).unwrap();
    let b = r.world().bodies().temperature.clone();
    let wb = r.world().heat.as_ref().unwrap().wall_heat.clone();
    assert_eq!(
        a.iter().map(|t| t.to_bits()).collect::<Vec<_>>(),
        b.iter().map(|t| t.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(wa, wb);
    let ta = std::fs::read(whole.join("thermo.csv")).unwrap();
    let tb = std::fs::read(split.join("thermo.csv")).unwrap();
    assert!(ta == tb, "thermo.csv differs after the resume");
    let _ = std::fs::remove_dir_all(&d);
}

/// `patch` makes the chain scenario invalid: the message names the file,
/// the line of the key (`after` lines below the first line starting with
/// `key_line`) and contains `want`.
fn refused(name: &str, patch: &[(&str, &str)], (key_line, after): (&str, usize), want: &str) {
    let d = dir(name);
    let path = chain(&d, 100, patch);
    let text = std::fs::read_to_string(&path).unwrap();
    let line = 1
        + after
        + text
            .lines()
            .position(|l| l.starts_with(key_line))
            .unwrap_or_else(|| panic!("no line {key_line}"));
    let e = scenario::load(&path)
        .err()
        .unwrap_or_else(|| panic!("{name}: accepted"));
    let msg = e.to_string();
    assert!(
        msg.contains(&format!("chain.toml:{line}:")),
        "{name}: not at line {line}:\n{msg}"
    );
    assert!(msg.contains(want), "{name}: lacks {want:?}:\n{msg}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_heat_input_is_refused_at_its_key() {
    refused(
        "negative_k",
        &[(
            "thermal_conductivity = 10000.0\nspecific_heat",
            "thermal_conductivity = -1.0\nspecific_heat",
        )],
        ("thermal_conductivity = -1.0", 0),
        "'thermal_conductivity' must be >= 0 W/(m K)",
    );
    refused(
        "zero_kelvin",
        &[(
            "temperature = 300.0\n\n[[wall]]",
            "temperature = 0.0\n\n[[wall]]",
        )],
        ("temperature = 0.0", 0),
        "temperature must be > 0 K",
    );
    refused(
        "negative_wall_t",
        &[("temperature = 400.0", "temperature = -5.0")],
        ("temperature = -5.0", 0),
        "temperature must be > 0 K",
    );
    refused(
        "adiabatic_rigid_wall_with_heat_keys",
        &[(
            "normal = [-1.0, 0.0, 0.0]\ntemperature = 300.0\n",
            "normal = [-1.0, 0.0, 0.0]\n",
        )],
        ("name = \"cold\"", 1),
        "has heat keys, but the wall has no temperature",
    );
    refused(
        "heat_keys_without_heat",
        &[("[heat]\nconductance = \"batchelor_obrien\"\n", "")],
        ("thermal_conductivity = 10000.0", 0),
        "a heat key without [heat]",
    );
    refused(
        "heat_key_removed",
        &[(
            "conductance = \"batchelor_obrien\"",
            "convection = \"ranz_marshall\"",
        )],
        ("convection", 0),
        "convection",
    );
    refused(
        "no_specific_heat",
        &[(
            "thermal_conductivity = 10000.0\nspecific_heat = 800.0\n",
            "",
        )],
        ("material = \"grain\"", 0),
        "needs thermal_conductivity and specific_heat",
    );
    refused(
        "dt_above_the_thermal_limit",
        &[("specific_heat = 800.0", "specific_heat = 1e-3")],
        ("dt = 5e-5", 0),
        "above the thermal stability limit",
    );
}

/// Initial temperatures: the body file's `temperature` column over the
/// insert's `temperature` over the template's (conduction off, k = 0, so
/// they stay).
#[test]
fn initial_temperatures_come_from_the_file_then_the_insert_then_the_template() {
    let still = [
        (
            "thermal_conductivity = 10000.0\nspecific_heat",
            "thermal_conductivity = 0.0\nspecific_heat",
        ),
        ("fixed = true\n", "fixed = true\ntemperature = 500.0\n"),
    ];
    let temps = |d: &Path, column: bool| {
        let path = chain(d, 10, &still);
        if column {
            let mut csv = String::from("template,x,y,z,temperature\n");
            for k in 0..N {
                csv.push_str(&format!("sphere,{:?},0,0,{}\n", x(k), 310 + 10 * k));
            }
            std::fs::write(d.join("chain.csv"), csv).unwrap();
        }
        let mut r = Runner::new(scenario::load(&path).unwrap(), &d.join("out")).unwrap();
        r.run(RunOptions::default()).unwrap();
        let w = r.world();
        (1..=N as u64)
            .map(|id| w.bodies().temperature[w.body_index(id).unwrap()])
            .collect::<Vec<f64>>()
    };
    let d = dir("initial");
    assert_eq!(
        temps(&d.join("a"), true),
        [310.0, 320.0, 330.0, 340.0, 350.0]
    );
    assert_eq!(temps(&d.join("b"), false), [500.0; N]);
    // a temperature of 0 K in the file is refused at the insert's file
    let path = chain(&d.join("c"), 10, &[]);
    std::fs::write(
        d.join("c/chain.csv"),
        "template,x,y,z,temperature\nsphere,0,0,0,0\n",
    )
    .unwrap();
    let msg = scenario::load(&path).err().unwrap().to_string();
    assert!(
        msg.contains("chain.csv:2: temperature must be > 0 K"),
        "{msg}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// `[fluid]` with a temperature, for [`chain`]'s patches: water at 350 K
/// flowing at 0.1 m/s across the chain.
const FLUID: &str = "[heat]\nconductance = \"batchelor_obrien\"\n\n[fluid]\ndensity = 1000.0\nviscosity = 1e-3\nvelocity = [0.0, 0.0, 0.1]\ntemperature = 350.0\nthermal_conductivity = 0.6\nspecific_heat = 4180.0\n";

/// Convection through the scenario file: the chain's spheres, held in
/// place and not conducting (k = 0), each follow the lumped closed form
/// `T_f + (T₀ − T_f) exp(−h A t / (m c))` with h from Ranz & Marshall
/// (1952), written here: Nu = 2 + 0.6 Re^½ Pr^⅓, Re = ρ_f u d / μ,
/// Pr = c_f μ / k_f, h = Nu k_f / d, A = π d².
#[test]
fn convection_from_the_fluid_follows_the_lumped_closed_form() {
    let d = dir("convection");
    let steps = 2000;
    let path = chain(
        &d,
        steps,
        &[
            (
                "thermal_conductivity = 10000.0\nspecific_heat",
                "thermal_conductivity = 0.0\nspecific_heat",
            ),
            ("[heat]\nconductance = \"batchelor_obrien\"\n", FLUID),
        ],
    );
    let sc = scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut r = Runner::new(sc, &out).unwrap();
    r.run(RunOptions::default()).unwrap();
    let (dp, u) = (2.0 * R, 0.1);
    let re = 1000.0 * u * dp / 1e-3;
    let pr: f64 = 4180.0 * 1e-3 / 0.6;
    let h = (2.0 + 0.6 * re.sqrt() * pr.powf(1.0 / 3.0)) * 0.6 / dp;
    let (area, mass) = (
        std::f64::consts::PI * dp * dp,
        2500.0 * std::f64::consts::PI * dp.powi(3) / 6.0,
    );
    let t = steps as f64 * 5e-5;
    let expect = 350.0 - 50.0 * (-h * area * t / (mass * 800.0)).exp();
    let (header, row) = last_row(&std::fs::read_to_string(out.join("thermo.csv")).unwrap());
    for c in [
        "mean_temperature[K]",
        "min_temperature[K]",
        "max_temperature[K]",
    ] {
        let got = row[column(&header, c)];
        assert!(
            ((got - 350.0) / (expect - 350.0) - 1.0).abs() < 1e-9,
            "{c}: {got} K, closed form {expect} K"
        );
    }
    println!(
        "convection through the scenario: h = {h:.4} W/(m² K), T = {expect:.9} K at t = {t} s"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_convection_input_is_refused_at_its_key() {
    let with = |from: &'static str, to: &'static str| {
        let fluid: &'static str = Box::leak(FLUID.replacen(from, to, 1).into_boxed_str());
        [("[heat]\nconductance = \"batchelor_obrien\"\n", fluid)]
    };
    refused(
        "fluid_at_0_k",
        &with("temperature = 350.0", "temperature = 0.0"),
        ("temperature = 0.0", 0),
        "temperature must be > 0 K",
    );
    refused(
        "fluid_without_conductivity",
        &with("thermal_conductivity = 0.6\n", ""),
        ("[fluid]", 0),
        "missing key 'thermal_conductivity'",
    );
    refused(
        "fluid_negative_specific_heat",
        &with("specific_heat = 4180.0", "specific_heat = -1.0"),
        ("specific_heat = -1.0", 0),
        "'specific_heat' must be",
    );
    refused(
        "fluid_conductivity_without_temperature",
        &with("temperature = 350.0\n", ""),
        ("thermal_conductivity = 0.6", 0),
        "without the fluid's temperature",
    );
}
