//! Sphere–mesh contact detection (see the [parent module](super) for the rules).

use super::closest::{closest_point_triangle, Feature};
use super::TriMesh;
use glam::DVec3;

/// Most contacts one sphere can have with one mesh after merging (the
/// deepest are kept).
pub const MAX_MESH_CONTACTS: usize = 4;

/// Valid contacts gathered before the merge (the deepest are kept).
const GATHER: usize = 16;

/// Relative tolerance of the Voronoi-region tests, in favour of keeping a
/// contact (the merge removes the resulting near-duplicates).
const REGION_TOL: f64 = 1e-9;

/// One sphere–mesh contact, mesh frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshContact {
    /// Unit normal from the surface towards the sphere centre, mesh frame.
    pub normal: DVec3,
    /// Overlap, m (`r − distance`; ≤ 0 for a near miss within the margin).
    pub overlap: f64,
    /// Triangle the contact was found on.
    pub triangle: u32,
    /// Feature of that triangle.
    pub feature: Feature,
}

impl Default for MeshContact {
    fn default() -> Self {
        MeshContact {
            normal: DVec3::ZERO,
            overlap: 0.0,
            triangle: 0,
            feature: Feature::Face,
        }
    }
}

#[inline(always)]
fn rank(f: Feature) -> u8 {
    match f {
        Feature::Face => 0,
        Feature::Edge(_) => 1,
        Feature::Vertex(_) => 2,
    }
}

/// `a` goes before `b`: deeper first, then face < edge < vertex, then lower triangle.
#[inline(always)]
fn before(a: &MeshContact, b: &MeshContact) -> bool {
    if a.overlap != b.overlap {
        return a.overlap > b.overlap;
    }
    if rank(a.feature) != rank(b.feature) {
        return rank(a.feature) < rank(b.feature);
    }
    a.triangle < b.triangle
}

impl TriMesh {
    /// Contacts of a sphere with centre `x` (mesh frame, m) and radius `r`
    /// (m) within the extra distance `margin` ≥ 0 (m): one per contact
    /// patch (see the [module docs](super)), deepest first, at most
    /// [`MAX_MESH_CONTACTS`]. Writes into `out`, returns the count. No
    /// allocation.
    pub fn sphere_contacts(
        &self,
        x: DVec3,
        r: f64,
        margin: f64,
        out: &mut [MeshContact; MAX_MESH_CONTACTS],
    ) -> usize {
        let reach = r + margin;
        if !(reach > 0.0) {
            return 0;
        }
        let reach2 = reach * reach;
        let mut acc = [MeshContact::default(); GATHER];
        let mut n = 0usize;
        self.bvh.for_each_near(x, reach, |t| {
            let tri = self.triangles[t as usize];
            let [a, b, c] = self.corners(t);
            let (q, feature) = closest_point_triangle(x, a, b, c);
            let d = x - q;
            let d2 = d.length_squared();
            if d2 >= reach2 {
                return;
            }
            let contact = match feature {
                Feature::Face => {
                    // distance and normal from the plane, exactly as an analytic plane
                    let nrm = self.normals[t as usize];
                    let s = (x - a).dot(nrm);
                    let (normal, dist) = if s >= 0.0 { (nrm, s) } else { (-nrm, -s) };
                    MeshContact {
                        normal,
                        overlap: r - dist,
                        triangle: t,
                        feature,
                    }
                }
                Feature::Edge(k) => {
                    let (va, vb) = (tri[k as usize], tri[(k as usize + 1) % 3]);
                    let pa = self.vertices[va as usize];
                    // neighbours across the edge: the other triangles on both va and vb
                    for &t2 in self.vertex_triangles(va) {
                        if t2 == t {
                            continue;
                        }
                        let o = self.triangles[t2 as usize];
                        if !o.contains(&vb) {
                            continue;
                        }
                        let w = o
                            .iter()
                            .copied()
                            .find(|&i| i != va && i != vb)
                            .unwrap_or(va);
                        let e = self.vertices[w as usize] - pa;
                        if d.dot(e) > REGION_TOL * d2.sqrt() * e.length() {
                            return; // the centre is over the neighbouring face
                        }
                    }
                    let dist = d2.sqrt();
                    if dist == 0.0 {
                        return;
                    }
                    MeshContact {
                        normal: d / dist,
                        overlap: r - dist,
                        triangle: t,
                        feature,
                    }
                }
                Feature::Vertex(k) => {
                    let v = tri[k as usize];
                    let pv = self.vertices[v as usize];
                    for &t2 in self.vertex_triangles(v) {
                        for &w in &self.triangles[t2 as usize] {
                            if w == v {
                                continue;
                            }
                            let e = self.vertices[w as usize] - pv;
                            if d.dot(e) > REGION_TOL * d2.sqrt() * e.length() {
                                return; // an edge or face at v is closer
                            }
                        }
                    }
                    let dist = d2.sqrt();
                    if dist == 0.0 {
                        return;
                    }
                    MeshContact {
                        normal: d / dist,
                        overlap: r - dist,
                        triangle: t,
                        feature,
                    }
                }
            };
            if n < GATHER {
                acc[n] = contact;
                n += 1;
            } else {
                // full: replace the shallowest if this one is deeper
                let (wi, worst) = acc.iter().enumerate().fold((0, acc[0]), |m, (i, c)| {
                    if before(&m.1, c) {
                        (i, *c)
                    } else {
                        m
                    }
                });
                if before(&contact, &worst) {
                    acc[wi] = contact;
                }
            }
        });
        if n == 0 {
            return 0;
        }
        // insertion sort: deepest first (deterministic tie-breaks)
        for i in 1..n {
            let mut j = i;
            while j > 0 && before(&acc[j], &acc[j - 1]) {
                acc.swap(j, j - 1);
                j -= 1;
            }
        }
        let cos_merge = self.merge_angle.cos();
        let mut m = 0usize;
        for c in &acc[..n] {
            if out[..m].iter().any(|k| k.normal.dot(c.normal) > cos_merge) {
                continue;
            }
            out[m] = *c;
            m += 1;
            if m == MAX_MESH_CONTACTS {
                break;
            }
        }
        m
    }
}
