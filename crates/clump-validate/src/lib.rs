//! # clump-validate
//!
//! The validation suite of Clump: every case compares a quantity measured
//! by the engine (`clump-core`, through its public API) with an expected
//! value that comes from outside the code — a closed-form solution, a
//! published benchmark or `validation/REFERENCE.md` — and a stated
//! tolerance. [`run_suite`] runs the cases, [`report::write`] writes
//! `report.md` with PNG plots.
//!
//! Conventions: SI units; vectors are in the world frame unless a name says
//! `_body`; quaternions map body → world.
#![warn(missing_docs)]

pub mod bulk;
pub mod case;
pub mod chung_ooi;
pub mod clump_cases;
pub mod cohesion;
pub mod contact_models;
pub mod dem_order;
pub mod liggghts;
pub mod mass;
pub mod mbf;
pub mod micro_slip;
pub mod ode;
pub mod plot;
pub mod plot_discs;
pub mod plot_segments;
pub mod report;
pub mod rigid_body;
pub mod setup;
pub mod twisting;

pub use case::{Case, Group, Suite};

use std::path::Path;
use std::time::Instant;

/// Which cases to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    /// The cheap subset CI runs (seconds).
    Quick,
    /// Every case, the bulk ones included (minutes; sized to run in under
    /// 15 minutes on two cores).
    Full,
}

/// Runs the selected groups, writing each group's plots into `dir` (which
/// must exist). Never panics on a failed case: a failure is a row with
/// `pass = false`; a plot that cannot be written is reported as a note.
pub fn run_suite(selection: Selection, dir: &Path) -> Suite {
    let mut suite = Suite::default();
    let groups: Vec<(&str, fn(Selection, &Path) -> Group)> = vec![
        ("Chung & Ooi (2011) impacts", chung_ooi::run),
        ("Rigid-body rotation", rigid_body::run),
        ("Rotation schemes inside the DEM step", dem_order::run),
        ("Mass properties", mass::run),
        ("Clump-specific dynamics", clump_cases::run),
        ("Contact models users ask for", contact_models::run),
        ("Bulk behaviour", bulk::run),
    ];
    for (name, f) in groups {
        let t0 = Instant::now();
        eprintln!("validate: {name} ...");
        let mut g = f(selection, dir);
        g.name = name.to_string();
        g.seconds = t0.elapsed().as_secs_f64();
        eprintln!(
            "validate: {name}: {} cases, {} failed, {:.1} s",
            g.cases.len(),
            g.cases.iter().filter(|c| !c.pass).count(),
            g.seconds
        );
        suite.groups.push(g);
    }
    suite
}
