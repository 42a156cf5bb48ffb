//! A classical fourth-order Runge–Kutta integrator for small ODE systems,
//! used for reference solutions that are independent of the engine, and a
//! least-squares slope.

/// One RK4 step of `y' = f(y)` (autonomous) with step `h`.
pub fn rk4_step<const N: usize>(
    y: [f64; N],
    h: f64,
    f: &impl Fn([f64; N]) -> [f64; N],
) -> [f64; N] {
    let add = |a: [f64; N], b: [f64; N], s: f64| {
        let mut r = a;
        for i in 0..N {
            r[i] += s * b[i];
        }
        r
    };
    let k1 = f(y);
    let k2 = f(add(y, k1, 0.5 * h));
    let k3 = f(add(y, k2, 0.5 * h));
    let k4 = f(add(y, k3, h));
    let mut out = y;
    for i in 0..N {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}

/// A normal impact against a nonlinear spring–dashpot in non-dimensional
/// form, `x'' = −F`, `F = x^p + c·x^q·x'` for `x > 0`, starting at `x = 0`,
/// `x' = 1`; with `clamped` the force cannot pull, `F ← max(F, 0)` (a
/// non-cohesive contact). Returns the restitution (rebound speed at `x = 0`;
/// 0 when the motion creeps back without crossing) and the trajectory
/// `(t, x, force)` sampled every `every` steps.
pub fn impact_restitution(
    p: f64,
    q: f64,
    c: f64,
    clamped: bool,
    h: f64,
    every: usize,
) -> (f64, Vec<[f64; 3]>) {
    let force = |y: [f64; 2]| {
        let x = y[0].max(0.0);
        let f = x.powf(p) + c * x.powf(q) * y[1];
        if clamped {
            f.max(0.0)
        } else {
            f
        }
    };
    let f = |y: [f64; 2]| [y[1], -force(y)];
    let mut y = [0.0, 1.0];
    let mut samples = Vec::new();
    let max_steps = (200.0 / h) as usize;
    for n in 0..max_steps {
        let next = rk4_step(y, h, &f);
        if n % every.max(1) == 0 {
            samples.push([n as f64 * h, y[0], force(y)]);
        }
        if next[0] <= 0.0 && next[1] < 0.0 {
            let s = y[0] / (y[0] - next[0]);
            return (-(y[1] + s * (next[1] - y[1])), samples);
        }
        y = next;
    }
    (0.0, samples)
}

/// The damping constant `c` of [`impact_restitution`] (clamped or not) that
/// gives restitution `e ∈ (0, 1)`, by bisection on `[0, 10]`.
pub fn damping_for_restitution(p: f64, q: f64, e: f64, clamped: bool, h: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if impact_restitution(p, q, mid, clamped, h, usize::MAX).0 > e {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Least-squares slope of `(x, y)` points (NaN for fewer than two distinct x).
pub fn slope(p: &[(f64, f64)]) -> f64 {
    line_fit(p).slope
}

/// A least-squares straight line `y = intercept + slope · x` with the
/// variances and covariance of its two coefficients estimated from the
/// residual scatter (n − 2 degrees of freedom; NaN for n ≤ 2).
#[derive(Debug, Clone, Copy)]
pub struct Line {
    /// Intercept, in y units.
    pub intercept: f64,
    /// Slope, in y units per x unit.
    pub slope: f64,
    /// Variance of the intercept.
    pub var_intercept: f64,
    /// Variance of the slope.
    pub var_slope: f64,
    /// Covariance of intercept and slope.
    pub cov: f64,
}

/// Fits a [`Line`] to `(x, y)` points.
pub fn line_fit(p: &[(f64, f64)]) -> Line {
    let n = p.len() as f64;
    let mx = p.iter().map(|a| a.0).sum::<f64>() / n;
    let my = p.iter().map(|a| a.1).sum::<f64>() / n;
    let sxy: f64 = p.iter().map(|a| (a.0 - mx) * (a.1 - my)).sum();
    let sxx: f64 = p.iter().map(|a| (a.0 - mx).powi(2)).sum();
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let s2 = p
        .iter()
        .map(|a| (a.1 - intercept - slope * a.0).powi(2))
        .sum::<f64>()
        / (n - 2.0);
    let var_slope = s2 / sxx;
    Line {
        intercept,
        slope,
        var_intercept: s2 * (1.0 / n + mx * mx / sxx),
        var_slope,
        cov: -mx * var_slope,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undamped_impact_is_elastic_and_damping_inverts() {
        let (e, _) = impact_restitution(1.5, 0.25, 0.0, false, 1e-3, usize::MAX);
        assert!((e - 1.0).abs() < 1e-6, "{e}");
        // linear spring with a linear dashpot: e = exp(−ζπ/√(1−ζ²)), c = 2ζ
        let zeta: f64 = 0.2;
        let (e_lin, _) = impact_restitution(1.0, 0.0, 2.0 * zeta, false, 1e-4, usize::MAX);
        let exact = (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp();
        assert!((e_lin - exact).abs() < 1e-4, "{e_lin} vs {exact}");
        // clamped: the force ends where x'' = 0; with ζ = cos α it ends at
        // ω_d t = 2α and e = exp(−2ζα/√(1−ζ²)) (by hand, Schwager & Pöschel)
        let (e_cl, _) = impact_restitution(1.0, 0.0, 2.0 * zeta, true, 1e-4, usize::MAX);
        let exact_cl = (-2.0 * zeta * zeta.acos() / (1.0 - zeta * zeta).sqrt()).exp();
        assert!((e_cl - exact_cl).abs() < 1e-4, "{e_cl} vs {exact_cl}");
        assert!((slope(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]) - 2.0).abs() < 1e-12);
        // by hand: x̄ = 1.5, ȳ = 4, Sxx = 5, Sxy = 9.8, so slope 1.96 and
        // intercept 1.06; residuals ±0.04, ∓0.12 give s² = 0.032/2 = 0.016,
        // var(slope) = s²/Sxx = 0.0032, var(intercept) = s²(1/4 + x̄²/Sxx) = 0.0112
        let l = line_fit(&[(0.0, 1.1), (1.0, 2.9), (2.0, 5.1), (3.0, 6.9)]);
        assert!((l.slope - 1.96).abs() < 1e-12 && (l.intercept - 1.06).abs() < 1e-12);
        assert!((l.var_slope - 0.0032).abs() < 1e-12);
        assert!((l.var_intercept - 0.0112).abs() < 1e-12);
        assert!((l.cov + 1.5 * 0.0032).abs() < 1e-12);
        for clamped in [false, true] {
            let c = damping_for_restitution(1.5, 0.25, 0.5, clamped, 1e-3);
            let e = impact_restitution(1.5, 0.25, c, clamped, 1e-3, usize::MAX).0;
            assert!((e - 0.5).abs() < 1e-6);
        }
    }
}
