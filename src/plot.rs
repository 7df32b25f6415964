//! PNG and SVG plots for reports and the command line (feature `plot`): line plots with optional
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

/// Tick label of an axis spanning `span`: on a linear axis, rounding noise near zero
/// (below 1e-9 of the span) reads 0; on a log axis a small value is a decade, not noise.
/// Ticks on a narrow span far from zero (-300 N varying by 1e-4 N) carry the decimals that
/// tell them apart: one more than the tenth of the span needs.
fn axis_tick(v: f64, span: f64, log: bool) -> String {
    let v = if !log && v.abs() < 1e-9 * span {
        0.0
    } else {
        v
    };
    if log || v == 0.0 || !(span > 0.0 && span.is_finite()) {
        return tick(v, log);
    }
    let decimals = (1.0 - (0.1 * span).log10().floor()).clamp(0.0, 12.0) as usize;
    if decimals <= 4 || v.abs() < 1e-3 || v.abs() >= 1e5 {
        return tick(v, log);
    }
    let s = format!("{v:.decimals$}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Tick label: powers of ten on log axes (`1e-6`), plain short numbers otherwise.
fn tick(v: f64, log: bool) -> String {
    if log {
        // A log axis has no tick at or below zero (plotters may still ask for one at its
        // lower end): none drawn rather than a misleading "0.0e0".
        if !(v > 0.0 && v.is_finite()) {
            return String::new();
        }
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

/// The series colours, by position (cycling after the last).
const COLORS: [RGBColor; N_COLORS] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
];

/// Number of distinct series colours.
pub const N_COLORS: usize = 8;

/// A rectangle in pixels (x to the right, y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Left.
    pub x0: f64,
    /// Top.
    pub y0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y1: f64,
}

impl Rect {
    /// Whether `p` lies inside (edges included).
    pub fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }

    /// Whether the segment `a`–`b` meets the rectangle (Liang–Barsky clipping: Liang &
    /// Barsky, *ACM Trans. Graphics* 3 (1984)).
    pub fn meets_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// Data of one series in pixels, for the legend placement: the points, whether they are
/// joined by a line, and the radius of a drawn point.
#[derive(Debug, Clone)]
pub struct Drawn {
    /// Points, pixels.
    pub points: Vec<(f64, f64)>,
    /// Joined by line segments.
    pub line: bool,
    /// Half size of a point marker, pixels (0 for a line).
    pub radius: f64,
}

/// Where a legend of `size` (pixels) goes inside `area`: the first of the corners upper
/// right, upper left, lower right, lower left (`pad` pixels in) where the box, grown by a
/// point's radius, holds no data point and crosses no line segment; `None` when every
/// corner is taken (then the caller adds headroom above the data).
pub fn legend_place(area: Rect, size: (f64, f64), pad: f64, data: &[Drawn]) -> Option<Rect> {
    let (w, h) = size;
    let corners = [
        (area.x1 - pad - w, area.y0 + pad),
        (area.x0 + pad, area.y0 + pad),
        (area.x1 - pad - w, area.y1 - pad - h),
        (area.x0 + pad, area.y1 - pad - h),
    ];
    corners.into_iter().find_map(|(x, y)| {
        let b = Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        };
        if b.x0 < area.x0 || b.y0 < area.y0 || b.x1 > area.x1 || b.y1 > area.y1 {
            return None;
        }
        let free = data.iter().all(|d| {
            let g = Rect {
                x0: b.x0 - d.radius - 1.0,
                y0: b.y0 - d.radius - 1.0,
                x1: b.x1 + d.radius + 1.0,
                y1: b.y1 + d.radius + 1.0,
            };
            let point_in = d.points.iter().any(|p| g.contains(*p));
            let line_through = d.line && d.points.windows(2).any(|s| g.meets_segment(s[0], s[1]));
            !(point_in || line_through)
        });
        free.then_some(b)
    })
}

/// Rows for marker labels so that no two labels on a row overlap: `spans` are (centre,
/// width) in pixels; each label takes the lowest row where it clears the labels already
/// there by `gap` pixels (greedy in order of position). Returns the row of each label.
pub fn label_rows(spans: &[(f64, f64)], gap: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..spans.len()).collect();
    order.sort_by(|&a, &b| spans[a].0.total_cmp(&spans[b].0));
    let mut right_end: Vec<f64> = Vec::new();
    let mut rows = vec![0; spans.len()];
    for i in order {
        let (c, w) = spans[i];
        let left = c - 0.5 * w;
        let r = match right_end.iter().position(|&e| left >= e + gap) {
            Some(r) => r,
            None => {
                right_end.push(f64::NEG_INFINITY);
                right_end.len() - 1
            }
        };
        right_end[r] = c + 0.5 * w;
        rows[i] = r;
    }
    rows
}

/// Height of one row of marker labels above the plot, pixels.
const LABEL_ROW: i32 = 15;

/// Draw `series` (and `markers`) into a PNG at `path` (1000 x 625 px). Point series are
/// drawn with distinct shapes (filled circle, cross, hollow triangle, ...); the legend goes
/// into a corner free of data (with headroom added above the data when none is); marker
/// labels are stacked in rows above the plot so that none overlaps another.
pub fn plot(path: &Path, axes: &Axes<'_>, series: &[Series<'_>], markers: &[Marker]) -> Result<()> {
    plot_dpi(path, DEFAULT_DPI, axes, series, markers)
}

/// The resolution of a PNG: [`plot`] and [`plot_stack`] are drawn at this many dots per
/// inch (a plot is 10 in wide: 1000 px at 100 dpi).
pub const DEFAULT_DPI: u32 = 100;

/// The resolutions a PNG can be drawn at, dots per inch (a 400 dpi plot is 4000 px wide).
pub const DPI_RANGE: std::ops::RangeInclusive<u32> = 50..=400;

/// The scale of every length of a drawing (pixel sizes, fonts, line widths) at `dpi`.
fn dpi_scale(dpi: u32) -> Result<f64> {
    if !DPI_RANGE.contains(&dpi) {
        return Err(Error::invalid(
            "dpi",
            dpi,
            format!("{} to {}", DPI_RANGE.start(), DPI_RANGE.end()),
        ));
    }
    Ok(dpi as f64 / DEFAULT_DPI as f64)
}

/// `(w, h)` pixels times `s`, rounded.
fn scaled(px: (u32, u32), s: f64) -> (u32, u32) {
    (
        (px.0 as f64 * s).round() as u32,
        (px.1 as f64 * s).round() as u32,
    )
}

/// [`plot`] at `dpi` dots per inch (in [`DPI_RANGE`]): the same drawing, every length
/// (size, fonts, lines, markers) scaled by `dpi / 100`.
pub fn plot_dpi(
    path: &Path,
    dpi: u32,
    axes: &Axes<'_>,
    series: &[Series<'_>],
    markers: &[Marker],
) -> Result<()> {
    png(path, dpi, PLOT_PX, |root, s| {
        draw_area(root, s, axes, series, markers)
    })
}

/// A drawing of `px` pixels at 100 dpi into a PNG at `path` at `dpi` (in [`DPI_RANGE`]):
/// `draw(root, s)` draws every length times `s = dpi / 100`. Under a temporary name, then
/// renamed: never half-written.
fn png(
    path: &Path,
    dpi: u32,
    px: (u32, u32),
    draw: impl FnOnce(&Area<BitMapBackend<'_>>, f64) -> Result<()>,
) -> Result<()> {
    let s = dpi_scale(dpi)?;
    register_font();
    crate::fsutil::write_atomic_with(path, |tmp| {
        let root = BitMapBackend::new(tmp, scaled(px, s)).into_drawing_area();
        draw(&root, s)?;
        root.present().map_err(io)
    })
}

/// A drawing of `px` pixels as SVG text (`draw(root)` at scale 1).
fn svg(px: (u32, u32), draw: impl FnOnce(&Area<SVGBackend<'_>>) -> Result<()>) -> Result<String> {
    register_font();
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, px).into_drawing_area();
        draw(&root)?;
        root.present().map_err(io)?;
    }
    Ok(buf)
}

/// `svg` beside the PNG at `path` (`path` with the extension `svg`).
fn svg_beside(path: &Path, svg: String) -> Result<()> {
    crate::fsutil::write_atomic(&path.with_extension("svg"), svg).map_err(io)
}

/// Size of a [`plot`], pixels.
const PLOT_PX: (u32, u32) = (1000, 625);

/// The drawing of [`plot`] as SVG text (text as `<text>` elements in the reader's
/// sans-serif font).
pub fn plot_svg(axes: &Axes<'_>, series: &[Series<'_>], markers: &[Marker]) -> Result<String> {
    svg(PLOT_PX, |root| draw_area(root, 1.0, axes, series, markers))
}

/// [`plot`] into the PNG at `path` and [`plot_svg`] beside it (`path` with the extension
/// `svg`).
pub fn plot_pair(
    path: &Path,
    axes: &Axes<'_>,
    series: &[Series<'_>],
    markers: &[Marker],
) -> Result<()> {
    plot_pair_dpi(path, DEFAULT_DPI, axes, series, markers)
}

/// [`plot_pair`] with the PNG at `dpi` (see [`plot_dpi`]); the SVG is the same at any dpi.
pub fn plot_pair_dpi(
    path: &Path,
    dpi: u32,
    axes: &Axes<'_>,
    series: &[Series<'_>],
    markers: &[Marker],
) -> Result<()> {
    plot_dpi(path, dpi, axes, series, markers)?;
    svg_beside(path, plot_svg(axes, series, markers)?)
}

/// Panels stacked vertically in one PNG (1000 x 300 px per panel) under one `title`, each
/// with its own y axis (e.g. Fx, Fy, Fz, so that each ripple shows at its own scale).
pub fn plot_stack(path: &Path, title: &str, panels: &[(Axes<'_>, Vec<Series<'_>>)]) -> Result<()> {
    plot_stack_dpi(path, DEFAULT_DPI, title, panels)
}

/// [`plot_stack`] at `dpi` dots per inch (see [`plot_dpi`]).
pub fn plot_stack_dpi(
    path: &Path,
    dpi: u32,
    title: &str,
    panels: &[(Axes<'_>, Vec<Series<'_>>)],
) -> Result<()> {
    png(path, dpi, stack_px(panels.len()), |root, s| {
        draw_stack(root, s, title, panels)
    })
}

/// Size of a [`plot_stack`] of `n` panels, pixels.
fn stack_px(n: usize) -> (u32, u32) {
    (1000, 44 + 300 * n.max(1) as u32)
}

/// The drawing of [`plot_stack`] as SVG text.
pub fn stack_svg(title: &str, panels: &[(Axes<'_>, Vec<Series<'_>>)]) -> Result<String> {
    svg(stack_px(panels.len()), |root| {
        draw_stack(root, 1.0, title, panels)
    })
}

/// [`plot_stack`] into the PNG at `path` and [`stack_svg`] beside it.
pub fn stack_pair(path: &Path, title: &str, panels: &[(Axes<'_>, Vec<Series<'_>>)]) -> Result<()> {
    stack_pair_dpi(path, DEFAULT_DPI, title, panels)
}

/// [`stack_pair`] with the PNG at `dpi` (see [`plot_dpi`]).
pub fn stack_pair_dpi(
    path: &Path,
    dpi: u32,
    title: &str,
    panels: &[(Axes<'_>, Vec<Series<'_>>)],
) -> Result<()> {
    plot_stack_dpi(path, dpi, title, panels)?;
    svg_beside(path, stack_svg(title, panels)?)
}

/// A title in lines that fit the width of `area` (40 px to spare: the size estimate runs
/// a few per cent short): one line at 20 px (times `s`), or smaller down to 14 px; longer,
/// two lines, split after the scene's part (`"name (title):"`, else at the space nearest
/// the middle), each fitted alike down to 11 px. Returns the lines and the font size.
fn title_lines<DB: DrawingBackend>(area: &Area<DB>, title: &str, s: f64) -> (Vec<String>, f64) {
    let w = area.dim_in_pixel().0 as f64 - 40.0 * s;
    let width = |t: &str| {
        area.estimate_text_size(t, &("sans-serif", 20.0 * s).into())
            .map(|(w, _)| w as f64)
            .unwrap_or(0.0)
    };
    let fit = |t: &str| 20.0 * s * (w / width(t).max(1.0)).min(1.0);
    let one = fit(title);
    if one >= 14.0 * s {
        return (vec![title.to_string()], one);
    }
    let mid = title.len() / 2;
    let cut = title.find("): ").map(|i| i + 2).or_else(|| {
        title
            .char_indices()
            .filter(|(_, c)| *c == ' ')
            .map(|(i, _)| i)
            .min_by_key(|i| i.abs_diff(mid))
    });
    let Some(cut) = cut else {
        return (vec![title.to_string()], one.max(11.0 * s));
    };
    let (a, b) = title.split_at(cut);
    let (a, b) = (a.trim_end(), b.trim_start());
    let size = fit(a).min(fit(b)).clamp(11.0 * s, 14.4 * s);
    (vec![a.to_string(), b.to_string()], size)
}

/// Draw `lines` centred in the top of `area` from `top` px down; returns the height used.
fn draw_title<DB: DrawingBackend>(
    area: &Area<DB>,
    lines: &[String],
    size: f64,
    top: f64,
) -> Result<f64> {
    let w = area.dim_in_pixel().0 as i32;
    let style: TextStyle<'_> = ("sans-serif", size).into();
    for (k, l) in lines.iter().enumerate() {
        let tw = area
            .estimate_text_size(l, &style)
            .map(|(w, _)| w as i32)
            .unwrap_or(0);
        let y = top + k as f64 * 1.25 * size;
        area.draw(&Text::new(
            l.as_str(),
            ((w - tw) / 2, y as i32),
            style.clone(),
        ))
        .map_err(io)?;
    }
    Ok(lines.len() as f64 * 1.25 * size)
}

fn draw_stack<DB: DrawingBackend>(
    root: &Area<DB>,
    s: f64,
    title: &str,
    panels: &[(Axes<'_>, Vec<Series<'_>>)],
) -> Result<()> {
    root.fill(&WHITE).map_err(io)?;
    // 20 px, smaller (or two lines) when a long title (scene, bearing, operating point,
    // window) would not fit the width; the panels below the 44 px it has.
    let (lines, size) = title_lines(root, title, s);
    draw_title(root, &lines, size, 6.0 * s)?;
    let (_, body) = root.split_vertically((44.0 * s) as i32);
    for (area, (axes, series)) in body
        .split_evenly((panels.len().max(1), 1))
        .iter()
        .zip(panels)
    {
        draw_area(area, s, axes, series, &[])?;
    }
    Ok(())
}

type Area<DB> = DrawingArea<DB, plotters::coord::Shift>;

/// Shape of the `k`-th point series.
fn draw_point<DB: DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    s: f64,
    k: usize,
    p: CT::From,
    c: RGBColor,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    CT::From: Clone,
{
    let (px, w) = (|v: f64| (v * s).round() as i32, lw(2, s));
    match k % 3 {
        0 => area.draw(&Circle::new(p, px(4.0), c.filled())),
        1 => area.draw(&Cross::new(p, px(6.0), c.stroke_width(w))),
        _ => area.draw(&TriangleMarker::new(p, px(7.0), c.stroke_width(w))),
    }
}

/// A line `w` px wide at 100 dpi, at scale `s` (at least 1 px).
fn lw(w: u32, s: f64) -> u32 {
    ((w as f64 * s).round() as u32).max(1)
}

fn draw_area<DB: DrawingBackend>(
    area: &Area<DB>,
    s: f64,
    axes: &Axes<'_>,
    series: &[Series<'_>],
    markers: &[Marker],
) -> Result<()> {
    let (x0, x1) = range(series.iter().flat_map(|s| s.x.iter().copied()), axes.log_x);
    let (mut y0, mut y1) = range(series.iter().flat_map(|s| s.y.iter().copied()), axes.log_y);
    let (mut x0, mut x1) = (x0, x1);
    if axes.equal {
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let half = 0.5 * (x1 - x0).max(y1 - y0) * 1.6;
        (x0, x1, y0, y1) = (cx - half, cx + half, cy - 0.625 * half, cy + 0.625 * half);
    }
    let font: TextStyle<'_> = ("sans-serif", 16.0 * s).into();
    let label_font: TextStyle<'_> = ("sans-serif", 14.0 * s).into();
    // Pixel lengths at 100 dpi, scaled.
    let px = |v: f64| v * s;
    let ipx = |v: f64| (v * s).round() as i32;
    let label_row = ipx(LABEL_ROW as f64);
    // The shape of each point series: its rank among the point series.
    let shape: Vec<usize> = series
        .iter()
        .scan(0, |k, s| {
            let r = *k;
            *k += usize::from(s.points);
            Some(r)
        })
        .collect();
    let labelled: Vec<(usize, usize, &Series<'_>)> = series
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.label.is_empty())
        .map(|(i, s)| (i, shape[i], s))
        .collect();
    // Legend box: a sample 24 px wide, the text, 6 px padding, 18 px per entry.
    let text_w = labelled
        .iter()
        .map(|(_, _, s)| {
            area.estimate_text_size(s.label, &font)
                .map(|(w, _)| w)
                .unwrap_or(0)
        })
        .max()
        .unwrap_or(0) as f64;
    let legend_size = (
        px(24.0 + 8.0 + 12.0) + text_w,
        px(18.0 * labelled.len() as f64 + 8.0),
    );
    // A legend taller than 45 % of the picture cannot find a free corner without squeezing
    // the data into a sliver (on a log axis the headroom spans decades): it goes beside the
    // plot instead, in a column of its own, and the data keep the rest of the width.
    let (w_px, h_px) = area.dim_in_pixel();
    if !labelled.is_empty()
        && legend_size.1 > 0.45 * h_px as f64
        && legend_size.0 < 0.4 * w_px as f64
    {
        let split = w_px as i32 - legend_size.0 as i32 - ipx(16.0);
        let (left, right) = area.split_horizontally(split);
        right.fill(&WHITE).map_err(io)?;
        let unlabelled: Vec<Series<'_>> =
            series.iter().map(|s| Series { label: "", ..*s }).collect();
        draw_area(&left, s, axes, &unlabelled, markers)?;
        let top = px(if axes.title.is_empty() { 12.0 } else { 42.0 });
        let r = Rect {
            x0: px(4.0),
            y0: top,
            x1: px(4.0) + legend_size.0,
            y1: top + legend_size.1,
        };
        return draw_legend(&right, s, r, &labelled, &font);
    }
    let visible: Vec<&Marker> = markers.iter().filter(|m| m.x >= x0 && m.x <= x1).collect();
    let mut rows_reserved = 0usize;
    let mut headroom = 0.0f64;
    for pass in 0..3 {
        area.fill(&WHITE).map_err(io)?;
        // Headroom: the data keep the lower (1 - headroom) of the height.
        let y1h = if axes.log_y {
            y0 * (y1 / y0).powf(1.0 / (1.0 - headroom))
        } else {
            y0 + (y1 - y0) / (1.0 - headroom)
        };
        // The title drawn here (not as the chart's caption) so that the rows of marker
        // labels go between it and the plot.
        // 20 px, smaller (or two lines) when a long title (scene, bearing, operating
        // point) would not fit the width.
        let title_h = if axes.title.is_empty() {
            0
        } else {
            let (lines, size) = title_lines(area, axes.title, s);
            let used = draw_title(area, &lines, size, px(8.0))?;
            ipx(30.0).max((used + px(6.0)) as i32)
        };
        // Room for the widest y tick label (many decimals on a narrow span far from 0,
        // "-300.000015") beside the axis description.
        let tick_w = [y0, 0.5 * (y0 + y1h), y1h]
            .iter()
            .map(|&v| {
                area.estimate_text_size(
                    &axis_tick(v, y1h - y0, axes.log_y),
                    &("sans-serif", px(16.0)).into(),
                )
                .map(|(w, _)| w as i32)
                .unwrap_or(0)
            })
            .max()
            .unwrap_or(0);
        let mut b = ChartBuilder::on(area);
        b.margin(ipx(12.0))
            .margin_top(ipx(12.0) + title_h + label_row * rows_reserved as i32)
            .x_label_area_size(ipx(48.0))
            .y_label_area_size(ipx(86.0).max(tick_w + ipx(36.0)));
        let base = area.get_base_pixel();
        let rel = |p: (i32, i32)| ((p.0 - base.0) as f64, (p.1 - base.1) as f64);
        // What the pass found: the legend's place (if any labels) and the label rows.
        let mut legend: Option<Option<Rect>> = None;
        let rows: Vec<usize>;
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                let fx = |v: &f64| axis_tick(*v, x1 - x0, axes.log_x);
                let fy = |v: &f64| axis_tick(*v, y1h - y0, axes.log_y);
                chart
                    .configure_mesh()
                    .x_desc(axes.x_label)
                    .y_desc(axes.y_label)
                    .x_label_formatter(&fx)
                    .y_label_formatter(&fy)
                    .label_style(("sans-serif", px(16.0)))
                    .axis_desc_style(("sans-serif", px(17.0)))
                    .draw()
                    .map_err(io)?;
                let (xr, yr) = chart.plotting_area().get_pixel_range();
                let top = (yr.start - base.1) as f64;
                let spans: Vec<(f64, f64)> = visible
                    .iter()
                    .map(|m| {
                        let w = area
                            .estimate_text_size(&m.label, &label_font)
                            .map(|(w, _)| w)
                            .unwrap_or(0);
                        (rel(chart.backend_coord(&(m.x, y1h))).0, w as f64)
                    })
                    .collect();
                rows = label_rows(&spans, px(4.0));
                for (m, (sp, r)) in visible.iter().zip(spans.iter().zip(&rows)) {
                    chart
                        .draw_series(LineSeries::new(
                            vec![(m.x, y0), (m.x, y1h)],
                            RGBColor(150, 150, 150).stroke_width(lw(1, s)),
                        ))
                        .map_err(io)?;
                    let y = top - (*r as f64 + 1.0) * label_row as f64 + px(2.0);
                    area.draw(&Text::new(
                        m.label.clone(),
                        ((sp.0 - 0.5 * sp.1) as i32, y as i32),
                        label_font.clone(),
                    ))
                    .map_err(io)?;
                }
                let mut drawn = Vec::new();
                for (i, ser) in series.iter().enumerate() {
                    let c = COLORS[i % COLORS.len()];
                    let pts: Vec<(f64, f64)> = ser
                        .x
                        .iter()
                        .zip(ser.y)
                        .map(|(&x, &y)| (x, y))
                        .filter(|(x, y)| {
                            x.is_finite()
                                && y.is_finite()
                                && (!axes.log_x || *x > 0.0)
                                && (!axes.log_y || *y > 0.0)
                        })
                        .collect();
                    // Long histories: one column of pixels draws the same with its
                    // first, lowest, highest and last point (keeps the SVG small).
                    let pts = if ser.points {
                        pts
                    } else {
                        thin(pts, |p| chart.backend_coord(p))
                    };
                    if ser.points {
                        for p in &pts {
                            draw_point(chart.plotting_area(), s, shape[i], *p, c).map_err(io)?;
                        }
                    } else {
                        // Thick polylines get mitred spikes at sharp reversals (plotters
                        // joins segments with mitres): dense data is drawn 1 px wide.
                        let w = lw(if pts.len() > 500 { 1 } else { 2 }, s);
                        chart
                            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(w)))
                            .map_err(io)?;
                    }
                    drawn.push(Drawn {
                        points: pts.iter().map(|p| rel(chart.backend_coord(p))).collect(),
                        line: !ser.points,
                        radius: px(if ser.points { 7.0 } else { 1.0 }),
                    });
                }
                if !labelled.is_empty() {
                    let plot_rect = Rect {
                        x0: (xr.start - base.0) as f64,
                        y0: top,
                        x1: (xr.end - base.0) as f64,
                        y1: (yr.end - base.1) as f64,
                    };
                    legend = Some(legend_place(plot_rect, legend_size, px(8.0), &drawn));
                }
            }};
        }
        match (axes.log_x, axes.log_y) {
            (false, false) => draw!(b.build_cartesian_2d(x0..x1, y0..y1h).map_err(io)?),
            (true, false) => draw!(b
                .build_cartesian_2d((x0..x1).log_scale(), y0..y1h)
                .map_err(io)?),
            (false, true) => draw!(b
                .build_cartesian_2d(x0..x1, (y0..y1h).log_scale())
                .map_err(io)?),
            (true, true) => draw!(b
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1h).log_scale())
                .map_err(io)?),
        }
        let rows_needed = rows.iter().map(|r| r + 1).max().unwrap_or(0);
        let legend_ok = !matches!(legend, Some(None));
        if (rows_needed > rows_reserved || !legend_ok) && pass < 2 {
            rows_reserved = rows_reserved.max(rows_needed);
            if !legend_ok {
                // Room for the box and its padding above the data.
                let h = area.dim_in_pixel().1 as f64
                    - px(52.0)
                    - (label_row as usize * rows_reserved) as f64
                    - px(40.0);
                headroom = ((legend_size.1 + px(24.0)) / h.max(1.0)).clamp(0.0, 0.6);
            }
            continue;
        }
        if let Some(Some(r)) = legend {
            draw_legend(area, s, r, &labelled, &font)?;
        }
        return Ok(());
    }
    Ok(())
}

/// The points of a polyline that draw the same picture at the pixel grid: of each run of
/// consecutive points in one pixel column, the first, the lowest, the highest and the last,
/// in their order (the segments between them cover the same pixels).
fn thin(pts: Vec<(f64, f64)>, px: impl Fn(&(f64, f64)) -> (i32, i32)) -> Vec<(f64, f64)> {
    if pts.len() < 4000 {
        return pts;
    }
    let mut out = Vec::with_capacity(4 * 1000);
    let mut i = 0;
    while i < pts.len() {
        let col = px(&pts[i]).0;
        let mut j = i + 1;
        let (mut lo, mut hi) = (i, i);
        while j < pts.len() && px(&pts[j]).0 == col {
            if pts[j].1 < pts[lo].1 {
                lo = j;
            }
            if pts[j].1 > pts[hi].1 {
                hi = j;
            }
            j += 1;
        }
        let mut keep = [i, lo, hi, j - 1];
        keep.sort_unstable();
        let mut last = usize::MAX;
        for k in keep {
            if k != last {
                out.push(pts[k]);
                last = k;
            }
        }
        i = j;
    }
    out
}

/// The legend box at `r` (pixels relative to `area`): a line or the point shape of each
/// labelled series, then its label.
fn draw_legend<DB: DrawingBackend>(
    area: &Area<DB>,
    s: f64,
    r: Rect,
    labelled: &[(usize, usize, &Series<'_>)],
    font: &TextStyle<'_>,
) -> Result<()> {
    let ipx = |v: f64| (v * s).round() as i32;
    let (x0, y0) = (r.x0 as i32, r.y0 as i32);
    area.draw(&Rectangle::new(
        [(x0, y0), (r.x1 as i32, r.y1 as i32)],
        WHITE.filled(),
    ))
    .map_err(io)?;
    area.draw(&Rectangle::new(
        [(x0, y0), (r.x1 as i32, r.y1 as i32)],
        BLACK.stroke_width(lw(1, s)),
    ))
    .map_err(io)?;
    for (row, (i, k, ser)) in labelled.iter().enumerate() {
        let c = COLORS[i % COLORS.len()];
        let y = y0 + ipx(4.0 + 18.0 * row as f64 + 9.0);
        if ser.points {
            draw_point(area, s, *k, (x0 + ipx(18.0), y), c).map_err(io)?;
        } else {
            area.draw(&PathElement::new(
                vec![(x0 + ipx(6.0), y), (x0 + ipx(30.0), y)],
                c.stroke_width(lw(2, s)),
            ))
            .map_err(io)?;
        }
        area.draw(&Text::new(
            ser.label.to_string(),
            (x0 + ipx(38.0), y - ipx(7.0)),
            font.clone(),
        ))
        .map_err(io)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A title too long for one line at 14 px on a 1000 px figure (the scene, its title
    /// and a spectrum's description with a speed sweep: 220 characters) is drawn in two
    /// lines split after the scene's part, each within the width at the size chosen; a
    /// short one stays one line at 20 px.
    #[test]
    fn long_titles_wrap_after_the_scene() {
        register_font();
        let mut buf = vec![0u8; 1000 * 100 * 3];
        let root = BitMapBackend::with_buffer(&mut buf, (1000, 100)).into_drawing_area();
        let long = "7004-startup (7004 start-up from rest to 30 000 rpm in 50 ms, Fa 2000 N, \
                    Fr 400 N, full dynamics): spectrum of force.y, t >= 0.025 s (Hann, bins \
                    39.84 Hz; shaft 14940 to 29940 rpm over it, marks at the final speed)";
        let (lines, size) = title_lines(&root, long, 1.0);
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(lines[0].ends_with("dynamics):") && lines[1].starts_with("spectrum"));
        assert!((11.0..=14.4).contains(&size), "{size}");
        for l in &lines {
            let (w, _) = root
                .estimate_text_size(l, &("sans-serif", size).into())
                .unwrap();
            assert!(w <= 960, "{l}: {w} px");
        }
        let (short, size) = title_lines(&root, "sine: amplitude", 1.0);
        assert_eq!((short.len(), size), (1, 20.0));
    }

    /// A decade far below a log axis's top keeps its label (it read "0.0e0" when snapped
    /// as rounding noise: 1e-7 on an axis up to 300), while a linear axis's noise near 0
    /// still reads 0; a log axis labels nothing at or below zero.
    #[test]
    fn log_ticks_are_decades_not_noise() {
        assert_eq!(axis_tick(1e-7, 300.0, true), "1e-7");
        assert_eq!(axis_tick(3e-9, 300.0, true), "3.0e-9");
        assert_eq!(axis_tick(1e-12, 1.0, false), "0");
        assert_eq!(axis_tick(0.0, 1.0, true), "");
        // Ticks 2e-5 apart on -300 N read apart; plain axes as before.
        assert_eq!(axis_tick(-300.00002, 1e-4, false), "-300.00002");
        assert_ne!(
            axis_tick(-300.00002, 1e-4, false),
            axis_tick(-300.00004, 1e-4, false)
        );
        assert_eq!(axis_tick(0.05, 0.2, false), "0.05");
        assert_eq!(axis_tick(4450.8, 2.0, false), "4450.8");
    }

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The legend never covers data: over 300 random data sets (points and polylines) in
    /// a 700 x 400 px area, a placed box holds no point (nor one within its marker radius)
    /// and no segment passes through it, checked independently by sampling each segment
    /// every 0.25 px; a plot whose four corners are all taken gets `None` (headroom).
    #[test]
    fn the_legend_never_covers_a_data_point() {
        let area = Rect {
            x0: 80.0,
            y0: 50.0,
            x1: 780.0,
            y1: 450.0,
        };
        let size = (150.0, 44.0);
        let mut seed = 1u64;
        let mut placed = 0;
        for case in 0..300 {
            let n = 2 + (lcg(&mut seed) * 12.0) as usize;
            let line = case % 2 == 0;
            let data = vec![Drawn {
                points: (0..n)
                    .map(|_| {
                        (
                            area.x0 + lcg(&mut seed) * (area.x1 - area.x0),
                            area.y0 + lcg(&mut seed) * (area.y1 - area.y0),
                        )
                    })
                    .collect(),
                line,
                radius: if line { 1.0 } else { 7.0 },
            }];
            let Some(r) = legend_place(area, size, 8.0, &data) else {
                continue;
            };
            placed += 1;
            assert!(r.x0 >= area.x0 && r.x1 <= area.x1 && r.y0 >= area.y0 && r.y1 <= area.y1);
            let d = &data[0];
            let grown = Rect {
                x0: r.x0 - d.radius,
                y0: r.y0 - d.radius,
                x1: r.x1 + d.radius,
                y1: r.y1 + d.radius,
            };
            for p in &d.points {
                assert!(!grown.contains(*p), "case {case}: point {p:?} under {r:?}");
            }
            if line {
                for s in d.points.windows(2) {
                    let len = (s[1].0 - s[0].0).hypot(s[1].1 - s[0].1);
                    let k = (len / 0.25).ceil() as usize;
                    for j in 0..=k {
                        let t = j as f64 / k as f64;
                        let p = (
                            s[0].0 + t * (s[1].0 - s[0].0),
                            s[0].1 + t * (s[1].1 - s[0].1),
                        );
                        assert!(
                            !r.contains(p),
                            "case {case}: segment through {r:?} at {p:?}"
                        );
                    }
                }
            }
        }
        assert!(
            placed > 50,
            "only {placed} placements: the test checks too little"
        );
        // Every corner taken: no place.
        let corners = vec![Drawn {
            points: vec![(100.0, 70.0), (760.0, 70.0), (100.0, 430.0), (760.0, 430.0)],
            line: false,
            radius: 7.0,
        }];
        assert_eq!(legend_place(area, size, 8.0, &corners), None);
        // Only the upper right taken (the default scene's loaded balls): the upper left.
        let ur = vec![Drawn {
            points: vec![(700.0, 60.0), (600.0, 200.0)],
            line: false,
            radius: 7.0,
        }];
        let r = legend_place(area, size, 8.0, &ur).unwrap();
        assert_eq!((r.x0, r.y0), (88.0, 58.0));
    }

    /// Marker labels on one row never overlap (nor come closer than the gap), and a label
    /// goes up a row only when the rows below are taken where it stands.
    #[test]
    fn marker_labels_never_overlap() {
        let mut seed = 5u64;
        for _ in 0..200 {
            let n = 1 + (lcg(&mut seed) * 15.0) as usize;
            let spans: Vec<(f64, f64)> = (0..n)
                .map(|_| (lcg(&mut seed) * 700.0, 20.0 + lcg(&mut seed) * 40.0))
                .collect();
            let rows = label_rows(&spans, 4.0);
            let clash =
                |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 0.5 * (a.1 + b.1) + 4.0 - 1e-9;
            for i in 0..n {
                for j in 0..n {
                    if i != j && rows[i] == rows[j] {
                        assert!(!clash(spans[i], spans[j]), "{:?} {:?}", spans[i], spans[j]);
                    }
                }
                for r in 0..rows[i] {
                    assert!(
                        (0..n).any(|j| j != i && rows[j] == r && clash(spans[i], spans[j])),
                        "label {i} raised to row {} with row {r} free",
                        rows[i]
                    );
                }
            }
        }
        // The overlaps of the old spectrum plot ("FTFfs", "2BSFBPFI"): FTF 11.6 Hz and fs
        // 29.2 Hz, 2BSF 137 Hz and BPFI 158 Hz, at about 1 px per Hz.
        let rows = label_rows(
            &[(11.6, 24.0), (29.2, 14.0), (137.0, 30.0), (158.0, 30.0)],
            4.0,
        );
        assert_ne!(rows[0], rows[1]);
        assert_ne!(rows[2], rows[3]);
    }

    #[test]
    fn thinning_keeps_each_pixel_columns_extremes_and_ends() {
        // 100 000 points of a fast sine over 1000 columns: every column keeps its first,
        // lowest, highest and last point, so the drawn band is unchanged.
        let n = 100_000;
        let pts: Vec<(f64, f64)> = (0..n)
            .map(|k| (k as f64, (k as f64 * 0.37).sin() + 1e-6 * k as f64))
            .collect();
        let px = |p: &(f64, f64)| ((p.0 / 100.0) as i32, 0);
        let t = thin(pts.clone(), px);
        assert!(t.len() <= 4 * 1000 && t.len() >= 2 * 1000, "{}", t.len());
        assert_eq!(t.first(), pts.first());
        assert_eq!(t.last(), pts.last());
        for c in 0..1000 {
            let col = |v: &[(f64, f64)]| -> (f64, f64) {
                v.iter()
                    .filter(|p| px(p).0 == c)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                        (a.min(p.1), b.max(p.1))
                    })
            };
            assert_eq!(col(&t), col(&pts), "column {c}");
        }
        // Order kept: x never decreases along the thinned line.
        assert!(t.windows(2).all(|w| w[1].0 > w[0].0));
    }

    /// Width and height of a PNG (its IHDR chunk).
    fn png_size(p: &Path) -> (u32, u32) {
        let b = std::fs::read(p).unwrap();
        assert_eq!(&b[1..4], b"PNG");
        let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
        (be(16), be(20))
    }

    /// A PNG's pixel size is proportional to its dpi (1000 x 625 px at 100 dpi, a stack of
    /// two panels 1000 x 644 px), the SVG beside it is the same at any dpi, and a dpi out
    /// of range is refused naming the range, with nothing written.
    #[test]
    fn png_size_scales_with_dpi() {
        let dir = std::env::temp_dir().join(format!("raceway-dpi-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let x: Vec<f64> = (0..300).map(|i| i as f64 * 0.01).collect();
        let y: Vec<f64> = x.iter().map(|t| (7.0 * t).sin()).collect();
        let axes = Axes {
            title: "dpi",
            x_label: "t (s)",
            y_label: "y (m)",
            ..Axes::default()
        };
        let ser = [Series {
            label: "y",
            x: &x,
            y: &y,
            points: false,
        }];
        let panels = vec![(axes.clone(), ser.to_vec()), (axes.clone(), ser.to_vec())];
        let mut svgs = Vec::new();
        for (dpi, w, h, hs) in [
            (100, 1000, 625, 644),
            (50, 500, 313, 322),
            (200, 2000, 1250, 1288),
            (300, 3000, 1875, 1932),
        ] {
            let p = dir.join(format!("p{dpi}.png"));
            plot_pair_dpi(&p, dpi, &axes, &ser, &[]).unwrap();
            assert_eq!(png_size(&p), (w, h), "{dpi} dpi");
            svgs.push(std::fs::read_to_string(p.with_extension("svg")).unwrap());
            let q = dir.join(format!("s{dpi}.png"));
            stack_pair_dpi(&q, dpi, "stack", &panels).unwrap();
            assert_eq!(png_size(&q), (w, hs), "{dpi} dpi stack");
        }
        assert!(svgs.windows(2).all(|w| w[0] == w[1]));
        assert_eq!(png_size(&dir.join("p100.png")), PLOT_PX);
        for dpi in [0, 49, 401] {
            let p = dir.join(format!("bad{dpi}.png"));
            let e = plot_pair_dpi(&p, dpi, &axes, &ser, &[])
                .unwrap_err()
                .to_string();
            assert!(e.contains("dpi") && e.contains("50 to 400"), "{e}");
            assert!(!p.exists() && !p.with_extension("svg").exists());
        }
    }

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
        plot_pair(
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
        // The SVG beside it: the title and the marker label as text, the curve as a
        // polyline.
        let svg = std::fs::read_to_string(p.with_extension("svg")).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..40.min(svg.len())]);
        assert!(svg.contains(">\nsine\n</text>") && svg.contains(">\n1 s\n</text>"));
        assert!(svg.contains("<polyline"));
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
