//! No body is lost without a word: insertion regions and body-file rows are
//! checked against the domain (a body whose centre lies outside a
//! non-periodic side is removed at the first step), and body-file rows that
//! put two bodies at one point (complete overlap, which no contact law can
//! resolve) are refused.
#![allow(clippy::result_large_err)]

use super::diag::Diagnostic;
use super::model::{InsertDef, InsertSpec};
use super::source::{Seg, Source};
use clump_core::boundary::Domain;
use clump_core::insert::Region;
use glam::DVec3;

type R<T> = Result<T, Diagnostic>;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Checks `[[insert]]` number `i` (0-based) against `domain`: an error when
/// its region lies wholly outside, or when body-file rows lie outside or
/// coincide; a warning (pushed on `warnings`) when its region reaches
/// partly outside.
pub fn check_insert(
    src: &Source,
    i: usize,
    def: &InsertDef,
    domain: &Domain,
    warnings: &mut Vec<Diagnostic>,
) -> R<()> {
    let path = |k: &'static str| [Seg::K("insert"), Seg::I(i), Seg::K(k)];
    match &def.kind {
        InsertSpec::File { bodies } => {
            let outside: Vec<usize> = (0..bodies.len())
                .filter(|&k| domain.is_outside(bodies[k].position))
                .collect();
            if let Some(&first) = outside.first() {
                let x = bodies[first].position;
                return Err(src
                    .error_at(
                        &path("file"),
                        format!(
                            "{} of {} bodies in the body file lie outside the domain {} .. {} m (the first: body {} at {}); they would be removed at the first step",
                            outside.len(),
                            bodies.len(),
                            short(domain.lo),
                            short(domain.hi),
                            first + 1,
                            short(x)
                        ),
                    )
                    .label("bodies outside the domain")
                    .note("help: move the bodies, or enlarge [domain] (body numbers count the file's data rows from 1)"));
            }
            let positions: Vec<DVec3> = bodies.iter().map(|b| b.position).collect();
            if let Some((a, b)) = coincident(&positions, domain) {
                return Err(src
                    .error_at(
                        &path("file"),
                        format!(
                            "bodies {} and {} of the body file are at the same point {}: they overlap completely",
                            a + 1,
                            b + 1,
                            short(positions[a])
                        ),
                    )
                    .label("overlapping placement")
                    .note("help: remove the duplicate row (body numbers count the file's data rows from 1)"));
            }
            Ok(())
        }
        InsertSpec::Pack { spec, .. } => {
            region(src, &path("region"), &spec.region, domain, warnings)
        }
        InsertSpec::Stream { spec, .. } => {
            region(src, &path("region"), &spec.region, domain, warnings)
        }
    }
}

/// `[x, y, z]` with 4 significant digits, for messages.
fn short(v: DVec3) -> String {
    format!("[{:.4}, {:.4}, {:.4}]", v.x, v.y, v.z)
}

fn region(
    src: &Source,
    path: &[Seg],
    r: &Region,
    domain: &Domain,
    warnings: &mut Vec<Diagnostic>,
) -> R<()> {
    let (lo, hi) = r.bounds();
    for a in (0..3).filter(|&a| !domain.periodic[a]) {
        let (dlo, dhi) = (domain.lo[a], domain.hi[a]);
        let span = format!(
            "region {:.4} .. {:.4} m, domain {dlo:.4} .. {dhi:.4} m",
            lo[a], hi[a]
        );
        if hi[a] <= dlo || lo[a] >= dhi {
            return Err(src
                .error_at(
                    path,
                    format!(
                        "the region lies outside the domain along {} ({span}): every body placed there would be removed at the first step",
                        AXES[a]
                    ),
                )
                .label("outside the domain")
                .note("help: move the region into [domain], or enlarge the domain"));
        }
        if lo[a] < dlo || hi[a] > dhi {
            warnings.push(
                src.warning_at(
                    path,
                    format!(
                        "the region reaches outside the domain along {} ({span}): bodies placed in the part outside are removed at the first step",
                        AXES[a]
                    ),
                )
                .label("partly outside the domain"),
            );
            return Ok(());
        }
    }
    Ok(())
}

/// Two of `p` (indices, ascending) closer than 10⁻⁹ of the domain's
/// diagonal, if any.
fn coincident(p: &[DVec3], domain: &Domain) -> Option<(usize, usize)> {
    let eps = 1e-9 * (domain.hi - domain.lo).length();
    let mut idx: Vec<usize> = (0..p.len()).collect();
    idx.sort_by(|&a, &b| p[a].x.total_cmp(&p[b].x));
    for (k, &a) in idx.iter().enumerate() {
        for &b in &idx[k + 1..] {
            if p[b].x - p[a].x > eps {
                break;
            }
            if p[a].distance(p[b]) <= eps {
                return Some((a.min(b), a.max(b)));
            }
        }
    }
    None
}
