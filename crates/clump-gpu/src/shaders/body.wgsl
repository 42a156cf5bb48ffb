// Body kernels: the first half of the step (half kick, drift, LIGGGHTS'
// Richardson rotation, docs/theory.md T-15 and T-19), the spheres following
// their bodies (T-2), and the body gather with the final half kick.
// Formulas and operation order as crates/clump-core/src/step/kick.rs,
// first_half.rs and rotation/richardson_liggghts.rs (NO_SQUISH: rotation.wgsl).

// LAMMPS MathExtra::vecquat: (0, a) (x) b
fn vecquat(a: vec3<f64>, b: vec4<f64>) -> vec4<f64> {
    return vec4<f64>(b.w * a.x + a.y * b.z - a.z * b.y,
                     b.w * a.y + a.z * b.x - a.x * b.z,
                     b.w * a.z + a.x * b.y - a.y * b.x,
                     -a.x * b.x - a.y * b.y - a.z * b.z);
}
fn qnormalize(q: vec4<f64>) -> vec4<f64> {
    let norm = 1.0lf / sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return vec4<f64>(q.x * norm, q.y * norm, q.z * norm, q.w * norm);
}
fn inv_or_zero(t: f64, m: f64) -> f64 {
    if (m == 0.0lf) { return 0.0lf; }
    return t / m;
}
// LAMMPS MathExtra::mq_to_omega
fn mq_to_omega(l: vec3<f64>, q: vec4<f64>, m: vec3<f64>) -> vec3<f64> {
    let w2 = q.w * q.w; let i2 = q.x * q.x; let j2 = q.y * q.y; let k2 = q.z * q.z;
    let twoij = 2.0lf * q.x * q.y; let twoik = 2.0lf * q.x * q.z; let twojk = 2.0lf * q.y * q.z;
    let twoiw = 2.0lf * q.x * q.w; let twojw = 2.0lf * q.y * q.w; let twokw = 2.0lf * q.z * q.w;
    let r0 = vec3<f64>(w2 + i2 - j2 - k2, twoij - twokw, twojw + twoik);
    let r1 = vec3<f64>(twoij + twokw, w2 - i2 + j2 - k2, twojk - twoiw);
    let r2 = vec3<f64>(twoik - twojw, twojk + twoiw, w2 - i2 - j2 + k2);
    let wb = vec3<f64>(inv_or_zero(r0.x * l.x + r1.x * l.y + r2.x * l.z, m.x),
                       inv_or_zero(r0.y * l.x + r1.y * l.y + r2.y * l.z, m.y),
                       inv_or_zero(r0.z * l.x + r1.z * l.y + r2.z * l.z, m.z));
    return vec3<f64>(r0.x * wb.x + r0.y * wb.y + r0.z * wb.z,
                     r1.x * wb.x + r1.y * wb.y + r1.z * wb.z,
                     r2.x * wb.x + r2.y * wb.y + r2.z * wb.z);
}
// glam DQuat + DQuat and DQuat * f64 (componentwise)
fn drift_q(q: vec4<f64>, wq: vec4<f64>, h: f64) -> vec4<f64> {
    return q + wq * h;
}

struct QW { q: vec4<f64>, w: vec3<f64> }
// richardson_liggghts::drift_omega: the orientation and the world angular
// velocity of the first half sub-step, which moves the spheres this step
fn richardson_liggghts(q: vec4<f64>, l: vec3<f64>, inertia: vec3<f64>, dt: f64) -> QW {
    let dtq = 0.5lf * dt;
    var w = mq_to_omega(l, q, inertia);
    var wq = vecquat(w, q);
    let qfull = qnormalize(drift_q(q, wq, dtq));
    var qhalf = qnormalize(drift_q(q, wq, 0.5lf * dtq));
    w = mq_to_omega(l, qhalf, inertia);
    wq = vecquat(w, qhalf);
    qhalf = qnormalize(drift_q(qhalf, wq, 0.5lf * dtq));
    return QW(qnormalize(qhalf * 2.0lf - qfull), w);
}

// rotation::omega_world_rot: omega = R (1/I (R^T L)), c L for a spherical top
fn omega_world(rot: Mat3, l: vec3<f64>, inv: vec3<f64>) -> vec3<f64> {
    if (inv.x == inv.y && inv.y == inv.z) {
        return l * inv.x;
    }
    let lb = vec3<f64>(dot3(rot.x, l), dot3(rot.y, l), dot3(rot.z, l));
    return mat_mul(rot, lb * inv);
}

// A driven (or fixed) body's first half (dof.rs; step/first_half.rs, a
// body before its start step, and driven_turn): no kick; x += v dt; it
// turns at its prescribed world angular velocity, q <- exp(w dt) q, and
// its L is the one that w gives at the new orientation, R (I (R^T w)).
fn driven_first_half(i: u32, dt: f64) {
    let w = ld_bw(i);
    var q = ldq(i);
    if (any(w != vec3<f64>(0.0lf))) {
        q = renormalize(qmul(quat_from_rotation_vector(w * dt), q));
    }
    let rot = mat_from_quat(q);
    let inertia = vec3<f64>(bm[9u * i + 1u], bm[9u * i + 2u], bm[9u * i + 3u]);
    let wb = vec3<f64>(dot3(rot.x, w), dot3(rot.y, w), dot3(rot.z, w));
    st_bl(i, mat_mul(rot, inertia * wb));
    st_bx(i, ld_bx(i) + ld_bv(i) * dt);
    bq[4u * i] = q.x; bq[4u * i + 1u] = q.y; bq[4u * i + 2u] = q.z; bq[4u * i + 3u] = q.w;
}

@compute @workgroup_size(64)
fn first_half(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= pu[PU_NB]) { return; }
    // a lost body stays where it left (lost.wgsl)
    if (lost(i)) { return; }
    let dt = pf[PF_DT];
    if (driven(i)) {
        driven_first_half(i, dt);
        return;
    }
    let dtfm = bm[9u * i + 7u];
    let dtt = 0.5lf * dt;
    let f = vec3<f64>(bft[6u * i], bft[6u * i + 1u], bft[6u * i + 2u]);
    let m = vec3<f64>(bft[6u * i + 3u], bft[6u * i + 4u], bft[6u * i + 5u]);
    // kick::HalfKick::apply: a locked axis keeps its value
    let fl = dof_flags(i);
    let v = select(ld_bv(i), ld_bv(i) + dtfm * f, fl[0]);
    let l = select(ld_bl(i), ld_bl(i) + dtt * m, fl[1]);
    // the drift, wrapped into a periodic box (periodic.wgsl)
    let x = wrap_point(ld_bx(i) + v * dt);
    let inertia = vec3<f64>(bm[9u * i + 1u], bm[9u * i + 2u], bm[9u * i + 3u]);
    var qn: vec4<f64>;
    var w: vec3<f64>;
    if (pu[PU_ROT] == 0u) {
        let qw = richardson_liggghts(ldq(i), l, inertia, dt);
        qn = qw.q;
        w = qw.w;
    } else {
        let inv = vec3<f64>(bm[9u * i + 4u], bm[9u * i + 5u], bm[9u * i + 6u]);
        if (pu[PU_ROT] == 2u) {
            qn = richardson_drift(ldq(i), l, inertia, inv, dt);
        } else {
            qn = no_squish_drift(ldq(i), l, inertia, dt);
        }
        w = omega_world(mat_from_quat(qn), l, inv);
    }
    st_bv(i, v);
    st_bl(i, l);
    st_bx(i, x);
    st_bw(i, w);
    bq[4u * i] = qn.x; bq[4u * i + 1u] = qn.y; bq[4u * i + 2u] = qn.z; bq[4u * i + 3u] = qn.w;
}

// Sphere centres r = r_cm + R(q) r_b, their lever arms R(q) r_b, whether
// one left half the skin, and their cell keys (linear index of the cell of the grid, clamped to the grid:
// the boundary cells reach to infinity, so no touching pair is missed).
@compute @workgroup_size(64)
fn spheres(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = gid.x;
    let ns = pu[PU_NS];
    if (s >= pu[PU_NPOW2]) { return; }
    if (s >= ns) {
        keys[s] = 0xffffffffu;
        idx[s] = 0xffffffffu;
        return;
    }
    let b = sown[2u * s];
    let rot = mat_from_quat(ldq(b));
    let off = vec3<f64>(sref[4u * s], sref[4u * s + 1u], sref[4u * s + 2u]);
    let arm = mat_mul(rot, off);
    let x = ld_bx(b) + arm;
    st_sarm(s, arm);
    st_sx(s, x);
    keys[s] = cell_key(cell_of(x));
    idx[s] = s;
    // the skin check (the CPU's rule): the table holds every pair within
    // the radius sum plus the skin at its build, so it is good until a
    // sphere has moved half the skin. Every invocation that finds one
    // stores the same 1: the flag does not depend on which does.
    let d = moved_since_build(s, x);
    let h = 0.5lf * pf[PF_SKIN];
    if (dot3(d, d) > h * h) { pu[PU_STALE] = 1u; }
}

fn cell_of(x: vec3<f64>) -> vec3<i32> {
    let lo = vec3<f64>(pf[PF_LO], pf[PF_LO + 1u], pf[PF_LO + 2u]);
    // a periodic axis bins the sphere's image in the box (periodic.wgsl)
    let c = (wrap_point(x) - lo) / pf[PF_CELL];
    let n = vec3<i32>(i32(pu[PU_GRID]), i32(pu[PU_GRID + 1u]), i32(pu[PU_GRID + 2u]));
    // clamp in f64 first: a far-away sphere must not overflow the i32
    let cc = clamp(floor(c), vec3<f64>(0.0lf), vec3<f64>(n - vec3<i32>(1)));
    return vec3<i32>(cc);
}
fn cell_key(c: vec3<i32>) -> u32 {
    return u32((c.z * i32(pu[PU_GRID + 1u]) + c.y) * i32(pu[PU_GRID]) + c.x);
}

// Per body, its spheres' loads summed in slot order: the pair force and
// torque, gravity m g, then the wall force and torque (the CPU gather's
// order of stages, step/gather.rs).
fn body_load(b: u32) -> array<vec3<f64>, 2> {
    var pfor = vec3<f64>(0.0lf);
    var ptor = vec3<f64>(0.0lf);
    var wfor = vec3<f64>(0.0lf);
    var wtor = vec3<f64>(0.0lf);
    for (var s = bfirst[b]; s < bfirst[b + 1u]; s++) {
        pfor += vec3<f64>(sft[12u * s], sft[12u * s + 1u], sft[12u * s + 2u]);
        ptor += vec3<f64>(sft[12u * s + 3u], sft[12u * s + 4u], sft[12u * s + 5u]);
        wfor += vec3<f64>(sft[12u * s + 6u], sft[12u * s + 7u], sft[12u * s + 8u]);
        wtor += vec3<f64>(sft[12u * s + 9u], sft[12u * s + 10u], sft[12u * s + 11u]);
    }
    let g = vec3<f64>(pf[PF_G], pf[PF_G + 1u], pf[PF_G + 2u]);
    let f = (bm[9u * b] * g + pfor) + wfor;
    let m = ptor + wtor;
    return array<vec3<f64>, 2>(f, m);
}

fn store_load(b: u32, f: vec3<f64>, m: vec3<f64>) {
    bft[6u * b] = f.x; bft[6u * b + 1u] = f.y; bft[6u * b + 2u] = f.z;
    bft[6u * b + 3u] = m.x; bft[6u * b + 4u] = m.y; bft[6u * b + 5u] = m.z;
}

// The load only (World::prepare: the forces of the initial state).
@compute @workgroup_size(64)
fn body_gather(@builtin(global_invocation_id) gid: vec3<u32>) {
    let b = gid.x;
    if (b >= pu[PU_NB]) { return; }
    let fm = body_load(b);
    store_load(b, fm[0], fm[1]);
}

// The load and the second half kick: v += F dt/(2m), L += M dt/2, omega
// from L (rotation::omega_world_inv).
@compute @workgroup_size(64)
fn gather_kick(@builtin(global_invocation_id) gid: vec3<u32>) {
    let b = gid.x;
    if (b >= pu[PU_NB] || lost(b)) { return; }
    let fm = body_load(b);
    store_load(b, fm[0], fm[1]);
    // a driven body keeps its prescribed v and w (its load is only summed)
    if (driven(b)) { return; }
    let dtt = 0.5lf * pf[PF_DT];
    let fl = dof_flags(b);
    let v = select(ld_bv(b), ld_bv(b) + bm[9u * b + 7u] * fm[0], fl[0]);
    let l = select(ld_bl(b), ld_bl(b) + dtt * fm[1], fl[1]);
    st_bv(b, v);
    st_bl(b, l);
    let inv = vec3<f64>(bm[9u * b + 4u], bm[9u * b + 5u], bm[9u * b + 6u]);
    // rotation::omega_world_inv
    st_bw(b, omega_world(mat_from_quat(ldq(b)), l, inv));
}
