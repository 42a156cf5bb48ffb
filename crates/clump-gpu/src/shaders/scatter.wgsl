// The wall springs of an upload, sent sparse (walls.rs `sparse_slots`):
// `pout`, scratch until the first step's pair forces, holds their count
// and then per spring its slot and its 6 f64s (tangential, rolling); each
// invocation writes one slot of `whist` (zero elsewhere, as created).
@compute @workgroup_size(64)
fn whist_scatter(@builtin(global_invocation_id) gid: vec3<u32>) {
    let k = gid.x;
    if (k >= u32(pout[0])) { return; }
    let o = 1u + 7u * k;
    let slot = u32(pout[o]);
    for (var c = 0u; c < 6u; c++) {
        whist[6u * slot + c] = pout[o + 1u + c];
    }
}
