//! Exact area moments of a union of discs in the plane (Green's theorem).
//!
//! The boundary of a union of discs consists of arcs of the circles that are
//! not covered by any other disc. With the boundary oriented counter-clockwise,
//! Green's theorem turns every area moment into a boundary integral:
//!
//! | moment | boundary form |
//! |---|---|
//! | A = ∫dA | ∮ x dy |
//! | ∫x dA | ∮ ½x² dy |
//! | ∫y dA | −∮ ½y² dx |
//! | ∫x² dA | ∮ ⅓x³ dy |
//! | ∫y² dA | −∮ ⅓y³ dx |
//! | ∫xy dA | ∮ ½x²y dy |
//!
//! On an arc of the circle (a + ρ cos θ, b + ρ sin θ), θ ∈ [α, β], each form is
//! a polynomial in cos θ and sin θ of degree ≤ 4 and is integrated in closed
//! form. Coordinates and lengths are in whatever unit the caller uses (the
//! moments come out in that unit to the powers 2, 3, 4).

use std::f64::consts::{PI, TAU};

/// A disc in the plane: centre (x, y) and radius r (same length unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// Centre x coordinate.
    pub x: f64,
    /// Centre y coordinate.
    pub y: f64,
    /// Radius (≥ 0).
    pub r: f64,
}

/// Area moments of a plane region: `[A, ∫x dA, ∫y dA, ∫x² dA, ∫y² dA, ∫xy dA]`
/// (units: length², length³, length³, length⁴, length⁴, length⁴).
pub type AreaMoments = [f64; 6];

/// Reusable scratch space for [`DiscUnion::moments`] (avoids allocation per slice).
#[derive(Debug, Default, Clone)]
pub struct DiscUnion {
    intervals: Vec<(f64, f64)>,
    sorted: Vec<Disc>,
    chords: Vec<(f64, f64)>,
}

/// Antiderivatives at angle θ of cos^m θ sin^n θ needed by the forms above,
/// in the order I10, I01, I20, I02, I11, I30, I03, I21, I40, I04, I31.
#[inline]
fn antiderivatives(theta: f64) -> [f64; 11] {
    let (s, c) = theta.sin_cos();
    let s2 = 2.0 * s * c; // sin 2θ
    let c2 = c * c - s * s; // cos 2θ
    let s4 = 2.0 * s2 * c2; // sin 4θ
    let c3 = c * c * c;
    [
        s,                                     // I10 = ∫c
        -c,                                    // I01 = ∫s
        0.5 * theta + 0.25 * s2,               // I20 = ∫c²
        0.5 * theta - 0.25 * s2,               // I02 = ∫s²
        0.5 * s * s,                           // I11 = ∫cs
        s - s * s * s / 3.0,                   // I30 = ∫c³
        -c + c3 / 3.0,                         // I03 = ∫s³
        -c3 / 3.0,                             // I21 = ∫c²s
        0.375 * theta + 0.25 * s2 + s4 / 32.0, // I40 = ∫c⁴
        0.375 * theta - 0.25 * s2 + s4 / 32.0, // I04 = ∫s⁴
        -0.25 * c3 * c,                        // I31 = ∫c³s
    ]
}

/// Adds to `m` the boundary integrals over the arcs of `disc` whose angular
/// integrals of the monomials are `d` (see [`antiderivatives`]).
#[inline]
fn accumulate(m: &mut AreaMoments, disc: &Disc, d: &[f64; 11]) {
    let (a, b, r) = (disc.x, disc.y, disc.r);
    let [d10, d01, d20, d02, d11, d30, d03, d21, d40, d04, d31] = *d;
    let (a2, b2, r2) = (a * a, b * b, r * r);
    m[0] += r * (a * d10 + r * d20);
    m[1] += 0.5 * r * (a2 * d10 + 2.0 * a * r * d20 + r2 * d30);
    m[2] += 0.5 * r * (b2 * d01 + 2.0 * b * r * d02 + r2 * d03);
    m[3] += r / 3.0 * (a2 * a * d10 + 3.0 * a2 * r * d20 + 3.0 * a * r2 * d30 + r2 * r * d40);
    m[4] += r / 3.0 * (b2 * b * d01 + 3.0 * b2 * r * d02 + 3.0 * b * r2 * d03 + r2 * r * d04);
    m[5] += 0.5
        * r
        * (a2 * b * d10
            + a2 * r * d11
            + 2.0 * a * b * r * d20
            + 2.0 * a * r2 * d21
            + b * r2 * d30
            + r2 * r * d31);
}

/// Exact moments of a whole disc.
#[inline]
fn full_disc(m: &mut AreaMoments, disc: &Disc) {
    let (a, b, r) = (disc.x, disc.y, disc.r);
    let area = PI * r * r;
    m[0] += area;
    m[1] += area * a;
    m[2] += area * b;
    m[3] += area * (a * a + 0.25 * r * r);
    m[4] += area * (b * b + 0.25 * r * r);
    m[5] += area * a * b;
}

impl DiscUnion {
    /// New scratch space.
    pub fn new() -> Self {
        Self::default()
    }

    /// Area moments of the union of `discs` (overlaps counted once), exact up
    /// to floating-point rounding. Discs with r = 0 contribute nothing;
    /// identical discs are counted once.
    pub fn moments(&mut self, discs: &[Disc]) -> AreaMoments {
        self.moments_in_strip(discs, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// Area moments of the part of the union of `discs` with
    /// `x_lo ≤ x ≤ x_hi` (either bound may be infinite). The boundary of that
    /// region is the uncovered arcs inside the strip and the parts of the
    /// lines x = x_lo and x = x_hi inside the union, on which the forms of
    /// the table above are polynomials in y.
    pub fn moments_in_strip(&mut self, discs: &[Disc], x_lo: f64, x_hi: f64) -> AreaMoments {
        let mut m = [0.0; 6];
        // Sort by centre x (ties by y, r) so that only discs within
        // rk + rmax in x are examined; the order also breaks ties between
        // identical discs.
        self.sorted.clear();
        self.sorted.extend(discs.iter().filter(|d| d.r > 0.0));
        self.sorted.sort_unstable_by(|p, q| {
            p.x.total_cmp(&q.x)
                .then(p.y.total_cmp(&q.y))
                .then(p.r.total_cmp(&q.r))
        });
        let discs = &self.sorted[..];
        let rmax = discs.iter().map(|d| d.r).fold(0.0, f64::max);
        'circles: for (k, dk) in discs.iter().enumerate() {
            self.intervals.clear();
            if dk.x + dk.r <= x_lo || dk.x - dk.r >= x_hi {
                continue; // no arc of this circle lies in the strip
            }
            // the arcs outside the strip count as covered
            let c_lo = (x_lo - dk.x) / dk.r;
            if c_lo > -1.0 {
                let t = c_lo.acos();
                self.intervals.push((t, TAU - t));
            }
            let c_hi = (x_hi - dk.x) / dk.r;
            if c_hi < 1.0 {
                let t = c_hi.acos();
                self.intervals.push((0.0, t));
                self.intervals.push((TAU - t, TAU));
            }
            let reach = dk.r + rmax;
            let lo = discs.partition_point(|d| d.x < dk.x - reach);
            let hi = discs.partition_point(|d| d.x <= dk.x + reach);
            for (j, dj) in discs.iter().enumerate().take(hi).skip(lo) {
                if j == k {
                    continue;
                }
                let dx = dj.x - dk.x;
                let dy = dj.y - dk.y;
                let d2 = dx * dx + dy * dy;
                let sum = dk.r + dj.r;
                if d2 >= sum * sum {
                    continue; // disjoint or externally tangent
                }
                let d = d2.sqrt();
                if d + dk.r <= dj.r {
                    // circle k lies inside disc j; if j also lies inside k the
                    // discs are identical and only the lower index counts.
                    if d + dj.r <= dk.r && j > k {
                        continue;
                    }
                    continue 'circles;
                }
                if d + dj.r <= dk.r {
                    continue; // disc j inside circle k: covers no arc of k
                }
                // Proper intersection: arc of k centred on the direction to j,
                // half-width ψ with cos ψ = (rk² + d² − rj²)/(2 rk d).
                let phi = dy.atan2(dx);
                let num = (dk.r - dj.r) * (dk.r + dj.r) + d2;
                let h2 = (sum + d) * (d - dk.r + dj.r) * (dk.r - d + dj.r) * (dk.r + d - dj.r);
                let psi = h2.max(0.0).sqrt().atan2(num);
                if psi >= PI {
                    continue 'circles;
                }
                let start = (phi - psi).rem_euclid(TAU);
                let end = start + 2.0 * psi;
                if end > TAU {
                    self.intervals.push((start, TAU));
                    self.intervals.push((0.0, end - TAU));
                } else {
                    self.intervals.push((start, end));
                }
            }
            if self.intervals.is_empty() {
                full_disc(&mut m, dk);
                continue;
            }
            self.intervals.sort_unstable_by(|p, q| {
                p.0.partial_cmp(&q.0).unwrap_or(std::cmp::Ordering::Equal)
            });
            // Sweep the uncovered gaps of [0, 2π].
            let mut d = [0.0; 11];
            let mut covered_to = 0.0_f64;
            let mut any_gap = false;
            let add_gap = |lo: f64, hi: f64, d: &mut [f64; 11]| {
                let fa = antiderivatives(lo);
                let fb = antiderivatives(hi);
                for i in 0..11 {
                    d[i] += fb[i] - fa[i];
                }
            };
            for &(s, e) in &self.intervals {
                if s > covered_to {
                    add_gap(covered_to, s, &mut d);
                    any_gap = true;
                }
                covered_to = covered_to.max(e);
            }
            if covered_to < TAU {
                add_gap(covered_to, TAU, &mut d);
                any_gap = true;
            }
            if any_gap {
                accumulate(&mut m, dk, &d);
            }
        }
        // the cut lines: x_hi traversed upwards, x_lo downwards
        for (x, sign) in [(x_hi, 1.0), (x_lo, -1.0)] {
            if x.is_finite() {
                add_cut(&mut self.chords, &mut m, discs, x, sign);
            }
        }
        m
    }
}

/// Adds the boundary integrals along the line x = `x` over the parts of
/// it inside the union (`sign` +1 upwards, −1 downwards). On the line
/// dx = 0, so only the `dy` forms contribute: x, ½x², ⅓x³ and ½x²y.
fn add_cut(chords: &mut Vec<(f64, f64)>, m: &mut AreaMoments, discs: &[Disc], x: f64, sign: f64) {
    chords.clear();
    for d in discs {
        let dx = x - d.x;
        if dx.abs() < d.r {
            let h = ((d.r - dx) * (d.r + dx)).sqrt();
            chords.push((d.y - h, d.y + h));
        }
    }
    chords.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
    let mut add = |y0: f64, y1: f64| {
        let len = sign * (y1 - y0);
        m[0] += x * len;
        m[1] += 0.5 * x * x * len;
        m[3] += x * x * x / 3.0 * len;
        m[5] += 0.25 * x * x * sign * (y1 - y0) * (y1 + y0);
    };
    let mut run: Option<(f64, f64)> = None;
    for &(a, b) in chords.iter() {
        run = match run {
            Some((r0, r1)) if a <= r1 => Some((r0, r1.max(b))),
            Some((r0, r1)) => {
                add(r0, r1);
                Some((a, b))
            }
            None => Some((a, b)),
        };
    }
    if let Some((r0, r1)) = run {
        add(r0, r1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn single_disc_and_duplicates() {
        let d = Disc {
            x: 0.3,
            y: -0.7,
            r: 1.3,
        };
        let mut u = DiscUnion::new();
        let m1 = u.moments(&[d]);
        let m3 = u.moments(&[d, d, d]);
        assert_eq!(m1, m3);
        assert!(close(m1[0], PI * 1.69, 1e-15));
    }

    #[test]
    fn two_discs_lens_area() {
        // Two unit discs at distance 1: union area = 2π − lens,
        // lens = 2 acos(d/2) − (d/2) sqrt(4 − d²).
        let dist: f64 = 1.0;
        let lens = 2.0 * (dist / 2.0).acos() - dist / 2.0 * (4.0 - dist * dist).sqrt();
        let mut u = DiscUnion::new();
        let m = u.moments(&[
            Disc {
                x: 0.0,
                y: 0.0,
                r: 1.0,
            },
            Disc {
                x: 0.6,
                y: 0.8,
                r: 1.0,
            },
        ]);
        assert!(close(m[0], 2.0 * PI - lens, 1e-14), "{}", m[0]);
        // centroid at the midpoint by symmetry
        assert!(close(m[1] / m[0], 0.3, 1e-14));
        assert!(close(m[2] / m[0], 0.4, 1e-14));
    }

    #[test]
    fn contained_disc() {
        let mut u = DiscUnion::new();
        let big = Disc {
            x: 0.0,
            y: 0.0,
            r: 2.0,
        };
        let m = u.moments(&[
            Disc {
                x: 0.5,
                y: 0.2,
                r: 0.3,
            },
            big,
        ]);
        assert_eq!(m, u.moments(&[big]));
    }

    /// Half a unit disc (x ≥ 0): A = π/2, ∫x = 2/3, ∫x² = ∫y² = π/8,
    /// ∫y = ∫xy = 0 (closed forms).
    #[test]
    fn half_disc_in_a_strip() {
        let mut u = DiscUnion::new();
        let d = [Disc {
            x: 0.0,
            y: 0.0,
            r: 1.0,
        }];
        let m = u.moments_in_strip(&d, 0.0, f64::INFINITY);
        let want = [PI / 2.0, 2.0 / 3.0, 0.0, PI / 8.0, PI / 8.0, 0.0];
        for c in 0..6 {
            assert!(close(m[c], want[c], 1e-14), "{c}: {} vs {}", m[c], want[c]);
        }
    }

    /// Cutting a union of discs into strips and adding the pieces gives the
    /// whole (independent of where the cuts fall).
    #[test]
    fn strips_add_up_to_the_whole() {
        let mut u = DiscUnion::new();
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12345);
        let mut rnd = || rng.gen::<f64>();
        let discs: Vec<Disc> = (0..40)
            .map(|_| Disc {
                x: 4.0 * rnd(),
                y: 4.0 * rnd(),
                r: 0.3 + 0.5 * rnd(),
            })
            .collect();
        let whole = u.moments(&discs);
        let cuts = [f64::NEG_INFINITY, 0.7, 1.3, 2.05, 3.9, f64::INFINITY];
        let mut sum = [0.0; 6];
        for w in cuts.windows(2) {
            let m = u.moments_in_strip(&discs, w[0], w[1]);
            for c in 0..6 {
                sum[c] += m[c];
            }
        }
        for c in 0..6 {
            assert!(
                close(sum[c], whole[c], 1e-12),
                "{c}: {} vs {}",
                sum[c],
                whole[c]
            );
        }
    }
}
