//! Spatial sorting of bodies in Morton (Z-curve) order.

use super::grid::CellGrid;
use glam::DVec3;

/// Spreads the low 21 bits of `v` so that there are two zero bits between
/// consecutive bits.
fn spread(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | (x << 32)) & 0x1f00000000ffff;
    x = (x | (x << 16)) & 0x1f0000ff0000ff;
    x = (x | (x << 8)) & 0x100f00f00f00f00f;
    x = (x | (x << 4)) & 0x10c30c30c30c30c3;
    x = (x | (x << 2)) & 0x1249249249249249;
    x
}

/// Morton code of a grid cell.
pub fn morton(c: [i64; 3]) -> u64 {
    spread(c[0] as u64) | (spread(c[1] as u64) << 1) | (spread(c[2] as u64) << 2)
}

/// Writes into `perm` the order of bodies (by storage index) sorted by the
/// Morton code of the cell of their (wrapped) centre of mass, ties broken by
/// global id, so the order is deterministic. `keep[b] = false` drops body `b`.
pub fn morton_order(
    grid: &CellGrid,
    wrapped: &[DVec3],
    ids: &[u64],
    keep: &[bool],
    perm: &mut Vec<u32>,
    keys: &mut Vec<(u64, u64, u32)>,
) {
    keys.clear();
    for (b, &x) in wrapped.iter().enumerate() {
        if keep[b] {
            keys.push((morton(grid.coords(x)), ids[b], b as u32));
        }
    }
    keys.sort_unstable();
    perm.clear();
    perm.extend(keys.iter().map(|k| k.2));
}
