//! What the partition needs from a communicator, and an in-process one.

use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Barrier, Mutex};

/// The messages a partitioned world sends: gathers to every rank and
/// point-to-point exchanges with known partners. Every rank calls the same
/// collective calls in the same order.
pub trait Comm: Send + Sync {
    /// This rank, `0..size`.
    fn rank(&self) -> usize;
    /// Number of ranks.
    fn size(&self) -> usize;
    /// Every rank's bytes, in rank order, on every rank.
    fn all_gather(&mut self, mine: &[u8]) -> Vec<Vec<u8>>;
    /// Sends each `(rank, bytes)` of `sends` and receives one message from
    /// each rank of `from`, returned in that order. Both sides know their
    /// partners; a pair of ranks exchanges at most one message per call.
    fn exchange(&mut self, sends: &[(usize, Vec<u8>)], from: &[usize]) -> Vec<Vec<u8>>;
}

struct Shared {
    barrier: Barrier,
    slots: Mutex<Vec<Vec<u8>>>,
}

/// Ranks as threads of one process (tests, and checking a decomposition
/// without MPI): channels between every pair, a barrier for gathers. (The
/// receivers sit behind a mutex only so that a world holding this is
/// `Sync`; one thread uses it.)
pub struct ThreadComm {
    rank: usize,
    size: usize,
    shared: Arc<Shared>,
    to: Vec<Sender<Vec<u8>>>,
    from: Mutex<Vec<Receiver<Vec<u8>>>>,
}

impl ThreadComm {
    /// One communicator per rank, to be moved each into its own thread.
    pub fn group(size: usize) -> Vec<ThreadComm> {
        let shared = Arc::new(Shared {
            barrier: Barrier::new(size),
            slots: Mutex::new(vec![Vec::new(); size]),
        });
        // channel (s → d) at [s][d]
        let mut tx: Vec<Vec<Option<Sender<Vec<u8>>>>> = (0..size).map(|_| vec![]).collect();
        let mut rx: Vec<Vec<Option<Receiver<Vec<u8>>>>> = (0..size)
            .map(|_| (0..size).map(|_| None).collect())
            .collect();
        for (s, row) in tx.iter_mut().enumerate() {
            for rx_d in rx.iter_mut() {
                let (t, r) = channel();
                row.push(Some(t));
                rx_d[s] = Some(r);
            }
        }
        tx.into_iter()
            .zip(rx)
            .enumerate()
            .map(|(rank, (t, r))| ThreadComm {
                rank,
                size,
                shared: shared.clone(),
                to: t.into_iter().map(Option::unwrap).collect(),
                from: Mutex::new(r.into_iter().map(Option::unwrap).collect()),
            })
            .collect()
    }
}

impl Comm for ThreadComm {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.size
    }

    fn all_gather(&mut self, mine: &[u8]) -> Vec<Vec<u8>> {
        self.shared.barrier.wait();
        self.shared.slots.lock().unwrap()[self.rank] = mine.to_vec();
        self.shared.barrier.wait();
        let all = self.shared.slots.lock().unwrap().clone();
        self.shared.barrier.wait();
        all
    }

    fn exchange(&mut self, sends: &[(usize, Vec<u8>)], from: &[usize]) -> Vec<Vec<u8>> {
        for (d, bytes) in sends {
            self.to[*d]
                .send(bytes.clone())
                .expect("a rank thread ended during an exchange");
        }
        let rx = self.from.get_mut().expect("one thread uses a rank");
        from.iter()
            .map(|&s| {
                rx[s]
                    .recv()
                    .expect("a rank thread ended during an exchange")
            })
            .collect()
    }
}
