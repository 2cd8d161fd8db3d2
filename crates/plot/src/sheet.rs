//! Sheets: one or more charts, each with its own axes, stacked vertically under a title and over
//! caption lines. A chart can carry a colour map of a grid with contour lines, filled regions,
//! thin outlines, line/marker series, points coloured by a value, text notes, a colour bar and a
//! legend. Like [`Figure`](super::Figure), a [`Sheet`] is plain data; [`render_sheet`] draws it.
//!
//! Axes take fixed ticks with any labels, so a compactified axis can put `∞` at its end.

use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::path::Path;

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{clip_polyline, draw_series_set, register_font, rgb, Legend, PlotError, Series, Style};
use super::{draw_frame, FAMILY};

/// Tick marks of an axis.
#[derive(Debug, Clone, PartialEq)]
pub enum Ticks {
    /// Round numbers chosen from the range ([`nice_ticks`]).
    Auto,
    /// These positions with these labels (e.g. `∞` at the end of a compactified axis).
    Fixed(Vec<(f64, String)>),
}

/// One axis of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Label, with symbol and unit.
    pub label: String,
    /// Range `(lo, hi)` in plot coordinates, `lo < hi`.
    pub range: (f64, f64),
    /// Tick marks.
    pub ticks: Ticks,
}

/// Colour maps (perceptually ordered).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Colormap {
    /// Blue – white – red (ColorBrewer RdBu, reversed): for signed quantities, white at the middle.
    Diverging,
    /// Dark violet – green – yellow (viridis): for magnitudes.
    Sequential,
}

const DIVERGING: [(u8, u8, u8); 11] = [
    (5, 48, 97),
    (33, 102, 172),
    (67, 147, 195),
    (146, 197, 222),
    (209, 229, 240),
    (247, 247, 247),
    (253, 219, 199),
    (244, 165, 130),
    (214, 96, 77),
    (178, 24, 43),
    (103, 0, 31),
];

const SEQUENTIAL: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

impl Colormap {
    /// Colour at `t ∈ [0, 1]` (clamped), interpolated linearly between the map's stops.
    pub fn at(self, t: f64) -> (u8, u8, u8) {
        let stops: &[(u8, u8, u8)] = match self {
            Colormap::Diverging => &DIVERGING,
            Colormap::Sequential => &SEQUENTIAL,
        };
        let t = if t.is_finite() {
            t.clamp(0.0, 1.0)
        } else {
            0.0
        };
        let u = t * (stops.len() - 1) as f64;
        let i = (u.floor() as usize).min(stops.len() - 2);
        let f = u - i as f64;
        let mix = |a: u8, b: u8| (a as f64 + f * (b as f64 - a as f64)).round() as u8;
        let (a, b) = (stops[i], stops[i + 1]);
        (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
    }
}

/// How values are placed on a colour scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear in the value.
    Linear,
    /// Linear in `log10` of the value (values ≤ 0 get the lowest colour).
    Log10,
}

/// Value → colour, with its colour bar.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorScale {
    /// Colour bar label, with symbol and unit.
    pub label: String,
    /// The colours.
    pub colormap: Colormap,
    /// Linear or logarithmic.
    pub scale: Scale,
    /// Values `(lo, hi)` at the ends of the bar; values outside get the end colours.
    pub range: (f64, f64),
    /// Number of discrete colour bands (0: continuous). Bands make a colour map read like
    /// filled contours.
    pub bands: usize,
    /// Ticks on the colour bar: value and label.
    pub ticks: Vec<(f64, String)>,
}

impl ColorScale {
    fn transform(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => v,
            Scale::Log10 => {
                if v > 0.0 {
                    v.log10()
                } else {
                    f64::NEG_INFINITY
                }
            }
        }
    }

    /// Position of `v` on the bar, `[0, 1]` (clamped); `None` for NaN.
    pub fn position(&self, v: f64) -> Option<f64> {
        if v.is_nan() {
            return None;
        }
        let (a, b) = (self.transform(self.range.0), self.transform(self.range.1));
        let t = (self.transform(v) - a) / (b - a);
        Some(if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) })
    }

    /// Band index of `v` (0 … `bands` − 1), or `None` for NaN or a continuous scale.
    fn band(&self, v: f64) -> Option<usize> {
        let t = self.position(v)?;
        (self.bands > 0).then(|| ((t * self.bands as f64).floor() as usize).min(self.bands - 1))
    }

    /// Colour of `v` (`None` for NaN).
    pub fn color(&self, v: f64) -> Option<(u8, u8, u8)> {
        let t = self.position(v)?;
        Some(match self.band(v) {
            Some(k) => self.colormap.at((k as f64 + 0.5) / self.bands as f64),
            None => self.colormap.at(t),
        })
    }
}

/// Values on a rectangular grid of nodes: `values[i · ys.len() + j]` at `(xs[i], ys[j])`.
/// Both coordinate lists increase. NaN marks a node without a value.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Node x positions (plot coordinates).
    pub xs: Vec<f64>,
    /// Node y positions (plot coordinates).
    pub ys: Vec<f64>,
    /// Node values, x outer.
    pub values: Vec<f64>,
}

impl Grid {
    /// Value at node `(i, j)`.
    pub fn value(&self, i: usize, j: usize) -> f64 {
        self.values[i * self.ys.len() + j]
    }
}

/// Contour lines of a chart's grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Contours {
    /// Levels drawn as thin lines.
    pub levels: Vec<f64>,
    /// Levels drawn as thicker lines.
    pub bold: Vec<f64>,
    /// Line colour.
    pub color: (u8, u8, u8),
}

/// A filled polygon (e.g. a regime of a diagram).
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// Legend entry (empty: none).
    pub label: String,
    /// Vertices, plot coordinates.
    pub polygon: Vec<(f64, f64)>,
    /// Fill colour.
    pub color: (u8, u8, u8),
}

/// Text placed at a point of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// The text.
    pub text: String,
    /// Position (plot coordinates); the text is centred there.
    pub at: (f64, f64),
    /// Text colour.
    pub color: (u8, u8, u8),
    /// Font size (px).
    pub size: u32,
    /// Draw a white box behind the text.
    pub boxed: bool,
}

/// Points filled with the colour of a value on the chart's colour scale.
#[derive(Debug, Clone, PartialEq)]
pub struct Scatter {
    /// Legend entry (empty: none).
    pub label: String,
    /// `(x, y, value)`.
    pub points: Vec<(f64, f64, f64)>,
    /// Radius (px).
    pub radius: u32,
}

/// Where a chart's legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LegendPlace {
    /// No legend.
    None,
    /// In a corner of the plot area, boxed.
    Inside(Legend),
    /// In a column to the right of the plot area (never covers data).
    Right,
}

/// One chart: two axes and what is drawn on them, bottom layer first: regions, colour map,
/// contours, outlines, series, coloured points, notes.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// Line above the chart (may be empty).
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Filled polygons.
    pub regions: Vec<Region>,
    /// Grid drawn as a colour map (needs `color_scale`); each node colours the rectangle halfway
    /// to its neighbours.
    pub map: Option<Grid>,
    /// Contour lines of `map`.
    pub contours: Option<Contours>,
    /// Thin grey polylines (e.g. a mesh).
    pub outlines: Vec<Vec<(f64, f64)>>,
    /// Line/marker series.
    pub series: Vec<Series>,
    /// Points coloured by value (needs `color_scale`).
    pub scatter: Option<Scatter>,
    /// Colour scale of `map` and `scatter`, drawn as a colour bar at the right.
    pub color_scale: Option<ColorScale>,
    /// Text notes.
    pub notes: Vec<Note>,
    /// Legend of the labelled regions, series and scatter.
    pub legend: LegendPlace,
}

/// A sheet: charts stacked vertically, a title, a subtitle and caption lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Sheet {
    /// Title line at the top.
    pub title: String,
    /// Smaller line under the title (may be empty).
    pub subtitle: String,
    /// The charts, top to bottom.
    pub charts: Vec<Chart>,
    /// Caption lines at the bottom (provenance, the command that made it).
    pub caption: Vec<String>,
    /// Size in pixels (width, height).
    pub size: (u32, u32),
}

/// Round-number ticks for `[lo, hi]`, about `target` of them, labelled with just enough decimals
/// (and a true minus sign).
pub fn nice_ticks(lo: f64, hi: f64, target: usize) -> Vec<(f64, String)> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    // The round step (1, 2, 2.5 or 5 times a power of ten) whose tick count is closest to
    // `target`; ties go to the larger step.
    let count = |step: f64| ((hi / step + 1e-9).floor() - (lo / step - 1e-9).ceil() + 1.0).max(0.0);
    let mag = 10f64.powf(((hi - lo) / target.max(1) as f64).log10().floor());
    let (mult, step) = [0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0]
        .into_iter()
        .map(|m| (m, m * mag))
        .min_by(|a, b| {
            let da = (count(a.1) - target as f64).abs();
            let db = (count(b.1) - target as f64).abs();
            da.total_cmp(&db).then(b.1.total_cmp(&a.1))
        })
        .unwrap_or((1.0, mag));
    let decimals =
        (-(step * (1.0 + 1e-9)).log10().floor()).max(0.0) as usize + usize::from(mult == 2.5);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            let v = if v.abs() < 1e-12 * step { 0.0 } else { v };
            (v, format!("{v:.decimals$}").replace('-', "−"))
        })
        .collect()
}

/// Contour lines of `grid` at `level` (marching squares, linear interpolation along cell edges),
/// joined into polylines. Cells with a NaN corner are skipped. A node exactly at `level` counts as
/// above it.
pub fn contour_lines(grid: &Grid, level: f64) -> Vec<Vec<(f64, f64)>> {
    let (nx, ny) = (grid.xs.len(), grid.ys.len());
    if nx < 2 || ny < 2 || grid.values.len() != nx * ny {
        return Vec::new();
    }
    // Edge ids: 2·(i·ny + j) for the edge (i, j)–(i+1, j), 2·(i·ny + j) + 1 for (i, j)–(i, j+1).
    let h_edge = |i: usize, j: usize| 2 * (i * ny + j);
    let v_edge = |i: usize, j: usize| 2 * (i * ny + j) + 1;
    let mut point: HashMap<usize, (f64, f64)> = HashMap::new();
    let mut segs: Vec<(usize, usize)> = Vec::new();
    let cross = |a: f64, b: f64| (a >= level) != (b >= level);
    let frac = |a: f64, b: f64| (level - a) / (b - a);
    for i in 0..nx - 1 {
        for j in 0..ny - 1 {
            let v00 = grid.value(i, j);
            let v10 = grid.value(i + 1, j);
            let v01 = grid.value(i, j + 1);
            let v11 = grid.value(i + 1, j + 1);
            if [v00, v10, v01, v11].iter().any(|v| v.is_nan()) {
                continue;
            }
            let (x0, x1, y0, y1) = (grid.xs[i], grid.xs[i + 1], grid.ys[j], grid.ys[j + 1]);
            // Crossed edges in the order bottom, right, top, left.
            let mut hits: Vec<usize> = Vec::with_capacity(4);
            if cross(v00, v10) {
                let id = h_edge(i, j);
                point.insert(id, (x0 + frac(v00, v10) * (x1 - x0), y0));
                hits.push(id);
            }
            if cross(v10, v11) {
                let id = v_edge(i + 1, j);
                point.insert(id, (x1, y0 + frac(v10, v11) * (y1 - y0)));
                hits.push(id);
            }
            if cross(v01, v11) {
                let id = h_edge(i, j + 1);
                point.insert(id, (x0 + frac(v01, v11) * (x1 - x0), y1));
                hits.push(id);
            }
            if cross(v00, v01) {
                let id = v_edge(i, j);
                point.insert(id, (x0, y0 + frac(v00, v01) * (y1 - y0)));
                hits.push(id);
            }
            match hits.len() {
                2 => segs.push((hits[0], hits[1])),
                4 => {
                    // Saddle: the centre value decides which corners are connected.
                    let centre = 0.25 * (v00 + v10 + v01 + v11);
                    if (centre >= level) == (v00 >= level) {
                        // v00's side joins the centre: cut off the corners v10 and v01.
                        segs.push((hits[0], hits[1]));
                        segs.push((hits[2], hits[3]));
                    } else {
                        segs.push((hits[0], hits[3]));
                        segs.push((hits[1], hits[2]));
                    }
                }
                _ => {}
            }
        }
    }
    let mut at_edge: HashMap<usize, Vec<usize>> = HashMap::new();
    for (k, &(a, b)) in segs.iter().enumerate() {
        at_edge.entry(a).or_default().push(k);
        at_edge.entry(b).or_default().push(k);
    }
    let mut used = vec![false; segs.len()];
    let mut lines = Vec::new();
    for start in 0..segs.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b) = segs[start];
        let mut chain = std::collections::VecDeque::from([a, b]);
        for forward in [true, false] {
            let mut end = if forward { b } else { a };
            loop {
                let next = at_edge
                    .get(&end)
                    .and_then(|ks| ks.iter().copied().find(|&k| !used[k]));
                let Some(k) = next else { break };
                used[k] = true;
                let (p, q) = segs[k];
                end = if p == end { q } else { p };
                if forward {
                    chain.push_back(end);
                } else {
                    chain.push_front(end);
                }
            }
        }
        lines.push(
            chain
                .iter()
                .filter_map(|id| point.get(id).copied())
                .collect(),
        );
    }
    lines
}

/// An axis with fixed ticks, as a `plotters` coordinate.
#[derive(Clone)]
struct TickedRange {
    lo: f64,
    hi: f64,
    ticks: Vec<(f64, String)>,
}

impl TickedRange {
    fn new(axis: &Axis) -> Self {
        let (lo, hi) = axis.range;
        let ticks = match &axis.ticks {
            Ticks::Auto => nice_ticks(lo, hi, 6),
            Ticks::Fixed(t) => t.clone(),
        };
        TickedRange { lo, hi, ticks }
    }
}

impl Ranged for TickedRange {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let t = (v - self.lo) / (self.hi - self.lo);
        let t = if t.is_finite() {
            t.clamp(-4.0, 5.0)
        } else {
            0.0
        };
        limit.0 + (t * (limit.1 - limit.0) as f64).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            return Vec::new();
        }
        let span = self.hi - self.lo;
        self.ticks
            .iter()
            .map(|t| t.0)
            .filter(|&v| v >= self.lo - 1e-9 * span && v <= self.hi + 1e-9 * span)
            .collect()
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for TickedRange {
    fn format_ext(&self, value: &f64) -> String {
        self.ticks
            .iter()
            .min_by(|a, b| (a.0 - value).abs().total_cmp(&(b.0 - value).abs()))
            .map(|t| t.1.clone())
            .unwrap_or_default()
    }
}

/// Draw a sheet to `path`; the format follows the extension (`.png` or `.svg`), written through
/// `oblique_output` like [`render`](super::render).
pub fn render_sheet(sheet: &Sheet, path: &Path) -> Result<(), PlotError> {
    let mut files = oblique_output::Files::new();
    render_sheet_into(sheet, path, &mut files)?;
    Ok(files.commit()?)
}

/// Draw a sheet for `path` (`.png` or `.svg`) into a set of files that are put in place
/// together ([`oblique_output::Files`]), like [`render_into`](super::render_into).
pub fn render_sheet_into(
    sheet: &Sheet,
    path: &Path,
    files: &mut oblique_output::Files,
) -> Result<(), PlotError> {
    let shown = path.display().to_string();
    let draw_err = |message: String| PlotError::Draw {
        path: shown.clone(),
        message,
    };
    register_font().map_err(draw_err)?;
    let format = super::format_of(path)?;
    files.write_via_path(path, |tmp| {
        if format == "png" {
            let root = BitMapBackend::new(tmp, sheet.size).into_drawing_area();
            draw_sheet(sheet, &root).map_err(draw_err)?;
            root.present().map_err(|e| draw_err(e.to_string()))
        } else {
            let root = SVGBackend::new(tmp, sheet.size).into_drawing_area();
            draw_sheet(sheet, &root).map_err(draw_err)?;
            root.present().map_err(|e| draw_err(e.to_string()))
        }
    })
}

fn draw_sheet<DB: DrawingBackend>(
    sheet: &Sheet,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let plots = draw_frame(root, &sheet.title, &sheet.subtitle, &sheet.caption)?;
    let n = sheet.charts.len().max(1);
    for (chart, area) in sheet.charts.iter().zip(plots.split_evenly((n, 1)).iter()) {
        draw_chart(chart, area)?;
    }
    Ok(())
}

/// What a legend entry shows.
enum Glyph {
    Line(Style),
    Patch,
    Dot,
}

fn legend_entries(c: &Chart) -> Vec<(Glyph, (u8, u8, u8), &str)> {
    let mut out: Vec<(Glyph, (u8, u8, u8), &str)> = Vec::new();
    for r in c.regions.iter().filter(|r| !r.label.is_empty()) {
        out.push((Glyph::Patch, r.color, &r.label));
    }
    for s in c.series.iter().filter(|s| !s.label.is_empty()) {
        out.push((Glyph::Line(s.style), s.color, &s.label));
    }
    if let Some(s) = c.scatter.as_ref().filter(|s| !s.label.is_empty()) {
        out.push((Glyph::Dot, (120, 120, 120), &s.label));
    }
    out
}

const LEGEND_FONT: u32 = 14;
const LEGEND_ROW: i32 = 20;

fn legend_width<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Glyph, (u8, u8, u8), &str)],
) -> u32 {
    let font = (FAMILY, LEGEND_FONT).into_font().color(&BLACK);
    entries
        .iter()
        .map(|e| {
            area.estimate_text_size(e.2, &font)
                .map(|s| s.0)
                .unwrap_or(8 * e.2.chars().count() as u32)
        })
        .max()
        .unwrap_or(0)
        + 48
}

/// Draw legend entries with their top-left corner at `(x, y)` of `area` (pixels).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Glyph, (u8, u8, u8), &str)],
    (x, y): (i32, i32),
    boxed: bool,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    if entries.is_empty() {
        return Ok(());
    }
    let w = legend_width(area, entries) as i32;
    let h = LEGEND_ROW * entries.len() as i32 + 8;
    if boxed {
        area.draw(&Rectangle::new(
            [(x, y), (x + w, y + h)],
            WHITE.mix(0.9).filled(),
        ))
        .map_err(e)?;
        area.draw(&Rectangle::new(
            [(x, y), (x + w, y + h)],
            RGBColor(180, 180, 180).stroke_width(1),
        ))
        .map_err(e)?;
    }
    let font = (FAMILY, LEGEND_FONT)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (k, (glyph, color, label)) in entries.iter().enumerate() {
        let cy = y + 4 + LEGEND_ROW * k as i32 + LEGEND_ROW / 2;
        let (gx0, gx1) = (x + 8, x + 34);
        let col = rgb(*color);
        match glyph {
            Glyph::Patch => area
                .draw(&Rectangle::new(
                    [(gx0 + 4, cy - 6), (gx1 - 4, cy + 6)],
                    col.filled(),
                ))
                .map_err(e)?,
            Glyph::Dot => area
                .draw(&Circle::new(((gx0 + gx1) / 2, cy), 5, col.filled()))
                .map_err(e)?,
            Glyph::Line(Style::Markers) => area
                .draw(&Circle::new(((gx0 + gx1) / 2, cy), 4, col.stroke_width(2)))
                .map_err(e)?,
            Glyph::Line(Style::Dashed) => area
                .draw(&DashedPathElement::new(
                    vec![(gx0, cy), (gx1, cy)],
                    6,
                    4,
                    col.stroke_width(2),
                ))
                .map_err(e)?,
            Glyph::Line(Style::Dotted) => area
                .draw(&DashedPathElement::new(
                    vec![(gx0, cy), (gx1, cy)],
                    2,
                    3,
                    col.stroke_width(2),
                ))
                .map_err(e)?,
            Glyph::Line(Style::Line | Style::LineMarkers) => area
                .draw(&PathElement::new(
                    vec![(gx0, cy), (gx1, cy)],
                    col.stroke_width(2),
                ))
                .map_err(e)?,
        }
        area.draw_text(label, &font, (gx1 + 8, cy)).map_err(e)?;
    }
    Ok(())
}

/// Cell edges of node-centred cells: halfway between nodes, the outer nodes on the edges.
fn cell_edges(nodes: &[f64]) -> Vec<f64> {
    let n = nodes.len();
    let mut edges = Vec::with_capacity(n + 1);
    edges.push(nodes[0]);
    edges.extend(nodes.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    edges.push(nodes[n - 1]);
    edges
}

/// Side column width for a colour bar (px).
const BAR_WIDTH: u32 = 130;

fn draw_chart<DB: DrawingBackend>(c: &Chart, area: &DrawingArea<DB, Shift>) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let area = if c.title.is_empty() {
        area.clone()
    } else {
        let (top, rest) = area.split_vertically(30);
        top.draw_text(
            &c.title,
            &(FAMILY, 17).into_font().color(&RGBColor(30, 30, 30)),
            (20, 8),
        )
        .map_err(e)?;
        rest
    };
    let entries = legend_entries(c);
    let (w, _) = area.dim_in_pixel();
    let legend_w = match c.legend {
        LegendPlace::Right if !entries.is_empty() => legend_width(&area, &entries) + 16,
        _ => 0,
    };
    let bar_w = if c.color_scale.is_some() {
        BAR_WIDTH
    } else {
        0
    };
    let (main, side) = area.split_horizontally(w.saturating_sub(legend_w + bar_w).max(100));
    let (bar_area, legend_area) = side.split_horizontally(bar_w);
    let (x0, x1) = c.x.range;
    let (y0, y1) = c.y.range;
    if !(x0.is_finite() && x1.is_finite() && x1 > x0 && y0.is_finite() && y1.is_finite() && y1 > y0)
    {
        return Err(format!(
            "chart '{}': axis ranges must be finite and increasing",
            c.title
        ));
    }
    let mut chart = ChartBuilder::on(&main)
        .margin_left(12)
        .margin_right(16)
        .margin_top(10)
        .margin_bottom(4)
        .x_label_area_size(52)
        .y_label_area_size(84)
        .build_cartesian_2d(TickedRange::new(&c.x), TickedRange::new(&c.y))
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(c.x.label.as_str())
        .y_desc(c.y.label.as_str())
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17))
        .bold_line_style(RGBColor(220, 220, 220))
        .draw()
        .map_err(e)?;
    for r in &c.regions {
        chart
            .draw_series(std::iter::once(Polygon::new(
                r.polygon.clone(),
                rgb(r.color).filled(),
            )))
            .map_err(e)?;
    }
    if let (Some(grid), Some(scale)) = (&c.map, &c.color_scale) {
        draw_map(&mut chart, grid, scale)?;
    }
    if let (Some(grid), Some(ct)) = (&c.map, &c.contours) {
        for (levels, width) in [(&ct.levels, 1u32), (&ct.bold, 2)] {
            for &level in levels {
                for line in contour_lines(grid, level) {
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            line,
                            rgb(ct.color).mix(0.75).stroke_width(width),
                        )))
                        .map_err(e)?;
                }
            }
        }
    }
    for line in &c.outlines {
        for seg in clip_polyline(line, y0, y1) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    seg,
                    RGBColor(150, 150, 150).stroke_width(1),
                )))
                .map_err(e)?;
        }
    }
    draw_series_set(&mut chart, &c.series, (y0, y1))?;
    if let (Some(sc), Some(scale)) = (&c.scatter, &c.color_scale) {
        let r = sc.radius as i32;
        for &(x, y, v) in &sc.points {
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            let Some(col) = scale.color(v) else { continue };
            chart
                .draw_series([
                    Circle::new((x, y), r, rgb(col).filled()),
                    Circle::new((x, y), r, RGBColor(60, 60, 60).stroke_width(1)),
                ])
                .map_err(e)?;
        }
    }
    for n in &c.notes {
        let font = (FAMILY, n.size)
            .into_font()
            .color(&rgb(n.color))
            .pos(Pos::new(HPos::Center, VPos::Center));
        if n.boxed {
            let (tw, th) = area.estimate_text_size(&n.text, &font).map_err(e)?;
            let (px, py) = chart.backend_coord(&n.at);
            let (ax, ay) = main.get_base_pixel();
            let (hw, hh) = (tw as i32 / 2 + 5, th as i32 / 2 + 3);
            main.draw(&Rectangle::new(
                [(px - ax - hw, py - ay - hh), (px - ax + hw, py - ay + hh)],
                WHITE.mix(0.85).filled(),
            ))
            .map_err(e)?;
        }
        chart
            .draw_series(std::iter::once(Text::new(n.text.clone(), n.at, font)))
            .map_err(e)?;
    }
    let plot_area = chart.plotting_area().strip_coord_spec();
    match c.legend {
        LegendPlace::None => {}
        LegendPlace::Right => {
            let (_, top) = plot_area.get_base_pixel();
            let (_, base) = legend_area.get_base_pixel();
            draw_legend(&legend_area, &entries, (8, top - base), false)?;
        }
        LegendPlace::Inside(corner) => {
            let (pw, ph) = plot_area.dim_in_pixel();
            let lw = legend_width(&plot_area, &entries) as i32;
            let lh = LEGEND_ROW * entries.len() as i32 + 8;
            let (pw, ph) = (pw as i32, ph as i32);
            let at = match corner {
                Legend::UpperRight => (pw - lw - 10, 10),
                Legend::LowerRight => (pw - lw - 10, ph - lh - 10),
                Legend::UpperLeft => (10, 10),
                Legend::LowerLeft => (10, ph - lh - 10),
            };
            draw_legend(&plot_area, &entries, at, true)?;
        }
    }
    if let Some(scale) = &c.color_scale {
        let (_, top) = plot_area.get_base_pixel();
        let (_, ph) = plot_area.dim_in_pixel();
        let (_, base) = bar_area.get_base_pixel();
        draw_color_bar(&bar_area, scale, top - base, ph)?;
    }
    Ok(())
}

fn draw_map<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<TickedRange, TickedRange>>,
    grid: &Grid,
    scale: &ColorScale,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let (nx, ny) = (grid.xs.len(), grid.ys.len());
    if nx == 0 || ny == 0 || grid.values.len() != nx * ny {
        return Err("colour map: grid values do not match its nodes".into());
    }
    let xe = cell_edges(&grid.xs);
    let ye = cell_edges(&grid.ys);
    // Runs of equal colour along x are one rectangle, and a run repeated exactly in the next
    // rows extends it upwards (few elements in an SVG).
    type Run = (usize, usize, (u8, u8, u8));
    let mut open: BTreeMap<Run, usize> = BTreeMap::new();
    let mut rects = Vec::new();
    let mut flush = |run: Run, j0: usize, j1: usize| {
        rects.push(Rectangle::new(
            [(xe[run.0], ye[j0]), (xe[run.1], ye[j1])],
            rgb(run.2).filled(),
        ))
    };
    for j in 0..ny {
        let mut row: Vec<Run> = Vec::new();
        let mut i = 0;
        while i < nx {
            let col = scale.color(grid.value(i, j));
            let mut k = i + 1;
            while k < nx && scale.color(grid.value(k, j)) == col {
                k += 1;
            }
            if let Some(col) = col {
                row.push((i, k, col));
            }
            i = k;
        }
        let ended: Vec<Run> = open
            .keys()
            .filter(|r| row.binary_search(r).is_err())
            .copied()
            .collect();
        for run in ended {
            if let Some(j0) = open.remove(&run) {
                flush(run, j0, j);
            }
        }
        for run in row {
            open.entry(run).or_insert(j);
        }
    }
    for (run, j0) in std::mem::take(&mut open) {
        flush(run, j0, ny);
    }
    chart.draw_series(rects).map_err(e)?;
    Ok(())
}

/// The colour bar of `scale` in `area`, its bar spanning `height` px from `top` (area pixels).
fn draw_color_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: &ColorScale,
    top: i32,
    height: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let (bx0, bx1) = (10, 34);
    let (by0, by1) = (top, top + height as i32);
    let steps = if scale.bands > 0 { scale.bands } else { 200 };
    for k in 0..steps {
        let (t0, t1) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        let col = if scale.bands > 0 {
            scale.colormap.at((k as f64 + 0.5) / steps as f64)
        } else {
            scale.colormap.at(0.5 * (t0 + t1))
        };
        let ya = by1 - (t0 * height as f64).round() as i32;
        let yb = by1 - (t1 * height as f64).round() as i32;
        area.draw(&Rectangle::new([(bx0, yb), (bx1, ya)], rgb(col).filled()))
            .map_err(e)?;
    }
    area.draw(&Rectangle::new(
        [(bx0, by0), (bx1, by1)],
        BLACK.stroke_width(1),
    ))
    .map_err(e)?;
    let font = (FAMILY, 14)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (v, label) in &scale.ticks {
        let Some(t) = scale.position(*v) else {
            continue;
        };
        let y = by1 - (t * height as f64).round() as i32;
        area.draw(&PathElement::new(
            vec![(bx1, y), (bx1 + 5, y)],
            BLACK.stroke_width(1),
        ))
        .map_err(e)?;
        area.draw_text(label, &font, (bx1 + 8, y)).map_err(e)?;
    }
    let desc = (FAMILY, 16)
        .into_font()
        .color(&BLACK)
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw_text(&scale.label, &desc, (112, (by0 + by1) / 2))
        .map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_ticks_are_round_and_inside() {
        let t = nice_ticks(0.1, 3.5, 6);
        let v: Vec<f64> = t.iter().map(|t| t.0).collect();
        assert_eq!(v, vec![0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5]);
        assert_eq!(t[0].1, "0.5");
        let t = nice_ticks(-1.0, 1.0, 5);
        assert_eq!(t.first().map(|t| t.1.as_str()), Some("−1.0"));
        assert!(t.iter().any(|t| t.1 == "0.0"));
    }

    #[test]
    fn contours_of_a_plane_are_straight_lines_at_the_level() {
        // f = x + 2y on a 11 x 7 grid: the level set x + 2y = 1.3 is one straight line.
        let xs: Vec<f64> = (0..11).map(|i| i as f64 * 0.1).collect();
        let ys: Vec<f64> = (0..7).map(|j| j as f64 * 0.1).collect();
        let values = xs
            .iter()
            .flat_map(|x| ys.iter().map(move |y| x + 2.0 * y))
            .collect();
        let g = Grid { xs, ys, values };
        let lines = contour_lines(&g, 1.3);
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(lines[0].len() > 5);
        for &(x, y) in &lines[0] {
            assert!((x + 2.0 * y - 1.3).abs() < 1e-12, "({x}, {y})");
        }
        // Endpoints on the grid's boundary.
        let on_edge = |(x, y): (f64, f64)| {
            x.abs() < 1e-12 || (x - 1.0).abs() < 1e-12 || y.abs() < 1e-12 || (y - 0.6).abs() < 1e-12
        };
        assert!(on_edge(lines[0][0]) && on_edge(*lines[0].last().unwrap()));
        assert!(contour_lines(&g, 5.0).is_empty());
    }

    #[test]
    fn a_closed_contour_closes() {
        // f = x² + y² on [−1, 1]²: the level 0.25 is a closed ring.
        let xs: Vec<f64> = (0..21).map(|i| -1.0 + 0.1 * i as f64).collect();
        let ys = xs.clone();
        let values = xs
            .iter()
            .flat_map(|x| ys.iter().map(move |y| x * x + y * y))
            .collect();
        let lines = contour_lines(&Grid { xs, ys, values }, 0.25);
        assert_eq!(lines.len(), 1);
        let l = &lines[0];
        assert_eq!(l.first(), l.last(), "ring is closed");
        for &(x, y) in l {
            assert!(((x * x + y * y).sqrt() - 0.5).abs() < 0.02);
        }
    }

    #[test]
    fn colour_bands_quantise_and_log_scale_clamps() {
        let s = ColorScale {
            label: String::new(),
            colormap: Colormap::Sequential,
            scale: Scale::Log10,
            range: (1e-8, 1e-4),
            bands: 4,
            ticks: Vec::new(),
        };
        assert_eq!(s.position(1e-6), Some(0.5));
        assert_eq!(s.position(0.0), Some(0.0));
        assert_eq!(s.position(1.0), Some(1.0));
        assert_eq!(s.position(f64::NAN), None);
        assert_eq!(s.color(2e-6), s.color(5e-6));
        assert_ne!(s.color(2e-6), s.color(2e-5));
        assert_eq!(Colormap::Diverging.at(0.5), (247, 247, 247));
    }
}
