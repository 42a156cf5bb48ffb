// Rolling resistance (docs/theory.md, crates/clump-core/src/contact/
// rolling.rs and ContactModel::rolling_couple): the couple on i of a
// contact with unit normal n (j to i) and relative angular velocity
// w_rel = w_i - w_j (world), the same equations in the same operation
// order. CDT: -mu_r R* |F_n| w_r / |w_r|; EPSD: the spring M_r rotated into
// the contact plane, less k_r dt w_r, k_r = 2.25 k_n (mu_r R*)^2, limited to
// mu_r R* |F_n|, with the viscous part -C_r w_r while it holds.

const ROLL_NONE: u32 = 0u;
const ROLL_CDT: u32 = 1u;
const ROLL_EPSD: u32 = 2u;

struct Rolling { couple: vec3<f64>, spring: vec3<f64> }

// rolling::rolling_omega: w - (w . n) n
fn rolling_omega(w: vec3<f64>, n: vec3<f64>) -> vec3<f64> {
    return w - dot3(w, n) * n;
}

// ContactModel::rolling_couple for a law with rolling kind `kind`,
// coefficient `mu_r` and viscous ratio `eta_r`; R* `radius`, m* `mass`,
// the normal force `f_n` (after the tensile clamp) and the normal
// stiffness `kn` of the sliding law, the EPSD spring `m_r`
fn rolling_couple(kind: u32, mu_r: f64, eta_r: f64, n: vec3<f64>, w_rel: vec3<f64>,
                  radius: f64, mass: f64, f_n: f64, kn: f64, m_r: vec3<f64>) -> Rolling {
    let abs_fn = abs(f_n);
    if (kind == ROLL_CDT) {
        // rolling::cdt
        let wr = rolling_omega(w_rel, n);
        let m_max = mu_r * radius * abs_fn;
        let w2 = dot3(wr, wr);
        var c = vec3<f64>(0.0lf);
        if (w2 > 1e-12lf * 1e-12lf) { c = wr * (-m_max / sqrt(w2)); }
        return Rolling(c, m_r);
    }
    if (kind == ROLL_EPSD) {
        let mr = mu_r * radius;
        let kr = 2.25lf * kn * mr * mr;
        let cr = eta_r * 2.0lf * sqrt(1.4lf * mass * radius * radius * kr);
        let wr = rolling_omega(w_rel, n);
        let m_max = mr * abs_fn;
        // rolling::epsd
        var m = rotate_into_plane(m_r, n) - kr * pf[PF_DT] * wr;
        let m2 = dot3(m, m);
        if (m2 >= m_max * m_max) {
            // fully mobilised: plastic rolling, no dashpot
            if (m2 > 0.0lf) { m = m * (m_max / sqrt(m2)); } else { m = vec3<f64>(0.0lf); }
            return Rolling(m, m);
        }
        return Rolling(m - cr * wr, m);
    }
    return Rolling(vec3<f64>(0.0lf), m_r);
}
