// Bodies that leave the domain through a non-periodic side (clump-core
// boundary.rs `Domain::exit_cause`, lost.rs). At a table build, as the
// CPU path at its list rebuild (step/rebuild.rs), a body whose centre of
// mass lies beyond a non-periodic side is marked lost (bit 7 of its DOF
// word, the side x_lo, x_hi, y_lo, y_hi, z_lo, z_hi + 1 in bits 8-10, the
// first side beyond which it lies, x then y then z). From then on it stays
// where it is and touches nothing (the build leaves it out of the table);
// the host removes it at the next download with the CPU path's count
// (lost.rs). With the same skin the two paths build at the same steps
// (the same half-skin rule), so they remove a body at the same step.

const PU_LOST: u32 = 19u; // 1: a body was marked lost; after average.wgsl's PU_AVERAGE
const LOST_BIT: u32 = 128u;

fn lost(b: u32) -> bool {
    return (u32(bm[9u * b + 8u]) & LOST_BIT) != 0u;
}

// Per body, at a table build (dispatched with the build's sphere count):
// marks it lost when its centre of mass lies beyond a non-periodic side.
@compute @workgroup_size(64)
fn mark_lost(@builtin(global_invocation_id) gid: vec3<u32>) {
    let b = gid.x;
    if (b >= pu[PU_NB] || lost(b)) { return; }
    let x = ld_bx(b);
    var side = 6u;
    for (var a = 0u; a < 3u; a++) {
        if (side < 6u || is_periodic(a)) { continue; }
        if (x[a] < pf[PF_LO + a]) {
            side = 2u * a;
        } else if (x[a] > pf[PF_HI + a]) {
            side = 2u * a + 1u;
        }
    }
    if (side == 6u) { return; }
    let flags = u32(bm[9u * b + 8u]);
    bm[9u * b + 8u] = f64(flags | LOST_BIT | ((side + 1u) << 8u));
    // every invocation that marks one stores the same 1
    pu[PU_LOST] = 1u;
}
