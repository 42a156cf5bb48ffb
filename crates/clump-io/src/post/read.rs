//! Reads a run's saved frames back into [`Frame`]s for `clump post`: the
//! `.vtp` files that [`crate::vtk`] and [`crate::vtk_contacts`] write (raw
//! appended data), `contacts.pvd` for the list of frames and `domain.json`.

use super::frame::{BodyState, ContactState, Frame, Side};
use clump_core::boundary::Domain;
use glam::{DQuat, DVec3};
use std::collections::HashMap;
use std::path::Path;

/// One numeric array of a file, as f64 (ids below 2⁵³ are exact).
type Arrays = HashMap<String, Vec<f64>>;

const DATA_START: &[u8] = b"<AppendedData encoding=\"raw\">\n   _";

fn attr<'a>(line: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = line.find(&key)? + key.len();
    let j = line[i..].find('"')?;
    Some(&line[i..i + j])
}

/// The arrays of a `.vtp` written by Clump: point data and `Points` under
/// their names, cell data under `cell:<name>` (a `.vtu` of Clump reads
/// alike: the same arrays, its `Cells` skipped). A `.pvtp` or `.pvtu` (a
/// frame of a run on MPI ranks, [`crate::vtk_pieces`]) reads as its pieces
/// one after another, in the order it lists them; every piece must hold
/// the same arrays.
pub fn read_vtp(path: &Path) -> Result<Arrays, String> {
    if path.extension().is_some_and(|e| e == "pvtp" || e == "pvtu") {
        return read_pvtp(path);
    }
    read_one_vtp(path)
}

/// The point arrays of a spheres or bodies frame ([`read_vtp`], so also a
/// `.pvtp` or `.pvtu` in pieces) with the points in the order of their `body_id`
/// (stable: a body's spheres stay in their order), sorted by name: the
/// same for a frame of one process and the pieces of any rank count.
pub fn arrays_by_body(path: &Path) -> Result<Vec<(String, Vec<f64>)>, String> {
    let a = read_vtp(path)?;
    let ids = a
        .get("body_id")
        .ok_or_else(|| format!("{}: no array body_id", path.display()))?;
    let mut order: Vec<usize> = (0..ids.len()).collect();
    order.sort_by_key(|&i| ids[i] as u64);
    let mut out: Vec<(String, Vec<f64>)> = a
        .iter()
        .filter(|(k, _)| !k.starts_with("cell:"))
        .map(|(k, v)| {
            let c = v.len() / ids.len().max(1);
            let sorted = order
                .iter()
                .flat_map(|&i| v[c * i..c * (i + 1)].iter().copied())
                .collect();
            (k.clone(), sorted)
        })
        .collect();
    out.sort_by(|x, y| x.0.cmp(&y.0));
    Ok(out)
}

fn read_pvtp(path: &Path) -> Result<Arrays, String> {
    let mut out: Option<Arrays> = None;
    for piece in crate::vtk_pieces::sources(path)? {
        let a = read_one_vtp(&piece)?;
        match out.as_mut() {
            None => out = Some(a),
            Some(o) => {
                let mut names: Vec<&String> = o.keys().collect();
                let mut theirs: Vec<&String> = a.keys().collect();
                names.sort();
                theirs.sort();
                if names != theirs {
                    return Err(format!(
                        "{}: its arrays differ from the first piece's ({} lists both)",
                        piece.display(),
                        path.display()
                    ));
                }
                for (k, v) in a {
                    o.get_mut(&k).expect("same names").extend(v);
                }
            }
        }
    }
    Ok(out.unwrap_or_default())
}

fn read_one_vtp(path: &Path) -> Result<Arrays, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let start = bytes
        .windows(DATA_START.len())
        .position(|w| w == DATA_START)
        .ok_or_else(|| {
            format!(
                "{}: not a Clump .vtp (no raw appended data)",
                path.display()
            )
        })?;
    let head = String::from_utf8_lossy(&bytes[..start]);
    let data = &bytes[start + DATA_START.len()..];
    let mut out = Arrays::new();
    let mut section = "";
    for line in head.lines() {
        let t = line.trim_start();
        for s in [
            "<PointData",
            "<CellData",
            "<Points",
            "<Cells",
            "<Verts",
            "<Lines",
            "<Polys",
        ] {
            if t.starts_with(s) {
                section = s;
            }
        }
        if !t.starts_with("<DataArray") {
            continue;
        }
        let bad = || format!("{}: malformed DataArray: {t}", path.display());
        let name = attr(t, "Name").ok_or_else(bad)?;
        let ty = attr(t, "type").ok_or_else(bad)?;
        let off: usize = attr(t, "offset")
            .and_then(|x| x.parse().ok())
            .ok_or_else(bad)?;
        let len_bytes = data.get(off..off + 8).ok_or_else(bad)?;
        let n = u64::from_le_bytes(len_bytes.try_into().unwrap()) as usize;
        let raw = data.get(off + 8..off + 8 + n).ok_or_else(bad)?;
        let values: Vec<f64> = match ty {
            "Float64" => raw
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect(),
            "UInt64" => raw
                .chunks_exact(8)
                .map(|c| u64::from_le_bytes(c.try_into().unwrap()) as f64)
                .collect(),
            "Int64" => raw
                .chunks_exact(8)
                .map(|c| i64::from_le_bytes(c.try_into().unwrap()) as f64)
                .collect(),
            "Int32" => raw
                .chunks_exact(4)
                .map(|c| i32::from_le_bytes(c.try_into().unwrap()) as f64)
                .collect(),
            "UInt8" => raw.iter().map(|&b| b as f64).collect(),
            _ => return Err(bad()),
        };
        let key = match section {
            "<PointData" => name.to_string(),
            "<Points" => "Points".to_string(),
            "<CellData" => format!("cell:{name}"),
            _ => continue,
        };
        out.insert(key, values);
    }
    Ok(out)
}

fn v3(a: &[f64], i: usize) -> DVec3 {
    DVec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2])
}

/// The steps and times of the contact frames listed in `contacts.pvd`.
pub fn contact_frames(run: &Path) -> Result<Vec<(u64, f64)>, String> {
    let path = run.join("contacts.pvd");
    let pvd = crate::vtk::PvdWriter::resume(&path, f64::INFINITY);
    if !path.exists() {
        return Err(format!(
            "{}: no contact frames (run with [output] contacts = {{ every = … }})",
            path.display()
        ));
    }
    pvd.entries()
        .iter()
        .map(|(t, f)| {
            f.strip_prefix("contacts_")
                .and_then(|x| x.strip_suffix(".vtp").or_else(|| x.strip_suffix(".pvtp")))
                .and_then(|x| x.parse().ok())
                .map(|s| (s, *t))
                .ok_or_else(|| format!("{}: unexpected entry {f}", path.display()))
        })
        .collect()
}

/// The frame at `step` of the run in `run`: `bodies_<step>.vtp`,
/// `contacts_<step>.vtp`, `domain.json` (a run on MPI ranks: the `.pvtp`
/// of its pieces, read in the ranks' order).
pub fn read_frame(run: &Path, step: u64, time: f64) -> Result<Frame, String> {
    let dj = run.join("domain.json");
    let text =
        std::fs::read_to_string(&dj).map_err(|e| format!("cannot read {}: {e}", dj.display()))?;
    let domain: Domain =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", dj.display()))?;
    // a run on MPI ranks writes its frames in pieces; `.vtu` in that format
    let names = ["vtp", "pvtp", "vtu", "pvtu"].map(|e| run.join(format!("bodies_{step:06}.{e}")));
    let b = read_vtp(names.iter().find(|p| p.exists()).unwrap_or(&names[0]))?;
    let need = |a: &Arrays, k: &str| -> Result<Vec<f64>, String> {
        a.get(k)
            .cloned()
            .ok_or_else(|| format!("frame {step}: no array {k} (a frame of an older version?)"))
    };
    let (pos, id, q, v, w, t, m, vol, inertia, force, torque) = (
        need(&b, "Points")?,
        need(&b, "body_id")?,
        need(&b, "quaternion")?,
        need(&b, "velocity")?,
        need(&b, "angular_velocity")?,
        need(&b, "template")?,
        need(&b, "mass")?,
        need(&b, "volume")?,
        need(&b, "inertia")?,
        need(&b, "force")?,
        need(&b, "torque")?,
    );
    let bodies = (0..id.len())
        .map(|i| BodyState {
            id: id[i] as u64,
            template: t[i] as usize,
            position: v3(&pos, i),
            velocity: v3(&v, i),
            angular_velocity: v3(&w, i),
            orientation: DQuat::from_xyzw(q[4 * i + 1], q[4 * i + 2], q[4 * i + 3], q[4 * i]),
            mass: m[i],
            volume: vol[i],
            inertia: v3(&inertia, i),
            force: v3(&force, i),
            torque: v3(&torque, i),
        })
        .collect();
    let plain = run.join(format!("contacts_{step:06}.vtp"));
    let c = read_vtp(&if plain.exists() {
        plain
    } else {
        run.join(format!("contacts_{step:06}.pvtp"))
    })?;
    let (pts, f, n, o, p, bi, bj, wall, sl) = (
        need(&c, "Points")?,
        need(&c, "cell:force")?,
        need(&c, "cell:normal")?,
        need(&c, "cell:overlap")?,
        need(&c, "cell:contact_point")?,
        need(&c, "cell:body_i")?,
        need(&c, "cell:body_j")?,
        need(&c, "cell:wall")?,
        need(&c, "cell:sliding")?,
    );
    let contacts = (0..o.len())
        .map(|k| ContactState {
            body_i: bi[k] as u64,
            partner: if wall[k] >= 0.0 {
                Side::Wall(wall[k] as usize)
            } else {
                Side::Body(bj[k] as u64)
            },
            centre_i: v3(&pts, 2 * k),
            end_j: v3(&pts, 2 * k + 1),
            point: v3(&p, k),
            normal: v3(&n, k),
            overlap: o[k],
            force: v3(&f, k),
            sliding: sl[k] != 0.0,
        })
        .collect();
    Ok(Frame {
        step,
        time,
        domain,
        bodies,
        contacts: Some(contacts),
    })
}
