//! Reader of the body list of `[[insert]] kind = "file"`: a CSV file with a
//! header row naming the columns.
//!
//! Columns (any order; `template`, `x`, `y`, `z` required, the rest default
//! to the identity orientation and zero velocities):
//! `template` (name, or 0-based index in the scenario's `[[template]]` list),
//! `x, y, z` (centre of mass, world frame, m), `qw, qx, qy, qz` (orientation
//! body → world, normalised on reading), `vx, vy, vz` (m/s, world),
//! `wx, wy, wz` (angular velocity, rad/s, world). `#` starts a comment line.
#![allow(clippy::needless_range_loop)]

use clump_core::body::BodyInit;
use glam::{DQuat, DVec3};

const COLUMNS: [&str; 14] = [
    "template", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
];

/// Parses the file; errors are `(1-based line, message)`.
pub fn parse(bytes: &[u8], template_names: &[String]) -> Result<Vec<BodyInit>, (usize, String)> {
    let text = std::str::from_utf8(bytes)
        .map_err(|_| (1, "not UTF-8 text (expected a CSV file)".to_string()))?;
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
                            "unknown column '{f}' in the header; allowed columns: {}",
                            COLUMNS.join(", ")
                        ),
                    )
                })?;
                if cols.contains(&k) {
                    return Err((ln, format!("column '{f}' appears twice")));
                }
                cols.push(k);
            }
            for req in 0..4 {
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
        let mut template = 0u32;
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
                                    "template '{f}' does not exist; defined templates: {}",
                                    template_names.join(", ")
                                ),
                            ))
                        }
                    },
                };
            } else {
                vals[k] = f
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        (
                            ln,
                            format!(
                                "column '{}': expected a finite number, found '{f}'",
                                COLUMNS[k]
                            ),
                        )
                    })?;
            }
        }
        let q = DQuat::from_xyzw(vals[5], vals[6], vals[7], vals[4]);
        if q.length() < 1e-12 {
            return Err((ln, "the quaternion (qw, qx, qy, qz) is zero".into()));
        }
        let mut b = BodyInit::at_rest(
            template,
            DVec3::new(vals[1], vals[2], vals[3]),
            q.normalize(),
        );
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
