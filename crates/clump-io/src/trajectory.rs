//! Per-body trajectories: one CSV per requested global body id,
//! `traj_<id>.csv`, with columns `time` (s), `x,y,z` (centre of mass, world,
//! m), `vx,vy,vz` (world, m/s), `qw,qx,qy,qz` (orientation, body → world),
//! `wx,wy,wz` (angular velocity, world, rad/s), `wbx,wby,wbz` (angular
//! velocity, body frame, rad/s: q⁻¹ ω q).
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

/// Writes trajectory rows for a fixed set of bodies.
pub struct TrajectoryWriter {
    ids: Vec<u64>,
    files: Vec<AppendLog>,
    slot: HashMap<u64, usize>,
}

impl TrajectoryWriter {
    /// The file of body `id` in `dir`.
    pub fn file_path(dir: &Path, id: u64) -> PathBuf {
        dir.join(format!("traj_{id}.csv"))
    }

    /// Creates (truncates) one file per id in `dir` (created if missing).
    pub fn create(dir: impl AsRef<Path>, ids: &[u64]) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, None)
    }

    /// Reopens the files for a resumed run, keeping the complete rows with
    /// `time ≤ max_time` (s); missing files are created.
    pub fn resume(dir: impl AsRef<Path>, ids: &[u64], max_time: f64) -> io::Result<Self> {
        Self::open(dir.as_ref(), ids, Some(max_time))
    }

    fn open(dir: &Path, ids: &[u64], resume: Option<f64>) -> io::Result<Self> {
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
            let mut keep = format!("{TRAJECTORY_HEADER}\n");
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
        })
    }

    /// The tracked global body ids.
    pub fn ids(&self) -> &[u64] {
        &self.ids
    }

    /// Appends one row per tracked body present in `world` at `world.time`,
    /// and flushes.
    pub fn write(&mut self, world: &World) -> io::Result<()> {
        let b = &world.bodies;
        let mut index = vec![None; self.ids.len()];
        for (i, id) in b.id.iter().enumerate() {
            if let Some(&k) = self.slot.get(id) {
                index[k] = Some(i);
            }
        }
        for (k, f) in self.files.iter_mut().enumerate() {
            let Some(i) = index[k] else { continue };
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
            let row: Vec<String> = vals.iter().map(|&v| fmt_f64(v)).collect();
            f.append(format!("{}\n", row.join(",")).as_bytes())?;
        }
        Ok(())
    }
}
