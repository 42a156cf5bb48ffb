//! Streaming bodies into the domain during a run at a prescribed rate.

use super::mix::{Mix, ResolvedMix, TemplateCache};
use super::pack::Orientation;
use super::region::Region;
use super::space::{body_spheres, fits, Occupancy};
use super::{InsertError, Placement};
use crate::body::BodyInit;
use crate::world::World;
use glam::DVec3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Insertion rate of a stream.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StreamRate {
    /// Bodies per second (1/s).
    BodiesPerSecond(f64),
    /// Mass per second, kg/s. Converted to bodies per second with the mix's
    /// mean body mass, so the mass rate holds on average.
    MassPerSecond(f64),
}

fn default_stream_attempts() -> u32 {
    20
}

/// What a [`StreamInserter`] inserts, where and when.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StreamSpec {
    /// Where new bodies appear (every sphere fully inside).
    pub region: Region,
    /// Which bodies.
    pub mix: Mix,
    /// How fast.
    pub rate: StreamRate,
    /// Initial centre-of-mass velocity, world frame, m/s.
    pub velocity: DVec3,
    /// Start of the insertion window, s (simulated time).
    #[serde(default)]
    pub start: f64,
    /// End of the insertion window, s; `None`: no end.
    #[serde(default)]
    pub end: Option<f64>,
    /// Outward normal of the region face through which the bodies leave
    /// (world frame, normalised internally). When given, each body moves
    /// ballistically at `velocity`, ignoring forces, until the step at which
    /// its centre of mass crosses that face; otherwise forces act at once.
    #[serde(default)]
    pub exit_normal: Option<DVec3>,
    /// Orientations (default: uniformly random).
    #[serde(default)]
    pub orientation: Orientation,
    /// Random poses tried per body and call before the body is postponed to
    /// a later call (default 20).
    #[serde(default = "default_stream_attempts")]
    pub max_attempts_per_body: u32,
    /// Initial angular velocity of every body, world frame, rad/s.
    #[serde(default)]
    pub angular_velocity: DVec3,
    /// Degrees of freedom of the bodies by the index of their (unscaled)
    /// template in the mix; a template past the end is free.
    #[serde(default)]
    pub dof: Vec<crate::dof::Dof>,
    /// Time (s) each body moves ballistically at `velocity` after its
    /// insertion, ignoring forces, before they act (LIGGGHTS'
    /// `start_step`, given by the user); when set, it replaces the
    /// exit-face rule of `exit_normal`.
    #[serde(default)]
    pub start_after: Option<f64>,
    /// 2D insertion (`[domain] dimension = 2`): every centre of mass on the
    /// plane z = this (world frame, m), every body turned about z only
    /// (see the [module docs](super)); `None`: 3D.
    #[serde(default)]
    pub plane: Option<f64>,
}

/// Inserts bodies at a rate during a run. Serializable, RNG state included,
/// so that a run resumed from a checkpoint inserts exactly the same bodies.
///
/// Call [`StreamInserter::insert_due`] once per step. The number of bodies
/// due by time `t` is `floor(rate · (min(t, end) − start))`; bodies that find
/// no free pose are postponed (kept in a backlog, also after `end`) and
/// tried again at the next call.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StreamInserter {
    spec: StreamSpec,
    /// Bodies per second (1/s).
    body_rate: f64,
    rng: ChaCha8Rng,
    scheduled: u64,
    backlog: u64,
    inserted: u64,
    postponed: u64,
    inserted_mass: f64,
    templates: TemplateCache,
    #[serde(skip)]
    resolved: Option<ResolvedMix>,
}

impl StreamInserter {
    /// A stream for `world` (its templates must exist), deterministic for `seed`.
    pub fn new(spec: StreamSpec, world: &World, seed: u64) -> Result<Self, InsertError> {
        let mut spec = spec;
        spec.region.validate()?;
        let bad = |m: String| Err(InsertError::InvalidSpec(m));
        if !spec.velocity.is_finite() {
            return bad(format!(
                "stream velocity must be finite, got {}",
                spec.velocity
            ));
        }
        if !spec.start.is_finite() {
            return bad(format!(
                "stream start time must be finite, got {}",
                spec.start
            ));
        }
        if let Some(end) = spec.end {
            if !(end.is_finite() || end == f64::INFINITY) || end < spec.start {
                return bad(format!(
                    "stream end time {end} s must not be before its start {} s",
                    spec.start
                ));
            }
        }
        if spec.max_attempts_per_body == 0 {
            return bad("stream max_attempts_per_body must be at least 1".into());
        }
        if let Some(n) = spec.exit_normal {
            let len = n.length();
            if !(len.is_finite() && len > 0.0) {
                return bad(format!(
                    "stream exit_normal must be a finite non-zero vector, got {n}"
                ));
            }
            let n = n / len;
            if spec.velocity.dot(n) <= 0.0 {
                return bad(format!(
                    "stream velocity {} does not move bodies out through the exit face with normal {n} (need velocity · normal > 0)",
                    spec.velocity
                ));
            }
            spec.exit_normal = Some(n);
        }
        let mix = spec.mix.resolve(world)?;
        let place = Placement::of(&spec.region, &spec.orientation, spec.plane);
        place.check_plane(spec.velocity, spec.angular_velocity, mix.max_radius)?;
        let body_rate = match spec.rate {
            StreamRate::BodiesPerSecond(r) => r,
            StreamRate::MassPerSecond(m) => m / mix.mean_mass,
        };
        if !(body_rate.is_finite() && body_rate >= 0.0) {
            return bad(format!(
                "stream rate must be finite and ≥ 0, got {:?}",
                spec.rate
            ));
        }
        Ok(StreamInserter {
            spec,
            body_rate,
            rng: ChaCha8Rng::seed_from_u64(seed),
            scheduled: 0,
            backlog: 0,
            inserted: 0,
            postponed: 0,
            inserted_mass: 0.0,
            templates: TemplateCache::default(),
            resolved: Some(mix),
        })
    }

    /// The specification.
    pub fn spec(&self) -> &StreamSpec {
        &self.spec
    }

    /// Insertion rate in bodies per second (1/s).
    pub fn body_rate(&self) -> f64 {
        self.body_rate
    }

    /// Bodies inserted so far.
    pub fn inserted(&self) -> u64 {
        self.inserted
    }

    /// Mass inserted so far, kg.
    pub fn inserted_mass(&self) -> f64 {
        self.inserted_mass
    }

    /// Bodies due but not yet placed (waiting for room).
    pub fn backlog(&self) -> u64 {
        self.backlog
    }

    /// How many times a body found no room and was postponed.
    pub fn postponed(&self) -> u64 {
        self.postponed
    }

    /// True when the window has ended and nothing is left to insert at time `t` (s).
    pub fn finished(&self, t: f64) -> bool {
        self.backlog == 0 && self.spec.end.is_some_and(|e| t >= e)
    }

    /// Scaled templates this stream added to the world.
    pub fn template_cache(&self) -> &TemplateCache {
        &self.templates
    }

    /// Inserts the bodies due by `world.time`; returns how many were inserted.
    pub fn insert_due(&mut self, world: &mut World) -> Result<usize, InsertError> {
        let t = world.time;
        if t < self.spec.start {
            return Ok(0);
        }
        let due = self.due_at(t);
        if due > self.scheduled {
            self.backlog += due - self.scheduled;
            self.scheduled = due;
        }
        if self.backlog == 0 {
            return Ok(0);
        }
        if self.resolved.is_none() {
            self.resolved = Some(self.spec.mix.resolve(world)?);
        }
        let mix = self.resolved.as_ref().expect("resolved above").clone();
        let mut occ = Occupancy::from_world(world, &self.spec.region, mix.max_radius);
        let mut buf = Vec::new();
        let mut n = 0;
        while self.backlog > 0 {
            let (k, scale) = mix.sample(&mut self.rng);
            let base = mix.entries[k].template;
            let t = &world.templates[base as usize];
            let margin = t.min_radius * scale;
            let mut pose = None;
            for _ in 0..self.spec.max_attempts_per_body {
                let place =
                    Placement::of(&self.spec.region, &self.spec.orientation, self.spec.plane);
                let Some((x, q)) = place.sample(&mut self.rng, margin) else {
                    continue;
                };
                body_spheres(t, scale, x, q, &mut buf);
                if fits(&buf, &self.spec.region, world, &occ) {
                    pose = Some((x, q));
                    break;
                }
            }
            let Some((x, q)) = pose else {
                self.postponed += 1;
                break;
            };
            let mass = t.mass * scale.powi(3);
            for &(c, r) in &buf {
                occ.insert(c, r);
            }
            let template = self.templates.resolve(world, base, scale)?;
            let start_step = match (self.spec.start_after, self.spec.exit_normal) {
                (Some(t), _) => world.step + (t / world.config.dt).ceil() as u64,
                (None, Some(nrm)) => {
                    let d = (self.spec.region.support(nrm) - x.dot(nrm)).max(0.0);
                    let vn = self.spec.velocity.dot(nrm).abs();
                    world.step + (d / vn / world.config.dt).ceil() as u64
                }
                (None, None) => world.step,
            };
            let mut init = BodyInit {
                velocity: self.spec.velocity,
                angular_velocity: self.spec.angular_velocity,
                ..BodyInit::at_rest(template, x, q)
            };
            let dof = self
                .spec
                .dof
                .get(base as usize)
                .copied()
                .unwrap_or_default();
            dof.apply(&mut init);
            if !dof.driven {
                init.start_step = start_step;
            }
            world.add_body(&init)?;
            self.backlog -= 1;
            self.inserted += 1;
            self.inserted_mass += mass;
            n += 1;
        }
        Ok(n)
    }

    /// Bodies due by time `t` (s) since the stream began.
    fn due_at(&self, t: f64) -> u64 {
        if t < self.spec.start {
            return 0;
        }
        let t_eff = self.spec.end.map_or(t, |e| t.min(e));
        let due = (self.body_rate * (t_eff - self.spec.start) * (1.0 + 1e-12) + 1e-9).floor();
        if due.is_finite() && due > 0.0 {
            due as u64
        } else {
            0
        }
    }

    /// The first step after `step` at which [`Self::insert_due`] has bodies
    /// to place, for a world whose time at step `k` is `k · dt`; `u64::MAX`
    /// when no more are due. A run loop may step to there without calling
    /// `insert_due` in between: the steps skipped would insert nothing.
    pub fn next_due_step(&self, step: u64, dt: f64) -> u64 {
        if self.backlog > 0 {
            return step.saturating_add(1);
        }
        let due = |k: u64| self.due_at(k as f64 * dt);
        let horizon = self.spec.end.unwrap_or(f64::INFINITY);
        if self.body_rate <= 0.0 || (horizon.is_finite() && self.due_at(horizon) <= self.scheduled)
        {
            return u64::MAX;
        }
        // the time the count passes `scheduled`, from the inverse of
        // `due_at`, then the exact step by the same formula
        let t = self.spec.start
            + ((self.scheduled + 1) as f64 - 1e-9) / (self.body_rate * (1.0 + 1e-12));
        let guess = (t / dt).floor() - 2.0;
        if !(guess < 1e18) {
            return u64::MAX;
        }
        let mut k = (guess.max(0.0) as u64).max(step.saturating_add(1));
        while due(k) <= self.scheduled {
            k += 1;
        }
        k
    }
}
