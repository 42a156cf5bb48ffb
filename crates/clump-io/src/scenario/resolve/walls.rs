//! `[[wall]]`: planes, cylinders, boxes and triangle meshes with their motion.

use super::keys::{kind_keys, kind_specific, WALL_TYPE_KEYS};
use super::raw::*;
use super::Seg::{I, K};
use super::{lookup, unique_name, v3, Cx, R};
use crate::scenario::diag::num;
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape};
use glam::{DQuat, DVec3};

/// The walls, in file order: their names, the walls, the meshes they refer
/// to and each wall's torque point.
#[allow(clippy::type_complexity)]
pub(super) fn walls(
    cx: &mut Cx,
    raw: &RawScenario,
    material_names: &[String],
) -> R<(Vec<String>, Vec<Wall>, Vec<TriMesh>, Vec<Option<DVec3>>)> {
    // ---------------- walls
    let mut wall_names: Vec<String> = Vec::new();
    let mut walls: Vec<Wall> = Vec::new();
    let mut meshes: Vec<TriMesh> = Vec::new();
    let mut torque_points: Vec<Option<DVec3>> = Vec::new();
    let global_multi_contact = raw.simulation.as_ref().and_then(|s| s.multi_contact);
    for (i, w) in raw.wall.iter().enumerate() {
        let built =
            build_wall(cx, i, w, material_names, &wall_names, &mut meshes).and_then(|wall| {
                let tp = w
                    .torque_point
                    .map(|a| cx.vec3(&[K("wall"), I(i), K("torque_point")], a, "torque_point"))
                    .transpose()?;
                Ok((wall, tp))
            });
        let Ok((mut wall, tp)) = built.map_err(|d| cx.errors.push(d)) else {
            continue;
        };
        // [simulation] multi_contact is also the walls' default
        if let (None, Some(mc)) = (w.multi_contact, global_multi_contact) {
            wall.multi_contact = mc;
        }
        torque_points.push(tp);
        wall_names.push(wall.name.clone());
        walls.push(wall);
    }
    cx.barrier()?;
    Ok((wall_names, walls, meshes, torque_points))
}

fn build_wall(
    cx: &mut Cx,
    i: usize,
    w: &RawWall,
    material_names: &[String],
    seen: &[String],
    meshes: &mut Vec<TriMesh>,
) -> R<Wall> {
    let tp = [K("wall"), I(i)];
    let p = |k: &'static str| [K("wall"), I(i), K(k)];
    let name = w
        .name
        .clone()
        .ok_or_else(|| cx.missing(&tp, "[[wall]]", "name", "name = \"floor\""))?;
    unique_name(cx, &p("name"), "wall", &name, seen)?;
    let mname = w
        .material
        .as_ref()
        .ok_or_else(|| cx.missing(&tp, "[[wall]]", "material", "the name of a [[material]]"))?;
    let material = lookup(cx, &p("material"), "material", mname, material_names)? as u16;
    let kind = w.kind.ok_or_else(|| {
        cx.missing(
            &tp,
            "[[wall]]",
            "type",
            "type = \"plane\" (or \"cylinder\", \"box\", \"mesh\")",
        )
    })?;
    let kname = match kind {
        WallKind::Plane => "plane",
        WallKind::Cylinder => "cylinder",
        WallKind::Box => "box",
        WallKind::Mesh => "mesh",
    };
    let allowed = kind_keys(WALL_TYPE_KEYS, kname);
    for k in kind_specific(WALL_TYPE_KEYS) {
        if cx.src.has(&p(k)) && !allowed.contains(&k) {
            return Err(cx
                .src
                .error_at_key(
                    &p(k),
                    format!("'{k}' does not apply to a wall of type \"{kname}\""),
                )
                .label(format!("a {kname} uses {}", allowed.join(", "))));
        }
    }
    let req3 = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>, help: &str| -> R<[f64; 3]> {
        v.ok_or_else(|| cx.missing(&tp, &format!("[[wall]] of type \"{kname}\""), k, help))
    };
    let shape = match kind {
        WallKind::Plane => {
            let point = cx.vec3(
                &p("point"),
                req3(
                    cx,
                    "point",
                    w.point,
                    "a point on the plane in m, point = [0, 0, 0]",
                )?,
                "point",
            )?;
            let normal = cx.unit(
                &p("normal"),
                req3(
                    cx,
                    "normal",
                    w.normal,
                    "unit normal towards the particles, normal = [0, 0, 1]",
                )?,
                "normal",
            )?;
            WallShape::Plane { point, normal }
        }
        WallKind::Cylinder => {
            let point = cx.vec3(
                &p("point"),
                req3(cx, "point", w.point, "a point on the axis in m")?,
                "point",
            )?;
            let axis = cx.unit(
                &p("axis"),
                req3(cx, "axis", w.axis, "axis direction, e.g. axis = [0, 1, 0]")?,
                "axis",
            )?;
            let radius = w.radius.ok_or_else(|| {
                cx.missing(
                    &tp,
                    "[[wall]] of type \"cylinder\"",
                    "radius",
                    "radius in m",
                )
            })?;
            let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
            WallShape::Cylinder {
                point,
                axis,
                radius,
                inside: w.inside.unwrap_or(true),
            }
        }
        WallKind::Box => {
            let lo = cx.vec3(&p("lo"), req3(cx, "lo", w.lo, "lower corner in m")?, "lo")?;
            let hi = cx.vec3(&p("hi"), req3(cx, "hi", w.hi, "upper corner in m")?, "hi")?;
            if hi.cmple(lo).any() {
                return Err(cx.err(
                    &p("hi"),
                    format!("box 'hi' {hi} must be above 'lo' {lo} on every axis"),
                ));
            }
            WallShape::Box {
                lo,
                hi,
                inside: w.inside.unwrap_or(true),
            }
        }
        WallKind::Mesh => {
            let mesh = build_mesh(cx, i, w)?;
            meshes.push(mesh);
            WallShape::Mesh {
                mesh: meshes.len() as u32 - 1,
                position: DVec3::ZERO,
                orientation: DQuat::IDENTITY,
            }
        }
    };
    let default_center = match shape {
        WallShape::Plane { point, .. } | WallShape::Cylinder { point, .. } => point,
        WallShape::Box { lo, hi, .. } => 0.5 * (lo + hi),
        // the image of the file's origin
        WallShape::Mesh { .. } => w.offset.map(v3).unwrap_or_default(),
    };
    let o3 = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>| -> R<DVec3> {
        v.map(|a| cx.vec3(&p(k), a, k))
            .transpose()
            .map(|x| x.unwrap_or_default())
    };
    let motion = WallMotion {
        velocity: o3(cx, "velocity", w.velocity)?,
        angular_velocity: o3(cx, "angular_velocity", w.angular_velocity)?,
        center: match w.center {
            Some(c) => cx.vec3(&p("center"), c, "center")?,
            None => default_center,
        },
        surface_velocity: o3(cx, "surface_velocity", w.surface_velocity)?,
    };
    Ok(Wall {
        name,
        shape,
        material,
        motion,
        multi_contact: w.multi_contact.unwrap_or_default(),
        active: w.active.unwrap_or(true),
    })
}

/// Reads and places the mesh of a `type = "mesh"` wall: file point `p`
/// becomes `offset + R(axis, angle) · (scale · p)` (world frame, m).
fn build_mesh(cx: &mut Cx, i: usize, w: &RawWall) -> R<TriMesh> {
    let tp = [K("wall"), I(i)];
    let p = |k: &'static str| [K("wall"), I(i), K(k)];
    let f = w.file.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            "[[wall]] of type \"mesh\"",
            "file",
            "an STL or OBJ file relative to the scenario, file = \"data/hopper.stl\"",
        )
    })?;
    let scale = match w.scale {
        Some(s) => cx.positive(&p("scale"), s, "scale", "")?,
        None => 1.0,
    };
    let offset = match w.offset {
        Some(o) => cx.vec3(&p("offset"), o, "offset")?,
        None => DVec3::ZERO,
    };
    let rotation = match &w.rotation {
        None => DQuat::IDENTITY,
        Some(r) => {
            let rp = |k: &'static str| [K("wall"), I(i), K("rotation"), K(k)];
            let what = "'rotation' of a [[wall]] of type \"mesh\"";
            let axis = r.axis.ok_or_else(|| {
                cx.missing(
                    &p("rotation"),
                    what,
                    "axis",
                    "rotation = { axis = [1, 0, 0], angle = 90 }",
                )
            })?;
            let angle = r.angle.ok_or_else(|| {
                cx.missing(
                    &p("rotation"),
                    what,
                    "angle",
                    "the angle in degrees, e.g. angle = 90",
                )
            })?;
            let axis = cx.unit(&rp("axis"), axis, "axis")?;
            if !angle.is_finite() {
                return Err(cx.err(
                    &rp("angle"),
                    format!("'angle' must be finite (degrees), found {}", num(angle)),
                ));
            }
            DQuat::from_axis_angle(axis, angle.to_radians())
        }
    };
    let merge_angle = match w.merge_angle {
        None => clump_core::wall::mesh::DEFAULT_MERGE_ANGLE,
        Some(a) if a.is_finite() && (0.0..90.0).contains(&a) => a.to_radians(),
        Some(a) => {
            return Err(cx
                .err(
                    &p("merge_angle"),
                    format!("'merge_angle' must be in [0, 90) degrees, found {}", num(a)),
                )
                .label("out of range"))
        }
    };
    let bytes = cx.read_file(&p("file"), "mesh", f)?;
    let t = crate::mesh_file::MeshTransform {
        scale,
        rotation,
        offset,
    };
    let mut mesh = crate::mesh_file::read_mesh_bytes(&bytes, std::path::Path::new(f), &t)
        .map_err(|e| {
            cx.err(&p("file"), format!("mesh file '{f}' is invalid: {e}"))
                .note("help: a mesh wall needs an STL (ASCII or binary) or OBJ file with at least one triangle of non-zero area")
        })?;
    mesh.merge_angle = merge_angle;
    Ok(mesh)
}

/// A plane wall whose normal has a component along a periodic axis cuts
/// through the periodic images: bodies wrap to the far side of the plane.
/// Refused at the wall's `normal`.
pub(super) fn periodic_planes(
    cx: &mut Cx,
    raw: &RawScenario,
    domain: &clump_core::boundary::Domain,
) -> R<()> {
    for (i, w) in raw.wall.iter().enumerate() {
        let (Some(WallKind::Plane), Some(n)) = (w.kind, w.normal) else {
            continue;
        };
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        for (a, name) in ["x", "y", "z"].iter().enumerate() {
            if domain.periodic[a] && len > 0.0 && (n[a] / len).abs() > 1e-12 {
                return Err(cx
                    .err(
                        &[K("wall"), I(i), K("normal")],
                        format!(
                            "plane wall '{}' has a normal with a component along the periodic axis {name}: bodies would wrap around to its far side",
                            w.name.as_deref().unwrap_or("?")
                        ),
                    )
                    .note(format!("help: a plane in a periodic domain must be parallel to its periodic axes (normal component {name} = 0), or make {name} non-periodic")));
            }
        }
    }
    Ok(())
}
