//! Twisting resistance (`contact::twisting`, Marshall 2009) against its
//! closed forms: a sphere resting on a plane, spinning about the normal.

use crate::setup::{body, coincident_spheres, material, open_box, plane, world, PARTICLE};
use clump_core::contact::{PairProperties, TwistingLaw};
use glam::{DQuat, DVec3};

/// The spin-down set-up: a 2 mm sphere (E = 10 MPa, ν = 0.3, ρ = 2500
/// kg/m³, μ = 0.5, e = 0.5) at rest on a plane of its own material under
/// gravity, at its Hertz equilibrium overlap, spinning about the vertical.
/// The constants of the closed forms, computed here from the materials.
#[derive(Debug, Clone, Copy)]
pub struct SpinDown {
    /// Moment of inertia `(2/5)mr²`, kg m².
    pub inertia: f64,
    /// Twisting stiffness `k_tw = ½ k_t a²`, N m/rad.
    pub k: f64,
    /// Twisting dashpot `γ_tw = ½ γ_t a²`, N m s/rad.
    pub c: f64,
    /// Slider limit `M_max = (2/3) a μ m g`, N m.
    pub m_max: f64,
}

impl SpinDown {
    /// Spin (rad/s) at time `t` (s) after starting at `w0` (rad/s) while
    /// the contact slips: `ω₀ − (M_max/I) t` (a constant opposing couple).
    pub fn slipping(&self, w0: f64, t: f64) -> f64 {
        w0 - self.m_max / self.inertia * t
    }
    /// Spin (rad/s) at time `t` (s) after starting at `w0` (rad/s) from an
    /// unloaded spring while the contact sticks: the damped torsional
    /// oscillator `Iθ'' + γ_tw θ' + k_tw θ = 0`, `θ(0) = 0`, `θ'(0) = ω₀`:
    /// `ω = ω₀ e^{−ζω_n t}(cos ω_d t − ζ/√(1−ζ²) sin ω_d t)`.
    pub fn sticking(&self, w0: f64, t: f64) -> f64 {
        let wn = (self.k / self.inertia).sqrt();
        let zeta = self.c / (2.0 * (self.k * self.inertia).sqrt());
        let wd = wn * (1.0 - zeta * zeta).sqrt();
        w0 * (-zeta * wn * t).exp()
            * ((wd * t).cos() - zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin())
    }
}

/// Runs the spin-down from `w0` (rad/s) for `t_end` (s) at `dt` (s);
/// returns the closed forms' constants and `(t, ω_z)` every `every` steps.
pub fn spin_down(
    w0: f64,
    dt: f64,
    t_end: f64,
    every: usize,
) -> Result<(SpinDown, Vec<(f64, f64)>), String> {
    let mat = material(1e7, 0.3, 2500.0);
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.5,
        twisting: TwistingLaw::Marshall,
        ..PairProperties::default()
    };
    let g = 9.81;
    let r = 2e-3;
    let mut w = world(mat, props, dt, open_box(0.05), DVec3::new(0.0, 0.0, -g))?;
    let mut floor = plane(DVec3::ZERO, DVec3::Z);
    floor.material = PARTICLE;
    w.add_wall(floor).map_err(|e| e.to_string())?;
    let t = coincident_spheres(1, r, mat.density)?;
    let t = w.add_template(t, PARTICLE).map_err(|e| e.to_string())?;
    // closed-form constants from the materials (Hertz, Mindlin, the
    // contact's exact damping ratio)
    let m = mat.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let e_star = crate::setup::effective_modulus(&mat, &mat);
    let nu = mat.poisson_ratio;
    let g_star = 1.0 / (2.0 * 2.0 * (2.0 - nu) * (1.0 + nu) / mat.youngs_modulus);
    let delta = (m * g / (4.0 / 3.0 * e_star * r.sqrt())).powf(2.0 / 3.0);
    let a = (r * delta).sqrt();
    let beta = clump_core::contact::damping::clamped_beta(props.restitution);
    let kt = 8.0 * g_star * a;
    let gamma_t = clump_core::contact::damping::hertz_gamma(beta, kt, m);
    let sd = SpinDown {
        inertia: 0.4 * m * r * r,
        k: 0.5 * kt * a * a,
        c: 0.5 * gamma_t * a * a,
        m_max: 2.0 / 3.0 * a * props.friction * m * g,
    };
    let id = w
        .add_body(&body(
            t,
            DVec3::new(0.0, 0.0, r - delta),
            DQuat::IDENTITY,
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, w0),
        ))
        .map_err(|e| e.to_string())?;
    let mut out = vec![(0.0, w0)];
    let n = (t_end / dt / every as f64).round() as usize;
    for k in 1..=n {
        w.run(every as u64).map_err(|e| e.to_string())?;
        let b = w.body_index(id).ok_or("lost body")?;
        out.push(((k * every) as f64 * dt, w.bodies().angular_velocity[b].z));
    }
    Ok((sd, out))
}
