//! Bodies CSV parsing and its error messages.

use clump_io::bodies_csv::{parse_bodies_csv, read_bodies_csv, resolve_bodies, BodiesCsvError};
use glam::DVec3;
use proptest::prelude::*;
use std::path::Path;

fn parse(s: &str) -> Result<Vec<clump_io::bodies_csv::BodyRecord>, BodiesCsvError> {
    parse_bodies_csv(s, Path::new("bodies.csv"))
}

#[test]
fn parses_full_and_short_forms() {
    let text = "# my bodies\n\
                template,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n\
                tetra, 1, 2, 3, 2, 0, 0, 0, 0.5, 0, -1, 0, 0, 7 # trailing comment\n\
                \n\
                ball,0,0,0,0,0,0,3,0,0,0,0,0,0\n";
    let r = parse(text).unwrap();
    assert_eq!(r.len(), 2);
    assert_eq!(r[0].template, "tetra");
    assert_eq!(r[0].line, 3);
    assert_eq!(r[0].position, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(r[0].orientation.w, 1.0);
    assert_eq!(r[0].velocity, DVec3::new(0.5, 0.0, -1.0));
    assert_eq!(r[0].angular_velocity, DVec3::new(0.0, 0.0, 7.0));
    assert_eq!(r[1].orientation.z, 1.0);
    let short = parse("template,x,y,z,qw,qx,qy,qz\nball,1,1,1,1,0,0,0\n").unwrap();
    assert_eq!(short[0].velocity, DVec3::ZERO);
    assert_eq!(short[0].angular_velocity, DVec3::ZERO);
    let names = vec!["tetra".to_string(), "ball".to_string()];
    let inits = resolve_bodies(&r, &names, Path::new("bodies.csv")).unwrap();
    assert_eq!(inits[0].template, 0);
    assert_eq!(inits[1].template, 1);
}

#[test]
fn errors_name_file_line_and_column() {
    let h = "template,x,y,z,qw,qx,qy,qz\n";
    let e = parse(&format!("{h}ball,1,abc,1,1,0,0,0\n"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bodies.csv:2")
            && e.contains("column 'y'")
            && e.contains("abc")
            && e.contains("number"),
        "{e}"
    );
    let e = parse(&format!("{h}ball,1,1,1,0,0,0,0\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("bodies.csv:2") && e.contains("zero"), "{e}");
    let e = parse(&format!("{h}ball,1,1,1,1,0,0\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("expected 8") && e.contains("found 7"), "{e}");
    let e = parse("x,y,z\n").unwrap_err().to_string();
    assert!(
        e.contains("bodies.csv:1") && e.contains("template,x,y,z,qw"),
        "{e}"
    );
    let e = parse("# only a comment\n").unwrap_err().to_string();
    assert!(e.contains("no header"), "{e}");
    let e = parse(&format!("{h}ball,1,inf,1,1,0,0,0\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("finite"), "{e}");
    let e = parse(&format!("{h} ,1,1,1,1,0,0,0\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("column 'template'"), "{e}");
    let r = parse(&format!("{h}cube,1,1,1,1,0,0,0\n")).unwrap();
    let e = resolve_bodies(&r, &["ball".into()], Path::new("bodies.csv"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bodies.csv:2") && e.contains("unknown template `cube`") && e.contains("ball"),
        "{e}"
    );
    let e = read_bodies_csv("/nonexistent/bodies.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("/nonexistent/bodies.csv"), "{e}");
}

proptest! {
    #[test]
    fn arbitrary_text_never_panics(s in ".{0,200}") {
        let _ = parse(&s);
        let _ = parse(&format!("template,x,y,z,qw,qx,qy,qz\n{s}"));
    }
}
