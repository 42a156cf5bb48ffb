//! What became of the bodies a scenario asked for: per `[[insert]]`, how
//! many were asked for so far, placed, and still waiting for room; and how
//! many left the domain. Shown after every run and stored in the manifest,
//! so that no body is lost without a word.

use super::Runner;
use crate::scenario::InsertSpec;
use serde::Serialize;

/// The account of one `[[insert]]`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct InsertionCount {
    /// 1-based number of the `[[insert]]` in the scenario.
    pub insert: usize,
    /// "file", "pack" or "stream".
    pub kind: &'static str,
    /// Bodies asked for up to now (a stream: those due by the current time).
    pub asked: u64,
    /// Bodies placed.
    pub placed: u64,
    /// Bodies due but not placed (a stream that found no room).
    pub waiting: u64,
}

impl Runner {
    /// The account of every `[[insert]]` whose stage has begun.
    pub fn insertions(&self) -> Vec<InsertionCount> {
        let mut v = Vec::new();
        for (k, ins) in self.scenario.inserts.iter().enumerate() {
            let placed = self.st.inserted.get(k).copied().unwrap_or(0);
            let begun =
                ins.stage < self.st.stage || (ins.stage == self.st.stage && self.st.stage_started);
            if !begun {
                continue;
            }
            let (kind, asked, waiting) = match &ins.kind {
                InsertSpec::File { bodies } => ("file", bodies.len() as u64, 0),
                InsertSpec::Pack { .. } => ("pack", placed, 0),
                InsertSpec::Stream { .. } => {
                    let waiting = self
                        .st
                        .streams
                        .get(k)
                        .and_then(Option::as_ref)
                        .map_or(0, |s| s.backlog());
                    ("stream", placed + waiting, waiting)
                }
            };
            v.push(InsertionCount {
                insert: k + 1,
                kind,
                asked,
                placed,
                waiting,
            });
        }
        v
    }

    /// Bodies lost so far, by cause (a side of the domain their centre
    /// crossed, a non-finite position, removal by a driver).
    pub fn lost_bodies(&self) -> clump_core::lost::LostBodies {
        self.world.lost
    }
}
