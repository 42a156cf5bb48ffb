//! Insertion regions (world frame, m).

use super::InsertError;
use glam::DVec3;
use rand::Rng;
use serde::{Deserialize, Serialize};

/// Draws of [`Region::sample_in_plane`] before it gives up (one pose try).
pub const PLANE_TRIES: usize = 64;

/// A region of space into which bodies are inserted, world frame, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Region {
    /// The axis-aligned box `[lo, hi]`.
    Box {
        /// Lower corner, world frame, m.
        lo: DVec3,
        /// Upper corner, world frame, m.
        hi: DVec3,
    },
    /// A finite circular cylinder: the disc of radius `radius` centred on
    /// `base`, perpendicular to `axis`, swept `height` along `axis`.
    Cylinder {
        /// Centre of the bottom disc, world frame, m.
        base: DVec3,
        /// Unit axis direction, world frame.
        axis: DVec3,
        /// Radius, m.
        radius: f64,
        /// Height along `axis`, m.
        height: f64,
    },
}

impl Region {
    /// Checks the geometry: finite values, `hi > lo`, a unit axis, positive
    /// radius and height.
    pub fn validate(&self) -> Result<(), InsertError> {
        match *self {
            Region::Box { lo, hi } => {
                if !lo.is_finite() || !hi.is_finite() || hi.cmple(lo).any() {
                    return Err(InsertError::InvalidSpec(format!(
                        "box region needs finite corners with hi > lo on every axis, got lo = {lo}, hi = {hi}"
                    )));
                }
            }
            Region::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                if !base.is_finite() || !axis.is_finite() || (axis.length() - 1.0).abs() > 1e-6 {
                    return Err(InsertError::InvalidSpec(format!(
                        "cylinder region needs a finite base and a unit axis, got base = {base}, axis = {axis} (length {})",
                        axis.length()
                    )));
                }
                if !(radius.is_finite() && radius > 0.0 && height.is_finite() && height > 0.0) {
                    return Err(InsertError::InvalidSpec(format!(
                        "cylinder region needs radius > 0 and height > 0 (m), got radius = {radius}, height = {height}"
                    )));
                }
            }
        }
        Ok(())
    }

    /// Volume, m³.
    pub fn volume(&self) -> f64 {
        match *self {
            Region::Box { lo, hi } => {
                let d = hi - lo;
                d.x * d.y * d.z
            }
            Region::Cylinder { radius, height, .. } => {
                std::f64::consts::PI * radius * radius * height
            }
        }
    }

    /// True when the sphere with centre `center` (world, m) and radius
    /// `radius` (m) lies entirely inside the region (touching the boundary
    /// counts as inside).
    pub fn contains_sphere(&self, center: DVec3, radius: f64) -> bool {
        match *self {
            Region::Box { lo, hi } => {
                (center - radius).cmpge(lo).all() && (center + radius).cmple(hi).all()
            }
            Region::Cylinder {
                base,
                axis,
                radius: rc,
                height,
            } => {
                let rel = center - base;
                let h = rel.dot(axis);
                if h - radius < 0.0 || h + radius > height {
                    return false;
                }
                let rho = (rel - axis * h).length();
                rho + radius <= rc
            }
        }
    }

    /// True when the point `x` (world, m) is inside the region.
    pub fn contains_point(&self, x: DVec3) -> bool {
        self.contains_sphere(x, 0.0)
    }

    /// Axis-aligned bounding box `(lo, hi)`, world frame, m.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        match *self {
            Region::Box { lo, hi } => (lo, hi),
            Region::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let top = base + axis * height;
                // extent of a disc of radius r perpendicular to a: r·sqrt(1 − a_i²)
                let e = DVec3::new(
                    (1.0 - axis.x * axis.x).max(0.0).sqrt(),
                    (1.0 - axis.y * axis.y).max(0.0).sqrt(),
                    (1.0 - axis.z * axis.z).max(0.0).sqrt(),
                ) * radius;
                (base.min(top) - e, base.max(top) + e)
            }
        }
    }

    /// Support function: the largest `x · n` over the region, m, for a
    /// world-frame direction `n` (unit).
    pub fn support(&self, n: DVec3) -> f64 {
        match *self {
            Region::Box { lo, hi } => {
                let mut s = 0.0;
                for a in 0..3 {
                    s += if n[a] >= 0.0 {
                        hi[a] * n[a]
                    } else {
                        lo[a] * n[a]
                    };
                }
                s
            }
            Region::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let top = base + axis * height;
                let an = axis.dot(n);
                base.dot(n).max(top.dot(n))
                    + radius * (n.length_squared() - an * an).max(0.0).sqrt()
            }
        }
    }

    /// A point drawn uniformly from the region (world, m).
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        self.sample_eroded(rng, 0.0)
            .expect("a valid region is never empty")
    }

    /// A point drawn uniformly from the cross-section of the region shrunk
    /// by `margin` ≥ 0 (m) with the plane at height `z` (m, world frame;
    /// 2D insertion): drawn from the cross-section's bounding rectangle
    /// until inside (at most [`PLANE_TRIES`] draws of two numbers); `None`
    /// when no draw was inside (the cross-section is empty or thin).
    pub fn sample_in_plane<R: Rng + ?Sized>(
        &self,
        rng: &mut R,
        margin: f64,
        z: f64,
    ) -> Option<DVec3> {
        let (lo, hi) = self.bounds();
        let (lo, hi) = (lo + margin, hi - margin);
        if hi.x < lo.x || hi.y < lo.y {
            return None;
        }
        for _ in 0..PLANE_TRIES {
            let (u, v): (f64, f64) = (rng.gen(), rng.gen());
            let x = DVec3::new(lo.x + (hi.x - lo.x) * u, lo.y + (hi.y - lo.y) * v, z);
            if self.contains_sphere(x, margin) {
                return Some(x);
            }
        }
        None
    }

    /// A point drawn uniformly from the region shrunk by `margin` ≥ 0 (m) on
    /// every face (world, m); `None` when the shrunk region is empty.
    pub fn sample_eroded<R: Rng + ?Sized>(&self, rng: &mut R, margin: f64) -> Option<DVec3> {
        match *self {
            Region::Box { lo, hi } => {
                let (lo, hi) = (lo + margin, hi - margin);
                if hi.cmplt(lo).any() {
                    return None;
                }
                let u = DVec3::new(rng.gen(), rng.gen(), rng.gen());
                Some(lo + (hi - lo) * u)
            }
            Region::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let (r, h) = (radius - margin, height - 2.0 * margin);
                if r < 0.0 || h < 0.0 {
                    return None;
                }
                let (e1, e2) = axis.any_orthonormal_pair();
                let rho = r * rng.gen::<f64>().sqrt();
                let phi = std::f64::consts::TAU * rng.gen::<f64>();
                let z = margin + h * rng.gen::<f64>();
                Some(base + axis * z + (e1 * phi.cos() + e2 * phi.sin()) * rho)
            }
        }
    }
}
