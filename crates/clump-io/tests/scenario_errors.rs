//! The bad-input corpus: every `tests/bad_scenarios/NN_name.toml` must be
//! rejected with a message that contains each line of `NN_name.expected`
//! (including `file:LINE:` of the offending key). `base_valid.toml`, from
//! which the cases are derived (see `generate.py`), must load.

use clump_io::scenario;
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenarios")
}

#[test]
fn base_scenario_is_valid() {
    let sc = scenario::load(&corpus().join("base_valid.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(sc.stages.len(), 2);
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
}

#[test]
fn every_bad_scenario_is_rejected_with_its_message() {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "toml")
                && p.file_name().unwrap().to_string_lossy().as_bytes()[0].is_ascii_digit()
        })
        .collect();
    cases.sort();
    assert!(
        cases.len() >= 30,
        "the corpus has only {} cases",
        cases.len()
    );
    let mut failures = Vec::new();
    for case in &cases {
        let expected = std::fs::read_to_string(case.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{} has no .expected sibling", case.display()));
        match scenario::load(case) {
            Ok(_) => failures.push(format!("{}: accepted, but it is invalid", case.display())),
            Err(e) => {
                let msg = e.to_string();
                for want in expected.lines().map(str::trim).filter(|l| !l.is_empty()) {
                    if !msg.contains(want) {
                        failures.push(format!(
                            "{}: message lacks {want:?}; got:\n{msg}",
                            case.display()
                        ));
                    }
                }
                // every message names the file
                if !msg.contains(&*case.file_name().unwrap().to_string_lossy()) {
                    failures.push(format!(
                        "{}: message does not name the file:\n{msg}",
                        case.display()
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n\n")
    );
}

#[test]
fn unknown_key_message_has_the_documented_layout() {
    let e = scenario::load(&corpus().join("01_unknown_key_pair.toml"))
        .unwrap_err()
        .to_string();
    let lines: Vec<&str> = e.lines().collect();
    assert_eq!(lines[0], "error: unknown key 'restitutoin' in [[pair]]");
    assert!(
        lines[1].trim_start().starts_with("--> ")
            && lines[1].ends_with("01_unknown_key_pair.toml:28:1"),
        "{e}"
    );
    assert_eq!(lines[3], "28 | restitutoin = 0.4");
    assert_eq!(lines[4], "   | ^^^^^^^^^^^ did you mean 'restitution'?");
}

#[test]
fn base_scenario_resolves_to_the_expected_values() {
    use clump_core::contact::time_scale::rayleigh_time;
    let sc = scenario::load(&corpus().join("base_valid.toml")).unwrap();
    // dt = 0.2 t_R of the smallest sphere (tetrahedron spheres, r = 2 mm, rock)
    let tr = rayleigh_time(&sc.materials[0], 0.002);
    assert!(
        (sc.config.dt - 0.2 * tr).abs() < 1e-18,
        "{} vs {}",
        sc.config.dt,
        0.2 * tr
    );
    assert!(sc.time_step.auto);
    // [contact] for rock–rock, [[pair]] for rock–steel (symmetric), unlisted keys from [contact]
    let n = sc.materials.len();
    let rr = sc.pair_table[0];
    let rs = sc.pair_table[1];
    assert_eq!(rs, sc.pair_table[n]);
    assert_eq!((rr.restitution, rr.friction), (0.5, 0.5));
    assert_eq!((rs.restitution, rs.friction), (0.4, 0.3));
    // stages: fill then drain, the gate switched off at the start of drain
    assert_eq!(sc.stages[0].name, "fill");
    assert_eq!(sc.stages[1].first_step, sc.stages[0].steps);
    assert_eq!(sc.stages[1].walls[0].wall, 1);
    assert_eq!(sc.stages[1].walls[0].active, Some(false));
    assert_eq!(sc.inserts[0].stage, 0);
    assert_eq!(sc.expected_bodies(), 100.0);
    assert_eq!(sc.expected_spheres(), 400.0);
}

#[test]
fn large_time_step_is_a_warning_below_the_limit() {
    use clump_core::contact::time_scale::rayleigh_time;
    let base = std::fs::read_to_string(corpus().join("base_valid.toml")).unwrap();
    let sc = scenario::load(&corpus().join("base_valid.toml")).unwrap();
    let tr = rayleigh_time(&sc.materials[0], 0.002);
    let text = base.replace("dt = \"auto\"", &format!("dt = {:e}", 0.4 * tr));
    let dir = tempfile::Builder::new()
        .prefix("clump-scn-warn-")
        .tempdir()
        .unwrap();
    let p = dir.path().join("warn.toml");
    std::fs::write(&p, text).unwrap();
    let sc = scenario::load(&p).unwrap_or_else(|e| panic!("{e}"));
    // 0.4 t_R is also 0.53 × the tetrahedra's damped-contact limit dt_c
    // (clump check: dt = 0.264 dt_c at 0.2 t_R), above the 0.4 dt_c warned about
    assert_eq!(sc.warnings.len(), 2, "{:?}", sc.warnings);
    let w = sc.warnings[0].to_string();
    assert!(
        w.starts_with("warning: dt = ") && w.contains("warn.toml:3:") && w.contains("Rayleigh"),
        "{w}"
    );
    let w = sc.warnings[1].to_string();
    assert!(
        w.starts_with("warning: dt = ")
            && w.contains("warn.toml:3:")
            && w.contains("damped-contact stability limit"),
        "{w}"
    );
}

/// `tensile` is read from `[contact]` and `[[pair]]` (default false: the
/// normal force is clamped); a pair inherits it from `[contact]` unless it
/// sets its own.
#[test]
fn tensile_key_is_parsed() {
    let base = std::fs::read_to_string(corpus().join("base_valid.toml")).unwrap();
    let load = |text: String| {
        scenario::parse(
            &corpus().join("tensile.toml"),
            text,
            scenario::Files::disk(&corpus()),
        )
        .unwrap_or_else(|e| panic!("{e}"))
    };
    // material order: rock (0), steel (1); table row-major n × n
    let sc = load(base.clone());
    assert!(sc.pair_table.iter().all(|p| !p.tensile), "default: clamped");
    let text = base
        .replacen("friction = 0.5\n", "friction = 0.5\ntensile = true\n", 1)
        .replacen("friction = 0.3\n", "friction = 0.3\ntensile = false\n", 1);
    let sc = load(text);
    let n = sc.material_names.len();
    let at = |a: usize, b: usize| sc.pair_table[a * n + b];
    assert!(
        at(0, 0).tensile && at(1, 1).tensile,
        "[contact] tensile = true"
    );
    assert!(
        !at(0, 1).tensile && !at(1, 0).tensile,
        "[[pair]] tensile = false"
    );
    assert_eq!(at(0, 1).restitution, 0.4);
}

#[test]
fn fluid_velocity_grid_file_is_read() {
    // the grid file holds u = (0, 0, 0.01) m/s at the corners of the
    // domain box; its trilinear interpolation is that value everywhere
    let base = std::fs::read_to_string(corpus().join("base_valid.toml")).unwrap();
    let text =
        base + "\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = \"data_fluid_grid.csv\"\n";
    let sc = scenario::parse(
        &corpus().join("fluid_grid.toml"),
        text,
        scenario::Files::disk(&corpus()),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let g = sc.fluid_grid.as_ref().expect("a velocity grid");
    let (lo, hi) = g.bounds();
    assert_eq!(
        (lo.to_array(), hi.to_array()),
        ([-0.1, -0.1, -0.01], [0.1, 0.1, 0.3])
    );
    let u = g.sample(glam::DVec3::new(0.03, -0.02, 0.11));
    assert_eq!(u.to_array(), [0.0, 0.0, 0.01]);
    assert_eq!(sc.fluid.unwrap().velocity, glam::DVec3::ZERO);
    sc.build_world().unwrap_or_else(|e| panic!("{e}"));
}
