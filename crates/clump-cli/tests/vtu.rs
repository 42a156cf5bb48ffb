//! `[output] vtk_format = "vtu"` writes UnstructuredGrid frames that
//! meshio reads (Debian `python3-meshio`; the test prints a note and passes
//! without it): the same points and arrays as the `.vtp` frames.

use std::path::Path;
use std::process::Command;

const SCENARIO: &str = r#"
[simulation]
dt = 2e-5
steps = 40

[domain]
lo = [-0.03, -0.03, -0.01]
hi = [0.03, 0.03, 0.1]

[[material]]
name = "rock"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[[template]]
name = "tetra"
material = "rock"
shape = "tetrahedron"
radius = 0.002
edge = 0.0025

[[wall]]
name = "floor"
material = "rock"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "pack"
template = "tetra"
count = 20
region = { type = "box", lo = [-0.02, -0.02, 0.005], hi = [0.02, 0.02, 0.05] }
seed = 3

[output]
vtk = { every_steps = 20 }
vtk_format = "vtu"
"#;

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
    let d = std::env::temp_dir().join(format!("clump-vtu-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let sc = d.join("vtu.toml");
    std::fs::write(&sc, SCENARIO).unwrap();
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
    assert!(text.contains("bodies 20 ['angular_velocity', 'body_id', 'ex', 'ey', 'ez', 'mass', 'quaternion', 'scale', 'template', 'velocity']"), "{text}");
    assert!(
        text.contains("walls ") && text.contains("'polygon'"),
        "{text}"
    );
    assert!(text.contains("radius_min 0.002"), "{text}");
    let _ = std::fs::remove_dir_all(&d);
}
