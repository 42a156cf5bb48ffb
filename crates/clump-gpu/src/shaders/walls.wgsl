// Sphere-wall contacts: planes, cylinders (inside or outside) and
// axis-aligned boxes (inside: each face a one-sided plane; outside: a solid
// obstacle), with the walls' prescribed motion. The touches are
// crates/clump-core/src/wall/shape.rs `WallShape::contacts`, the contact
// step/wall_contacts.rs (contact point, wall surface velocity, law, torque
// about the body's centre, rolling couple), in the same operation order.
// The host computes the walls' geometry for every step of a submission
// (walls.rs): row set PU_WSTEP of `walls` is this step's.

const WALL_ROW: u32 = 25u;  // f64s per wall (walls.rs WALL_ROW); W_AVERAGE is average.wgsl's
const W_KIND: u32 = 7u;     // 0 plane (point, normal), 1 cylinder (point, axis, radius), 2 box (lo, hi), 3 mesh (mesh.wgsl)
const W_INSIDE: u32 = 8u;
const W_MAT: u32 = 9u;
const W_BASE: u32 = 10u;    // the wall's first slot in a sphere's row
const W_VEL: u32 = 11u;
const W_OMEGA: u32 = 14u;
const W_CENTER: u32 = 17u;
const W_SURFACE: u32 = 20u;
const W_ACTIVE: u32 = 23u;  // 0: the wall touches nothing (a gate removed at a stage)

// the first f64 of wall w's row this step
fn wall_at(w: u32) -> u32 {
    return (pu[PU_WSTEP] * pu[PU_NW] + w) * WALL_ROW;
}
fn wall_v3(w: u32, k: u32) -> vec3<f64> {
    let o = wall_at(w) + k;
    return vec3<f64>(walls[o], walls[o + 1u], walls[o + 2u]);
}
fn wall_f(w: u32, k: u32) -> f64 {
    return walls[wall_at(w) + k];
}

struct Touch { n: vec3<f64>, overlap: f64, face: u32 }

// WallShape::contacts with margin 0: the touches of a sphere at x with
// radius r (at most MAX_TOUCHES), how many
fn wall_touches(w: u32, x: vec3<f64>, r: f64, out: ptr<function, array<Touch, 4>>) -> u32 {
    let kind = u32(wall_f(w, W_KIND));
    if (kind == 3u) { return mesh_touches(w, x, r, out); }
    let inside = wall_f(w, W_INSIDE) != 0.0lf;
    let a = wall_v3(w, 0u);
    let b = wall_v3(w, 3u);
    if (kind == 0u) {
        let overlap = r - dot3(x - a, b);
        if (overlap + 0.0lf > 0.0lf) { (*out)[0] = Touch(b, overlap, 0u); return 1u; }
        return 0u;
    }
    if (kind == 1u) {
        let radius = wall_f(w, 6u);
        let rel = x - a;
        let rho = rel - b * dot3(rel, b);
        let d = sqrt(dot3(rho, rho));
        var overlap: f64;
        var n = vec3<f64>(0.0lf);
        if (inside) {
            overlap = d + r - radius;
            if (d > 0.0lf) { n = -rho / d; }
        } else {
            overlap = radius + r - d;
            if (d > 0.0lf) { n = rho / d; }
        }
        if (overlap + 0.0lf > 0.0lf && any(n != vec3<f64>(0.0lf))) {
            (*out)[0] = Touch(n, overlap, 0u);
            return 1u;
        }
        return 0u;
    }
    if (inside) {
        var k = 0u;
        for (var ax = 0u; ax < 3u; ax++) {
            for (var side = 0u; side < 2u; side++) {
                var dist = x[ax] - a[ax];
                var sign = 1.0lf;
                if (side == 1u) { dist = b[ax] - x[ax]; sign = -1.0lf; }
                let overlap = r - dist;
                if (overlap + 0.0lf > 0.0lf && k < 4u) {
                    var n = vec3<f64>(0.0lf);
                    n[ax] = sign;
                    (*out)[k] = Touch(n, overlap, 2u * ax + side);
                    k++;
                }
            }
        }
        return k;
    }
    // glam DVec3::clamp: max then min
    let c = min(max(x, a), b);
    let d = x - c;
    let dl = sqrt(dot3(d, d));
    if (dl > 0.0lf) {
        let overlap = r - dl;
        if (overlap + 0.0lf > 0.0lf) { (*out)[0] = Touch(d / dl, overlap, 0u); return 1u; }
        return 0u;
    }
    // the centre inside the solid box: out through the nearest face
    // (the CPU starts from infinity: the first face sets all three)
    var best = x[0] - a[0];
    var best_ax = 0u;
    var best_sign = -1.0lf;
    for (var ax = 0u; ax < 3u; ax++) {
        let dlo = x[ax] - a[ax];
        let dhi = b[ax] - x[ax];
        if (dlo < best) { best = dlo; best_ax = ax; best_sign = -1.0lf; }
        if (dhi < best) { best = dhi; best_ax = ax; best_sign = 1.0lf; }
    }
    var n = vec3<f64>(0.0lf);
    n[best_ax] = best_sign;
    (*out)[0] = Touch(n, r + best, 0u);
    return 1u;
}

struct WallSprings { t: vec3<f64>, r: vec3<f64> }

// The law of sphere i's touch of wall w with unit normal n and overlap
// `overlap`, springs (t0, r0) before it: its force and its torque about
// the body's centre, times the multi-contact scale `sc` (average.wgsl
// `wall_scale`; 1 under "sum"), added to the sums; the springs after it.
fn touch_law(i: u32, w: u32, n: vec3<f64>, overlap: f64, t0: vec3<f64>, r0: vec3<f64>, sc: f64,
             fsum: ptr<function, vec3<f64>>, tsum: ptr<function, vec3<f64>>) -> WallSprings {
    let x = ld_sx(i);
    let r = sref[4u * i + 3u];
    let b = sown[2u * i];
    let com = ld_bx(b);
    let law = law_of(sown[2u * i + 1u], u32(wall_f(w, W_MAT)));
    let vw = wall_v3(w, W_VEL);
    let ww = wall_v3(w, W_OMEGA);
    let cw = wall_v3(w, W_CENTER);
    let sw = wall_v3(w, W_SURFACE);
    // geometry::contact_point, sphere::point_velocity,
    // Wall::surface_velocity_at less the surface velocity's normal part
    let xc = x - n * (r - 0.5lf * overlap);
    let lever = xc - com;
    let v_body = ld_bv(b) + cross3(ld_bw(b), lever);
    var v_wall = (vw + cross3(ww, xc - cw)) + sw;
    v_wall -= n * dot3(n, sw);
    let vrel = v_body - v_wall;
    let out = sliding(law, n, overlap, vrel, r, bm[9u * b], t0);
    // the load times the scale, the torque's sum scaled as a whole
    // (wall_contacts.rs flush)
    *fsum += out.force * sc;
    var roll = r0;
    if (law.roll != ROLL_NONE) {
        // the wall's rolling: w_rel = w_body - w_wall
        let rc = rolling_couple(law.roll, law.mu_r, law.eta_r, n, ld_bw(b) - ww, r, bm[9u * b],
                                out.f_n, out.kn, r0);
        roll = rc.spring;
        *tsum += (cross3(lever, out.force) + rc.couple) * sc;
    } else {
        *tsum += cross3(lever, out.force) * sc;
    }
    return WallSprings(out.xi, roll);
}

// Sphere i's contacts with wall w, added to its wall force and torque
// about its body's centre; each face's springs in slot (i, face), cleared
// where it does not touch. A mesh wall's are mesh.wgsl's.
fn wall_contact(i: u32, w: u32, fsum: ptr<function, vec3<f64>>, tsum: ptr<function, vec3<f64>>) {
    if (u32(wall_f(w, W_KIND)) == 3u) {
        mesh_wall_contact(i, w, fsum, tsum);
        return;
    }
    let x = ld_sx(i);
    let r = sref[4u * i + 3u];
    let row = i * pu[PU_NWF] + u32(wall_f(w, W_BASE));
    let faces = select(1u, 6u, u32(wall_f(w, W_KIND)) == 2u && wall_f(w, W_INSIDE) != 0.0lf);
    var touch: array<Touch, 4>;
    var k = 0u;
    // a lost body (lost.wgsl) touches nothing
    if (wall_f(w, W_ACTIVE) != 0.0lf && !lost(sown[2u * i])) { k = wall_touches(w, x, r, &touch); }
    var live = array<bool, 6>(false, false, false, false, false, false);
    // the multi-contact scale (average.wgsl; 1 under "sum")
    var sc = 1.0lf;
    if (k > 0u) { sc = wall_scale(i, w); }
    for (var t = 0u; t < k; t++) {
        let slot = row + touch[t].face;
        live[touch[t].face] = true;
        let sp = touch_law(i, w, touch[t].n, touch[t].overlap, ld_whist(slot), ld_wroll(slot), sc, fsum, tsum);
        st_whist(slot, sp.t);
        st_wroll(slot, sp.r);
    }
    for (var f = 0u; f < faces; f++) {
        if (!live[f]) {
            st_whist(row + f, vec3<f64>(0.0lf));
            st_wroll(row + f, vec3<f64>(0.0lf));
        }
    }
}

// One step on for the walls' geometry (the next row set).
@compute @workgroup_size(1)
fn wall_step() {
    pu[PU_WSTEP] += 1u;
}
