//! Heat: one temperature per body (lumped: the Biot number of a grain is
//! small), conduction through every sphere–sphere and sphere–wall contact,
//! and volumetric sources (docs/theory.md T-53 … T-57).
//!
//! This module holds the settings and the conductance formulas; the stage
//! that applies them each step is `step::heat`. The body temperatures
//! (`Bodies::temperature`, K) and source powers (`Bodies::heat_source`, W)
//! live with the rest of the body state, so that every reorder, checkpoint
//! and copy of the bodies carries them; they are empty while the world has
//! no heat.

use serde::{Deserialize, Serialize};

/// Thermal properties of one material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ThermalMaterial {
    /// Thermal conductivity `k`, W/(m K) (`≥ 0`; 0 conducts nothing).
    pub conductivity: f64,
    /// Specific heat capacity `c_p`, J/(kg K) (`> 0` for a particle
    /// material; unused for a wall's).
    pub specific_heat: f64,
}

/// How the conductance of a contact follows from its geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Conductance {
    /// Batchelor & O'Brien (1977): `H = 2 k* a`, with `a = √(R* δ)` the
    /// Hertzian contact radius (T-53).
    #[default]
    BatchelorObrien,
    /// LIGGGHTS `fix heat/gran/conduction` (without `areaCorrection`):
    /// `H = 2 k* √A` with `A` the area of the circle in which the two
    /// undeformed spheres intersect (T-54).
    Geometric,
}

/// The heat settings of a world, fixed at set-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeatModel {
    /// The conductance of a contact.
    pub conductance: Conductance,
    /// Per material (index as in `World::materials`): its thermal
    /// properties; `None` for a material without them (a wall of it
    /// conducts nothing; no template may use it).
    pub materials: Vec<Option<ThermalMaterial>>,
    /// Per wall (index as in `World::walls`): its fixed temperature, K;
    /// `None` (or a wall beyond the list): adiabatic.
    pub wall_temperature: Vec<Option<f64>>,
    /// Per template: the initial temperature of its bodies, K.
    pub template_temperature: Vec<f64>,
    /// Per template: the volumetric heat source of its bodies, W/m³.
    pub template_source: Vec<f64>,
}

impl HeatModel {
    /// The conductivity of material `m`, W/(m K) (0 without thermal
    /// properties).
    #[inline]
    pub fn conductivity(&self, m: u16) -> f64 {
        self.materials
            .get(m as usize)
            .copied()
            .flatten()
            .map_or(0.0, |t| t.conductivity)
    }

    /// The fixed temperature of wall `w`, K, or `None` when adiabatic.
    #[inline]
    pub fn wall_temperature(&self, w: usize) -> Option<f64> {
        self.wall_temperature.get(w).copied().flatten()
    }
}

/// The heat of a world: its settings and what the stage measures.
#[derive(Debug, Clone, PartialEq)]
pub struct Heat {
    /// The settings.
    pub model: HeatModel,
    /// Per wall: the heat flow from the wall into the bodies in the last
    /// step, W.
    pub wall_flow: Vec<f64>,
    /// Per wall: the heat that has flowed from the wall into the bodies
    /// since the start of the run, J.
    pub wall_heat: Vec<f64>,
    /// The largest `dt Σ H / C` of any body in the last step: the step is
    /// stable and keeps temperatures within their neighbours' while it is
    /// at most 1 (T-57).
    pub stability: f64,
    /// Per body: the heat flow into it in this step, W (stage scratch).
    pub(crate) flow: Vec<f64>,
    /// Per body: the sum of its contacts' conductances, W/K (stage
    /// scratch).
    pub(crate) conductance_sum: Vec<f64>,
    // --- convection from the fluid (T-90 … T-93)
    /// The fluid's thermal properties; `None`: no convection
    /// ([`crate::world::World::set_fluid_heat`]).
    pub convection: Option<FluidHeat>,
    /// The heat flow from the fluid into the bodies in the last step, W.
    pub fluid_flow: f64,
    /// Per body: its convective conductance `h A`, W/K (stage scratch;
    /// empty without convection).
    pub(crate) convective: Vec<f64>,
    /// Per template: its `(g₀, g₁)` of [`convective_coefficients`] (stage
    /// scratch).
    pub(crate) convective_template: Vec<(f64, f64)>,
    /// On a rank of a split world: this step's heat flow through each wall
    /// touch of an owned sphere, for the sum over the ranks in one
    /// process's order (T-94; stage scratch).
    pub(crate) rank_wall_flows: Vec<RankWallFlow>,
    /// Per pair-list entry: its conductance and heat flow (stage scratch).
    pub(crate) pair_flow: Vec<(f64, f64)>,
}

/// The heat flow through one wall touch of a rank's owned sphere, with the
/// key that sorts it as one process's wall pass meets it (T-94).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub(crate) struct RankWallFlow {
    /// The wall.
    pub wall: u32,
    /// The body's place in the whole world's storage order.
    pub body_order: (u64, u64),
    /// The sphere's index in its template.
    pub sphere: u32,
    /// The touch's index among the sphere's touches of the wall.
    pub touch: u32,
    /// Heat flow from the wall into the body, W.
    pub flow: f64,
}

impl Heat {
    /// The heat of a world with `walls` walls under `model`.
    pub fn new(model: HeatModel, walls: usize) -> Self {
        Heat {
            model,
            wall_flow: vec![0.0; walls],
            wall_heat: vec![0.0; walls],
            stability: 0.0,
            flow: Vec::new(),
            conductance_sum: Vec::new(),
            convection: None,
            fluid_flow: 0.0,
            convective: Vec::new(),
            convective_template: Vec::new(),
            rank_wall_flows: Vec::new(),
            pair_flow: Vec::new(),
        }
    }
}

/// The thermal properties of the fluid the bodies are in, for convection
/// (docs/theory.md T-90 … T-93).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FluidHeat {
    /// The fluid's temperature, K (uniform).
    pub temperature: f64,
    /// The fluid's thermal conductivity `k_f`, W/(m K).
    pub conductivity: f64,
    /// The fluid's specific heat capacity `c_f`, J/(kg K).
    pub specific_heat: f64,
}

impl FluidHeat {
    /// Checks the values; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        let positive = |x: f64| x > 0.0 && x.is_finite();
        if !positive(self.temperature) {
            return Err(format!(
                "fluid temperature must be > 0 K, got {}",
                self.temperature
            ));
        }
        if !positive(self.conductivity) {
            return Err(format!(
                "fluid thermal conductivity must be > 0 W/(m K), got {}",
                self.conductivity
            ));
        }
        if !positive(self.specific_heat) {
            return Err(format!(
                "fluid specific heat must be > 0 J/(kg K), got {}",
                self.specific_heat
            ));
        }
        Ok(())
    }
}

/// (T-90) The Ranz–Marshall (1952) Nusselt number of a sphere at particle
/// Reynolds number `re` and Prandtl number `pr`: `Nu = 2 + 0.6 Re^½ Pr^⅓`.
#[inline]
pub fn ranz_marshall(re: f64, pr: f64) -> f64 {
    2.0 + 0.6 * re.sqrt() * pr.cbrt()
}

/// (T-91, T-92) The convective conductance `h A` (W/K) of a clump with the
/// fluid data `t` (volume-equivalent diameter `d_v`, sphericity `φ`) at
/// slip speed `w` (m/s) in fluid `f` with thermal properties `h`:
/// `Re = ρ_f w d_v / μ`, `Pr = c_f μ / k_f`, `h = Nu k_f / d_v`, on the
/// clump's true surface area `A = π d_v² / φ`.
#[inline]
pub fn convective_conductance(
    f: &crate::fluid::Fluid,
    h: &FluidHeat,
    t: &crate::fluid::TemplateFluid,
    w: f64,
) -> f64 {
    let (g0, g1) = convective_coefficients(f, h, t);
    g0 + g1 * w.sqrt()
}

/// T-90 … T-92 as `h A = g₀ + g₁ √w` for slip speed `w` (m/s), with the
/// clump's and the fluid's constants folded into `(g₀, g₁)`: `g₀ = 2 k_f A
/// / d_v` (W/K), `g₁ = 0.6 Pr^⅓ (ρ_f d_v / μ)^½ k_f A / d_v` (W/K per
/// (m/s)^½); once per template, so that a body costs one square root.
pub fn convective_coefficients(
    f: &crate::fluid::Fluid,
    h: &FluidHeat,
    t: &crate::fluid::TemplateFluid,
) -> (f64, f64) {
    let d = t.diameter;
    let area = std::f64::consts::PI * d * d / t.sphericity;
    let pr = h.specific_heat * f.viscosity / h.conductivity;
    let per_nu = h.conductivity * area / d;
    // Nu = 2 + 0.6 Pr^⅓ Re^½, Re^½ = (ρ_f d_v / μ)^½ √w
    let g0 = ranz_marshall(0.0, pr) * per_nu;
    let g1 = 0.6 * pr.cbrt() * (f.density * d / f.viscosity).sqrt() * per_nu;
    (g0, g1)
}

/// The harmonic combination `k* = 2 k₁ k₂ / (k₁ + k₂)` of two
/// conductivities, W/(m K) (0 when either is 0; `k` for two equal ones).
#[inline]
pub fn harmonic_conductivity(k1: f64, k2: f64) -> f64 {
    if k1 > 0.0 && k2 > 0.0 {
        2.0 * k1 * k2 / (k1 + k2)
    } else {
        0.0
    }
}

/// The conductance (W/K) of a contact between spheres of radii `r1`, `r2`
/// (m) whose centres are `dist` apart (m), with combined conductivity
/// `k_star` (W/(m K)); zero unless they overlap.
#[inline]
pub fn pair_conductance(model: Conductance, k_star: f64, r1: f64, r2: f64, dist: f64) -> f64 {
    let overlap = r1 + r2 - dist;
    if !(overlap > 0.0) || k_star == 0.0 {
        return 0.0;
    }
    match model {
        Conductance::BatchelorObrien => {
            // T-53: a = √(R* δ)
            let r_star = r1 * r2 / (r1 + r2);
            2.0 * k_star * (r_star * overlap).sqrt()
        }
        Conductance::Geometric => {
            // T-54: the area of the intersection circle, as LIGGGHTS writes it
            let r = dist;
            let area = -std::f64::consts::FRAC_PI_4
                * ((r - r1 - r2) * (r + r1 - r2) * (r - r1 + r2) * (r + r1 + r2))
                / (r * r);
            2.0 * k_star * area.max(0.0).sqrt()
        }
    }
}

/// The conductance (W/K) of a contact between a sphere of radius `r` (m)
/// and a flat wall it overlaps by `overlap` (m), with combined conductivity
/// `k_star` (W/(m K)).
#[inline]
pub fn wall_conductance(model: Conductance, k_star: f64, r: f64, overlap: f64) -> f64 {
    if !(overlap > 0.0) || k_star == 0.0 {
        return 0.0;
    }
    match model {
        // T-53 with R* = r (the wall's radius is infinite)
        Conductance::BatchelorObrien => 2.0 * k_star * (r * overlap).sqrt(),
        Conductance::Geometric => {
            // T-54: the circle in which the wall plane cuts the sphere
            let d = r - overlap;
            let area = (r * r - d * d) * std::f64::consts::PI;
            2.0 * k_star * area.max(0.0).sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn harmonic_mean_of_equal_conductivities_is_the_conductivity() {
        assert_eq!(harmonic_conductivity(3.0, 3.0), 3.0);
        assert_eq!(harmonic_conductivity(3.0, 0.0), 0.0);
        // 2·1·3/4
        assert_eq!(harmonic_conductivity(1.0, 3.0), 1.5);
    }

    #[test]
    fn geometric_area_of_equal_spheres_is_the_lens_circle() {
        // two unit spheres 1.8 apart cut in a circle of radius √(1 − 0.9²)
        let a2 = 1.0 - 0.81;
        let h = pair_conductance(Conductance::Geometric, 1.0, 1.0, 1.0, 1.8);
        let expect = 2.0 * (std::f64::consts::PI * a2).sqrt();
        assert!((h - expect).abs() < 1e-12 * expect, "{h} {expect}");
        // the wall: a plane 0.9 from the centre cuts the same circle
        let hw = wall_conductance(Conductance::Geometric, 1.0, 1.0, 0.1);
        assert!((hw - expect).abs() < 1e-12 * expect, "{hw} {expect}");
    }

    #[test]
    fn folded_convective_conductance_is_ranz_marshall() {
        use crate::fluid::{DragLaw, Fluid, TemplateFluid};
        let f = Fluid {
            density: 1.2,
            viscosity: 1.8e-5,
            velocity: glam::DVec3::ZERO,
            pressure_gradient: glam::DVec3::ZERO,
            drag: DragLaw::Stokes,
            buoyancy: false,
        };
        let h = FluidHeat {
            temperature: 300.0,
            conductivity: 0.026,
            specific_heat: 1005.0,
        };
        let t = TemplateFluid {
            volume: 1e-9,
            diameter: 1.24e-3,
            sphericity: 0.8,
        };
        for w in [0.0, 1e-3, 0.7, 30.0] {
            let re: f64 = 1.2 * w * 1.24e-3 / 1.8e-5;
            let pr: f64 = 1005.0 * 1.8e-5 / 0.026;
            let nu = 2.0 + 0.6 * re.sqrt() * pr.powf(1.0 / 3.0);
            let direct = nu * 0.026 / 1.24e-3 * std::f64::consts::PI * 1.24e-3 * 1.24e-3 / 0.8;
            let got = convective_conductance(&f, &h, &t, w);
            assert!(
                (got - direct).abs() < 1e-14 * direct,
                "w = {w}: {got} {direct}"
            );
        }
    }

    #[test]
    fn apart_spheres_conduct_nothing() {
        for m in [Conductance::BatchelorObrien, Conductance::Geometric] {
            assert_eq!(pair_conductance(m, 1.0, 1.0, 1.0, 2.0), 0.0);
            assert_eq!(wall_conductance(m, 1.0, 1.0, -1e-9), 0.0);
        }
    }
}
