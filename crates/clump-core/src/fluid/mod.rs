//! Particles in a fluid (docs/theory.md §16, T-60 to T-68): drag with the
//! local void fraction, buoyancy and the pressure-gradient force on each
//! clump, as its volume-equivalent sphere with the Hölzer–Sommerfeld shape
//! correction; the per-body arrays a coupled CFD code sets (fluid velocity,
//! void fraction, external forces); and the void fraction on a grid.
//!
//! The fluid force on a clump is computed once per body from its centre
//! of mass velocity, not per sphere: a clump's spheres overlap, so the
//! per-sphere sum of single-sphere drags overcounts (two coincident
//! spheres would double it), and the volume-equivalent sphere with a
//! sphericity correction is the standard for non-spherical particles in
//! unresolved CFD–DEM (Hölzer & Sommerfeld 2008). No fluid torque.

pub mod coupling;
pub mod drag;
pub mod grid;
pub mod shape;
pub mod void;

pub use coupling::BodyCoupling;
pub use drag::FluidProps;
use glam::DVec3;
pub use grid::VelocityGrid;
use serde::{Deserialize, Serialize};

/// A drag law (docs/theory.md T-60 to T-64).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum DragLaw {
    /// Stokes, `3π μ d`.
    Stokes,
    /// Schiller & Naumann (1933), single particle.
    SchillerNaumann,
    /// Di Felice (1994), with Dallavalle's `C_d`.
    DiFelice,
    /// Beetstra, van der Hoef & Kuipers (2007).
    Beetstra,
    /// Gidaspow (1994): Ergun below ε = 0.8, Wen–Yu above.
    Gidaspow,
}

impl DragLaw {
    /// The scenario names of the laws, in order.
    pub const NAMES: [&'static str; 5] = [
        "stokes",
        "schiller_naumann",
        "di_felice",
        "beetstra",
        "gidaspow",
    ];

    /// The law named `name` (see [`DragLaw::NAMES`]).
    pub fn from_name(name: &str) -> Option<Self> {
        let all = [
            DragLaw::Stokes,
            DragLaw::SchillerNaumann,
            DragLaw::DiFelice,
            DragLaw::Beetstra,
            DragLaw::Gidaspow,
        ];
        Self::NAMES.iter().position(|n| *n == name).map(|k| all[k])
    }

    /// The drag coefficient `β` (kg/s) of a sphere of diameter `d` (m) at
    /// void fraction `eps` and slip speed `w` (m/s): `F_d = β (u − v)`.
    pub fn beta(self, f: FluidProps, d: f64, eps: f64, w: f64) -> f64 {
        match self {
            DragLaw::Stokes => drag::stokes(f, d, eps, w),
            DragLaw::SchillerNaumann => drag::schiller_naumann(f, d, eps, w),
            DragLaw::DiFelice => drag::di_felice(f, d, eps, w),
            DragLaw::Beetstra => drag::beetstra(f, d, eps, w),
            DragLaw::Gidaspow => drag::gidaspow(f, d, eps, w),
        }
    }
}

/// The fluid the bodies are in: uniform properties; the velocity is
/// uniform unless a driver sets it per body ([`BodyCoupling`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Fluid {
    /// Density, kg/m³.
    pub density: f64,
    /// Dynamic viscosity, Pa s.
    pub viscosity: f64,
    /// Interstitial velocity where no per-body value is set, world frame, m/s.
    pub velocity: DVec3,
    /// Pressure gradient beyond the hydrostatic one, world frame, Pa/m:
    /// the force `−V ∇p` on a body of volume `V` (T-67).
    pub pressure_gradient: DVec3,
    /// The drag law.
    pub drag: DragLaw,
    /// Buoyancy in the hydrostatic pressure field, `−ρ_f V g` (T-66).
    pub buoyancy: bool,
}

impl Fluid {
    /// Checks the values; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.density.is_finite() && self.density > 0.0) {
            return Err(format!(
                "fluid density must be > 0 kg/m³, got {}",
                self.density
            ));
        }
        if !(self.viscosity.is_finite() && self.viscosity > 0.0) {
            return Err(format!(
                "fluid viscosity must be > 0 Pa s, got {}",
                self.viscosity
            ));
        }
        if !self.velocity.is_finite() {
            return Err(format!(
                "fluid velocity must be finite, got {}",
                self.velocity
            ));
        }
        if !self.pressure_gradient.is_finite() {
            return Err(format!(
                "fluid pressure_gradient must be finite, got {}",
                self.pressure_gradient
            ));
        }
        Ok(())
    }

    /// The properties a drag law reads.
    pub fn props(&self) -> FluidProps {
        FluidProps {
            rho: self.density,
            mu: self.viscosity,
        }
    }
}

/// What the fluid force reads of a template: its volume and
/// volume-equivalent diameter, and its sphericity (T-65).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemplateFluid {
    /// Volume of the union of the spheres, m³.
    pub volume: f64,
    /// `(6V/π)^{1/3}`, m.
    pub diameter: f64,
    /// Sphericity `φ`: the area of the volume-equivalent sphere over the
    /// surface area of the union (1 for one sphere).
    pub sphericity: f64,
}

impl TemplateFluid {
    /// The fluid data of `t`.
    pub fn of(t: &crate::shape::ClumpTemplate) -> Self {
        let diameter = (6.0 * t.volume / std::f64::consts::PI).cbrt();
        let sphericity = if t.spheres.len() == 1 {
            1.0
        } else {
            let area = shape::union_area(&t.spheres);
            (std::f64::consts::PI * diameter * diameter / area).min(1.0)
        };
        TemplateFluid {
            volume: t.volume,
            diameter,
            sphericity,
        }
    }
}

/// A body's fluid load at its velocity `v` in fluid velocity `u` and void
/// fraction `eps` (all world frame): the drag coefficient `β` (kg/s,
/// T-60..T-65; the crosswise sphericity taken equal to `φ`, the
/// orientation average not being known) and the force other than drag,
/// buoyancy plus pressure gradient (N).
#[inline]
pub fn body_load(
    f: &Fluid,
    t: &TemplateFluid,
    gravity: DVec3,
    v: DVec3,
    u: DVec3,
    eps: f64,
) -> (f64, DVec3) {
    let w = (u - v).length();
    let props = f.props();
    let mut beta = f.drag.beta(props, t.diameter, eps, w);
    if t.sphericity < 1.0 {
        let re = props.rho * w * t.diameter / props.mu;
        beta *= drag::shape_factor(re, t.sphericity, t.sphericity);
    }
    let mut other = -t.volume * f.pressure_gradient;
    if f.buoyancy {
        other -= f.density * t.volume * gravity;
    }
    (beta, other)
}

/// (T-68) The factor of the exponential drag integrator: with the drag
/// coefficient and the other forces frozen over a step, the velocity
/// relaxes towards its terminal value as `exp(−x)`, `x = β dt/m'`; the
/// load `c (F_o + β(u − v))` with `c = (1 − e^{−x})/x`, applied over the
/// step's two half kicks, reproduces that exactly, for any `x`.
#[inline]
pub fn relaxation_factor(x: f64) -> f64 {
    if x > 1e-12 {
        -(-x).exp_m1() / x
    } else {
        1.0
    }
}

/// A world's fluid with the data of each of its templates, in template order.
#[derive(Debug, Clone)]
pub struct FluidState {
    /// The fluid.
    pub fluid: Fluid,
    /// Per template: what the fluid force reads of it.
    pub templates: Vec<TemplateFluid>,
    /// The velocity field on a grid, sampled at each body's centre of
    /// mass (where no per-body velocity is set); None: the uniform velocity.
    pub grid: Option<std::sync::Arc<VelocityGrid>>,
    /// A void-fraction field set by a coupled CFD code, read at each
    /// body's centre of mass (where no per-body value is set); None: 1.
    pub void_field: Option<std::sync::Arc<void::VoidField>>,
}
