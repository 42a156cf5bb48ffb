//! Flow measurement (`[[output.flow]]`): bodies crossing planes, with
//! direction, and the bodies held in box regions with their size
//! distribution by volume-equivalent diameter, sampled at a fixed interval
//! into `flow.csv`.
//!
//! A crossing is a change of side of a body's centre of mass between two
//! samples (the displacement taken as its minimum image across periodic
//! sides). A body removed between two samples (lost through an open side)
//! is not seen crossing after its last sample, so the interval has to be
//! shorter than the time a body takes from the plane to the domain's edge.

use super::frame::{min_image, Frame};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt::Write as _;

/// What one `[[output.flow]]` entry measures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Probe {
    /// An infinite plane through `point` with unit `normal`; crossings
    /// along the normal count as positive.
    Plane {
        /// A point of the plane, m.
        point: DVec3,
        /// Unit normal.
        normal: DVec3,
    },
    /// An axis-aligned box, with the edges (m, ascending) of the
    /// volume-equivalent diameter bins of its size distribution.
    Region {
        /// Lower corner, m.
        lo: DVec3,
        /// Upper corner, m.
        hi: DVec3,
        /// Bin edges, m.
        bins: Vec<f64>,
    },
}

/// A named probe.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FlowProbe {
    /// Name (column prefix).
    pub name: String,
    /// What it measures.
    pub probe: Probe,
}

/// The running state of the measurement (saved in checkpoints).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FlowState {
    /// Per plane probe: each body's centre of mass at the last sample, by
    /// body id, m.
    pub last: Vec<Vec<(u64, DVec3)>>,
    /// Per plane probe: net mass crossed along the normal since the start, kg.
    pub net_mass: Vec<f64>,
}

/// The header of flow.csv for `probes`.
pub fn header(probes: &[FlowProbe]) -> String {
    let mut h = String::from("time[s],step");
    for p in probes {
        let n = &p.name;
        match &p.probe {
            Probe::Plane { .. } => {
                let _ = write!(
                    h,
                    ",{n}_mass_pos[kg],{n}_mass_neg[kg],{n}_count_pos,{n}_count_neg,{n}_net_mass_total[kg]"
                );
            }
            Probe::Region { bins, .. } => {
                let _ = write!(h, ",{n}_mass[kg],{n}_count");
                for w in bins.windows(2) {
                    let _ = write!(h, ",{n}_d_{:e}_{:e}[m]", w[0], w[1]);
                }
            }
        }
    }
    h
}

/// One row of flow.csv for `frame` (without newline), updating `state`.
/// The first sample of a plane counts no crossings.
pub fn sample(probes: &[FlowProbe], state: &mut FlowState, frame: &Frame) -> String {
    let mut row = format!("{:e},{}", frame.time, frame.step);
    let np = probes.len();
    state.last.resize(np, Vec::new());
    state.net_mass.resize(np, 0.0);
    for (k, p) in probes.iter().enumerate() {
        match &p.probe {
            Probe::Plane { point, normal } => {
                let prev: HashMap<u64, DVec3> = state.last[k].iter().copied().collect();
                let (mut mp, mut mn, mut cp, mut cn) = (0.0, 0.0, 0u64, 0u64);
                let mut now = Vec::with_capacity(frame.bodies.len());
                for b in &frame.bodies {
                    if let Some(&x0) = prev.get(&b.id) {
                        // the side reached from the last sample's side by
                        // the minimum-image displacement (a body that
                        // wrapped across a periodic side moved a short way)
                        let s0 = (x0 - *point).dot(*normal);
                        let s1 = s0 + min_image(&frame.domain, b.position - x0).dot(*normal);
                        if s0 < 0.0 && s1 >= 0.0 {
                            mp += b.mass;
                            cp += 1;
                        } else if s0 >= 0.0 && s1 < 0.0 {
                            mn += b.mass;
                            cn += 1;
                        }
                    }
                    now.push((b.id, b.position));
                }
                state.last[k] = now;
                state.net_mass[k] += mp - mn;
                let _ = write!(row, ",{mp:e},{mn:e},{cp},{cn},{:e}", state.net_mass[k]);
            }
            Probe::Region { lo, hi, bins } => {
                let (mut m, mut c) = (0.0, 0u64);
                let mut hist = vec![0u64; bins.len().saturating_sub(1)];
                for b in &frame.bodies {
                    let x = b.position;
                    if (0..3).all(|a| x[a] >= lo[a] && x[a] < hi[a]) {
                        m += b.mass;
                        c += 1;
                        let d = b.equivalent_diameter();
                        if let Some(i) = bins.windows(2).position(|w| d >= w[0] && d < w[1]) {
                            hist[i] += 1;
                        }
                    }
                }
                let _ = write!(row, ",{m:e},{c}");
                for n in hist {
                    let _ = write!(row, ",{n}");
                }
            }
        }
    }
    row
}

/// Opens `flow.csv` at `path` with `header`: new (`resume_step` `None`),
/// or continued after a checkpoint at `resume_step` (rows after it are
/// dropped; a missing file starts anew).
pub fn open_csv(
    path: &std::path::Path,
    header: &str,
    resume_step: Option<u64>,
) -> std::io::Result<crate::append::AppendLog> {
    let mut text = format!("{header}\n");
    if let Some(step) = resume_step {
        if let Ok(old) = std::fs::read_to_string(path) {
            let mut lines = old.lines();
            if lines.next() != Some(header) {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!(
                        "{}: the header does not match this run's probes",
                        path.display()
                    ),
                ));
            }
            for l in lines {
                let s: Option<u64> = l.split(',').nth(1).and_then(|x| x.parse().ok());
                if s.is_some_and(|s| s <= step) {
                    text.push_str(l);
                    text.push('\n');
                }
            }
        }
    }
    crate::atomic::write_atomic(path, text.as_bytes())?;
    crate::append::AppendLog::open(path)
}
