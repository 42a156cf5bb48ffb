//! Coarse-grained fields of a world split over MPI ranks, without the
//! whole world: every rank deposits the terms of the bodies it owns and of
//! the contacts it counts (its region's, when the world is whole at the
//! event; the rule of the statistics) in fixed point (T-74,
//! [`crate::post::fields_sum`]), the scales come from the ranks' extents
//! reduced over every rank, and the grids' integer sums go up a binomial
//! tree to rank 0, which writes one process's fields bit for bit.

use super::{RunError, Runner};
use crate::post::fields::{deposit, Fields};
use crate::post::fields_sum::{Extent, FixedGrid};
use crate::post::frame::Frame;
use crate::post::spec::FieldSeries;
use clump_core::world::World;
use std::collections::HashSet;

impl Runner {
    /// True when this run's fields are summed over the ranks (a world
    /// split over several ranks, with fields).
    pub(super) fn fields_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1) && self.out.fields.is_some()
    }
}

/// The ids of the bodies of this rank's piece ([`World::piece_mask`]) and
/// how many of them `frame` (captured before this boundary's insertions)
/// holds.
pub(super) fn piece_ids(world: &World, frame: &Frame) -> (HashSet<u64>, usize) {
    let mask = world.piece_mask().expect("a world split over ranks");
    let ids = &world.bodies().id;
    let keep: HashSet<u64> = (0..ids.len())
        .filter(|&i| mask[i])
        .map(|i| ids[i])
        .collect();
    let held = frame.bodies.iter().filter(|b| keep.contains(&b.id)).count();
    (keep, held)
}

fn bad(what: &str, from: usize) -> String {
    format!("rank {from} sent unreadable {what}")
}

/// Sums the fields of `frame` (this rank's capture) over the ranks and
/// writes them on rank 0 (a collective call: every rank makes it, also a
/// rank without bodies). Returns whether the fields were written: as in
/// one process, not when no rank holds a body.
pub(super) fn write_fields_in_pieces(
    world: &mut World,
    series: &mut FieldSeries,
    frame: &Frame,
) -> Result<bool, RunError> {
    let (keep, held) = piece_ids(world, frame);
    let grid = series.grid(&frame.domain);
    let mut extent = Extent::default();
    deposit(frame, &grid, Some(&keep), &mut |k, _, v| extent.see(k, v));
    let mut mine = extent.to_bytes();
    mine.extend((held as u64).to_le_bytes());
    let merge = |acc: &mut Vec<u8>, theirs: &[u8], from: usize| -> Result<(), String> {
        let split = |b: &[u8]| -> Option<(Extent, u64)> {
            let (e, n) = b.split_at_checked(b.len().checked_sub(8)?)?;
            Some((
                Extent::from_bytes(e)?,
                u64::from_le_bytes(n.try_into().ok()?),
            ))
        };
        let (mut a, na) = split(acc).ok_or_else(|| bad("field extents", from))?;
        let (b, nb) = split(theirs).ok_or_else(|| bad("field extents", from))?;
        a.merge(&b);
        *acc = a.to_bytes();
        acc.extend((na + nb).to_le_bytes());
        Ok(())
    };
    let all = world.all_reduce(mine, &merge).map_err(RunError::Runtime)?;
    let (e, n) = all.split_at(all.len() - 8);
    let extent = Extent::from_bytes(e).ok_or_else(|| RunError::Runtime(bad("field extents", 0)))?;
    if u64::from_le_bytes(n.try_into().expect("8 bytes")) == 0 {
        return Ok(false); // no bodies anywhere: one process writes no fields
    }
    let mut sums = FixedGrid::new(grid.len(), &extent);
    deposit(frame, &grid, Some(&keep), &mut |k, cell, v| {
        sums.add(k, cell, v)
    });
    let merge = |acc: &mut Vec<u8>, theirs: &[u8], from: usize| -> Result<(), String> {
        let mut a = FixedGrid::from_bytes(acc).ok_or_else(|| bad("field sums", from))?;
        let b = FixedGrid::from_bytes(theirs).ok_or_else(|| bad("field sums", from))?;
        a.merge(&b)
            .ok_or_else(|| bad("field sums (other scales)", from))?;
        *acc = a.to_bytes();
        Ok(())
    };
    let Some(total) = world
        .reduce_to_root(sums.to_bytes(), &merge)
        .map_err(RunError::Runtime)?
    else {
        return Ok(true);
    };
    let total =
        FixedGrid::from_bytes(&total).ok_or_else(|| RunError::Runtime(bad("field sums", 0)))?;
    series
        .add_fields(grid, Fields::from_fixed(&total), frame.step)
        .map_err(|e| RunError::Runtime(format!("cannot write the coarse-grained fields: {e}")))?;
    Ok(true)
}
