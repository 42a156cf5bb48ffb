//! Checkpoints of a world split over MPI ranks, written without gathering
//! it: each rank writes its piece (`<stem>.rank<r>of<n>.piece`, the state of
//! the bodies it owns, see [`clump_core::state_pieces::RankPiece`]) next to the
//! manifest `<stem>.ckpt` that rank 0 writes once every piece is on disk.
//! The manifest is an ordinary checkpoint whose world has no bodies and
//! which lists the pieces with their sizes and CRC-32s; reading it, each
//! rank (at any rank count) reads and checks the pieces that hold its
//! share of the world and keeps only that share, and one process reads
//! every piece ([`read_share`]). A missing piece, a piece of another
//! checkpoint or run, and a truncated or damaged piece are each a clear
//! error naming the file.

use super::error::rt;
use super::{RunError, Runner};
use crate::checkpoint::{decode_checkpoint, encode_checkpoint};
use clump_core::state::WorldState;
use clump_core::state_pieces::RankPiece;
use clump_core::state_share::PieceOutline;
use clump_core::world::World;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A piece as the manifest lists it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PieceRef {
    /// File name, in the manifest's folder.
    pub file: String,
    /// Its size, bytes.
    pub bytes: u64,
    /// CRC-32 (IEEE) of the whole file.
    pub crc32: u32,
}

/// What a piece file holds.
#[derive(Serialize, Deserialize)]
struct PieceFile {
    /// The run's id (rank 0's).
    run_id: Option<String>,
    /// The step of the checkpoint.
    step: u64,
    /// The rank that wrote it, and the number of ranks.
    rank: usize,
    ranks: usize,
    piece: RankPiece,
}

/// The piece file name of rank `r` of `n` for the manifest `manifest`.
fn piece_name(manifest: &Path, r: usize, n: usize) -> String {
    let stem = manifest
        .file_stem()
        .map_or_else(|| "checkpoint".into(), |s| s.to_string_lossy().into_owned());
    format!("{stem}.rank{r}of{n}.piece")
}

/// Rank 0's value of `mine` on every rank (a collective call).
pub(super) fn from_root(w: &mut World, mine: &str) -> String {
    let all = w.gather_from_ranks(mine.as_bytes());
    String::from_utf8_lossy(&all[0]).into_owned()
}

/// Every rank's report of writing its piece of `what` (`mine` here), in
/// rank order (a collective call). A rank that could not write its piece,
/// or whose report is unreadable, is an error on every rank.
pub(super) fn gather_reports<T: Serialize + for<'de> Deserialize<'de>>(
    w: &mut World,
    mine: &Result<T, String>,
    what: &str,
) -> Result<Vec<T>, RunError> {
    all_ok(w, mine).map_err(|(r, e)| {
        RunError::Runtime(format!(
            "cannot write {what}: rank {r} could not write its piece: {e}"
        ))
    })
}

impl Runner {
    /// Writes a checkpoint of a world split over ranks to rank 0's `path`
    /// (every rank calls it): each rank's piece, then rank 0's manifest.
    /// An error on any rank is an error on every rank, and no manifest is
    /// written (the last complete checkpoint stays the last one listed).
    pub(super) fn write_split_checkpoint(&mut self, path: &Path) -> Result<(), RunError> {
        let info = self
            .world
            .part_info()
            .expect("a split world is partitioned");
        let (me, n) = (info.rank, info.size);
        let dir = path.parent().filter(|p| !p.as_os_str().is_empty());
        let dir = dir.map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let dir = std::fs::canonicalize(&dir).unwrap_or(dir);
        let manifest = dir.join(path.file_name().unwrap_or_default());
        let manifest = PathBuf::from(from_root(&mut self.world, &manifest.to_string_lossy()));
        let run_id = from_root(&mut self.world, &self.out.run_id);
        let run_id = (!run_id.is_empty()).then_some(run_id);
        let step = self.world.step;
        let fingerprint = self.scenario.fingerprint();
        let name = piece_name(&manifest, me, n);
        let piece_path = manifest.with_file_name(&name);
        let mut global = None;
        let written = self
            .world
            .save_rank_piece()
            .map_err(|e| format!("cannot capture the state: {e}"))
            .and_then(|piece| {
                let file = PieceFile {
                    run_id: run_id.clone(),
                    step,
                    rank: me,
                    ranks: n,
                    piece,
                };
                let json = serde_json::to_string(&file).map_err(|e| e.to_string())?;
                let bytes = encode_checkpoint(&json, fingerprint).map_err(|e| e.to_string())?;
                crate::atomic::write_atomic(&piece_path, &bytes)
                    .map_err(|e| format!("{}: {e}", piece_path.display()))?;
                global = Some(file.piece.state.into_global());
                Ok(PieceRef {
                    file: name,
                    bytes: bytes.len() as u64,
                    crc32: crc32fast::hash(&bytes),
                })
            });
        let what = format!("the checkpoint of step {step}");
        let refs = gather_reports(&mut self.world, &written, &what)?;
        if me != 0 {
            return Ok(());
        }
        let Some(global) = global else {
            return Err(RunError::Runtime(format!(
                "cannot write the checkpoint of step {step}: rank 0 could not capture its state"
            )));
        };
        let mut ck = self.checkpoint_of(global, run_id);
        ck.pieces = Some(refs);
        let json = serde_json::to_string(&ck).map_err(rt("cannot encode the checkpoint"))?;
        crate::checkpoint::write_checkpoint(&manifest, &json, fingerprint)
            .map_err(rt("cannot write the checkpoint"))?;
        tracing::info!(
            step,
            ranks = n,
            "checkpoint written to {} with one piece per rank",
            manifest.display()
        );
        Ok(())
    }
}

/// The checkpoint in pieces a manifest describes, not read yet.
pub(super) struct Pending {
    /// The manifest's path.
    pub checkpoint: PathBuf,
    /// The run's id, as the manifest and every piece give it.
    pub run_id: Option<String>,
    /// The manifest's world: the global part, no bodies.
    pub global: WorldState,
    pub refs: Vec<PieceRef>,
    /// The scenario's fingerprint.
    pub fingerprint: u64,
}

/// Reads and checks piece `r` of the checkpoint `pending`.
fn read_piece(pending: &Pending, r: usize) -> Result<RankPiece, String> {
    let (checkpoint, refs) = (&pending.checkpoint, &pending.refs);
    let (p, n, step) = (&refs[r], refs.len(), pending.global.step);
    let bad = |m: String| format!("checkpoint {}: {m}", checkpoint.display());
    if p.file.contains(['/', '\\']) || p.file.is_empty() {
        return Err(bad(format!(
            "piece {r} has the name '{}', not a file name",
            p.file
        )));
    }
    let path = checkpoint.with_file_name(&p.file);
    let bytes = std::fs::read(&path).map_err(|e| {
        bad(format!(
            "piece {r} of {n}, {}, cannot be read ({e}): a checkpoint written on {n} MPI ranks is this manifest and one piece per rank, in the same folder",
            path.display()
        ))
    })?;
    let crc = crc32fast::hash(&bytes);
    if bytes.len() as u64 != p.bytes || crc != p.crc32 {
        return Err(bad(format!(
            "piece {r} of {n}, {}, has {} bytes (CRC-32 {crc:08x}) but the manifest lists {} bytes (CRC-32 {:08x}): the piece is truncated or damaged, or belongs to another checkpoint",
            path.display(),
            bytes.len(),
            p.bytes,
            p.crc32
        )));
    }
    let (json, fp): (String, u64) = decode_checkpoint(&bytes, &path).map_err(|e| e.to_string())?;
    drop(bytes);
    if fp != pending.fingerprint {
        return Err(bad(format!(
            "piece {} is of another scenario (fingerprint {fp:016x}, the manifest's {:016x})",
            path.display(),
            pending.fingerprint
        )));
    }
    let f: PieceFile = serde_json::from_str(&json)
        .map_err(|e| bad(format!("piece {} cannot be decoded: {e}", path.display())))?;
    if f.run_id != pending.run_id || f.step != step || f.rank != r || f.ranks != n {
        return Err(bad(format!(
            "piece {} is rank {} of {} of run {:?} at step {}, but the manifest lists rank {r} of {n} of run {:?} at step {}",
            path.display(),
            f.rank,
            f.ranks,
            f.run_id,
            f.step,
            pending.run_id,
            step
        )));
    }
    Ok(f.piece)
}

/// Every rank's `mine`, in rank order, when every rank's is `Ok` (a
/// collective call); otherwise the first rank's error, with its rank.
fn all_ok<T: Serialize + for<'de> Deserialize<'de>>(
    w: &mut World,
    mine: &Result<T, String>,
) -> Result<Vec<T>, (usize, String)> {
    let bytes = serde_json::to_vec(mine).unwrap_or_default();
    let all = w.gather_from_ranks(&bytes);
    let mut out = Vec::with_capacity(all.len());
    for (r, bytes) in all.iter().enumerate() {
        match serde_json::from_slice::<Result<T, String>>(bytes) {
            Ok(Ok(p)) => out.push(p),
            Ok(Err(e)) => return Err((r, e)),
            Err(e) => return Err((r, format!("its report is unreadable: {e}"))),
        }
    }
    Ok(out)
}

/// Reads this rank's share of the checkpoint `pending` into `w` (whose
/// state is the manifest's global part): on a partitioned world, every
/// rank first reads the outlines of the pieces `r ≡ rank (mod ranks)`, the
/// ranks share them and balance their regions on them, and each rank then
/// reads the pieces that come within the halo of its region and keeps its
/// owned bodies and ghosts ([`World::restore_rank_share`]); one process
/// reads every piece and keeps every body. Every rank calls it; an error
/// on any rank is an error on every rank. A rank holds one decoded piece
/// at a time besides its share.
pub(super) fn read_share(w: &mut World, pending: &Pending) -> Result<(), RunError> {
    let info = w.part_info();
    let (me, size) = info.map_or((0, 1), |i| (i.rank, i.size));
    let n = pending.refs.len();
    let on_ranks = |r: usize, e: String| match info {
        Some(_) => RunError::InputMessage(format!("rank {r} of {size}: {e}")),
        None => RunError::InputMessage(e),
    };
    let mut outlines = Vec::new();
    if info.is_some() {
        let mine: Result<Vec<(usize, PieceOutline)>, String> = (me..n)
            .step_by(size)
            .map(|r| {
                let p = read_piece(pending, r)?;
                let o = w.piece_outline(&p).map_err(|e| {
                    format!(
                        "checkpoint {}: piece {r}: {e}",
                        pending.checkpoint.display()
                    )
                })?;
                Ok((r, o))
            })
            .collect();
        let mut all: Vec<(usize, PieceOutline)> = all_ok(w, &mine)
            .map_err(|(r, e)| on_ranks(r, e))?
            .into_iter()
            .flatten()
            .collect();
        all.sort_by_key(|e| e.0);
        outlines = all.into_iter().map(|e| e.1).collect();
    }
    let mut reader = w.share_reader(&pending.global, &outlines);
    let bad = |e: String| format!("checkpoint {}: {e}", pending.checkpoint.display());
    let share = (|| {
        for r in 0..n {
            if outlines.get(r).is_some_and(|o| !reader.wants(o)) {
                continue;
            }
            let piece = read_piece(pending, r)?;
            reader.add(r, piece).map_err(bad)?;
        }
        reader.finish().map_err(bad)
    })();
    if info.is_some() {
        let status = share.as_ref().map(|_| ()).map_err(Clone::clone);
        all_ok(w, &status).map_err(|(r, e)| on_ranks(r, e))?;
    }
    let (state, order) = share.map_err(RunError::InputMessage)?;
    let restored = match info {
        Some(_) => w.restore_rank_share(state, order),
        None => w.restore_state(state),
    };
    restored.map_err(|e| {
        RunError::InputMessage(format!(
            "checkpoint {} does not fit its scenario: {e}",
            pending.checkpoint.display()
        ))
    })
}
