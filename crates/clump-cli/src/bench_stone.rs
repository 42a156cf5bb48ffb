//! `clump bench --case stone-pile | stone-bed`: many-sphere asymmetric
//! stones, side by side with LIGGGHTS, both codes starting from the same
//! initial condition (the tetra-bed way).
//!
//! The stone is LIGGGHTS' own `stone1.multisphere` (50 spheres, radii 2.8 to
//! 10.4 mm, about 56 × 22 × 41 mm; GPL data of Debian's `liggghts-doc`, read
//! from the install and never shipped), or a procedurally made stone of the
//! same size and sphere count (`--stone procedural`), or any `x y z r` file
//! in mm. Material and contact are those of LIGGGHTS' tutorial
//! `multisphere_stone_restitution`: E = 10 MPa, ν = 0.45, ρ = 2500 kg/m³,
//! e = 0.3, μ = 0.5, Hertz–Mindlin with history, dt = 1e-5 s, LIGGGHTS'
//! damping law and no tensile clamp (`limitForce off`), Richardson rotation
//! (LIGGGHTS' `fix multisphere` scheme).
//!
//! The bench writes, in `--work`: the stone shifted to its centre of mass
//! (`stone.xyzr`, m; both codes read it, and LIGGGHTS gets Clump's exact mass
//! and inertia tensor so that both integrate the same body, instead of its
//! Monte-Carlo estimate), the initial condition (`ic.csv`: centre of mass,
//! quaternion mapping the file frame to the world, vz), the Clump scenario
//! (`scenario.toml`) and the LIGGGHTS input (`liggghts/in.stone`, with
//! `liggghts/ins.in` placing each stone at its pose).
//!
//! - **stone pile**: `--stones` (200) stones at random poses (seeded, no two
//!   overlapping) in the tutorial's insertion region, the cylinder r = 0.25 m,
//!   0.1 < z < 0.4 m, moving down at 1 m/s, fall into a cylinder r = 0.26 m
//!   on the floor z = 0. Phase A: the fall; phase B: the pile, timed on its own.
//! - **stone bed**: `--stones` (2000) stones on a loose lattice (each stone
//!   along its principal axes, turned by a random half turn, jittered) in a
//!   box of about 0.6 × 0.6 m are settled by Clump alone (`--bed-settle`
//!   steps; the settled poses are kept in `--work` and reused), and both
//!   codes start from the settled poses at rest: phase A re-settles (the
//!   contact histories start from zero), phase B is the dense bed, timed on
//!   its own.
//!
//! After the rounds the bench compares the physics of the two codes' final
//! states (the last round's): bed height, packing fraction and contacts,
//! computed the same way from the final sphere centres of both.

use crate::cmd_bench::{
    median, peak_rss_mb, report, run_liggghts_input, which, BenchArgs, Figures,
};
use anyhow::{bail, Context, Result};
use clump_core::shape::sphere::Sphere;
use clump_core::shape::template::ClumpTemplate;
use glam::{DQuat, DVec3};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// LIGGGHTS' stone of the tutorial `multisphere_stone_restitution` (Debian
/// `liggghts-doc`), 50 spheres in mm.
pub const LIGGGHTS_STONE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution/data/stone1.multisphere";

/// The stone cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StoneCase {
    /// Stones falling into a cylinder.
    Pile,
    /// A dense bed of stones in a box.
    Bed,
}

impl StoneCase {
    fn name(self) -> &'static str {
        match self {
            StoneCase::Pile => "stone-pile",
            StoneCase::Bed => "stone-bed",
        }
    }
}

/// Density of the stone, kg/m³ (the tutorial's).
const DENSITY: f64 = 2500.0;
/// Radius of the pile's container, m.
const PILE_WALL_RADIUS: f64 = 0.26;
/// The tutorial's insertion region: cylinder radius, bottom and top, m.
const PILE_REGION: (f64, f64, f64) = (0.25, 0.1, 0.4);
/// Initial velocity of the pile's stones, m/s (the tutorial's).
const PILE_VZ: f64 = -1.0;
/// Side of the bed's box footprint, m (about).
const BED_SIDE: f64 = 0.6;
/// Gap between lattice cells of the bed, m.
const BED_GAP: f64 = 0.002;
/// LIGGGHTS' neighbour skin, m (the tutorial's 4 mm is 1.4 smallest radii;
/// 1 mm keeps its lists as lean as Clump's).
const LIGGGHTS_SKIN: f64 = 0.001;

/// The stone: spheres in the input frame shifted to the centre of mass (m),
/// and its mass properties.
#[derive(Debug, Clone)]
pub struct Stone {
    /// Where it came from (for the report).
    pub source: String,
    /// Spheres, m, input frame with the centre of mass at the origin.
    pub spheres: Vec<Sphere>,
    /// Mass properties (exact, Clump's).
    pub template: ClumpTemplate,
}

/// Reads or makes the stone of `--stone`: `liggghts` (the tutorial's, from
/// Debian's liggghts-doc), `procedural`, or a path to an `x y z r` file in mm.
pub fn load_stone(spec: &str) -> Result<Stone> {
    let (source, mm) = match spec {
        "procedural" => (
            "procedural (seeded, 50 spheres)".to_string(),
            procedural_stone(50, 7),
        ),
        _ => {
            let path = if spec == "liggghts" {
                LIGGGHTS_STONE
            } else {
                spec
            };
            if !Path::new(path).is_file() {
                if spec == "liggghts" {
                    bail!(
                        "LIGGGHTS' stone template {path} is missing: it ships with Debian's liggghts-doc \
                         (apt-get install liggghts-doc; GPL data, so Clump does not ship it). \
                         Use --stone procedural for the shipped stand-in of the same size and sphere count, \
                         or --stone FILE for an `x y z r` file in mm"
                    );
                }
                bail!("--stone: no stone template file at {path} (give `liggghts`, `procedural` or a file of `x y z r` rows in mm)");
            }
            let s = clump_io::template_file::read_template_file(Path::new(path))
                .map_err(|e| anyhow::anyhow!("--stone: {e}"))?;
            (path.to_string(), s)
        }
    };
    if mm.is_empty() {
        bail!("--stone: {source} holds no spheres");
    }
    let raw: Vec<Sphere> = mm
        .iter()
        .map(|s| Sphere::new(s.center * 1e-3, s.radius * 1e-3))
        .collect();
    let t0 = ClumpTemplate::from_spheres("stone", &raw, DENSITY)
        .map_err(|e| anyhow::anyhow!("--stone {source}: {e}"))?;
    let spheres: Vec<Sphere> = raw
        .iter()
        .map(|s| Sphere::new(s.center - t0.input_center_of_mass, s.radius))
        .collect();
    let template = ClumpTemplate::from_spheres("stone", &spheres, DENSITY)
        .map_err(|e| anyhow::anyhow!("--stone {source}: {e}"))?;
    Ok(Stone {
        source,
        spheres,
        template,
    })
}

/// SplitMix64: a tiny seeded generator, so that the initial conditions and
/// the procedural stone are the same on every machine.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn f(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f()
    }
    /// Uniform random rotation (Shoemake), scalar part ≥ 0.
    fn quat(&mut self) -> DQuat {
        let (u1, u2, u3) = (self.f(), self.f(), self.f());
        let tau = std::f64::consts::TAU;
        let q = DQuat::from_xyzw(
            (1.0 - u1).sqrt() * (tau * u2).sin(),
            (1.0 - u1).sqrt() * (tau * u2).cos(),
            u1.sqrt() * (tau * u3).sin(),
            u1.sqrt() * (tau * u3).cos(),
        )
        .normalize();
        if q.w < 0.0 {
            -q
        } else {
            q
        }
    }
}

/// A procedurally made stone, mm: `n` spheres of radii 2.8 to 10.4 mm
/// inside an ellipsoid of semi-axes 28 × 11 × 20.5 mm (LIGGGHTS' stone's
/// bounding box is 56 × 22 × 41 mm and its radii span 2.8 to 10.4 mm), each
/// sphere touching or overlapping the ones before it (one connected body).
pub fn procedural_stone(n: usize, seed: u64) -> Vec<Sphere> {
    let axes = DVec3::new(28.0, 11.0, 20.5);
    let mut rng = Rng(seed);
    let mut out: Vec<Sphere> = Vec::with_capacity(n);
    while out.len() < n {
        let r = rng.range(2.8, 10.4);
        let room = axes - DVec3::splat(r);
        let u = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if u.length_squared() > 1.0 {
            continue;
        }
        let c = u * room;
        let joined = out.is_empty()
            || out
                .iter()
                .any(|s| (s.center - c).length() < s.radius + r - 0.5 * r.min(s.radius));
        if joined {
            out.push(Sphere::new(c, r));
        }
    }
    out
}

/// One body of the initial condition: centre of mass (m), quaternion mapping
/// the stone file's frame (shifted to the centre of mass) to the world, and
/// vertical velocity (m/s).
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    /// Centre of mass, m.
    pub x: DVec3,
    /// File frame → world.
    pub q: DQuat,
    /// Vertical velocity, m/s.
    pub vz: f64,
}

/// World sphere centres of `stone` at pose `p`.
fn placed<'a>(stone: &'a Stone, p: &Pose) -> impl Iterator<Item = Sphere> + 'a {
    let (x, q) = (p.x, p.q);
    stone
        .spheres
        .iter()
        .map(move |s| Sphere::new(x + q * s.center, s.radius))
}

/// Whether any sphere of `a` overlaps any sphere of `b`.
fn overlapping(a: &[Sphere], b: &[Sphere]) -> bool {
    a.iter().any(|s| {
        b.iter()
            .any(|t| (s.center - t.center).length_squared() < (s.radius + t.radius).powi(2))
    })
}

/// The pile's initial condition: `n` stones at random poses in the tutorial's
/// region (every sphere inside the cylinder r = 0.25 m, 0.1 < z < 0.4 m), no
/// two overlapping (random sequential addition, seeded).
pub fn pile_poses(stone: &Stone, n: usize, seed: u64) -> Result<Vec<Pose>> {
    let (rr, z0, z1) = PILE_REGION;
    let rb = stone.template.bounding_radius;
    let mut rng = Rng(seed);
    let mut poses: Vec<Pose> = Vec::new();
    let mut placed_spheres: Vec<Vec<Sphere>> = Vec::new();
    let mut tries = 0u64;
    while poses.len() < n {
        tries += 1;
        if tries > 2_000_000 {
            bail!(
                "the pile's region (cylinder r = {rr} m, {z0} < z < {z1} m) holds only {} of {n} stones this size",
                poses.len()
            );
        }
        let x = DVec3::new(rng.range(-rr, rr), rng.range(-rr, rr), rng.range(z0, z1));
        let q = rng.quat();
        let p = Pose { x, q, vz: PILE_VZ };
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
            .any(|(o, osp)| (o.x - x).length() < 2.0 * rb && overlapping(&sp, osp));
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
                x,
                q: (turn * t.input_to_body).normalize(),
                vz: 0.0,
            });
        }
    }
    let top = layers as f64 * cell.z + BED_GAP;
    (poses, BedBox { hx, hy, top })
}

/// The files of one stone case, written into a folder.
#[derive(Debug, Clone)]
pub struct CaseFiles {
    /// The Clump scenario.
    pub scenario: PathBuf,
    /// The LIGGGHTS folder (`in.stone`, `ins.in`, `stone.xyzr`).
    pub liggghts: PathBuf,
}

/// Writes `stone.xyzr` (m, centred on the centre of mass).
fn write_stone(stone: &Stone, path: &Path) -> Result<()> {
    let mut s = String::from("# x y z r (m), centre of mass at the origin\n");
    for sp in &stone.spheres {
        writeln!(
            s,
            "{:.15e} {:.15e} {:.15e} {:.15e}",
            sp.center.x, sp.center.y, sp.center.z, sp.radius
        )?;
    }
    std::fs::write(path, s).with_context(|| format!("writing {}", path.display()))
}

/// Writes the initial condition `ic.csv` (Clump's CSV body file).
pub fn write_ic(poses: &[Pose], path: &Path) -> Result<()> {
    let mut s = String::from("x,y,z,qw,qx,qy,qz,vz\n");
    for p in poses {
        writeln!(
            s,
            "{:.12e},{:.12e},{:.12e},{:.15},{:.15},{:.15},{:.15},{}",
            p.x.x, p.x.y, p.x.z, p.q.w, p.q.x, p.q.y, p.q.z, p.vz
        )?;
    }
    std::fs::write(path, s).with_context(|| format!("writing {}", path.display()))
}

/// Reads an `ic.csv` written by [`write_ic`].
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
        if v.len() != 8 {
            bail!("{}:{}: expected 8 columns", path.display(), i + 1);
        }
        out.push(Pose {
            x: DVec3::new(v[0], v[1], v[2]),
            q: DQuat::from_xyzw(v[4], v[5], v[6], v[3]),
            vz: v[7],
        });
    }
    Ok(out)
}

/// The geometry of a case: walls and domain.
#[derive(Debug, Clone, Copy)]
enum Geometry {
    /// Floor and a cylinder r = [`PILE_WALL_RADIUS`].
    Pile,
    /// Floor and four side walls.
    Bed(BedBox),
}

impl Geometry {
    /// Domain corners, m.
    fn domain(self) -> (DVec3, DVec3) {
        match self {
            Geometry::Pile => {
                let r = PILE_WALL_RADIUS + 0.01;
                (DVec3::new(-r, -r, -0.01), DVec3::new(r, r, 0.5))
            }
            Geometry::Bed(b) => (
                DVec3::new(-b.hx - 0.01, -b.hy - 0.01, -0.01),
                DVec3::new(b.hx + 0.01, b.hy + 0.01, b.top + 0.05),
            ),
        }
    }
}

/// Writes the Clump scenario and the LIGGGHTS input of a case whose initial
/// condition is `poses`, into `dir`.
fn write_case(
    dir: &Path,
    stone: &Stone,
    poses: &[Pose],
    geometry: Geometry,
    na: u64,
    nb: u64,
    liggghts_tangential: bool,
) -> Result<CaseFiles> {
    std::fs::create_dir_all(dir.join("liggghts"))
        .with_context(|| format!("creating {}", dir.join("liggghts").display()))?;
    write_stone(stone, &dir.join("stone.xyzr"))?;
    write_stone(stone, &dir.join("liggghts/stone.xyzr"))?;
    write_ic(poses, &dir.join("ic.csv"))?;
    let (lo, hi) = geometry.domain();
    // --- Clump
    let mut sc = String::new();
    writeln!(
        sc,
        "# Generated by `clump bench` (stone case; see crates/clump-cli/src/bench_stone.rs).\n\
         # Stone: {}, {} spheres, mass {:.6e} kg.\n\
         [simulation]\ndt = 1e-5\ngravity = [0.0, 0.0, -9.81]\nmax_overlap_ratio = 0.8\n\n\
         [domain]\nlo = [{}, {}, {}]\nhi = [{}, {}, {}]\n\n\
         [integrator]\nrotation = \"richardson\"\n\n\
         [[material]]\nname = \"stone\"\nyoungs_modulus = 1e7\npoisson_ratio = 0.45\ndensity = {DENSITY}\n\n\
         [contact]\nlaw = \"hertz\"\ndamping = \"liggghts\"\nrestitution = 0.3\nfriction = 0.5\ntensile = true\n{}\n\
         [[template]]\nname = \"stone\"\nmaterial = \"stone\"\nfile = \"stone.xyzr\"\n\n\
         [[insert]]\nkind = \"file\"\nstage = \"fall\"\nfile = \"ic.csv\"\nformat = \"csv\"\ntemplate = \"stone\"\norientation_frame = \"input\"\n\n\
         [[wall]]\nname = \"floor\"\nmaterial = \"stone\"\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n",
        stone.source,
        stone.spheres.len(),
        stone.template.mass,
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z,
        if liggghts_tangential {
            "tangential = \"liggghts\"\n"
        } else {
            ""
        },
    )?;
    match geometry {
        Geometry::Pile => writeln!(
            sc,
            "\n[[wall]]\nname = \"cylinder\"\nmaterial = \"stone\"\ntype = \"cylinder\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = {PILE_WALL_RADIUS}\ninside = true"
        )?,
        Geometry::Bed(b) => {
            for (name, p, nrm) in [
                ("xlo", [-b.hx, 0.0], [1.0, 0.0]),
                ("xhi", [b.hx, 0.0], [-1.0, 0.0]),
                ("ylo", [0.0, -b.hy], [0.0, 1.0]),
                ("yhi", [0.0, b.hy], [0.0, -1.0]),
            ] {
                writeln!(
                    sc,
                    "\n[[wall]]\nname = \"{name}\"\nmaterial = \"stone\"\ntype = \"plane\"\npoint = [{:?}, {:?}, 0.0]\nnormal = [{:?}, {:?}, 0.0]",
                    p[0], p[1], nrm[0], nrm[1]
                )?;
            }
        }
    }
    writeln!(
        sc,
        "\n[[stage]]\nname = \"fall\"\nsteps = {na}\n\n[[stage]]\nname = \"dense\"\nsteps = {nb}"
    )?;
    let scenario = dir.join("scenario.toml");
    std::fs::write(&scenario, sc)?;
    // --- LIGGGHTS
    let m = stone.template.mass;
    let i = stone.template.properties.inertia;
    let walls = match geometry {
        Geometry::Pile => format!(
            "fix w1 all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n\
             fix w2 all wall/gran model hertz tangential history primitive type 1 zcylinder {PILE_WALL_RADIUS} 0. 0.\n"
        ),
        Geometry::Bed(b) => format!(
            "fix w1 all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n\
             fix w2 all wall/gran model hertz tangential history primitive type 1 xplane {}\n\
             fix w3 all wall/gran model hertz tangential history primitive type 1 xplane {}\n\
             fix w4 all wall/gran model hertz tangential history primitive type 1 yplane {}\n\
             fix w5 all wall/gran model hertz tangential history primitive type 1 yplane {}\n",
            -b.hx, b.hx, -b.hy, b.hy
        ),
    };
    let input = format!(
        "# Generated by `clump bench` (stone case), LIGGGHTS-PUBLIC 3.8.0.\n\
         # vars: NA (phase A steps), NB (phase B steps)\n\
         atom_style\tsphere\natom_modify\tmap array sort 0 0\nboundary\tf f f\nnewton\t\toff\n\
         communicate\tsingle vel yes\nprocessors\t1 1 1\nunits\t\tsi\n\n\
         region\t\treg block {} {} {} {} {} {} units box\ncreate_box\t1 reg\n\n\
         neighbor\t{LIGGGHTS_SKIN} bin\nneigh_modify\tdelay 0\n\n\
         fix \t\tm1 all property/global youngsModulus peratomtype 1.e7\n\
         fix \t\tm2 all property/global poissonsRatio peratomtype 0.45\n\
         fix \t\tm3 all property/global coefficientRestitution peratomtypepair 1 0.3\n\
         fix \t\tm4 all property/global coefficientFriction peratomtypepair 1 0.5\n\n\
         pair_style\tgran model hertz tangential history\npair_coeff\t* *\ntimestep\t0.00001\n\n\
         {walls}\n\
         # the stone centred on its centre of mass, with Clump's exact mass and inertia tensor (file frame)\n\
         fix\t\tpts1 all particletemplate/multisphere 15485863 atom_type 1 density constant {DENSITY} nspheres {} ntry 1000000 spheres file stone.xyzr scale 1.0 type 1 mass {:.9e} inertia_tensor {:.9e} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e} use_density\n\
         fix\t\tpdd1 all particledistribution/discrete 15485867 1 pts1 1.0\n\n\
         fix\t\tintegr all multisphere\n\n\
         thermo_style\tcustom step atoms\nthermo\t\t1\n\
         # every stone at its pose of the common initial condition (gravity off meanwhile)\n\
         include\t\tins.in\nreset_timestep\t0\n\n\
         fix\t\tgravi all gravity 9.81 vector 0.0 0.0 -1.0\n\
         compute\t\tke all ke/multisphere\n\
         thermo_style\tcustom step atoms c_ke\nthermo\t\t1000\nthermo_modify\tlost ignore norm no\n\n\
         # phase A\nrun\t\t${{NA}}\n# phase B, timed on its own\nrun\t\t${{NB}}\n\
         dump\t\tdfin all custom 1 final.dump id x y z radius\ndump_modify\tdfin sort id\nrun\t\t0\n",
        lo.x,
        hi.x,
        lo.y,
        hi.y,
        lo.z,
        hi.z,
        stone.spheres.len(),
        m,
        i.x_axis.x,
        i.y_axis.x,
        i.z_axis.x,
        i.y_axis.y,
        i.z_axis.y,
        i.z_axis.z,
    );
    let lig = dir.join("liggghts");
    std::fs::write(lig.join("in.stone"), input)?;
    std::fs::write(lig.join("ins.in"), liggghts_insertions(poses, 500))?;
    Ok(CaseFiles {
        scenario,
        liggghts: lig,
    })
}

/// LIGGGHTS commands placing each body at its pose (one `insert/pack` in a
/// tiny region per body, `run 1` per chunk), as the tetra bed's
/// gen_liggghts.py.
pub fn liggghts_insertions(poses: &[Pose], chunk: usize) -> String {
    let h = 1e-9;
    let mut f = String::new();
    for (c, part) in poses.chunks(chunk).enumerate() {
        let mut ids = Vec::new();
        for (k, p) in part.iter().enumerate() {
            let i = c * chunk + k + 1;
            let (x, q) = (p.x, p.q);
            let _ = writeln!(
                f,
                "region r{i} block {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} units box volume_limit 1e-30",
                x.x - h,
                x.x + h,
                x.y - h,
                x.y + h,
                x.z - h,
                x.z + h
            );
            let _ = writeln!(
                f,
                "fix i{i} all insert/pack seed 10007 distributiontemplate pdd1 verbose no maxattempt 1 insert_every once overlapcheck no all_in no vel constant 0. 0. {} orientation constant {:.15} {:.15} {:.15} {:.15} region r{i} particles_in_region 1 ntry_mc 1001",
                p.vz, q.w, q.x, q.y, q.z
            );
            ids.push(i);
        }
        f.push_str("run 1\n");
        for i in ids {
            let _ = writeln!(f, "unfix i{i}");
        }
    }
    f
}

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

/// The final state of a Clump world (bodies in id order = IC order).
fn clump_final(w: &clump_core::world::World) -> FinalState {
    let sp = w.spheres();
    let mut order: Vec<usize> = (0..w.bodies.len()).collect();
    order.sort_by_key(|&b| w.bodies.id[b]);
    let mut f = FinalState::default();
    for (k, b) in order.into_iter().enumerate() {
        for s in sp.of_body(b) {
            f.pos.push(sp.position(s));
            f.rad.push(sp.radius[s]);
            f.body.push(k);
        }
    }
    f
}

/// The final state in a LIGGGHTS dump (`id x y z radius`, sorted by id;
/// LIGGGHTS numbers the spheres of each inserted body consecutively).
fn liggghts_final(path: &Path, per_body: usize) -> Result<FinalState> {
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
    let mut f = FinalState::default();
    for (id, x, r) in rows {
        f.pos.push(x);
        f.rad.push(r);
        f.body.push((id - 1) / per_body.max(1));
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
    /// Bulk packing fraction: bodies × stone volume / (footprint × surface).
    pub phi: f64,
    /// Overlapping sphere pairs of different bodies.
    pub sphere_contacts: usize,
    /// Body pairs with at least one overlapping sphere pair.
    pub body_contacts: usize,
}

/// Bed height, packing fraction and contacts of `f` (`footprint`: floor
/// area under the bed, m², for the packing fraction).
pub fn physics(f: &FinalState, stone_volume: f64, footprint: f64) -> Physics {
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
    let phi = bodies as f64 * stone_volume / (footprint * surface);
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

/// Runs Clump on `scenario` for `na` + `nb` steps; the figures and the final state.
fn run_clump_stone(
    scenario: &Path,
    threads: usize,
    skin: Option<f64>,
    na: u64,
    nb: u64,
) -> Result<(Figures, FinalState)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    pool.install(|| {
        let (mut w, _, _) = crate::cmd_bench::build_world(scenario, skin)?;
        w.prepare()?;
        let t0 = Instant::now();
        w.run(na)?;
        let a = t0.elapsed().as_secs_f64();
        w.stage_times = Default::default();
        let (t1, r1, c1) = (Instant::now(), w.rebuilds, crate::cmd_bench::cpu_seconds());
        w.run(nb)?;
        let b = t1.elapsed().as_secs_f64();
        let cb = crate::cmd_bench::cpu_seconds() - c1;
        let st = w.stage_times;
        let total = st.rows().iter().map(|r| r.1).sum::<f64>().max(1e-12);
        let shares: Vec<String> = st
            .rows()
            .iter()
            .map(|(name, t)| format!("{name} {:.1} %", 100.0 * t / total))
            .collect();
        errln!(
            "clump: phase B by stage: {} ({:.2} s of {:.2} s wall, CPU time of all threads {:.2} s; {} rebuilds, skin {:.3} mm at the end, {:.1} ns per sphere-step)",
            shares.join(", "),
            total,
            b,
            cb,
            w.rebuilds - r1,
            w.skin() * 1e3,
            1e9 * b / (w.spheres().len() as f64 * nb.max(1) as f64)
        );
        crate::cmd_bench::print_end_state(&w);
        Ok((
            Figures {
                a_seconds: a,
                b_seconds: b,
                spheres: w.spheres().len(),
                peak_rss_mb: peak_rss_mb(),
            },
            clump_final(&w),
        ))
    })
}

/// Settles the bed's lattice in Clump alone (`steps` steps) and returns
/// the settled poses at rest. Reuses `settled.csv` in `dir` when its key
/// line matches.
fn settled_bed(
    dir: &Path,
    stone: &Stone,
    n: usize,
    seed: u64,
    steps: u64,
    threads: usize,
) -> Result<(Vec<Pose>, BedBox)> {
    let (lattice, bbox) = bed_lattice(stone, n, seed);
    let key = format!(
        "# settled stone bed: stones {n}, seed {seed}, settle {steps}, stone {} ({} spheres, mass {:.9e})",
        stone.source,
        stone.spheres.len(),
        stone.template.mass
    );
    let cache = dir.join("settled.csv");
    let keyfile = dir.join("settled.key");
    if cache.is_file() && std::fs::read_to_string(&keyfile).ok().as_deref() == Some(key.as_str()) {
        errln!("stone bed: reusing the settled bed {}", cache.display());
        return Ok((read_ic(&cache)?, bbox));
    }
    let prep = dir.join("settle");
    let files = write_case(
        &prep,
        stone,
        &lattice,
        Geometry::Bed(bbox),
        steps.max(1),
        1,
        false,
    )?;
    errln!(
        "stone bed: settling {n} stones from the lattice in Clump alone, {steps} steps, {threads} threads (once; kept in {})",
        cache.display()
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let t0 = Instant::now();
    let poses = pool.install(|| -> Result<Vec<Pose>> {
        let (mut w, _, _) = crate::cmd_bench::build_world(&files.scenario, None)?;
        w.prepare()?;
        w.run(steps)?;
        let th = w.thermo();
        errln!(
            "stone bed: settled in {:.0} s: KE {:.3e} J, {} contacts, lost {}",
            t0.elapsed().as_secs_f64(),
            th.kinetic_translational + th.kinetic_rotational,
            th.pair_contacts + th.wall_contacts,
            th.lost_bodies
        );
        if th.lost_bodies > 0 {
            bail!(
                "stone bed: {} stones were lost while settling",
                th.lost_bodies
            );
        }
        let to_body = stone.template.input_to_body;
        let mut order: Vec<usize> = (0..w.bodies.len()).collect();
        order.sort_by_key(|&b| w.bodies.id[b]);
        Ok(order
            .into_iter()
            .map(|b| Pose {
                x: w.bodies.position[b],
                // body → world times file → body
                q: (w.bodies.orientation[b] * to_body).normalize(),
                vz: 0.0,
            })
            .collect())
    })?;
    write_ic(&poses, &cache)?;
    std::fs::write(&keyfile, &key)?;
    Ok((poses, bbox))
}

/// What to prepare: stones and steps.
#[derive(Debug, Clone, Copy)]
pub struct Plan {
    /// Number of stones.
    pub n: usize,
    /// Steps of phase A.
    pub na: u64,
    /// Steps of phase B.
    pub nb: u64,
    /// Bed: steps of the Clump-only settling.
    pub settle: u64,
    /// Bed: threads of the settling.
    pub threads: usize,
    /// Clump uses LIGGGHTS' tangential rule.
    pub liggghts_tangential: bool,
}

/// Writes the case's files (initial condition, Clump scenario, LIGGGHTS
/// input) into `dir`; for the bed, settles it first (or reuses the settled
/// bed). Returns the files and the floor area under the bed, m².
pub fn prepare(
    case: StoneCase,
    dir: &Path,
    stone: &Stone,
    plan: &Plan,
) -> Result<(CaseFiles, f64)> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let Plan {
        n,
        na,
        nb,
        settle,
        threads,
        liggghts_tangential: lt,
    } = *plan;
    match case {
        StoneCase::Pile => {
            let poses = pile_poses(stone, n, 32452843)?;
            let files = write_case(dir, stone, &poses, Geometry::Pile, na, nb, lt)?;
            Ok((files, std::f64::consts::PI * PILE_WALL_RADIUS.powi(2)))
        }
        StoneCase::Bed => {
            let (poses, bbox) = settled_bed(dir, stone, n, 2024, settle, threads)?;
            let files = write_case(dir, stone, &poses, Geometry::Bed(bbox), na, nb, lt)?;
            Ok((files, 4.0 * bbox.hx * bbox.hy))
        }
    }
}

/// `clump bench --case stone-pile | stone-bed`.
pub fn run(args: &BenchArgs, case: StoneCase) -> Result<()> {
    let stone = load_stone(&args.stone)?;
    let n = args.stones.unwrap_or(match case {
        StoneCase::Pile => 200,
        StoneCase::Bed => 2000,
    });
    if n == 0 {
        bail!("--stones: the bench needs at least one stone");
    }
    let (na, nb) = match case {
        StoneCase::Pile => (args.na.unwrap_or(30000), args.nb.unwrap_or(10000)),
        StoneCase::Bed => (args.na.unwrap_or(2000), args.nb.unwrap_or(10000)),
    };
    let dir = args
        .work
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("out/bench-{}", case.name())));
    let lig = if args.liggghts_rounds > 0 {
        let l = which("liggghts");
        if l.is_none() {
            errln!("liggghts is not installed (apt-get install liggghts): running Clump only");
        }
        l
    } else {
        None
    };
    let (files, footprint) = prepare(
        case,
        &dir,
        &stone,
        &Plan {
            n,
            na,
            nb,
            settle: args.bed_settle,
            threads: args.threads,
            liggghts_tangential: args.liggghts_tangential,
        },
    )?;
    let nsph = stone.spheres.len();
    outln!(
        "{}: {n} stones of {nsph} spheres ({}; mass {:.4e} kg, bounding radius {:.1} mm), phase A {na} steps, phase B {nb} steps, clump threads {}; files in {}",
        case.name(),
        stone.source,
        stone.template.mass,
        stone.template.bounding_radius * 1e3,
        args.threads,
        dir.display()
    );
    let rounds = args.liggghts_rounds.max(1);
    let (mut clump, mut peer) = (Vec::new(), Vec::new());
    let (mut cfin, mut lfin) = (None, None);
    for round in 0..rounds {
        let (f, fin) = run_clump_stone(&files.scenario, args.threads, args.skin, na, nb)?;
        report("clump", round, na, nb, &f);
        clump.push(f);
        cfin = Some(fin);
        if let Some(bin) = &lig {
            let vars = [("NA", na.to_string()), ("NB", nb.to_string())];
            let f = run_liggghts_input(bin, &files.liggghts, "in.stone", &vars, na, nb, n * nsph)?;
            report("liggghts", round, na, nb, &f);
            peer.push(f);
            lfin = Some(liggghts_final(&files.liggghts.join("final.dump"), nsph)?);
        }
    }
    let tput = |s: f64, steps: u64| (n * nsph) as f64 * steps as f64 / s;
    let (ca, cb) = (
        tput(median(&clump, |f| f.a_seconds), na),
        tput(median(&clump, |f| f.b_seconds), nb),
    );
    outln!(
        "clump    (threads {}): phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s (medians), peak RSS {:.0} MB",
        args.threads,
        ca / 1e6,
        cb / 1e6,
        median(&clump, |f| f.peak_rss_mb)
    );
    if !peer.is_empty() {
        let (la, lb) = (
            tput(median(&peer, |f| f.a_seconds), na),
            tput(median(&peer, |f| f.b_seconds), nb),
        );
        outln!(
            "liggghts (serial):    phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s (medians), peak RSS {:.0} MB",
            la / 1e6,
            lb / 1e6,
            median(&peer, |f| f.peak_rss_mb)
        );
        for (phase, key) in [
            ("A", (|f: &Figures| f.a_seconds) as fn(&Figures) -> f64),
            ("B", |f: &Figures| f.b_seconds),
        ] {
            let mut r: Vec<f64> = clump
                .iter()
                .zip(&peer)
                .map(|(c, l)| key(l) / key(c))
                .collect();
            let list: Vec<String> = r.iter().map(|x| format!("{x:.2}x")).collect();
            r.sort_by(f64::total_cmp);
            outln!(
                "phase {phase} ratio clump/liggghts per round: {}; median {:.2}x",
                list.join(", "),
                r[r.len() / 2]
            );
        }
    }
    let vol = stone.template.volume;
    if let Some(c) = &cfin {
        let pc = physics(c, vol, footprint);
        print_physics("clump", &pc, case);
        if let Some(l) = &lfin {
            let pl = physics(l, vol, footprint);
            print_physics("liggghts", &pl, case);
            let rel = |a: f64, b: f64| 100.0 * (a - b) / b;
            outln!(
                "physics clump vs liggghts: mean sphere height {:+.2} %, surface {:+.2} %, packing fraction {:+.2} %, sphere contacts {:+.2} %, body contacts {:+.2} %",
                rel(pc.mean_z, pl.mean_z),
                rel(pc.surface, pl.surface),
                rel(pc.phi, pl.phi),
                rel(pc.sphere_contacts as f64, pl.sphere_contacts as f64),
                rel(pc.body_contacts as f64, pl.body_contacts as f64)
            );
        }
    }
    Ok(())
}

fn print_physics(code: &str, p: &Physics, case: StoneCase) {
    outln!(
        "physics {code:8}: {} bodies, mean sphere height {:.4} m, surface {:.4} m, {} {:.4}, sphere contacts {}, body contacts {}",
        p.bodies,
        p.mean_z,
        p.surface,
        match case {
            StoneCase::Pile => "packing fraction (of the container floor, a loose pile)",
            StoneCase::Bed => "packing fraction",
        },
        p.phi,
        p.sphere_contacts,
        p.body_contacts
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("clump-bench-stone-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    /// The LIGGGHTS input and the Clump scenario describe the same bodies:
    /// the spheres Clump builds from scenario.toml sit where LIGGGHTS'
    /// insertions put them (pose of ins.in applied to liggghts/stone.xyzr),
    /// and LIGGGHTS gets Clump's mass.
    #[test]
    fn liggghts_input_and_clump_scenario_describe_the_same_bodies() {
        let stone = load_stone("procedural").unwrap();
        assert_eq!(stone.spheres.len(), 50);
        let d = tmp("same");
        let (files, _) = prepare(
            StoneCase::Pile,
            &d,
            &stone,
            &Plan {
                n: 20,
                na: 10,
                nb: 10,
                settle: 0,
                threads: 1,
                liggghts_tangential: false,
            },
        )
        .unwrap();
        // LIGGGHTS' side: the insertions and the template file it reads
        let ins = std::fs::read_to_string(files.liggghts.join("ins.in")).unwrap();
        let tpl = clump_io::template_file::read_template_file(&files.liggghts.join("stone.xyzr"))
            .unwrap();
        let mut lig = Vec::new();
        let lines: Vec<&str> = ins.lines().collect();
        for w in lines.windows(2) {
            if !w[0].starts_with("region r") {
                continue;
            }
            let r: Vec<f64> = w[0]
                .split_whitespace()
                .skip(3)
                .take(6)
                .map(|x| x.parse().unwrap())
                .collect();
            let x = DVec3::new(
                0.5 * (r[0] + r[1]),
                0.5 * (r[2] + r[3]),
                0.5 * (r[4] + r[5]),
            );
            let t: Vec<&str> = w[1].split_whitespace().collect();
            let at = |k: &str| t.iter().position(|s| *s == k).unwrap();
            let o = at("constant");
            let o = o + 1 + t[o + 1..].iter().position(|s| *s == "constant").unwrap();
            let q: Vec<f64> = t[o + 1..o + 5].iter().map(|x| x.parse().unwrap()).collect();
            let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
            let vz: f64 = t[at("vel") + 4].parse().unwrap();
            assert_eq!(vz, PILE_VZ);
            for s in &tpl {
                lig.push(x + q * s.center);
            }
        }
        assert_eq!(lig.len(), 20 * 50);
        // Clump's side
        let (mut w, na, nb) = crate::cmd_bench::build_world(&files.scenario, None).unwrap();
        assert_eq!((na, nb), (10, 10));
        w.prepare().unwrap();
        let f = clump_final(&w);
        assert_eq!(f.pos.len(), lig.len());
        for (a, b) in f.pos.iter().zip(&lig) {
            assert!((*a - *b).length() < 1e-9, "{a} vs {b}");
        }
        for b in 0..w.bodies.len() {
            assert!((w.bodies.velocity[b] - DVec3::new(0.0, 0.0, PILE_VZ)).length() < 1e-12);
        }
        let input = std::fs::read_to_string(files.liggghts.join("in.stone")).unwrap();
        assert!(input.contains(&format!("mass {:.9e}", stone.template.mass)));
        assert!(input.contains("zcylinder 0.26"));
        // Clump's own tangential rule unless asked for LIGGGHTS'
        let sc = std::fs::read_to_string(&files.scenario).unwrap();
        assert!(!sc.contains("tangential"));
        let poses = read_ic(&d.join("ic.csv")).unwrap();
        let f = write_case(&d.join("lt"), &stone, &poses, Geometry::Pile, 1, 1, true).unwrap();
        let sc = std::fs::read_to_string(&f.scenario).unwrap();
        assert!(sc.contains("tangential = \"liggghts\""));
        crate::cmd_bench::build_world(&f.scenario, None).unwrap();
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_missing_stone_template_is_refused_clearly() {
        let e = load_stone("/nonexistent/stone1.multisphere")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no stone template file at /nonexistent/stone1.multisphere"),
            "{e}"
        );
        if !Path::new(LIGGGHTS_STONE).is_file() {
            let e = load_stone("liggghts").unwrap_err().to_string();
            assert!(
                e.contains("liggghts-doc") && e.contains("--stone procedural"),
                "{e}"
            );
        }
    }

    /// The bed's lattice holds no overlapping stones and stays in its box.
    #[test]
    fn bed_lattice_is_loose_and_inside() {
        let stone = load_stone("procedural").unwrap();
        let (poses, b) = bed_lattice(&stone, 300, 5);
        assert_eq!(poses.len(), 300);
        let placed: Vec<Vec<Sphere>> = poses.iter().map(|p| placed(&stone, p).collect()).collect();
        for (i, a) in placed.iter().enumerate() {
            for s in a {
                assert!(s.center.x.abs() + s.radius <= b.hx + 1e-9);
                assert!(s.center.y.abs() + s.radius <= b.hy + 1e-9);
                assert!(s.center.z - s.radius >= 0.0 && s.center.z + s.radius <= b.top);
            }
            for c in &placed[i + 1..] {
                assert!(!overlapping(a, c));
            }
        }
    }
}
