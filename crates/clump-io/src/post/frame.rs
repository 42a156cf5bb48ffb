//! One output frame as the post-processing sees it: the bodies (pose,
//! velocity, mass, volume, principal inertia, template) and the contacts
//! of the force evaluation that ended at that step, world frame, SI units.
//! Taken from a running [`World`] ([`Frame::capture`]) or read back from a
//! run's saved files ([`super::read`]), so the coarse-graining, the contact
//! network and the flow measurement work the same in both.

use clump_core::boundary::Domain;
use clump_core::recorded_contacts::Partner;
use clump_core::sphere::SPHERE_ID_BITS;
use clump_core::world::World;
use glam::{DQuat, DVec3};

/// One body at a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState {
    /// Global body id (1-based, insertion order).
    pub id: u64,
    /// The scenario's template index (scaled copies map to their base).
    pub template: usize,
    /// Centre of mass, world frame, m.
    pub position: DVec3,
    /// Velocity of the centre of mass, world frame, m/s.
    pub velocity: DVec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
    /// Orientation, body frame → world frame (the body frame is the
    /// principal frame).
    pub orientation: DQuat,
    /// Mass, kg.
    pub mass: f64,
    /// Volume of the sphere union, m³.
    pub volume: f64,
    /// Principal moments of inertia, body frame, kg m².
    pub inertia: DVec3,
    /// Total force (contacts + gravity), world frame, N.
    pub force: DVec3,
    /// Total torque about the centre of mass, world frame, N m.
    pub torque: DVec3,
}

impl BodyState {
    /// Diameter of the sphere with the body's volume, m.
    pub fn equivalent_diameter(&self) -> f64 {
        (6.0 * self.volume / std::f64::consts::PI).cbrt()
    }

    /// The principal axis (unit, world frame) of the smallest principal
    /// moment: the long axis of an elongated clump.
    pub fn long_axis(&self) -> DVec3 {
        let m = self.inertia;
        let axis = if m.x <= m.y && m.x <= m.z {
            DVec3::X
        } else if m.y <= m.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        self.orientation * axis
    }
}

/// The other side of a contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// A sphere of the body with this global id.
    Body(u64),
    /// The wall with this index (scenario order).
    Wall(usize),
}

/// One touching sphere contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Global id of the body of sphere `i`.
    pub body_i: u64,
    /// The partner.
    pub partner: Side,
    /// Centre of sphere `i`, world frame, m.
    pub centre_i: DVec3,
    /// The partner's end of the contact line: the centre of sphere `j` (its
    /// image next to sphere `i` across a periodic boundary) or the wall's
    /// surface point, world frame, m.
    pub end_j: DVec3,
    /// Contact point, world frame, m.
    pub point: DVec3,
    /// Unit normal from the partner to sphere `i`, world frame.
    pub normal: DVec3,
    /// Overlap, m.
    pub overlap: f64,
    /// Force on sphere `i` (its body), world frame, N; the partner gets
    /// its negative.
    pub force: DVec3,
    /// The contact slides (tangential force at the Coulomb limit).
    pub sliding: bool,
}

impl ContactState {
    /// Magnitude of the normal force, N.
    pub fn normal_force(&self) -> f64 {
        self.force.dot(self.normal).abs()
    }

    /// Magnitude of the tangential force, N.
    pub fn tangential_force(&self) -> f64 {
        (self.force - self.normal * self.force.dot(self.normal)).length()
    }
}

/// The data of one frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Step.
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// The domain (periodic axes, extent).
    pub domain: Domain,
    /// The bodies, in storage order.
    pub bodies: Vec<BodyState>,
    /// The contacts; `None` when the frame has no force evaluation
    /// recorded (the first frame of a run, before any step).
    pub contacts: Option<Vec<ContactState>>,
}

/// The index of the template every world template is a scaled copy of
/// (the first template with its name; scenario templates map to
/// themselves).
pub fn base_templates(world: &World) -> Vec<usize> {
    let mut first: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    world
        .templates
        .iter()
        .enumerate()
        .map(|(i, t)| *first.entry(t.name.as_str()).or_insert(i))
        .collect()
}

/// The minimum image of the separation `d` in `domain`, m.
pub fn min_image(domain: &Domain, d: DVec3) -> DVec3 {
    let l = domain.size();
    let mut d = d;
    for a in 0..3 {
        if domain.periodic[a] {
            d[a] -= l[a] * (d[a] / l[a]).round();
        }
    }
    d
}

impl Frame {
    /// The world's bodies and, when the step that ended here recorded
    /// them, its contacts.
    pub fn capture(world: &World) -> Frame {
        let mut f = Frame::bodies_only(world);
        f.contacts = contacts(world);
        f
    }

    /// The world's bodies, without contacts.
    pub fn bodies_only(world: &World) -> Frame {
        let b = &world.bodies();
        let base = base_templates(world);
        let bodies = (0..b.len())
            .map(|i| {
                let t = b.template[i] as usize;
                BodyState {
                    id: b.id[i],
                    template: base[t],
                    position: b.position[i],
                    velocity: b.velocity[i],
                    angular_velocity: b.angular_velocity[i],
                    orientation: b.orientation[i],
                    mass: b.mass[i],
                    volume: world.templates[t].volume,
                    inertia: b.inertia[i],
                    force: b.force[i],
                    torque: b.torque[i],
                }
            })
            .collect();
        Frame {
            step: world.step,
            time: world.time,
            domain: world.config.domain,
            bodies,
            contacts: None,
        }
    }

    /// Body storage index by id.
    pub fn index_by_id(&self) -> std::collections::HashMap<u64, usize> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.id, i))
            .collect()
    }
}

/// The contacts of the step that ended at the world's boundary, when it
/// recorded them.
fn contacts(world: &World) -> Option<Vec<ContactState>> {
    let b = &world.bodies();
    {
        let radius = |gid: u64| -> f64 {
            let i = world.body_index(gid >> SPHERE_ID_BITS).unwrap_or(0);
            let t = &world.templates[b.template[i] as usize];
            let k = (gid & ((1 << SPHERE_ID_BITS) - 1)) as usize;
            t.spheres.get(k).map_or(0.0, |s| s.radius)
        };
        world.contacts().ok().map(|it| {
            it.map(|c| {
                let ri = radius(c.sphere_id);
                let half = 0.5 * c.overlap;
                let centre_i = c.point + c.normal * (ri - half);
                let (partner, end_j) = match c.partner {
                    Partner::Sphere { sphere_id, body_id } => (
                        Side::Body(body_id),
                        c.point - c.normal * (radius(sphere_id) - half),
                    ),
                    Partner::Wall { wall, .. } => (Side::Wall(wall), c.point + c.normal * half),
                };
                ContactState {
                    body_i: c.body_id,
                    partner,
                    centre_i,
                    end_j,
                    point: c.point,
                    normal: c.normal,
                    overlap: c.overlap,
                    force: c.force(),
                    sliding: c.sliding,
                }
            })
            .collect()
        })
    }
}
