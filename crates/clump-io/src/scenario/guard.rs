//! The default of the overlap guard (`[simulation] max_overlap_ratio`) from
//! the scenario's own contact estimate, so that it never stops a physically
//! legitimate run: soft particles at speed overlap deeply (LIGGGHTS' stone
//! tutorial, E = 1e7 Pa at 2.5 m/s, reaches about 0.35 of a sphere radius).
//!
//! The largest expected overlap is that of an undamped impact at the
//! largest speed the scenario lets bodies reach, `v = √(2 |g| H + v_max²)`
//! (a fall across the domain's height `H` along gravity, from the largest
//! insertion or wall speed; [`MotionBounds`]), for every pair of templates
//! and every template against every wall material, with the whole body mass
//! on one sphere of the body's volume-equivalent radius (at most its largest
//! sphere; the overlap is compared with that radius):
//! - Hertz: `δ = (15 m* v²/(16 E* √R*))^{2/5}` ([`hertz_max_overlap`]);
//! - linear spring: `δ = v √(m*/k_n)`.
//!
//! The guard's default is [`GUARD_MARGIN`] times the largest `δ / r`
//! (smaller radius), but at least [`DEFAULT_MAX_OVERLAP_RATIO`] and at most
//! 1. Damping, restitution < 1 and several contacts sharing the load only
//! make the real overlap smaller, so a legitimate run stays below it; a
//! numerical blow-up overshoots it (and the NaN and kinetic-energy checks
//! remain).

use super::model::{InsertDef, InsertSpec, MixDef, OverlapEstimate, StageDef, TemplateDef};
use clump_core::contact::material::effective_modulus;
use clump_core::contact::normal::hertz_max_overlap;
use clump_core::contact::{Material, NormalLaw, PairProperties};
use clump_core::health::DEFAULT_MAX_OVERLAP_RATIO;
use clump_core::wall::Wall;
use clump_core::world::WorldConfig;
use glam::DVec3;

/// The speeds and fall heights a scenario lets its bodies reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionBounds {
    /// Largest `|g|` over the stages times the domain diagonal, m²/s².
    pub g_diagonal: f64,
    /// Largest `|g|` times the domain's extent along that gravity, m²/s².
    pub g_height: f64,
    /// Largest insertion speed (translation, or rotation × diagonal) or
    /// wall speed (translation + rotation × diagonal + surface speed, also
    /// after stage changes), m/s.
    pub v_max: f64,
}

impl MotionBounds {
    /// The bounds of a scenario's domain, gravity, insertions and walls.
    pub fn new(
        config: &WorldConfig,
        inserts: &[InsertDef],
        walls: &[Wall],
        stages: &[StageDef],
    ) -> Self {
        let size = config.domain.size();
        let d = size.length();
        let gravities: Vec<DVec3> = std::iter::once(config.gravity)
            .chain(stages.iter().filter_map(|s| s.gravity))
            .collect();
        let g_diagonal = gravities.iter().map(|g| g.length() * d).fold(0.0, f64::max);
        let g_height = gravities
            .iter()
            .map(|g| g.abs().dot(size))
            .fold(0.0, f64::max);
        let mut v: f64 = 0.0;
        for i in inserts {
            match &i.kind {
                InsertSpec::File { bodies } => {
                    for b in bodies {
                        v = v.max(b.velocity.length() + b.angular_velocity.length() * d);
                    }
                }
                InsertSpec::Pack { spec, .. } => v = v.max(spec.velocity.length()),
                InsertSpec::Stream { spec, .. } => v = v.max(spec.velocity.length()),
            }
        }
        for w in walls {
            let m = &w.motion;
            v = v.max(
                m.velocity.length() + m.angular_velocity.length() * d + m.surface_velocity.length(),
            );
        }
        for c in stages.iter().flat_map(|s| &s.walls) {
            let len = |x: Option<DVec3>| x.map_or(0.0, |x| x.length());
            v = v.max(len(c.velocity) + len(c.angular_velocity) * d + len(c.surface_velocity));
        }
        MotionBounds {
            g_diagonal,
            g_height,
            v_max: v,
        }
    }

    /// Kinetic energy per kilogram that bodies may legitimately reach, J/kg:
    /// `½ (2 |g| D + v_max²)` with the domain diagonal `D` (the floor of the
    /// kinetic-energy check; 0 when not finite).
    pub fn energy_floor(&self) -> f64 {
        let e = 0.5 * (2.0 * self.g_diagonal + self.v_max * self.v_max);
        if e.is_finite() {
            e
        } else {
            0.0
        }
    }

    /// Largest impact speed, m/s: a fall across the domain's height along
    /// gravity from the largest insertion or wall speed,
    /// `√(2 |g| H + v_max²)`.
    pub fn impact_speed(&self) -> f64 {
        (2.0 * self.g_height + self.v_max * self.v_max).sqrt()
    }
}

/// Factor between the largest expected overlap and the guard's default.
pub const GUARD_MARGIN: f64 = 1.5;

/// Inputs of [`expected_overlap`], borrowed from the scenario being built.
pub struct Contacts<'a> {
    /// Templates.
    pub templates: &'a [TemplateDef],
    /// Mixes (their size factors scale the templates).
    pub mixes: &'a [MixDef],
    /// Materials.
    pub materials: &'a [Material],
    /// Material names.
    pub material_names: &'a [String],
    /// Pair properties, `n × n` by material index.
    pub pair_table: &'a [PairProperties],
    /// Walls.
    pub walls: &'a [Wall],
}

fn overlap(props: &PairProperties, e_star: f64, r_star: f64, m_star: f64, v: f64) -> f64 {
    match props.normal {
        NormalLaw::Hertz if e_star.is_finite() => hertz_max_overlap(e_star, r_star, m_star, v),
        NormalLaw::Hertz => 0.0,
        NormalLaw::Linear { kn, .. } => v * (m_star / kn).sqrt(),
    }
}

/// The largest expected overlap at impact speed `speed` (m/s); `None`
/// without templates or at zero speed.
pub fn expected_overlap(c: &Contacts, speed: f64) -> Option<OverlapEstimate> {
    if !(speed > 0.0 && speed.is_finite()) {
        return None;
    }
    let n = c.materials.len();
    // (contact radius m, mass kg, material, name) per template, at its
    // largest size factor (the Hertz ratio does not depend on it; a linear
    // spring's grows with it)
    let bodies: Vec<(f64, f64, usize, &str)> = c
        .templates
        .iter()
        .enumerate()
        .map(|(ti, t)| {
            let s = super::model::template_sizes(c.mixes, ti)
                .map(|z| z.max_scale())
                .fold(1.0, f64::max);
            let r_eq = (0.75 * t.template.volume / std::f64::consts::PI).cbrt();
            (
                r_eq.min(t.template.max_radius) * s,
                t.template.mass * s * s * s,
                t.material as usize,
                t.name.as_str(),
            )
        })
        .collect();
    let mut best: Option<OverlapEstimate> = None;
    let mut consider = |ratio: f64, what: String| {
        if ratio.is_finite() && best.as_ref().map_or(true, |b| ratio > b.ratio) {
            best = Some(OverlapEstimate { ratio, speed, what });
        }
    };
    for (i, &(ra, ma, mat_a, na)) in bodies.iter().enumerate() {
        for &(rb, mb, mat_b, nb) in &bodies[i..] {
            let props = &c.pair_table[mat_a * n + mat_b];
            let e = effective_modulus(&c.materials[mat_a], &c.materials[mat_b]);
            let d = overlap(props, e, ra * rb / (ra + rb), ma * mb / (ma + mb), speed);
            consider(d / ra.min(rb), format!("templates '{na}' and '{nb}'"));
        }
        let mut seen = Vec::new();
        for w in c.walls {
            let mw = w.material as usize;
            if seen.contains(&mw) || mw >= n {
                continue;
            }
            seen.push(mw);
            let props = &c.pair_table[mat_a * n + mw];
            let e = effective_modulus(&c.materials[mat_a], &c.materials[mw]);
            let d = overlap(props, e, ra, ma, speed);
            consider(
                d / ra,
                format!(
                    "template '{na}' on a wall of material '{}'",
                    c.material_names[mw]
                ),
            );
        }
    }
    best
}

/// The guard's default for `estimate` (see the module doc).
pub fn default_limit(estimate: Option<&OverlapEstimate>) -> f64 {
    estimate.map_or(DEFAULT_MAX_OVERLAP_RATIO, |e| {
        (GUARD_MARGIN * e.ratio).clamp(DEFAULT_MAX_OVERLAP_RATIO, 1.0)
    })
}
