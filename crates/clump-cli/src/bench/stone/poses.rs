//! Initial poses of the stone cases (pile region, bed lattice) and the IC
//! file both codes read.

use super::*;

/// One body of the initial condition: its stone (template index), centre of
/// mass (m), quaternion mapping the stone file's frame (shifted to the
/// centre of mass) to the world, and vertical velocity (m/s).
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    /// Index of the body's stone among the case's stones.
    pub kind: usize,
    /// Centre of mass, m.
    pub x: DVec3,
    /// File frame → world.
    pub q: DQuat,
    /// Vertical velocity, m/s.
    pub vz: f64,
}

/// World sphere centres of `stone` at pose `p`.
pub(super) fn placed<'a>(stone: &'a Stone, p: &Pose) -> impl Iterator<Item = Sphere> + 'a {
    let (x, q) = (p.x, p.q);
    stone
        .spheres
        .iter()
        .map(move |s| Sphere::new(x + q * s.center, s.radius))
}

/// Whether any sphere of `a` overlaps any sphere of `b`.
pub(super) fn overlapping(a: &[Sphere], b: &[Sphere]) -> bool {
    a.iter().any(|s| {
        b.iter()
            .any(|t| (s.center - t.center).length_squared() < (s.radius + t.radius).powi(2))
    })
}

/// How many of `n` bodies each of the `fractions` gets (largest remainders,
/// ties to the first), as the list of kinds in the order given.
pub fn kinds_by_fraction(n: usize, fractions: &[f64]) -> Vec<usize> {
    let total: f64 = fractions.iter().sum();
    let exact: Vec<f64> = fractions.iter().map(|f| n as f64 * f / total).collect();
    let mut count: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
    let mut order: Vec<usize> = (0..fractions.len()).collect();
    order.sort_by(|&a, &b| {
        (exact[b] - exact[b].floor())
            .total_cmp(&(exact[a] - exact[a].floor()))
            .then(a.cmp(&b))
    });
    let short = n - count.iter().sum::<usize>();
    for &k in order.iter().take(short) {
        count[k] += 1;
    }
    count
        .iter()
        .enumerate()
        .flat_map(|(k, &c)| std::iter::repeat(k).take(c))
        .collect()
}

/// The pile's initial condition: a stone of each of `kinds` (indices into
/// `stones`) at a random pose in the tutorial's region (every sphere inside
/// the cylinder r = 0.25 m, 0.1 < z < 0.4 m), no two overlapping (random
/// sequential addition, seeded; the largest stones are placed first).
pub fn pile_poses(stones: &[Stone], kinds: &[usize], seed: u64) -> Result<Vec<Pose>> {
    let (rr, z0, z1) = PILE_REGION;
    let n = kinds.len();
    let mut kinds = kinds.to_vec();
    let rb = |k: usize| stones[k].template.bounding_radius;
    kinds.sort_by(|&a, &b| rb(b).total_cmp(&rb(a)).then(a.cmp(&b)));
    let rb_max = kinds.first().map_or(0.0, |&k| rb(k));
    let mut rng = Rng(seed);
    let mut poses: Vec<Pose> = Vec::new();
    let mut placed_spheres: Vec<Vec<Sphere>> = Vec::new();
    let mut tries = 0u64;
    while poses.len() < n {
        let kind = kinds[poses.len()];
        let stone = &stones[kind];
        tries += 1;
        if tries > 2_000_000 {
            bail!(
                "the pile's region (cylinder r = {rr} m, {z0} < z < {z1} m) holds only {} of {n} stones this size",
                poses.len()
            );
        }
        let x = DVec3::new(rng.range(-rr, rr), rng.range(-rr, rr), rng.range(z0, z1));
        let q = rng.quat();
        let p = Pose {
            kind,
            x,
            q,
            vz: PILE_VZ,
        };
        let sp: Vec<Sphere> = placed(stone, &p).collect();
        let inside = sp.iter().all(|s| {
            s.center.truncate().length() + s.radius <= rr
                && s.center.z - s.radius >= z0
                && s.center.z + s.radius <= z1
        });
        if !inside {
            continue;
        }
        let clash = poses
            .iter()
            .zip(&placed_spheres)
            .any(|(o, osp)| (o.x - x).length() < rb(kind) + rb_max && overlapping(&sp, osp));
        if clash {
            continue;
        }
        poses.push(p);
        placed_spheres.push(sp);
    }
    Ok(poses)
}

/// The bed's box: half sides along x and y (m) and the lattice cells.
#[derive(Debug, Clone, Copy)]
pub struct BedBox {
    /// Half side along x, m.
    pub hx: f64,
    /// Half side along y, m.
    pub hy: f64,
    /// Top of the lattice (the bed's domain height), m.
    pub top: f64,
}

/// The bed's loose lattice: stones along their principal axes (each turned by
/// a random half turn about x, y or z, or not at all), in cells of their
/// bounding box plus a 2 mm gap, jittered by up to ±0.8 mm, filling a box
/// of about 0.6 × 0.6 m layer by layer (the top layer a random subset).
pub fn bed_lattice(stone: &Stone, n: usize, seed: u64) -> (Vec<Pose>, BedBox) {
    let t = &stone.template;
    // body frame extents of the stone about its centre of mass
    let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
    for s in &t.spheres {
        lo = lo.min(s.center - DVec3::splat(s.radius));
        hi = hi.max(s.center + DVec3::splat(s.radius));
    }
    let ext = hi - lo;
    let mid = 0.5 * (hi + lo);
    // a half turn maps the box [lo, hi] to one of the same size: the cell
    // holds the largest extent in x and y both ways
    let cell = DVec3::new(ext.x, ext.y, ext.z) + DVec3::splat(BED_GAP);
    let nx = ((BED_SIDE / cell.x).floor() as usize).max(1);
    let ny = ((BED_SIDE / cell.y).floor() as usize).max(1);
    let per_layer = nx * ny;
    let layers = n.div_ceil(per_layer);
    let (hx, hy) = (0.5 * nx as f64 * cell.x, 0.5 * ny as f64 * cell.y);
    let mut rng = Rng(seed);
    let turns = [
        DQuat::IDENTITY,
        DQuat::from_rotation_x(std::f64::consts::PI),
        DQuat::from_rotation_y(std::f64::consts::PI),
        DQuat::from_rotation_z(std::f64::consts::PI),
    ];
    // body → world is turn; file → world is turn · input_to_body
    let mut poses = Vec::with_capacity(n);
    for k in 0..layers {
        let mut sites: Vec<(usize, usize)> =
            (0..nx).flat_map(|i| (0..ny).map(move |j| (i, j))).collect();
        let left = n - poses.len();
        if left < sites.len() {
            // a random subset, in lattice order
            for i in 0..sites.len() {
                let j = i + (rng.next_u64() % (sites.len() - i) as u64) as usize;
                sites.swap(i, j);
            }
            sites.truncate(left);
            sites.sort_unstable();
        }
        for (i, j) in sites {
            let turn = turns[(rng.next_u64() % 4) as usize];
            let centre = DVec3::new(
                -hx + (i as f64 + 0.5) * cell.x,
                -hy + (j as f64 + 0.5) * cell.y,
                (k as f64 + 0.5) * cell.z + 0.5 * BED_GAP,
            );
            let jitter = DVec3::new(
                rng.range(-0.8e-3, 0.8e-3),
                rng.range(-0.8e-3, 0.8e-3),
                rng.range(-0.8e-3, 0.8e-3),
            );
            // the turned stone's box is centred on turn · mid
            let x = centre + jitter - turn * mid;
            poses.push(Pose {
                kind: 0,
                x,
                q: (turn * t.input_to_body).normalize(),
                vz: 0.0,
            });
        }
    }
    let top = layers as f64 * cell.z + BED_GAP;
    (poses, BedBox { hx, hy, top })
}

/// Writes the initial condition `ic.csv` (Clump's CSV body file; the
/// template column is the stone's index among the scenario's templates).
pub fn write_ic(poses: &[Pose], path: &Path) -> Result<()> {
    let mut s = String::from("template,x,y,z,qw,qx,qy,qz,vz\n");
    for p in poses {
        writeln!(
            s,
            "{},{:.12e},{:.12e},{:.12e},{:.15},{:.15},{:.15},{:.15},{}",
            p.kind, p.x.x, p.x.y, p.x.z, p.q.w, p.q.x, p.q.y, p.q.z, p.vz
        )?;
    }
    std::fs::write(path, s).with_context(|| format!("writing {}", path.display()))
}

/// Reads an `ic.csv` written by [`write_ic`] (or by its earlier form
/// without the template column: one stone).
pub fn read_ic(path: &Path) -> Result<Vec<Pose>> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let mut out = Vec::new();
    for (i, l) in text.lines().enumerate().skip(1) {
        let v: Vec<f64> = l
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .with_context(|| format!("{}:{}: not a number", path.display(), i + 1))?;
        let (kind, v) = match v.len() {
            8 => (0, &v[..]),
            9 => (v[0] as usize, &v[1..]),
            _ => bail!("{}:{}: expected 8 or 9 columns", path.display(), i + 1),
        };
        out.push(Pose {
            kind,
            x: DVec3::new(v[0], v[1], v[2]),
            q: DQuat::from_xyzw(v[4], v[5], v[6], v[3]),
            vz: v[7],
        });
    }
    Ok(out)
}
