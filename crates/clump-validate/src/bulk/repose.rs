//! Angle of repose of tetra-clump heaps on a fixed base: clumps are poured
//! gently, in small batches, onto the centre of a rough circular pedestal
//! (a layer of fixed spheres); what does not stay on the pedestal falls over
//! its edge and leaves the domain. Pouring goes on until the heap is full
//! (saturated): its flanks then stand at the angle of repose and the size
//! of the heap is set by the pedestal radius, not by a runout. The angle is
//! that of a cone on the same base (the fixed-base method, ISO 4324 style,
//! which measures the cone's height) with the heap's centroid height: the
//! mean height of all the clump centres, a quarter of the cone's height.
//! Published trend:
//! the angle rises with sliding and rolling friction. World frame: z up,
//! gravity −z, the pedestal centred on the z axis with its top at z = 2R.

use super::{rayleigh_dt, settle};
use crate::case::{Case, Group};
use crate::ode::slope;
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{CohesionLaw, PairProperties, RollingLaw};
use clump_core::insert::{pack, Mix, Orientation, PackSpec, PackTarget, Region};
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};
use std::path::Path;

/// Sphere radius of the clumps and of the pedestal spheres, m.
const R: f64 = 1e-3;
/// Centre distance of the tetra clump's spheres, m.
const EDGE: f64 = 1.2e-3;
/// Standard gravity, m/s².
const G: f64 = 9.81;

/// Set-up of one heap.
#[derive(Debug, Clone, Copy)]
pub struct HeapSpec {
    /// Sliding friction coefficient (every pair, pedestal included).
    pub mu: f64,
    /// Rolling friction coefficient (CDT law when > 0).
    pub mu_r: f64,
    /// Seed of the pedestal jitter and of the pour.
    pub seed: u64,
    /// Most clumps poured (the pour stops earlier once the heap is full).
    pub max_clumps: usize,
    /// Pedestal radius, m.
    pub pedestal_radius: f64,
    /// Clumps per poured batch.
    pub batch: usize,
    /// Radius of the pour's source cylinder, m.
    pub source_radius: f64,
    /// Downward speed of the poured clumps, m/s.
    pub pour_speed: f64,
    /// Verlet skin, m.
    pub skin: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Time step as a fraction of the Rayleigh time of a sphere R.
    pub dt_fraction: f64,
    /// Height of the domain's top above the pedestal's base, m (room for
    /// the heap and the pour's source cylinder above it).
    pub ceiling: f64,
    /// Granular Bond number: JKR pull-off force of two of the clumps'
    /// spheres, (3/2) π Γ R* with R* = R/2, over a clump's weight m g
    /// (0: no cohesion). Sets the work of adhesion Γ of every pair.
    pub bond: f64,
}

impl HeapSpec {
    /// The suite's heap for friction `mu`, rolling friction `mu_r` and `seed`.
    pub fn new(mu: f64, mu_r: f64, seed: u64) -> Self {
        let pedestal_radius = 0.022;
        HeapSpec {
            mu,
            mu_r,
            seed,
            max_clumps: 2000,
            pedestal_radius,
            batch: 10,
            source_radius: 6e-3,
            pour_speed: 0.1,
            skin: 0.6 * R,
            youngs_modulus: 1e6,
            dt_fraction: 0.25,
            ceiling: pedestal_radius + 0.03,
            bond: 0.0,
        }
    }
}

/// What one heap gave.
#[derive(Debug, Clone)]
pub struct Heap {
    /// Angle of repose, deg: that of the cone on the pedestal whose
    /// centroid height (a quarter of its height) is the mean height z̄ of the
    /// clump centres above the pedestal top, atan(4 z̄ / r_p).
    pub angle: f64,
    /// Least-squares slope of the flank h(r) between [`FIT_FROM`] and
    /// [`FIT_TO`] of the pedestal radius, deg.
    pub flank_angle: f64,
    /// Surface profile `(r mm, height above the pedestal top mm)`, mean
    /// over the azimuthal sectors.
    pub profile: Vec<(f64, f64)>,
    /// Clumps poured.
    pub poured: usize,
    /// Clumps left on the pedestal.
    pub clumps_left: usize,
    /// Steps run.
    pub steps: u64,
    /// Wall time of the heap's run, s.
    pub seconds: f64,
    /// Largest fall, between two batches of the pour, of the number of
    /// clumps at rest on the pedestal: the clumps the largest avalanche set
    /// moving or carried off (a measure of how the heap fails).
    pub largest_drop: usize,
    /// Largest overlap ratio at the end.
    pub max_overlap: f64,
}

/// Number of azimuthal sectors of the surface measurement.
const SECTORS: usize = 8;
/// Width of the radial bins of the profile, m.
const BIN: f64 = 2.0 * R;
/// Radial range of the flank fit, as fractions of the pedestal radius.
pub const FIT_FROM: f64 = 0.3;
/// See [`FIT_FROM`].
pub const FIT_TO: f64 = 0.85;
/// The pour stops when the number of clumps at rest on the pedestal has
/// not reached a new maximum during this many batches.
const SATURATED_AFTER: usize = 10;

/// Lays the pedestal: one fixed body made of spheres of radius R on a
/// hexagonal lattice of spacing 2.05 R inside the disc of radius `radius`,
/// centres at height R jittered by ±0.25 R (a rough base of glued
/// particles; one body, so it costs one body's integration). Returns the
/// height of its top (m).
fn pedestal(w: &mut World, radius: f64, seed: u64) -> Result<f64, String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x9e37_79b9);
    let a = 2.05 * R;
    let row = a * 0.75f64.sqrt();
    let rows = (radius / row) as i64 + 1;
    let cols = (radius / a) as i64 + 2;
    let mut spheres = Vec::new();
    for j in -rows..=rows {
        let y = j as f64 * row;
        let shift = if j.rem_euclid(2) == 1 { 0.5 * a } else { 0.0 };
        for i in -cols..=cols {
            let x = i as f64 * a + shift;
            if x.hypot(y) <= radius - R {
                let z = R + rng.gen_range(-0.25..0.25) * R;
                spheres.push(Sphere {
                    center: DVec3::new(x, y, z),
                    radius: R,
                });
            }
        }
    }
    let tp = ClumpTemplate::from_spheres("pedestal", &spheres, w.materials[0].density)
        .map_err(|e| e.to_string())?;
    // body pose that puts the template's spheres back where they were laid
    let (x, q) = (tp.input_center_of_mass, tp.input_to_body.inverse());
    let t = w.add_template(tp, PARTICLE).map_err(|e| e.to_string())?;
    let init = BodyInit {
        force_flag: [false; 3],
        torque_flag: [false; 3],
        ..BodyInit::at_rest(t, x, q)
    };
    w.add_body(&init).map_err(|e| e.to_string())?;
    Ok(2.0 * R)
}

/// Free clumps (template `t`) at rest (speed below 0.05 m/s) above the
/// pedestal: their number and the highest top of their bounding spheres (m).
fn resting(w: &World, t: u32, br: f64) -> (usize, f64) {
    let b = w.bodies();
    (0..b.len())
        .filter(|&i| b.template[i] == t && b.position[i].z > 0.0 && b.velocity[i].length() < 0.05)
        .fold((0, 0.0), |(n, top), i| {
            (n + 1, f64::max(top, b.position[i].z + br))
        })
}

/// Azimuthal sector (0..SECTORS) of a point at `(x, y)`.
fn sector(x: f64, y: f64) -> usize {
    (((y.atan2(x) + PI) / TAU * SECTORS as f64) as usize).min(SECTORS - 1)
}

/// Pours the heap of `spec` and measures it.
pub fn heap(spec: &HeapSpec) -> Result<Heap, String> {
    let t0 = std::time::Instant::now();
    let mat = material(spec.youngs_modulus, 0.3, 2500.0);
    let dt = rayleigh_dt(&mat, R, spec.dt_fraction);
    let rp = spec.pedestal_radius;
    // a clump that falls over the pedestal's edge leaves the domain
    let span = rp + 0.005;
    let dom = Domain {
        lo: DVec3::new(-span, -span, -0.003),
        hi: DVec3::new(span, span, spec.ceiling),
        periodic: [false; 3],
    };
    let clump = tetra(R, EDGE, mat.density)?;
    let p = PairProperties {
        restitution: 0.3,
        friction: spec.mu,
        rolling_friction: spec.mu_r,
        rolling: if spec.mu_r > 0.0 {
            RollingLaw::Cdt
        } else {
            RollingLaw::None
        },
        cohesion: if spec.bond > 0.0 {
            // Bo = (3/2) π Γ (R/2) / (m g)
            CohesionLaw::Jkr {
                surface_energy: spec.bond * clump.mass * G / (0.75 * PI * R),
            }
        } else {
            CohesionLaw::None
        },
        ..PairProperties::default()
    };
    let mut w = world(mat, p, dt, dom, DVec3::new(0.0, 0.0, -G))?;
    w.config.skin = Some(spec.skin);
    let t = w.add_template(clump, PARTICLE).map_err(|e| e.to_string())?;
    let base = pedestal(&mut w, rp, spec.seed)?;
    let br = w.templates[t as usize].bounding_radius;
    let m = w.templates[t as usize].mass;
    // pour: batches into a cylinder of radius `source_radius` whose bottom
    // is 2 mm above the current heap top, moving down at `pour_speed`; the
    // next batch follows when this one has left the cylinder
    let r_src = spec.source_radius;
    let v0 = spec.pour_speed;
    let (mut poured, mut batch_no) = (0, 0u64);
    let (mut most, mut since_most) = (0, 0);
    let (mut last_on, mut largest_drop) = (0usize, 0usize);
    while poured < spec.max_clumps && since_most < SATURATED_AFTER {
        let (on, top) = resting(&w, t, br);
        largest_drop = largest_drop.max(last_on.saturating_sub(on));
        last_on = on;
        if on > most {
            (most, since_most) = (on, 0);
        } else {
            since_most += 1;
        }
        let n = spec.batch.min(spec.max_clumps - poured);
        let z0 = top.max(base) + 2e-3;
        // a loose batch: solid fraction 0.12 in the source cylinder
        let h_src = n as f64 * (m / mat.density) / (0.12 * PI * r_src * r_src) + 2.0 * br;
        let ps = PackSpec {
            region: Region::Cylinder {
                base: DVec3::new(0.0, 0.0, z0),
                axis: DVec3::Z,
                radius: r_src,
                height: h_src,
            },
            target: PackTarget::Count(n),
            mix: Mix::single(t),
            velocity: DVec3::new(0.0, 0.0, -v0),
            orientation: Orientation::Random,
            max_attempts_per_body: 2000,
            angular_velocity: Default::default(),
            dof: Vec::new(),
            plane: None,
        };
        let r = pack(&mut w, &ps, spec.seed * 1000 + batch_no).map_err(|e| e.to_string())?;
        poured += r.placed;
        batch_no += 1;
        // h = v0 t + g t²/2
        let clear = ((v0 * v0 + 2.0 * G * h_src).sqrt() - v0) / G;
        w.run((clear / dt).ceil() as u64)
            .map_err(|e| e.to_string())?;
    }
    if since_most < SATURATED_AFTER {
        return Err(format!(
            "heap μ = {}, μ_r = {}, Bo = {}, seed {}: not full after {poured} clumps",
            spec.mu, spec.mu_r, spec.bond, spec.seed
        ));
    }
    let settled = settle(&mut w, 4_000, 60_000, 1e-4 * m * G * 2.0 * R)?;
    if std::env::var_os("CLUMP_VALIDATE_VERBOSE").is_some() {
        eprintln!(
            "heap μ {} μ_r {} seed {}: {poured} poured, {} + {settled} steps, {} rebuilds, stage seconds {:?}",
            spec.mu,
            spec.mu_r,
            spec.seed,
            w.step - settled,
            w.rebuilds,
            w.stage_times.rows()
        );
    }
    // the surface: highest sphere top of the free clumps per cell of 2-mm
    // rings × SECTORS sectors (the innermost ring one cell); an empty cell
    // has height 0
    let nb = (rp / BIN).ceil() as usize;
    let mut bins = vec![[0.0f64; SECTORS]; nb];
    let sp = w.spheres();
    for (s, x) in sp.positions().enumerate() {
        let r = x.x.hypot(x.y);
        if w.bodies().template[sp.body[s] as usize] != t || x.z < 0.0 || r >= rp {
            continue;
        }
        let sec = sector(x.x, x.y);
        let h = x.z + R - base;
        let k = ((r / BIN) as usize).min(nb - 1);
        // the innermost ring is too small to split into sectors: one cell
        let cells = if k == 0 { 0..SECTORS } else { sec..sec + 1 };
        for c in &mut bins[k][cells] {
            *c = c.max(h);
        }
    }
    let on: Vec<f64> = (0..w.bodies().len())
        .filter(|&i| {
            let x = w.bodies().position[i];
            w.bodies().template[i] == t && x.z > 0.0 && x.x.hypot(x.y) < rp
        })
        .map(|i| w.bodies().position[i].z - base)
        .collect();
    let clumps_left = on.len();
    let centroid = on.iter().sum::<f64>() / on.len().max(1) as f64;
    let profile: Vec<(f64, f64)> = bins
        .iter()
        .enumerate()
        .map(|(k, row)| {
            (
                (k as f64 + 0.5) * BIN * 1e3,
                row.iter().sum::<f64>() / SECTORS as f64 * 1e3,
            )
        })
        .collect();
    let pts: Vec<(f64, f64)> = profile
        .iter()
        .copied()
        .filter(|p| p.0 >= FIT_FROM * rp * 1e3 && p.0 <= FIT_TO * rp * 1e3)
        .collect();
    Ok(Heap {
        angle: (4.0 * centroid / rp).atan().to_degrees(),
        flank_angle: (-slope(&pts)).atan().to_degrees(),
        profile,
        poured,
        clumps_left,
        steps: w.step,
        largest_drop,
        seconds: t0.elapsed().as_secs_f64(),
        max_overlap: w.thermo().max_overlap_ratio,
    })
}

/// Seeds per configuration of the cohesive series.
pub(super) const SEEDS: [u64; 4] = [1, 2, 3, 4];

/// Seeds per configuration of the dry series: eight, as the step from
/// μ_r = 0 to 0.1 at μ = 0.3 (about +1.3°) is of the order of twice the
/// standard error of four seeds.
const DRY_SEEDS: [u64; 8] = [1, 2, 3, 4, 5, 6, 7, 8];

/// Mean ± standard error of the seeds' values.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stat {
    pub(super) mean: f64,
    pub(super) se: f64,
}

impl Stat {
    pub(super) fn of(x: &[f64]) -> Stat {
        let (mean, se) = super::mean_se(x);
        Stat { mean, se }
    }
}

/// One configuration's heaps.
struct Config {
    mu: f64,
    mu_r: f64,
    heaps: Vec<Heap>,
    angle: Stat,
    flank: Stat,
    profile: Vec<(f64, f64)>,
}

/// Whether every step of `s` rises by more than twice the combined
/// standard error of its two ends, and the steps as text.
fn rises(s: &[Stat]) -> (bool, String) {
    let ok = s.iter().all(|x| x.mean.is_finite() && x.se.is_finite())
        && s.windows(2)
            .all(|p| p[1].mean - p[0].mean > 2.0 * p[0].se.hypot(p[1].se));
    let text = s
        .windows(2)
        .map(|p| {
            format!(
                "{:+.1}° vs 2σ = {:.1}°",
                p[1].mean - p[0].mean,
                2.0 * p[0].se.hypot(p[1].se)
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    (ok, text)
}

/// The trend case of one series.
fn trend_case(label: &str, key: &str, xs: &[f64], cs: &[&Config]) -> Case {
    let s: Vec<Stat> = cs.iter().map(|c| c.angle).collect();
    rise_case(
        format!(
            "tetra-clump heap on a rough pedestal (fixed base, r_p = {:.0} mm): angle of repose rises with {label}",
            HeapSpec::new(0.0, 0.0, 0).pedestal_radius * 1e3
        ),
        "published trend (e.g. Zhou et al. 2002, angle of repose vs sliding and rolling friction)",
        key,
        xs,
        &s,
        DRY_SEEDS.len(),
    )
}

/// The case `name` (from `source`) that the angles `s` of the series
/// `key` = `xs` rise by more than twice their combined standard error at
/// every step ([`rises`]), `seeds` seeds per value.
pub(super) fn rise_case(
    name: String,
    source: &str,
    key: &str,
    xs: &[f64],
    s: &[Stat],
    seeds: usize,
) -> Case {
    let (pass, steps) = rises(s);
    let measured: Vec<String> = xs
        .iter()
        .zip(s)
        .map(|(x, a)| format!("{key} {x}: {:.1} ± {:.1}°", a.mean, a.se))
        .collect();
    Case {
        name,
        source: source.into(),
        expected: "strictly increasing".into(),
        measured: format!("{} (steps {steps})", measured.join(", ")),
        tolerance: format!(
            "each step > 2σ, σ = √(SE₁² + SE₂²), SE = standard error of the mean of {seeds} seeds"
        ),
        pass,
    }
}

/// Runs the friction and rolling-friction series.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    // (μ, μ_r): the sliding series at μ_r = 0 and the rolling series at μ = 0.3
    let configs = [(0.1, 0.0), (0.3, 0.0), (0.6, 0.0), (0.3, 0.1), (0.3, 0.3)];
    let mut jobs: Vec<super::Job<Result<Heap, String>>> = Vec::new();
    for &(mu, mu_r) in &configs {
        for seed in DRY_SEEDS {
            jobs.push(Box::new(move || heap(&HeapSpec::new(mu, mu_r, seed))));
        }
    }
    let mut results = super::run_parallel(jobs).into_iter();
    let mut cs = Vec::new();
    for &(mu, mu_r) in &configs {
        let heaps = (&mut results)
            .take(DRY_SEEDS.len())
            .collect::<Result<Vec<Heap>, String>>()?;
        let angle = Stat::of(&heaps.iter().map(|h| h.angle).collect::<Vec<_>>());
        let flank = Stat::of(&heaps.iter().map(|h| h.flank_angle).collect::<Vec<_>>());
        // every heap's profile has the same bins
        let profile = heaps[0]
            .profile
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let h = heaps.iter().map(|h| h.profile[k].1).sum::<f64>() / heaps.len() as f64;
                (p.0, h)
            })
            .collect();
        cs.push(Config {
            mu,
            mu_r,
            heaps,
            angle,
            flank,
            profile,
        });
    }
    let (xs_mu, xs_mur) = ([0.1, 0.3, 0.6], [0.0, 0.1, 0.3]);
    let by_mu = [&cs[0], &cs[1], &cs[2]];
    let by_mur = [&cs[1], &cs[3], &cs[4]];
    g.cases.push(trend_case(
        "sliding friction μ (μ_r = 0)",
        "μ",
        &xs_mu,
        &by_mu,
    ));
    g.cases.push(trend_case(
        "rolling friction μ_r (μ = 0.3, CDT law)",
        "μ_r",
        &xs_mur,
        &by_mur,
    ));
    let s = HeapSpec::new(0.3, 0.0, 1);
    g.notes.push(format!(
        "angle of repose: tetra clumps (4 spheres R = 1 mm, centres 1.2 mm apart) poured in batches of {} from a cylinder of radius {} mm whose bottom follows 2 mm above the heap top (loose, solid fraction 0.12, moving down at {} m/s; the next batch when the last has left the cylinder) onto the centre of a rough circular pedestal of radius r_p = {} mm: one fixed body of spheres R = 1 mm on a hexagonal lattice of spacing 2.05 R, heights jittered by ±0.25 R. Clumps that fall over its edge leave the domain. The pour stops when the heap is full: the number of clumps at rest on it has not reached a new maximum for {SATURATED_AFTER} batches; then the heap settles until the kinetic energy is below 1e-4 m g d per clump. E = {:.0e} Pa, ν = 0.3, e = 0.3, dt = {} t_R, Verlet skin {} R; the same μ, μ_r for clump–clump and clump–pedestal contacts; {} seeds per configuration (seed: pedestal jitter and pour), mean ± standard error.",
        s.batch, s.source_radius * 1e3, s.pour_speed, s.pedestal_radius * 1e3,
        s.youngs_modulus, s.dt_fraction, s.skin / R, DRY_SEEDS.len()
    ));
    g.notes.push(format!("angle of repose, the measure: the fixed-base method (ISO 4324 style) takes the heap as a cone on the pedestal, tan θ = H / r_p with H the cone's height. The height of one apex is the least certain point of a heap a few clumps high, so H is taken from all the clumps instead: the centroid of a cone of uniform density lies at H/4, so θ = atan(4 z̄ / r_p), z̄ the mean height of the clump centres above the pedestal top. It uses the heap's whole mass distribution (apex, flanks and rim alike); in this run its standard error over the seeds is on average {:.1} times smaller than that of the flank slope below.",
        cs.iter().map(|c| c.flank.se).sum::<f64>() / cs.iter().map(|c| c.angle.se).sum::<f64>()
    ));
    let (flank_mu_ok, flank_mu) = rises(&by_mu.iter().map(|c| c.flank).collect::<Vec<_>>());
    let (flank_mur_ok, flank_mur) = rises(&by_mur.iter().map(|c| c.flank).collect::<Vec<_>>());
    g.notes.push(format!(
        "angle of repose, flank slope for comparison (least-squares slope of h(r), the highest sphere top per 2-mm ring averaged over {SECTORS} sectors, for {:.1} mm ≤ r ≤ {:.1} mm: the apex under the source and the rim left out; not asserted): {}; sliding series steps {flank_mu} ({}), rolling series steps {flank_mur} ({}). The flanks of heaps this small are convex (steeper over the last clump or two at the rim), so the flank slope is lower than the cone angle and depends on the fitted range.",
        FIT_FROM * s.pedestal_radius * 1e3,
        FIT_TO * s.pedestal_radius * 1e3,
        cs.iter()
            .map(|c| format!("μ {} μ_r {}: {:.1} ± {:.1}°", c.mu, c.mu_r, c.flank.mean, c.flank.se))
            .collect::<Vec<_>>()
            .join(", "),
        if flank_mu_ok { "each step > 2σ" } else { "not every step > 2σ" },
        if flank_mur_ok { "each step > 2σ" } else { "not every step > 2σ" },
    ));
    let rp_mm = HeapSpec::new(0.0, 0.0, 0).pedestal_radius * 1e3;
    let zone = |c: &Config, lo: f64, hi: f64| {
        let h: Vec<f64> = c
            .profile
            .iter()
            .filter(|p| p.0 >= lo * rp_mm && p.0 < hi * rp_mm)
            .map(|p| p.1)
            .collect();
        h.iter().sum::<f64>() / h.len().max(1) as f64
    };
    g.notes.push(format!(
        "angle of repose, where the heaps differ: mean surface height (mm) under the source (r < {:.1} mm) / on the fitted flank / at the rim (r > {:.1} mm): {}",
        FIT_FROM * rp_mm,
        FIT_TO * rp_mm,
        cs.iter()
            .map(|c| format!(
                "μ {} μ_r {}: {:.1} / {:.1} / {:.1}",
                c.mu,
                c.mu_r,
                zone(c, 0.0, FIT_FROM),
                zone(c, FIT_FROM, FIT_TO),
                zone(c, FIT_TO, 1.01)
            ))
            .collect::<Vec<_>>()
            .join("; ")
    ));
    let (cone_mur_ok, _) = rises(&by_mur.iter().map(|c| c.angle).collect::<Vec<_>>());
    if cone_mur_ok && !flank_mur_ok {
        g.notes.push(format!(
            "angle of repose, rolling series, cone angle against flank slope: with μ_r = {} the heaps hold {:.0} → {:.0} → {:.0} clumps on average, with mean surface heights under the source {:.1} → {:.1} → {:.1} mm, on the flank {:.1} → {:.1} → {:.1} mm and at the rim {:.1} → {:.1} → {:.1} mm; the fixed-base angle rises by more than 2σ at every step, the slope fitted to the flank between the source and the rim not at every step (above). The two weigh the heap differently: the cone angle counts every clump, under the source and at the rim included, the flank slope only the mid-flank of heaps 5–6 clumps high, where the scatter over the seeds is larger. Resolving the mid-flank slope's response to μ_r at μ = 0.3 would need a larger pedestal, beyond this budget.",
            xs_mur.map(|x| x.to_string()).join(", "),
            by_mur[0].heaps.iter().map(|h| h.clumps_left as f64).sum::<f64>() / DRY_SEEDS.len() as f64,
            by_mur[1].heaps.iter().map(|h| h.clumps_left as f64).sum::<f64>() / DRY_SEEDS.len() as f64,
            by_mur[2].heaps.iter().map(|h| h.clumps_left as f64).sum::<f64>() / DRY_SEEDS.len() as f64,
            zone(by_mur[0], 0.0, FIT_FROM),
            zone(by_mur[1], 0.0, FIT_FROM),
            zone(by_mur[2], 0.0, FIT_FROM),
            zone(by_mur[0], FIT_FROM, FIT_TO),
            zone(by_mur[1], FIT_FROM, FIT_TO),
            zone(by_mur[2], FIT_FROM, FIT_TO),
            zone(by_mur[0], FIT_TO, 1.01),
            zone(by_mur[1], FIT_TO, 1.01),
            zone(by_mur[2], FIT_TO, 1.01),
        ));
    }
    g.notes.push(format!(
        "angle of repose, per seed: cone angle (deg) / clumps poured / clumps left on the pedestal: {}",
        cs.iter()
            .map(|c| format!(
                "μ {} μ_r {}: {}",
                c.mu,
                c.mu_r,
                c.heaps
                    .iter()
                    .map(|h| format!("{:.1}/{}/{}", h.angle, h.poured, h.clumps_left))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
            .collect::<Vec<_>>()
            .join("; ")
    ));
    let series = |cs: &[&Config], xs: &[f64], label: &str| {
        Series::with_errors(
            label,
            xs.iter().zip(cs).map(|(&x, c)| (x, c.angle.mean)).collect(),
            cs.iter().map(|c| c.angle.se).collect(),
            Style::LinePoints,
        )
    };
    let c = Chart {
        title: "Angle of repose vs friction (tetra clumps, fixed base)".into(),
        x_label: "friction coefficient".into(),
        y_label: "angle of repose (deg), mean ± SE".into(),
        series: vec![
            series(&by_mu, &xs_mu, "sliding friction μ (μ_r = 0)"),
            series(&by_mur, &xs_mur, "rolling friction μ_r (μ = 0.3)"),
        ],
    };
    g.plot(
        "bulk_repose_trend.png",
        "Angle of repose of tetra-clump heaps on a rough pedestal, atan(4 z̄ / r_p), against sliding and rolling friction (mean ± standard error of 8 seeds)",
        draw(&dir.join("bulk_repose_trend.png"), &c),
    );
    let c = Chart {
        title: "Heap surface profiles (mean of the seeds)".into(),
        x_label: "distance from the axis r (mm)".into(),
        y_label: "surface height above the pedestal (mm)".into(),
        series: cs
            .iter()
            .map(|c| {
                Series::new(
                    format!("μ = {}, μ_r = {}: {:.1}°", c.mu, c.mu_r, c.angle.mean),
                    c.profile.clone(),
                    Style::LinePoints,
                )
            })
            .collect(),
    };
    g.plot(
        "bulk_repose_profiles.png",
        "Surface profiles h(r) of the heaps (highest sphere top per 2-mm ring, mean over 8 sectors and the seeds)",
        draw(&dir.join("bulk_repose_profiles.png"), &c),
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trend_passes_only_with_steps_above_twice_the_combined_error() {
        let st = |mean, se| Stat { mean, se };
        // steps 2 and 3 against 2√(0.5² + 0.5²) = 1.41
        assert!(rises(&[st(20.0, 0.5), st(22.0, 0.5), st(25.0, 0.5)]).0);
        // a step of 1 is within 2σ
        assert!(!rises(&[st(20.0, 0.5), st(21.0, 0.5), st(25.0, 0.5)]).0);
        assert!(!rises(&[st(20.0, 0.1), st(19.0, 0.1)]).0);
        assert!(!rises(&[st(20.0, f64::NAN), st(30.0, 0.1)]).0);
    }

    #[test]
    fn pedestal_spheres_lie_where_they_were_laid() {
        let mat = material(1e6, 0.3, 2500.0);
        let dom = Domain {
            lo: DVec3::splat(-0.01),
            hi: DVec3::splat(0.01),
            periodic: [false; 3],
        };
        let mut w = world(mat, PairProperties::default(), 1e-5, dom, DVec3::ZERO).unwrap();
        let top = pedestal(&mut w, 0.008, 1).unwrap();
        assert_eq!(top, 2.0 * R);
        w.step().unwrap();
        let sp = w.spheres();
        assert!(sp.len() > 20);
        for x in sp.positions() {
            assert!(x.x.hypot(x.y) <= 0.008 - R + 1e-12);
            assert!((x.z - R).abs() <= 0.25 * R + 1e-12, "{x}");
        }
        // centres on the lattice: no two closer than its spacing
        for (i, a) in sp.positions().enumerate() {
            for b in sp.positions().skip(i + 1) {
                assert!((a.truncate() - b.truncate()).length() > 2.05 * R - 1e-9);
            }
        }
    }

    /// One dry heap of the suite (μ 0.3, μ_r 0, seed 1), to compare with
    /// the committed report's per-seed figures.
    #[test]
    #[ignore]
    fn one_dry_heap() {
        let h = heap(&HeapSpec::new(0.3, 0.0, 1)).unwrap();
        eprintln!("{:.1}/{}/{}", h.angle, h.poured, h.clumps_left);
    }
}
