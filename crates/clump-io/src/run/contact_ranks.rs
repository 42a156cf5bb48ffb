//! Contact frames of a world split over MPI ranks, as LIGGGHTS and LAMMPS
//! users know them from per-processor dumps: every rank writes the
//! contacts it counts as one piece, `contacts_<step>.rank<r>of<n>.vtp`,
//! and rank 0 writes `contacts_<step>.pvtp` (parallel PolyData, listed in
//! `contacts.pvd`) that ParaView and vtk read as one data set
//! ([`crate::vtk_pieces`]). A rank counts the contacts in the rows of the
//! bodies it owns (its region's, when the world is whole at the event):
//! the rule of the statistics, so every contact is in one piece.
//!
//! The body network `network_<step>.csv` is one file, one process's bytes:
//! each rank makes the edges of its counted contacts (the sphere contacts
//! of two bodies all lie in the rows of the one stored first, so an edge
//! is made whole by one rank, summed in one process's order) and sends
//! only those lines to rank 0, which writes them ordered by body ids, as
//! one process does. The world is not gathered.

use super::pieces::{from_root, gather_reports};
use super::{RunError, Runner};
use crate::post::frame::Frame;
use crate::post::network::{csv_line, edges, CSV_HEADER};
use crate::vtk_contacts::{contacts_vtp, ContactSeries};
use crate::vtk_pieces::piece_name;
use clump_core::world::World;
use std::path::PathBuf;

impl Runner {
    /// True when this run's contact frames are written in pieces (a world
    /// split over several ranks, with contact frames).
    pub(super) fn contacts_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1) && self.out.contacts.is_some()
    }
}

/// The contacts of `frame` (the rank's capture) that this rank counts:
/// those whose sphere `i` belongs to a body of the rank's piece (`mine`,
/// [`World::piece_mask`]); the bodies stay (the partners' positions give
/// the network's branch vectors).
fn counted(mine: &std::collections::HashSet<u64>, frame: &Frame) -> Frame {
    let mut f = frame.clone();
    if let Some(cs) = f.contacts.as_mut() {
        cs.retain(|c| mine.contains(&c.body_i));
    }
    f
}

/// Writes the contact frame of `frame` in pieces (a collective call: every
/// rank makes it, with its own series and capture, also a rank without
/// bodies; rank 0's series is the run's). Returns whether the frame was
/// written: as in one process, not when no rank holds a body. An error on
/// any rank is an error on every rank.
pub(super) fn write_contacts_in_pieces(
    world: &mut World,
    series: &mut ContactSeries,
    frame: &Frame,
) -> Result<bool, RunError> {
    let info = world.part_info().expect("a world split over ranks");
    let (me, n, step) = (info.rank, info.size, frame.step);
    let dir = std::fs::canonicalize(series.dir()).unwrap_or_else(|_| series.dir().to_path_buf());
    let dir = PathBuf::from(from_root(world, &dir.to_string_lossy()));
    let (keep, owned) = super::fields_ranks::piece_ids(world, frame);
    let mine = counted(&keep, frame);
    let held = mine.contacts.as_ref().map_or(0, Vec::len);
    let piece = contacts_vtp(&mine, series.wall_names());
    let path = dir.join(piece_name("contacts", step, me, n, "vtp"));
    // rank 0's piece declares the arrays, so it is written even when empty
    let written: Result<[usize; 2], String> = if held > 0 || me == 0 {
        crate::atomic::write_atomic(&path, &piece)
            .map(|_| [held, owned])
            .map_err(|e| format!("{}: {e}", path.display()))
    } else {
        Ok([0, owned])
    };
    let what = format!("the contact frame of step {step}");
    let reports = gather_reports(world, &written, &what)?;
    if reports.iter().all(|r| r[1] == 0) {
        // no bodies anywhere: one process writes no contact frame
        if me == 0 {
            let _ = std::fs::remove_file(&path);
        }
        return Ok(false);
    }
    let lines: Vec<(u64, u64, String)> = edges(&mine)
        .iter()
        .map(|e| (e.body_i, e.body_j, csv_line(e)))
        .collect();
    let bytes = postcard::to_stdvec(&lines)
        .map_err(|e| RunError::Runtime(format!("cannot encode network rows: {e}")))?;
    let Some(all) = world.gather_to_root(bytes) else {
        return Ok(true);
    };
    let mut rows: Vec<(u64, u64, String)> = Vec::new();
    for (rank, b) in all.iter().enumerate() {
        let r: Vec<(u64, u64, String)> = postcard::from_bytes(b).map_err(|e| {
            RunError::Runtime(format!("rank {rank} sent unreadable network rows: {e}"))
        })?;
        rows.extend(r);
    }
    rows.sort_by_key(|r| (r.0, r.1));
    if rows
        .windows(2)
        .any(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1))
    {
        return Err(RunError::Runtime(format!(
            "{what}: a pair of bodies has contacts counted on two ranks"
        )));
    }
    let network: String = std::iter::once(CSV_HEADER)
        .chain(rows.iter().map(|r| r.2.as_str()))
        .collect();
    let mut listed: Vec<usize> = (0..n).filter(|&r| reports[r][0] > 0).collect();
    if listed.is_empty() {
        listed.push(0);
    }
    series
        .write_parallel_frame(frame.time, step, &piece, &listed, n, &network)
        .map_err(|e| RunError::Runtime(format!("cannot write contact output: {e}")))?;
    Ok(true)
}
