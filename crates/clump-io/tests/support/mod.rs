//! Helpers shared by the scenario-level tests.
#![allow(dead_code)]

use std::path::Path;

/// The last row of a CSV output (trajectory, thermo): value of column `name`.
pub fn last_value(path: &Path, name: &str) -> f64 {
    let text = std::fs::read_to_string(path).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    last[header
        .iter()
        .position(|c| *c == name)
        .unwrap_or_else(|| panic!("no column {name}"))]
}
