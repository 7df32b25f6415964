//! PNG plots for reports and the command line (feature `plot`): line plots with optional
//! log axes and vertical frequency markers, and equal-aspect orbit plots. Text is drawn
//! with the bundled DejaVu Sans font (assets/), so no system fonts are needed.

use crate::error::{Error, Result};
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../assets/DejaVuSans.ttf");
        // Registration fails only for a malformed font, which the bundled one is not.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, bytes);
    });
}

/// One curve.
#[derive(Debug, Clone, Copy)]
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates.
    pub y: &'a [f64],
    /// Draw points instead of a line.
    pub points: bool,
}

/// A labelled vertical line (e.g. a characteristic frequency).
#[derive(Debug, Clone)]
pub struct Marker {
    /// Position on the x axis.
    pub x: f64,
    /// Label.
    pub label: String,
}

/// Axes and labels of a plot.
#[derive(Debug, Clone, Default)]
pub struct Axes<'a> {
    /// Title.
    pub title: &'a str,
    /// x-axis label.
    pub x_label: &'a str,
    /// y-axis label.
    pub y_label: &'a str,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Same scale on both axes (orbits).
    pub equal: bool,
}

fn io(e: impl std::fmt::Display) -> Error {
    Error::Io(format!("plot: {e}"))
}

fn range(vals: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (1e-3, 1.0) } else { (-1.0, 1.0) };
    }
    if log {
        (lo / 1.5, hi * 1.5)
    } else if hi - lo < 1e-300 + 1e-12 * hi.abs().max(lo.abs()) {
        let d = if hi == 0.0 { 1.0 } else { 0.1 * hi.abs() };
        (lo - d, hi + d)
    } else {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

/// Tick label: powers of ten on log axes (`1e-6`), plain short numbers otherwise.
fn tick(v: f64, log: bool) -> String {
    if log {
        let e = v.log10();
        if (e - e.round()).abs() < 1e-6 {
            format!("1e{}", e.round() as i32)
        } else {
            format!("{v:.1e}")
        }
    } else if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.2e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-" {
            "0".into()
        } else {
            s.to_string()
        }
    }
}

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

/// Draw `series` (and `markers`) into a PNG at `path` (800 x 500 px).
pub fn plot(path: &Path, axes: &Axes<'_>, series: &[Series<'_>], markers: &[Marker]) -> Result<()> {
    register_font();
    let (mut x0, mut x1) = range(series.iter().flat_map(|s| s.x.iter().copied()), axes.log_x);
    let (mut y0, mut y1) = range(series.iter().flat_map(|s| s.y.iter().copied()), axes.log_y);
    if axes.equal {
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let half = 0.5 * (x1 - x0).max(y1 - y0) * 1.6;
        (x0, x1, y0, y1) = (
            cx - half,
            cx + half,
            cy - 0.625 * half * 1.0,
            cy + 0.625 * half,
        );
        let _ = (&mut y0, &mut y1);
    }
    let root = BitMapBackend::new(path, (800, 500)).into_drawing_area();
    root.fill(&WHITE).map_err(io)?;
    let mut b = ChartBuilder::on(&root);
    b.caption(axes.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart;
            // A tick within round-off of zero (a grid computed across it) reads 0.
            let fx = |v: &f64| {
                tick(
                    if v.abs() < 1e-9 * (x1 - x0) { 0.0 } else { *v },
                    axes.log_x,
                )
            };
            let fy = |v: &f64| {
                tick(
                    if v.abs() < 1e-9 * (y1 - y0) { 0.0 } else { *v },
                    axes.log_y,
                )
            };
            chart
                .configure_mesh()
                .x_desc(axes.x_label)
                .y_desc(axes.y_label)
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .label_style(("sans-serif", 13))
                .draw()
                .map_err(io)?;
            for m in markers {
                if m.x >= x0 && m.x <= x1 {
                    let c = RGBColor(150, 150, 150);
                    chart
                        .draw_series(LineSeries::new(
                            vec![(m.x, y0), (m.x, y1)],
                            c.stroke_width(1),
                        ))
                        .map_err(io)?;
                    chart
                        .draw_series(std::iter::once(Text::new(
                            m.label.clone(),
                            (m.x, y1),
                            ("sans-serif", 12).into_font(),
                        )))
                        .map_err(io)?;
                }
            }
            for (i, s) in series.iter().enumerate() {
                let c = COLORS[i % COLORS.len()];
                let pts: Vec<(f64, f64)> =
                    s.x.iter()
                        .zip(s.y)
                        .map(|(&x, &y)| (x, y))
                        .filter(|(x, y)| {
                            x.is_finite()
                                && y.is_finite()
                                && (!axes.log_x || *x > 0.0)
                                && (!axes.log_y || *y > 0.0)
                        })
                        .collect();
                let anno = if s.points {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                        .map_err(io)?
                } else {
                    chart
                        .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                        .map_err(io)?
                };
                if !s.label.is_empty() {
                    anno.label(s.label).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                    });
                }
            }
            if series.iter().any(|s| !s.label.is_empty()) {
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK)
                    .label_font(("sans-serif", 13))
                    .draw()
                    .map_err(io)?;
            }
        }};
    }
    match (axes.log_x, axes.log_y) {
        (false, false) => draw!(b.build_cartesian_2d(x0..x1, y0..y1).map_err(io)?),
        (true, false) => draw!(b
            .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
            .map_err(io)?),
        (false, true) => draw!(b
            .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
            .map_err(io)?),
        (true, true) => draw!(b
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(io)?),
    }
    root.present().map_err(io)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_of_the_data() {
        let dir = std::env::temp_dir().join(format!("raceway-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let x: Vec<f64> = (0..200).map(|i| i as f64 * 0.01).collect();
        let y: Vec<f64> = x.iter().map(|t| (10.0 * t).sin()).collect();
        let p = dir.join("sine.png");
        let axes = Axes {
            title: "sine",
            x_label: "t (s)",
            y_label: "y",
            ..Axes::default()
        };
        plot(
            &p,
            &axes,
            &[Series {
                label: "sin",
                x: &x,
                y: &y,
                points: false,
            }],
            &[Marker {
                x: 1.0,
                label: "1 s".into(),
            }],
        )
        .unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(
            bytes.len() > 5000,
            "a drawn plot, not an empty image: {} bytes",
            bytes.len()
        );
        let p2 = dir.join("loglog.png");
        let axes = Axes {
            log_x: true,
            log_y: true,
            ..axes
        };
        plot(
            &p2,
            &axes,
            &[Series {
                label: "",
                x: &x[1..],
                y: &x[1..],
                points: true,
            }],
            &[],
        )
        .unwrap();
        assert!(std::fs::metadata(&p2).unwrap().len() > 2000);
    }
}
