//! Coarse-graining kernels in one dimension and their integrals over a
//! grid cell (docs/theory.md, "Coarse-grained fields").
//!
//! Both are normalised on the line and have standard deviation `w` (the
//! `width`): the Gaussian `exp(−x²/2w²)` cut at `|x| = 3w` and rescaled so
//! it integrates to one; Lucy's polynomial `(1 + 3u)(1 − u)³`, `u = |x|/c`,
//! with the cut-off `c = w √(21/2)` (its variance is `2c²/21`). The grid
//! kernel is the product of the 1D kernels of the grid's axes; a field is
//! the average over each cell, `∫_cell φ / |cell|`, from the kernel's
//! cumulative distribution, so the cells' values sum exactly (to
//! round-off) to what each particle deposits.

/// A coarse-graining kernel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kernel {
    /// Gaussian, cut at three standard deviations.
    Gaussian,
    /// Lucy's quartic with compact support.
    Lucy,
}

/// `erf(x)` by its Taylor series (|x| ≤ 3/√2 here: 40 terms reach
/// round-off).
fn erf(x: f64) -> f64 {
    let (mut term, mut sum) = (x, x);
    let x2 = x * x;
    for n in 1..60 {
        term *= -x2 / n as f64;
        let t = term / (2 * n + 1) as f64;
        sum += t;
        if t.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    sum * 2.0 / std::f64::consts::PI.sqrt()
}

impl Kernel {
    /// Half-width of the support for standard deviation `w`, m.
    pub fn support(self, w: f64) -> f64 {
        match self {
            Kernel::Gaussian => 3.0 * w,
            Kernel::Lucy => w * (21.0f64 / 2.0).sqrt(),
        }
    }

    /// The cumulative distribution `∫_{−∞}^{x} φ`, exactly 0 below the
    /// support and 1 above it.
    pub fn cdf(self, x: f64, w: f64) -> f64 {
        let c = self.support(w);
        if x <= -c {
            return 0.0;
        }
        if x >= c {
            return 1.0;
        }
        let half = match self {
            Kernel::Gaussian => {
                let s = std::f64::consts::SQRT_2 * w;
                0.5 * erf(x.abs() / s) / erf(3.0 / std::f64::consts::SQRT_2)
            }
            Kernel::Lucy => {
                let u = x.abs() / c;
                // ∫_0^u (1 + 3t)(1 − t)³ dt over its value at 1 (0.4), halved
                (u - 2.0 * u.powi(3) + 2.0 * u.powi(4) - 0.6 * u.powi(5)) / 0.8
            }
        };
        if x < 0.0 {
            0.5 - half
        } else {
            0.5 + half
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erf_matches_tabulated_values() {
        // Abramowitz & Stegun, Table 7.1
        for (x, e) in [
            (0.5, 0.520_499_877_8),
            (1.0, 0.842_700_792_9),
            (2.0, 0.995_322_265_0),
        ] {
            assert!((erf(x) - e).abs() < 1e-10, "{x}");
        }
    }

    #[test]
    fn kernels_have_unit_mass_and_variance_w2() {
        for k in [Kernel::Gaussian, Kernel::Lucy] {
            let w = 0.7;
            let c = k.support(w);
            let n = 20000;
            let (mut m, mut v) = (0.0, 0.0);
            for i in 0..n {
                let (a, b) = (
                    -c + 2.0 * c * i as f64 / n as f64,
                    -c + 2.0 * c * (i + 1) as f64 / n as f64,
                );
                let p = k.cdf(b, w) - k.cdf(a, w);
                let x = 0.5 * (a + b);
                m += p;
                v += p * x * x;
            }
            assert!((m - 1.0).abs() < 1e-14);
            // the cut Gaussian's variance is below w² by the cut tails
            let expect = match k {
                Kernel::Lucy => w * w,
                Kernel::Gaussian => {
                    w * w
                        * (1.0
                            - 6.0 * (-4.5f64).exp()
                                / (2.0 * std::f64::consts::PI).sqrt()
                                / erf(3.0 / std::f64::consts::SQRT_2))
                }
            };
            assert!((v - expect).abs() < 1e-6 * expect, "{k:?}: {v} vs {expect}");
        }
    }
}
