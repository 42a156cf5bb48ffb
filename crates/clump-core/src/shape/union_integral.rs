//! Volume, first and second moments of a union of spheres, integrated exactly
//! (to quadrature accuracy, ~1e-10 relative) by slicing along z.
//!
//! For each height z the cross-section of the union is a union of discs; its
//! area moments are exact ([`disc_union`](super::disc_union)). As a function
//! of z they are analytic except at the heights where the topology of the
//! cross-section changes:
//! - the poles z_i ± r_i of every sphere (a disc appears or vanishes);
//! - the top and bottom of the intersection circle of every overlapping pair
//!   (two discs become tangent; the moments behave like (z − z*)^{3/2} there);
//! - the common points of every overlapping triple (an intersection point of
//!   two circles crosses a third circle; a jump in the second derivative).
//!
//! Heights of events that lie strictly inside another sphere are dropped. Each
//! sub-interval [a, b] between consecutive events is mapped with
//! z = a + (b − a)(3t² − 2t³), which turns the square-root behaviour at the
//! ends into a smooth function of t, and is integrated with adaptive
//! Gauss–Kronrod (7/15 points) until the summed |Kronrod − Gauss| estimates are
//! below 1e-11 of the relevant scale. The sum of those estimates is reported as
//! the error bound (it is pessimistic: Kronrod results are usually far more
//! accurate than the Gauss results they are compared with).
//!
//! All lengths are in the unit of the input (m in the rest of the crate);
//! the computation is done in coordinates shifted to the volume-weighted
//! centre of the spheres to avoid cancellation, and results are returned in
//! the input frame.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::{DMat3, DVec3};
use rayon::prelude::*;

use super::disc_union::{Disc, DiscUnion};
use super::progress::Progress;
use super::slabs::{cut_events, slabs, Slab};
use super::sphere_grid::union_sphere_indices;
use super::sphere_grid::SphereGrid;
use super::template_sphere::Sphere;

/// Geometric (density-free) properties of a union of spheres, input frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnionIntegrals {
    /// Volume of the union, length³.
    pub volume: f64,
    /// Centroid of the union, length, input frame.
    pub centroid: DVec3,
    /// Central second moment ∫ (x − c)(x − c)ᵀ dV, length⁵, input frame.
    pub second_moment: DMat3,
    /// Estimated relative error: max of the relative errors of the volume,
    /// of the centroid (relative to the bounding radius) and of the second
    /// moment (relative to its trace).
    pub relative_error_bound: f64,
    /// Number of integrand evaluations (slices) used.
    pub evaluations: usize,
}

/// Number of integrand components: A, Sx, Sy, zA, Sxx, Syy, z²A, Sxy, zSx, zSy.
const NC: usize = 10;
type Vals = [f64; NC];

/// Target for the summed error estimates, relative to the scales.
const TOLERANCE: f64 = 1e-11;

// Gauss–Kronrod 7/15 abscissae and weights on [-1, 1] (QUADPACK qk15).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
/// Gauss weights for XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Slice integrand: moments of the cross-section of one slab at height z
/// (shifted frame).
struct Slicer<'a> {
    slabs: &'a [Slab],
    /// The slab being integrated.
    slab: usize,
    discs: Vec<Disc>,
    union: DiscUnion,
    evaluations: usize,
}

impl Slicer<'_> {
    fn eval(&mut self, z: f64) -> Vals {
        self.evaluations += 1;
        self.discs.clear();
        let slab = &self.slabs[self.slab];
        // a slice visits only the spheres within r_max of it; the disc union
        // sorts its discs, so the order here does not matter
        let spheres = &slab.by_height;
        let lo = spheres.partition_point(|s| s.center.z < z - slab.rmax);
        let hi = spheres.partition_point(|s| s.center.z <= z + slab.rmax);
        for s in &spheres[lo..hi] {
            let dz = z - s.center.z;
            if dz.abs() < s.radius {
                let r = ((s.radius - dz) * (s.radius + dz)).sqrt();
                self.discs.push(Disc {
                    x: s.center.x,
                    y: s.center.y,
                    r,
                });
            }
        }
        let m = self
            .union
            .moments_in_strip(&self.discs, slab.x_lo, slab.x_hi);
        [
            m[0],
            m[1],
            m[2],
            z * m[0],
            m[3],
            m[4],
            z * z * m[0],
            m[5],
            z * m[1],
            z * m[2],
        ]
    }
}

/// A piece of a base interval [a, b], in the smoothing variable t ∈ [t0, t1].
#[derive(Debug, Clone, Copy)]
struct Segment {
    slab: usize,
    a: f64,
    b: f64,
    t0: f64,
    t1: f64,
    value: Vals,
    error: Vals,
    norm: f64,
}

impl PartialEq for Segment {
    fn eq(&self, other: &Self) -> bool {
        self.norm == other.norm
    }
}
impl Eq for Segment {}
impl PartialOrd for Segment {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Segment {
    fn cmp(&self, other: &Self) -> Ordering {
        self.norm.total_cmp(&other.norm)
    }
}

fn gk15(slicer: &mut Slicer, slab: usize, a: f64, b: f64, t0: f64, t1: f64) -> (Vals, Vals) {
    slicer.slab = slab;
    let half = 0.5 * (t1 - t0);
    let mid = 0.5 * (t1 + t0);
    let width = b - a;
    let mut f = |t: f64| -> Vals {
        let u = t * t * (3.0 - 2.0 * t);
        let jac = 6.0 * width * t * (1.0 - t);
        let mut v = slicer.eval(a + width * u);
        for x in v.iter_mut() {
            *x *= jac;
        }
        v
    };
    let mut k = [0.0; NC];
    let mut g = [0.0; NC];
    let fc = f(mid);
    for c in 0..NC {
        k[c] = WGK[7] * fc[c];
        g[c] = WG[3] * fc[c];
    }
    for j in 0..7 {
        let dx = half * XGK[j];
        let f1 = f(mid - dx);
        let f2 = f(mid + dx);
        for c in 0..NC {
            let s = f1[c] + f2[c];
            k[c] += WGK[j] * s;
            if j % 2 == 1 {
                g[c] += WG[j / 2] * s;
            }
        }
    }
    let mut err = [0.0; NC];
    for c in 0..NC {
        k[c] *= half;
        g[c] *= half;
        err[c] = (k[c] - g[c]).abs();
    }
    (k, err)
}

/// Heights (shifted frame) where the cross-section topology may change.
fn breakpoints(sph: &[Sphere]) -> Vec<f64> {
    let n = sph.len();
    // Overlapping pairs (symmetric adjacency lists, ascending).
    // overlapping pairs, each list sorted (the triple search below bisects)
    let grid = SphereGrid::new(sph);
    let adjacent: Vec<Vec<usize>> = (0..n)
        .map(|i| {
            let mut near = Vec::new();
            grid.for_each_near(sph, i, |j| {
                let d2 = (sph[j].center - sph[i].center).length_squared();
                let rs = sph[i].radius + sph[j].radius;
                if d2 < rs * rs && d2 > 0.0 {
                    near.push(j);
                }
            });
            near.sort_unstable();
            near.dedup();
            near
        })
        .collect();
    // A point on the surface of sphere i can only lie strictly inside a
    // sphere that overlaps sphere i.
    let inside_other = |p: DVec3, i: usize, skip: &[usize]| -> bool {
        adjacent[i].iter().any(|&l| {
            let s = &sph[l];
            !skip.contains(&l)
                && (p - s.center).length_squared() < s.radius * s.radius * (1.0 - 1e-12)
        })
    };
    let mut z = Vec::with_capacity(4 * n);
    for s in sph {
        z.push(s.center.z - s.radius);
        z.push(s.center.z + s.radius);
    }
    for i in 0..n {
        for &j in adjacent[i].iter().filter(|&&j| j > i) {
            let (si, sj) = (&sph[i], &sph[j]);
            let u = sj.center - si.center;
            let d = u.length();
            let nrm = u / d;
            let t = (d * d + si.radius * si.radius - sj.radius * sj.radius) / (2.0 * d);
            let h2 = si.radius * si.radius - t * t;
            if h2 <= 0.0 {
                continue;
            }
            let h = h2.sqrt();
            let m = si.center + t * nrm;
            let e = DVec3::Z - nrm.z * nrm;
            let el = e.length();
            if el < 1e-12 {
                z.push(m.z);
                continue;
            }
            for sign in [-1.0, 1.0] {
                let p = m + sign * h / el * e;
                if !inside_other(p, i, &[i, j]) {
                    z.push(p.z);
                }
            }
        }
    }
    // Overlapping triples: common points of three spheres.
    for i in 0..n {
        let up: Vec<usize> = adjacent[i].iter().copied().filter(|&j| j > i).collect();
        for (aj, &j) in up.iter().enumerate() {
            for &k in &up[aj + 1..] {
                if adjacent[j].binary_search(&k).is_err() {
                    continue;
                }
                let ci = sph[i].center;
                let u = sph[j].center - ci;
                let v = sph[k].center - ci;
                let w = u.cross(v);
                let w2 = w.length_squared();
                let scale2 = u.length_squared() * v.length_squared();
                if w2 <= 1e-20 * scale2 {
                    continue; // collinear centres: no isolated common points
                }
                let ri2 = sph[i].radius * sph[i].radius;
                let alpha = 0.5 * (u.length_squared() + ri2 - sph[j].radius * sph[j].radius);
                let beta = 0.5 * (v.length_squared() + ri2 - sph[k].radius * sph[k].radius);
                let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
                let det = uu * vv - uv * uv;
                let ca = (alpha * vv - beta * uv) / det;
                let cb = (beta * uu - alpha * uv) / det;
                let q0 = ca * u + cb * v;
                let rest = ri2 - q0.length_squared();
                if rest < 0.0 {
                    continue;
                }
                let s = (rest / w2).sqrt();
                for sign in [-1.0, 1.0] {
                    let p = ci + q0 + sign * s * w;
                    if !inside_other(p, i, &[i, j, k]) {
                        z.push(p.z);
                    }
                }
            }
        }
    }
    z.retain(|v| v.is_finite());
    z.sort_by(|a, b| a.total_cmp(b));
    z.dedup();
    z
}

/// Integrates the union of `spheres` (which must be valid: non-empty, finite,
/// radii > 0). Overlaps, duplicates and contained spheres are counted once.
///
/// The union is cut into slabs and, along z, into windows between the
/// breakpoints where its cross-section changes shape; each window is
/// integrated by Gauss–Kronrod (15 points) and the windows with the largest
/// error are halved until the relative error is below `TOLERANCE`.
pub fn union_integrals(spheres: &[Sphere]) -> UnionIntegrals {
    let (origin, shifted, l) = centred_union(spheres);
    let slabs = slabs(&shifted);
    let windows = slab_windows(&slabs);
    let new_slicer = || Slicer {
        slabs: &slabs,
        slab: 0,
        discs: Vec::with_capacity(shifted.len()),
        union: DiscUnion::new(),
        evaluations: 0,
    };
    // First pass over all sub-intervals, in parallel (each result depends on
    // its interval only, so the outcome does not depend on the thread count).
    let progress = Progress::new(shifted.len());
    let intervals = windows.len();
    if shifted.len() >= Progress::ESTIMATED_FROM && intervals > 0 {
        // time a sample of intervals spread along the union (results
        // discarded) to announce the pass
        let sample: Vec<_> = (0..Progress::SAMPLE)
            .map(|k| windows[k * intervals / Progress::SAMPLE])
            .collect();
        let timer = std::time::Instant::now();
        for &(slab, a, b) in &sample {
            let _ = gk15(&mut new_slicer(), slab, a, b, 0.0, 1.0);
        }
        let mean = timer.elapsed().as_secs_f64() / sample.len() as f64;
        progress.estimate(mean, intervals, rayon::current_num_threads());
    }
    let segments: Vec<Segment> = windows
        .par_iter()
        .map_init(new_slicer, |slicer, &(slab, a, b)| {
            let (value, error) = gk15(slicer, slab, a, b, 0.0, 1.0);
            progress.interval_done(intervals);
            Segment {
                slab,
                a,
                b,
                t0: 0.0,
                t1: 1.0,
                value,
                error,
                norm: 0.0,
            }
        })
        .collect();
    let mut slicer = new_slicer();
    slicer.evaluations = 15 * segments.len();
    // Scales of the 10 components (volume-like, ×L, ×L²), from a first estimate
    // of the volume: the largest sphere is a lower bound.
    let vmax = shifted.iter().map(|s| s.volume()).fold(0.0, f64::max);
    let total_volume: f64 = segments.iter().map(|s| s.value[0]).sum::<f64>().max(vmax);
    let scales: Vals = {
        let (v, v1, v2) = (total_volume, total_volume * l, total_volume * l * l);
        [v, v1, v1, v1, v2, v2, v2, v2, v2, v2]
    };
    let max_evaluations = 2_000_000usize.max(2000 * shifted.len());
    let segs = refine(segments, &scales, &mut slicer, max_evaluations, &progress);
    finish(&segs, origin, l, slicer.evaluations)
}

/// The spheres of the union's boundary, shifted to their volume-weighted
/// centre: that centre (m), the shifted spheres, and their reach `l` from
/// it (m).
fn centred_union(spheres: &[Sphere]) -> (DVec3, Vec<Sphere>, f64) {
    let kept: Vec<Sphere> = union_sphere_indices(spheres)
        .into_iter()
        .map(|i| spheres[i])
        .collect();
    // Shift to the volume-weighted centre of the kept spheres.
    let (mut vsum, mut csum) = (0.0, DVec3::ZERO);
    for s in &kept {
        let v = s.radius.powi(3);
        vsum += v;
        csum += v * s.center;
    }
    let origin = csum / vsum;
    let shifted: Vec<Sphere> = kept
        .iter()
        .map(|s| Sphere::new(s.center - origin, s.radius))
        .collect();
    let l = shifted
        .iter()
        .map(|s| s.center.length() + s.radius)
        .fold(0.0, f64::max);
    (origin, shifted, l)
}

/// The integration windows along z of every slab, `(slab, z0, z1)`:
/// between the breakpoints of its spheres and of its cuts, within the
/// slab's extent.
fn slab_windows(slabs: &[Slab]) -> Vec<(usize, f64, f64)> {
    slabs
        .iter()
        .enumerate()
        .flat_map(|(k, slab)| {
            let mut z = breakpoints(&slab.spheres);
            if slabs.len() > 1 {
                cut_events(&slab.spheres, slab.x_lo, &mut z);
                cut_events(&slab.spheres, slab.x_hi, &mut z);
                z.retain(|v| v.is_finite());
                z.sort_by(|a, b| a.total_cmp(b));
                z.dedup();
            }
            let zmin = slab
                .spheres
                .iter()
                .map(|s| s.center.z - s.radius)
                .fold(f64::INFINITY, f64::min);
            let zmax = slab
                .spheres
                .iter()
                .map(|s| s.center.z + s.radius)
                .fold(f64::NEG_INFINITY, f64::max);
            let z: Vec<f64> = z.into_iter().filter(|&v| v >= zmin && v <= zmax).collect();
            z.windows(2)
                .filter(|w| w[1] > w[0])
                .map(|w| (k, w[0], w[1]))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Halves the segment of the largest error until the summed error,
/// measured against `scales`, is below [`TOLERANCE`] (or the evaluations
/// reach `max_evaluations`); returns the segments sorted by position, so
/// that their sums run in a fixed order.
fn refine(
    segments: Vec<Segment>,
    scales: &Vals,
    slicer: &mut Slicer,
    max_evaluations: usize,
    progress: &Progress,
) -> Vec<Segment> {
    let norm = |e: &Vals| -> f64 {
        e.iter()
            .zip(scales.iter())
            .map(|(e, s)| e / s)
            .fold(0.0, f64::max)
    };
    let mut heap = BinaryHeap::with_capacity(segments.len() * 2);
    let mut total_err = 0.0;
    for mut s in segments {
        s.norm = norm(&s.error);
        total_err += s.norm;
        heap.push(s);
    }
    while total_err > TOLERANCE && slicer.evaluations < max_evaluations {
        let Some(seg) = heap.pop() else { break };
        progress.refining(total_err, TOLERANCE);
        let tm = 0.5 * (seg.t0 + seg.t1);
        if tm <= seg.t0 || tm >= seg.t1 {
            heap.push(Segment { norm: 0.0, ..seg });
            total_err -= seg.norm;
            continue;
        }
        total_err -= seg.norm;
        for (t0, t1) in [(seg.t0, tm), (tm, seg.t1)] {
            let (value, error) = gk15(slicer, seg.slab, seg.a, seg.b, t0, t1);
            let n = norm(&error);
            total_err += n;
            heap.push(Segment {
                slab: seg.slab,
                a: seg.a,
                b: seg.b,
                t0,
                t1,
                value,
                error,
                norm: n,
            });
        }
        // Guard against drift of the running sum.
        if slicer.evaluations % 30_000 < 30 {
            total_err = heap.iter().map(|s| s.norm).sum();
        }
    }
    // Final sums, in a deterministic order (by position).
    let mut segs = heap.into_vec();
    segs.sort_by(|p, q| {
        p.slab
            .cmp(&q.slab)
            .then(p.a.total_cmp(&q.a))
            .then(p.t0.total_cmp(&q.t0))
    });
    segs
}

/// The integrals from the refined segments: volume, centroid (shifted back
/// by `origin`), second moment about the centroid, and the error bound.
fn finish(segs: &[Segment], origin: DVec3, l: f64, evaluations: usize) -> UnionIntegrals {
    let mut val = [0.0; NC];
    let mut err = [0.0; NC];
    for s in segs {
        for c in 0..NC {
            val[c] += s.value[c];
            err[c] += s.error[c];
        }
    }
    let [v, sx, sy, sz, sxx, syy, szz, sxy, sxz, syz] = val;
    let first = DVec3::new(sx, sy, sz);
    let c = first / v;
    let s2 = DMat3::from_cols(
        DVec3::new(sxx, sxy, sxz),
        DVec3::new(sxy, syy, syz),
        DVec3::new(sxz, syz, szz),
    );
    let cc = DMat3::from_cols(c * c.x, c * c.y, c * c.z);
    let second = s2 - cc * v;

    // Error bounds.
    let ev = err[0];
    let ef = err[1].max(err[2]).max(err[3]);
    let es = err[4..].iter().cloned().fold(0.0, f64::max);
    let cl = c.length();
    let trace = second.x_axis.x + second.y_axis.y + second.z_axis.z;
    let rel_v = ev / v;
    let rel_c = (ef + cl * ev) / (v * l);
    let rel_s = 3.0 * (es + 2.0 * cl * ef + cl * cl * ev) / trace;
    let roundoff = 1e-13;
    let relative_error_bound = rel_v.max(rel_c).max(rel_s) + roundoff;

    UnionIntegrals {
        volume: v,
        centroid: origin + c,
        second_moment: second,
        relative_error_bound,
        evaluations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn single_sphere_exact() {
        let s = [Sphere::new(DVec3::new(1.0, 2.0, 3.0), 0.5)];
        let u = union_integrals(&s);
        let v = 4.0 / 3.0 * PI * 0.125;
        assert!((u.volume - v).abs() < 1e-14 * v);
        assert!((u.centroid - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-14);
        let c = v * 0.25 / 5.0;
        assert!((u.second_moment.x_axis.x - c).abs() < 1e-13 * c);
        assert!(u.relative_error_bound < 1e-10);
    }

    /// A chain of 300 unit spheres 1.5 apart (only neighbours overlap), cut
    /// into slabs by the integration: its volume is N V_sphere − (N − 1)
    /// V_lens with V_lens = π(4r + d)(2r − d)²/12, and its centroid is the
    /// middle of the chain; along x (every cut crosses the chain) and along
    /// a diagonal (cuts cross obliquely).
    #[test]
    fn long_chain_through_many_slabs() {
        let (n, r, d) = (300usize, 1.0f64, 1.5f64);
        let lens = PI * (4.0 * r + d) * (2.0 * r - d).powi(2) / 12.0;
        let exact = n as f64 * 4.0 / 3.0 * PI * r.powi(3) - (n - 1) as f64 * lens;
        for dir in [DVec3::X, DVec3::new(1.0, 0.6, 0.3).normalize()] {
            let s: Vec<Sphere> = (0..n)
                .map(|k| Sphere::new(dir * (d * k as f64), r))
                .collect();
            assert!(slabs(&s).len() > 50);
            let u = union_integrals(&s);
            let mid = dir * (d * (n - 1) as f64 / 2.0);
            eprintln!(
                "chain along {dir}: volume {:.15e} vs {exact:.15e}, centroid off by {:.2e}, bound {:.1e}",
                u.volume,
                (u.centroid - mid).length(),
                u.relative_error_bound
            );
            assert!((u.volume - exact).abs() < 1e-10 * exact);
            assert!((u.centroid - mid).length() < 1e-10 * d * n as f64);
        }
    }
}
