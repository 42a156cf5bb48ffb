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

/// Every body's state after a run, bit for bit.
fn state_bits(r: &Runner) -> Vec<u64> {
    let b = &r.world().bodies();
    let mut out = Vec::new();
    for i in 0..b.len() {
        out.push(b.id[i]);
        for v in [b.position[i], b.velocity[i], b.angular_velocity[i]] {
            out.extend(v.to_array().map(f64::to_bits));
        }
        out.extend(b.orientation[i].to_array().map(f64::to_bits));
    }
    out
}

/// Runs `text` whole and stopped at step `stop` then resumed from its
/// checkpoint, whose world state `edit` may change first (the checkpoint
/// is re-encoded with the same fingerprint): both final states.
fn whole_and_resumed(
    name: &str,
    text: &str,
    stop: u64,
    edit: impl Fn(&mut serde_json::Value),
) -> (Vec<u64>, Vec<u64>) {
    use clump_io::checkpoint::{decode_checkpoint, encode_checkpoint};
    let d = post::dir(name);
    let path = d.join("bed.toml");
    std::fs::write(&path, text).unwrap();
    let mut r = Runner::new(scenario::load(&path).unwrap(), &d.join("whole")).unwrap();
    r.run(RunOptions::default()).unwrap();
    let whole = state_bits(&r);
    drop(r);
    let mut r = Runner::new(scenario::load(&path).unwrap(), &d.join("split")).unwrap();
    let s = r
        .run(RunOptions {
            max_steps: Some(stop),
            ..Default::default()
        })
        .unwrap();
    drop(r);
    let ck = s.checkpoint.unwrap();
    let (json, fp): (String, u64) = decode_checkpoint(&std::fs::read(&ck).unwrap(), &ck).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    edit(&mut v["world"]);
    let edited = d.join("edited.ckpt");
    std::fs::write(&edited, encode_checkpoint(&v.to_string(), fp).unwrap()).unwrap();
    let mut r = Runner::resume(&edited, None).unwrap();
    r.run(RunOptions::default()).unwrap();
    let resumed = state_bits(&r);
    let _ = std::fs::remove_dir_all(&d);
    (whole, resumed)
}

/// A checkpoint in the format written before the MDR profiles were kept
/// (commit 621d058: the world state without `pair_slip` and `wall_slip`,
/// which is the present checkpoint less these two keys; the container's
/// format version is unchanged) still loads, and the run it resumes
/// repeats the uninterrupted run bit for bit.
#[test]
fn a_checkpoint_without_slip_profiles_resumes_bit_for_bit() {
    let text = post::bed_text_steps(40, 5, 3000, "");
    let (whole, resumed) = whole_and_resumed("old_format", &text, 1500, |w| {
        let o = w.as_object_mut().unwrap();
        for key in ["pair_slip", "wall_slip"] {
            let v = o.remove(key).expect("the present format has the key");
            assert_eq!(v, serde_json::json!([]), "{key}: no law keeps profiles");
        }
    });
    assert!(
        whole == resumed,
        "the old-format checkpoint resumed differently"
    );
}

/// With `tangential = "mdr"` the checkpoint file holds the profiles of
/// the touching pairs and wall slots (JSON, numbers in shortest
/// round-trip form), and the resumed run repeats the uninterrupted one bit
/// for bit.
#[test]
fn an_mdr_checkpoint_file_resumes_bit_for_bit() {
    // the bed has landed (about 0.1 s of fall) at the checkpoint
    let text = post::bed_text_steps(40, 5, 30000, "")
        .replace("friction = 0.5\n", "friction = 0.5\ntangential = \"mdr\"\n");
    let (whole, resumed) = whole_and_resumed("mdr_format", &text, 25000, |w| {
        let pairs = w["pair_slip"].as_array().unwrap().len();
        let walls = w["wall_slip"].as_array().unwrap();
        let wall_profiles = walls
            .iter()
            .flat_map(|slots| slots.as_array().unwrap())
            .filter(|p| p["len"].as_u64().unwrap() > 0)
            .count();
        assert!(
            pairs > 20 && wall_profiles > 5,
            "{pairs} pair profiles, {wall_profiles} wall profiles"
        );
    });
    assert!(whole == resumed, "the mdr checkpoint resumed differently");
}
