//! The writer of one VTK XML PolyData file (`.vtp`): points, vertex, line
//! and polygon cells, point, cell and field data, every numeric array in
//! one raw appended block (`header_type="UInt64"`, little endian). Used by
//! the frames of [`crate::vtk`] and the contact frames of
//! [`crate::vtk_contacts`].

use glam::DVec3;
use std::fmt::Write as _;

/// Element types of the data arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ty {
    F64,
    I64,
    U64,
    I32,
    U8,
}

impl Ty {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Ty::F64 => "Float64",
            Ty::I64 => "Int64",
            Ty::U64 => "UInt64",
            Ty::I32 => "Int32",
            Ty::U8 => "UInt8",
        }
    }
}

pub(crate) struct Array {
    name: String,
    ty: Ty,
    components: usize,
    offset: usize,
}

/// Assembles one `.vtp` file: arrays go to the appended block as they are added.
#[derive(Default)]
pub(crate) struct Vtp {
    data: Vec<u8>,
    point_data: Vec<Array>,
    cell_data: Vec<Array>,
    points: Option<Array>,
    verts: Vec<Array>,
    polys: Vec<Array>,
    lines: Vec<Array>,
    /// Field data: (name, strings), written inline as ASCII string arrays.
    strings: Vec<(String, Vec<String>)>,
    n_points: usize,
    n_lines: usize,
    n_verts: usize,
    n_polys: usize,
}

impl Vtp {
    pub(crate) fn push_block(
        &mut self,
        name: &str,
        ty: Ty,
        components: usize,
        bytes: Vec<u8>,
    ) -> Array {
        let offset = self.data.len();
        self.data
            .extend_from_slice(&(bytes.len() as u64).to_le_bytes());
        self.data.extend_from_slice(&bytes);
        Array {
            name: name.to_string(),
            ty,
            components,
            offset,
        }
    }

    pub(crate) fn f64s(values: impl Iterator<Item = f64>) -> Vec<u8> {
        let mut b = Vec::new();
        for v in values {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b
    }

    pub(crate) fn vec3s<'a>(values: impl Iterator<Item = &'a DVec3>) -> Vec<u8> {
        Self::f64s(values.flat_map(|v| [v.x, v.y, v.z]))
    }

    pub(crate) fn set_points(&mut self, pts: &[DVec3]) {
        self.n_points = pts.len();
        let a = self.push_block("Points", Ty::F64, 3, Self::vec3s(pts.iter()));
        self.points = Some(a);
    }

    pub(crate) fn point_vec3(&mut self, name: &str, v: &[DVec3]) {
        let a = self.push_block(name, Ty::F64, 3, Self::vec3s(v.iter()));
        self.point_data.push(a);
    }

    pub(crate) fn point_f64(&mut self, name: &str, comps: usize, v: impl Iterator<Item = f64>) {
        let a = self.push_block(name, Ty::F64, comps, Self::f64s(v));
        self.point_data.push(a);
    }

    pub(crate) fn point_u64(&mut self, name: &str, v: impl Iterator<Item = u64>) {
        let bytes: Vec<u8> = v.flat_map(|x| x.to_le_bytes()).collect();
        let a = self.push_block(name, Ty::U64, 1, bytes);
        self.point_data.push(a);
    }

    pub(crate) fn point_i32(&mut self, name: &str, v: impl Iterator<Item = i32>) {
        let bytes: Vec<u8> = v.flat_map(|x| x.to_le_bytes()).collect();
        let a = self.push_block(name, Ty::I32, 1, bytes);
        self.point_data.push(a);
    }

    pub(crate) fn cell_i32(&mut self, name: &str, v: impl Iterator<Item = i32>) {
        let bytes: Vec<u8> = v.flat_map(|x| x.to_le_bytes()).collect();
        let a = self.push_block(name, Ty::I32, 1, bytes);
        self.cell_data.push(a);
    }

    pub(crate) fn cell_u8(&mut self, name: &str, v: impl Iterator<Item = u8>) {
        let bytes: Vec<u8> = v.collect();
        let a = self.push_block(name, Ty::U8, 1, bytes);
        self.cell_data.push(a);
    }

    pub(crate) fn cell_f64(&mut self, name: &str, comps: usize, v: impl Iterator<Item = f64>) {
        let a = self.push_block(name, Ty::F64, comps, Self::f64s(v));
        self.cell_data.push(a);
    }

    pub(crate) fn cell_vec3(&mut self, name: &str, v: &[DVec3]) {
        let a = self.push_block(name, Ty::F64, 3, Self::vec3s(v.iter()));
        self.cell_data.push(a);
    }

    pub(crate) fn cell_u64(&mut self, name: &str, v: impl Iterator<Item = u64>) {
        let bytes: Vec<u8> = v.flat_map(|x| x.to_le_bytes()).collect();
        let a = self.push_block(name, Ty::U64, 1, bytes);
        self.cell_data.push(a);
    }

    /// A list of names as field data (a VTK string array), e.g. the wall
    /// or template names that an index array refers to.
    pub(crate) fn field_strings(&mut self, name: &str, values: &[String]) {
        self.strings.push((name.to_string(), values.to_vec()));
    }

    /// Line cells between consecutive pairs of points (0–1, 2–3, …).
    pub(crate) fn pair_lines(&mut self) {
        let n = (self.n_points / 2) as i64;
        self.n_lines = n as usize;
        let conn: Vec<u8> = (0..2 * n).flat_map(|i| i.to_le_bytes()).collect();
        let offs: Vec<u8> = (1..=n).flat_map(|i| (2 * i).to_le_bytes()).collect();
        let a = self.push_block("connectivity", Ty::I64, 1, conn);
        let b = self.push_block("offsets", Ty::I64, 1, offs);
        self.lines = vec![a, b];
    }

    /// One vertex cell per point.
    pub(crate) fn vertex_cells(&mut self) {
        let n = self.n_points as i64;
        self.n_verts = self.n_points;
        let conn: Vec<u8> = (0..n).flat_map(|i| i.to_le_bytes()).collect();
        let offs: Vec<u8> = (1..=n).flat_map(|i| i.to_le_bytes()).collect();
        let a = self.push_block("connectivity", Ty::I64, 1, conn);
        let b = self.push_block("offsets", Ty::I64, 1, offs);
        self.verts = vec![a, b];
    }

    /// Polygons given as lists of point indices.
    pub(crate) fn polygons(&mut self, polys: &[Vec<i64>]) {
        self.n_polys = polys.len();
        let mut conn = Vec::new();
        let mut offs = Vec::new();
        let mut end = 0i64;
        for p in polys {
            for &i in p {
                conn.extend_from_slice(&i.to_le_bytes());
            }
            end += p.len() as i64;
            offs.extend_from_slice(&end.to_le_bytes());
        }
        let a = self.push_block("connectivity", Ty::I64, 1, conn);
        let b = self.push_block("offsets", Ty::I64, 1, offs);
        self.polys = vec![a, b];
    }

    pub(crate) fn finish(self) -> Vec<u8> {
        let mut x = String::new();
        let arr = |x: &mut String, a: &Array, indent: &str| {
            let _ = writeln!(
                x,
                "{indent}<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>",
                a.ty.name(),
                a.name,
                a.components,
                a.offset
            );
        };
        x.push_str("<?xml version=\"1.0\"?>\n");
        x.push_str("<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
        x.push_str("  <PolyData>\n");
        if !self.strings.is_empty() {
            x.push_str("    <FieldData>\n");
            for (name, values) in &self.strings {
                // VTK's ASCII string arrays: the bytes of each string as
                // numbers, each string ended by a 0
                let codes: Vec<String> = values
                    .iter()
                    .flat_map(|v| v.bytes().map(|b| b.to_string()).chain(["0".to_string()]))
                    .collect();
                let _ = writeln!(
                    x,
                    "      <Array type=\"String\" Name=\"{name}\" NumberOfTuples=\"{}\" format=\"ascii\">\n        {}\n      </Array>",
                    values.len(),
                    codes.join(" ")
                );
            }
            x.push_str("    </FieldData>\n");
        }
        let _ = writeln!(
            x,
            "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">",
            self.n_points, self.n_verts, self.n_lines, self.n_polys
        );
        x.push_str("      <PointData>\n");
        for a in &self.point_data {
            arr(&mut x, a, "        ");
        }
        x.push_str("      </PointData>\n      <CellData>\n");
        for a in &self.cell_data {
            arr(&mut x, a, "        ");
        }
        x.push_str("      </CellData>\n      <Points>\n");
        if let Some(a) = &self.points {
            arr(&mut x, a, "        ");
        }
        x.push_str("      </Points>\n");
        for (tag, list) in [
            ("Verts", &self.verts),
            ("Lines", &self.lines),
            ("Polys", &self.polys),
        ] {
            if !list.is_empty() {
                let _ = writeln!(x, "      <{tag}>");
                for a in list {
                    arr(&mut x, a, "        ");
                }
                let _ = writeln!(x, "      </{tag}>");
            }
        }
        x.push_str("    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _");
        let mut out = x.into_bytes();
        out.extend_from_slice(&self.data);
        out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
        out
    }
}
