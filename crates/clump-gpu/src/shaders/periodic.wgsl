// Periodic boxes (docs/theory.md T-22, the minimum image): bodies' centres of mass wrap into
// [lo, hi) along a periodic axis, and a pair's partner is the nearest image
// of its sphere. The formulas and operation order are the CPU path's:
// boundary.rs `Domain::wrap`, neighbor/body_search.rs `Image::candidate`
// and step/pair_kernel `partner_position`. The device wraps a body in the
// step it leaves the box (the CPU path at its next list rebuild) and takes
// each pair's image anew every step (the CPU path keeps the image of its
// last rebuild); a near pair's nearest image is the same either way,
// because a periodic axis spans at least three cells of the largest
// diameter plus the skin.

const PF_LEN: u32 = 9u;      // box edges hi - lo, 3
const PF_HI: u32 = 12u;      // upper corner, 3
const PU_PERIODIC: u32 = 17u; // periodic axes, bits 0-2 (x, y, z); after common.wgsl's PU_NWF

fn is_periodic(a: u32) -> bool {
    return (pu[PU_PERIODIC] & (1u << a)) != 0u;
}
fn box_len() -> vec3<f64> {
    return vec3<f64>(pf[PF_LEN], pf[PF_LEN + 1u], pf[PF_LEN + 2u]);
}

// Domain::wrap: a point into the box along the periodic axes
fn wrap_point(p: vec3<f64>) -> vec3<f64> {
    var x = p;
    if (pu[PU_PERIODIC] == 0u) { return x; }
    let l = box_len();
    for (var a = 0u; a < 3u; a++) {
        if (!is_periodic(a)) { continue; }
        let lo = pf[PF_LO + a];
        let f = floor((x[a] - lo) / l[a]);
        if (f != 0.0lf) { x[a] -= f * l[a]; }
        // round-off may put x exactly at hi
        if (x[a] >= pf[PF_HI + a]) { x[a] = lo; }
    }
    return x;
}

// Rust's f64::round: halves away from zero
fn round_away(x: f64) -> f64 {
    let t = trunc(x);
    if (abs(x - t) >= 0.5lf) { return t + sign(x); }
    return t;
}

// Image::candidate's shift s (per axis, an integer in f64) of sphere j as
// seen from sphere i: x_i - x_j + s L is the nearest image's separation
fn image_shift(i: u32, j: u32) -> vec3<f64> {
    var s = vec3<f64>(0.0lf);
    if (pu[PU_PERIODIC] == 0u) { return s; }
    let d = ld_sx(i) - ld_sx(j);
    let l = box_len();
    for (var a = 0u; a < 3u; a++) {
        if (is_periodic(a) && abs(d[a]) > 0.5lf * l[a]) {
            s[a] = -round_away(d[a] / l[a]);
        }
    }
    return s;
}

// pair_kernel `partner_position`: sphere j's centre as seen from sphere i
// across the periodic faces (world, m): x_j - s L
fn partner_of(i: u32, j: u32) -> vec3<f64> {
    let s = image_shift(i, j);
    if (all(s == vec3<f64>(0.0lf))) { return ld_sx(j); }
    return ld_sx(j) - s * box_len();
}

// The displacement d of a sphere since the last table build, the nearest
// image along the periodic axes (its body may have wrapped since)
fn moved_since_build(s: u32, x: vec3<f64>) -> vec3<f64> {
    var d = x - ld_sx0(s);
    if (pu[PU_PERIODIC] == 0u) { return d; }
    let l = box_len();
    for (var a = 0u; a < 3u; a++) {
        if (is_periodic(a) && abs(d[a]) > 0.5lf * l[a]) {
            d[a] -= round_away(d[a] / l[a]) * l[a];
        }
    }
    return d;
}

// A neighbour cell's coordinate along axis a, wrapped on a periodic axis;
// -1 outside the grid on another
fn cell_wrap(c: i32, a: u32, n: i32) -> i32 {
    if (is_periodic(a)) { return (c + n) % n; }
    if (c < 0 || c >= n) { return -1; }
    return c;
}
