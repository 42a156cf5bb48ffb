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
//!   Optional instead of the quaternion: `phi, theta, psi` (z-x-z Euler
//!   angles of docs/theory.md T-3, rad, see `clump_core::math::euler`); instead of the
//!   world angular velocity: `wbx, wby, wbz` (rad/s, in the frame the
//!   orientation maps from). Degrees of freedom per body: `ffx, ffy, ffz`,
//!   `tfx, tfy, tfz` (force and torque flags, 1 or 0; default the template's
//!   and the insert's), `driven` (1: velocity and angular velocity held,
//!   see `clump_core::dof`); `start_step` or `start_time` (s): before it the
//!   body moves ballistically, ignoring forces (LIGGGHTS' `start_step`, docs/theory.md T-16);
//!   `temperature` (K, with `[heat]`; read by [`temperature_column`]).
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

const COLUMNS: [&str; 30] = [
    "template",
    "x",
    "y",
    "z",
    "qw",
    "qx",
    "qy",
    "qz",
    "vx",
    "vy",
    "vz",
    "wx",
    "wy",
    "wz",
    "wbx",
    "wby",
    "wbz",
    "phi",
    "theta",
    "psi",
    "ffx",
    "ffy",
    "ffz",
    "tfx",
    "tfy",
    "tfz",
    "driven",
    "start_step",
    "start_time",
    "temperature",
];
/// Index of the first column after `wz`.
const WB: usize = 14;
const EULER: usize = 17;
const FLAGS: usize = 20;
const DRIVEN_COL: usize = 26;
const START_STEP: usize = 27;
const START_TIME: usize = 28;

/// What a row of a CSV body file starts from before its own columns.
#[derive(Debug, Clone, Default)]
pub struct RowDefaults {
    /// Degrees of freedom by template index (the template's flags with the
    /// insert's overrides); a template past the end is free.
    pub dof: Vec<clump_core::dof::Dof>,
    /// Time step, s (turns `start_time` into a step).
    pub dt: f64,
}

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
    defaults: &RowDefaults,
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
        BodyFileFormat::Csv => parse_csv(text, template_names, default_template, defaults),
        BodyFileFormat::Xyzq => {
            let t = default_template.ok_or_else(|| {
                (
                    1,
                    "format \"xyzq\" has no template column: name the template of the insert"
                        .to_string(),
                )
            })?;
            let mut bodies = parse_xyzq(text, t)?;
            let dof = defaults.dof.get(t as usize).copied().unwrap_or_default();
            bodies.iter_mut().for_each(|b| dof.apply(b));
            Ok(bodies)
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

/// The unit quaternion along `(w, x, y, z)` (finite components); an error
/// when it is zero. A quaternion whose squared length is a normal number is
/// normalised as it is (the bits every earlier version gave); one with huge
/// or tiny components is first scaled by its largest component, so that
/// the squared length neither overflows nor underflows.
fn unit_quaternion(ln: usize, w: f64, x: f64, y: f64, z: f64) -> Result<DQuat, (usize, String)> {
    let m = w.abs().max(x.abs()).max(y.abs()).max(z.abs());
    if !(m > 0.0) {
        return Err((ln, "the quaternion (qw, qx, qy, qz) is zero".into()));
    }
    let q = DQuat::from_xyzw(x, y, z, w);
    let l2 = q.length_squared();
    if l2.is_finite() && l2.is_normal() {
        return Ok(q.normalize());
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
    defaults: &RowDefaults,
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
                    let hint = super::diag::did_you_mean(f, COLUMNS)
                        .map(|c| format!(" (did you mean '{c}'?)"))
                        .unwrap_or_default();
                    (
                        ln,
                        format!(
                            "unknown column '{}' in the header{hint}; allowed columns: {}",
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
            check_column_groups(&cols).map_err(|m| (ln, m))?;
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
        let mut vals = [0.0f64; COLUMNS.len()];
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
        out.push(row_body(ln, h, &vals, template, defaults)?);
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

/// Columns that go together (all or none) or exclude each other.
fn check_column_groups(cols: &[usize]) -> Result<(), String> {
    let has = |k: usize| cols.contains(&k);
    let group = |ks: &[usize], what: &str| -> Result<bool, String> {
        let n = ks.iter().filter(|&&k| has(k)).count();
        if n != 0 && n != ks.len() {
            let names: Vec<&str> = ks.iter().map(|&k| COLUMNS[k]).collect();
            return Err(format!(
                "{what} needs all of the columns {}",
                names.join(", ")
            ));
        }
        Ok(n != 0)
    };
    let quat = [4, 5, 6, 7].iter().any(|&k| has(k));
    let euler = group(
        &[EULER, EULER + 1, EULER + 2],
        "an orientation by Euler angles",
    )?;
    if quat && euler {
        return Err("give the orientation either as a quaternion (qw, qx, qy, qz) or as Euler angles (phi, theta, psi), not both".into());
    }
    let world = [11, 12, 13].iter().any(|&k| has(k));
    let body = [WB, WB + 1, WB + 2].iter().any(|&k| has(k));
    if world && body {
        return Err("give the angular velocity either in the world frame (wx, wy, wz) or in the body frame (wbx, wby, wbz), not both".into());
    }
    if has(START_STEP) && has(START_TIME) {
        return Err("give either 'start_step' or 'start_time', not both".into());
    }
    Ok(())
}

/// A flag column's value: 1 (free) or 0 (locked); `driven` likewise.
fn flag(ln: usize, k: usize, x: f64) -> Result<bool, (usize, String)> {
    match x {
        v if v == 1.0 => Ok(true),
        v if v == 0.0 => Ok(false),
        _ => Err((
            ln,
            format!("column '{}': expected 1 or 0, found {x}", COLUMNS[k]),
        )),
    }
}

/// The body of one CSV row: `h` lists the row's columns (indices into
/// [`COLUMNS`]), `vals` their values (the rest at their defaults).
fn row_body(
    ln: usize,
    h: &[usize],
    vals: &[f64; COLUMNS.len()],
    template: u32,
    defaults: &RowDefaults,
) -> Result<BodyInit, (usize, String)> {
    let q = if h.contains(&EULER) {
        let (phi, theta, psi) = (vals[EULER], vals[EULER + 1], vals[EULER + 2]);
        if !(0.0..=std::f64::consts::PI).contains(&theta) {
            return Err((
                ln,
                format!(
                    "column 'theta': the z-x-z nutation angle lies in [0, pi] rad, found {theta}"
                ),
            ));
        }
        clump_core::math::euler_to_quat(phi, theta, psi)
    } else {
        unit_quaternion(ln, vals[4], vals[5], vals[6], vals[7])?
    };
    let mut b = BodyInit::at_rest(template, DVec3::new(vals[1], vals[2], vals[3]), q);
    b.velocity = DVec3::new(vals[8], vals[9], vals[10]);
    b.angular_velocity = if h.contains(&WB) {
        q * DVec3::new(vals[WB], vals[WB + 1], vals[WB + 2])
    } else {
        DVec3::new(vals[11], vals[12], vals[13])
    };
    let mut dof = defaults
        .dof
        .get(template as usize)
        .copied()
        .unwrap_or_default();
    for a in 0..3 {
        if h.contains(&(FLAGS + a)) {
            dof.force_flag[a] = flag(ln, FLAGS + a, vals[FLAGS + a])?;
        }
        if h.contains(&(FLAGS + 3 + a)) {
            dof.torque_flag[a] = flag(ln, FLAGS + 3 + a, vals[FLAGS + 3 + a])?;
        }
    }
    if h.contains(&DRIVEN_COL) {
        dof.driven = flag(ln, DRIVEN_COL, vals[DRIVEN_COL])?;
    }
    let start = if h.contains(&START_STEP) {
        let s = vals[START_STEP];
        if !(s >= 0.0 && s.fract() == 0.0 && s < 9.0e15) {
            return Err((
                ln,
                format!("column 'start_step': expected a whole step number >= 0, found {s}"),
            ));
        }
        Some(s as u64)
    } else if h.contains(&START_TIME) {
        let t = vals[START_TIME];
        if t < 0.0 {
            return Err((
                ln,
                format!("column 'start_time': expected a time >= 0 s, found {t}"),
            ));
        }
        Some((t / defaults.dt).ceil() as u64)
    } else {
        None
    };
    if dof.driven && start.is_some() {
        return Err((
            ln,
            "a driven body never feels forces: 'start_step'/'start_time' do not apply to it".into(),
        ));
    }
    dof.apply(&mut b);
    if let Some(s) = start {
        b.start_step = s;
    }
    Ok(b)
}

/// The `temperature` column of a CSV body file (K, one per body in file
/// order), `None` when the file has none. Call on a file [`parse`]
/// accepted (the values are then finite); errors are `(1-based line,
/// message)` for a temperature not above 0 K.
pub fn temperature_column(bytes: &[u8]) -> Result<Option<Vec<f64>>, (usize, String)> {
    let text = String::from_utf8_lossy(bytes);
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let mut col: Option<Option<usize>> = None;
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut fields = line.split(',').map(str::trim);
        match col {
            None => col = Some(fields.position(|f| f == "temperature")),
            Some(None) => return Ok(None),
            Some(Some(k)) => {
                let t = fields
                    .nth(k)
                    .and_then(|f| f.parse::<f64>().ok())
                    .unwrap_or(f64::NAN);
                if !(t > 0.0 && t.is_finite()) {
                    return Err((ln + 1, format!("temperature must be > 0 K, found {t}")));
                }
                out.push(t);
            }
        }
    }
    Ok(col.flatten().map(|_| out))
}
