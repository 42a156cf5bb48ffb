//! A fluid velocity field given on a regular grid (docs/theory.md T-83):
//! each body is given the trilinear interpolation of the grid at its
//! centre of mass, every step, by the coupling stage.

use glam::DVec3;

/// Velocities at the nodes of a regular grid, world frame, m/s.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityGrid {
    /// Position of node (0, 0, 0), world frame, m.
    origin: DVec3,
    /// Node spacing along x, y, z, m (1 along an axis with one node).
    spacing: DVec3,
    /// The largest node coordinates, world frame, m (as in the nodes, so
    /// the bounds carry no rounding of `origin + (n − 1) spacing`).
    top: DVec3,
    /// Nodes along x, y, z.
    n: [usize; 3],
    /// Node velocities, x fastest: node (i, j, k) at `i + n_x (j + n_y k)`.
    u: Vec<DVec3>,
}

/// The sorted distinct values of one coordinate of the points.
fn axis_values(points: &[(DVec3, DVec3)], a: usize) -> Vec<f64> {
    let mut v: Vec<f64> = points.iter().map(|p| p.0[a]).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

impl VelocityGrid {
    /// The grid through the `(position, velocity)` nodes, in any order.
    /// The nodes must be finite, fill a regular grid (each axis's distinct
    /// coordinates equally spaced to 1e-9 of the spacing, every node
    /// present exactly once); the error says what is wrong.
    pub fn from_nodes(points: &[(DVec3, DVec3)]) -> Result<Self, String> {
        if let Some((p, u)) = points
            .iter()
            .find(|(p, u)| !(p.is_finite() && u.is_finite()))
        {
            return Err(format!("a node is not finite: position {p}, velocity {u}"));
        }
        if points.is_empty() {
            return Err("the grid has no nodes".into());
        }
        let mut n = [0usize; 3];
        let mut origin = DVec3::ZERO;
        let mut spacing = DVec3::ONE;
        let mut top = DVec3::ZERO;
        for a in 0..3 {
            let v = axis_values(points, a);
            n[a] = v.len();
            origin[a] = v[0];
            top[a] = v[v.len() - 1];
            if v.len() > 1 {
                let h = (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64;
                for (k, x) in v.iter().enumerate() {
                    if (x - (v[0] + k as f64 * h)).abs() > 1e-9 * h {
                        return Err(format!(
                            "not a regular grid: the {} coordinates are not equally spaced ({x} where {} was expected)",
                            ["x", "y", "z"][a],
                            v[0] + k as f64 * h
                        ));
                    }
                }
                spacing[a] = h;
            }
        }
        let total = n[0] * n[1] * n[2];
        if total != points.len() {
            return Err(format!(
                "not a regular grid: {} x {} x {} distinct coordinates need {total} nodes, found {}",
                n[0],
                n[1],
                n[2],
                points.len()
            ));
        }
        let mut u = vec![DVec3::NAN; total];
        for (p, v) in points {
            let idx = |a: usize| ((p[a] - origin[a]) / spacing[a]).round() as usize;
            let k = idx(0) + n[0] * (idx(1) + n[1] * idx(2));
            if !u[k].is_nan() {
                return Err(format!("not a regular grid: node {p} appears twice"));
            }
            u[k] = *v;
        }
        Ok(VelocityGrid {
            origin,
            spacing,
            top,
            n,
            u,
        })
    }

    /// The grid of `n` nodes along x, y, z from `origin` (world frame, m)
    /// at `spacing` (m), with the velocities `u` (world frame, m/s) of
    /// node (i, j, k) at `i + n_x (j + n_y k)`, as a coupled CFD code
    /// hands over a regular grid. Needs at least one node along each axis,
    /// finite values, a positive spacing along an axis of more than one
    /// node, and `n_x n_y n_z` velocities; the error says what is wrong.
    pub fn regular(
        origin: DVec3,
        spacing: DVec3,
        n: [usize; 3],
        u: Vec<DVec3>,
    ) -> Result<Self, String> {
        if !(origin.is_finite() && spacing.is_finite()) {
            return Err(format!(
                "origin {origin} and spacing {spacing} must be finite"
            ));
        }
        if n.contains(&0) {
            return Err(format!("every axis needs at least one node, got {n:?}"));
        }
        if let Some(a) = (0..3).find(|&a| n[a] > 1 && spacing[a] <= 0.0) {
            return Err(format!(
                "the spacing along {} must be > 0 m, got {}",
                ["x", "y", "z"][a],
                spacing[a]
            ));
        }
        let total = n
            .iter()
            .try_fold(1usize, |a, &b| a.checked_mul(b))
            .ok_or_else(|| format!("{n:?} nodes are too many"))?;
        if u.len() != total {
            return Err(format!(
                "{} x {} x {} nodes need {total} velocities, found {}",
                n[0],
                n[1],
                n[2],
                u.len()
            ));
        }
        if let Some(k) = u.iter().position(|v| !v.is_finite()) {
            return Err(format!("the velocity of node {k} is not finite: {}", u[k]));
        }
        let mut spacing = spacing;
        let mut top = origin;
        for a in 0..3 {
            if n[a] == 1 {
                spacing[a] = 1.0;
            } else {
                top[a] = origin[a] + (n[a] - 1) as f64 * spacing[a];
            }
        }
        Ok(VelocityGrid {
            origin,
            spacing,
            top,
            n,
            u,
        })
    }

    /// Nodes along x, y, z.
    pub fn counts(&self) -> [usize; 3] {
        self.n
    }

    /// The lower and upper corners of the grid, world frame, m.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        (self.origin, self.top)
    }

    /// The trilinear interpolation at `p` (world frame, m), in m/s, as
    /// nested linear interpolations `u0 + t (u1 − u0)` along x, then y,
    /// then z (so a uniform field is returned bit for bit); a point
    /// outside the grid takes the value at the nearest point of it. No
    /// allocation.
    pub fn sample(&self, p: DVec3) -> DVec3 {
        let mut lo = [0usize; 3];
        let mut hi = [0usize; 3];
        let mut t = [0.0f64; 3];
        for a in 0..3 {
            if self.n[a] == 1 {
                continue;
            }
            let s = ((p[a] - self.origin[a]) / self.spacing[a]).clamp(0.0, (self.n[a] - 1) as f64);
            let i = (s.floor() as usize).min(self.n[a] - 2);
            lo[a] = i;
            hi[a] = i + 1;
            t[a] = s - i as f64;
        }
        let at = |i: usize, j: usize, k: usize| self.u[i + self.n[0] * (j + self.n[1] * k)];
        let lerp = |u0: DVec3, u1: DVec3, t: f64| u0 + t * (u1 - u0);
        let x = |j: usize, k: usize| lerp(at(lo[0], j, k), at(hi[0], j, k), t[0]);
        let y = |k: usize| lerp(x(lo[1], k), x(hi[1], k), t[1]);
        lerp(y(lo[2]), y(hi[2]), t[2])
    }
}
