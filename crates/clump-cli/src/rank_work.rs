//! What each rank of an MPI run did: the bodies it integrated and the
//! ghosts it held, the pairs it evaluated and those between two ghosts it
//! left out, its stage times and its time in the exchanges (waits
//! included). A collective call at the end of a run; rank 0 prints the
//! table (docs/scaling.md reads its figures).

use clump_io::run::Runner;

/// Values sent per rank, in this order.
const FIELDS: usize = 11;

/// Every rank's figures, gathered to every rank (a collective call: every
/// rank makes it); lines to print, one per rank. Empty without a partition.
pub fn rank_lines(runner: &mut Runner) -> Vec<String> {
    let w = runner.world_mut();
    let Some(info) = w.part_info() else {
        return Vec::new();
    };
    let t = info.traffic;
    let st = w.stage_times;
    let owned = t.local_body_steps.saturating_sub(t.ghost_body_steps);
    let mine: [f64; FIELDS] = [
        t.steps as f64,
        owned as f64,
        t.ghost_body_steps as f64,
        t.pair_steps as f64,
        t.ghost_pair_steps as f64,
        st.initial,
        st.neighbor,
        st.pair,
        st.gather,
        t.ghost_seconds,
        t.reduce_seconds,
    ];
    let bytes: Vec<u8> = mine.iter().flat_map(|x| x.to_le_bytes()).collect();
    let all = w.gather_from_ranks(&bytes);
    all.iter()
        .enumerate()
        .map(|(r, b)| {
            let v: Vec<f64> = b
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
                .collect();
            if v.len() != FIELDS {
                return format!("rank {r}: unreadable figures");
            }
            let n = v[0].max(1.0);
            format!(
                "rank {r}: per step {:.0} bodies integrated, {:.0} ghosts held (not integrated), {:.0} candidate pairs evaluated, {:.0} between two ghosts left out; seconds in first half {:.3}, neighbours {:.3}, pairs {:.3}, gather and exchanges {:.3} (ghost exchange {:.3}, reductions {:.3}, waits included)",
                v[1] / n,
                v[2] / n,
                v[3] / n,
                v[4] / n,
                v[5],
                v[6],
                v[7],
                v[8],
                v[9],
                v[10],
            )
        })
        .collect()
}
