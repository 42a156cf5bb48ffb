//! The material-pair table: one contact model for every pair of materials.

use super::{ContactModel, Material, PairProperties};

/// Contact models for every pair of materials (symmetric table).
#[derive(Debug, Clone, Default)]
pub struct ContactTable {
    n: usize,
    models: Vec<ContactModel>,
    /// Some model has a rolling couple.
    rolling: bool,
    /// Some model runs the scalar composition ([`ContactModel::is_extended`]).
    extended: bool,
    /// Some model keeps an MDR profile ([`ContactModel::keeps_slip_profile`]).
    slip: bool,
    /// Largest [`ContactModel::reach`] at `R* = 1 m` of the entries that
    /// can touch (not two rigid materials); the reach scales as `R*^{1/3}`
    /// (JKR's critical separation), 0 without JKR.
    reach_coef: f64,
}

impl ContactTable {
    /// Builds the table; `props(a, b)` gives the pair properties of materials `a`, `b`.
    pub fn new(
        materials: &[Material],
        mut props: impl FnMut(usize, usize) -> PairProperties,
    ) -> Result<Self, String> {
        let n = materials.len();
        let mut models = Vec::with_capacity(n * n);
        // the largest reach of the entries that can touch: a pair of two
        // rigid (wall) materials never does, and its filler moduli of 1 Pa
        // would give it a JKR critical separation ∝ E*^(−2/3) of the order
        // of a metre, which the Verlet skin (`World::skin`) would then
        // follow, making every sphere a candidate of every other
        let mut reach_coef = 0.0f64;
        for a in 0..n {
            for b in 0..n {
                let (lo, hi) = (a.min(b), a.max(b));
                let (mut ma, mut mb) = (materials[lo], materials[hi]);
                let both_rigid = ma.youngs_modulus.is_infinite() && mb.youngs_modulus.is_infinite();
                if both_rigid {
                    // Two rigid (wall) materials never touch each other; the
                    // entry only fills the table.
                    ma.youngs_modulus = 1.0;
                    mb.youngs_modulus = 1.0;
                    // a wall material may have density 0 (it never moves)
                    ma.density = 1.0;
                    mb.density = 1.0;
                }
                let m = ContactModel::new(&ma, &mb, &props(lo, hi))
                    .map_err(|e| format!("materials {lo} and {hi}: {e}"))?;
                if !both_rigid {
                    reach_coef = reach_coef.max(m.reach(1.0));
                }
                models.push(m);
            }
        }
        let rolling = models.iter().any(|m| m.has_rolling());
        let extended = models.iter().any(|m| m.is_extended());
        let slip = models.iter().any(|m| m.keeps_slip_profile());
        Ok(Self {
            n,
            models,
            rolling,
            extended,
            slip,
            reach_coef,
        })
    }

    /// The model for materials `a` and `b`.
    #[inline(always)]
    pub fn get(&self, a: u16, b: u16) -> &ContactModel {
        &self.models[a as usize * self.n + b as usize]
    }

    /// Index of the model for materials `a` and `b` (see [`Self::by_index`]).
    #[inline(always)]
    pub fn index(&self, a: u16, b: u16) -> u32 {
        (a as usize * self.n + b as usize) as u32
    }

    /// The model at `index` (from [`Self::index`]).
    #[inline(always)]
    pub fn by_index(&self, index: u32) -> &ContactModel {
        &self.models[index as usize]
    }

    /// Whether some model has a rolling couple.
    pub fn any_rolling(&self) -> bool {
        self.rolling
    }

    /// Whether some model keeps contacts beyond touching (JKR,
    /// [`ContactModel::reach`]).
    pub fn any_reach(&self) -> bool {
        self.reach_coef > 0.0
    }

    /// The largest reach (m) of any model for effective radii up to
    /// `r_star` (m): `max δ_c ∝ R*^{1/3}`; 0 without JKR.
    pub fn max_reach(&self, r_star: f64) -> f64 {
        if self.reach_coef > 0.0 {
            self.reach_coef * r_star.cbrt()
        } else {
            0.0
        }
    }

    /// Whether some model runs the scalar composition
    /// ([`ContactModel::is_extended`]).
    pub fn any_extended(&self) -> bool {
        self.extended
    }

    /// Whether the pairs need a rolling spring (N m, world frame): some
    /// model has a rolling couple or runs the scalar composition, which
    /// carries the rolling and twisting springs.
    pub fn keeps_rolling_spring(&self) -> bool {
        self.rolling || self.extended
    }

    /// Whether the contacts keep MDR profiles beside their histories: some
    /// model is `tangential = "mdr"` ([`super::mdr`]).
    pub fn keeps_slip_profile(&self) -> bool {
        self.slip
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::CohesionLaw;

    /// With a rigid (wall) material in the table, the reach is that of the
    /// particle pairs, not of the rigid–rigid filler (moduli of 1 Pa).
    #[test]
    fn reach_ignores_the_rigid_rigid_filler() {
        let particle = Material {
            youngs_modulus: 1e6,
            poisson_ratio: 0.3,
            density: 2500.0,
        };
        let rigid = Material {
            youngs_modulus: f64::INFINITY,
            ..particle
        };
        let p = PairProperties {
            cohesion: CohesionLaw::Jkr {
                surface_energy: 0.17,
            },
            ..PairProperties::default()
        };
        let t = ContactTable::new(&[particle, rigid], |_, _| p).unwrap();
        let r = 1e-3;
        // particle–particle has the smaller E*, so the larger δ_c ∝ E*^(−2/3)
        let want = t.get(0, 0).reach(r).max(t.get(0, 1).reach(r));
        assert_eq!(want, t.get(0, 0).reach(r));
        assert!((t.max_reach(r) - want).abs() <= 1e-12 * want);
        // δ_c of two 1 mm spheres (R* = 0.5 mm) is a few µm
        assert!(t.max_reach(r) < 1e-5, "{}", t.max_reach(r));
        assert!(t.any_reach());
    }
}
