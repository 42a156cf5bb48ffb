//! The ParaView recipe for the spheres (Glyph → Sphere, scale by `radius`,
//! factor 2, **Glyph Mode = All Points**) glyphs every sphere of the stones
//! example, checked with ParaView's own `pvpython` under `xvfb-run`
//! (Debian packages `paraview` and `xvfb`; the test prints a note and
//! passes when they are missing). ParaView's default glyph mode samples at
//! most 5 000 points, so without "All Points" most spheres are not drawn.
//! Also: the spheres series starts at the first frame with bodies, so
//! `radius` is offered at the first time.

use std::path::Path;
use std::process::Command;

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn paraview_recipe_glyphs_every_sphere() {
    if !have("pvpython") || !have("xvfb-run") {
        eprintln!("SKIPPED: pvpython or xvfb-run not found (apt-get install paraview xvfb)");
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = std::env::temp_dir().join(format!("clump-paraview-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let out = d.join("stones");
    // to the end of the pour: all 160 stones, more than 5 000 spheres
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .arg("run")
        .arg(root.join("../../examples/stones.toml"))
        .arg("-o")
        .arg(&out)
        .args(["--steps", "7400"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let png = d.join("stones.png");
    let o = Command::new("xvfb-run")
        .args(["-a", "pvpython"])
        .arg(root.join("tests/paraview_recipe.py"))
        .arg(out.join("spheres.pvd"))
        .arg(&png)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let value = |key: &str| -> String {
        text.lines()
            .find_map(|l| l.strip_prefix(&format!("{key} ")))
            .unwrap_or_else(|| panic!("no {key} in:\n{text}"))
            .to_string()
    };
    let count = |key: &str| -> usize { value(key).parse().unwrap() };
    let spheres = count("spheres");
    assert!(spheres > 5_000, "{text}");
    assert_eq!(count("glyphs_all_points"), spheres, "{text}");
    assert!(count("glyphs_default") < spheres, "{text}");
    assert!(
        value("first_arrays").split(',').any(|a| a == "radius"),
        "{text}"
    );
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    let _ = std::fs::remove_dir_all(&d);
}
