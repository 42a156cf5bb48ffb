//! Per-body trajectories: one CSV per requested global body id,
//! `traj_<id>.csv`, with columns `time` (s), `x,y,z` (centre of mass, world,
//! m), `vx,vy,vz` (world, m/s), `qw,qx,qy,qz` (orientation, body → world),
//! `wx,wy,wz` (angular velocity, world, rad/s), `wbx,wby,wbz` (angular
//! velocity, body frame, rad/s: q⁻¹ ω q). With `euler = true` also
//! `phi,theta,psi` (the z-x-z Euler angles of docs/theory.md T-3, rad, gimbal lock as in
//! `clump_core::math::euler`) and `exx,exy,exz,eyx,eyy,eyz,ezx,ezy,ezz`: the
//! rows of the matrix A (docs/theory.md T-2) (world → body), i.e. the body axes in world
//! coordinates, LIGGGHTS' `ex_space, ey_space, ez_space`. With
//! `loads = true` also `fx,fy,fz,mx,my,mz` (see [`Extras::loads`]); in the
//! 2D mode `theta_2d` (see [`PLANAR_COLUMNS`]); with `[heat]` last
//! `temperature` (K).
//!
//! Like `thermo.csv` these are append-only logs flushed at each row; a body
//! absent at a write (not yet inserted, or lost) gets no row.

use crate::append::AppendLog;
use crate::atomic::write_atomic;
use crate::thermo_csv::fmt_f64;
use clump_core::world::World;
use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};

/// The header line of a trajectory file.
pub const TRAJECTORY_HEADER: &str = "time,x,y,z,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz,wbx,wby,wbz";

/// The columns `euler = true` appends to [`TRAJECTORY_HEADER`].
pub const EULER_COLUMNS: &str = "phi,theta,psi,exx,exy,exz,eyx,eyy,eyz,ezx,ezy,ezz";

/// The columns `loads = true` appends (after the Euler columns, if any).
pub const LOAD_COLUMNS: &str = "fx,fy,fz,mx,my,mz";

/// Optional column groups of the trajectory rows.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Extras {
    /// [`EULER_COLUMNS`].
    pub euler: bool,
    /// [`LOAD_COLUMNS`]: the body's total force (N) and torque about its
    /// centre of mass (N m), world frame, of the last force evaluation
    /// (contacts and gravity; for a fixed or driven body the load its
    /// motion is held against).
    pub loads: bool,
    /// [`PLANAR_COLUMNS`] (the 2D mode).
    pub planar: bool,
    /// [`TEMPERATURE_COLUMNS`] (with heat).
    pub temperature: bool,
}

/// The column heat appends (last): the body's temperature, K.
pub const TEMPERATURE_COLUMNS: &str = "temperature";

/// The column the 2D mode appends (last): the rotation angle θ about z
/// (rad, in (−π, π]) of the planar matrix `A_θ`, `2 atan2(q_z, q_w)`.
pub const PLANAR_COLUMNS: &str = "theta_2d";

/// Writes trajectory rows for a fixed set of bodies.
pub struct TrajectoryWriter {
    ids: Vec<u64>,
    files: Vec<AppendLog>,
    slot: HashMap<u64, usize>,
    /// Optional columns.
    extras: Extras,
}

impl TrajectoryWriter {
    /// The file of body `id` in `dir`.
    pub fn file_path(dir: &Path, id: u64) -> PathBuf {
        dir.join(format!("traj_{id}.csv"))
    }

    /// Creates (truncates) one file per id in `dir` (created if missing).
    pub fn create(dir: impl AsRef<Path>, ids: &[u64]) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, None, Extras::default())
    }

    /// [`Self::create`] with the optional columns `extras`.
    pub fn create_with(dir: impl AsRef<Path>, ids: &[u64], extras: Extras) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, None, extras)
    }

    /// [`Self::resume`] with the optional columns `extras`.
    pub fn resume_with(
        dir: impl AsRef<Path>,
        ids: &[u64],
        max_time: f64,
        extras: Extras,
    ) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, Some(max_time), extras)
    }

    /// Reopens the files for a resumed run, keeping the complete rows with
    /// `time ≤ max_time` (s); missing files are created.
    pub fn resume(dir: impl AsRef<Path>, ids: &[u64], max_time: f64) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, Some(max_time), Extras::default())
    }

    fn open(dir: &Path, ids: &[u64], resume: Option<f64>, extras: Extras) -> io::Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| {
            io::Error::new(e.kind(), format!("cannot create {}: {e}", dir.display()))
        })?;
        let mut uniq = Vec::new();
        for &id in ids {
            if !uniq.contains(&id) {
                uniq.push(id);
            }
        }
        let mut files = Vec::with_capacity(uniq.len());
        for &id in &uniq {
            let path = Self::file_path(dir, id);
            let mut keep = TRAJECTORY_HEADER.to_string();
            for (on, cols) in [
                (extras.euler, EULER_COLUMNS),
                (extras.loads, LOAD_COLUMNS),
                (extras.planar, PLANAR_COLUMNS),
                (extras.temperature, TEMPERATURE_COLUMNS),
            ] {
                if on {
                    keep = format!("{keep},{cols}");
                }
            }
            keep.push('\n');
            if let Some(max_time) = resume {
                if let Ok(b) = std::fs::read(&path) {
                    let text = String::from_utf8_lossy(&b);
                    for line in text.split_inclusive('\n').skip(1) {
                        if !line.ends_with('\n') {
                            break;
                        }
                        match line
                            .split(',')
                            .next()
                            .and_then(|s| s.trim().parse::<f64>().ok())
                        {
                            Some(t) if t <= max_time => keep.push_str(line),
                            _ => {}
                        }
                    }
                }
            }
            write_atomic(&path, keep.as_bytes())?;
            files.push(AppendLog::open(&path)?);
        }
        let slot = uniq.iter().enumerate().map(|(k, &id)| (id, k)).collect();
        Ok(TrajectoryWriter {
            ids: uniq,
            files,
            slot,
            extras,
        })
    }

    /// The tracked global body ids.
    pub fn ids(&self) -> &[u64] {
        &self.ids
    }

    /// Appends one row per tracked body present in `world` at `world.time`,
    /// and flushes.
    pub fn write(&mut self, world: &World) -> io::Result<()> {
        let rows = self.rows(world, None);
        self.append_rows(&rows)
    }

    /// The rows at `world.time` of the tracked bodies present in `world`
    /// (of those whose entry in `mask` is true, when given: a rank's owned
    /// bodies), each with the index of its file, in file order.
    pub fn rows(&self, world: &World, mask: Option<&[bool]>) -> Vec<(u32, String)> {
        let b = &world.bodies();
        let mut index = vec![None; self.ids.len()];
        for (i, id) in b.id.iter().enumerate() {
            if let Some(&k) = self.slot.get(id) {
                if mask.map_or(true, |m| m[i]) {
                    index[k] = Some(i);
                }
            }
        }
        let rows = index.iter().enumerate();
        rows.filter_map(|(k, i)| Some((k as u32, self.row(world, (*i)?))))
            .collect()
    }

    /// Appends each `(file, row)` of [`Self::rows`] (from any rank) to its
    /// file, and flushes; an error for a file index out of range.
    pub fn append_rows(&mut self, rows: &[(u32, String)]) -> io::Result<()> {
        for (k, row) in rows {
            let f = self.files.get_mut(*k as usize).ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!("no trajectory file {k}"),
                )
            })?;
            f.append(row.as_bytes())?;
        }
        Ok(())
    }

    /// The row (with its newline) of body `i` of `world`.
    fn row(&self, world: &World, i: usize) -> String {
        let b = &world.bodies();
        let (x, v, q, w) = (
            b.position[i],
            b.velocity[i],
            b.orientation[i],
            b.angular_velocity[i],
        );
        let wb = q.inverse() * w;
        let vals = [
            world.time, x.x, x.y, x.z, v.x, v.y, v.z, q.w, q.x, q.y, q.z, w.x, w.y, w.z, wb.x,
            wb.y, wb.z,
        ];
        let mut row: Vec<String> = vals.iter().map(|&v| fmt_f64(v)).collect();
        if self.extras.euler {
            row.extend(euler_columns(q).iter().map(|&v| fmt_f64(v)));
        }
        if self.extras.loads {
            let (f, m) = (b.force[i], b.torque[i]);
            row.extend([f.x, f.y, f.z, m.x, m.y, m.z].iter().map(|&v| fmt_f64(v)));
        }
        if self.extras.planar {
            let mut theta = 2.0 * q.z.atan2(q.w);
            if theta > std::f64::consts::PI {
                theta -= std::f64::consts::TAU;
            } else if theta <= -std::f64::consts::PI {
                theta += std::f64::consts::TAU;
            }
            row.push(fmt_f64(theta));
        }
        if self.extras.temperature {
            row.push(fmt_f64(b.temperature.get(i).copied().unwrap_or(f64::NAN)));
        }
        format!("{}\n", row.join(","))
    }
}

/// The values of [`EULER_COLUMNS`] for the orientation `q` (body → world):
/// `phi, theta, psi` and the rows of A = R(q)ᵀ (the body axes in world
/// coordinates).
pub fn euler_columns(q: glam::DQuat) -> [f64; 12] {
    let (phi, theta, psi) = clump_core::math::quat_to_euler(q);
    let r = glam::DMat3::from_quat(q);
    let (ex, ey, ez) = (r.x_axis, r.y_axis, r.z_axis);
    [
        phi, theta, psi, ex.x, ex.y, ex.z, ey.x, ey.y, ey.z, ez.x, ez.y, ez.z,
    ]
}
