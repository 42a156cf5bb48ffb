//! Free-space queries for insertion: a uniform hash grid over sphere centres
//! (with periodic images) and wall checks.

use super::region::Region;
use crate::wall::{TriMesh, Wall, WallTouch, MAX_TOUCHES_PER_WALL};
use crate::world::World;
use glam::{DQuat, DVec3};
use std::collections::HashMap;

/// Spheres that may overlap a candidate inside a region.
pub(crate) struct Occupancy {
    inv_cell: f64,
    lo: DVec3,
    hi: DVec3,
    images: Vec<DVec3>,
    map: HashMap<[i64; 3], Vec<u32>>,
    center: Vec<DVec3>,
    radius: Vec<f64>,
}

impl Occupancy {
    /// An occupancy grid for candidates inside `region` whose spheres have
    /// radius ≤ `candidate_max_radius`, filled with the current spheres of
    /// every body of `world` (computed from the body poses, so bodies added
    /// since the last step count too). A world split over ranks gathers the
    /// owned spheres near the region from every rank (a collective call);
    /// the answers of [`Self::overlaps`] do not depend on their order.
    pub(crate) fn from_world(
        world: &mut World,
        region: &Region,
        candidate_max_radius: f64,
    ) -> Self {
        let rmax = candidate_max_radius.max(world.max_radius()).max(1e-300);
        let (rlo, rhi) = region.bounds();
        let margin = candidate_max_radius + world.max_radius();
        let d = world.config.domain;
        let l = d.size();
        let mut images = vec![DVec3::ZERO];
        for a in 0..3 {
            if d.periodic[a] {
                let n = images.len();
                for k in 0..n {
                    for s in [-1.0, 1.0] {
                        let mut v = images[k];
                        v[a] += s * l[a];
                        images.push(v);
                    }
                }
            }
        }
        let mut occ = Occupancy {
            inv_cell: 1.0 / (2.0 * rmax),
            lo: rlo - margin,
            hi: rhi + margin,
            images,
            map: HashMap::new(),
            center: Vec::new(),
            radius: Vec::new(),
        };
        for (c, r) in world.spheres_near(|c| occ.near(c)) {
            occ.insert(c, r);
        }
        occ
    }

    /// True when a periodic image of `c` (world frame, m) lies where
    /// [`Self::insert`] keeps it.
    fn near(&self, c: DVec3) -> bool {
        self.images.iter().any(|&i| {
            let x = c + i;
            x.cmpge(self.lo).all() && x.cmple(self.hi).all()
        })
    }

    fn key(&self, x: DVec3) -> [i64; 3] {
        let c = (x - self.lo) * self.inv_cell;
        [c.x.floor() as i64, c.y.floor() as i64, c.z.floor() as i64]
    }

    /// Adds a sphere (and its periodic images near the region).
    pub(crate) fn insert(&mut self, c: DVec3, r: f64) {
        for k in 0..self.images.len() {
            let x = c + self.images[k];
            if x.cmpge(self.lo).all() && x.cmple(self.hi).all() {
                let idx = self.center.len() as u32;
                self.center.push(x);
                self.radius.push(r);
                let key = self.key(x);
                self.map.entry(key).or_default().push(idx);
            }
        }
    }

    /// True when a sphere at `c` with radius `r` (≤ the candidate maximum)
    /// overlaps any stored sphere (touching is allowed).
    pub(crate) fn overlaps(&self, c: DVec3, r: f64) -> bool {
        let k = self.key(c);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.map.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &j in list {
                            let j = j as usize;
                            let rr = r + self.radius[j];
                            if (c - self.center[j]).length_squared() < rr * rr {
                                return true;
                            }
                        }
                    }
                }
            }
        }
        false
    }
}

/// True when a sphere at `c` with radius `r` touches any active wall
/// (`meshes`: the world's mesh table, for mesh walls).
pub(crate) fn touches_walls(walls: &[Wall], meshes: &[TriMesh], c: DVec3, r: f64) -> bool {
    let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
    walls
        .iter()
        .any(|w| w.active && w.shape.contacts(meshes, c, r, 0.0, &mut buf) > 0)
}

/// World-frame spheres (centre, radius) of a template's spheres scaled by
/// `scale`, for a body at `x` with orientation `q`; written into `out`.
pub(crate) fn body_spheres(
    t: &crate::shape::ClumpTemplate,
    scale: f64,
    x: DVec3,
    q: DQuat,
    out: &mut Vec<(DVec3, f64)>,
) {
    out.clear();
    out.extend(
        t.spheres
            .iter()
            .map(|s| (x + q * (s.center * scale), s.radius * scale)),
    );
}

/// True when all spheres lie in the region, touch no active wall and
/// overlap no stored sphere.
pub(crate) fn fits(
    spheres: &[(DVec3, f64)],
    region: &Region,
    world: &World,
    occ: &Occupancy,
) -> bool {
    spheres.iter().all(|&(c, r)| region.contains_sphere(c, r))
        && !spheres
            .iter()
            .any(|&(c, r)| touches_walls(&world.walls, &world.walls.meshes, c, r))
        && !spheres.iter().any(|&(c, r)| occ.overlaps(c, r))
}
