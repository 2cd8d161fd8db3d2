//! Sheets: one or more charts, each with its own axes, stacked vertically under a title and over
//! caption lines. A chart can carry a colour map of a grid with contour lines, filled regions,
//! thin outlines, line/marker series, points coloured by a value, text notes, a colour bar and a
//! legend. Like [`Figure`](super::Figure), a [`Sheet`] is plain data; [`render_sheet`] draws it.
//!
//! Axes take fixed ticks with any labels, so a compactified axis can put `∞` at its end.
//!
//! The data model is here; the ticks and contour lines are computed in `sheet/geometry.rs`,
//! the drawing is `sheet/draw.rs`.

mod draw;
mod geometry;

pub use draw::{render_sheet, render_sheet_into};
pub use geometry::{contour_lines, nice_ticks};

use super::{Legend, Series};

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

#[cfg(test)]
mod tests {
    use super::*;

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
