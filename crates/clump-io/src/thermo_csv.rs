//! `thermo.csv`: one row of global quantities per thermo output (SI units,
//! world frame).
//!
//! Columns (the header carries the units in brackets, e.g.
//! `ke_translational[J]`; counts and ratios have none): `time[s]`, `step`,
//! `bodies`, `contacts` (pair + wall), `pair_contacts`, `wall_contacts`,
//! `ke_translational[J]`, `ke_rotational[J]`, `elastic_energy[J]`,
//! `potential_energy[J]`, `max_overlap_ratio`, `lost_bodies`, then per wall
//! `<name>_fx[N],<name>_fy[N],<name>_fz[N]` and
//! `<name>_tx[N*m],<name>_ty[N*m],<name>_tz[N*m]` (about the wall's
//! `torque_point`, by default its motion centre): the load the particles
//! exert on it; for a wall that moves (in any stage) also `<name>_power[W]`: the power the wall's rigid motion delivers to the
//! particles, `−(F·v + T_c·ω)` with the load `F` and the torque `T_c` about
//! the centre of rotation exerted on the wall by the particles, and the wall's
//! velocity `v` and angular velocity `ω` (a conveyor's `surface_velocity` is
//! not included). With `[heat]`, last: `mean_temperature[K]`,
//! `min_temperature[K]`, `max_temperature[K]`, `heat_content[J]` (Σ m c_p T
//! of the bodies), `heat_stability` (the last step's largest dt Σ H /
//! (m c_p), stable up to 1), then per wall `<name>_heat_flow[W]` (from the
//! wall into the bodies in the last step) and `<name>_heat[J]` (since the
//! start). With `[fluid]`, last: `fluid_fx[N],fluid_fy[N],fluid_fz[N]`, the
//! total fluid force on the bodies (drag, buoyancy, pressure gradient) of
//! the last force evaluation.
//!
//! The file is an append-only log: each row is written to the file at once,
//! so an interrupted run keeps every row written so far (a row cut by a
//! crash is dropped on resume; one cut by a full disk is removed at once,
//! see [`crate::append`]). This is deliberately not written through
//! [`crate::atomic`]: rewriting the whole log at every row would be
//! quadratic. On resume, [`ThermoWriter::resume`] rewrites the file
//! atomically without the rows after the resume step and then appends.

use crate::append::AppendLog;
use crate::atomic::write_atomic;
use clump_core::thermo::Thermo;
use std::io;
use std::path::{Path, PathBuf};

/// Writes `thermo.csv` rows.
pub struct ThermoWriter {
    path: PathBuf,
    header: String,
    power: Vec<bool>,
    /// The heat columns are written.
    heat: bool,
    /// The fluid-force columns are written.
    fluid: bool,
    out: AppendLog,
}

/// The columns of one wall.
#[derive(Debug, Clone, PartialEq)]
pub struct WallColumns {
    /// The wall's name.
    pub name: String,
    /// Whether it has a `<name>_power` column.
    pub power: bool,
}

impl WallColumns {
    /// Force and torque columns only, for each name.
    pub fn plain(names: &[String]) -> Vec<WallColumns> {
        names
            .iter()
            .map(|n| WallColumns {
                name: n.clone(),
                power: false,
            })
            .collect()
    }
}

/// Formats a float so that it reads back exactly (shortest round-trip),
/// in exponent notation for very small or large magnitudes.
pub fn fmt_f64(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || (1e-4..1e15).contains(&a) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A wall name usable in a CSV column: characters other than ASCII letters,
/// digits, `_`, `-` and `.` become `_`.
pub fn column_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "wall".into()
    } else {
        s
    }
}

/// `header` without its `[unit]` suffixes.
pub fn without_units(header: &str) -> String {
    let mut out = String::with_capacity(header.len());
    let mut depth = 0;
    for c in header.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

impl ThermoWriter {
    /// The header line (without newline) for the given wall names.
    pub fn header(wall_names: &[String]) -> String {
        Self::header_walls(&WallColumns::plain(wall_names))
    }

    /// The header line (without newline) for the given walls, with the
    /// heat columns when `heat`.
    pub fn header_heat(walls: &[WallColumns], heat: bool) -> String {
        let mut h = Self::header_walls(walls);
        if heat {
            h.push_str(",mean_temperature[K],min_temperature[K],max_temperature[K],heat_content[J],heat_stability");
            for c in unique_columns(walls) {
                h.push_str(&format!(",{c}_heat_flow[W],{c}_heat[J]"));
            }
        }
        h
    }

    /// The header line (without newline) for the given walls, with the
    /// heat columns when `heat` and the fluid-force columns when `fluid`.
    pub fn header_columns(walls: &[WallColumns], heat: bool, fluid: bool) -> String {
        let mut h = Self::header_heat(walls, heat);
        if fluid {
            h.push_str(",fluid_fx[N],fluid_fy[N],fluid_fz[N]");
        }
        h
    }

    /// The values of the heat columns of [`Self::header_heat`], in order.
    pub fn heat_values(h: &clump_core::thermo::HeatThermo) -> Vec<f64> {
        let mut v = vec![
            h.mean_temperature,
            h.min_temperature,
            h.max_temperature,
            h.heat_content,
            h.stability,
        ];
        for (q, e) in h.wall_flow.iter().zip(&h.wall_heat) {
            v.push(*q);
            v.push(*e);
        }
        v
    }

    /// The header line (without newline) for the given walls.
    pub fn header_walls(walls: &[WallColumns]) -> String {
        let mut h = String::from(
            "time[s],step,bodies,contacts,pair_contacts,wall_contacts,ke_translational[J],\
             ke_rotational[J],elastic_energy[J],potential_energy[J],max_overlap_ratio,lost_bodies",
        );
        for (w, c) in walls.iter().zip(unique_columns(walls)) {
            for s in ["fx[N]", "fy[N]", "fz[N]", "tx[N*m]", "ty[N*m]", "tz[N*m]"] {
                h.push_str(&format!(",{c}_{s}"));
            }
            if w.power {
                h.push_str(&format!(",{c}_power[W]"));
            }
        }
        h
    }

    /// Creates (truncates) `path` and writes the header (force and torque
    /// columns per wall).
    pub fn create(path: impl AsRef<Path>, wall_names: &[String]) -> io::Result<Self> {
        Self::create_walls(path, &WallColumns::plain(wall_names), false)
    }

    /// Creates (truncates) `path` and writes the header for `walls` (and
    /// the heat columns when `heat`).
    pub fn create_walls(
        path: impl AsRef<Path>,
        walls: &[WallColumns],
        heat: bool,
    ) -> io::Result<Self> {
        Self::create_columns(path, walls, heat, false)
    }

    /// [`ThermoWriter::create_walls`], with the fluid-force columns when `fluid`.
    pub fn create_columns(
        path: impl AsRef<Path>,
        walls: &[WallColumns],
        heat: bool,
        fluid: bool,
    ) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        let header = Self::header_columns(walls, heat, fluid);
        write_atomic(&path, format!("{header}\n").as_bytes())?;
        Self::open_append(path, header, walls, (heat, fluid))
    }

    /// Reopens `path` for a resumed run: keeps the header and the complete
    /// rows with `step ≤ resume_step`, drops the others, then appends. A
    /// missing file is created. Fails if the existing header differs (the
    /// walls changed).
    pub fn resume(
        path: impl AsRef<Path>,
        wall_names: &[String],
        resume_step: u64,
    ) -> io::Result<Self> {
        Self::resume_walls(path, &WallColumns::plain(wall_names), resume_step, false)
    }

    /// [`ThermoWriter::resume`] for `walls` (and the heat columns when
    /// `heat`).
    pub fn resume_walls(
        path: impl AsRef<Path>,
        walls: &[WallColumns],
        resume_step: u64,
        heat: bool,
    ) -> io::Result<Self> {
        Self::resume_columns(path, walls, resume_step, heat, false)
    }

    /// [`ThermoWriter::resume_walls`], with the fluid-force columns when `fluid`.
    pub fn resume_columns(
        path: impl AsRef<Path>,
        walls: &[WallColumns],
        resume_step: u64,
        heat: bool,
        fluid: bool,
    ) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        let header = Self::header_columns(walls, heat, fluid);
        let text = match std::fs::read(&path) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return Self::create_columns(path, walls, heat, fluid)
            }
            Err(e) => {
                return Err(io::Error::new(
                    e.kind(),
                    format!("cannot read {}: {e}", path.display()),
                ))
            }
        };
        let mut lines = text.split_inclusive('\n');
        let first = lines.next().unwrap_or("").trim_end();
        // a header of an older version, without units, continues too
        if first != header && first != without_units(&header) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "{}: the header does not match this run's columns (were walls added, removed or renamed?); found `{first}`, expected `{header}`",
                    path.display()
                ),
            ));
        }
        let mut keep = format!("{header}\n");
        for line in lines {
            if !line.ends_with('\n') {
                break; // a row cut by an interruption
            }
            let step = line
                .split(',')
                .nth(1)
                .and_then(|s| s.trim().parse::<u64>().ok());
            match step {
                Some(s) if s <= resume_step => keep.push_str(line),
                _ => {}
            }
        }
        write_atomic(&path, keep.as_bytes())?;
        Self::open_append(path, header, walls, (heat, fluid))
    }

    fn open_append(
        path: PathBuf,
        header: String,
        walls: &[WallColumns],
        (heat, fluid): (bool, bool),
    ) -> io::Result<Self> {
        Ok(ThermoWriter {
            out: AppendLog::open(&path)?,
            path,
            header,
            power: walls.iter().map(|w| w.power).collect(),
            heat,
            fluid,
        })
    }

    /// The file path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The header line.
    pub fn header_line(&self) -> &str {
        &self.header
    }

    /// Appends one row and flushes it to the file (power columns, if any, 0).
    pub fn write(&mut self, t: &Thermo) -> io::Result<()> {
        self.write_row(t, &[])
    }

    /// Appends one row with `power[i]` (W) in the power column of wall `i`
    /// (0 where `power` is shorter), and flushes it to the file.
    pub fn write_row(&mut self, t: &Thermo, power: &[f64]) -> io::Result<()> {
        let mut row = format!(
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            fmt_f64(t.time),
            t.step,
            t.bodies,
            t.pair_contacts + t.wall_contacts,
            t.pair_contacts,
            t.wall_contacts,
            fmt_f64(t.kinetic_translational),
            fmt_f64(t.kinetic_rotational),
            fmt_f64(t.elastic),
            fmt_f64(t.potential),
            fmt_f64(t.max_overlap_ratio),
            t.lost_bodies
        );
        for (i, &has_power) in self.power.iter().enumerate() {
            let l = t.wall_loads.get(i).copied().unwrap_or_default();
            for v in [
                l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z,
            ] {
                row.push(',');
                row.push_str(&fmt_f64(v));
            }
            if has_power {
                row.push(',');
                row.push_str(&fmt_f64(power.get(i).copied().unwrap_or(0.0)));
            }
        }
        if let (true, Some(h)) = (self.heat, &t.heat) {
            for v in Self::heat_values(h) {
                row.push(',');
                row.push_str(&fmt_f64(v));
            }
        }
        if self.fluid {
            for v in t.fluid_force.unwrap_or_default().to_array() {
                row.push(',');
                row.push_str(&fmt_f64(v));
            }
        }
        row.push('\n');
        self.out.append(row.as_bytes())
    }
}

/// The column name of each wall, made unique by its index where two names
/// read the same.
fn unique_columns(walls: &[WallColumns]) -> Vec<String> {
    let mut used: Vec<String> = Vec::new();
    for (i, w) in walls.iter().enumerate() {
        let mut c = column_name(&w.name);
        if used.contains(&c) {
            c = format!("{c}_{i}");
        }
        used.push(c);
    }
    used
}
