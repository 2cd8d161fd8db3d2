//! Figures: one figure model (stacked line/marker panels sharing an x axis, and sheets),
//! written as PNG or SVG. The engine knows nothing of tables or the solver: the pictures of a
//! table are built above it (`oblique_study::figures`).
//!
//! Shared by every command that draws. A [`Figure`] is plain
//! data; [`render`] draws it with `plotters`. The font (a subset of DejaVu Sans, see
//! `assets/fonts/`) is embedded, so a PNG looks the same on every machine.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::FontStyle;
use thiserror::Error;

mod sheet;
pub use sheet::*;

/// The embedded font (DejaVu Sans subset: Latin, Greek, math symbols).
static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans-subset.ttf");
const FAMILY: &str = "sans-serif";

/// Errors of figure rendering.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The output name has no extension we can write.
    #[error("cannot write figure {path}: unknown extension (use .png or .svg)")]
    Format {
        /// Output path.
        path: String,
    },
    /// Drawing or writing failed.
    #[error("cannot write figure {path}: {message}")]
    Draw {
        /// Output path.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// The output path is not a regular file, or the finished figure could not be put there.
    #[error(transparent)]
    Output(#[from] oblique_output::OutputError),
}

impl PlotError {
    /// Whether the caller can fix it: an unknown output format or an output path in the way
    /// (not: a failed drawing or write).
    pub fn user_can_fix(&self) -> bool {
        match self {
            PlotError::Format { .. } => true,
            PlotError::Output(e) => e.user_can_fix(),
            PlotError::Draw { .. } => false,
        }
    }
}

/// The format of `path` by its extension, or [`PlotError::Format`].
fn format_of(path: &Path) -> Result<&'static str, PlotError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("png") => Ok("png"),
        Some("svg") => Ok("svg"),
        _ => Err(PlotError::Format {
            path: path.display().to_string(),
        }),
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid line.
    Line,
    /// Solid line with a small marker at each point.
    LineMarkers,
    /// Dashed line.
    Dashed,
    /// Dotted line.
    Dotted,
    /// Open circles, no line.
    Markers,
}

/// One data series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// Points `(x, y)`; a non-finite `y` breaks the line.
    pub points: Vec<(f64, f64)>,
    /// Line or markers.
    pub style: Style,
    /// RGB colour.
    pub color: (u8, u8, u8),
    /// Whether the series sets the automatic y range (approximations that run off to
    /// infinity should not); parts outside the range are clipped.
    pub sets_range: bool,
}

/// Where a panel's legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Upper right corner.
    #[default]
    UpperRight,
    /// Lower right corner.
    LowerRight,
    /// Upper left corner.
    UpperLeft,
    /// Lower left corner.
    LowerLeft,
}

/// One panel: an y axis and its series.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Y axis label, with symbol and unit.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Vertical marker lines `(x, label)`, e.g. regime boundaries.
    pub vlines: Vec<(f64, String)>,
    /// Fixed y range; automatic (from the series with `sets_range`) when `None`.
    pub y_range: Option<(f64, f64)>,
    /// Legend position.
    pub legend: Legend,
}

/// A figure: panels stacked vertically over one x axis, a title and caption lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title line at the top.
    pub title: String,
    /// Smaller line under the title (may be empty).
    pub subtitle: String,
    /// X axis label, with symbol and unit.
    pub x_label: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Caption lines at the bottom (what was run, from which file).
    pub caption: Vec<String>,
    /// Size in pixels (width, height).
    pub size: (u32, u32),
}

fn register_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
                .map_err(|_| "the embedded font is not a valid TrueType font".to_string())
        })
        .clone()
}

/// Draw a figure to `path`; the format follows the extension (`.png` or `.svg`). The file is
/// written through `oblique_output`: on any error `path` is left as it was.
pub fn render(fig: &Figure, path: &Path) -> Result<(), PlotError> {
    let mut files = oblique_output::Files::new();
    render_into(fig, path, &mut files)?;
    Ok(files.commit()?)
}

/// Draw a figure for `path` (`.png` or `.svg`) into a set of files that are put in place
/// together ([`oblique_output::Files`]): `path` is replaced only when the set is committed.
pub fn render_into(
    fig: &Figure,
    path: &Path,
    files: &mut oblique_output::Files,
) -> Result<(), PlotError> {
    render_with(fig, path, false, files)
}

/// Draw a figure with logarithmic x and y axes (every panel) to `path` (`.png` or `.svg`).
///
/// Points with a non-positive or non-finite coordinate are left out; `y_range` and `vlines` are
/// ignored.
pub fn render_log_log(fig: &Figure, path: &Path) -> Result<(), PlotError> {
    let mut files = oblique_output::Files::new();
    render_with(fig, path, true, &mut files)?;
    Ok(files.commit()?)
}

fn render_with(
    fig: &Figure,
    path: &Path,
    log_log: bool,
    files: &mut oblique_output::Files,
) -> Result<(), PlotError> {
    let shown = path.display().to_string();
    let draw_err = |message: String| PlotError::Draw {
        path: shown.clone(),
        message,
    };
    register_font().map_err(draw_err)?;
    let format = format_of(path)?;
    files.write_via_path(path, |tmp| {
        if format == "png" {
            let root = BitMapBackend::new(tmp, fig.size).into_drawing_area();
            if log_log {
                draw_log_log(fig, &root)
            } else {
                draw(fig, &root)
            }
            .map_err(draw_err)?;
            root.present().map_err(|e| draw_err(e.to_string()))
        } else {
            let root = SVGBackend::new(tmp, fig.size).into_drawing_area();
            if log_log {
                draw_log_log(fig, &root)
            } else {
                draw(fig, &root)
            }
            .map_err(draw_err)?;
            root.present().map_err(|e| draw_err(e.to_string()))
        }
    })
}

fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Range with 5 % padding; a degenerate range is widened.
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * lo.abs().max(hi.abs()).max(1e-300) {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - d, hi + d)
    } else {
        (lo - 0.05 * span, hi + 0.05 * span)
    }
}

fn bounds(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Split a polyline at non-finite points and clip it to `y ∈ [lo, hi]` (crossings interpolated).
pub fn clip_polyline(points: &[(f64, f64)], lo: f64, hi: f64) -> Vec<Vec<(f64, f64)>> {
    let inside = |y: f64| y >= lo && y <= hi;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let finish = |cur: &mut Vec<(f64, f64)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if !cur.is_empty() {
            out.push(std::mem::take(cur));
        }
    };
    for w in 0..points.len() {
        let (x, y) = points[w];
        if !(x.is_finite() && y.is_finite()) {
            finish(&mut cur, &mut out);
            continue;
        }
        let prev = (w > 0)
            .then(|| points[w - 1])
            .filter(|(px, py)| px.is_finite() && py.is_finite());
        if let Some((px, py)) = prev {
            // Crossings of the segment (px,py)-(x,y) with the two bounds, in order along it.
            let mut cuts: Vec<(f64, f64)> = [lo, hi]
                .iter()
                .filter(|&&b| (py - b) * (y - b) < 0.0)
                .map(|&b| {
                    let t = (b - py) / (y - py);
                    (t, b)
                })
                .collect();
            cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (t, b) in cuts {
                let xc = px + t * (x - px);
                if cur.is_empty() {
                    cur.push((xc, b));
                } else {
                    cur.push((xc, b));
                    finish(&mut cur, &mut out);
                }
            }
        }
        if inside(y) {
            cur.push((x, y));
        } else {
            finish(&mut cur, &mut out);
        }
    }
    finish(&mut cur, &mut out);
    out
}

/// White background, title and subtitle at the top, caption lines at the bottom; returns the
/// area left for the plots.
fn draw_frame<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: &str,
    caption: &[String],
) -> Result<DrawingArea<DB, Shift>, String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (_, h) = root.dim_in_pixel();
    let title_h = if subtitle.is_empty() { 44u32 } else { 66 };
    let caption_h = 10 + 20 * caption.len() as u32;
    let (title_area, rest) = root.split_vertically(title_h);
    let (plots, caption_area) = rest.split_vertically(h.saturating_sub(title_h + caption_h));
    title_area
        .draw_text(title, &(FAMILY, 22).into_font().color(&BLACK), (16, 12))
        .map_err(e)?;
    if !subtitle.is_empty() {
        title_area
            .draw_text(
                subtitle,
                &(FAMILY, 16).into_font().color(&RGBColor(60, 60, 60)),
                (16, 40),
            )
            .map_err(e)?;
    }
    for (i, line) in caption.iter().enumerate() {
        caption_area
            .draw_text(
                line,
                &(FAMILY, 14).into_font().color(&RGBColor(60, 60, 60)),
                (16, 4 + 20 * i as i32),
            )
            .map_err(e)?;
    }
    Ok(plots)
}

fn draw<DB: DrawingBackend>(fig: &Figure, root: &DrawingArea<DB, Shift>) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let plots = draw_frame(root, &fig.title, &fig.subtitle, &fig.caption)?;
    let n = fig.panels.len().max(1);
    let areas = plots.split_evenly((n, 1));
    let x_bounds = bounds(
        fig.panels
            .iter()
            .flat_map(|p| p.series.iter())
            .flat_map(|s| s.points.iter().map(|p| p.0)),
    )
    .unwrap_or((0.0, 1.0));
    let (x0, x1) = padded(x_bounds.0, x_bounds.1);
    for (panel, area) in fig.panels.iter().zip(areas.iter()) {
        let (y0, y1) = match panel.y_range {
            Some(r) => r,
            None => {
                let b = bounds(
                    panel
                        .series
                        .iter()
                        .filter(|s| s.sets_range)
                        .flat_map(|s| s.points.iter().map(|p| p.1)),
                )
                .unwrap_or((0.0, 1.0));
                padded(b.0, b.1)
            }
        };
        let mut chart = ChartBuilder::on(area)
            .margin_left(12)
            .margin_right(24)
            .margin_top(8)
            .margin_bottom(4)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(fig.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .label_style((FAMILY, 15))
            .axis_desc_style((FAMILY, 17))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()
            .map_err(e)?;
        for (x, label) in &panel.vlines {
            if !(x.is_finite() && *x >= x0 && *x <= x1) {
                continue;
            }
            let grey = RGBColor(140, 140, 140);
            chart
                .draw_series(DashedLineSeries::new(
                    [(*x, y0), (*x, y1)],
                    4,
                    4,
                    grey.stroke_width(1),
                ))
                .map_err(e)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    label.clone(),
                    (*x, y1 - 0.01 * (y1 - y0)),
                    (FAMILY, 15).into_font().color(&RGBColor(90, 90, 90)),
                )))
                .map_err(e)?;
        }
        draw_series_set(&mut chart, &panel.series, (y0, y1))?;
        draw_legend(&mut chart, panel.legend)?;
    }
    Ok(())
}

/// Decade-padded bounds of the positive finite values.
fn log_bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = bounds(values.filter(|v| *v > 0.0)).unwrap_or((1.0, 10.0));
    let (lo, hi) = (lo.log10().floor(), hi.log10().ceil());
    let hi = if hi <= lo { lo + 1.0 } else { hi };
    (10f64.powf(lo), 10f64.powf(hi))
}

fn draw_log_log<DB: DrawingBackend>(
    fig: &Figure,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let plots = draw_frame(root, &fig.title, &fig.subtitle, &fig.caption)?;
    let usable = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0;
    let (x0, x1) = log_bounds(
        fig.panels
            .iter()
            .flat_map(|p| p.series.iter())
            .flat_map(|s| s.points.iter().filter(usable).map(|p| p.0)),
    );
    let areas = plots.split_evenly((fig.panels.len().max(1), 1));
    for (panel, area) in fig.panels.iter().zip(areas.iter()) {
        let series: Vec<Series> = panel
            .series
            .iter()
            .map(|s| Series {
                points: s.points.iter().filter(usable).copied().collect(),
                ..s.clone()
            })
            .collect();
        let (y0, y1) = log_bounds(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
        let mut chart = ChartBuilder::on(area)
            .margin_left(12)
            .margin_right(24)
            .margin_top(8)
            .margin_bottom(4)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(fig.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style((FAMILY, 15))
            .axis_desc_style((FAMILY, 17))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()
            .map_err(e)?;
        draw_series_set(&mut chart, &series, (y0, y1))?;
        draw_legend(&mut chart, panel.legend)?;
    }
    Ok(())
}

/// The legend box of a chart at the panel's corner.
fn draw_legend<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    legend: Legend,
) -> Result<(), String>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let pos = match legend {
        Legend::UpperRight => SeriesLabelPosition::UpperRight,
        Legend::LowerRight => SeriesLabelPosition::LowerRight,
        Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
        Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
    };
    chart
        .configure_series_labels()
        .position(pos)
        .label_font((FAMILY, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .draw()
        .map_err(|err| err.to_string())
}

/// Draw series on a chart (lines, dashes, markers; clipped to `y ∈ [y0, y1]`) and register
/// their legend entries (series with an empty label get none).
fn draw_series_set<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    series: &[Series],
    (y0, y1): (f64, f64),
) -> Result<(), String>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();

    for s in series {
        let color = rgb(s.color);
        let legend_color = color;
        let style = s.style;
        let segments = clip_polyline(&s.points, y0, y1);
        let legend = move |(x, y): (i32, i32)| -> DynElement<'static, DB, (i32, i32)> {
            match style {
                Style::Markers => {
                    Circle::new((x + 12, y), 4, legend_color.stroke_width(2)).into_dyn()
                }
                Style::Dashed => DashedPathElement::new(
                    vec![(x, y), (x + 24, y)],
                    6,
                    4,
                    legend_color.stroke_width(2),
                )
                .into_dyn(),
                Style::Dotted => DashedPathElement::new(
                    vec![(x, y), (x + 24, y)],
                    2,
                    3,
                    legend_color.stroke_width(2),
                )
                .into_dyn(),
                Style::Line | Style::LineMarkers => {
                    PathElement::new(vec![(x, y), (x + 24, y)], legend_color.stroke_width(2))
                        .into_dyn()
                }
            }
        };
        let anno = match style {
            Style::Markers => chart
                .draw_series(
                    s.points
                        .iter()
                        .filter(|(x, y)| x.is_finite() && y.is_finite() && *y >= y0 && *y <= y1)
                        .map(|&p| Circle::new(p, 4, color.stroke_width(2))),
                )
                .map_err(e)?,
            Style::Line | Style::LineMarkers => {
                for seg in &segments {
                    chart
                        .draw_series(LineSeries::new(seg.iter().copied(), color.stroke_width(2)))
                        .map_err(e)?;
                }
                let marker_size = if style == Style::LineMarkers { 2 } else { 0 };
                chart
                    .draw_series(
                        s.points
                            .iter()
                            .filter(|(x, y)| {
                                marker_size > 0
                                    && x.is_finite()
                                    && y.is_finite()
                                    && *y >= y0
                                    && *y <= y1
                            })
                            .map(|&p| Circle::new(p, marker_size, color.filled())),
                    )
                    .map_err(e)?
            }
            Style::Dashed | Style::Dotted => {
                let (dash, gap) = if style == Style::Dashed {
                    (8, 5)
                } else {
                    (2, 4)
                };
                for seg in &segments {
                    chart
                        .draw_series(DashedLineSeries::new(
                            seg.iter().copied(),
                            dash,
                            gap,
                            color.stroke_width(2),
                        ))
                        .map_err(e)?;
                }
                chart
                    .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                    .map_err(e)?
            }
        };
        if !s.label.is_empty() {
            anno.label(s.label.as_str()).legend(legend);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_splits_at_bounds_and_gaps() {
        let pts = [
            (0.0, 0.5),
            (1.0, 2.0),
            (2.0, 0.5),
            (3.0, f64::NAN),
            (4.0, 0.2),
        ];
        let segs = clip_polyline(&pts, 0.0, 1.0);
        assert_eq!(segs.len(), 3, "{segs:?}");
        let near = |a: &[(f64, f64)], b: &[(f64, f64)]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12)
        };
        assert!(near(&segs[0], &[(0.0, 0.5), (1.0 / 3.0, 1.0)]), "{segs:?}");
        assert!(near(&segs[1], &[(5.0 / 3.0, 1.0), (2.0, 0.5)]), "{segs:?}");
        assert_eq!(segs[2], vec![(4.0, 0.2)]);
    }
}
