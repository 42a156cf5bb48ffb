//! Bulk behaviour (many bodies). Filled in below.

use crate::case::Group;
use crate::Selection;
use std::path::Path;

/// Runs the bulk group (full suite only).
pub fn run(_sel: Selection, _dir: &Path) -> Group {
    Group::default()
}
