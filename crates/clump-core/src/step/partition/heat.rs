//! After each step of a world split over ranks with heat (T-94): the
//! walls' heat flows of the step summed over the ranks in one process's
//! order, so that the walls' heat is one process's to the bit; the
//! stability ratio and the fluid's flow combined over the ranks. The
//! ghosts' temperatures travel with their state (`ghosts::refresh`).

use crate::heat::RankWallFlow;
use crate::world::World;

/// What a rank sends: its owned wall touches' flows, its largest
/// stability ratio and its owned bodies' heat flow from the fluid.
type RankHeat = (Vec<RankWallFlow>, f64, f64);

/// Replaces this rank's wall flows by the whole world's (each wall's
/// touches summed in the order of one process's wall pass: by body, sphere
/// and touch), adds them to the walls' heat, and takes the largest
/// stability ratio and the sum of the fluid flows over the ranks.
pub(crate) fn reduce(w: &mut World) {
    let dt = w.config.dt;
    let (Some(part), Some(heat)) = (w.part.as_mut(), w.heat.as_deref_mut()) else {
        return;
    };
    let mine: RankHeat = (
        std::mem::take(&mut heat.rank_wall_flows),
        heat.stability,
        heat.fluid_flow,
    );
    let bytes = postcard::to_stdvec(&mine).unwrap_or_default();
    heat.rank_wall_flows = mine.0;
    part.traffic.reductions += 1;
    let all = part.comm.all_gather(&bytes);
    let mut touches = Vec::new();
    let (mut stability, mut fluid_flow) = (0.0f64, 0.0);
    for b in &all {
        if let Ok((t, s, f)) = postcard::from_bytes::<RankHeat>(b) {
            touches.extend(t);
            stability = stability.max(s);
            fluid_flow += f;
        }
    }
    touches.sort_by_key(|t| (t.wall, t.body_order, t.sphere, t.touch));
    heat.wall_flow.iter_mut().for_each(|q| *q = 0.0);
    for t in &touches {
        heat.wall_flow[t.wall as usize] += t.flow;
    }
    for (e, q) in heat.wall_heat.iter_mut().zip(&heat.wall_flow) {
        *e += dt * q;
    }
    heat.stability = stability;
    heat.fluid_flow = fluid_flow;
}
