//! PNG pictures of line segments with a width each (force chains: contact
//! lines projected on a plane, width ∝ |F|), with the plots' font
//! ([`crate::plot`]) and equal scales on both axes.

use plotters::coord::types::RangedCoordf64;
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
    let area = root.titled(title, ("sans-serif", 22)).map_err(|x| e(&x))?;
    let (mut c, _) = equal_scale_chart(&area, (x0, x1, y0, y1), (x_label, y_label))?;
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

/// A chart drawn on `area` for data within `bounds` = `(x0, x1, y0, y1)`
/// (m), with axis labels, whose ranges are widened about their centre so
/// that one metre is as many pixels across as up (pictures to scale).
/// Returns it and the metres per pixel.
pub(crate) fn equal_scale_chart<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, plotters::coord::Shift>,
    bounds: (f64, f64, f64, f64),
    labels: (&str, &str),
) -> Result<
    (
        ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        f64,
    ),
    String,
> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let (x0, x1, y0, y1) = bounds;
    let (margin, x_area, y_area) = (15u32, 45u32, 75u32);
    let (aw, ah) = area.dim_in_pixel();
    let pw = aw.saturating_sub(2 * margin + y_area).max(1) as f64;
    let ph = ah.saturating_sub(2 * margin + x_area).max(1) as f64;
    let per_px = ((x1 - x0) / pw).max((y1 - y0) / ph);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (x0, x1) = (cx - 0.5 * per_px * pw, cx + 0.5 * per_px * pw);
    let (y0, y1) = (cy - 0.5 * per_px * ph, cy + 0.5 * per_px * ph);
    let mut c = ChartBuilder::on(area)
        .margin(margin)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    c.configure_mesh()
        .disable_mesh()
        .x_desc(labels.0)
        .y_desc(labels.1)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(|x| e(&x))?;
    Ok((c, per_px))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A metre spans as many pixels across as up, for data ten times wider
    /// than tall and for data taller than wide (to the pixel rounding of
    /// the plotting area).
    #[test]
    fn chart_is_to_scale() {
        crate::plot::register();
        for bounds in [(0.0, 1.0, 0.0, 0.1), (0.0, 0.1, 0.0, 1.0)] {
            let mut buf = vec![0u8; 900 * 400 * 3];
            let root = BitMapBackend::with_buffer(&mut buf, (900, 400)).into_drawing_area();
            let (c, _) = equal_scale_chart(&root, bounds, ("x", "y")).unwrap();
            let (pw, ph) = c.plotting_area().dim_in_pixel();
            let (xr, yr) = (c.x_range(), c.y_range());
            let sx = (xr.end - xr.start) / pw as f64;
            let sy = (yr.end - yr.start) / ph as f64;
            assert!(
                (sx / sy - 1.0).abs() < 0.01,
                "{bounds:?}: {sx} vs {sy} m/px"
            );
            assert!(xr.start <= bounds.0 && xr.end >= bounds.1);
            assert!(yr.start <= bounds.2 && yr.end >= bounds.3);
        }
    }
}
