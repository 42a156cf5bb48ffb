//! Writers of coarse-grained fields: VTK image data (`.vti`, ParaView) for
//! any grid, CSV for a 1D grid (depth profiles), the names and units of the
//! columns in the header.

use super::fields::Fields;
use super::grid::Grid;
use glam::{DMat3, DVec3};
use std::fmt::Write as _;

/// One output quantity: name, unit, components per cell.
struct Column {
    name: &'static str,
    unit: &'static str,
    values: Vec<f64>,
    components: usize,
}

fn mat(m: &[DMat3]) -> Vec<f64> {
    // row-major: xx, xy, xz, yx, …
    m.iter()
        .flat_map(|a| {
            let t = a.transpose();
            t.to_cols_array()
        })
        .collect()
}

fn vec3(v: &[DVec3]) -> Vec<f64> {
    v.iter().flat_map(|a| [a.x, a.y, a.z]).collect()
}

fn columns(f: &Fields) -> Vec<Column> {
    let stress = f.stress();
    vec![
        Column {
            name: "density",
            unit: "kg/m^3",
            values: f.density.clone(),
            components: 1,
        },
        Column {
            name: "momentum",
            unit: "kg/(m^2*s)",
            values: vec3(&f.momentum),
            components: 3,
        },
        Column {
            name: "velocity",
            unit: "m/s",
            values: vec3(&f.velocity()),
            components: 3,
        },
        Column {
            name: "pressure",
            unit: "Pa",
            values: stress
                .iter()
                .map(|s| (s.x_axis.x + s.y_axis.y + s.z_axis.z) / 3.0)
                .collect(),
            components: 1,
        },
        Column {
            name: "stress",
            unit: "Pa",
            values: mat(&stress),
            components: 9,
        },
        Column {
            name: "kinetic_stress",
            unit: "Pa",
            values: mat(&f.kinetic_stress),
            components: 9,
        },
        Column {
            name: "contact_stress",
            unit: "Pa",
            values: mat(&f.contact_stress),
            components: 9,
        },
        Column {
            name: "fabric",
            unit: "",
            values: mat(&f.fabric()),
            components: 9,
        },
        Column {
            name: "order",
            unit: "",
            values: mat(&f.order()),
            components: 9,
        },
        Column {
            name: "coordination",
            unit: "",
            values: f.coordination(),
            components: 1,
        },
        Column {
            name: "number_density",
            unit: "1/m^3",
            values: f.number_density.clone(),
            components: 1,
        },
        Column {
            name: "void_fraction",
            unit: "",
            values: f.void_fraction(),
            components: 1,
        },
    ]
}

const AXES: [&str; 3] = ["x", "y", "z"];
const COMPONENTS: [&str; 9] = ["xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"];

/// The fields of a 1D grid as CSV: the cell centre, then every quantity
/// (vectors as `_x, _y, _z`, tensors as `_xx … _zz`), units in brackets.
pub fn csv_1d(grid: &Grid, f: &Fields) -> String {
    let cols = columns(f);
    let mut s = format!("{}[m]", AXES[grid.axes[0]]);
    for c in &cols {
        let unit = if c.unit.is_empty() {
            String::new()
        } else {
            format!("[{}]", c.unit)
        };
        match c.components {
            1 => {
                let _ = write!(s, ",{}{unit}", c.name);
            }
            3 => {
                for a in AXES {
                    let _ = write!(s, ",{}_{a}{unit}", c.name);
                }
            }
            _ => {
                for a in COMPONENTS {
                    let _ = write!(s, ",{}_{a}{unit}", c.name);
                }
            }
        }
    }
    s.push('\n');
    for i in 0..grid.len() {
        let _ = write!(s, "{:e}", grid.centre(0, i));
        for c in &cols {
            for k in 0..c.components {
                let _ = write!(s, ",{:e}", c.values[i * c.components + k]);
            }
        }
        s.push('\n');
    }
    s
}

/// The fields as VTK XML image data: one point per cell at its centre
/// (axes that are averaged over have one point at the domain's middle),
/// the arrays as in [`csv_1d`], tensors with 9 components, row-major.
pub fn vti(grid: &Grid, f: &Fields) -> String {
    let d = &grid.domain;
    let mut dims = [1usize; 3];
    let mut origin = (d.lo + d.hi) * 0.5;
    let mut spacing = d.size();
    for (k, &a) in grid.axes.iter().enumerate() {
        dims[a] = grid.cells[k];
        origin[a] = grid.centre(k, 0);
        spacing[a] = grid.spacing(k);
    }
    // the grid's cell index of VTK's point (x fastest)
    let mut order = Vec::with_capacity(grid.len());
    for iz in 0..dims[2] {
        for iy in 0..dims[1] {
            for ix in 0..dims[0] {
                let world = [ix, iy, iz];
                let mut c = 0;
                for (k, &a) in grid.axes.iter().enumerate() {
                    c = c * grid.cells[k] + world[a];
                }
                order.push(c);
            }
        }
    }
    let ext = format!("0 {} 0 {} 0 {}", dims[0] - 1, dims[1] - 1, dims[2] - 1);
    let mut x = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    let _ = writeln!(
        x,
        "  <ImageData WholeExtent=\"{ext}\" Origin=\"{:e} {:e} {:e}\" Spacing=\"{:e} {:e} {:e}\">\n    <Piece Extent=\"{ext}\">\n      <PointData>",
        origin.x, origin.y, origin.z, spacing.x, spacing.y, spacing.z
    );
    for c in columns(f) {
        let _ = write!(
            x,
            "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n         ",
            c.name, c.components
        );
        for &i in &order {
            for k in 0..c.components {
                let _ = write!(x, " {:e}", c.values[i * c.components + k]);
            }
        }
        x.push_str("\n        </DataArray>\n");
    }
    x.push_str("      </PointData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n");
    x
}
