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
    /// Largest [`ContactModel::reach`] at `R* = 1 m`; the reach scales as
    /// `R*^{1/3}` (JKR's critical separation), 0 without JKR.
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
        for a in 0..n {
            for b in 0..n {
                let (lo, hi) = (a.min(b), a.max(b));
                let (mut ma, mut mb) = (materials[lo], materials[hi]);
                if ma.youngs_modulus.is_infinite() && mb.youngs_modulus.is_infinite() {
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
                models.push(m);
            }
        }
        let rolling = models.iter().any(|m| m.has_rolling());
        let extended = models.iter().any(|m| m.is_extended());
        let reach_coef = models.iter().map(|m| m.reach(1.0)).fold(0.0, f64::max);
        Ok(Self {
            n,
            models,
            rolling,
            extended,
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
}
