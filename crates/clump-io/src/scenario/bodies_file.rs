//! Reader of the body list of `[[insert]] kind = "file"`, in one of two
//! formats ([`BodyFileFormat`]):
//!
//! - **`csv`**: a header row naming the columns, then one body per row.
//!   Columns (any order; `x`, `y`, `z` required, and `template` unless the
//!   insert names a default template; the rest default to the identity
//!   orientation and zero velocities): `template` (name, or 0-based index in
//!   the scenario's `[[template]]` list), `x, y, z` (centre of mass, world
//!   frame, m), `qw, qx, qy, qz` (orientation, normalised on reading),
//!   `vx, vy, vz` (m/s, world), `wx, wy, wz` (angular velocity, rad/s, world).
//! - **`xyzq`**: whitespace-separated `id x y z qw qx qy qz` rows without a
//!   header (the format of the shared tetra-bed initial conditions and of
//!   many LIGGGHTS/Yade scripts); every body uses the insert's template and
//!   starts at rest. `id` is read and checked but not used (bodies get ids
//!   in file order).
//!
//! `#` starts a comment line in both. Which frame the quaternion starts from
//! (the principal body frame, or the template's input frame) is applied by
//! the caller.
#![allow(clippy::needless_range_loop)]

use clump_core::body::BodyInit;
use glam::{DQuat, DVec3};

const COLUMNS: [&str; 14] = [
    "template", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
];

/// Layout of a body file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BodyFileFormat {
    /// Comma-separated with a header row naming the columns.
    #[default]
    Csv,
    /// Whitespace-separated `id x y z qw qx qy qz`, no header.
    Xyzq,
}

/// Parses the file; `default_template` serves rows without a `template`
/// column (and every row of `xyzq`). Errors are `(1-based line, message)`.
pub fn parse(
    bytes: &[u8],
    format: BodyFileFormat,
    template_names: &[String],
    default_template: Option<u32>,
) -> Result<Vec<BodyInit>, (usize, String)> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let (line, column) = super::diag::utf8_position(bytes, &e);
        (
            line,
            format!(
                "not UTF-8 text: invalid byte at column {column} (expected a text file of bodies)"
            ),
        )
    })?;
    // a byte-order mark (spreadsheet exports) is not part of the first column
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    match format {
        BodyFileFormat::Csv => parse_csv(text, template_names, default_template),
        BodyFileFormat::Xyzq => {
            let t = default_template.ok_or_else(|| {
                (
                    1,
                    "format \"xyzq\" has no template column: name the template of the insert"
                        .to_string(),
                )
            })?;
            parse_xyzq(text, t)
        }
    }
}

fn finite(ln: usize, what: &str, f: &str) -> Result<f64, (usize, String)> {
    f.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| {
            (
                ln,
                format!(
                    "column '{what}': expected a finite number, found '{}'",
                    super::diag::shorten(f)
                ),
            )
        })
}

/// The unit quaternion along `(w, x, y, z)` (finite components): scaled by
/// its largest component first, so that huge or tiny components neither
/// overflow nor underflow; an error when it is zero.
fn unit_quaternion(ln: usize, w: f64, x: f64, y: f64, z: f64) -> Result<DQuat, (usize, String)> {
    let m = w.abs().max(x.abs()).max(y.abs()).max(z.abs());
    if !(m > 0.0) {
        return Err((ln, "the quaternion (qw, qx, qy, qz) is zero".into()));
    }
    Ok(DQuat::from_xyzw(x / m, y / m, z / m, w / m).normalize())
}

fn parse_xyzq(text: &str, template: u32) -> Result<Vec<BodyInit>, (usize, String)> {
    const COLS: [&str; 8] = ["id", "x", "y", "z", "qw", "qx", "qy", "qz"];
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let ln = ln + 1;
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != COLS.len() {
            return Err((
                ln,
                format!(
                    "expected 8 fields `id x y z qw qx qy qz`, found {}",
                    fields.len()
                ),
            ));
        }
        let mut v = [0.0; 8];
        for k in 0..8 {
            v[k] = finite(ln, COLS[k], fields[k])?;
        }
        let q = unit_quaternion(ln, v[4], v[5], v[6], v[7])?;
        out.push(BodyInit::at_rest(template, DVec3::new(v[1], v[2], v[3]), q));
    }
    if out.is_empty() {
        return Err((1, "no bodies: expected rows `id x y z qw qx qy qz`".into()));
    }
    Ok(out)
}

fn parse_csv(
    text: &str,
    template_names: &[String],
    default_template: Option<u32>,
) -> Result<Vec<BodyInit>, (usize, String)> {
    let mut header: Option<Vec<usize>> = None; // column index in COLUMNS per field
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let ln = ln + 1;
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let Some(h) = &header else {
            let mut cols = Vec::new();
            for f in &fields {
                let k = COLUMNS.iter().position(|c| c == f).ok_or_else(|| {
                    (
                        ln,
                        format!(
                            "unknown column '{}' in the header; allowed columns: {}",
                            super::diag::shorten(f),
                            COLUMNS.join(", ")
                        ),
                    )
                })?;
                if cols.contains(&k) {
                    return Err((ln, format!("column '{f}' appears twice")));
                }
                cols.push(k);
            }
            let first_required = if default_template.is_some() { 1 } else { 0 };
            for req in first_required..4 {
                if !cols.contains(&req) {
                    return Err((
                        ln,
                        format!(
                            "the header lacks the required column '{}' (needs template, x, y, z)",
                            COLUMNS[req]
                        ),
                    ));
                }
            }
            header = Some(cols);
            continue;
        };
        if fields.len() != h.len() {
            return Err((
                ln,
                format!(
                    "expected {} fields as in the header, found {}",
                    h.len(),
                    fields.len()
                ),
            ));
        }
        let mut vals = [0.0f64; 14];
        vals[4] = 1.0;
        let mut template = default_template.unwrap_or(0);
        for (f, &k) in fields.iter().zip(h) {
            if k == 0 {
                template = match template_names.iter().position(|n| n == f) {
                    Some(i) => i as u32,
                    None => match f.parse::<usize>() {
                        Ok(i) if i < template_names.len() => i as u32,
                        _ => {
                            return Err((
                                ln,
                                format!(
                                    "template '{}' does not exist; defined templates: {}",
                                    super::diag::shorten(f),
                                    template_names.join(", ")
                                ),
                            ))
                        }
                    },
                };
            } else {
                vals[k] = finite(ln, COLUMNS[k], f)?;
            }
        }
        let q = unit_quaternion(ln, vals[4], vals[5], vals[6], vals[7])?;
        let mut b = BodyInit::at_rest(template, DVec3::new(vals[1], vals[2], vals[3]), q);
        b.velocity = DVec3::new(vals[8], vals[9], vals[10]);
        b.angular_velocity = DVec3::new(vals[11], vals[12], vals[13]);
        out.push(b);
    }
    if header.is_none() {
        return Err((
            1,
            format!(
                "empty file: expected a header row such as {}",
                COLUMNS.join(",")
            ),
        ));
    }
    Ok(out)
}
