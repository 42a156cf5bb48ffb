//! What the device path runs, checked before a world is uploaded: each
//! feature it does not have yet is named by the scenario key that turns it
//! on, so `clump check --device gpu` can refuse it at the key.

use clump_core::rotation::RotationScheme;
use clump_core::world::World;

/// One step of a scenario key's path: a table key or an array index.
#[derive(Debug, Clone, PartialEq)]
pub enum KeySeg {
    Key(&'static str),
    Index(usize),
}

/// One refusal: the scenario key and what the device path allows.
#[derive(Debug, Clone, PartialEq)]
pub struct Unsupported {
    /// The scenario key that selects the feature (`integrator.rotation`,
    /// `wall[2].type`); where a default selects it, the key that would
    /// change it.
    pub path: Vec<KeySeg>,
    /// What is allowed there on the device.
    pub allowed: String,
}

impl Unsupported {
    /// The key as written in docs/scenario.md: `wall[2].type`.
    pub fn key(&self) -> String {
        let mut out = String::new();
        for s in &self.path {
            match s {
                KeySeg::Key(k) if out.is_empty() => out.push_str(k),
                KeySeg::Key(k) => out.push_str(&format!(".{k}")),
                KeySeg::Index(i) => out.push_str(&format!("[{i}]")),
            }
        }
        out
    }
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "'{}' is not on the GPU path yet; allowed there: {}",
            self.key(),
            self.allowed
        )
    }
}

/// `a.b.c` as key segments.
fn keys(dotted: &'static str) -> Vec<KeySeg> {
    dotted.split('.').map(KeySeg::Key).collect()
}

/// Everything in `world` the device step does not do (empty: it runs):
/// [`unsupported_settings`] and bodies before their start step (a
/// stream's ballistic entry; [`crate::DeviceStepper`] takes those steps on
/// the CPU path).
pub fn unsupported(world: &World) -> Vec<Unsupported> {
    let mut out = unsupported_settings(world);
    if late_start(world) > world.step {
        out.push(Unsupported {
            path: keys("insert"),
            allowed: "bodies present from the start of the device run".into(),
        });
    }
    out
}

/// The last start step of a body that starts (a stream's; a driven or
/// fixed body never starts and runs on the device), 0 without one.
pub(crate) fn late_start(world: &World) -> u64 {
    let b = world.bodies();
    (0..b.len())
        .map(|i| b.start_step[i])
        .filter(|&s| s != clump_core::dof::DRIVEN)
        .max()
        .unwrap_or(0)
}

/// The settings of `world` (its scenario's keys) that the device step
/// does not run: what `clump check|run|resume --device gpu` refuse.
pub fn unsupported_settings(world: &World) -> Vec<Unsupported> {
    let mut out = Vec::new();
    let mut no = |path: Vec<KeySeg>, allowed: &str| {
        out.push(Unsupported {
            path,
            allowed: allowed.into(),
        })
    };
    let c = &world.config;
    if !matches!(
        c.rotation,
        RotationScheme::NoSquish | RotationScheme::Richardson | RotationScheme::RichardsonLiggghts
    ) {
        no(
            keys("integrator.rotation"),
            "\"no_squish\" (the default), \"richardson\" or \"richardson_liggghts\"",
        );
    }
    if c.added_mass.coefficient != 0.0 {
        no(keys("integrator.added_mass"), "none");
    }
    let t = &world.contact_table;
    if t.any_extended() || t.any_reach() {
        no(
            keys("pair"),
            "Hertz-Mindlin or linear laws, rolling resistance none, cdt or epsd, without twisting, cohesion or micro-slip",
        );
    }
    // every wall shape, motion and multi_contact the CPU path allows
    // runs (walls.rs, mesh.rs, average.rs)
    if world.heat.is_some() {
        no(keys("heat"), "off");
    }
    out
}
