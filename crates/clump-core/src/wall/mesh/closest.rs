//! Closest point of a triangle to a point, with the feature (face, edge or
//! vertex) it lies on.
//!
//! Ericson, *Real-Time Collision Detection* (2005), §5.1.5
//! `ClosestPtPointTriangle`: the Voronoi regions of the three vertices, then
//! of the three edges, are tested with barycentric dot products; otherwise
//! the point projects inside the face. Boundaries (`≤`, `≥`) go to the
//! lower-dimensional feature, so a point that projects exactly onto an edge
//! is classified as that edge.

use glam::DVec3;

/// The feature of a triangle `[v0, v1, v2]` that a closest point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    /// The interior of the face.
    Face,
    /// The interior of edge `k`, from local vertex `k` to local vertex `(k + 1) % 3`.
    Edge(u8),
    /// Local vertex `k` (0, 1, 2).
    Vertex(u8),
}

/// Closest point to `p` on the triangle `(a, b, c)` and its feature. All
/// points in the same frame (any), same length unit.
#[inline]
pub fn closest_point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, Feature) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Feature::Vertex(0));
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, Feature::Edge(0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, Feature::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    (a + ab * v + ac * w, Feature::Face)
}

/// Squared distance from `p` to the axis-aligned box `[lo, hi]` (0 inside).
#[inline(always)]
pub fn aabb_distance2(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    let d = (lo - p).max(DVec3::ZERO).max(p - hi);
    d.length_squared()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let (q, f) = closest_point_triangle(DVec3::new(0.2, 0.2, 1.0), a, b, c);
        assert!(f == Feature::Face && (q - DVec3::new(0.2, 0.2, 0.0)).length() < 1e-15);
        assert_eq!(
            closest_point_triangle(DVec3::new(-1.0, -1.0, 1.0), a, b, c).1,
            Feature::Vertex(0)
        );
        assert_eq!(
            closest_point_triangle(DVec3::new(2.0, -0.1, 0.0), a, b, c).1,
            Feature::Vertex(1)
        );
        assert_eq!(
            closest_point_triangle(DVec3::new(-0.1, 2.0, 0.0), a, b, c).1,
            Feature::Vertex(2)
        );
        assert_eq!(
            closest_point_triangle(DVec3::new(0.5, -1.0, 0.3), a, b, c),
            (DVec3::new(0.5, 0.0, 0.0), Feature::Edge(0))
        );
        assert_eq!(
            closest_point_triangle(DVec3::new(1.0, 1.0, 0.0), a, b, c).1,
            Feature::Edge(1)
        );
        assert_eq!(
            closest_point_triangle(DVec3::new(-1.0, 0.5, 0.0), a, b, c),
            (DVec3::new(0.0, 0.5, 0.0), Feature::Edge(2))
        );
    }
}
