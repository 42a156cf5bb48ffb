//! `clump validate --quick`: exit 0, report.md and PNG plots written.

use std::process::Command;

#[test]
fn validate_quick_passes_and_writes_report_and_plots() {
    let dir = std::env::temp_dir().join(format!("clump-validate-quick-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_clump"))
        .args(["validate", "--quick", "-o"])
        .arg(&dir)
        .output()
        .expect("run clump validate");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "clump validate --quick failed ({:?}):\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let report = std::fs::read_to_string(dir.join("report.md")).expect("report.md");
    assert!(report.contains("| case | source | expected | measured | tolerance | result |"));
    assert!(!report.contains("**FAIL**"));
    let pngs: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().extension().is_some_and(|x| x == "png"))
        .collect();
    assert!(pngs.len() >= 5, "only {} PNGs", pngs.len());
    for p in &pngs {
        let bytes = std::fs::read(p.path()).unwrap();
        assert!(
            bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
            "{:?} is not a PNG",
            p.path()
        );
        // every PNG referenced from the report
        let name = p.file_name().into_string().unwrap();
        assert!(report.contains(&name), "{name} not in report.md");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn validate_bad_output_folder_is_exit_2() {
    let file = std::env::temp_dir().join(format!("clump-validate-file-{}", std::process::id()));
    std::fs::write(&file, b"not a folder").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_clump"))
        .args(["validate", "--quick", "-o"])
        .arg(file.join("sub"))
        .output()
        .expect("run clump validate");
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_file(&file);
}
