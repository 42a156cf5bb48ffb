//! Particle mixes: which templates to insert, in which proportions and sizes.

use super::InsertError;
use crate::shape::ClumpTemplate;
use crate::world::World;
use rand::Rng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Distribution of the length scale factor (dimensionless) applied to a
/// template: every sphere centre and radius is multiplied by it, at the same
/// density (mass × s³).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum SizeDistribution {
    /// Always the same scale factor.
    Fixed {
        /// Scale factor (> 0).
        scale: f64,
    },
    /// Uniform in `[min, max]`.
    Uniform {
        /// Smallest scale factor (> 0).
        min: f64,
        /// Largest scale factor (≥ min).
        max: f64,
    },
    /// Normal with mean `mean` and standard deviation `std`, truncated to
    /// `[min, max]` (by rejection).
    Normal {
        /// Mean scale factor.
        mean: f64,
        /// Standard deviation (≥ 0).
        std: f64,
        /// Smallest scale factor (> 0).
        min: f64,
        /// Largest scale factor (≥ min).
        max: f64,
    },
}

impl Default for SizeDistribution {
    /// `Fixed { scale: 1 }`: the template as it is.
    fn default() -> Self {
        SizeDistribution::Fixed { scale: 1.0 }
    }
}

impl SizeDistribution {
    /// Checks that the parameters are finite and positive and that the
    /// interval `[min, max]` is non-empty.
    pub fn validate(&self) -> Result<(), InsertError> {
        let bad = |msg: String| Err(InsertError::InvalidSpec(msg));
        match *self {
            SizeDistribution::Fixed { scale } => {
                if !(scale.is_finite() && scale > 0.0) {
                    return bad(format!(
                        "fixed size scale must be finite and > 0, got {scale}"
                    ));
                }
            }
            SizeDistribution::Uniform { min, max } => {
                if !(min.is_finite() && max.is_finite() && min > 0.0 && max >= min) {
                    return bad(format!(
                        "uniform size needs 0 < min ≤ max, got min = {min}, max = {max}"
                    ));
                }
            }
            SizeDistribution::Normal {
                mean,
                std,
                min,
                max,
            } => {
                if !(mean.is_finite() && std.is_finite() && std >= 0.0) {
                    return bad(format!("normal size needs a finite mean and std ≥ 0, got mean = {mean}, std = {std}"));
                }
                if !(min.is_finite() && max.is_finite() && min > 0.0 && max >= min) {
                    return bad(format!(
                        "normal size needs 0 < min ≤ max, got min = {min}, max = {max}"
                    ));
                }
                if std == 0.0 && !(min..=max).contains(&mean) {
                    return bad(format!("normal size with std = 0 needs min ≤ mean ≤ max, got mean = {mean} outside [{min}, {max}]"));
                }
                if std > 0.0 && ((min - mean) / std > 6.0 || (mean - max) / std > 6.0) {
                    return bad(format!(
                        "normal size: the interval [{min}, {max}] lies more than 6 standard deviations from the mean {mean}"
                    ));
                }
            }
        }
        Ok(())
    }

    /// Draws one scale factor.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        match *self {
            SizeDistribution::Fixed { scale } => scale,
            SizeDistribution::Uniform { min, max } => {
                if max > min {
                    min + (max - min) * rng.gen::<f64>()
                } else {
                    min
                }
            }
            SizeDistribution::Normal {
                mean,
                std,
                min,
                max,
            } => {
                if std == 0.0 {
                    return mean.clamp(min, max);
                }
                let n = Normal::new(mean, std).expect("validated std");
                for _ in 0..10_000 {
                    let s = n.sample(rng);
                    if (min..=max).contains(&s) {
                        return s;
                    }
                }
                mean.clamp(min, max)
            }
        }
    }

    /// Expected value of s³ (dimensionless): the mean volume (and mass)
    /// factor of a scaled template.
    pub fn mean_cube(&self) -> f64 {
        match *self {
            SizeDistribution::Fixed { scale } => scale.powi(3),
            SizeDistribution::Uniform { min, max } => {
                if max > min {
                    (max.powi(4) - min.powi(4)) / (4.0 * (max - min))
                } else {
                    min.powi(3)
                }
            }
            SizeDistribution::Normal {
                mean,
                std,
                min,
                max,
            } => {
                if std == 0.0 || max == min {
                    return mean.clamp(min, max).powi(3);
                }
                // Simpson's rule on the truncated density.
                let n = 2000;
                let h = (max - min) / n as f64;
                let (mut w_sum, mut m_sum) = (0.0, 0.0);
                for i in 0..=n {
                    let s = min + i as f64 * h;
                    let c = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    let p = (-0.5 * ((s - mean) / std).powi(2)).exp();
                    w_sum += c * p;
                    m_sum += c * p * s.powi(3);
                }
                if w_sum > 0.0 {
                    m_sum / w_sum
                } else {
                    mean.clamp(min, max).powi(3)
                }
            }
        }
    }

    /// Largest possible scale factor.
    pub fn max_scale(&self) -> f64 {
        match *self {
            SizeDistribution::Fixed { scale } => scale,
            SizeDistribution::Uniform { max, .. } | SizeDistribution::Normal { max, .. } => max,
        }
    }

    /// Smallest possible scale factor.
    pub fn min_scale(&self) -> f64 {
        match *self {
            SizeDistribution::Fixed { scale } => scale,
            SizeDistribution::Uniform { min, .. } | SizeDistribution::Normal { min, .. } => min,
        }
    }
}

/// How the fractions of a [`Mix`] are counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FractionBasis {
    /// Fractions of the number of bodies.
    #[default]
    Number,
    /// Fractions of the inserted mass.
    Mass,
}

/// One component of a [`Mix`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MixEntry {
    /// Index of the base template in the world.
    pub template: u32,
    /// Relative share (> 0; normalised over the entries), by number or by
    /// mass according to [`Mix::basis`].
    pub fraction: f64,
    /// Size distribution (length scale factor of the base template).
    #[serde(default)]
    pub size: SizeDistribution,
}

/// A particle mix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mix {
    /// Whether fractions count bodies or mass.
    #[serde(default)]
    pub basis: FractionBasis,
    /// The components.
    pub entries: Vec<MixEntry>,
}

impl Mix {
    /// A mix of a single template at its own size.
    pub fn single(template: u32) -> Self {
        Mix {
            basis: FractionBasis::Number,
            entries: vec![MixEntry {
                template,
                fraction: 1.0,
                size: SizeDistribution::default(),
            }],
        }
    }

    /// Checks the entries against the world's templates and resolves the
    /// selection probabilities.
    pub fn resolve(&self, world: &World) -> Result<ResolvedMix, InsertError> {
        if self.entries.is_empty() {
            return Err(InsertError::InvalidSpec(
                "the particle mix has no entries".into(),
            ));
        }
        let mut entries = Vec::with_capacity(self.entries.len());
        let mut weights = Vec::with_capacity(self.entries.len());
        for (k, e) in self.entries.iter().enumerate() {
            let t = world.templates.get(e.template as usize).ok_or_else(|| {
                InsertError::InvalidSpec(format!(
                    "mix entry {k} uses template {}, but the world has {} templates",
                    e.template,
                    world.templates.len()
                ))
            })?;
            if !(e.fraction.is_finite() && e.fraction > 0.0) {
                return Err(InsertError::InvalidSpec(format!(
                    "mix entry {k} (template '{}') needs a fraction > 0, got {}",
                    t.name, e.fraction
                )));
            }
            e.size.validate()?;
            let mean_cube = e.size.mean_cube();
            let mean_mass = t.mass * mean_cube;
            let w = match self.basis {
                FractionBasis::Number => e.fraction,
                FractionBasis::Mass => e.fraction / mean_mass,
            };
            weights.push(w);
            entries.push(*e);
        }
        let total: f64 = weights.iter().sum();
        let mut cumulative = Vec::with_capacity(weights.len());
        let mut acc = 0.0;
        let mut probability = Vec::with_capacity(weights.len());
        for w in &weights {
            acc += w / total;
            cumulative.push(acc);
            probability.push(w / total);
        }
        let mut mean_volume = 0.0;
        let mut mean_mass = 0.0;
        let mut max_radius: f64 = 0.0;
        let mut max_bounding: f64 = 0.0;
        for (e, p) in entries.iter().zip(&probability) {
            let t = &world.templates[e.template as usize];
            let c = e.size.mean_cube();
            mean_volume += p * t.volume * c;
            mean_mass += p * t.mass * c;
            max_radius = max_radius.max(t.max_radius * e.size.max_scale());
            max_bounding = max_bounding.max(t.bounding_radius * e.size.max_scale());
        }
        Ok(ResolvedMix {
            entries,
            cumulative,
            probability,
            mean_volume,
            mean_mass,
            max_radius,
            max_bounding,
        })
    }
}

/// A [`Mix`] checked against a world, with its selection probabilities.
#[derive(Debug, Clone)]
pub struct ResolvedMix {
    /// The entries.
    pub entries: Vec<MixEntry>,
    cumulative: Vec<f64>,
    /// Probability of picking each entry per inserted body.
    pub probability: Vec<f64>,
    /// Expected volume of one inserted body, m³.
    pub mean_volume: f64,
    /// Expected mass of one inserted body, kg.
    pub mean_mass: f64,
    /// Largest sphere radius any inserted body can have, m.
    pub max_radius: f64,
    /// Largest bounding radius any inserted body can have, m.
    pub max_bounding: f64,
}

impl ResolvedMix {
    /// Draws an entry index and a scale factor.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> (usize, f64) {
        let u: f64 = rng.gen();
        let k = self
            .cumulative
            .iter()
            .position(|&c| u < c)
            .unwrap_or(self.entries.len() - 1);
        let s = self.entries[k].size.sample(rng);
        (k, s)
    }
}

/// Scaled templates already added to a world, keyed by (base template,
/// scale factor bits). Serializable so that a resumed run reuses the same
/// template indices (the run layer must re-add the world's non-scenario
/// templates, `world.templates[n_scenario..]`, in order before restoring).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct TemplateCache {
    /// (base template, scale factor as f64 bits, template index in the world),
    /// in the order they were added.
    pub entries: Vec<(u32, u64, u32)>,
    /// Lookup index over `entries` (rebuilt after deserialization).
    #[serde(skip)]
    index: HashMap<(u32, u64), u32>,
}

impl PartialEq for TemplateCache {
    fn eq(&self, other: &Self) -> bool {
        self.entries == other.entries
    }
}

impl TemplateCache {
    /// The world template index for `base` scaled by `scale`: the base itself
    /// for a scale of exactly 1, a cached scaled copy, or a newly added
    /// [`ClumpTemplate::scaled`] copy with the base's material.
    pub fn resolve(
        &mut self,
        world: &mut World,
        base: u32,
        scale: f64,
    ) -> Result<u32, InsertError> {
        if scale == 1.0 {
            return Ok(base);
        }
        let bits = scale.to_bits();
        if self.index.len() != self.entries.len() {
            self.index = self.entries.iter().map(|e| ((e.0, e.1), e.2)).collect();
        }
        if let Some(&idx) = self.index.get(&(base, bits)) {
            // also after a restart, whose world re-added the scaled copies
            world.inherit_template_heat(idx, base);
            return Ok(idx);
        }
        let t: ClumpTemplate = world.templates[base as usize].scaled(scale);
        let material = world.templates.material(base as usize);
        let idx = world.add_template(t, material)?;
        world.inherit_template_heat(idx, base);
        self.entries.push((base, bits, idx));
        self.index.insert((base, bits), idx);
        Ok(idx)
    }
}
