//! A run with contact frames, fields and flow probes stopped at a step
//! limit and resumed from its checkpoint writes the same files, byte for
//! byte, as the run without the stop.

mod post;

use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;

const OUT: &str = r#"thermo = { every_steps = 500 }
contacts = { every_steps = 1500 }
fields = { every_steps = 1500, axes = ["x", "z"], cells = [4, 20], width = 0.0015 }

[[output.flow]]
name = "mid"
type = "plane"
point = [0.0, 0.0, 0.01]
normal = [0.0, 0.0, -1.0]
every_steps = 300

[[output.flow]]
name = "low"
type = "region"
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.01]
bins = [0.0, 0.003, 0.004]
"#;

#[test]
fn stopped_and_resumed_run_writes_the_same_post_files() {
    let d = post::dir("resume");
    let text = post::bed_text_steps(60, 3, 9000, OUT);
    let path = d.join("bed.toml");
    std::fs::write(&path, &text).unwrap();
    let whole = d.join("whole");
    let mut r = Runner::new(scenario::load(&path).unwrap(), &whole).unwrap();
    r.run(RunOptions::default()).unwrap();
    drop(r);
    let split = d.join("split");
    let mut r = Runner::new(scenario::load(&path).unwrap(), &split).unwrap();
    let s = r
        .run(RunOptions {
            max_steps: Some(4000),
            ..Default::default()
        })
        .unwrap();
    let ck = s.checkpoint.unwrap();
    drop(r);
    let mut r = Runner::resume(&ck, None).unwrap();
    r.run(RunOptions::default()).unwrap();
    let mut compared = 0;
    for e in std::fs::read_dir(&whole).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        let post_file = ["contacts", "network_", "fields_", "flow.csv", "domain.json"]
            .iter()
            .any(|p| name.starts_with(p));
        if post_file {
            let a = std::fs::read(whole.join(&name)).unwrap();
            let b = std::fs::read(split.join(&name)).unwrap_or_default();
            assert!(a == b, "{name} differs after the resume");
            compared += 1;
        }
    }
    assert!(compared >= 12, "{compared} files compared");
    let flow = std::fs::read_to_string(whole.join("flow.csv")).unwrap();
    assert_eq!(
        flow.lines().count(),
        1 + 31,
        "a row every 300 steps, 0..=9000"
    );
    let _ = std::fs::remove_dir_all(&d);
}
