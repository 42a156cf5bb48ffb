//! Fields on grids across the boundary: the fluid velocity on a regular
//! grid of nodes and a void-fraction field on a grid of cells, both set by
//! the host (a CFD code's fields, world frame), and the void fraction
//! Clump computes on a grid of cells. Every argument is checked before
//! anything changes.

use crate::arrays::{in_slice, out_slice, world_err};
use crate::handle::{with_run, Fail};
use crate::*;
use clump_core::fluid::void::{VoidField, VoidGrid};
use clump_core::fluid::VelocityGrid;
use glam::DVec3;
use std::sync::Arc;

/// The 3 counts behind `n`, and their product.
fn counts_in(n: *const usize) -> Result<([usize; 3], usize), Fail> {
    if n.is_null() {
        return Err(Fail(CLUMP_ERR_NULL, "grid counts are NULL".into()));
    }
    // SAFETY: `n` points to 3 values (the caller's contract).
    let n = unsafe { [*n, *n.add(1), *n.add(2)] };
    if n.contains(&0) {
        return Err(Fail::value(format!(
            "grid counts must be at least 1 along each axis, got {n:?}"
        )));
    }
    let total = n
        .iter()
        .try_fold(1usize, |a, &b| a.checked_mul(b))
        .ok_or_else(|| Fail::value(format!("grid of {n:?} is too large")))?;
    Ok((n, total))
}

/// The grid of cells of corner `lo`, edges `cell` and counts `n`
/// (`periodic` 3 values or NULL), and its number of cells.
fn cells_in(
    lo: *const f64,
    cell: *const f64,
    n: *const usize,
    periodic: *const i32,
) -> Result<(VoidGrid, usize), Fail> {
    let lo = DVec3::from_slice(in_slice(lo, 3, 3, "grid corner")?);
    let cell = DVec3::from_slice(in_slice(cell, 3, 3, "grid cell")?);
    let (n, cells) = counts_in(n)?;
    if cell.min_element() <= 0.0 {
        return Err(Fail::value(format!(
            "grid cells must have positive edges, got {cell} m"
        )));
    }
    // SAFETY: a non-NULL `periodic` points to 3 values (the caller's contract).
    let periodic = match unsafe { periodic.as_ref() } {
        Some(_) => unsafe { [*periodic != 0, *periodic.add(1) != 0, *periodic.add(2) != 0] },
        None => [false; 3],
    };
    let grid = VoidGrid {
        lo,
        cell,
        n,
        periodic,
    };
    Ok((grid, cells))
}

/// Writes the void fraction of every cell of a grid of `n[0] × n[1] ×
/// n[2]` cells of edges `cell` (m) from the corner `lo` (m, world frame),
/// cell (i, j, k) at entry `i + n0 (j + n1 k)` (`len` = cells), from the
/// bodies as they are (theory T-69: each sphere divided among the cells by
/// a fixed lattice of points, overlaps within a body counted once).
/// `periodic` (3 values, or NULL for none): per axis, non-zero where the
/// solid beyond the grid wraps into it (a grid spanning a periodic axis).
///
/// # Safety
/// `sim` is a live handle; `lo`, `cell` hold 3 values, `n` 3, `periodic`
/// 3 or NULL, `out` `len`.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_void_fraction_grid(
    sim: *mut ClumpSim,
    lo: *const f64,
    cell: *const f64,
    n: *const usize,
    periodic: *const i32,
    out: *mut f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let (grid, cells) = cells_in(lo, cell, n, periodic)?;
        let o = out_slice(out, len, cells, "void fraction")?;
        let mut v = Vec::with_capacity(cells);
        r.runner.world_mut().void_fraction(&grid, &mut v);
        o.copy_from_slice(&v);
        Ok(())
    })
}

/// Sets the fluid velocity field on a regular grid of `n[0] × n[1] ×
/// n[2]` nodes from `origin` (m, world frame) at `spacing` (m; ignored
/// along an axis of one node): `velocity` holds 3 values (m/s, world
/// frame) per node, node (i, j, k) starting at `3 (i + n0 (j + n1 k))`
/// (`len` = 3 × nodes). Each step a body without a per-body velocity
/// (`clump_sim_set_fluid_velocities`) is given the trilinear interpolation
/// at its centre of mass (theory T-83; outside the grid, the value at the
/// nearest point of it). A NULL `velocity` removes the grid (the other
/// arguments are then not read). The scenario must have a `[fluid]`; the
/// grid is not kept in checkpoints (set it again after a resume).
///
/// # Safety
/// `sim` is a live handle; `origin`, `spacing` hold 3 values, `n` 3,
/// `velocity` `len` or NULL.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_fluid_velocity_grid(
    sim: *mut ClumpSim,
    origin: *const f64,
    spacing: *const f64,
    n: *const usize,
    velocity: *const f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let grid = if velocity.is_null() {
            None
        } else {
            let o = DVec3::from_slice(in_slice(origin, 3, 3, "grid origin")?);
            let h = DVec3::from_slice(in_slice(spacing, 3, 3, "grid spacing")?);
            let (n, nodes) = counts_in(n)?;
            let v = in_slice(velocity, len, 3 * nodes, "grid velocities")?;
            let u = v.chunks_exact(3).map(DVec3::from_slice).collect();
            let g = VelocityGrid::regular(o, h, n, u)
                .map_err(|e| Fail::value(format!("velocity grid: {e}")))?;
            Some(Arc::new(g))
        };
        r.runner
            .world_mut()
            .set_fluid_velocity_grid(grid)
            .map_err(world_err)
    })
}

/// Sets a void-fraction field the host computed, one value per cell of a
/// grid of `n[0] × n[1] × n[2]` cells of edges `cell` (m) from the corner
/// `lo` (m, world frame), cell (i, j, k) at entry `i + n0 (j + n1 k)`
/// (`len` = cells), each in (0, 1]. Each step a body without a per-body
/// void fraction (`clump_sim_set_void_fractions`) takes the value of the
/// cell holding its centre of mass (1 outside the grid), and the drag laws
/// read it (without a field or a per-body value they use 1). A NULL `eps`
/// removes the field (the other arguments are then not read). The
/// scenario must have a `[fluid]`; the field is not kept in checkpoints.
///
/// # Safety
/// `sim` is a live handle; `lo`, `cell` hold 3 values, `n` 3, `eps` `len` or NULL.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_void_fraction_field(
    sim: *mut ClumpSim,
    lo: *const f64,
    cell: *const f64,
    n: *const usize,
    eps: *const f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let field = if eps.is_null() {
            None
        } else {
            let (grid, cells) = cells_in(lo, cell, n, std::ptr::null())?;
            let e = in_slice(eps, len, cells, "void fractions")?;
            let f = VoidField::new(grid, e.to_vec())
                .map_err(|e| Fail::value(format!("void-fraction field: {e}")))?;
            Some(Arc::new(f))
        };
        r.runner
            .world_mut()
            .set_void_fraction_field(field)
            .map_err(world_err)
    })
}
