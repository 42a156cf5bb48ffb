// Mesh walls: the touches of a sphere with a triangle mesh at its pose
// and their contact slots, the CPU path's rules in its operation order:
// crates/clump-core/src/wall/shape.rs `WallShape::contacts` (the centre
// into the mesh frame, the normals back), wall/mesh/contact.rs
// `TriMesh::sphere_contacts` (closest point and feature, wall/mesh/
// closest.rs; the edge and vertex region tests; the deepest 16 gathered,
// sorted deepest first, merged by normal, at most 4 kept) and
// step/wall_contacts.rs (a slot per contact, matched to the last step's
// by its stored normal, `match_mesh_slot`, `oct_encode`). The triangles
// near a sphere come from a grid in the mesh frame (mesh.rs).

@group(0) @binding(30) var<storage, read_write> mesh_u: array<u32>; // meshes' index arrays, then the wall slot keys (mesh.rs)

const M_KEYS: u32 = 0u;     // mesh_u: first slot key (one per (sphere, wall slot))
const M_F64: u32 = 2u;      // mesh_u: first f64 of the meshes in `walls`
const M_HEAD: u32 = 4u;
const MESH_ROW: u32 = 16u;  // per mesh: ntri, nv, then offsets in mesh_u of
const MR_TRI: u32 = 2u;     //   the triangles (3 vertex indices each),
const MR_VT_START: u32 = 3u; //  the first triangle at each vertex (nv + 1),
const MR_VT: u32 = 4u;      //   the triangles at each vertex,
const MR_CELL_START: u32 = 5u; // the first triangle of each grid cell (cells + 1),
const MR_CELL_TRI: u32 = 6u; //  the triangles of each cell,
const MR_TRI_CELL: u32 = 7u; //  each triangle's first cell (3);
const MR_DIMS: u32 = 8u;    //   cells per axis (3), then
const MR_F: u32 = 11u;      //   its f64s after M_F64: grid origin (3), cell, cos merge angle, vertices (3 nv), normals (3 ntri)
const W_MESH: u32 = 8u;     // wall row: the mesh index (position at 0, orientation x y z at 3, w at 6)
const MESH_KEEP: u32 = 4u;  // MAX_MESH_CONTACTS
const GATHER: u32 = 16u;
const REGION_TOL: f64 = 1e-9lf;

fn mrow(m: u32, k: u32) -> u32 { return mesh_u[M_HEAD + MESH_ROW * m + k]; }
// f64 k of mesh m's block
fn mf(m: u32, k: u32) -> f64 { return walls[mesh_u[M_F64] + mrow(m, MR_F) + k]; }
fn mf3(m: u32, k: u32) -> vec3<f64> { return vec3<f64>(mf(m, k), mf(m, k + 1u), mf(m, k + 2u)); }
fn mvert(m: u32, v: u32) -> vec3<f64> { return mf3(m, 5u + 3u * v); }
fn mnormal(m: u32, t: u32) -> vec3<f64> { return mf3(m, 5u + 3u * mrow(m, 1u) + 3u * t); }
fn mtri(m: u32, t: u32, k: u32) -> u32 { return mesh_u[mrow(m, MR_TRI) + 3u * t + k]; }

// glam DQuat * DVec3 (mul_vec3)
fn quat_rotate(q: vec4<f64>, v: vec3<f64>) -> vec3<f64> {
    let b = q.xyz;
    let b2 = dot3(b, b);
    return (v * (q.w * q.w - b2) + b * (dot3(v, b) * 2.0lf)) + cross3(b, v) * (q.w * 2.0lf);
}

// closest.rs closest_point_triangle: the point and its feature, kind 0
// face, 1 edge k (from local vertex k to k + 1), 2 vertex k
struct Closest { q: vec3<f64>, kind: u32, k: u32 }
fn closest_point_triangle(p: vec3<f64>, a: vec3<f64>, b: vec3<f64>, c: vec3<f64>) -> Closest {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = dot3(ab, ap);
    let d2 = dot3(ac, ap);
    if (d1 <= 0.0lf && d2 <= 0.0lf) { return Closest(a, 2u, 0u); }
    let bp = p - b;
    let d3 = dot3(ab, bp);
    let d4 = dot3(ac, bp);
    if (d3 >= 0.0lf && d4 <= d3) { return Closest(b, 2u, 1u); }
    let vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0lf && d1 >= 0.0lf && d3 <= 0.0lf) {
        let v = d1 / (d1 - d3);
        return Closest(a + ab * v, 1u, 0u);
    }
    let cp = p - c;
    let d5 = dot3(ab, cp);
    let d6 = dot3(ac, cp);
    if (d6 >= 0.0lf && d5 <= d6) { return Closest(c, 2u, 2u); }
    let vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0lf && d2 >= 0.0lf && d6 <= 0.0lf) {
        let w = d2 / (d2 - d6);
        return Closest(a + ac * w, 1u, 2u);
    }
    let va = d3 * d6 - d5 * d4;
    if (va <= 0.0lf && (d4 - d3) >= 0.0lf && (d5 - d6) >= 0.0lf) {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return Closest(b + (c - b) * w, 1u, 1u);
    }
    let denom = 1.0lf / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    return Closest((a + ab * v) + ac * w, 0u, 0u);
}

// MeshContact, mesh frame; rank 0 face, 1 edge, 2 vertex
struct MC { n: vec3<f64>, overlap: f64, tri: u32, rank: u32 }

// contact.rs `before`: deeper first, then face < edge < vertex, then lower triangle
fn before(a: MC, b: MC) -> bool {
    if (a.overlap != b.overlap) { return a.overlap > b.overlap; }
    if (a.rank != b.rank) { return a.rank < b.rank; }
    return a.tri < b.tri;
}

// The centre is not over a neighbour of the feature: (x - c).e <= tol |x - c| |e|
fn in_region(d: vec3<f64>, d2: f64, e: vec3<f64>) -> bool {
    return !(dot3(d, e) > (REGION_TOL * sqrt(d2)) * sqrt(dot3(e, e)));
}

struct Found { ok: bool, c: MC }
// Triangle t of mesh m as a contact of the sphere (xl, r), if it is one
fn mesh_candidate(m: u32, t: u32, xl: vec3<f64>, r: f64) -> Found {
    var no: Found;
    no.ok = false;
    let a = mvert(m, mtri(m, t, 0u));
    let cp = closest_point_triangle(xl, a, mvert(m, mtri(m, t, 1u)), mvert(m, mtri(m, t, 2u)));
    let d = xl - cp.q;
    let d2 = dot3(d, d);
    if (d2 >= r * r) { return no; }
    if (cp.kind == 0u) {
        let nrm = mnormal(m, t);
        let s = dot3(xl - a, nrm);
        if (s >= 0.0lf) { return Found(true, MC(nrm, r - s, t, 0u)); }
        return Found(true, MC(-nrm, r - (-s), t, 0u));
    }
    let vt0 = mrow(m, MR_VT_START);
    let vt = mrow(m, MR_VT);
    if (cp.kind == 1u) {
        let va = mtri(m, t, cp.k);
        let vb = mtri(m, t, (cp.k + 1u) % 3u);
        let pa = mvert(m, va);
        for (var e = mesh_u[vt0 + va]; e < mesh_u[vt0 + va + 1u]; e++) {
            let t2 = mesh_u[vt + e];
            if (t2 == t) { continue; }
            let o = vec3<u32>(mtri(m, t2, 0u), mtri(m, t2, 1u), mtri(m, t2, 2u));
            if (!any(o == vec3<u32>(vb))) { continue; }
            var w = va;
            for (var k = 0u; k < 3u; k++) {
                if (o[k] != va && o[k] != vb) { w = o[k]; break; }
            }
            if (!in_region(d, d2, mvert(m, w) - pa)) { return no; }
        }
    } else {
        let v = mtri(m, t, cp.k);
        let pv = mvert(m, v);
        for (var e = mesh_u[vt0 + v]; e < mesh_u[vt0 + v + 1u]; e++) {
            let t2 = mesh_u[vt + e];
            for (var k = 0u; k < 3u; k++) {
                let w = mtri(m, t2, k);
                if (w == v) { continue; }
                if (!in_region(d, d2, mvert(m, w) - pv)) { return no; }
            }
        }
    }
    let dist = sqrt(d2);
    if (dist == 0.0lf) { return no; }
    return Found(true, MC(d / dist, r - dist, t, cp.kind));
}

// The grid cell of coordinate x along axis k of mesh m, unclamped (f64)
fn mesh_cell(m: u32, x: f64, k: u32) -> f64 {
    return floor((x - mf(m, k)) / mf(m, 3u));
}

// TriMesh::sphere_contacts with margin 0: the contacts (mesh frame) of a
// sphere with centre xl (mesh frame) and radius r, deepest first, how many
struct Gathered { acc: array<MC, 16>, n: u32 }
fn mesh_gather(m: u32, xl: vec3<f64>, r: f64) -> Gathered {
    var g: Gathered;
    g.n = 0u;
    if (!(r > 0.0lf)) { return g; }
    var qlo: vec3<u32>;
    var qhi: vec3<u32>;
    for (var k = 0u; k < 3u; k++) {
        let top = f64(mrow(m, MR_DIMS + k) - 1u);
        let a = mesh_cell(m, xl[k] - r, k);
        let b = mesh_cell(m, xl[k] + r, k);
        if (b < 0.0lf || a > top) { return g; }
        qlo[k] = u32(clamp(a, 0.0lf, top));
        qhi[k] = u32(clamp(b, 0.0lf, top));
    }
    let nx = mrow(m, MR_DIMS);
    let ny = mrow(m, MR_DIMS + 1u);
    let cs = mrow(m, MR_CELL_START);
    let ct = mrow(m, MR_CELL_TRI);
    let tc = mrow(m, MR_TRI_CELL);
    for (var z = qlo.z; z <= qhi.z; z++) {
        for (var y = qlo.y; y <= qhi.y; y++) {
            for (var x = qlo.x; x <= qhi.x; x++) {
                let cell = (z * ny + y) * nx + x;
                for (var e = mesh_u[cs + cell]; e < mesh_u[cs + cell + 1u]; e++) {
                    let t = mesh_u[ct + e];
                    // once per triangle: from the first cell of the overlap
                    let first = max(vec3<u32>(mesh_u[tc + 3u * t], mesh_u[tc + 3u * t + 1u], mesh_u[tc + 3u * t + 2u]), qlo);
                    if (any(first != vec3<u32>(x, y, z))) { continue; }
                    let f = mesh_candidate(m, t, xl, r);
                    if (!f.ok) { continue; }
                    if (g.n < GATHER) {
                        g.acc[g.n] = f.c;
                        g.n++;
                    } else {
                        // full: replace the shallowest if this one is deeper
                        var wi = 0u;
                        for (var j = 1u; j < GATHER; j++) {
                            if (before(g.acc[wi], g.acc[j])) { wi = j; }
                        }
                        if (before(f.c, g.acc[wi])) { g.acc[wi] = f.c; }
                    }
                }
            }
        }
    }
    // insertion sort, deepest first
    for (var i = 1u; i < g.n; i++) {
        var j = i;
        while (j > 0u && before(g.acc[j], g.acc[j - 1u])) {
            let s = g.acc[j];
            g.acc[j] = g.acc[j - 1u];
            g.acc[j - 1u] = s;
            j--;
        }
    }
    return g;
}

// The touches of sphere (x, r) with mesh wall w (world frame normals),
// merged by normal, deepest first, at most MESH_KEEP; how many
fn mesh_touches(w: u32, x: vec3<f64>, r: f64, out: ptr<function, array<Touch, 4>>) -> u32 {
    let m = u32(wall_f(w, W_MESH));
    let pos = wall_v3(w, 0u);
    let q = vec4<f64>(wall_v3(w, 3u), wall_f(w, 6u));
    let identity = all(q == vec4<f64>(0.0lf, 0.0lf, 0.0lf, 1.0lf));
    var xl = x - pos;
    if (!identity) { xl = quat_rotate(vec4<f64>(-q.xyz, q.w), x - pos); }
    let g = mesh_gather(m, xl, r);
    let cos_merge = mf(m, 4u);
    var kept = 0u;
    for (var i = 0u; i < g.n; i++) {
        let c = g.acc[i];
        var dup = false;
        for (var j = 0u; j < kept; j++) {
            if (dot3((*out)[j].n, c.n) > cos_merge) { dup = true; }
        }
        if (dup) { continue; }
        (*out)[kept] = Touch(c.n, c.overlap, 0u);
        kept++;
        if (kept == MESH_KEEP) { break; }
    }
    if (!identity) {
        for (var j = 0u; j < kept; j++) { (*out)[j].n = quat_rotate(q, (*out)[j].n); }
    }
    return kept;
}

// Rust f64::signum: 1 for +0 and positive, -1 for -0 and negative
fn signum(a: f64) -> f64 {
    if (a > 0.0lf || (a == 0.0lf && 1.0lf / a > 0.0lf)) { return 1.0lf; }
    return -1.0lf;
}

// wall_contacts.rs oct_encode: a unit normal in 16 bits
fn oct_encode(n: vec3<f64>) -> u32 {
    let l1 = (abs(n.x) + abs(n.y)) + abs(n.z);
    if (!(l1 > 0.0lf)) { return 0u; }
    var u = n.x / l1;
    var v = n.y / l1;
    if (n.z < 0.0lf) {
        let pu_ = u;
        let pv = v;
        u = (1.0lf - abs(pv)) * signum(pu_);
        v = (1.0lf - abs(pu_)) * signum(pv);
    }
    let qu = u32(round_away((clamp(u, -1.0lf, 1.0lf) * 0.5lf + 0.5lf) * 255.0lf));
    let qv = u32(round_away((clamp(v, -1.0lf, 1.0lf) * 0.5lf + 0.5lf) * 255.0lf));
    return (qu << 8u) | qv;
}

// wall_contacts.rs oct_decode, normalized as glam does (times 1/length)
fn oct_decode(k: u32) -> vec3<f64> {
    let u = f64(k >> 8u) / 255.0lf * 2.0lf - 1.0lf;
    let v = f64(k & 255u) / 255.0lf * 2.0lf - 1.0lf;
    let z = (1.0lf - abs(u)) - abs(v);
    var p = vec3<f64>(u, v, z);
    if (z < 0.0lf) { p = vec3<f64>((1.0lf - abs(v)) * signum(u), (1.0lf - abs(u)) * signum(v), z); }
    return p * (1.0lf / sqrt(dot3(p, p)));
}

// Sphere i's contacts with mesh wall w: each touch continues the slot of
// the last step with the nearest stored normal within the match angle
// (match_mesh_slot), takes slot row + t, its key and springs; the slots
// after the touches are emptied.
fn mesh_wall_contact(i: u32, w: u32, fsum: ptr<function, vec3<f64>>, tsum: ptr<function, vec3<f64>>) {
    let x = ld_sx(i);
    let r = sref[4u * i + 3u];
    let row = i * pu[PU_NWF] + u32(wall_f(w, W_BASE));
    let kb = mesh_u[M_KEYS] + row;
    var touch: array<Touch, 4>;
    var k = 0u;
    // a lost body (lost.wgsl) touches nothing
    if (wall_f(w, W_ACTIVE) != 0.0lf && !lost(sown[2u * i])) { k = mesh_touches(w, x, r, &touch); }
    // the multi-contact scale (average.wgsl; 1 under "sum")
    var sc = 1.0lf;
    if (k > 0u) { sc = wall_scale(i, w); }
    var old_key: array<u32, 4>;
    var old_t: array<vec3<f64>, 4>;
    var old_r: array<vec3<f64>, 4>;
    for (var s = 0u; s < MESH_KEEP; s++) {
        old_key[s] = mesh_u[kb + s];
        old_t[s] = ld_whist(row + s);
        old_r[s] = ld_wroll(row + s);
    }
    var used = array<bool, 4>(false, false, false, false);
    let cos_min = walls[mesh_u[M_F64]];
    for (var t = 0u; t < k; t++) {
        let n = touch[t].n;
        var best = 4u;
        var best_c = 0.0lf;
        for (var s = 0u; s < MESH_KEEP; s++) {
            let key = old_key[s];
            if (key == 0u || used[s] || ((key - 1u) >> 16u) != w) { continue; }
            let c = dot3(oct_decode((key - 1u) & 65535u), n);
            if (c > cos_min && (best == 4u || c > best_c)) { best = s; best_c = c; }
        }
        var h0 = vec3<f64>(0.0lf);
        var r0 = vec3<f64>(0.0lf);
        if (best < 4u) { used[best] = true; h0 = old_t[best]; r0 = old_r[best]; }
        mesh_u[kb + t] = ((w << 16u) | oct_encode(n)) + 1u;
        let sp = touch_law(i, w, n, touch[t].overlap, h0, r0, sc, fsum, tsum);
        st_whist(row + t, sp.t);
        st_wroll(row + t, sp.r);
    }
    for (var s = k; s < MESH_KEEP; s++) {
        mesh_u[kb + s] = 0u;
        st_whist(row + s, vec3<f64>(0.0lf));
        st_wroll(row + s, vec3<f64>(0.0lf));
    }
}
