//! The four input parsers — scenario files, template files, mesh files
//! (STL/OBJ) and checkpoints — return errors, never panic, on arbitrary
//! bytes and on damaged valid inputs (random byte edits, insertions,
//! deletions, bit flips, truncation). The regression inputs found by the
//! cargo-fuzz targets (`fuzz/`) are replayed here as well.
//!
//! Case counts are modest (CI time); `fuzz/` explores much further.

use clump_io::checkpoint::encode_checkpoint;
use clump_io::mesh_file::{parse_obj, parse_stl, stl_ascii, stl_binary};
use clump_io::run::{load_checkpoint, Checkpoint, RunOptions, Runner};
use clump_io::scenario::{self, Files};
use clump_io::template_file::parse_template_bytes;
use glam::DVec3;
use proptest::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

/// A small valid scenario using a template file and a bodies file.
const SCENARIO: &str = r#"
[simulation]
dt = 2e-5
steps = 20
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.02, -0.02, -0.01]
hi = [0.02, 0.02, 0.05]

[[material]]
name = "rock"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.4
friction = 0.5
rolling = "epsd"
rolling_friction = 0.1

[[template]]
name = "duo"
material = "rock"
file = "duo.txt"

[[template]]
name = "rod"
material = "rock"
shape = "rod"
n = 3
radius = 0.001
spacing = 0.001

[[mix]]
name = "m"
[[mix.component]]
template = "rod"
size = { distribution = "uniform", min = 0.9, max = 1.1 }

[[wall]]
name = "floor"
material = "rock"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "file"
file = "bodies.csv"

[[insert]]
kind = "pack"
mix = "m"
count = 4
region = { type = "box", lo = [-0.01, -0.01, 0.005], hi = [0.01, 0.01, 0.02] }

[output]
thermo = { every_steps = 5 }
checkpoint = { every_steps = 10 }
"#;

const TEMPLATE: &str = "# two spheres\n0 0 0 0.001\n0.0008 0 0 0.0009\n";
const BODIES: &str = "template,x,y,z,vx\nduo,0,0,0.002,0.1\nduo,0.005,0,0.002,0\n";

fn files() -> BTreeMap<String, Vec<u8>> {
    let mut f = BTreeMap::new();
    f.insert("duo.txt".to_string(), TEMPLATE.as_bytes().to_vec());
    f.insert("bodies.csv".to_string(), BODIES.as_bytes().to_vec());
    f
}

fn parse_scenario(text: String) {
    if let Ok(sc) = scenario::parse(Path::new("p.toml"), text, Files::embedded(files())) {
        let _ = sc.build_world();
    }
}

/// A real checkpoint of [`SCENARIO`] at step 10 (bodies in contact, with
/// contact and rolling histories), written once.
fn checkpoint_bytes() -> &'static [u8] {
    static CK: OnceLock<Vec<u8>> = OnceLock::new();
    CK.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("clump-never-panic-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("duo.txt"), TEMPLATE).unwrap();
        std::fs::write(d.join("bodies.csv"), BODIES).unwrap();
        std::fs::write(d.join("p.toml"), SCENARIO).unwrap();
        let sc = scenario::load(&d.join("p.toml")).unwrap();
        let mut r = Runner::new(sc, &d.join("out")).unwrap();
        r.run(RunOptions {
            max_steps: Some(10),
            ..RunOptions::default()
        })
        .unwrap();
        let b = std::fs::read(d.join("out/checkpoint_000000010.ckpt")).unwrap();
        let _ = std::fs::remove_dir_all(&d);
        b
    })
}

/// The JSON payload of [`checkpoint_bytes`].
fn checkpoint_json() -> &'static str {
    static J: OnceLock<String> = OnceLock::new();
    J.get_or_init(|| {
        clump_io::checkpoint::decode_checkpoint::<String>(checkpoint_bytes(), Path::new("c"))
            .unwrap()
            .0
    })
}

/// Wraps a JSON payload in a valid header (length, CRC and, when the
/// payload's scenario parses, its fingerprint) and loads it.
fn load_payload(json: &str) {
    let fp = serde_json::from_str::<Checkpoint>(json)
        .ok()
        .and_then(|ck| {
            scenario::parse(
                Path::new(&ck.scenario_path),
                ck.scenario_text,
                Files::embedded(ck.files),
            )
            .ok()
        })
        .map_or(0, |s| s.fingerprint());
    let bytes = encode_checkpoint(&json.to_string(), fp).unwrap();
    let _ = load_checkpoint(&bytes, Path::new("c.ckpt"));
}

fn stl_cube() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let v: Vec<DVec3> = (0..8)
        .map(|k| DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64))
        .collect();
    let t = vec![
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    (v, t)
}

const OBJ: &str = "# tetra\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nf 1 3 2\nf 1//1 2//1 4//1\nf 1/1 4/1 3/1\nf 2 3 4\n";

fn parse_mesh(bytes: &[u8], obj: bool) {
    let r = if obj {
        parse_obj(bytes)
    } else {
        parse_stl(bytes)
    };
    if let Ok((v, t)) = r {
        let _ = clump_core::wall::TriMesh::new(v, t);
    }
}

/// One damage to a byte string.
#[derive(Debug, Clone)]
enum Edit {
    Set(usize, u8),
    Flip(usize, u8),
    Insert(usize, u8),
    Delete(usize),
    Truncate(usize),
    /// Repeat a slice (large counts, long lines, duplicated tables).
    Repeat(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        4 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Set(i, b)),
        3 => (any::<usize>(), 0u8..8).prop_map(|(i, b)| Edit::Flip(i, b)),
        3 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Insert(i, b)),
        2 => any::<usize>().prop_map(Edit::Delete),
        1 => any::<usize>().prop_map(Edit::Truncate),
        1 => (any::<usize>(), 1usize..64).prop_map(|(i, n)| Edit::Repeat(i, n)),
    ]
}

/// Digits and TOML punctuation make edits of text inputs more interesting.
fn text_edit() -> impl Strategy<Value = Edit> {
    let interesting = prop::sample::select(b"0123456789-+.eE[]{}=,\"'#\n inf nan".to_vec());
    prop_oneof![
        2 => edit(),
        2 => (any::<usize>(), interesting.clone()).prop_map(|(i, b)| Edit::Set(i, b)),
        1 => (any::<usize>(), interesting).prop_map(|(i, b)| Edit::Insert(i, b)),
    ]
}

fn apply(mut b: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    for e in edits {
        let n = b.len().max(1);
        match *e {
            Edit::Set(i, x) if !b.is_empty() => b[i % n] = x,
            Edit::Flip(i, bit) if !b.is_empty() => b[i % n] ^= 1 << bit,
            Edit::Insert(i, x) => b.insert(i % (b.len() + 1), x),
            Edit::Delete(i) if !b.is_empty() => {
                b.remove(i % n);
            }
            Edit::Truncate(i) => b.truncate(i % (b.len() + 1)),
            Edit::Repeat(i, k) if !b.is_empty() => {
                let s = i % n;
                let e = (s + 16).min(b.len());
                let piece = b[s..e].to_vec();
                for _ in 0..k {
                    b.splice(e..e, piece.iter().copied());
                }
            }
            _ => {}
        }
    }
    b
}

fn lossy(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn scenario_arbitrary_text(s in "\\PC{0,400}") {
        parse_scenario(s);
    }

    #[test]
    fn scenario_damaged(edits in prop::collection::vec(text_edit(), 1..8)) {
        parse_scenario(lossy(&apply(SCENARIO.as_bytes().to_vec(), &edits)));
    }

    #[test]
    fn template_arbitrary_bytes(b in prop::collection::vec(any::<u8>(), 0..300)) {
        let _ = parse_template_bytes(&b, Path::new("t.txt"));
    }

    #[test]
    fn template_damaged(edits in prop::collection::vec(text_edit(), 1..8)) {
        let _ = parse_template_bytes(&apply(TEMPLATE.as_bytes().to_vec(), &edits), Path::new("t.txt"));
    }

    #[test]
    fn mesh_arbitrary_bytes(b in prop::collection::vec(any::<u8>(), 0..400), obj in any::<bool>()) {
        parse_mesh(&b, obj);
    }

    #[test]
    fn mesh_damaged(edits in prop::collection::vec(edit(), 1..8), kind in 0u8..3) {
        let (v, t) = stl_cube();
        let good = match kind {
            0 => stl_binary(&v, &t),
            1 => stl_ascii("cube", &v, &t).into_bytes(),
            _ => OBJ.as_bytes().to_vec(),
        };
        parse_mesh(&apply(good, &edits), kind == 2);
    }

    #[test]
    fn checkpoint_arbitrary_bytes(b in prop::collection::vec(any::<u8>(), 0..200)) {
        let _ = load_checkpoint(&b, Path::new("c.ckpt"));
        // with a valid magic and version in front
        let mut c = checkpoint_bytes()[..12].to_vec();
        c.extend_from_slice(&b);
        let _ = load_checkpoint(&c, Path::new("c.ckpt"));
    }
}

proptest! {
    // each case rebuilds a world from the checkpoint: fewer cases
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn checkpoint_damaged_file(edits in prop::collection::vec(edit(), 1..6)) {
        let _ = load_checkpoint(&apply(checkpoint_bytes().to_vec(), &edits), Path::new("c.ckpt"));
    }

    #[test]
    fn checkpoint_damaged_payload(edits in prop::collection::vec(text_edit(), 1..6)) {
        load_payload(&lossy(&apply(checkpoint_json().as_bytes().to_vec(), &edits)));
    }
}

#[test]
fn valid_inputs_load() {
    // the unmodified inputs are accepted, so the damaged ones test the parsers' depths
    scenario::parse(
        Path::new("p.toml"),
        SCENARIO.into(),
        Files::embedded(files()),
    )
    .unwrap();
    assert_eq!(
        parse_template_bytes(TEMPLATE.as_bytes(), Path::new("t"))
            .unwrap()
            .len(),
        2
    );
    let (v, t) = stl_cube();
    assert_eq!(parse_stl(&stl_binary(&v, &t)).unwrap().1.len(), 12);
    assert_eq!(parse_obj(OBJ.as_bytes()).unwrap().1.len(), 4);
    load_checkpoint(checkpoint_bytes(), Path::new("c.ckpt")).unwrap();
    let json = checkpoint_json();
    let fp = clump_io::checkpoint::decode_checkpoint::<String>(checkpoint_bytes(), Path::new("c"))
        .unwrap()
        .1;
    load_checkpoint(
        &encode_checkpoint(&json.to_string(), fp).unwrap(),
        Path::new("c"),
    )
    .unwrap();
}

/// Structured damage of a valid checkpoint payload that a byte fuzzer rarely
/// hits: every array of the world state one element short or long, walls
/// and materials that do not exist, a different domain or time step. Each
/// must be refused (or at least not panic), never crash the loader.
#[test]
fn checkpoint_with_inconsistent_state_is_refused() {
    let good: serde_json::Value = serde_json::from_str(checkpoint_json()).unwrap();
    let fp = clump_io::checkpoint::decode_checkpoint::<String>(checkpoint_bytes(), Path::new("c"))
        .unwrap()
        .1;
    let load = |v: &serde_json::Value| {
        let bytes = encode_checkpoint(&v.to_string(), fp).unwrap();
        load_checkpoint(&bytes, Path::new("c.ckpt")).map(|_| ())
    };
    load(&good).unwrap();
    let mut cases: Vec<(String, serde_json::Value)> = Vec::new();
    let bodies = good["world"]["bodies"].as_object().unwrap().clone();
    for (k, arr) in &bodies {
        if arr.as_array().is_some_and(|a| !a.is_empty()) {
            let mut v = good.clone();
            v["world"]["bodies"][k].as_array_mut().unwrap().pop();
            cases.push((format!("bodies.{k} one short"), v));
            let mut v = good.clone();
            let a = v["world"]["bodies"][k].as_array_mut().unwrap();
            let first = a[0].clone();
            a.push(first);
            cases.push((format!("bodies.{k} one long"), v));
        }
    }
    for k in [
        "wall_loads",
        "walls",
        "reference_pose",
        "wall_key",
        "wall_hist",
    ] {
        let mut v = good.clone();
        v["world"][k].as_array_mut().unwrap().pop();
        cases.push((format!("{k} one short"), v));
    }
    let mut v = good.clone();
    v["world"]["walls"][0]["material"] = 99.into();
    cases.push(("wall material 99".into(), v));
    let mut v = good.clone();
    v["world"]["config"]["domain"]["hi"] = serde_json::json!([0.0, 0.0, 0.0]);
    cases.push(("empty domain".into(), v));
    let mut v = good.clone();
    v["world"]["config"]["dt"] = serde_json::json!(-1.0);
    cases.push(("negative dt".into(), v));
    let mut v = good.clone();
    v["world"]["bodies"]["template"][0] = 77.into();
    cases.push(("template 77".into(), v));
    let mut v = good.clone();
    v["driver"]["stage"] = 5.into();
    cases.push(("stage 5".into(), v));
    let mut v = good.clone();
    v["driver"]["streams"].as_array_mut().unwrap().clear();
    cases.push(("no stream slots".into(), v));
    let mut v = good.clone();
    v["driver"]["inserted"].as_array_mut().unwrap().clear();
    cases.push(("no insert counts".into(), v));
    for (what, v) in cases {
        let r = std::panic::catch_unwind(|| load(&v));
        match r {
            Ok(Err(_)) => {}
            Ok(Ok(())) => panic!("{what}: accepted"),
            Err(_) => panic!("{what}: the loader panicked"),
        }
    }
}

/// Regression: a mistyped rod length (`n` up to u32::MAX) used to allocate
/// `n` spheres (tens of GB: an abort, not an error) before any check.
#[test]
fn huge_rod_is_an_error_not_an_allocation() {
    let text = SCENARIO.replace("n = 3\n", "n = 4000000000\n");
    let e = scenario::parse(Path::new("p.toml"), text, Files::embedded(files())).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("a rod may have at most 10000 spheres"),
        "{msg}"
    );
    assert!(msg.contains("p.toml:32:"), "{msg}");
}
