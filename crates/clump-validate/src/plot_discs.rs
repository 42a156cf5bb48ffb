//! PNG pictures of spheres as discs projected on a plane (a quick look at
//! the particles without ParaView): far spheres first, so nearer ones cover
//! them; each disc coloured by a value on a blue-to-red scale whose range
//! is printed under the title; equal scales on both axes.

use plotters::prelude::*;
use std::path::Path;

/// One sphere seen along the view axis: centre `(x, y)` (m) in the picture
/// plane, `depth` (m, larger is nearer the viewer), radius (m) and value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// Centre in the picture plane, m.
    pub centre: (f64, f64),
    /// Coordinate along the view axis, m (larger: nearer).
    pub depth: f64,
    /// Radius, m.
    pub radius: f64,
    /// The value that gives the colour.
    pub value: f64,
}

/// Blue (0) through white-ish green to red (1).
fn colour(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (r, g, b) = if t < 0.5 {
        let s = 2.0 * t;
        (40.0 + 160.0 * s, 70.0 + 150.0 * s, 200.0 - 40.0 * s)
    } else {
        let s = 2.0 * t - 1.0;
        (200.0 + 40.0 * s, 220.0 - 170.0 * s, 160.0 - 120.0 * s)
    };
    RGBColor(r as u8, g as u8, b as u8)
}

/// Draws `discs` into the PNG file `path` (900 pixels wide, the height from
/// the data's aspect ratio), coloured by value from `range.0` (blue) to
/// `range.1` (red), with axis labels and a title; `scale_label` names the
/// colour scale (e.g. "|v| [m/s]").
pub fn draw_discs(
    path: &Path,
    title: &str,
    labels: (&str, &str),
    scale_label: &str,
    range: (f64, f64),
    discs: &[Disc],
) -> Result<(), String> {
    crate::plot::register();
    if discs.is_empty() {
        return Err("no spheres to draw".into());
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for d in discs {
        x0 = x0.min(d.centre.0 - d.radius);
        x1 = x1.max(d.centre.0 + d.radius);
        y0 = y0.min(d.centre.1 - d.radius);
        y1 = y1.max(d.centre.1 + d.radius);
    }
    if !(x1 > x0 && y1 > y0) {
        return Err("the spheres have no extent".into());
    }
    let aspect = ((y1 - y0) / (x1 - x0)).clamp(0.2, 3.0);
    let w = 900u32;
    let h = ((w - 100) as f64 * aspect) as u32 + 130;
    let root = BitMapBackend::new(path, (w, h)).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let caption = format!(
        "{title}\ncolour: {scale_label} from {:.3e} (blue) to {:.3e} (red)",
        range.0, range.1
    );
    let mut area = root.clone();
    for line in caption.lines() {
        area = area.titled(line, ("sans-serif", 20)).map_err(|x| e(&x))?;
    }
    let (mut c, per_px) = crate::plot_segments::equal_scale_chart(&area, (x0, x1, y0, y1), labels)?;
    let mut order: Vec<usize> = (0..discs.len()).collect();
    order.sort_by(|&a, &b| discs[a].depth.total_cmp(&discs[b].depth));
    let span = (range.1 - range.0).max(f64::MIN_POSITIVE);
    let outline = RGBColor(60, 60, 60);
    c.draw_series(order.iter().map(|&i| {
        let d = &discs[i];
        let r_px = (d.radius / per_px).round().max(1.0) as i32;
        let fill = colour((d.value - range.0) / span);
        EmptyElement::at(d.centre)
            + Circle::new((0, 0), r_px, fill.filled())
            + Circle::new((0, 0), r_px, outline.stroke_width(1))
    }))
    .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
