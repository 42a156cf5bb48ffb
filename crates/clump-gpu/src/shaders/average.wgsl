// `average` multi-contact (docs/theory.md T-34, clump-core multi_contact.rs):
// the force of each touching sphere pair between two bodies, and each
// touch between a body and a wall whose `multi_contact` is "average", is
// divided by the number of such touches. The counts are the CPU path's:
// step/pair_stage.rs `average_scales` (a pair touches when its centres are
// nearer than the radius sum) and step/wall_contacts.rs `count_touches`
// (every touch `WallShape::contacts` returns with margin 0, over the
// body's spheres, the faces of a box counted together). Integer counts,
// each computed by one invocation: no atomics, the same bits every run.

const PU_AVERAGE: u32 = 18u; // 1: simulation.multi_contact = "average"; after periodic.wgsl's PU_PERIODIC
const W_AVERAGE: u32 = 24u;  // wall row: 1 when the wall's multi_contact is "average" (walls.rs)

// Per owning entry (i, j > i) of the table: whether the pair touches this
// step, kept in the entry's `mirror` slot (only the entries (i, j < i) use
// theirs, for the owner of their pair). The test is pair_forces's.
@compute @workgroup_size(64)
fn pair_touch(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= pu[PU_NS]) { return; }
    let cap = pu[PU_CAP];
    let ri = sref[4u * i + 3u];
    for (var e = noff[i]; e < min(noff[i + 1u], cap); e++) {
        let j = nbr[e];
        if (j < i) { continue; }
        let dv = ld_sx(i) - partner_of(i, j);
        let rsum = ri + sref[4u * j + 3u];
        let gone = lost(sown[2u * i]) || lost(sown[2u * j]);
        mirror[e] = select(0u, 1u, dot3(dv, dv) < rsum * rsum && !gone);
    }
}

// The scale of owning entry e of sphere i: 1, or under "average" 1/n, n
// the touching pairs between i's body and its partner's. The spheres of a
// body are contiguous and bodies ascend, so the partner's body comes after
// i's and every pair of the two bodies is owned by a sphere of i's body.
fn pair_scale(i: u32, e: u32) -> f64 {
    if (pu[PU_AVERAGE] == 0u) { return 1.0lf; }
    let cap = pu[PU_CAP];
    let bi = sown[2u * i];
    let bj = sown[2u * nbr[e]];
    var n = 0u;
    for (var s = bfirst[bi]; s < bfirst[bi + 1u]; s++) {
        for (var q = noff[s]; q < min(noff[s + 1u], cap); q++) {
            let j = nbr[q];
            if (j > s && sown[2u * j] == bj && mirror[q] == 1u) { n++; }
        }
    }
    return 1.0lf / f64(max(n, 1u));
}

// The scale of sphere i's touches with wall w: 1, or for an "average" wall
// 1/n, n the touches of w with the spheres of i's body.
fn wall_scale(i: u32, w: u32) -> f64 {
    if (wall_f(w, W_AVERAGE) == 0.0lf) { return 1.0lf; }
    let b = sown[2u * i];
    var touch: array<Touch, 4>;
    var n = 0u;
    for (var s = bfirst[b]; s < bfirst[b + 1u]; s++) {
        n += wall_touches(w, ld_sx(s), sref[4u * s + 3u], &touch);
    }
    return 1.0lf / f64(max(n, 1u));
}
