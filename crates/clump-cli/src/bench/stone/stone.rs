//! The benchmark's stone: LIGGGHTS' template read from liggghts-doc, a
//! file, or a procedural stone of the same size and sphere count.

use super::*;

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
    stone_from_mm(source, mm)
}

/// The stone of spheres `mm` (mm, any frame): in metres, shifted to its
/// centre of mass, with its exact mass properties.
fn stone_from_mm(source: String, mm: Vec<Sphere>) -> Result<Stone> {
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
    Stone::centred(source, spheres)
}

impl Stone {
    /// The stone of `spheres` (m, centred on their centre of mass), with its
    /// exact mass properties.
    fn centred(source: String, spheres: Vec<Sphere>) -> Result<Stone> {
        let template = ClumpTemplate::from_spheres("stone", &spheres, DENSITY)
            .map_err(|e| anyhow::anyhow!("--stone {source}: {e}"))?;
        Ok(Stone {
            source,
            spheres,
            template,
        })
    }

    /// The stone scaled by `s` about its centre of mass: a size class of a
    /// mix, with its own exact mass properties.
    pub fn scaled(&self, s: f64, source: String) -> Result<Stone> {
        let spheres = self
            .spheres
            .iter()
            .map(|p| Sphere::new(p.center * s, p.radius * s))
            .collect();
        Stone::centred(source, spheres)
    }
}

/// Linear scales of the mix's size classes and their number fractions
/// (per shape): a size distribution of 0.75, 1 and 1.25 times the stone,
/// the middle class the most common.
pub const MIX_SIZES: [(f64, f64); 3] = [(0.75, 0.3), (1.0, 0.4), (1.25, 0.3)];

/// The templates of the mixed case and the number fraction of each: two
/// shapes, `base` (the `--stone`) and a procedural stone (another seed when
/// `base` is the procedural one itself), each in the size classes of
/// [`MIX_SIZES`], half the stones of each shape.
pub fn mix_stones(base: &Stone) -> Result<Vec<(Stone, f64)>> {
    let other_seed = if base.source.starts_with("procedural") {
        11
    } else {
        7
    };
    let other = stone_from_mm(
        format!("procedural (seeded {other_seed}, 50 spheres)"),
        procedural_stone(50, other_seed),
    )?;
    let mut out = Vec::new();
    for shape in [base, &other] {
        for (s, f) in MIX_SIZES {
            let source = format!("{} x {s}", shape.source);
            out.push((shape.scaled(s, source)?, 0.5 * f));
        }
    }
    Ok(out)
}

/// SplitMix64: a tiny seeded generator, so that the initial conditions and
/// the procedural stone are the same on every machine.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub(super) fn f(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(super) fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f()
    }
    /// Uniform random rotation (Shoemake), scalar part ≥ 0.
    pub(super) fn quat(&mut self) -> DQuat {
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
