//! Figures as PNG and SVG: line panels (orbits, time series), log–log panels (work–precision)
//! and histograms.
//!
//! A [`Figure`] is a grid of [`Panel`]s with `columns` columns and one overall title.
//! [`write_figure`] draws it twice, to `<stem>.png` and to `<stem>.svg` (text stays text, so
//! labels can be searched; plotters snaps SVG coordinates to whole pixels, so curves there look
//! slightly jagged). The PNG is drawn at twice its size and each 2 × 2 block averaged: plotters'
//! raster lines have whole-pixel vertices and wide lines no anti-aliasing, and the averaging
//! smooths both. Polylines are drawn segment by segment in the PNG (plotters turns a wide
//! polyline into one polygon, which spikes where a noisy series zig-zags). Series are thinned
//! to what the pixels can show (see `thin`), so a 30,000-step time series stays a small SVG.
//! Text uses the embedded DejaVu Sans font, so no system font library is needed.
//!
//! # Data checks
//!
//! Nothing is drawn from bad data: a non-finite point is a [`PlotError::NonFinite`] naming the
//! panel, the series and the index; a point ≤ 0 on a logarithmic axis is a
//! [`PlotError::NonPositiveOnLogAxis`]; a panel without any finite point is
//! [`PlotError::NoData`]. An empty series is allowed (it appears in the legend only).
//!
//! # Axes
//!
//! Ticks are chosen here, not by plotters: a step of 1, 2, 2.5 or 5 × 10ᵏ with as many ticks as
//! fit the axis length without the labels touching. All labels of an axis share one format:
//! fixed-point with as many decimals as the step needs, or scientific (`1.5e-17`) when the
//! largest label is ≥ 10⁵ or < 10⁻³. Ranges are padded by 5 % of the span on each side.
//! Degenerate ranges are widened so that the axis stays readable:
//!
//! * constant data v ≠ 0 gets the range v ± 5 % |v| (so a constant 1e-17 gives 0.95e-17 …
//!   1.05e-17), constant 0 gets −1 … 1;
//! * data whose span is tiny against its magnitude (more than 6 significant digits would be
//!   needed in the labels, e.g. an energy −0.25 ± 1e-12) is drawn relative to a round offset
//!   c: the ticks show v − c and the axis title says `… − (c)`.
//!
//! With `equal_aspect` one data unit has the same length in pixels on both axes (the shorter
//! range is widened about its centre), so circles drawn to scale are round.
//!
//! Logarithmic axes (only in [`Panel::Log`]) place ticks at 10ᵏ (every n-th decade when there
//! are many) or at 1, 2, 5 × 10ᵏ when the data span less than about two decades.
//!
//! # Layout
//!
//! Each panel is [`PANEL_WIDTH`] × [`PANEL_HEIGHT`] pixels; the legend (series and labelled
//! circles) sits in a column to the right of the plotting area, so it never covers data.
//! Series colours follow the Okabe–Ito colour-blind-safe palette by index in the panel; circle
//! k has the colour of series k (a body's outline matches its orbit) and is dashed.

use std::ffi::OsString;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontStyle;

/// Width of one panel in pixels.
pub const PANEL_WIDTH: u32 = 780;
/// Height of one panel in pixels.
pub const PANEL_HEIGHT: u32 = 470;
/// Height of the figure's title band in pixels.
const TITLE_HEIGHT: u32 = 50;

const FONT: &str = "sans-serif";
const FIGURE_TITLE_SIZE: f64 = 28.0;
const PANEL_TITLE_SIZE: f64 = 21.0;
const AXIS_TITLE_SIZE: f64 = 18.0;
const TICK_SIZE: f64 = 15.0;
const LEGEND_SIZE: f64 = 16.0;

/// Okabe–Ito palette reordered for a white background (its yellow, too pale on white, left
/// out), then grey and two of Tol's muted colours (wine, olive). Series 11 and later reuse the
/// colours with another marker shape (circle, square, triangle).
const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(128, 128, 128), // grey
    RGBColor(136, 34, 85),   // wine
    RGBColor(153, 153, 51),  // olive
];

/// The PNG is drawn at this multiple of its size and averaged down (anti-aliased curves;
/// plotters' raster lines have whole-pixel vertices).
const SUPERSAMPLE: u32 = 2;

thread_local! {
    /// Pixels per layout pixel of the figure being drawn (1 for SVG, [`SUPERSAMPLE`] for PNG).
    static SCALE: std::cell::Cell<f64> = const { std::cell::Cell::new(1.0) };
}

/// A length in layout pixels, in drawn pixels.
fn px(v: f64) -> f64 {
    v * SCALE.with(|s| s.get())
}

fn pxi(v: i32) -> i32 {
    px(v as f64).round() as i32
}

fn pxu(v: u32) -> u32 {
    px(v as f64).round() as u32
}

/// Colour and marker shape of series `k`.
fn look(k: usize) -> (RGBColor, usize) {
    (PALETTE[k % PALETTE.len()], k / PALETTE.len())
}

/// A filled marker (circle, square or triangle by `shape`) centred at `at`.
fn draw_marker<DB: DrawingBackend, CT: CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    at: CT::From,
    shape: usize,
    colour: RGBColor,
) -> Result<(), DrawError>
where
    CT::From: Clone,
{
    let style = colour.filled();
    let (r, t) = (pxi(3), pxi(4));
    match shape % 3 {
        0 => area.draw(&(EmptyElement::at(at) + plotters::element::Circle::new((0, 0), r, style))),
        1 => area.draw(&(EmptyElement::at(at) + Rectangle::new([(-r, -r), (r, r)], style))),
        _ => {
            area.draw(&(EmptyElement::at(at) + Polygon::new(vec![(0, -t), (t, r), (-t, r)], style)))
        }
    }
    .map_err(err)
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// Solid line through the points in order (a series of a single point gets a dot, so
    /// that it is seen).
    Line,
    /// Dashed line through the points in order (a single point gets a dot).
    Dashed,
    /// A filled dot at each point.
    Points,
    /// Solid line through the points with a dot at each (measured settings of a sweep).
    LinePoints,
}

/// One named curve (colour chosen by its index in the panel, from a colour-blind-safe palette).
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text (an empty label leaves the series out of the legend).
    pub label: String,
    /// (x, y) in data units.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Style,
}

/// A circle drawn to scale (a body's outline in its equatorial plane), dashed.
#[derive(Debug, Clone)]
pub struct Circle {
    /// Centre in data units.
    pub centre: (f64, f64),
    /// Radius in data units (≥ 0).
    pub radius: f64,
    /// Legend text, if any.
    pub label: Option<String>,
}

/// A panel of curves.
#[derive(Debug, Clone)]
pub struct LinePanel {
    /// Title above the panel.
    pub title: String,
    /// Horizontal axis title, with units, e.g. "x (length units)".
    pub x_label: String,
    /// Vertical axis title, with units.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
    /// Circles drawn to scale (linear panels only).
    pub circles: Vec<Circle>,
    /// Same scale on both axes (orbits).
    pub equal_aspect: bool,
}

/// A histogram of values.
#[derive(Debug, Clone)]
pub struct HistogramPanel {
    /// Title above the panel.
    pub title: String,
    /// Horizontal axis title (the quantity binned, with units).
    pub x_label: String,
    /// Vertical axis title, usually "count".
    pub y_label: String,
    /// The values (all must be finite).
    pub values: Vec<f64>,
    /// Number of equal-width bins spanning the values (≥ 1).
    pub bins: usize,
}

/// One panel of a figure.
#[derive(Debug, Clone)]
pub enum Panel {
    /// Curves on linear axes.
    Lines(LinePanel),
    /// A histogram.
    Histogram(HistogramPanel),
    /// Curves with either axis logarithmic (base 10), e.g. error against time. Circles and
    /// `equal_aspect` are not supported here and are rejected.
    Log {
        /// The curves.
        lines: LinePanel,
        /// Logarithmic horizontal axis.
        log_x: bool,
        /// Logarithmic vertical axis.
        log_y: bool,
    },
}

/// A figure: panels laid out in a grid with `columns` columns, one overall title.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Title above all panels.
    pub title: String,
    /// Panels, filled row by row.
    pub panels: Vec<Panel>,
    /// Number of columns (≥ 1).
    pub columns: usize,
}

/// Why a figure could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// The figure has no panels.
    #[error("figure \"{figure}\" has no panels")]
    EmptyFigure {
        /// Figure title.
        figure: String,
    },
    /// The layout is impossible (zero columns, a circle on a log panel, …).
    #[error("figure \"{figure}\": {reason}")]
    Layout {
        /// Figure title.
        figure: String,
        /// What to change.
        reason: String,
    },
    /// A series (or circle, or histogram) holds a NaN or infinity.
    #[error("panel \"{panel}\", series \"{series}\": non-finite value at index {index} ({value})")]
    NonFinite {
        /// Panel title.
        panel: String,
        /// Series label (or "circle k", or "values" for a histogram).
        series: String,
        /// Index of the first offending point.
        index: usize,
        /// The offending point, as text.
        value: String,
    },
    /// A value ≤ 0 on a logarithmic axis.
    #[error(
        "panel \"{panel}\", series \"{series}\": value at index {index} ({value}) is not \
         positive, but the {axis} axis is logarithmic"
    )]
    NonPositiveOnLogAxis {
        /// Panel title.
        panel: String,
        /// Series label.
        series: String,
        /// Index of the first offending point.
        index: usize,
        /// The offending point, as text.
        value: String,
        /// "x" or "y".
        axis: &'static str,
    },
    /// A panel without any finite point to draw.
    #[error("panel \"{panel}\" has no data points")]
    NoData {
        /// Panel title.
        panel: String,
    },
    /// A histogram with zero bins.
    #[error("histogram \"{panel}\" needs at least one bin")]
    NoBins {
        /// Panel title.
        panel: String,
    },
    /// Data whose span overflows f64 (e.g. −1e308 … 1e308).
    #[error("panel \"{panel}\": the data range of the {axis} axis is too wide to draw")]
    RangeTooWide {
        /// Panel title.
        panel: String,
        /// "x" or "y".
        axis: &'static str,
    },
    /// Writing a file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The drawing backend failed.
    #[error("drawing {path} failed: {message}")]
    Backend {
        /// The file being drawn.
        path: PathBuf,
        /// The backend's message.
        message: String,
    },
}

/// Writes `<stem>.png` and `<stem>.svg`; returns both paths (PNG first).
///
/// The extensions are appended to `stem` (so `out/fig.2` gives `out/fig.2.png`). The parent
/// folder must exist. All data are checked before anything is written.
pub fn write_figure(figure: &Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let prepared = prepare(figure)?;
    let png = with_extension(stem, "png");
    let svg = with_extension(stem, "svg");
    let size = prepared.size;

    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        draw_figure(&root, &prepared, Target::Svg, 1.0).map_err(|e| PlotError::Backend {
            path: svg.clone(),
            message: e.to_string(),
        })?;
        root.present().map_err(|e| PlotError::Backend {
            path: svg.clone(),
            message: e.to_string(),
        })?;
    }
    std::fs::write(&svg, text).map_err(|source| PlotError::Io {
        path: svg.clone(),
        source,
    })?;

    let backend_error = |message: String| PlotError::Backend {
        path: png.clone(),
        message,
    };
    let big_size = (size.0 * SUPERSAMPLE, size.1 * SUPERSAMPLE);
    let mut big = vec![0u8; 3 * big_size.0 as usize * big_size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut big, big_size).into_drawing_area();
        draw_figure(&root, &prepared, Target::Png, SUPERSAMPLE as f64)
            .map_err(|e| backend_error(e.to_string()))?;
        root.present().map_err(|e| backend_error(e.to_string()))?;
    }
    let small = downsample(&big, size, SUPERSAMPLE);
    {
        let mut backend = BitMapBackend::new(&png, size);
        backend
            .blit_bitmap((0, 0), size, &small)
            .map_err(|e| backend_error(e.to_string()))?;
        backend
            .present()
            .map_err(|e| backend_error(e.to_string()))?;
    }
    Ok(vec![png, svg])
}

/// Averages `factor` × `factor` blocks of an RGB image of `size` × `factor` pixels.
fn downsample(big: &[u8], size: (u32, u32), factor: u32) -> Vec<u8> {
    let (w, h) = (size.0 as usize, size.1 as usize);
    let f = factor as usize;
    let big_w = w * f;
    let mut out = vec![0u8; 3 * w * h];
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut sum = 0u32;
                for dy in 0..f {
                    for dx in 0..f {
                        sum += big[3 * ((y * f + dy) * big_w + x * f + dx) + c] as u32;
                    }
                }
                out[3 * (y * w + x) + c] = ((sum + (f * f / 2) as u32) / (f * f) as u32) as u8;
            }
        }
    }
    out
}

fn with_extension(stem: &Path, ext: &str) -> PathBuf {
    let mut s: OsString = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// Registers DejaVu Sans as plotters' "sans-serif" once per process.
fn register_fonts() -> Result<(), DrawError> {
    static DONE: OnceLock<Result<(), DrawError>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
            .map_err(|_| DrawError::Font("DejaVu Sans"))?;
        plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold())
            .map_err(|_| DrawError::Font("DejaVu Sans Bold"))?;
        Ok(())
    })
    .clone()
}

// ---------------------------------------------------------------------------------------------
// Validation and preparation (no drawing): everything that can fail on data fails here.

/// A figure checked and reduced to what the drawing code needs.
struct Prepared {
    title: String,
    size: (u32, u32),
    columns: usize,
    rows: usize,
    panels: Vec<PreparedPanel>,
}

enum PreparedPanel {
    Lines(PreparedLines),
    Histogram(PreparedHistogram),
}

struct PreparedLines {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<PreparedSeries>,
    circles: Vec<(Circle, usize)>,
    equal_aspect: bool,
    log_x: bool,
    log_y: bool,
    /// Data bounds (transformed): x range, y range; None when only empty series.
    bounds: ((f64, f64), (f64, f64)),
}

/// A series with its points already transformed (log10 on log axes).
struct PreparedSeries {
    points: Vec<(f64, f64)>,
    style: Style,
    /// Index in the panel (chooses the colour).
    index: usize,
    label: String,
}

struct PreparedHistogram {
    title: String,
    x_label: String,
    y_label: String,
    /// Bin edges lo, width, counts.
    lo: f64,
    width: f64,
    counts: Vec<usize>,
    /// Range of the values (for the axis).
    bounds: (f64, f64),
}

fn prepare(figure: &Figure) -> Result<Prepared, PlotError> {
    if figure.panels.is_empty() {
        return Err(PlotError::EmptyFigure {
            figure: figure.title.clone(),
        });
    }
    if figure.columns == 0 {
        return Err(PlotError::Layout {
            figure: figure.title.clone(),
            reason: "columns must be at least 1".into(),
        });
    }
    let columns = figure.columns.min(figure.panels.len());
    let rows = figure.panels.len().div_ceil(columns);
    let mut panels = Vec::with_capacity(figure.panels.len());
    for panel in &figure.panels {
        panels.push(match panel {
            Panel::Lines(p) => PreparedPanel::Lines(prepare_lines(p, false, false, figure)?),
            Panel::Log {
                lines,
                log_x,
                log_y,
            } => PreparedPanel::Lines(prepare_lines(lines, *log_x, *log_y, figure)?),
            Panel::Histogram(h) => PreparedPanel::Histogram(prepare_histogram(h)?),
        });
    }
    let width = PANEL_WIDTH * columns as u32;
    let height = PANEL_HEIGHT * rows as u32 + TITLE_HEIGHT;
    Ok(Prepared {
        title: figure.title.clone(),
        size: (width, height),
        columns,
        rows,
        panels,
    })
}

fn fmt_point(p: (f64, f64)) -> String {
    format!("{:e}, {:e}", p.0, p.1)
}

fn prepare_lines(
    panel: &LinePanel,
    log_x: bool,
    log_y: bool,
    figure: &Figure,
) -> Result<PreparedLines, PlotError> {
    let log = log_x || log_y;
    if log && (panel.equal_aspect || !panel.circles.is_empty()) {
        return Err(PlotError::Layout {
            figure: figure.title.clone(),
            reason: format!(
                "panel \"{}\": circles and equal aspect need linear axes",
                panel.title
            ),
        });
    }
    let mut bounds = Bounds::default();
    let mut series = Vec::with_capacity(panel.series.len());
    for (k, s) in panel.series.iter().enumerate() {
        let mut points = Vec::with_capacity(s.points.len());
        for (i, &(x, y)) in s.points.iter().enumerate() {
            if !x.is_finite() || !y.is_finite() {
                return Err(PlotError::NonFinite {
                    panel: panel.title.clone(),
                    series: s.label.clone(),
                    index: i,
                    value: fmt_point((x, y)),
                });
            }
            for (is_log, v, axis) in [(log_x, x, "x"), (log_y, y, "y")] {
                if is_log && v <= 0.0 {
                    return Err(PlotError::NonPositiveOnLogAxis {
                        panel: panel.title.clone(),
                        series: s.label.clone(),
                        index: i,
                        value: fmt_point((x, y)),
                        axis,
                    });
                }
            }
            let p = (
                if log_x { x.log10() } else { x },
                if log_y { y.log10() } else { y },
            );
            bounds.add(p.0, p.1);
            points.push(p);
        }
        series.push(PreparedSeries {
            points,
            style: s.style,
            index: k,
            label: s.label.clone(),
        });
    }
    let mut circles = Vec::with_capacity(panel.circles.len());
    for (k, c) in panel.circles.iter().enumerate() {
        let (cx, cy) = c.centre;
        if !cx.is_finite() || !cy.is_finite() || !c.radius.is_finite() || c.radius < 0.0 {
            return Err(PlotError::NonFinite {
                panel: panel.title.clone(),
                series: c.label.clone().unwrap_or_else(|| format!("circle {k}")),
                index: 0,
                value: format!("centre ({}), radius {:e}", fmt_point(c.centre), c.radius),
            });
        }
        bounds.add(cx - c.radius, cy - c.radius);
        bounds.add(cx + c.radius, cy + c.radius);
        circles.push((c.clone(), k));
    }
    let Some(b) = bounds.get() else {
        return Err(PlotError::NoData {
            panel: panel.title.clone(),
        });
    };
    for (axis, (lo, hi)) in [("x", b.0), ("y", b.1)] {
        if !(hi - lo).is_finite() {
            return Err(PlotError::RangeTooWide {
                panel: panel.title.clone(),
                axis,
            });
        }
    }
    Ok(PreparedLines {
        title: panel.title.clone(),
        x_label: panel.x_label.clone(),
        y_label: panel.y_label.clone(),
        series,
        circles,
        equal_aspect: panel.equal_aspect,
        log_x,
        log_y,
        bounds: b,
    })
}

fn prepare_histogram(h: &HistogramPanel) -> Result<PreparedHistogram, PlotError> {
    if h.bins == 0 {
        return Err(PlotError::NoBins {
            panel: h.title.clone(),
        });
    }
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (i, &v) in h.values.iter().enumerate() {
        if !v.is_finite() {
            return Err(PlotError::NonFinite {
                panel: h.title.clone(),
                series: "values".into(),
                index: i,
                value: format!("{v}"),
            });
        }
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if h.values.is_empty() {
        return Err(PlotError::NoData {
            panel: h.title.clone(),
        });
    }
    if !(hi - lo).is_finite() {
        return Err(PlotError::RangeTooWide {
            panel: h.title.clone(),
            axis: "x",
        });
    }
    // Constant values: one visible bin around the value.
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        let half = if lo == 0.0 { 0.5 } else { 0.05 * lo.abs() };
        (lo - half, lo + half)
    };
    let width = (hi - lo) / h.bins as f64;
    let mut counts = vec![0usize; h.bins];
    for &v in &h.values {
        let k = (((v - lo) / width).floor() as isize).clamp(0, h.bins as isize - 1) as usize;
        counts[k] += 1;
    }
    Ok(PreparedHistogram {
        title: h.title.clone(),
        x_label: h.x_label.clone(),
        y_label: h.y_label.clone(),
        lo,
        width,
        counts,
        bounds: (lo, hi),
    })
}

#[derive(Default)]
struct Bounds {
    x: Option<(f64, f64)>,
    y: Option<(f64, f64)>,
}

impl Bounds {
    fn add(&mut self, x: f64, y: f64) {
        let grow = |r: &mut Option<(f64, f64)>, v: f64| {
            *r = Some(match *r {
                None => (v, v),
                Some((lo, hi)) => (lo.min(v), hi.max(v)),
            });
        };
        grow(&mut self.x, x);
        grow(&mut self.y, y);
    }

    fn get(&self) -> Option<((f64, f64), (f64, f64))> {
        Some((self.x?, self.y?))
    }
}

// ---------------------------------------------------------------------------------------------
// Axes: ranges, ticks and labels.

/// One axis ready to draw: the plotted range (in plotted units, i.e. after log10 and offset),
/// the ticks and their labels, the offset subtracted from the data, and the axis title.
#[derive(Debug, Clone)]
struct Axis {
    range: (f64, f64),
    ticks: Vec<f64>,
    labels: Vec<String>,
    minor: Vec<f64>,
    offset: f64,
    title: String,
}

impl Axis {
    fn label_for(&self, v: f64) -> String {
        let span = self.range.1 - self.range.0;
        self.ticks
            .iter()
            .zip(&self.labels)
            .find(|(t, _)| (**t - v).abs() <= 1e-9 * span)
            .map(|(_, l)| l.clone())
            .unwrap_or_default()
    }
}

/// Pads a data range by 5 % a side; widens degenerate ranges.
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else if lo == 0.0 {
        (-1.0, 1.0)
    } else {
        let pad = 0.05 * lo.abs();
        (lo - pad, lo + pad)
    }
}

/// A round offset near the middle of a range whose span is tiny against its magnitude, or 0.
fn offset_for(lo: f64, hi: f64) -> f64 {
    let span = hi - lo;
    let mag = lo.abs().max(hi.abs());
    if span <= 0.0 || mag == 0.0 || span > 1e-6 * mag {
        return 0.0;
    }
    let mid = 0.5 * (lo + hi);
    // Round the middle to a multiple of 10^k with 10^k just above the span.
    let k = span.log10().floor() as i32 + 1;
    let offset = if k < 0 {
        let p = 10f64.powi((-k).min(300));
        (mid * p).round() / p
    } else {
        let p = 10f64.powi(k.min(300));
        (mid / p).round() * p
    };
    if offset.is_finite() {
        offset
    } else {
        0.0
    }
}

/// "Nice" ticks in [lo, hi] with about `target` steps: step = {1, 2, 2.5, 5} × 10^e.
fn nice_ticks(lo: f64, hi: f64, target: usize) -> (Vec<f64>, f64) {
    let raw = (hi - lo) / target.max(1) as f64;
    let e = raw.log10().floor();
    let mag = 10f64.powf(e);
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let ticks = (first..=last).map(|k| k as f64 * step).collect();
    (ticks, step)
}

/// Formats ticks with one shared format chosen from the step and the largest magnitude.
fn format_ticks(ticks: &[f64], step: f64) -> Vec<String> {
    let maxabs = ticks.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    // Extra digit for steps like 2.5 × 10^e.
    let step_exp = step.log10().floor();
    let mantissa = step / 10f64.powf(step_exp);
    let extra = if (mantissa - 2.5).abs() < 1e-9 { 1 } else { 0 };
    let scientific = maxabs != 0.0 && !(1e-3..1e5).contains(&maxabs);
    ticks
        .iter()
        .map(|&t| {
            if t == 0.0 || t.abs() < 1e-9 * step {
                "0".to_string()
            } else if scientific {
                let max_exp = maxabs.log10().floor();
                let digits = ((max_exp - step_exp) as i32 + extra).clamp(0, 12) as usize;
                format!("{t:.digits$e}")
            } else {
                let decimals = ((-step_exp) as i32 + extra).clamp(0, 15) as usize;
                format!("{t:.decimals$}")
            }
        })
        .collect()
}

fn text_width(text: &str, size: f64) -> f64 {
    use plotters::style::FontDesc;
    FontDesc::new(FontFamily::Name(FONT), size, FontStyle::Normal)
        .box_size(text)
        .map(|(w, _)| w as f64)
        .unwrap_or(0.6 * size * text.chars().count() as f64)
}

/// Builds a linear axis over the (unpadded) data range for an axis `length` pixels long.
/// `horizontal` decides whether label widths or heights limit the tick count.
fn linear_axis(lo: f64, hi: f64, length: f64, horizontal: bool, title: &str) -> Axis {
    let offset = offset_for(lo, hi);
    let (lo, hi) = padded(lo - offset, hi - offset);
    linear_axis_on(lo, hi, length, horizontal, title, offset)
}

/// A linear axis on an already padded range.
fn linear_axis_on(
    lo: f64,
    hi: f64,
    length: f64,
    horizontal: bool,
    title: &str,
    offset: f64,
) -> Axis {
    let mut chosen = None;
    for target in (2..=10).rev() {
        let (ticks, step) = nice_ticks(lo, hi, target);
        let labels = format_ticks(&ticks, step);
        let need = if horizontal {
            labels
                .iter()
                .map(|l| text_width(l, TICK_SIZE) + 24.0)
                .fold(0.0, f64::max)
        } else {
            2.8 * TICK_SIZE
        };
        let fits = ticks.len() < 2 || need * ticks.len() as f64 <= length;
        if fits && ticks.len() >= 2 {
            chosen = Some((ticks, labels));
            break;
        }
        chosen.get_or_insert((ticks, labels));
    }
    let (ticks, labels) = chosen.unwrap_or_default();
    let title = if offset != 0.0 {
        format!("{title}  − ({})", offset)
    } else {
        title.to_string()
    };
    Axis {
        range: (lo, hi),
        ticks,
        labels,
        minor: Vec::new(),
        offset,
        title,
    }
}

/// A logarithmic axis over log10 data in [lo, hi].
fn log_axis(lo: f64, hi: f64, length: f64, horizontal: bool, title: &str) -> Axis {
    let (lo, hi) = if hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        (lo - 0.5, hi + 0.5)
    };
    let first = lo.ceil() as i64;
    let last = hi.floor() as i64;
    let decades = (last - first + 1).max(0) as usize;
    let slot = if horizontal {
        text_width("1e-10", TICK_SIZE) + 24.0
    } else {
        2.8 * TICK_SIZE
    };
    let max_ticks = ((length / slot).floor() as usize).max(2);
    let mut ticks = Vec::new();
    let mut minor = Vec::new();
    if decades >= 2 {
        let every = decades.div_ceil(max_ticks).max(1) as i64;
        for k in first..=last {
            if k.rem_euclid(every) == 0 {
                ticks.push(k as f64);
            }
            if every == 1 && decades <= 8 {
                for m in 2..10 {
                    let v = k as f64 + (m as f64).log10();
                    if v <= hi {
                        minor.push(v);
                    }
                }
            }
        }
        if every == 1 && decades <= 8 {
            for m in 2..10 {
                let v = (first - 1) as f64 + (m as f64).log10();
                if v >= lo {
                    minor.push(v);
                }
            }
        }
    } else {
        // Less than two decades: 1, 2, 5 × 10^k (and 3 when there is room).
        let mantissas: &[f64] = if max_ticks >= 8 {
            &[1.0, 2.0, 3.0, 5.0]
        } else {
            &[1.0, 2.0, 5.0]
        };
        for k in (lo.floor() as i64)..=(hi.ceil() as i64) {
            for &m in mantissas {
                let v = k as f64 + m.log10();
                if v >= lo && v <= hi {
                    ticks.push(v);
                }
            }
        }
        if ticks.len() < 2 {
            // Within one 1-2-5 cell: fall back to linear-looking ticks of the value.
            let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
            let (values, _) = nice_ticks(a, b, 4);
            ticks = values
                .into_iter()
                .filter(|v| *v > 0.0)
                .map(f64::log10)
                .collect();
        }
    }
    let plain = ticks.iter().all(|&v| (-3.0..5.0).contains(&v.floor()));
    let labels = ticks.iter().map(|&v| format_log_label(v, plain)).collect();
    Axis {
        range: (lo, hi),
        ticks,
        labels,
        minor,
        offset: 0.0,
        title: title.to_string(),
    }
}

/// Label for a tick at log10 value `v`: "1e-12", "2e-5", "0.5", "100".
fn format_log_label(v: f64, plain: bool) -> String {
    let value = 10f64.powf(v);
    let e = value.log10().floor();
    let mantissa = value / 10f64.powf(e);
    // Round to 3 significant digits and trim.
    let digits: usize = if (mantissa - mantissa.round()).abs() < 1e-6 {
        0
    } else {
        2
    };
    if plain {
        let decimals = ((-e) as i32 + digits as i32).max(0) as usize;
        let s = format!("{value:.decimals$}");
        trim_zeros(&s)
    } else {
        let m = format!("{mantissa:.digits$}");
        format!("{}e{}", trim_zeros(&m), e as i32)
    }
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

// ---------------------------------------------------------------------------------------------
// Drawing.

type Area<'a, DB> = DrawingArea<DB, Shift>;

/// Why drawing failed (inside [`write_figure`], which reports it with the file's path as
/// [`PlotError::Backend`]).
#[derive(Debug, Clone, thiserror::Error)]
enum DrawError {
    /// An embedded font could not be registered.
    #[error("the embedded {0} font could not be read")]
    Font(&'static str),
    /// The backend's message (its error type depends on the backend, so it is kept as text).
    #[error("{0}")]
    Backend(String),
}

fn err<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError::Backend(e.to_string())
}

/// What is being drawn: polylines are drawn whole in SVG (the viewer joins the segments) and
/// segment by segment in PNG (plotters' wide-polyline polygons spike at sharp zig-zags).
#[derive(Clone, Copy, PartialEq)]
enum Target {
    Svg,
    Png,
}

/// Sets [`SCALE`] while it lives.
struct ScaleGuard;

impl ScaleGuard {
    fn set(scale: f64) -> Self {
        SCALE.with(|s| s.set(scale));
        ScaleGuard
    }
}

impl Drop for ScaleGuard {
    fn drop(&mut self) {
        SCALE.with(|s| s.set(1.0));
    }
}

fn draw_figure<DB: DrawingBackend>(
    root: &Area<'_, DB>,
    fig: &Prepared,
    target: Target,
    scale: f64,
) -> Result<(), DrawError> {
    register_fonts()?;
    let _scale = ScaleGuard::set(scale);
    root.fill(&WHITE).map_err(err)?;
    let (title_band, body) = root.split_vertically(pxu(TITLE_HEIGHT));
    let (w, h) = title_band.dim_in_pixel();
    title_band
        .draw(&Text::new(
            fig.title.clone(),
            (w as i32 / 2, h as i32 / 2),
            TextStyle::from((FONT, px(FIGURE_TITLE_SIZE), FontStyle::Bold).into_font())
                .pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(err)?;
    let cells = body.split_evenly((fig.rows, fig.columns));
    for (panel, cell) in fig.panels.iter().zip(cells.iter()) {
        let cell = cell.margin(pxu(8), pxu(8), pxu(8), pxu(14));
        match panel {
            PreparedPanel::Lines(p) => draw_lines(&cell, p, target)?,
            PreparedPanel::Histogram(p) => draw_histogram(&cell, p)?,
        }
    }
    Ok(())
}

/// Space (pixels) taken by the x axis band (tick labels + axis title).
const X_AXIS_BAND: u32 = 62;

/// Width (pixels) of the y axis band for these tick labels.
fn y_band(labels: &[String]) -> u32 {
    let w = labels
        .iter()
        .map(|l| text_width(l, px(TICK_SIZE)))
        .fold(0.0, f64::max);
    (w + px(18.0 + AXIS_TITLE_SIZE + 18.0)).ceil() as u32
}

struct LegendEntry {
    label: String,
    colour: RGBColor,
    shape: usize,
    kind: LegendKind,
}

#[derive(Clone, Copy)]
enum LegendKind {
    Line,
    LinePoints,
    Dashed,
    Points,
    Circle,
}

fn legend_entries(p: &PreparedLines) -> Vec<LegendEntry> {
    let mut out = Vec::new();
    for PreparedSeries {
        style,
        index: k,
        label,
        ..
    } in &p.series
    {
        if !label.is_empty() {
            let (colour, shape) = look(*k);
            out.push(LegendEntry {
                label: label.clone(),
                colour,
                shape,
                kind: match style {
                    Style::Line => LegendKind::Line,
                    Style::Dashed => LegendKind::Dashed,
                    Style::Points => LegendKind::Points,
                    Style::LinePoints => LegendKind::LinePoints,
                },
            });
        }
    }
    for (c, k) in &p.circles {
        if let Some(label) = &c.label {
            out.push(LegendEntry {
                label: label.clone(),
                colour: look(*k).0,
                shape: 0,
                kind: LegendKind::Circle,
            });
        }
    }
    out
}

const LEGEND_SAMPLE: i32 = 36;

/// Splits off a legend column at the right of a panel (if there is a legend).
fn split_legend<'a, DB: DrawingBackend>(
    area: &Area<'a, DB>,
    entries: &[LegendEntry],
) -> (Area<'a, DB>, Option<Area<'a, DB>>) {
    if entries.is_empty() {
        return (area.clone(), None);
    }
    let text = entries
        .iter()
        .map(|e| text_width(&e.label, px(LEGEND_SIZE)))
        .fold(0.0, f64::max);
    let (w, _) = area.dim_in_pixel();
    let want = text as u32 + pxu(LEGEND_SAMPLE as u32 + 30);
    let legend_w = want.min(w * 2 / 5);
    let (left, right) = area.split_horizontally(w - legend_w);
    (left, Some(right))
}

fn draw_legend<DB: DrawingBackend>(
    area: &Area<'_, DB>,
    entries: &[LegendEntry],
    top: i32,
) -> Result<(), DrawError> {
    let (w, _) = area.dim_in_pixel();
    let line_h = px(LEGEND_SIZE * 1.6) as i32;
    let x0 = pxi(12);
    let sample = pxi(LEGEND_SAMPLE);
    let max_text = w as f64 - (x0 + sample + pxi(10)) as f64;
    for (i, e) in entries.iter().enumerate() {
        let y = pxi(top + 8) + i as i32 * line_h + line_h / 2;
        let style = ShapeStyle::from(e.colour).stroke_width(pxu(2));
        match e.kind {
            LegendKind::Line => area
                .draw(&PathElement::new(vec![(x0, y), (x0 + sample, y)], style))
                .map_err(err)?,
            LegendKind::LinePoints => {
                area.draw(&PathElement::new(vec![(x0, y), (x0 + sample, y)], style))
                    .map_err(err)?;
                draw_marker(area, (x0 + sample / 2, y), e.shape, e.colour)?;
            }
            LegendKind::Dashed | LegendKind::Circle => {
                let style = if matches!(e.kind, LegendKind::Circle) {
                    ShapeStyle::from(e.colour).stroke_width(pxu(1))
                } else {
                    style
                };
                let (dash, gap) = dash_pattern(e.kind);
                let mut x = x0;
                while x < x0 + sample {
                    let x1 = (x + dash).min(x0 + sample);
                    area.draw(&PathElement::new(vec![(x, y), (x1, y)], style))
                        .map_err(err)?;
                    x += dash + gap;
                }
            }
            LegendKind::Points => draw_marker(area, (x0 + sample / 2, y), e.shape, e.colour)?,
        }
        let label = shorten(&e.label, max_text);
        area.draw(&Text::new(
            label,
            (x0 + sample + pxi(8), y),
            TextStyle::from((FONT, px(LEGEND_SIZE)).into_font())
                .pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// Cuts a label to fit `max_width` pixels, ending it with "…".
fn shorten(text: &str, max_width: f64) -> String {
    if text_width(text, px(LEGEND_SIZE)) <= max_width {
        return text.to_string();
    }
    let mut chars: Vec<char> = text.chars().collect();
    while !chars.is_empty() {
        chars.pop();
        let s: String = chars.iter().collect::<String>() + "…";
        if text_width(&s, px(LEGEND_SIZE)) <= max_width {
            return s;
        }
    }
    "…".into()
}

fn dash_pattern(kind: LegendKind) -> (i32, i32) {
    match kind {
        LegendKind::Circle => (pxi(6), pxi(4)),
        _ => (pxi(10), pxi(6)),
    }
}

/// Draws the panel title; returns the area below it.
fn titled<'a, DB: DrawingBackend>(
    area: &Area<'a, DB>,
    title: &str,
) -> Result<Area<'a, DB>, DrawError> {
    let band = px(PANEL_TITLE_SIZE * 1.7) as u32;
    let (top, rest) = area.split_vertically(band);
    let (w, h) = top.dim_in_pixel();
    top.draw(&Text::new(
        title.to_string(),
        (w as i32 / 2, h as i32 / 2),
        TextStyle::from((FONT, px(PANEL_TITLE_SIZE)).into_font())
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))
    .map_err(err)?;
    Ok(rest)
}

fn draw_lines<DB: DrawingBackend>(
    cell: &Area<'_, DB>,
    p: &PreparedLines,
    target: Target,
) -> Result<(), DrawError> {
    let body = titled(cell, &p.title)?;
    let entries = legend_entries(p);
    let (plot_area, legend_area) = split_legend(&body, &entries);
    let (aw, ah) = plot_area.dim_in_pixel();
    let ((xlo, xhi), (ylo, yhi)) = p.bounds;

    // The plotting rectangle depends on the y band width, which depends on the y labels:
    // build the axes twice.
    let build = |plot_w: f64, plot_h: f64| -> (Axis, Axis) {
        if p.equal_aspect {
            let (x0, x1) = padded(xlo, xhi);
            let (y0, y1) = padded(ylo, yhi);
            let scale = ((x1 - x0) / plot_w).max((y1 - y0) / plot_h);
            let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
            let (hx, hy) = (0.5 * scale * plot_w, 0.5 * scale * plot_h);
            (
                linear_axis_on(cx - hx, cx + hx, plot_w, true, &p.x_label, 0.0),
                linear_axis_on(cy - hy, cy + hy, plot_h, false, &p.y_label, 0.0),
            )
        } else {
            let x = if p.log_x {
                log_axis(xlo, xhi, plot_w, true, &p.x_label)
            } else {
                linear_axis(xlo, xhi, plot_w, true, &p.x_label)
            };
            let y = if p.log_y {
                log_axis(ylo, yhi, plot_h, false, &p.y_label)
            } else {
                linear_axis(ylo, yhi, plot_h, false, &p.y_label)
            };
            (x, y)
        }
    };
    // Axes are laid out in layout pixels (tick label widths at the unscaled font size).
    let layout = |pixels: u32| pixels as f64 / px(1.0);
    let plot_h = layout(ah.saturating_sub(pxu(X_AXIS_BAND + 10)).max(pxu(40)));
    let guess_w = layout(aw.saturating_sub(pxu(90)).max(pxu(40)));
    let (_, y_axis) = build(guess_w, plot_h);
    let band = y_band(&y_axis.labels);
    let plot_w = layout(aw.saturating_sub(band + pxu(16)).max(pxu(40)));
    let (mut x_axis, mut y_axis) = build(plot_w, plot_h);
    // The y labels may have changed width with the new range; keep the band wide enough.
    let band = band.max(y_band(&y_axis.labels));
    if p.equal_aspect {
        let plot_w = layout(aw.saturating_sub(band + pxu(16)).max(pxu(40)));
        let axes = build(plot_w, plot_h);
        x_axis = axes.0;
        y_axis = axes.1;
    }

    let mut chart = ChartBuilder::on(&plot_area)
        .margin_top(pxu(10))
        .margin_right(pxu(16))
        .x_label_area_size(pxu(X_AXIS_BAND))
        .y_label_area_size(band)
        .build_cartesian_2d(coord(&x_axis), coord(&y_axis))
        .map_err(err)?;
    configure_mesh(&mut chart, &x_axis, &y_axis)?;

    let x_off = x_axis.offset;
    let y_off = y_axis.offset;
    let (pw, ph) = chart.plotting_area().dim_in_pixel();
    let pixels_per_unit = (
        pw as f64 / (x_axis.range.1 - x_axis.range.0),
        ph as f64 / (y_axis.range.1 - y_axis.range.0),
    );
    for PreparedSeries {
        points,
        style,
        index: k,
        ..
    } in &p.series
    {
        if points.is_empty() {
            continue;
        }
        let (colour, shape) = look(*k);
        let shifted: Vec<(f64, f64)> = points
            .iter()
            .map(|&(x, y)| (x - x_off, y - y_off))
            .collect();
        let thinned = if *style == Style::Points {
            shifted
        } else {
            thin(&shifted, pixels_per_unit, pw as usize)
        };
        let pts = thinned.iter().copied();
        let plotting = chart.plotting_area().clone();
        let dots = |pts: &mut dyn Iterator<Item = (f64, f64)>| -> Result<(), DrawError> {
            for c in pts {
                draw_marker(&plotting, c, shape, colour)?;
            }
            Ok(())
        };
        match style {
            Style::Line | Style::LinePoints if target == Target::Svg => {
                chart
                    .draw_series(LineSeries::new(pts, colour.stroke_width(pxu(2))))
                    .map_err(err)?;
            }
            Style::Line | Style::LinePoints => {
                let line = colour.stroke_width(pxu(2));
                chart
                    .draw_series(
                        thinned
                            .windows(2)
                            .map(|w| PathElement::new(vec![w[0], w[1]], line)),
                    )
                    .map_err(err)?;
            }
            Style::Dashed => {
                chart
                    .draw_series(DashedLineSeries::new(
                        pts,
                        pxi(10),
                        pxi(6),
                        colour.stroke_width(pxu(2)),
                    ))
                    .map_err(err)?;
            }
            Style::Points => dots(&mut pts.clone())?,
        }
        // Markers on top of the line.
        if *style == Style::LinePoints || (thinned.len() == 1 && *style != Style::Points) {
            dots(&mut shifted_points(points, x_off, y_off))?;
        }
    }
    for (c, k) in &p.circles {
        let colour = look(*k).0;
        let n = 240;
        let outline = (0..=n).map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            (
                c.centre.0 + c.radius * t.cos() - x_off,
                c.centre.1 + c.radius * t.sin() - y_off,
            )
        });
        let (dash, gap) = dash_pattern(LegendKind::Circle);
        chart
            .draw_series(DashedLineSeries::new(
                outline,
                dash,
                gap,
                colour.stroke_width(pxu(1)),
            ))
            .map_err(err)?;
    }
    if let Some(legend) = legend_area {
        draw_legend(&legend, &entries, 10)?;
    }
    Ok(())
}

/// A linear axis with the ticks chosen here (plotters' own f64 axis picks its own ticks).
#[derive(Clone)]
struct KeyCoord {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
    minor: Vec<f64>,
}

impl Ranged for KeyCoord {
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = (value - self.lo) / (self.hi - self.lo);
        let pixels = limit.0 as f64 + t * (limit.1 - limit.0) as f64;
        // Points far outside are clipped by the drawing area; keep the integer finite.
        pixels.round().clamp(-1e6, 1e6) as i32
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

fn shifted_points(
    points: &[(f64, f64)],
    x_off: f64,
    y_off: f64,
) -> impl Iterator<Item = (f64, f64)> + '_ {
    points.iter().map(move |&(x, y)| (x - x_off, y - y_off))
}

/// Drops points that cannot change the picture: for x-sorted series longer than four points per
/// pixel column, each column keeps its first, lowest, highest and last point (in order);
/// otherwise a point closer than 0.7 pixel to the last kept one is dropped (the last point is
/// always kept).
fn thin(points: &[(f64, f64)], pixels_per_unit: (f64, f64), columns: usize) -> Vec<(f64, f64)> {
    let (sx, sy) = pixels_per_unit;
    if points.len() < 3 {
        return points.to_vec();
    }
    let sorted = points.windows(2).all(|w| w[0].0 <= w[1].0);
    let mut out = Vec::with_capacity(points.len().min(8 * columns + 8));
    if sorted && points.len() > 4 * columns.max(1) {
        let column = |x: f64| ((x - points[0].0) * sx).floor() as i64;
        let mut start = 0;
        while start < points.len() {
            let c = column(points[start].0);
            let mut end = start + 1;
            while end < points.len() && column(points[end].0) == c {
                end += 1;
            }
            let group = &points[start..end];
            let (mut lo, mut hi) = (0, 0);
            for (i, p) in group.iter().enumerate() {
                if p.1 < group[lo].1 {
                    lo = i;
                }
                if p.1 > group[hi].1 {
                    hi = i;
                }
            }
            let mut keep = [0, lo.min(hi), lo.max(hi), group.len() - 1];
            keep.sort_unstable();
            let mut last = usize::MAX;
            for i in keep {
                if i != last {
                    out.push(group[i]);
                    last = i;
                }
            }
            start = end;
        }
        return out;
    }
    out.push(points[0]);
    for (i, &p) in points.iter().enumerate().skip(1) {
        let q = *out.last().unwrap_or(&p);
        let d = ((p.0 - q.0) * sx).hypot((p.1 - q.1) * sy);
        if d >= 0.7 || i == points.len() - 1 {
            out.push(p);
        }
    }
    out
}

fn coord(axis: &Axis) -> KeyCoord {
    KeyCoord {
        lo: axis.range.0,
        hi: axis.range.1,
        ticks: axis.ticks.clone(),
        minor: axis.minor.clone(),
    }
}

fn configure_mesh<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<KeyCoord, KeyCoord>>,
    x_axis: &Axis,
    y_axis: &Axis,
) -> Result<(), DrawError> {
    let fx = |v: &f64| x_axis.label_for(*v);
    let fy = |v: &f64| y_axis.label_for(*v);
    chart
        .configure_mesh()
        .x_desc(x_axis.title.clone())
        .y_desc(y_axis.title.clone())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style((FONT, px(TICK_SIZE)))
        .axis_desc_style((FONT, px(AXIS_TITLE_SIZE)))
        .bold_line_style(RGBColor(200, 200, 200).stroke_width(pxu(1)))
        .light_line_style(RGBColor(235, 235, 235).stroke_width(pxu(1)))
        .axis_style(RGBColor(60, 60, 60).stroke_width(pxu(1)))
        .set_all_tick_mark_size(pxi(5))
        .draw()
        .map_err(err)
}

fn draw_histogram<DB: DrawingBackend>(
    cell: &Area<'_, DB>,
    p: &PreparedHistogram,
) -> Result<(), DrawError> {
    let body = titled(cell, &p.title)?;
    let (aw, ah) = body.dim_in_pixel();
    let max_count = p.counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    let layout = |pixels: u32| pixels as f64 / px(1.0);
    let plot_h = layout(ah.saturating_sub(pxu(X_AXIS_BAND + 10)).max(pxu(40)));
    let y_axis = linear_axis_on(0.0, max_count * 1.08, plot_h, false, &p.y_label, 0.0);
    // Counts are integers: drop fractional ticks.
    let y_axis = integer_ticks(y_axis);
    let band = y_band(&y_axis.labels);
    let plot_w = layout(aw.saturating_sub(band + pxu(16)).max(pxu(40)));
    let x_axis = linear_axis(p.bounds.0, p.bounds.1, plot_w, true, &p.x_label);

    let mut chart = ChartBuilder::on(&body)
        .margin_top(pxu(10))
        .margin_right(pxu(16))
        .x_label_area_size(pxu(X_AXIS_BAND))
        .y_label_area_size(band)
        .build_cartesian_2d(coord(&x_axis), coord(&y_axis))
        .map_err(err)?;
    configure_mesh(&mut chart, &x_axis, &y_axis)?;
    let off = x_axis.offset;
    let fill = PALETTE[0].mix(0.75).filled();
    let edge = PALETTE[0].stroke_width(pxu(1));
    for (i, &n) in p.counts.iter().enumerate() {
        if n == 0 {
            continue;
        }
        let x0 = p.lo + p.width * i as f64 - off;
        let x1 = p.lo + p.width * (i + 1) as f64 - off;
        chart
            .draw_series([
                Rectangle::new([(x0, 0.0), (x1, n as f64)], fill),
                Rectangle::new([(x0, 0.0), (x1, n as f64)], edge),
            ])
            .map_err(err)?;
    }
    Ok(())
}

fn integer_ticks(mut axis: Axis) -> Axis {
    let keep: Vec<usize> = (0..axis.ticks.len())
        .filter(|&i| axis.ticks[i].fract() == 0.0)
        .collect();
    axis.ticks = keep.iter().map(|&i| axis.ticks[i]).collect();
    axis.labels = axis
        .ticks
        .iter()
        .map(|t| format!("{}", *t as i64))
        .collect();
    axis
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_ticks_cover_range_with_round_steps() {
        let (t, step) = nice_ticks(0.0, 300.0, 6);
        assert_eq!(step, 50.0);
        assert_eq!(t.first(), Some(&0.0));
        assert_eq!(t.last(), Some(&300.0));
    }

    #[test]
    fn tiny_values_get_scientific_labels() {
        let (t, step) = nice_ticks(0.95e-17, 1.05e-17, 4);
        let labels = format_ticks(&t, step);
        assert!(labels.iter().all(|l| l.contains("e-1")), "{labels:?}");
        // Distinct labels.
        let mut u = labels.clone();
        u.dedup();
        assert_eq!(u.len(), labels.len(), "{labels:?}");
    }

    #[test]
    fn offset_used_for_tiny_relative_span() {
        let off = offset_for(-0.25 - 1e-12, -0.25 + 1e-12);
        assert_eq!(off, -0.25);
        assert_eq!(offset_for(2.5, 7.0), 0.0);
    }

    #[test]
    fn log_labels_are_short() {
        assert_eq!(format_log_label(-12.0, false), "1e-12");
        assert_eq!(format_log_label(2.0, true), "100");
        assert_eq!(format_log_label(2f64.log10() - 5.0, false), "2e-5");
        assert_eq!(format_log_label(5f64.log10() - 1.0, true), "0.5");
    }
}
