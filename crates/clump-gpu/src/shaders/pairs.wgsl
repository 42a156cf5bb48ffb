// Binning and the pair table: a bitonic sort of (cell key, sphere) pairs,
// the cells' slot ranges, the neighbour count per sphere, an exclusive
// scan of the counts, and the table filled sorted by neighbour with each
// pair's tangential history carried from the last step's table.
// Every output is written by one invocation and integer-valued or copied:
// the table is the same whatever the scheduling.

// The indirect dispatch sizes of the table build (rebuild_args): all zero
// unless a sphere left half the skin; then clears the flag.
@group(1) @binding(0) var<storage, read_write> args: array<u32>;
@compute @workgroup_size(1)
fn rebuild_args() {
    let go = pu[PU_STALE] != 0u;
    let sizes = array<u32, 5>(pu[PU_NPOW2], arrayLength(&cells) / 2u, pu[PU_NS], 1u, pu[PU_CAP]);
    for (var k = 0u; k < 5u; k++) {
        var groups = (sizes[k] + WG - 1u) / WG;
        if (k == 3u) { groups = 1u; }
        if (!go) { groups = 0u; }
        args[3u * k] = groups;
        args[3u * k + 1u] = 1u;
        args[3u * k + 2u] = 1u;
    }
    if (go) { pu[PU_BUILDS] = pu[PU_BUILDS] + 1u; }
    pu[PU_STALE] = 0u;
}

// The current table becomes the old one, whose springs the build carries.
@compute @workgroup_size(64)
fn table_save(@builtin(global_invocation_id) gid: vec3<u32>) {
    let e = gid.x;
    if (e <= pu[PU_NS]) { old_off[e] = noff[e]; }
    if (e >= pu[PU_CAP]) { return; }
    old_nbr[e] = nbr[e];
    st_old_springs(e, ld_hist(e), ld_roll(e));
}

// One compare-exchange step (k, j in PU_SORT_K, PU_SORT_J) of the bitonic
// sort of (keys, idx) by key, then by sphere (a total order: stable bits).
@compute @workgroup_size(64)
fn sort_step(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    let n = pu[PU_NPOW2];
    if (i >= n) { return; }
    let k = pu[PU_SORT_K];
    let j = pu[PU_SORT_J];
    let l = i ^ j;
    if (l <= i) { return; }
    let ki = keys[i]; let kl = keys[l];
    let ii = idx[i]; let il = idx[l];
    let greater = ki > kl || (ki == kl && ii > il);
    let up = (i & k) == 0u;
    if (greater == up) {
        keys[i] = kl; keys[l] = ki;
        idx[i] = il; idx[l] = ii;
    }
}

// The next (k, j) of the bitonic network; k = 0 starts it.
@compute @workgroup_size(1)
fn sort_next() {
    var k = pu[PU_SORT_K];
    var j = pu[PU_SORT_J];
    if (k == 0u) {
        k = 2u; j = 1u;
    } else if (j > 1u) {
        j = j >> 1u;
    } else {
        k = k << 1u; j = k >> 1u;
    }
    pu[PU_SORT_K] = k;
    pu[PU_SORT_J] = j;
}

@compute @workgroup_size(64)
fn sort_reset(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (gid.x == 0u) { pu[PU_SORT_K] = 0u; pu[PU_SORT_J] = 0u; }
}

@compute @workgroup_size(64)
fn cells_clear(@builtin(global_invocation_id) gid: vec3<u32>) {
    let c = gid.x;
    if (c >= arrayLength(&cells) / 2u) { return; }
    cells[2u * c] = 0u;
    cells[2u * c + 1u] = 0u;
}

@compute @workgroup_size(64)
fn cells_bounds(@builtin(global_invocation_id) gid: vec3<u32>) {
    let k = gid.x;
    let ns = pu[PU_NS];
    if (k >= ns) { return; }
    let key = keys[k];
    if (k == 0u || keys[k - 1u] != key) { cells[2u * key] = k; }
    if (k == ns - 1u || keys[k + 1u] != key) { cells[2u * key + 1u] = k + 1u; }
}

// Whether spheres i and j (of different bodies) are nearer than their
// radius sum plus the skin: a pair of the table.
fn near(i: u32, j: u32) -> bool {
    if (sown[2u * i] == sown[2u * j] || lost(sown[2u * i]) || lost(sown[2u * j])) { return false; }
    let d = ld_sx(i) - partner_of(i, j);
    let cut = sref[4u * i + 3u] + sref[4u * j + 3u] + pf[PF_SKIN];
    return dot3(d, d) < cut * cut;
}

// Sphere i's near neighbours, in the order of the 27 cells and their
// sorted slots, at most MAXN (PU_OVERFLOW bit 1 set beyond).
fn neighbours(i: u32, out: ptr<function, array<u32, 32>>) -> u32 {
    let c = cell_of(ld_sx(i));
    let n = vec3<i32>(i32(pu[PU_GRID]), i32(pu[PU_GRID + 1u]), i32(pu[PU_GRID + 2u]));
    var count = 0u;
    for (var dz = -1; dz <= 1; dz++) {
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                // across a periodic face: the cell on the other side
                let cc = vec3<i32>(cell_wrap(c.x + dx, 0u, n.x), cell_wrap(c.y + dy, 1u, n.y),
                                   cell_wrap(c.z + dz, 2u, n.z));
                if (any(cc < vec3<i32>(0))) { continue; }
                let key = cell_key(cc);
                for (var k = cells[2u * key]; k < cells[2u * key + 1u]; k++) {
                    let j = idx[k];
                    if (j != i && near(i, j)) {
                        if (count < MAXN) { (*out)[count] = j; }
                        count++;
                    }
                }
            }
        }
    }
    if (count > MAXN) { pu[PU_OVERFLOW] = pu[PU_OVERFLOW] | 1u; }
    return min(count, MAXN);
}

@compute @workgroup_size(64)
fn pairs_count(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    let ns = pu[PU_NS];
    if (i >= ns) { return; }
    var list: array<u32, 32>;
    noff[i] = neighbours(i, &list);
}

// Exclusive scan of noff[0..ns] in place, the total in noff[ns]: one
// workgroup, each invocation a contiguous run, the runs' sums scanned by
// invocation 0 (integers: exact in any order).
var<workgroup> partial: array<u32, 256>;
@compute @workgroup_size(256)
fn pairs_scan(@builtin(local_invocation_id) lid: vec3<u32>) {
    let ns = pu[PU_NS];
    let t = lid.x;
    let per = (ns + 255u) / 256u;
    let a = min(t * per, ns);
    let b = min(a + per, ns);
    var sum = 0u;
    for (var s = a; s < b; s++) { sum += noff[s]; }
    partial[t] = sum;
    workgroupBarrier();
    if (t == 0u) {
        var run = 0u;
        for (var r = 0u; r < 256u; r++) {
            let p = partial[r];
            partial[r] = run;
            run += p;
        }
        noff[ns] = run;
        if (run > pu[PU_CAP]) { pu[PU_OVERFLOW] = pu[PU_OVERFLOW] | 2u; }
    }
    workgroupBarrier();
    var run = partial[t];
    for (var s = a; s < b; s++) {
        let c = noff[s];
        noff[s] = run;
        run += c;
    }
}

// Sphere i's entries, sorted by neighbour; an entry (i, j > i) owns the
// pair and takes its spring from the last table's entry (i, j), or zero
// for a new pair (a contact that ended lost its spring, as on the CPU).
// The sphere's position is kept for the skin check.
@compute @workgroup_size(64)
fn pairs_fill(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    let ns = pu[PU_NS];
    if (i >= ns) { return; }
    var list: array<u32, 32>;
    let n = neighbours(i, &list);
    for (var a = 1u; a < n; a++) {
        let v = list[a];
        var b = a;
        while (b > 0u && list[b - 1u] > v) {
            list[b] = list[b - 1u];
            b--;
        }
        list[b] = v;
    }
    st_sx0(i, ld_sx(i));
    let o = noff[i];
    let cap = pu[PU_CAP];
    for (var a = 0u; a < n; a++) {
        let e = o + a;
        if (e >= cap) { return; }
        let j = list[a];
        nbr[e] = j;
        var h = vec3<f64>(0.0lf);
        var r = vec3<f64>(0.0lf);
        if (j > i) {
            for (var q = old_off[i]; q < old_off[i + 1u]; q++) {
                if (old_nbr[q] == j) { h = ld_old_hist(q); r = ld_old_roll(q); break; }
            }
        }
        st_hist(e, h);
        st_roll(e, r);
    }
}

// For each entry (i, j < i), the entry (j, i) that owns the pair.
@compute @workgroup_size(64)
fn pairs_mirror(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= pu[PU_NS]) { return; }
    let cap = pu[PU_CAP];
    for (var e = noff[i]; e < min(noff[i + 1u], cap); e++) {
        let j = nbr[e];
        if (j < i) {
            for (var q = noff[j]; q < min(noff[j + 1u], cap); q++) {
                if (nbr[q] == i) { mirror[e] = q; break; }
            }
        }
    }
}
