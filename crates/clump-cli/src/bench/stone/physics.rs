//! Final states of both codes and the physics compared (bed height,
//! packing fraction, contacts).

use super::*;

/// Final sphere centres of one code, with their bodies.
#[derive(Debug, Clone, Default)]
pub struct FinalState {
    /// Sphere centres, m.
    pub pos: Vec<DVec3>,
    /// Radii, m.
    pub rad: Vec<f64>,
    /// Body of each sphere (0-based, in initial-condition order).
    pub body: Vec<usize>,
}

/// The final state in a LIGGGHTS-format dump (`id x y z radius`, sorted by
/// id), LIGGGHTS' or Clump's (`clump bench --dump`): both number the spheres
/// of each body consecutively, bodies in insertion order, and `per_body`
/// are the bodies' sphere counts in that order.
pub(super) fn final_from_dump(path: &Path, per_body: &[usize]) -> Result<FinalState> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let lines: Vec<&str> = text.lines().collect();
    let head = lines
        .iter()
        .rposition(|l| l.starts_with("ITEM: ATOMS"))
        .with_context(|| format!("{}: no ITEM: ATOMS", path.display()))?;
    let cols: Vec<&str> = lines[head].split_whitespace().skip(2).collect();
    let col = |n: &str| cols.iter().position(|c| *c == n);
    let (ci, cx, cy, cz, cr) = match (col("id"), col("x"), col("y"), col("z"), col("radius")) {
        (Some(a), Some(b), Some(c), Some(d), Some(e)) => (a, b, c, d, e),
        _ => bail!("{}: expected columns id x y z radius", path.display()),
    };
    let mut rows: Vec<(usize, DVec3, f64)> = Vec::new();
    for l in &lines[head + 1..] {
        let v: Vec<f64> = l
            .split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect();
        if v.len() < cols.len() {
            continue;
        }
        rows.push((v[ci] as usize, DVec3::new(v[cx], v[cy], v[cz]), v[cr]));
    }
    rows.sort_by_key(|r| r.0);
    // the body of sphere id k (1-based): the first whose spheres end past it
    let ends: Vec<usize> = per_body
        .iter()
        .scan(0, |acc, &c| {
            *acc += c;
            Some(*acc)
        })
        .collect();
    let mut f = FinalState::default();
    for (id, x, r) in rows {
        f.pos.push(x);
        f.rad.push(r);
        f.body.push(ends.partition_point(|&e| e < id));
    }
    Ok(f)
}

/// Physics of a final state, computed the same way for both codes.
#[derive(Debug, Clone, Copy, Default)]
pub struct Physics {
    /// Bodies present.
    pub bodies: usize,
    /// Mean height of the sphere centres, m.
    pub mean_z: f64,
    /// Surface height: mean over 40 mm columns of the footprint (those
    /// holding a sphere) of the highest sphere top, m.
    pub surface: f64,
    /// Bulk packing fraction: bodies × mean body volume / (footprint ×
    /// surface).
    pub phi: f64,
    /// Overlapping sphere pairs of different bodies.
    pub sphere_contacts: usize,
    /// Body pairs with at least one overlapping sphere pair.
    pub body_contacts: usize,
}

/// Bed height, packing fraction and contacts of `f` (`body_volume`: the
/// bodies' mean volume, m³; `footprint`: floor area under the bed, m², for
/// the packing fraction).
pub fn physics(f: &FinalState, body_volume: f64, footprint: f64) -> Physics {
    let n = f.pos.len();
    if n == 0 {
        return Physics::default();
    }
    let bodies = f.body.iter().copied().max().map_or(0, |b| b + 1);
    let mean_z = f.pos.iter().map(|p| p.z).sum::<f64>() / n as f64;
    // surface columns
    let col = 0.04;
    let mut tops: std::collections::HashMap<(i64, i64), f64> = Default::default();
    for (p, r) in f.pos.iter().zip(&f.rad) {
        let key = ((p.x / col).floor() as i64, (p.y / col).floor() as i64);
        let t = tops.entry(key).or_insert(f64::MIN);
        *t = t.max(p.z + r);
    }
    let surface = tops.values().sum::<f64>() / tops.len() as f64;
    let phi = bodies as f64 * body_volume / (footprint * surface);
    // contacts: a cell list of side 2 r_max
    let rmax = f.rad.iter().copied().fold(0.0, f64::max);
    let h = 2.0 * rmax;
    let mut cells: std::collections::HashMap<(i64, i64, i64), Vec<usize>> = Default::default();
    let key = |p: DVec3| {
        (
            (p.x / h).floor() as i64,
            (p.y / h).floor() as i64,
            (p.z / h).floor() as i64,
        )
    };
    for (i, p) in f.pos.iter().enumerate() {
        cells.entry(key(*p)).or_default().push(i);
    }
    let mut sphere_contacts = 0;
    let mut pairs = std::collections::HashSet::new();
    for (i, p) in f.pos.iter().enumerate() {
        let (a, b, c) = key(*p);
        for da in -1..=1 {
            for db in -1..=1 {
                for dc in -1..=1 {
                    if let Some(list) = cells.get(&(a + da, b + db, c + dc)) {
                        for &j in list {
                            if j <= i || f.body[i] == f.body[j] {
                                continue;
                            }
                            let d = (f.pos[j] - *p).length();
                            if d < f.rad[i] + f.rad[j] {
                                sphere_contacts += 1;
                                pairs.insert((f.body[i].min(f.body[j]), f.body[i].max(f.body[j])));
                            }
                        }
                    }
                }
            }
        }
    }
    Physics {
        bodies,
        mean_z,
        surface,
        phi,
        sphere_contacts,
        body_contacts: pairs.len(),
    }
}
