//! `.vtu` (VTK XML UnstructuredGrid) frames, for readers without PolyData
//! support such as meshio: the same points, arrays and cells as the `.vtp`
//! files of [`crate::vtk`], re-labelled. Vertex cells (spheres, bodies)
//! become `VTK_VERTEX` (1), polygons (walls) `VTK_POLYGON` (7); the cell
//! types array is appended to the raw data block. The string field data of
//! the `.vtp` files (template names) are left out: meshio refuses String
//! arrays (the names are in `manifest.json`).

use serde::{Deserialize, Serialize};

/// The file format of the VTK frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VtkFormat {
    /// XML PolyData (`.vtp`), ParaView's usual format.
    #[default]
    Vtp,
    /// XML UnstructuredGrid (`.vtu`), also read by meshio.
    Vtu,
}

impl VtkFormat {
    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            VtkFormat::Vtp => "vtp",
            VtkFormat::Vtu => "vtu",
        }
    }

    /// `vtp` (a file of [`crate::vtk`]) in this format.
    pub fn encode(self, vtp: Vec<u8>) -> Vec<u8> {
        match self {
            VtkFormat::Vtp => vtp,
            VtkFormat::Vtu => to_vtu(&vtp),
        }
    }
}

const DATA_START: &[u8] = b"<AppendedData encoding=\"raw\">\n   _";
const TRAILER: &[u8] = b"\n  </AppendedData>\n</VTKFile>\n";

fn attr(text: &str, name: &str) -> usize {
    let key = format!(" {name}=\"");
    text.find(&key)
        .and_then(|i| {
            let rest = &text[i + key.len()..];
            rest[..rest.find('"')?].parse().ok()
        })
        .unwrap_or(0)
}

/// The UnstructuredGrid form of a PolyData file written by [`crate::vtk`]
/// (vertex or polygon cells, raw appended data).
pub fn to_vtu(vtp: &[u8]) -> Vec<u8> {
    let start = vtp
        .windows(DATA_START.len())
        .position(|w| w == DATA_START)
        .map_or(vtp.len(), |i| i + DATA_START.len());
    let end = vtp.len().saturating_sub(TRAILER.len()).max(start);
    let mut head = String::from_utf8_lossy(&vtp[..start]).into_owned();
    // the string field data (template names) stay in the .vtp form only:
    // meshio refuses String arrays
    if let (Some(a), Some(b)) = (head.find("    <FieldData>"), head.find("</FieldData>\n")) {
        head.replace_range(a..b + "</FieldData>\n".len(), "");
    }
    let data = &vtp[start..end];
    let piece_start = head.find("<Piece ").unwrap_or(0);
    let piece_end = head[piece_start..]
        .find('>')
        .map_or(0, |i| piece_start + i + 1);
    let piece = &head[piece_start..piece_end];
    let (n_points, n_verts, n_polys) = (
        attr(piece, "NumberOfPoints"),
        attr(piece, "NumberOfVerts"),
        attr(piece, "NumberOfPolys"),
    );
    let (tag, cell_type) = if head.contains("<Polys>") {
        ("Polys", 7u8)
    } else {
        ("Verts", 1u8)
    };
    let n_cells = n_verts + n_polys;
    let types = format!(
        "        <DataArray type=\"UInt8\" Name=\"types\" NumberOfComponents=\"1\" format=\"appended\" offset=\"{}\"/>\n      </Cells>",
        data.len()
    );
    let head = head
        .replace("type=\"PolyData\"", "type=\"UnstructuredGrid\"")
        .replace("<PolyData>", "<UnstructuredGrid>")
        .replace("</PolyData>", "</UnstructuredGrid>")
        .replace(
            piece,
            &format!("<Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\">"),
        )
        .replace(&format!("<{tag}>"), "<Cells>")
        .replace(&format!("      </{tag}>"), &types);
    let mut out = head.into_bytes();
    out.extend_from_slice(data);
    out.extend_from_slice(&(n_cells as u64).to_le_bytes());
    out.extend(std::iter::repeat(cell_type).take(n_cells));
    out.extend_from_slice(TRAILER);
    out
}
