//! `[output] vtk_format = "vtu"` writes UnstructuredGrid frames that
//! meshio reads (Debian `python3-meshio`; the test prints a note and passes
//! without it): the same points and arrays as the `.vtp` frames.

mod common;

use std::path::Path;
use std::process::Command;

const READ: &str = r#"
import sys, meshio
d = sys.argv[1]
s = meshio.read(d + "/spheres_000040.vtu")
b = meshio.read(d + "/bodies_000040.vtu")
w = meshio.read(d + "/walls_000040.vtu")
print("spheres", len(s.points), sorted(s.point_data), [c.type for c in s.cells], sum(len(c.data) for c in s.cells))
print("bodies", len(b.points), sorted(b.point_data))
print("walls", len(w.points), [c.type for c in w.cells], sorted(w.cell_data))
print("radius_min", float(s.point_data["radius"].min()))
"#;

fn meshio() -> bool {
    Command::new("/usr/bin/python3")
        .args(["-c", "import meshio"])
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn vtu_frames_are_read_by_meshio() {
    let dir = tempfile::Builder::new()
        .prefix("clump-vtu-")
        .tempdir()
        .unwrap();
    let d = dir.path();
    let sc = d.join("vtu.toml");
    std::fs::write(
        &sc,
        common::fall(40, "vtk = { every_steps = 20 }\nvtk_format = \"vtu\"\n"),
    )
    .unwrap();
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let pvd = std::fs::read_to_string(out.join("spheres.pvd")).unwrap();
    assert!(pvd.contains("file=\"spheres_000040.vtu\""), "{pvd}");
    assert!(!Path::new(&out.join("spheres_000040.vtp")).exists());
    if !meshio() {
        eprintln!("SKIPPED: meshio not found (apt-get install python3-meshio)");
        return;
    }
    let o = Command::new("/usr/bin/python3")
        .args(["-c", READ])
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // 20 tetrahedra of 4 spheres, one vertex cell each
    assert!(
        text.contains("spheres 80 ['body_id', 'radius', 'velocity'] ['vertex'] 80"),
        "{text}"
    );
    assert!(text.contains("bodies 20 ['angular_velocity', 'body_id', 'contacts', 'coordination', 'euler', 'ex', 'ey', 'ez', 'force', 'inertia', 'mass', 'quaternion', 'scale', 'template', 'torque', 'velocity', 'volume', 'wall_contacts']"), "{text}");
    assert!(
        text.contains("walls ") && text.contains("'polygon'"),
        "{text}"
    );
    assert!(text.contains("radius_min 0.002"), "{text}");
}
