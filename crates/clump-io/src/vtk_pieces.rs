//! Frames of a world split over MPI ranks, written in VTK's parallel
//! formats without gathering the world: every rank writes the spheres and
//! bodies it holds as one piece, `spheres_<label>.rank<r>of<n>.vtp` (the
//! arrays of [`crate::vtk`], for its bodies only; `.vtu` for frames in
//! that format), and rank 0 writes `spheres_<label>.pvtp` (parallel
//! PolyData; `.pvtu`, parallel UnstructuredGrid, for `.vtu` pieces), which
//! lists the pieces (`<Piece Source=…>`) and declares their arrays
//! (`PPointData`, `PPoints`), and puts it in `spheres.pvd`. ParaView and
//! vtk (`vtkXMLPPolyDataReader`, `vtkXMLPUnstructuredGridReader`) read
//! the collection as one data set; every body is in exactly one piece.
//! Ranks without bodies write no piece (rank 0 always writes its own,
//! which declares the arrays).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The file name of rank `r`'s piece (of `n` ranks) of the `kind` frame
/// (`spheres`, `bodies`) at `label`, with the extension `ext` of the
/// frames (`vtp`, `vtu`).
pub fn piece_name(kind: &str, label: u64, r: usize, n: usize, ext: &str) -> String {
    format!("{kind}_{label:06}.rank{r}of{n}.{ext}")
}

/// The file name of the collection of the pieces of the `kind` frame at
/// `label` whose pieces have the extension `ext` (`vtp` → `.pvtp`, `vtu`
/// → `.pvtu`).
pub fn collection_name(kind: &str, label: u64, ext: &str) -> String {
    format!("{kind}_{label:06}.p{ext}")
}

/// True for a piece name of [`piece_name`] or a `<kind>_<digits>.pvtp`
/// (`.pvtu`), of the spheres, bodies or contacts frames.
pub fn is_piece_file(name: &str) -> bool {
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let Some(rest) = ["spheres_", "bodies_", "contacts_"]
        .iter()
        .find_map(|p| name.strip_prefix(p))
    else {
        return false;
    };
    if let Some(label) = rest
        .strip_suffix(".pvtp")
        .or_else(|| rest.strip_suffix(".pvtu"))
    {
        return digits(label);
    }
    rest.strip_suffix(".vtp")
        .or_else(|| rest.strip_suffix(".vtu"))
        .and_then(|r| r.split_once(".rank"))
        .and_then(|(label, rn)| Some((label, rn.split_once("of")?)))
        .is_some_and(|(label, (r, n))| digits(label) && digits(r) && digits(n))
}

/// The parallel file (`.pvtp` for PolyData pieces, `.pvtu` for
/// UnstructuredGrid ones) that lists the pieces `sources` (file names
/// beside it), with the arrays declared in `piece`, a piece of that frame
/// (its `PointData`, `CellData` and `Points` arrays, without their
/// offsets). Errors name what is missing in `piece`.
pub fn parallel_file(piece: &[u8], sources: &[String]) -> Result<Vec<u8>, String> {
    let end = piece
        .windows(b"<AppendedData".len())
        .position(|w| w == b"<AppendedData")
        .ok_or("a frame piece without appended data")?;
    let head = String::from_utf8_lossy(&piece[..end]);
    let grid = if head.contains("<VTKFile type=\"UnstructuredGrid\"") {
        "PUnstructuredGrid"
    } else {
        "PPolyData"
    };
    let mut x = format!("<?xml version=\"1.0\"?>\n<VTKFile type=\"{grid}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <{grid} GhostLevel=\"0\">\n");
    let mut section: Option<&str> = None;
    for line in head.lines() {
        let t = line.trim();
        let opened = ["PointData", "CellData", "Points"]
            .into_iter()
            .find(|s| t == format!("<{s}>"));
        if let Some(s) = opened {
            section = Some(s);
            let _ = writeln!(x, "    <P{s}>");
            continue;
        }
        if let Some(s) = section.filter(|s| t == format!("</{s}>")) {
            let _ = writeln!(x, "    </P{s}>");
            section = None;
            continue;
        }
        if section.is_some() && t.starts_with("<DataArray ") {
            // the declaration: type, name and components, no data
            let decl = t
                .split(" format=")
                .next()
                .unwrap_or(t)
                .trim_end_matches("/>")
                .trim_end();
            let _ = writeln!(x, "      <P{}/>", &decl[1..]);
        }
    }
    if !x.contains("<PPoints>") {
        return Err("a frame piece without points".into());
    }
    for s in sources {
        let _ = writeln!(x, "    <Piece Source=\"{s}\"/>");
    }
    let _ = write!(x, "  </{grid}>\n</VTKFile>\n");
    Ok(x.into_bytes())
}

/// The pieces a `.pvtp` (`.pvtu`) at `path` lists, as paths beside it, in its order.
pub fn sources(path: &Path) -> Result<Vec<PathBuf>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let list: Vec<PathBuf> = text
        .lines()
        .filter_map(|l| {
            let l = l.trim();
            let rest = l.strip_prefix("<Piece Source=\"")?;
            Some(dir.join(&rest[..rest.find('"')?]))
        })
        .collect();
    if list.is_empty() {
        return Err(format!(
            "{}: a parallel VTK file that lists no piece",
            path.display()
        ));
    }
    Ok(list)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_pieces_and_collections_are_recognised() {
        assert!(is_piece_file(&piece_name("spheres", 12, 3, 4, "vtp")));
        assert!(is_piece_file(&piece_name("bodies", 12, 3, 4, "vtu")));
        assert!(is_piece_file("bodies_000012.pvtp"));
        assert!(is_piece_file(&collection_name("spheres", 12, "vtu")));
        assert!(!is_piece_file("spheres_000012.vtu"));
        assert!(!is_piece_file("walls_000012.pvtp"));
        assert!(!is_piece_file("spheres_000012.rank3.vtp"));
        assert!(!is_piece_file("spheres_.pvtp"));
    }
}
