//! Drawing a [`Sheet`] with `plotters`: the frame, each chart's colour map, contours,
//! regions, outlines, series, scatter, notes, legend and colour bar, written as PNG or SVG
//! through `oblique_output`.

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{contour_lines, nice_ticks, Axis, Chart, ColorScale, Grid, LegendPlace, Sheet, Ticks};
use crate::{clip_polyline, draw_series_set, register_font, rgb, Legend, PlotError, Style};
use crate::{draw_frame, FAMILY};

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
/// `oblique_output` like [`render`](crate::render).
pub fn render_sheet(sheet: &Sheet, path: &Path) -> Result<(), PlotError> {
    let mut files = oblique_output::Files::new();
    render_sheet_into(sheet, path, &mut files)?;
    Ok(files.commit()?)
}

/// Draw a sheet for `path` (`.png` or `.svg`) into a set of files that are put in place
/// together ([`oblique_output::Files`]), like [`render_into`](crate::render_into).
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
    let format = crate::format_of(path)?;
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
