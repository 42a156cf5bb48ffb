//! `[domain] dimension = 2`: the planar case of docs/theory.md. Motion in the x–y plane
//! and rotation about z only: every template is re-framed so that body z is
//! its plane normal (`ClumpTemplate::planar`), every body's force flag z
//! and torque flags x, y are off, and bodies start in the plane's motion
//! (no z velocity, no x/y angular velocity, turned about z only). Bodies
//! come from body files (`kind = "file"`), or from packing and streams in
//! the mid-plane z of their region (`PackSpec::plane`, turned about z
//! only; clump_core::insert).

use super::Seg::{I, K};
use super::{Cx, InsertDef, InsertSpec, StageDef, TemplateDef, R};
use clump_core::dof::Dof;
use clump_core::insert::{Orientation, Region};
use glam::{DQuat, DVec3};

/// Reads `[domain] dimension`: `Some(true)` for 2, `Some(false)` for 3.
pub(super) fn two_d(cx: &Cx, dimension: Option<u8>) -> R<bool> {
    match dimension {
        None | Some(3) => Ok(false),
        Some(2) => Ok(true),
        Some(d) => Err(cx
            .err(
                &[K("domain"), K("dimension")],
                format!("dimension must be 2 or 3, found {d}"),
            )
            .label("2 (x–y plane, rotation about z) or 3")),
    }
}

/// Re-frames every template for the plane (errors name the template).
pub(super) fn templates(cx: &Cx, templates: &mut [TemplateDef]) -> R<()> {
    for (i, t) in templates.iter_mut().enumerate() {
        t.template = t.template.planar().map_err(|e| {
            cx.err(
                &[K("template"), I(i)],
                format!("template '{}' cannot be used in 2D: {e}", t.name),
            )
            .note("note: [domain] dimension = 2 needs clumps whose sphere centres lie in one plane z = const")
        })?;
        t.dof.force_flag[2] = false;
        t.dof.torque_flag[0] = false;
        t.dof.torque_flag[1] = false;
    }
    Ok(())
}

/// Checks and restricts the inserts and gravity to the plane.
pub(super) fn inserts(
    cx: &Cx,
    inserts: &mut [InsertDef],
    gravity: DVec3,
    stages: &[StageDef],
) -> R<()> {
    let g_off = |g: DVec3| g.z != 0.0;
    if g_off(gravity) {
        return Err(cx.err(
            &[K("simulation"), K("gravity")],
            format!(
                "in 2D gravity lies in the x–y plane: its z component must be 0, found {gravity}"
            ),
        ));
    }
    for (i, s) in stages.iter().enumerate() {
        if s.gravity.is_some_and(g_off) {
            return Err(cx.err(
                &[K("stage"), I(i), K("gravity")],
                "in 2D gravity lies in the x–y plane: its z component must be 0",
            ));
        }
    }
    for (i, ins) in inserts.iter_mut().enumerate() {
        // the pack's and the stream's specs have the same fields
        macro_rules! placed {
            ($spec:expr) => {
                Placed {
                    region: &$spec.region,
                    velocity: $spec.velocity,
                    angular_velocity: $spec.angular_velocity,
                    orientation: &mut $spec.orientation,
                    dof: &mut $spec.dof,
                    plane: &mut $spec.plane,
                }
            };
        }
        let p = match &mut ins.kind {
            InsertSpec::File { bodies } => {
                file_bodies(cx, i, bodies)?;
                continue;
            }
            InsertSpec::Pack { spec, .. } => placed!(spec),
            InsertSpec::Stream { spec, .. } => placed!(spec),
        };
        p.in_plane(cx, i)?;
    }
    Ok(())
}

/// Checks the bodies of file insert `i` for the plane and restricts them
/// to it.
fn file_bodies(cx: &Cx, i: usize, bodies: &mut [clump_core::body::BodyInit]) -> R<()> {
    for (k, b) in bodies.iter_mut().enumerate() {
        let q = b.orientation;
        let why = if q.x.abs() > 1e-12 || q.y.abs() > 1e-12 {
            Some("is turned about an axis other than z")
        } else if b.velocity.z != 0.0 {
            Some("has a z velocity")
        } else if b.angular_velocity.x != 0.0 || b.angular_velocity.y != 0.0 {
            Some("has an angular velocity about x or y")
        } else {
            None
        };
        if let Some(why) = why {
            return Err(cx.err(
                    &[K("insert"), I(i), K("file")],
                    format!("in 2D body {} of the file {why}; bodies move in the x–y plane and turn about z", k + 1),
                ));
        }
        b.orientation = DQuat::from_xyzw(0.0, 0.0, q.z, q.w).normalize();
        b.force_flag[2] = false;
        b.torque_flag[0] = false;
        b.torque_flag[1] = false;
    }
    Ok(())
}

/// What a pack or stream insert gives its bodies, checked for the plane.
struct Placed<'a> {
    region: &'a Region,
    velocity: DVec3,
    angular_velocity: DVec3,
    orientation: &'a mut Orientation,
    dof: &'a mut [Dof],
    plane: &'a mut Option<f64>,
}

impl Placed<'_> {
    /// Checks that insert `i` keeps its bodies in the plane (no z velocity,
    /// no angular velocity about x or y, a fixed orientation turned about z
    /// only), turns off every body's force flag z and torque flags x, y,
    /// and sets the plane: the mid-plane z of the region (m).
    fn in_plane(self, cx: &Cx, i: usize) -> R<()> {
        let at = |key: &'static str| [K("insert"), I(i), K(key)];
        if self.velocity.z != 0.0 {
            return Err(cx.err(
                &at("velocity"),
                format!("in 2D the bodies move in the x–y plane: the z component of the velocity must be 0, found {}", self.velocity.z),
            ));
        }
        let w = self.angular_velocity;
        if w.x != 0.0 || w.y != 0.0 {
            return Err(cx.err(
                &at("angular_velocity"),
                format!("in 2D the bodies turn about z only: the x and y components of the angular velocity must be 0, found {w}"),
            ));
        }
        if let Orientation::Fixed { quaternion: q } = *self.orientation {
            if q.x.abs() > 1e-12 || q.y.abs() > 1e-12 {
                return Err(cx
                    .err(
                        &at("orientation"),
                        format!("in 2D the bodies turn about z only: the orientation's x and y parts must be 0, found [{}, {}, {}, {}]", q.w, q.x, q.y, q.z),
                    )
                    .note("note: [w, 0, 0, z], or euler angles with theta = 0"));
            }
            *self.orientation = Orientation::Fixed {
                quaternion: DQuat::from_xyzw(0.0, 0.0, q.z, q.w).normalize(),
            };
        }
        for d in self.dof.iter_mut() {
            d.force_flag[2] = false;
            d.torque_flag[0] = false;
            d.torque_flag[1] = false;
        }
        let (lo, hi) = self.region.bounds();
        *self.plane = Some(0.5 * (lo.z + hi.z));
        Ok(())
    }
}
