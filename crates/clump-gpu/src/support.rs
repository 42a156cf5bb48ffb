//! What the device path runs, checked before a world is uploaded: each
//! feature it does not have yet is named by the scenario key that turns it
//! on, so `clump check --device gpu` can refuse it at the key.

use clump_core::rotation::RotationScheme;
use clump_core::wall::WallShape;
use clump_core::world::World;
use glam::DVec3;

/// One refusal: the scenario key and what the device path allows.
#[derive(Debug, Clone, PartialEq)]
pub struct Unsupported {
    /// The scenario key (dotted path) that selects the feature.
    pub key: String,
    /// What is allowed there on the device.
    pub allowed: String,
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "key '{}': not on the GPU path yet; allowed: {}", self.key, self.allowed)
    }
}

/// Everything in `world` the device step does not do (empty: it runs).
pub fn unsupported(world: &World) -> Vec<Unsupported> {
    let mut out = Vec::new();
    let mut no = |key: &str, allowed: &str| {
        out.push(Unsupported { key: key.into(), allowed: allowed.into() })
    };
    let c = &world.config;
    if c.rotation != RotationScheme::RichardsonLiggghts {
        no("simulation.rotation", "\"richardson_liggghts\" (the others need f64 sin/cos, see ARCHITECTURE.md)");
    }
    if c.domain.periodic.iter().any(|&p| p) {
        no("domain.periodic", "false on every axis");
    }
    if c.added_mass.coefficient != 0.0 {
        no("fluid.added_mass", "none");
    }
    if c.multi_contact != clump_core::multi_contact::MultiContact::Sum {
        no("contact.multi_contact", "\"sum\"");
    }
    let t = &world.contact_table;
    if t.any_extended() || t.any_rolling() || t.any_reach() {
        no("contact.*", "Hertz-Mindlin or linear laws without rolling, twisting, cohesion or micro-slip");
    }
    for (k, w) in world.walls.iter().enumerate() {
        if !matches!(w.shape, WallShape::Plane { .. }) {
            no(&format!("walls[{k}].type"), "\"plane\"");
        }
        let m = &w.motion;
        if m.velocity != DVec3::ZERO || m.angular_velocity != DVec3::ZERO || m.surface_velocity != DVec3::ZERO {
            no(&format!("walls[{k}].motion"), "none (static walls)");
        }
        if w.multi_contact != clump_core::multi_contact::MultiContact::Sum || !w.active {
            no(&format!("walls[{k}]"), "active, multi_contact = \"sum\"");
        }
    }
    let b = world.bodies();
    let free = (0..b.len()).all(|i| b.force_flag[i] == [true; 3] && b.torque_flag[i] == [true; 3]);
    if !free {
        no("bodies.dof", "every axis free");
    }
    if (0..b.len()).any(|i| b.start_step[i] > world.step) {
        no("insert (bodies with a later start step)", "bodies that have started");
    }
    if world.heat.is_some() {
        no("heat", "off");
    }
    out
}
