//! Reads a fluid velocity field from a VTK XML image-data file (`.vti`,
//! the `[fluid] velocity = "flow.vti"` of a scenario): the nodes of its
//! grid and a 3-component point-data array, as the `(position, velocity)`
//! pairs of [`clump_core::fluid::VelocityGrid::from_nodes`], so a field
//! read from a `.vti` and the same field from a CSV give the same grid.
//!
//! A small reader, not `vtkio`: vtkio keeps an image's `Origin` and
//! `Spacing` in f32 (a node would move by up to ~1e-7 of its coordinate,
//! so a grid built to cover the domain exactly could fall short of it),
//! and it pulls in nom 3. The XML is parsed by `roxmltree` (with line
//! numbers for errors), binary arrays decoded by `base64`.
//!
//! Read: one piece covering `WholeExtent`; `Float32` or `Float64` arrays,
//! `format="ascii"` or inline `format="binary"` (base64, `header_type`
//! `UInt32` or `UInt64`, little- or big-endian), without compression. The
//! array is the one `PointData`'s `Vectors` attribute names, else the only
//! 3-component array, else one named `velocity` or `U`. Refused with a
//! reason: compressed or appended data, a `Direction` other than the
//! identity, several pieces.

use base64::Engine as _;
use glam::DVec3;

/// A reading error: the line of the file it is at (when known) and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct VtiError {
    /// 1-based line of the file, when the error is at an element.
    pub line: Option<u32>,
    /// What is wrong.
    pub message: String,
}

fn fail(line: Option<u32>, message: impl Into<String>) -> VtiError {
    VtiError {
        line,
        message: message.into(),
    }
}

/// The `n` numbers of attribute `name` of `node`.
fn numbers<const N: usize, T: std::str::FromStr>(
    doc: &roxmltree::Document,
    node: roxmltree::Node,
    name: &str,
) -> Result<[T; N], VtiError> {
    let line = Some(doc.text_pos_at(node.range().start).row);
    let text = node
        .attribute(name)
        .ok_or_else(|| fail(line, format!("<{}> has no {name}", node.tag_name().name())))?;
    let v: Vec<T> = text
        .split_whitespace()
        .map(|s| s.parse::<T>())
        .collect::<Result<_, _>>()
        .map_err(|_| fail(line, format!("{name}=\"{text}\" is not {N} numbers")))?;
    v.try_into()
        .map_err(|_| fail(line, format!("{name}=\"{text}\" is not {N} numbers")))
}

/// The child elements of `n` with tag `tag`.
fn children<'a, 'i>(n: roxmltree::Node<'a, 'i>, tag: &str) -> Vec<roxmltree::Node<'a, 'i>> {
    n.children().filter(|c| c.has_tag_name(tag)).collect()
}

/// The nodes of the image data in `text`: position (m) and the velocity
/// array's value (m/s), world frame, x fastest.
pub fn read_vti(text: &str) -> Result<Vec<(DVec3, DVec3)>, VtiError> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        fail(Some(p.row), format!("not valid XML: {e}"))
    })?;
    let line = |n: roxmltree::Node| Some(doc.text_pos_at(n.range().start).row);
    let root = doc.root_element();
    if root.tag_name().name() != "VTKFile" || root.attribute("type") != Some("ImageData") {
        return Err(fail(
            line(root),
            "not a VTK XML image-data file (<VTKFile type=\"ImageData\">)",
        ));
    }
    if let Some(c) = root.attribute("compressor") {
        return Err(fail(
            line(root),
            format!(
                "compressed data ({c}) is not read: save the file uncompressed (ascii or binary)"
            ),
        ));
    }
    let big = root.attribute("byte_order") == Some("BigEndian");
    let header64 = root.attribute("header_type") == Some("UInt64");
    let image = children(root, "ImageData");
    let [image] = image[..] else {
        return Err(fail(line(root), "needs exactly one <ImageData>"));
    };
    let ext: [i64; 6] = numbers(&doc, image, "WholeExtent")?;
    let origin: [f64; 3] = numbers(&doc, image, "Origin")?;
    let spacing: [f64; 3] = numbers(&doc, image, "Spacing")?;
    if image.attribute("Direction").is_some() {
        let d: [f64; 9] = numbers(&doc, image, "Direction")?;
        if d != [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0] {
            return Err(fail(
                line(image),
                "a Direction other than the identity is not read: the grid's axes must be x, y, z",
            ));
        }
    }
    let pieces = children(image, "Piece");
    let [piece] = pieces[..] else {
        return Err(fail(
            line(image),
            format!("needs exactly one <Piece>, found {}", pieces.len()),
        ));
    };
    if numbers::<6, i64>(&doc, piece, "Extent")? != ext {
        return Err(fail(
            line(piece),
            "the piece's Extent must be the WholeExtent",
        ));
    }
    let n: Vec<usize> = (0..3)
        .map(|a| usize::try_from(ext[2 * a + 1] - ext[2 * a] + 1).unwrap_or(0))
        .collect();
    if n.contains(&0) {
        return Err(fail(
            line(image),
            format!("WholeExtent {ext:?} holds no node"),
        ));
    }
    let pd = children(piece, "PointData");
    let Some(&pd) = pd.first() else {
        return Err(fail(line(piece), "the piece has no <PointData>"));
    };
    let array = pick_array(&doc, pd)?;
    let total = n[0] * n[1] * n[2];
    let values = array_values(&doc, array, big, header64)?;
    if values.len() != 3 * total {
        return Err(fail(
            line(array),
            format!(
                "the array holds {} values, the {} x {} x {} nodes need {}",
                values.len(),
                n[0],
                n[1],
                n[2],
                3 * total
            ),
        ));
    }
    let mut nodes = Vec::with_capacity(total);
    let mut k = 0;
    for iz in ext[4]..=ext[5] {
        for iy in ext[2]..=ext[3] {
            for ix in ext[0]..=ext[1] {
                let p = DVec3::new(
                    origin[0] + ix as f64 * spacing[0],
                    origin[1] + iy as f64 * spacing[1],
                    origin[2] + iz as f64 * spacing[2],
                );
                nodes.push((p, DVec3::from_slice(&values[3 * k..3 * k + 3])));
                k += 1;
            }
        }
    }
    Ok(nodes)
}

/// The velocity array of `<PointData>`.
fn pick_array<'a, 'i>(
    doc: &roxmltree::Document,
    pd: roxmltree::Node<'a, 'i>,
) -> Result<roxmltree::Node<'a, 'i>, VtiError> {
    let line = Some(doc.text_pos_at(pd.range().start).row);
    let arrays: Vec<_> = pd
        .children()
        .filter(|c| c.has_tag_name("DataArray"))
        .collect();
    let three: Vec<_> = arrays
        .iter()
        .copied()
        .filter(|a| a.attribute("NumberOfComponents") == Some("3"))
        .collect();
    let named = |name: &str| {
        three
            .iter()
            .copied()
            .find(|a| a.attribute("Name") == Some(name))
    };
    let chosen = match pd.attribute("Vectors") {
        Some(v) => named(v),
        None if three.len() == 1 => Some(three[0]),
        None => named("velocity").or_else(|| named("U")),
    };
    chosen.ok_or_else(|| {
        let names: Vec<&str> = three.iter().filter_map(|a| a.attribute("Name")).collect();
        fail(
            line,
            format!(
                "no velocity array: the point data's 3-component arrays are [{}]; name one with Vectors=\"…\" on <PointData>, or call it velocity or U",
                names.join(", ")
            ),
        )
    })
}

/// The numbers of a `<DataArray>` (Float32 or Float64), as f64.
fn array_values(
    doc: &roxmltree::Document,
    a: roxmltree::Node,
    big: bool,
    header64: bool,
) -> Result<Vec<f64>, VtiError> {
    let line = Some(doc.text_pos_at(a.range().start).row);
    let ty = a.attribute("type").unwrap_or("");
    let width = match ty {
        "Float32" => 4,
        "Float64" => 8,
        _ => {
            return Err(fail(
                line,
                format!("the array's type is '{ty}': Float32 or Float64 is read"),
            ))
        }
    };
    let text = a.text().unwrap_or("");
    match a.attribute("format") {
        Some("ascii") => text
            .split_whitespace()
            .map(|s| s.parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| {
                fail(
                    line,
                    format!("the array has a value that is not a number: {e}"),
                )
            }),
        Some("binary") => {
            let bytes = binary_payload(text.trim(), header64, big).map_err(|m| fail(line, m))?;
            if bytes.len() % width != 0 {
                return Err(fail(
                    line,
                    format!("{} bytes of data are not whole {ty} values", bytes.len()),
                ));
            }
            Ok(bytes
                .chunks_exact(width)
                .map(|c| {
                    let mut b = [0u8; 8];
                    b[..width].copy_from_slice(c);
                    if big {
                        b[..width].reverse();
                    }
                    if width == 4 {
                        f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64
                    } else {
                        f64::from_le_bytes(b)
                    }
                })
                .collect())
        }
        other => Err(fail(
            line,
            format!("format {other:?} is not read: save the array as ascii or (inline) binary"),
        )),
    }
}

/// The data bytes of an inline binary array: base64 of a byte-count header
/// (UInt32 or UInt64) and the data, encoded as one stream or as two (the
/// header on its own, as VTK writes it).
fn binary_payload(text: &str, header64: bool, big: bool) -> Result<Vec<u8>, String> {
    let b64 = base64::engine::general_purpose::STANDARD;
    let hs = if header64 { 8 } else { 4 };
    let count = |h: &[u8]| -> u64 {
        let mut b = [0u8; 8];
        b[..hs].copy_from_slice(&h[..hs]);
        if big {
            b[..hs].reverse();
        }
        u64::from_le_bytes(b)
    };
    if let Ok(all) = b64.decode(text) {
        if all.len() >= hs && count(&all) == (all.len() - hs) as u64 {
            return Ok(all[hs..].to_vec());
        }
    }
    let split = 4 * hs.div_ceil(3);
    if text.len() >= split {
        if let (Ok(h), Ok(data)) = (b64.decode(&text[..split]), b64.decode(&text[split..])) {
            if h.len() >= hs && count(&h) == data.len() as u64 {
                return Ok(data);
            }
        }
    }
    Err("the binary array is not base64 of a byte count and as many bytes of data".into())
}
