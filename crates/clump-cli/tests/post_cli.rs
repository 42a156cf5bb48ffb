//! `clump post` on a small version of the hopper example with contact
//! frames and flow probes: the plots are PNG files, the fields of the saved
//! frames are written and their density integrates to the bodies' mass;
//! a picture of the particles and a ParaView script are written; without
//! `--width` the user is told how to get fields; a bad option is refused
//! with a message and exit status 1.

use std::path::Path;
use std::process::Command;

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

#[test]
fn post_plots_fields_and_force_chains_of_a_hopper_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("../../examples/hopper.toml")).unwrap();
    let text = text
        .replace("count = 1200", "count = 200")
        .replace("duration = 0.3 ", "duration = 0.12")
        .replace("duration = 0.6", "duration = 0.1")
        .replace(
            "vtk = { every = 0.01 }",
            "vtk = { every = 1.0 }\ncontacts = { every = 0.04 }",
        )
        .replace("checkpoint = { every = 0.3 }", "");
    let d = std::env::temp_dir().join(format!("clump-post-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let sc = d.join("hopper.toml");
    std::fs::write(&sc, text).unwrap();
    let run = d.join("run");
    let o = clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(&run)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = clump()
        .arg("post")
        .arg(&run)
        .args([
            "--width",
            "0.003",
            "--axes",
            "z",
            "--cells",
            "40",
            "--lo=-0.05",
            "--hi",
            "0.25",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let post = run.join("post");
    for f in [
        "thermo_energy.png",
        "thermo_walls.png",
        "thermo_contacts.png",
        "flow_planes.png",
        "flow_regions.png",
        "profile_density.png",
        "profile_stress.png",
        "force_chains.png",
        "particles.png",
    ] {
        let b = std::fs::read(post.join(f)).unwrap_or_else(|e| panic!("{f}: {e}\n{stdout}"));
        assert!(b.starts_with(b"\x89PNG") && b.len() > 5000, "{f}");
    }
    // the bed's share of the cross-section, per cell, lies in [0, 1], and
    // the user is told which frames were averaged
    let bed = std::fs::read_to_string(post.join("profile_bed.csv")).unwrap();
    assert!(bed.starts_with("z[m],occupied_fraction,density_in_bed[kg/m^3]\n"));
    let shares: Vec<f64> = bed
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(shares.len(), 40);
    assert!(
        shares.iter().all(|f| (0.0..=1.0 + 1e-12).contains(f)),
        "{bed}"
    );
    assert!(shares.iter().any(|&f| f > 0.0), "{bed}");
    assert!(stdout.contains("fields averaged over"), "{stdout}");
    // the last frame's density profile integrates to the bodies' mass (the
    // grid reaches beyond the domain's height by more than the kernel)
    let frames = std::fs::read_to_string(run.join("contacts.pvd")).unwrap();
    let last = frames
        .lines()
        .filter(|l| l.contains("contacts_"))
        .last()
        .unwrap();
    let step: String = last
        .split("contacts_")
        .nth(1)
        .unwrap()
        .chars()
        .take(6)
        .collect();
    let csv = std::fs::read_to_string(post.join(format!("fields_{step}.csv"))).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let dz = rows[1][0] - rows[0][0];
    let area = 0.14 * 0.07;
    let mass: f64 = rows.iter().map(|r| r[1]).sum::<f64>() * dz * area;
    let vtp = clump_io::post::read::read_vtp(&run.join(format!("bodies_{step}.vtp"))).unwrap();
    let total: f64 = vtp["mass"].iter().sum();
    assert!(
        total > 0.0 && (mass - total).abs() <= 1e-10 * total,
        "fields {mass} kg, bodies {total} kg"
    );
    // a bad option
    let o = clump()
        .arg("post")
        .arg(&run)
        .args(["--width", "0.003", "--axes", "w"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown axis 'w'"));
    // the ParaView script applies the README's recipe to this run's spheres
    let py = std::fs::read_to_string(post.join("paraview_view.py")).unwrap();
    for want in [
        "PVDReader",
        "\"spheres.pvd\"",
        "GlyphMode = \"All Points\"",
        "ScaleFactor = 2.0",
    ] {
        assert!(py.contains(want), "paraview_view.py lacks {want}:\n{py}");
    }
    // without --width the user is told how to get the fields
    let o = clump().arg("post").arg(&run).output().unwrap();
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("no coarse-grained fields without --width"),
        "{out}"
    );
    let o = clump()
        .arg("post")
        .arg(&run)
        .args(["--color", "heat"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("allowed are speed, radius, body_id"));
    let _ = std::fs::remove_dir_all(&d);
}
