//! VTK frames of a world split over MPI ranks, in pieces
//! ([`crate::vtk_pieces`]): every rank writes its bodies' piece into rank
//! 0's folder, then rank 0 writes the `.pvtp` (`.pvtu`) collections, the walls and
//! the `.pvd` entries. The world need not be whole: a split world's piece
//! holds the rank's owned bodies, a whole one's the bodies in the rank's
//! region ([`World::piece_mask`]).

use super::pieces::{from_root, gather_reports};
use super::{RunError, Runner};
use crate::vtk::{bodies_vtp_of, spheres_vtp_of, BodyCounts, VtkSeries};
use crate::vtk_pieces::piece_name;
use clump_core::world::World;
use std::path::{Path, PathBuf};

impl Runner {
    /// True when this run's VTK frames are written in pieces: a world
    /// split over several ranks, with VTK frames (`.vtp` or `.vtu`).
    pub(super) fn vtk_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1) && self.out.vtk.is_some()
    }
}

/// Writes the frame at `label` in pieces (a collective call: every rank
/// makes it, with its own series; rank 0's is the run's). An error on any
/// rank is an error on every rank.
pub(super) fn write_frame_in_pieces(
    world: &mut World,
    vtk: &mut VtkSeries,
    label: u64,
    counts: Option<&BodyCounts>,
) -> Result<(), RunError> {
    let info = world.part_info().expect("a world split over ranks");
    let (me, n) = (info.rank, info.size);
    let dir = std::fs::canonicalize(vtk.dir()).unwrap_or_else(|_| vtk.dir().to_path_buf());
    let dir = PathBuf::from(from_root(world, &dir.to_string_lossy()));
    let mask = world.piece_mask().expect("a world split over ranks");
    let mine = mask.iter().filter(|&&k| k).count();
    let format = vtk.format();
    let ext = format.extension();
    let spheres = format.encode(spheres_vtp_of(world, Some(&mask)));
    let bodies = format.encode(bodies_vtp_of(world, counts, Some(&mask)));
    let write = |kind: &str, bytes: &[u8]| {
        let path = dir.join(piece_name(kind, label, me, n, ext));
        crate::atomic::write_atomic(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))
    };
    // rank 0's piece declares the arrays, so it is written even when empty
    let written: Result<usize, String> = if mine > 0 || me == 0 {
        write("spheres", &spheres)
            .and_then(|_| write("bodies", &bodies))
            .map(|_| mine)
    } else {
        Ok(0)
    };
    let what = format!("the VTK frame of step {label}");
    let held = gather_reports(world, &written, &what)?;
    if me != 0 {
        return Ok(());
    }
    let mut listed: Vec<usize> = (0..n).filter(|&r| held[r] > 0).collect();
    if listed.is_empty() {
        listed.push(0);
    }
    let total = held.iter().sum();
    vtk.write_parallel_frame(world, label, [&spheres, &bodies], &listed, n, total)
        .map_err(|e| RunError::Runtime(format!("cannot write VTK output: {e}")))?;
    if !vtk.started() {
        // no bodies yet anywhere: the series has not started
        remove_own_pieces(&dir, label, n, ext);
    }
    Ok(())
}

/// Removes rank 0's pieces of the frame at `label`.
fn remove_own_pieces(dir: &Path, label: u64, n: usize, ext: &str) {
    for kind in ["spheres", "bodies"] {
        let _ = std::fs::remove_file(dir.join(piece_name(kind, label, 0, n, ext)));
    }
}
