//! Arrays across the boundary: counts, ids, body and sphere fields, the
//! sphere → body map (read, id order), external loads, per-body fluid
//! velocity and void fraction (set, id order); fields on grids are in
//! `fields.rs`. Every length is checked before anything is written or changed.

use crate::handle::{put, with_run, ClumpSim, Fail, Run};
use crate::*;
use clump_core::world::World;
use glam::DVec3;

impl Run {
    /// Body storage indices in id order.
    fn bodies_sorted(&mut self) -> &[usize] {
        let id = &self.runner.world().bodies().id;
        sort_by_key(&mut self.body_order, id);
        &self.body_order
    }
}

/// `order` = the indices of `key` sorted by it (keys are unique ids).
fn sort_by_key(order: &mut Vec<usize>, key: &[u64]) {
    order.clear();
    order.extend(0..key.len());
    order.sort_unstable_by_key(|&i| key[i]);
}

/// The caller's output array of `len` values as a slice, checked to hold
/// `need` of them.
pub(crate) fn out_slice<'a, T>(
    out: *mut T,
    len: usize,
    need: usize,
    what: &str,
) -> Result<&'a mut [T], Fail> {
    if out.is_null() {
        return Err(Fail(
            CLUMP_ERR_NULL,
            format!("{what}: output array is NULL"),
        ));
    }
    if len != need {
        return Err(Fail::value(format!(
            "{what}: the array holds {len} values, {need} are needed"
        )));
    }
    // SAFETY: `out` points to `len` writable values (the caller's contract).
    Ok(unsafe { std::slice::from_raw_parts_mut(out, len) })
}

/// The caller's input array of `need` values, checked to be finite.
pub(crate) fn in_slice<'a>(
    v: *const f64,
    len: usize,
    need: usize,
    what: &str,
) -> Result<&'a [f64], Fail> {
    if v.is_null() {
        return Err(Fail(CLUMP_ERR_NULL, format!("{what}: input array is NULL")));
    }
    if len != need {
        return Err(Fail::value(format!(
            "{what}: the array holds {len} values, {need} are needed"
        )));
    }
    // SAFETY: `v` points to `len` readable values (the caller's contract).
    let s = unsafe { std::slice::from_raw_parts(v, len) };
    match s.iter().position(|x| !x.is_finite()) {
        Some(k) => Err(Fail::value(format!(
            "{what}: value {k} is not finite ({})",
            s[k]
        ))),
        None => Ok(s),
    }
}

/// Per-body vectors given in id order (3 per body), in storage order.
fn vectors_in(order: &[usize], v: &[f64]) -> Vec<DVec3> {
    let mut out = vec![DVec3::ZERO; order.len()];
    for (k, &i) in order.iter().enumerate() {
        out[i] = DVec3::from_slice(&v[3 * k..3 * k + 3]);
    }
    out
}

/// `width` of a field, or an error for an unknown field (width 0).
fn known(width: usize, kind: &str, field: i32) -> Result<usize, Fail> {
    match width {
        0 => Err(Fail::value(format!("unknown {kind} field {field}"))),
        w => Ok(w),
    }
}

pub(crate) fn world_err(e: clump_core::world::WorldError) -> Fail {
    Fail::value(e.to_string())
}

/// Writes the number of bodies and of spheres (either may be NULL).
///
/// # Safety
/// `sim` is a live handle; each pointer NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_counts(
    sim: *mut ClumpSim,
    bodies: *mut usize,
    spheres: *mut usize,
) -> i32 {
    with_run(sim, |r| {
        let w = r.runner.world();
        if !bodies.is_null() {
            put(bodies, w.bodies().len())?;
        }
        if !spheres.is_null() {
            put(spheres, sphere_count(w))?;
        }
        Ok(())
    })
}

/// Writes the body ids, ascending (`len` = number of bodies): the order of
/// every per-body array.
///
/// # Safety
/// `sim` is a live handle; `out` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_body_ids(sim: *mut ClumpSim, out: *mut u64, len: usize) -> i32 {
    with_run(sim, |r| {
        let order = r.bodies_sorted().to_vec();
        let id = &r.runner.world().bodies().id;
        let o = out_slice(out, len, order.len(), "body ids")?;
        for (o, &i) in o.iter_mut().zip(&order) {
            *o = id[i];
        }
        Ok(())
    })
}

/// Values per body of a `CLUMP_BODY_…` field (0 for an unknown field).
#[no_mangle]
pub extern "C" fn clump_body_field_width(field: i32) -> usize {
    match field {
        CLUMP_BODY_POSITION
        | CLUMP_BODY_VELOCITY
        | CLUMP_BODY_ANGULAR_VELOCITY
        | CLUMP_BODY_FORCE
        | CLUMP_BODY_TORQUE
        | CLUMP_BODY_FLUID_FORCE => 3,
        CLUMP_BODY_ORIENTATION => 4,
        CLUMP_BODY_MASS | CLUMP_BODY_VOLUME => 1,
        _ => 0,
    }
}

/// Values of body `i` (storage index) for `field`, into `o`.
fn body_values(w: &World, field: i32, i: usize, o: &mut [f64]) {
    let b = w.bodies();
    let v = match field {
        CLUMP_BODY_POSITION => b.position[i],
        CLUMP_BODY_VELOCITY => b.velocity[i],
        CLUMP_BODY_ANGULAR_VELOCITY => b.angular_velocity[i],
        CLUMP_BODY_FORCE => b.force[i],
        CLUMP_BODY_TORQUE => b.torque[i],
        CLUMP_BODY_FLUID_FORCE => w.fluid_forces().get(i).copied().unwrap_or(DVec3::ZERO),
        CLUMP_BODY_ORIENTATION => {
            let q = b.orientation[i];
            o.copy_from_slice(&[q.w, q.x, q.y, q.z]);
            return;
        }
        CLUMP_BODY_MASS => {
            o[0] = b.mass[i];
            return;
        }
        _ => {
            o[0] = w.templates[b.template[i] as usize].volume;
            return;
        }
    };
    o.copy_from_slice(&v.to_array());
}

/// Writes a body field for every body in id order (`len` = bodies ×
/// `clump_body_field_width(field)`).
///
/// # Safety
/// `sim` is a live handle; `out` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_body_field(
    sim: *mut ClumpSim,
    field: i32,
    out: *mut f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let width = known(clump_body_field_width(field), "body", field)?;
        let order = r.bodies_sorted().to_vec();
        let o = out_slice(out, len, order.len() * width, "body field")?;
        for (o, &i) in o.chunks_exact_mut(width).zip(&order) {
            body_values(r.runner.world(), field, i, o);
        }
        Ok(())
    })
}

/// Values per sphere of a `CLUMP_SPHERE_…` field (0 for an unknown field).
#[no_mangle]
pub extern "C" fn clump_sphere_field_width(field: i32) -> usize {
    match field {
        CLUMP_SPHERE_POSITION | CLUMP_SPHERE_VELOCITY => 3,
        CLUMP_SPHERE_RADIUS => 1,
        _ => 0,
    }
}

/// Calls `f(k, centre, velocity, radius)` for every sphere in sphere-id
/// order, `k` its body's index in id order. The spheres are derived from
/// the bodies and their templates (sphere id = body id and index in the
/// template), so they are current also before the first step.
fn each_sphere(w: &World, order: &[usize], mut f: impl FnMut(usize, DVec3, DVec3, f64)) {
    let b = w.bodies();
    for (k, &i) in order.iter().enumerate() {
        let (x, q, v, om) = (
            b.position[i],
            b.orientation[i],
            b.velocity[i],
            b.angular_velocity[i],
        );
        for s in &w.templates[b.template[i] as usize].spheres {
            let arm = q * s.center;
            f(k, x + arm, v + om.cross(arm), s.radius);
        }
    }
}

/// Number of spheres of all bodies.
pub(crate) fn sphere_count(w: &World) -> usize {
    let b = w.bodies();
    b.template
        .iter()
        .map(|&t| w.templates[t as usize].spheres.len())
        .sum()
}

/// Writes a sphere field for every sphere in sphere-id order (`len` =
/// spheres × `clump_sphere_field_width(field)`).
///
/// # Safety
/// `sim` is a live handle; `out` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_sphere_field(
    sim: *mut ClumpSim,
    field: i32,
    out: *mut f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let width = known(clump_sphere_field_width(field), "sphere", field)?;
        let order = r.bodies_sorted().to_vec();
        let w = r.runner.world();
        let o = out_slice(out, len, sphere_count(w) * width, "sphere field")?;
        let mut rows = o.chunks_exact_mut(width);
        each_sphere(w, &order, |_, x, v, radius| {
            let o = rows.next().expect("one row per sphere");
            match field {
                CLUMP_SPHERE_POSITION => o.copy_from_slice(&x.to_array()),
                CLUMP_SPHERE_VELOCITY => o.copy_from_slice(&v.to_array()),
                _ => o[0] = radius,
            }
        });
        Ok(())
    })
}

/// Writes, for every sphere in sphere-id order, the index of its body in
/// the per-body arrays (id order; `len` = spheres).
///
/// # Safety
/// `sim` is a live handle; `out` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_sphere_body(
    sim: *mut ClumpSim,
    out: *mut usize,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let order = r.bodies_sorted().to_vec();
        let w = r.runner.world();
        let mut o = out_slice(out, len, sphere_count(w), "sphere body map")?.iter_mut();
        each_sphere(w, &order, |k, _, _, _| {
            *o.next().expect("one per sphere") = k
        });
        Ok(())
    })
}

/// Sets the external force (N) and torque about the centre of mass (N m)
/// of every body, id order, 3 values each (`len` = 3 × bodies; `torque`
/// may be NULL for none), world frame. `mode`: `CLUMP_LOAD_PERSISTENT`
/// (acts at every step until set again) or `CLUMP_LOAD_NEXT_STEP` (acts
/// in the next step only, added to the persistent one).
///
/// # Safety
/// `sim` is a live handle; `force` (and a non-NULL `torque`) hold `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_external_loads(
    sim: *mut ClumpSim,
    force: *const f64,
    torque: *const f64,
    len: usize,
    mode: i32,
) -> i32 {
    with_run(sim, |r| {
        if mode != CLUMP_LOAD_PERSISTENT && mode != CLUMP_LOAD_NEXT_STEP {
            return Err(Fail::value(format!("unknown load mode {mode}")));
        }
        let order = r.bodies_sorted().to_vec();
        let need = 3 * order.len();
        let f = vectors_in(&order, in_slice(force, len, need, "external forces")?);
        let t = if torque.is_null() {
            vec![DVec3::ZERO; order.len()]
        } else {
            vectors_in(&order, in_slice(torque, len, need, "external torques")?)
        };
        let w = r.runner.world_mut();
        if mode == CLUMP_LOAD_PERSISTENT {
            w.set_external_loads(&f, &t)
        } else {
            w.set_next_step_loads(&f, &t)
        }
        .map_err(world_err)
    })
}

/// Sets the interstitial fluid velocity at every body, id order, 3 values
/// each (m/s, world frame; `len` = 3 × bodies), as a CFD code interpolates
/// it; it replaces the scenario's uniform `[fluid] velocity` for the drag.
///
/// # Safety
/// `sim` is a live handle; `velocity` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_fluid_velocities(
    sim: *mut ClumpSim,
    velocity: *const f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let order = r.bodies_sorted().to_vec();
        let u = vectors_in(
            &order,
            in_slice(velocity, len, 3 * order.len(), "fluid velocities")?,
        );
        r.runner
            .world_mut()
            .set_body_fluid_velocities(&u)
            .map_err(world_err)
    })
}

/// Sets the local void fraction at every body, id order (`len` = bodies),
/// each in (0, 1]; the drag laws read it.
///
/// # Safety
/// `sim` is a live handle; `eps` holds `len` values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_void_fractions(
    sim: *mut ClumpSim,
    eps: *const f64,
    len: usize,
) -> i32 {
    with_run(sim, |r| {
        let order = r.bodies_sorted().to_vec();
        let e = in_slice(eps, len, order.len(), "void fractions")?;
        let mut stored = vec![1.0; order.len()];
        for (&v, &i) in e.iter().zip(&order) {
            stored[i] = v;
        }
        r.runner
            .world_mut()
            .set_body_void_fractions(&stored)
            .map_err(world_err)
    })
}

/// Sets the uniform fluid velocity (3 values, m/s, world frame), used for
/// bodies without a per-body value; the scenario must have a `[fluid]`.
///
/// # Safety
/// `sim` is a live handle; `velocity` holds 3 values.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_set_uniform_fluid_velocity(
    sim: *mut ClumpSim,
    velocity: *const f64,
) -> i32 {
    with_run(sim, |r| {
        let u = in_slice(velocity, 3, 3, "fluid velocity")?;
        r.runner
            .world_mut()
            .set_fluid_velocity(DVec3::from_slice(u))
            .map_err(world_err)
    })
}

/// Removes every external load and per-body fluid velocity and void fraction.
///
/// # Safety
/// `sim` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_clear_coupling(sim: *mut ClumpSim) -> i32 {
    with_run(sim, |r| {
        r.runner.world_mut().clear_coupling_arrays();
        Ok(())
    })
}
