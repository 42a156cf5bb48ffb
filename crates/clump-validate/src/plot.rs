//! PNG line/scatter plots with `plotters` (bitmap backend). The font is
//! DejaVu Sans, embedded at compile time (`assets/fonts/`), so no system
//! font is needed.

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// A solid line.
    Line,
    /// A dashed line (a reference or theory curve).
    Dashed,
    /// Markers only (measured points).
    Points,
    /// A line with markers.
    LinePoints,
}

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
    /// Half-length of a vertical error bar at each point (same units as
    /// y); empty for no error bars.
    pub y_err: Vec<f64>,
}

impl Series {
    /// A series from its label, points and style.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series {
            label: label.into(),
            points,
            style,
            y_err: Vec::new(),
        }
    }

    /// A series with a vertical error bar `y ± y_err[k]` at point `k`.
    pub fn with_errors(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        y_err: Vec<f64>,
        style: Style,
    ) -> Series {
        Series {
            y_err,
            ..Series::new(label, points, style)
        }
    }

    /// `(x, y − e, y + e)` of each finite point with a finite error bar.
    fn bars(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.points
            .iter()
            .zip(&self.y_err)
            .filter(|(p, e)| p.0.is_finite() && p.1.is_finite() && e.is_finite())
            .map(|(p, e)| (p.0, p.1 - e.abs(), p.1 + e.abs()))
    }
}

/// A whole chart.
#[derive(Debug, Clone)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Curves, drawn in order with colours from a fixed palette.
    pub series: Vec<Series>,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
];

/// Every finite point of the series, error-bar ends included.
fn finite_points(series: &[Series]) -> impl Iterator<Item = (f64, f64)> + '_ {
    series
        .iter()
        .flat_map(|s| {
            s.points
                .iter()
                .copied()
                .chain(s.bars().flat_map(|(x, lo, hi)| [(x, lo), (x, hi)]))
        })
        .filter(|p| p.0.is_finite() && p.1.is_finite())
}

fn bounds(series: &[Series]) -> Option<(f64, f64, f64, f64)> {
    let pts = finite_points(series);
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        return None;
    }
    let pad = |a: f64, b: f64| {
        let d = if b > a {
            0.05 * (b - a)
        } else {
            0.5 * a.abs().max(1e-12)
        };
        (a - d, b + d)
    };
    let (x0, x1) = pad(x0, x1);
    let (y0, y1) = pad(y0, y1);
    Some((x0, x1, y0, y1))
}

fn dashed(points: &[(f64, f64)], x_span: f64) -> Vec<Vec<(f64, f64)>> {
    // resample long segments, then break the polyline into dashes of about 1.5 % of the x span
    let dash = 0.015 * x_span;
    let mut fine = Vec::with_capacity(points.len() * 4);
    for w in points.windows(2) {
        let k = (((w[1].0 - w[0].0).abs() / (0.5 * dash)).ceil() as usize).clamp(1, 400);
        for i in 0..k {
            let s = i as f64 / k as f64;
            fine.push((
                w[0].0 + s * (w[1].0 - w[0].0),
                w[0].1 + s * (w[1].1 - w[0].1),
            ));
        }
    }
    if let Some(&last) = points.last() {
        fine.push(last);
    }
    let points = &fine[..];
    let mut out = Vec::new();
    let mut cur = Vec::new();
    let mut acc = 0.0;
    let mut on = true;
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if on {
            if cur.is_empty() {
                cur.push(a);
            }
            cur.push(b);
        }
        acc += (b.0 - a.0).abs().max(1e-300);
        if acc >= dash {
            acc = 0.0;
            if on {
                out.push(std::mem::take(&mut cur));
            }
            on = !on;
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    if out.is_empty() {
        out.push(points.to_vec());
    }
    out
}

/// The corner for the legend: the first of upper right, upper left, lower
/// right and lower left with the fewest points (error-bar ends included) in
/// its 40 % × 35 % of the plot area.
fn legend_corner(series: &[Series], (x0, x1, y0, y1): (f64, f64, f64, f64)) -> SeriesLabelPosition {
    let pts: Vec<(f64, f64)> = finite_points(series)
        .map(|p| ((p.0 - x0) / (x1 - x0), (p.1 - y0) / (y1 - y0)))
        .collect();
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let count = |right: bool, upper: bool| {
        pts.iter()
            .filter(|p| {
                (if right { p.0 > 0.6 } else { p.0 < 0.4 })
                    && (if upper { p.1 > 0.65 } else { p.1 < 0.35 })
            })
            .count()
    };
    let mut best = (usize::MAX, SeriesLabelPosition::UpperRight);
    for (pos, right, upper) in corners {
        let n = count(right, upper);
        if n < best.0 {
            best = (n, pos);
        }
    }
    best.1
}

/// Registers the embedded font as "sans-serif" (once).
pub(crate) fn register() {
    REGISTER.call_once(|| {
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Draws `chart` into the PNG file `path` (900×600 pixels).
pub fn draw(path: &Path, chart: &Chart) -> Result<(), String> {
    register();
    let (x0, x1, y0, y1) = bounds(&chart.series).ok_or("no finite data to plot")?;
    let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut c = ChartBuilder::on(&root)
        .caption(&chart.title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    c.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(|x| e(&x))?;
    for (i, s) in chart.series.iter().enumerate() {
        let col = PALETTE[i % PALETTE.len()];
        let line = col.stroke_width(2);
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        let anno = match s.style {
            Style::Line | Style::LinePoints => c
                .draw_series(LineSeries::new(pts.clone(), line))
                .map_err(|x| e(&x))?,
            Style::Dashed => {
                let mut last = None;
                for d in dashed(&pts, x1 - x0) {
                    last = Some(c.draw_series(LineSeries::new(d, line)).map_err(|x| e(&x))?);
                }
                last.ok_or("empty dashed series")?
            }
            Style::Points => c
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, col.filled())))
                .map_err(|x| e(&x))?,
        };
        anno.label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(3)));
        c.draw_series(
            s.bars()
                .map(|(x, lo, hi)| ErrorBar::new_vertical(x, lo, 0.5 * (lo + hi), hi, line, 8)),
        )
        .map_err(|x| e(&x))?;
        if s.style == Style::LinePoints {
            c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, col.filled())))
                .map_err(|x| e(&x))?;
        }
    }
    c.configure_series_labels()
        .label_font(("sans-serif", 15))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(legend_corner(&chart.series, (x0, x1, y0, y1)))
        .draw()
        .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_bars_widen_the_bounds_and_draw() {
        let s = Series::with_errors(
            "a",
            vec![(0.0, 1.0), (1.0, 2.0)],
            vec![0.5, 3.0],
            Style::LinePoints,
        );
        let (_, _, y0, y1) = bounds(std::slice::from_ref(&s)).unwrap();
        assert!(y0 < 0.5 && y1 > 5.0, "{y0} {y1}");
        let path = std::env::temp_dir().join(format!("clump-errbar-{}.png", std::process::id()));
        let c = Chart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![s],
        };
        draw(&path, &c).unwrap();
        assert!(std::fs::read(&path).unwrap().starts_with(b"\x89PNG"));
        let _ = std::fs::remove_file(&path);
    }
}
