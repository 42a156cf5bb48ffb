//! The heat stage (docs/theory.md T-53 … T-57): after the neighbours and
//! before the forces, at the sphere centres the force stage reads, each
//! body's heat flow is summed over its sphere–sphere contacts (in pair-list
//! order), its sphere–wall contacts with walls of fixed temperature (in
//! wall-list order) and its source, and its temperature takes one explicit
//! Euler step, `T ← T + dt Q / (m c_p)`.
//!
//! With convection (`Heat::convection` and a fluid set), each body also
//! exchanges `h A (T_f − T)` with the fluid (T-90 … T-92), and its step is
//! the exponential one of T-93, exact for convection alone and stable for
//! any `h A dt / C`.
//!
//! The pairs' flows are computed on several threads (`heat_pairs`), the
//! sums and the wall pass run on the calling thread: the sums have one
//! order whatever the thread count, and the stage allocates nothing once
//! its arrays have grown to the bodies and pairs. Without heat (`World::heat` is `None`) it is one
//! branch.

use crate::heat::{
    convective_coefficients, harmonic_conductivity, wall_conductance, Heat, RankWallFlow,
};
use crate::par::affinity::{Balance, HEAT_LOOP};
use crate::wall::{WallTouch, MAX_TOUCHES_PER_WALL};
use crate::world::World;

/// Conducts one step of heat, when the world has heat.
pub(crate) fn conduct(w: &mut World) {
    let Some(mut heat) = w.heat.take() else {
        return;
    };
    let mut balance = std::mem::take(&mut w.scratch.balance[HEAT_LOOP]);
    flows(w, &mut heat, &mut balance);
    w.scratch.balance[HEAT_LOOP] = balance;
    convect(w, &mut heat);
    integrate(w, &mut heat);
    w.heat = Some(heat);
}

/// Each body's heat flow (W) and conductance sum (W/K) into `heat`'s
/// scratch, and each wall's flow.
fn flows(w: &World, heat: &mut Heat, balance: &mut Balance) {
    let nb = w.bodies.len();
    let Heat {
        model,
        wall_flow,
        flow,
        conductance_sum,
        rank_wall_flows,
        pair_flow,
        ..
    } = heat;
    flow.clear();
    flow.extend_from_slice(&w.bodies.heat_source);
    conductance_sum.clear();
    conductance_sum.resize(nb, 0.0);
    wall_flow.iter_mut().for_each(|q| *q = 0.0);
    let temp = &w.bodies.temperature;
    let sp = &w.spheres;
    let pairs = &w.neighbors.pairs;
    // sphere–sphere contacts (T-53, T-54, T-55): each entry's flow on
    // several threads, summed per body here in pair-list order
    super::heat_pairs::pair_flows(w, model, pair_flow, balance);
    for i in 0..sp.len() {
        let (p0, p1) = (pairs.row_start[i] as usize, pairs.row_start[i + 1] as usize);
        let bi = sp.body[i] as usize;
        for (t, &(h, q)) in pairs.topo[p0..p1].iter().zip(&pair_flow[p0..p1]) {
            if h == super::heat_pairs::APART {
                continue;
            }
            let bj = sp.body[t.j as usize] as usize;
            flow[bi] += q;
            flow[bj] -= q;
            conductance_sum[bi] += h;
            conductance_sum[bj] += h;
        }
    }
    // sphere–wall contacts with the walls of fixed temperature; on a rank,
    // of its owned spheres only, each touch's flow also kept for the sum
    // over the ranks (T-94)
    let list = &w.neighbors.wall_list;
    let walls = &w.walls.list;
    let part = w.part.as_deref();
    rank_wall_flows.clear();
    let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
    for (e, &s) in list.sphere.iter().enumerate() {
        let s = s as usize;
        let (x, r) = (sp.position(s), sp.state[s].radius);
        let b = sp.body[s] as usize;
        if part.is_some_and(|p| !p.owned[b]) {
            continue;
        }
        let ks = model.conductivity(sp.material[s]);
        let near = (0..walls.len().min(64)).filter(|&wi| list.mask[e] >> wi & 1 == 1);
        for wi in near.chain(64..walls.len()) {
            let wall = &walls[wi];
            let Some(tw) = model.wall_temperature(wi).filter(|_| wall.active) else {
                continue;
            };
            let k = harmonic_conductivity(ks, model.conductivity(wall.material));
            let n = wall.shape.contacts(&w.walls.meshes, x, r, 0.0, &mut buf);
            for (k_touch, touch) in buf[..n].iter().enumerate() {
                let h = wall_conductance(model.conductance, k, r, touch.overlap);
                let q = h * (tw - temp[b]);
                flow[b] += q;
                wall_flow[wi] += q;
                conductance_sum[b] += h;
                if let Some(p) = part {
                    rank_wall_flows.push(RankWallFlow {
                        wall: wi as u32,
                        body_order: p.order[b],
                        sphere: sp.index_in_template[s],
                        touch: k_touch as u32,
                        flow: q,
                    });
                }
            }
        }
    }
}

/// Convection (T-90 … T-92): each body's conductance `h A` to the fluid
/// at its slip against the fluid velocity it sees (its own where a driver
/// set one per body, else the uniform one), into `heat.convective`, and
/// its flow `h A (T_f − T)` added to its heat flow, in body order. Clears
/// `heat.convective` when there is no convection.
fn convect(w: &World, heat: &mut Heat) {
    let (Some(fh), Some(fs)) = (heat.convection, w.fluid.as_ref()) else {
        heat.convective.clear();
        heat.fluid_flow = 0.0;
        return;
    };
    let b = &w.bodies;
    // inside a fused stretch the packed copy holds the current velocities
    let packed = &w.neighbors.pairs.body;
    let lag = w.phase.bodies_lag();
    let per_body = &b.coupling.fluid_velocity;
    let owned = w.part.as_deref().map(|p| &p.owned);
    heat.convective_template.clear();
    let per_template = fs.templates.iter();
    let coefficients = per_template.map(|t| convective_coefficients(&fs.fluid, &fh, t));
    heat.convective_template.extend(coefficients);
    heat.convective.clear();
    heat.fluid_flow = 0.0;
    for i in 0..b.len() {
        let v = if lag {
            packed[i].velocity
        } else {
            b.velocity[i]
        };
        let u = per_body.get(i).copied().unwrap_or(fs.fluid.velocity);
        let (g0, g1) = heat.convective_template[b.template[i] as usize];
        let ha = g0 + g1 * (u - v).length().sqrt();
        let q = ha * (fh.temperature - b.temperature[i]);
        heat.flow[i] += q;
        if owned.map_or(true, |o| o[i]) {
            heat.fluid_flow += q;
        }
        heat.convective.push(ha);
    }
}

/// (T-93) The factor `(1 − e^{−x})/x` of the exponential step of a body
/// with convective conductance `ha` and heat capacity `c`: over the step,
/// with the other flows held, the temperature relaxes as `e^{−x}`,
/// `x = h A dt / C`, towards its steady value.
#[inline]
fn convective_factor(ha: f64, dt: f64, c: f64) -> f64 {
    crate::fluid::relaxation_factor(ha * dt / c)
}

/// The explicit Euler step of every temperature (T-56), exponential in
/// the convection (T-93), the walls' heat and the step's stability ratio
/// (T-57; convection, integrated exactly, does not limit it).
fn integrate(w: &mut World, heat: &mut Heat) {
    let dt = w.config.dt;
    let mut worst = 0.0f64;
    for b in 0..w.bodies.len() {
        let m = w.templates.material(w.bodies.template[b] as usize);
        let cp = heat.model.materials[m as usize].map_or(f64::NAN, |t| t.specific_heat);
        let c = w.bodies.mass[b] * cp;
        match heat.convective.get(b) {
            Some(&ha) => {
                w.bodies.temperature[b] += convective_factor(ha, dt, c) * (dt * heat.flow[b] / c)
            }
            None => w.bodies.temperature[b] += dt * heat.flow[b] / c,
        }
        worst = worst.max(dt * heat.conductance_sum[b] / c);
    }
    heat.stability = worst;
    if w.part.is_some() {
        // a rank's flows are its part: summed over the ranks after the step
        return;
    }
    for (e, q) in heat.wall_heat.iter_mut().zip(&heat.wall_flow) {
        *e += dt * q;
    }
}
