// Contact forces: Hertz-Mindlin with the tangential history spring and the
// Coulomb limit, the CPU path's SlidingLaw (crates/clump-core/src/contact/
// model.rs, normal.rs, damping.rs, tangential.rs; docs/theory.md), the same
// equations in the same operation order; then the per-sphere gather (the
// wall contacts are walls.wgsl's).

// A row of `laws` (device_world.rs LAW_ROW): the SlidingLaw's constants,
// then the rolling law (rolling.wgsl ROLL_*), mu_r and eta_r.
const LAW_ROW: u32 = 11u;
struct Law { hertz: bool, fn_floor: f64, kn: f64, kt: f64, gn: f64, gt: f64, friction: f64,
             roll: u32, mu_r: f64, eta_r: f64 }
fn law_of(mi: u32, mj: u32) -> Law {
    let r = LAW_ROW * (mi * pu[PU_NMAT] + mj);
    return Law(laws[r] != 0.0lf, laws[r + 1u], laws[r + 2u], laws[r + 3u], laws[r + 4u], laws[r + 5u], laws[r + 7u],
               u32(laws[r + 8u]), laws[r + 9u], laws[r + 10u]);
}

// tangential::rotate_into_plane
fn rotate_into_plane(v: vec3<f64>, n: vec3<f64>) -> vec3<f64> {
    let l0 = dot3(v, v);
    let p = v - dot3(v, n) * n;
    let lp = dot3(p, p);
    var scale = 0.0lf;
    if (lp > 1e-12lf * l0) { scale = sqrt(l0 / lp); }
    return p * scale;
}

struct Sliding { force: vec3<f64>, xi: vec3<f64>, f_n: f64, kn: f64 }
// SlidingLaw::evaluate_as::<true>: the force on i (N, world) and the new
// spring (m, world) of a contact with unit normal n (j to i), overlap d,
// contact-point relative velocity vrel, R*, m*, spring xi.
fn sliding(law: Law, n: vec3<f64>, d: f64, vrel: vec3<f64>, radius: f64, mass: f64, xi: vec3<f64>) -> Sliding {
    let dt = pf[PF_DT];
    var s = 1.0lf;
    if (law.hertz) { s = sqrt(radius * d); }
    let kn = law.kn * s;
    let kt = law.kt * s;
    let gamma_n = law.gn * sqrt(s * mass);
    let gamma_t = law.gt * sqrt(s * mass);
    let vn = dot3(vrel, n);
    let vt = vrel - vn * n;
    let f_el = kn * d;
    var f_n = f_el - gamma_n * vn;
    if (f_n < law.fn_floor) { f_n = law.fn_floor; }
    let f_max = law.friction * abs(f_n);
    // tangential::history_spring_as::<true>
    let sp = rotate_into_plane(xi, n) + vt * dt;
    let f = -kt * sp - gamma_t * vt;
    let f2 = dot3(f, f);
    var xi_new = sp;
    var f_t = f;
    if (f2 > f_max * f_max) {
        let fl = f * (f_max / sqrt(f2));
        xi_new = fl * (-1.0lf / kt);
        f_t = fl;
    }
    if (kt <= 0.0lf) {
        xi_new = vec3<f64>(0.0lf);
        f_t = vec3<f64>(0.0lf);
    }
    return Sliding(f_n * n + f_t, xi_new, f_n, kn);
}

// Each entry (i, j > i): the pair's force on i and the torques about the
// two bodies' centres (step/pair_kernel/lanes.rs: kinematics, store).
@compute @workgroup_size(64)
fn pair_forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= pu[PU_NS]) { return; }
    let cap = pu[PU_CAP];
    let bi = sown[2u * i];
    let ri = sref[4u * i + 3u];
    for (var e = noff[i]; e < min(noff[i + 1u], cap); e++) {
        let j = nbr[e];
        if (j < i) { continue; }
        let bj = sown[2u * j];
        let rj = sref[4u * j + 3u];
        // j's nearest image across a periodic face (periodic.wgsl)
        let dv = ld_sx(i) - partner_of(i, j);
        // the pair kernel's test (step/pair_kernel): a pair of the table
        // that does not touch exerts nothing and loses its spring; nor
        // does one with a lost body (lost.wgsl)
        let rsum = ri + rj;
        if (!(dot3(dv, dv) < rsum * rsum) || lost(bi) || lost(bj)) {
            st_hist(e, vec3<f64>(0.0lf));
            st_roll(e, vec3<f64>(0.0lf));
            for (var c = 0u; c < 9u; c++) { pout[9u * e + c] = 0.0lf; }
            continue;
        }
        // contact::geometry::sphere_pair
        let dist = sqrt(dot3(dv, dv));
        let nrm = dv * (1.0lf / dist);
        let overlap = (ri + rj) - dist;
        let ai = ri - 0.5lf * overlap;
        let aj = rj - 0.5lf * overlap;
        let lever_i = ld_sarm(i) - nrm * ai;
        let lever_j = ld_sarm(j) + nrm * aj;
        let vrel = (ld_bv(bi) + cross3(ld_bw(bi), lever_i)) - (ld_bv(bj) + cross3(ld_bw(bj), lever_j));
        let mi = bm[9u * bi];
        let mj = bm[9u * bj];
        let law = law_of(sown[2u * i + 1u], sown[2u * j + 1u]);
        let r_star = ri * rj / (ri + rj);
        let m_star = mi * mj / (mi + mj);
        let out = sliding(law, nrm, overlap, vrel, r_star, m_star, ld_hist(e));
        st_hist(e, out.xi);
        // the multi-contact scale (average.wgsl; 1 under "sum")
        let sc = pair_scale(i, e);
        let f = out.force * sc;
        var ti = cross3(lever_i, f);
        var tj = cross3(f, lever_j);
        if (law.roll != ROLL_NONE) {
            // the rolling couple, on i and opposite on j (pair_kernel
            // scalar_laws: after the torques of the force)
            let rc = rolling_couple(law.roll, law.mu_r, law.eta_r, nrm, ld_bw(bi) - ld_bw(bj),
                                    r_star, m_star, out.f_n, out.kn, ld_roll(e));
            st_roll(e, rc.spring);
            ti = ti + rc.couple * sc;
            tj = tj - rc.couple * sc;
        }
        for (var c = 0u; c < 3u; c++) {
            pout[9u * e + c] = f[c];
            pout[9u * e + 3u + c] = ti[c];
            pout[9u * e + 6u + c] = tj[c];
        }
    }
}

// Per sphere, in the order of its entries (sorted by neighbour): the pair
// forces and torques on its body, then its wall contacts in wall order.
// Each output is one invocation's: no atomics, the same bits every run.
@compute @workgroup_size(64)
fn sphere_gather(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= pu[PU_NS]) { return; }
    let cap = pu[PU_CAP];
    var f = vec3<f64>(0.0lf);
    var t = vec3<f64>(0.0lf);
    for (var e = noff[i]; e < min(noff[i + 1u], cap); e++) {
        if (nbr[e] > i) {
            f += vec3<f64>(pout[9u * e], pout[9u * e + 1u], pout[9u * e + 2u]);
            t += vec3<f64>(pout[9u * e + 3u], pout[9u * e + 4u], pout[9u * e + 5u]);
        } else {
            let m = mirror[e];
            f -= vec3<f64>(pout[9u * m], pout[9u * m + 1u], pout[9u * m + 2u]);
            t += vec3<f64>(pout[9u * m + 6u], pout[9u * m + 7u], pout[9u * m + 8u]);
        }
    }
    var wf = vec3<f64>(0.0lf);
    var wt = vec3<f64>(0.0lf);
    for (var w = 0u; w < pu[PU_NW]; w++) {
        wall_contact(i, w, &wf, &wt);
    }
    for (var c = 0u; c < 3u; c++) {
        sft[12u * i + c] = f[c];
        sft[12u * i + 3u + c] = t[c];
        sft[12u * i + 6u + c] = wf[c];
        sft[12u * i + 9u + c] = wt[c];
    }
}
