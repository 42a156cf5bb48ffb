//! Periodic boxes on the device, host side: the box's edges and upper
//! corner and the periodic axes as the kernels' parameters
//! (`shaders/periodic.wgsl`), and the grid's check that the nearest image
//! of a near pair is the only one.

use clump_core::boundary::Domain;

/// Index of the box edges in the float parameters (periodic.wgsl PF_LEN),
/// followed by the upper corner (PF_HI).
const PF_LEN: usize = 9;
/// Index of the periodic axes in the integer parameters (periodic.wgsl
/// PU_PERIODIC), after common.wgsl's last (PU_NWF = 16).
pub(crate) const PU_PERIODIC: usize = 17;

/// Appends the box edges and upper corner to the float parameters `pf`
/// (which end at `PF_LEN`) and returns the periodic axes as bits 0-2
/// (periodic.wgsl PU_PERIODIC), or why the box cannot be binned. A
/// periodic axis needs at least three cells of the grid `dims` (cells of
/// edge `cell` m): the neighbour search then visits each cell once, and
/// the nearest image of a pair within a cell's edge is unique (the CPU
/// path's grid asks the same).
pub(crate) fn params(
    domain: &Domain,
    dims: [usize; 3],
    cell: f64,
    pf: &mut Vec<f64>,
) -> Result<u32, String> {
    debug_assert_eq!(pf.len(), PF_LEN);
    let (l, hi) = (domain.size(), domain.hi);
    pf.extend([l.x, l.y, l.z, hi.x, hi.y, hi.z]);
    let mut bits = 0;
    for a in 0..3 {
        if !domain.periodic[a] {
            continue;
        }
        if dims[a] < 3 {
            return Err(format!(
                "the periodic axis {} of the box is {} m long, shorter than three cells of {cell} m \
                 (the largest sphere diameter plus the skin)",
                ["x", "y", "z"][a],
                l[a]
            ));
        }
        bits |= 1 << a;
    }
    Ok(bits)
}

/// The nearest image of the separation `d` (world, m) along the periodic
/// axes of `domain`: how far apart two runs' copies of a body are when
/// the runs wrapped it into the box at different steps.
pub fn nearest_image(domain: &Domain, d: glam::DVec3) -> glam::DVec3 {
    d + domain.shift_vector(domain.minimum_image_shift(d))
}
