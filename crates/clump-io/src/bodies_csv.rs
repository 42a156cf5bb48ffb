//! Reading bodies from a CSV file.
//!
//! Format: a header line, then one body per line:
//!
//! ```text
//! template,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
//! ```
//!
//! - `template`: template name; `x,y,z`: centre of mass, world frame, m;
//!   `qw,qx,qy,qz`: orientation body → world (normalised on reading; a zero
//!   quaternion is an error); `vx,vy,vz`: velocity, world, m/s; `wx,wy,wz`:
//!   angular velocity, world, rad/s.
//! - The header must list the columns in this order; it may stop after `qz`
//!   (no velocities) or after `vz` (no angular velocities): missing columns
//!   are zero. Every row has as many fields as the header.
//! - `#` starts a comment (whole line or trailing); blank lines are ignored;
//!   spaces around fields are ignored.
//!
//! Every error names the file, the 1-based line, the column and what is
//! allowed; arbitrary input never panics.

use clump_core::body::BodyInit;
use glam::{DQuat, DVec3};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// All columns, in order.
pub const BODY_COLUMNS: [&str; 14] = [
    "template", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
];

/// Why a bodies file could not be read.
#[derive(Debug, Error)]
pub enum BodiesCsvError {
    /// The file could not be read.
    #[error("{path}: cannot read bodies file: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A syntax or value error.
    #[error("{path}:{line}: {}{message}", column.as_ref().map(|c| format!("column '{c}': ")).unwrap_or_default())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// The column, when the error is about one field.
        column: Option<String>,
        /// What is wrong and what is allowed.
        message: String,
    },
}

/// One body read from the file (world frame, SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyRecord {
    /// 1-based line number in the file.
    pub line: usize,
    /// Template name.
    pub template: String,
    /// Centre of mass, world frame, m.
    pub position: DVec3,
    /// Orientation, body → world (normalised).
    pub orientation: DQuat,
    /// Velocity, world frame, m/s.
    pub velocity: DVec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
}

/// Reads and parses a bodies file.
pub fn read_bodies_csv(path: impl AsRef<Path>) -> Result<Vec<BodyRecord>, BodiesCsvError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| BodiesCsvError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
            let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
            return Err(BodiesCsvError::Invalid {
                path: path.to_path_buf(),
                line,
                column: None,
                message: "not valid UTF-8 text (a bodies file is a text CSV file)".into(),
            });
        }
    };
    parse_bodies_csv(&text, path)
}

/// Parses the text of a bodies file (`path` is used in messages only).
pub fn parse_bodies_csv(text: &str, path: &Path) -> Result<Vec<BodyRecord>, BodiesCsvError> {
    let err = |line: usize, column: Option<&str>, message: String| BodiesCsvError::Invalid {
        path: path.to_path_buf(),
        line,
        column: column.map(str::to_string),
        message,
    };
    let mut ncols = None;
    let mut out = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line_no = k + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fields: Vec<&str> = content.split(',').map(str::trim).collect();
        let Some(n) = ncols else {
            let n = fields.len();
            let ok = matches!(n, 8 | 11 | 14)
                && fields
                    .iter()
                    .zip(BODY_COLUMNS.iter())
                    .all(|(a, b)| a.eq_ignore_ascii_case(b));
            if !ok {
                return Err(err(
                    line_no,
                    None,
                    format!(
                        "expected the header `{}` (the last 6 columns, or the last 3, may be left out), found `{content}`",
                        BODY_COLUMNS.join(",")
                    ),
                ));
            }
            ncols = Some(n);
            continue;
        };
        if fields.len() != n {
            return Err(err(
                line_no,
                None,
                format!(
                    "expected {n} comma-separated fields as in the header ({}), found {}",
                    BODY_COLUMNS[..n].join(","),
                    fields.len()
                ),
            ));
        }
        let template = fields[0];
        if template.is_empty() {
            return Err(err(
                line_no,
                Some("template"),
                "is empty; give the name of a template".into(),
            ));
        }
        let mut v = [0.0f64; 14];
        for c in 1..n {
            let f = fields[c];
            let x: f64 = f.parse().map_err(|_| {
                err(
                    line_no,
                    Some(BODY_COLUMNS[c]),
                    format!("`{f}` is not a number (expected a finite decimal number)"),
                )
            })?;
            if !x.is_finite() {
                return Err(err(
                    line_no,
                    Some(BODY_COLUMNS[c]),
                    format!("`{f}` is not finite (expected a finite number)"),
                ));
            }
            v[c] = x;
        }
        let q = DQuat::from_xyzw(v[5], v[6], v[7], v[4]);
        let len = q.length();
        if len <= 1e-300 || !len.is_finite() {
            return Err(err(
                line_no,
                Some("qw"),
                "the quaternion qw,qx,qy,qz is zero; give a non-zero orientation (1,0,0,0 for none)".into(),
            ));
        }
        out.push(BodyRecord {
            line: line_no,
            template: template.to_string(),
            position: DVec3::new(v[1], v[2], v[3]),
            orientation: q / len,
            velocity: DVec3::new(v[8], v[9], v[10]),
            angular_velocity: DVec3::new(v[11], v[12], v[13]),
        });
    }
    if ncols.is_none() {
        return Err(err(
            text.lines().count().max(1),
            None,
            format!(
                "no header line found; the file must start with `{}`",
                BODY_COLUMNS.join(",")
            ),
        ));
    }
    Ok(out)
}

/// Turns records into [`BodyInit`]s, looking templates up by name in
/// `template_names` (index = template index in the world). An unknown name
/// is an error that lists the known ones.
pub fn resolve_bodies(
    records: &[BodyRecord],
    template_names: &[String],
    path: &Path,
) -> Result<Vec<BodyInit>, BodiesCsvError> {
    records
        .iter()
        .map(|r| {
            let t = template_names
                .iter()
                .position(|n| *n == r.template)
                .ok_or_else(|| BodiesCsvError::Invalid {
                    path: path.to_path_buf(),
                    line: r.line,
                    column: Some("template".into()),
                    message: format!(
                        "unknown template `{}`; known templates: {}",
                        r.template,
                        template_names.join(", ")
                    ),
                })?;
            Ok(BodyInit {
                velocity: r.velocity,
                angular_velocity: r.angular_velocity,
                ..BodyInit::at_rest(t as u32, r.position, r.orientation)
            })
        })
        .collect()
}
