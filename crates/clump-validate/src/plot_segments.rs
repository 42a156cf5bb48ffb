//! PNG pictures of line segments with a width each (force chains: contact
//! lines projected on a plane, width ∝ |F|), with the plots' font
//! ([`crate::plot`]) and equal scales on both axes.

use plotters::prelude::*;
use std::path::Path;

/// One segment: its two ends `(x, y)` (m) and its width in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// First end.
    pub a: (f64, f64),
    /// Second end.
    pub b: (f64, f64),
    /// Width, pixels (drawn at least 1).
    pub width: f64,
}

/// Draws `segments` into the PNG file `path` (900 pixels wide, the height
/// from the data's aspect ratio), with axis labels and a title.
pub fn draw_segments(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    segments: &[Segment],
) -> Result<(), String> {
    crate::plot::register();
    let pts = segments.iter().flat_map(|s| [s.a, s.b]);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if segments.is_empty() || !(x1 > x0 && y1 > y0) {
        return Err("no segments to draw".into());
    }
    let aspect = ((y1 - y0) / (x1 - x0)).clamp(0.2, 3.0);
    let w = 900u32;
    let h = ((w - 100) as f64 * aspect) as u32 + 100;
    let root = BitMapBackend::new(path, (w, h)).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut c = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    c.configure_mesh()
        .disable_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(|x| e(&x))?;
    let col = RGBColor(31, 119, 180);
    for s in segments {
        let wpx = s.width.round().max(1.0) as u32;
        c.draw_series(std::iter::once(PathElement::new(
            vec![s.a, s.b],
            col.stroke_width(wpx),
        )))
        .map_err(|x| e(&x))?;
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
