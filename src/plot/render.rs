//! Rendering of [`Figure`] and [`Raster`] to files, with plotters.
//!
//! A figure is drawn twice from the same code: to SVG (scalable, text kept as text) and to
//! PNG (for Markdown viewers). Both are rendered in memory and written with
//! [`crate::io::write_atomic`], so a figure appears whole or not at all.
//!
//! Text uses DejaVu Sans, embedded by the `dejavu` crate and registered with plotters once
//! per process: the machines this runs on have no system fonts.
//!
//! Layout, from the top: the title (wrapped to the width), the chart, and a legend strip
//! below the chart, so the legend never hides data. Points that cannot be drawn
//! (non-finite, or non-positive on a logarithmic axis) are skipped and break a line;
//! lines are clipped to the axes' ranges.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::ranged1d::{
    KeyPointHint, KeyPointWeight, NoDefaultFormatting, Ranged, ValueFormatter,
};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{Axis, Figure, Point, Raster, Side, Style};
use crate::error::{Error, Result};

/// Width of every figure, pixels.
pub const WIDTH: u32 = 1000;
/// Height of the chart (axes, ticks and labels), pixels; the title and the legend add to it.
pub const CHART_HEIGHT: u32 = 620;

const FONT: &str = "sans-serif";
const TITLE_SIZE: f64 = 26.0;
const AXIS_LABEL_SIZE: f64 = 21.0;
const TICK_SIZE: f64 = 17.0;
const LEGEND_SIZE: f64 = 18.0;
const MARGIN: u32 = 18;
const LEGEND_ROW: u32 = 30;
const LEGEND_SAMPLE: i32 = 44;

/// Distinguishable colours (Okabe and Ito's colour-blind-safe set without yellow, then
/// three more), cycled in series order.
const COLOURS: [RGBColor; 10] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(120, 120, 120),
    RGBColor(140, 86, 75),
    RGBColor(128, 128, 0),
];

/// Renders `figure` into `dir` as `<name>.svg` and `<name>.png`; returns the paths.
pub fn render(figure: &Figure, dir: &Path) -> Result<Vec<PathBuf>> {
    check_stem("figure name", &figure.name)?;
    ensure_fonts()?;
    let layout = Layout::of(figure)?;
    let (w, h) = (WIDTH, layout.height());
    let fail = |path: &Path, e: String| Error::bad_file(path, format!("rendering: {e}"));

    let svg_path = dir.join(format!("{}.svg", figure.name));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        draw_figure(&root, figure, &layout).map_err(|e| fail(&svg_path, e.to_string()))?;
        root.present().map_err(|e| fail(&svg_path, e.to_string()))?;
    }
    crate::io::write_atomic(&svg_path, svg.as_bytes())?;

    let png_path = dir.join(format!("{}.png", figure.name));
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_figure(&root, figure, &layout).map_err(|e| fail(&png_path, e.to_string()))?;
        root.present().map_err(|e| fail(&png_path, e.to_string()))?;
    }
    write_png(&png_path, &rgb, w, h)?;
    Ok(vec![svg_path, png_path])
}

/// Renders `raster` into `dir` as `<name>.png`; returns the path.
///
/// Each grid point becomes a square of `s x s` pixels, with `s` chosen so that the map is
/// at least about 512 pixels wide; the palette is listed as a legend to its right, each
/// colour with its share of the grid points.
pub fn render_raster(raster: &Raster, dir: &Path) -> Result<Vec<PathBuf>> {
    check_stem("raster name", &raster.name)?;
    check_raster(raster)?;
    ensure_fonts()?;
    let path = dir.join(format!("{}.png", raster.name));
    let n = raster.n as u32;
    let scale = (512 / n).max(1);
    let map = n * scale;
    let legend_font = font(LEGEND_SIZE);
    let mut counts = vec![0usize; raster.palette.len()];
    for &c in &raster.pixels {
        counts[c as usize] += 1;
    }
    let labels: Vec<String> = raster
        .palette
        .iter()
        .zip(&counts)
        .map(|((_, label), &k)| {
            format!(
                "{label} ({:.1}%)",
                100.0 * k as f64 / raster.pixels.len() as f64
            )
        })
        .collect();
    let label_w = labels
        .iter()
        .map(|label| text_width(&legend_font, label))
        .max()
        .unwrap_or(0);
    let legend_w = 20 + 24 + 10 + label_w + MARGIN;
    let w = (MARGIN + map + legend_w).max(400);
    let title = wrap(
        &font(TITLE_SIZE).style(FontStyle::Bold),
        &raster.title,
        w - 2 * MARGIN,
    );
    let title_h = title_height(title.len());
    let legend_h = raster.palette.len() as u32 * LEGEND_ROW;
    let h = title_h + map.max(legend_h) + MARGIN;

    let mut rgb = vec![255u8; (w * h * 3) as usize];
    let (x0, y0) = (MARGIN, title_h);
    for (k, &c) in raster.pixels.iter().enumerate() {
        let colour = raster.palette[c as usize].0;
        let (row, col) = ((k / raster.n) as u32, (k % raster.n) as u32);
        for dy in 0..scale {
            let y = y0 + row * scale + dy;
            let start = ((y * w + x0 + col * scale) * 3) as usize;
            for px in rgb[start..start + (scale * 3) as usize].chunks_exact_mut(3) {
                px.copy_from_slice(&colour);
            }
        }
    }
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let draw = || -> std::result::Result<(), String> {
            draw_title(&root, &title).map_err(|e| e.to_string())?;
            let (mx, my) = (x0 as i32 - 1, y0 as i32 - 1);
            let frame = [(mx, my), (mx + map as i32 + 1, my + map as i32 + 1)];
            root.draw(&Rectangle::new(frame, BLACK))
                .map_err(|e| e.to_string())?;
            let lx = (MARGIN + map + 20) as i32;
            for (k, ((colour, _), label)) in raster.palette.iter().zip(&labels).enumerate() {
                let y = (title_h + k as u32 * LEGEND_ROW) as i32 + 4;
                let c = RGBColor(colour[0], colour[1], colour[2]);
                root.draw(&Rectangle::new([(lx, y), (lx + 22, y + 22)], c.filled()))
                    .map_err(|e| e.to_string())?;
                root.draw(&Rectangle::new([(lx, y), (lx + 22, y + 22)], BLACK))
                    .map_err(|e| e.to_string())?;
                root.draw(&Text::new(
                    label.clone(),
                    (lx + 32, y + 11),
                    TextStyle::from(legend_font.clone()).pos(Pos::new(HPos::Left, VPos::Center)),
                ))
                .map_err(|e| e.to_string())?;
            }
            root.present().map_err(|e| e.to_string())
        };
        draw().map_err(|e| Error::bad_file(&path, format!("rendering: {e}")))?;
    }
    write_png(&path, &rgb, w, h)?;
    Ok(vec![path])
}

/// Registers DejaVu Sans as plotters' sans-serif font, once per process.
fn ensure_fonts() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        let regular =
            plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let bold = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
        regular.is_ok() && bold.is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(
            "font",
            "DejaVu Sans (embedded)",
            "a font plotters can read",
        ))
    }
}

/// A file stem must be a plain name: no separators, not empty.
fn check_stem(field: &str, stem: &str) -> Result<()> {
    if stem.is_empty() || stem.contains(['/', '\\']) || stem == "." || stem == ".." {
        return Err(Error::invalid(
            field,
            format!("{stem:?}"),
            "a non-empty file stem without path separators",
        ));
    }
    Ok(())
}

fn check_raster(raster: &Raster) -> Result<()> {
    let field = |what: &str| format!("raster {}.{what}", raster.name);
    if raster.n == 0 {
        return Err(Error::invalid(&field("n"), 0, ">= 1"));
    }
    if raster.pixels.len() != raster.n * raster.n {
        return Err(Error::invalid(
            &field("pixels"),
            format!("{} values", raster.pixels.len()),
            format!("n^2 = {} values", raster.n * raster.n),
        ));
    }
    if raster.palette.is_empty() {
        return Err(Error::invalid(
            &field("palette"),
            "[]",
            "at least one colour",
        ));
    }
    if let Some(&bad) = raster
        .pixels
        .iter()
        .find(|&&c| c as usize >= raster.palette.len())
    {
        return Err(Error::invalid(
            &field("pixels"),
            format!("colour index {bad}"),
            format!("< the palette's {} colours", raster.palette.len()),
        ));
    }
    Ok(())
}

fn write_png(path: &Path, rgb: &[u8], w: u32, h: u32) -> Result<()> {
    use image::ImageEncoder;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| Error::bad_file(path, format!("encoding PNG: {e}")))?;
    crate::io::write_atomic(path, &bytes)
}

fn font(size: f64) -> FontDesc<'static> {
    FontDesc::new(FontFamily::SansSerif, size, FontStyle::Normal)
}

fn text_width(font: &FontDesc, text: &str) -> u32 {
    font.box_size(text).map(|(w, _)| w).unwrap_or(0)
}

/// Splits `text` into lines no wider than `width` pixels (at word boundaries).
fn wrap(font: &FontDesc, text: &str, width: u32) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && text_width(font, &candidate) > width {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = candidate;
        }
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

fn title_height(lines: usize) -> u32 {
    MARGIN + lines as u32 * (TITLE_SIZE as u32 + 8) + 6
}

fn draw_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    lines: &[String],
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (w, _) = root.dim_in_pixel();
    let style = TextStyle::from(font(TITLE_SIZE).style(FontStyle::Bold))
        .pos(Pos::new(HPos::Center, VPos::Top));
    for (k, line) in lines.iter().enumerate() {
        let y = MARGIN as i32 + k as i32 * (TITLE_SIZE as i32 + 8);
        root.draw(&Text::new(line.clone(), (w as i32 / 2, y), style.clone()))?;
    }
    Ok(())
}

/// One axis as drawn: its range in data units and its scale.
#[derive(Debug, Clone, PartialEq)]
struct AxisCoord {
    lo: f64,
    hi: f64,
    log: bool,
}

impl AxisCoord {
    /// The axis for `axis` and the values `values` it has to show.
    fn fit(axis: &Axis, values: impl Iterator<Item = f64>) -> Self {
        if let Some((lo, hi)) = axis.range {
            let ok = lo.is_finite() && hi.is_finite() && lo < hi && (!axis.log || lo > 0.0);
            if ok {
                return Self {
                    lo,
                    hi,
                    log: axis.log,
                };
            }
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| v.is_finite() && (!axis.log || *v > 0.0)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if axis.log {
            if lo > hi {
                (lo, hi) = (1.0, 10.0);
            } else if hi / lo < 1.0 + 1e-9 {
                (lo, hi) = (lo / 2.0, hi * 2.0);
            } else {
                let pad = (hi / lo).powf(0.04);
                (lo, hi) = (lo / pad, hi * pad);
            }
        } else if lo > hi {
            (lo, hi) = (0.0, 1.0);
        } else if hi - lo <= 1e-12 * lo.abs().max(hi.abs()) {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo, hi) = (lo - d, hi + d);
        } else {
            let pad = 0.05 * (hi - lo);
            (lo, hi) = (lo - pad, hi + pad);
        }
        Self {
            lo,
            hi,
            log: axis.log,
        }
    }

    /// Whether `v` can be drawn on this axis at all.
    fn drawable(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// Data value to axis space (`ln v` on a log axis).
    fn axis_of(&self, v: f64) -> f64 {
        if self.log {
            v.ln()
        } else {
            v
        }
    }

    fn data_of(&self, t: f64) -> f64 {
        if self.log {
            t.exp()
        } else {
            t
        }
    }

    fn t_range(&self) -> (f64, f64) {
        (self.axis_of(self.lo), self.axis_of(self.hi))
    }

    fn contains(&self, v: f64) -> bool {
        self.drawable(v) && v >= self.lo && v <= self.hi
    }

    fn clamp(&self, v: f64) -> f64 {
        v.clamp(self.lo, self.hi)
    }

    /// Tick positions on a logarithmic axis: powers of ten (every k-th decade when there are
    /// many), filled in with 2 and 5 or with every integer multiple when that gives fewer
    /// than four ticks; nice linear ticks when even those give fewer than three.
    fn log_ticks(&self, max_points: usize, light: bool) -> Vec<f64> {
        let (lo, hi) = (self.lo, self.hi);
        let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        let decades = (e1 - e0).max(1) as usize;
        let sets: &[&[f64]] = &[&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], &[1.0]];
        let within = |mantissas: &[f64], step: i32| -> Vec<f64> {
            let mut out = Vec::new();
            let mut e = e0;
            while e <= e1 {
                for m in mantissas {
                    let v = m * 10f64.powi(e);
                    if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                        out.push(v);
                    }
                }
                e += step;
            }
            out
        };
        let max = max_points.max(2);
        let powers = within(&[1.0], 1);
        if powers.len() > max {
            let step = decades.div_ceil(max) as i32;
            return within(&[1.0], step.max(1));
        }
        if light {
            return sets
                .iter()
                .map(|set| within(set, 1))
                .find(|t| t.len() <= max)
                .unwrap_or(powers);
        }
        // The sparsest set with at least four ticks, else the densest with three.
        let candidates: Vec<Vec<f64>> = [
            &[1.0][..],
            &[1.0, 2.0, 5.0],
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
        ]
        .iter()
        .map(|set| within(set, 1))
        .filter(|t| t.len() <= max)
        .collect();
        if let Some(t) = candidates.iter().find(|t| t.len() >= 4) {
            return t.clone();
        }
        if let Some(t) = candidates.iter().rev().find(|t| t.len() >= 3) {
            return t.clone();
        }
        // Less than a decade: plain nice ticks.
        RangedCoordf64::from(lo..hi).key_points(max_points)
    }
}

impl Ranged for AxisCoord {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (t0, t1) = self.t_range();
        let frac = (self.axis_of(*value) - t0) / (t1 - t0);
        let px = limit.0 as f64 + frac * (limit.1 - limit.0) as f64;
        px.round().clamp(-1e6, 1e6) as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let light = matches!(hint.weight(), KeyPointWeight::Any);
        if self.log {
            self.log_ticks(hint.max_num_points(), light)
        } else {
            RangedCoordf64::from(self.lo..self.hi).key_points(hint)
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for AxisCoord {
    fn format(value: &f64) -> String {
        format_tick(*value)
    }
}

/// A tick label: at most four significant digits, exponent form for very large or small
/// magnitudes, no trailing zeros.
pub(crate) fn format_tick(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { "0".into() } else { format!("{v}") };
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.3e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = trim_zeros(mantissa);
        return format!("{mantissa}e{exp}");
    }
    let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
    trim_zeros(&format!("{v:.decimals$}"))
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// What a figure needs besides its data: axes, title lines and legend geometry.
struct Layout {
    x: AxisCoord,
    y: AxisCoord,
    y2: Option<AxisCoord>,
    title: Vec<String>,
    legend_columns: usize,
    legend_rows: u32,
}

impl Layout {
    fn of(figure: &Figure) -> Result<Self> {
        let right = |s: &super::Series| s.side == Side::Right && figure.y2.is_some();
        let xs = figure
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.x));
        let x = AxisCoord::fit(&figure.x, xs);
        let ys = |on_right: bool| {
            let x = x.clone();
            figure
                .series
                .iter()
                .filter(move |s| right(s) == on_right)
                .flat_map(|s| s.points.iter())
                .filter(move |p| x.contains(p.x))
                .flat_map(|p| {
                    let e = p.err.filter(|e| e.is_finite()).unwrap_or(0.0).abs();
                    [p.y, p.y - e, p.y + e]
                })
                .filter(|v| v.is_finite())
                .collect::<Vec<_>>()
        };
        let y = AxisCoord::fit(&figure.y, ys(false).into_iter());
        let y2 = figure
            .y2
            .as_ref()
            .map(|axis| AxisCoord::fit(axis, ys(true).into_iter()));
        let title = wrap(
            &font(TITLE_SIZE).style(FontStyle::Bold),
            &figure.title,
            WIDTH - 2 * MARGIN,
        );
        let legend_font = font(LEGEND_SIZE);
        let widest = figure
            .series
            .iter()
            .map(|s| text_width(&legend_font, &legend_label(figure, s)))
            .max()
            .unwrap_or(0);
        let column = LEGEND_SAMPLE as u32 + 12 + widest + 24;
        let legend_columns = ((WIDTH - 2 * MARGIN) / column.max(1)).clamp(1, 3) as usize;
        let legend_rows = figure.series.len().div_ceil(legend_columns) as u32;
        Ok(Self {
            x,
            y,
            y2,
            title,
            legend_columns,
            legend_rows,
        })
    }

    fn title_height(&self) -> u32 {
        title_height(self.title.len())
    }

    fn legend_height(&self) -> u32 {
        if self.legend_rows == 0 {
            0
        } else {
            self.legend_rows * LEGEND_ROW + 24
        }
    }

    fn height(&self) -> u32 {
        self.title_height() + CHART_HEIGHT + self.legend_height()
    }
}

fn legend_label(figure: &Figure, s: &super::Series) -> String {
    let mut label = s.label.clone();
    if s.side == Side::Right && figure.y2.is_some() {
        label.push_str(" (right axis)");
    }
    let finite = |v: f64, axis: &Axis| v.is_finite() && (!axis.log || v > 0.0);
    let y_axis = match (s.side, &figure.y2) {
        (Side::Right, Some(axis)) => axis,
        _ => &figure.y,
    };
    if !s
        .points
        .iter()
        .any(|p| finite(p.x, &figure.x) && finite(p.y, y_axis))
    {
        label.push_str(" (no data)");
    }
    label
}

type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    layout: &Layout,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    draw_title(root, &layout.title)?;
    let legend_h = layout.legend_height();
    let (_, rest) = root.split_vertically(layout.title_height());
    let (chart_area, legend_area) = rest.split_vertically(CHART_HEIGHT);

    let has_y2 = layout.y2.is_some();
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(MARGIN)
        .margin_right(if has_y2 { MARGIN } else { 2 * MARGIN })
        .x_label_area_size(64)
        .y_label_area_size(96)
        .right_y_label_area_size(if has_y2 { 96 } else { 0 })
        .build_cartesian_2d(layout.x.clone(), layout.y.clone())?
        .set_secondary_coord(
            layout.x.clone(),
            layout.y2.clone().unwrap_or_else(|| layout.y.clone()),
        );
    chart
        .configure_mesh()
        .x_desc(figure.x.label.clone())
        .y_desc(figure.y.label.clone())
        .axis_desc_style(font(AXIS_LABEL_SIZE))
        .label_style(font(TICK_SIZE))
        .x_labels(10)
        .y_labels(10)
        .max_light_lines(4)
        .bold_line_style(RGBColor(0, 0, 0).mix(0.16))
        .light_line_style(RGBColor(0, 0, 0).mix(0.05))
        .draw()?;
    if let Some(axis) = &figure.y2 {
        chart
            .configure_secondary_axes()
            .y_desc(axis.label.clone())
            .axis_desc_style(font(AXIS_LABEL_SIZE))
            .label_style(font(TICK_SIZE))
            .y_labels(10)
            .draw()?;
    }

    for (k, series) in figure.series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let shape = Marker::of(k);
        let right = series.side == Side::Right && has_y2;
        let ya = if right {
            layout.y2.as_ref().expect("checked")
        } else {
            &layout.y
        };
        let frame = Frame {
            x: &layout.x,
            y: ya,
        };
        let line_style = colour.stroke_width(3);
        if matches!(
            series.style,
            Style::Line | Style::Dashed | Style::LinePoints
        ) {
            for line in frame.polylines(&series.points) {
                macro_rules! draw_line {
                    ($elements:expr) => {
                        if right {
                            chart.draw_secondary_series($elements)?;
                        } else {
                            chart.draw_series($elements)?;
                        }
                    };
                }
                if series.style == Style::Dashed {
                    draw_line!(DashedLineSeries::new(line.clone(), 12u32, 8u32, line_style));
                } else {
                    draw_line!(LineSeries::new(line.clone(), line_style));
                }
            }
        }
        if matches!(series.style, Style::Points | Style::LinePoints) {
            let inside: Vec<&Point> = series
                .points
                .iter()
                .filter(|p| frame.x.contains(p.x) && frame.y.contains(p.y))
                .collect();
            let bars: Vec<(f64, f64, f64, f64)> = inside
                .iter()
                .filter_map(|p| {
                    let e = p.err.filter(|e| e.is_finite() && *e > 0.0)?;
                    let lo = if ya.log && p.y - e <= 0.0 {
                        ya.lo
                    } else {
                        ya.clamp(p.y - e)
                    };
                    Some((p.x, lo, p.y, ya.clamp(p.y + e)))
                })
                .collect();
            let bar_style = colour.stroke_width(2);
            let bar = |b: &(f64, f64, f64, f64)| {
                ErrorBar::new_vertical(b.0, b.1, b.2, b.3, bar_style, 10)
            };
            if right {
                chart.draw_secondary_series(bars.iter().map(bar))?;
            } else {
                chart.draw_series(bars.iter().map(bar))?;
            }
            // Markers are drawn in pixels on the root area (whose origin is the backend's),
            // so that both axes share one marker code.
            for p in &inside {
                let px = if right {
                    chart.secondary_plotting_area().map_coordinate(&(p.x, p.y))
                } else {
                    chart.plotting_area().map_coordinate(&(p.x, p.y))
                };
                shape.draw(root, px, colour)?;
            }
        }
    }

    // Legend strip.
    if legend_h > 0 && !figure.series.is_empty() {
        let (lw, _) = legend_area.dim_in_pixel();
        let columns = layout.legend_columns;
        let col_w = (lw - 2 * MARGIN) / columns as u32;
        let text_style = TextStyle::from(font(LEGEND_SIZE)).pos(Pos::new(HPos::Left, VPos::Center));
        legend_area.draw(&Rectangle::new(
            [
                (MARGIN as i32 - 6, 2),
                ((lw - MARGIN) as i32 + 6, legend_h as i32 - 8),
            ],
            RGBColor(0, 0, 0).mix(0.3),
        ))?;
        for (k, series) in figure.series.iter().enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            let (row, col) = ((k / columns) as i32, (k % columns) as i32);
            let x0 = MARGIN as i32 + col * col_w as i32 + 8;
            let yc = 8 + row * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2;
            let seg = [(x0, yc), (x0 + LEGEND_SAMPLE, yc)];
            match series.style {
                Style::Line | Style::LinePoints => {
                    legend_area.draw(&PathElement::new(seg, colour.stroke_width(3)))?
                }
                Style::Dashed => legend_area.draw(&DashedPathElement::new(
                    seg,
                    12u32,
                    8u32,
                    colour.stroke_width(3),
                ))?,
                Style::Points => {}
            }
            if matches!(series.style, Style::Points | Style::LinePoints) {
                Marker::of(k).draw(&legend_area, (x0 + LEGEND_SAMPLE / 2, yc), colour)?;
            }
            legend_area.draw(&Text::new(
                legend_label(figure, series),
                (x0 + LEGEND_SAMPLE + 12, yc),
                text_style.clone(),
            ))?;
        }
    }
    Ok(())
}

/// Marker shapes, cycled in series order so that series stay apart in grey print.
#[derive(Debug, Clone, Copy)]
enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
}

impl Marker {
    fn of(k: usize) -> Self {
        [Self::Circle, Self::Square, Self::Triangle, Self::Diamond][k % 4]
    }

    fn draw<DB: DrawingBackend>(
        self,
        area: &DrawingArea<DB, Shift>,
        (x, y): (i32, i32),
        colour: RGBColor,
    ) -> DrawResult<DB> {
        let fill = colour.filled();
        let edge = WHITE.stroke_width(1);
        match self {
            Self::Circle => {
                area.draw(&Circle::new((x, y), 6, fill))?;
                area.draw(&Circle::new((x, y), 6, edge))
            }
            Self::Square => {
                area.draw(&Rectangle::new([(x - 5, y - 5), (x + 5, y + 5)], fill))?;
                area.draw(&Rectangle::new([(x - 5, y - 5), (x + 5, y + 5)], edge))
            }
            Self::Triangle => {
                let pts = vec![(x, y - 7), (x - 7, y + 5), (x + 7, y + 5)];
                area.draw(&Polygon::new(pts, fill))
            }
            Self::Diamond => {
                let pts = vec![(x, y - 7), (x - 7, y), (x, y + 7), (x + 7, y)];
                area.draw(&Polygon::new(pts, fill))
            }
        }
    }
}

/// The two axes a series is drawn against.
struct Frame<'a> {
    x: &'a AxisCoord,
    y: &'a AxisCoord,
}

impl Frame<'_> {
    /// The drawable parts of a line through `points`: broken where a point cannot be
    /// drawn, clipped to the axes' ranges.
    fn polylines(&self, points: &[Point]) -> Vec<Vec<(f64, f64)>> {
        let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut current: Vec<(f64, f64)> = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        for p in points {
            if !(self.x.drawable(p.x) && self.y.drawable(p.y)) {
                prev = None;
                continue;
            }
            let t = (self.x.axis_of(p.x), self.y.axis_of(p.y));
            if let Some(a) = prev {
                match self.clip(a, t) {
                    Some((s, e)) => {
                        let joined = current.last().is_some_and(|&l| l == s);
                        if !joined {
                            if current.len() >= 2 {
                                lines.push(std::mem::take(&mut current));
                            }
                            current.clear();
                            current.push(s);
                        }
                        current.push(e);
                    }
                    None => {
                        if current.len() >= 2 {
                            lines.push(std::mem::take(&mut current));
                        }
                        current.clear();
                    }
                }
            }
            prev = Some(t);
        }
        if current.len() >= 2 {
            lines.push(current);
        }
        lines
            .into_iter()
            .map(|l| {
                l.into_iter()
                    .map(|(tx, ty)| (self.x.data_of(tx), self.y.data_of(ty)))
                    .collect()
            })
            .collect()
    }

    /// Clips the segment `a -> b` (axis space) to the axes' rectangle (Liang-Barsky).
    fn clip(&self, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
        let (x0, x1) = self.x.t_range();
        let (y0, y1) = self.y.t_range();
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut u0, mut u1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - x0),
            (dx, x1 - a.0),
            (-dy, a.1 - y0),
            (dy, y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    u0 = u0.max(r);
                } else {
                    u1 = u1.min(r);
                }
            }
        }
        if u0 > u1 {
            return None;
        }
        let at = |u: f64| {
            if u == 0.0 {
                a
            } else if u == 1.0 {
                b
            } else {
                (a.0 + u * dx, a.1 + u * dy)
            }
        };
        Some((at(u0), at(u1)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::Series;

    /// A figure that uses every feature: log and linear axes, a fixed range, a right axis,
    /// all four styles, error bars, non-finite and non-positive points, an empty series.
    fn every_feature() -> Figure {
        let xs: Vec<f64> = (0..40)
            .map(|k| 10f64.powf(-3.0 + 3.0 * k as f64 / 39.0))
            .collect();
        let mut with_gaps = Series::xy(
            "line with gaps",
            Style::Line,
            xs.iter().map(|&x| (x, x.sqrt())),
        );
        with_gaps.points[5].y = f64::NAN;
        with_gaps.points[9].x = f64::INFINITY;
        with_gaps.points[12].y = -1.0; // not drawable on the log axis
        Figure {
            name: "every_feature".into(),
            title: "Every feature: log x, log y, a right axis, error bars and a title long \
                    enough to need a second line"
                .into(),
            x: Axis::log("reduced pressure p0 / (E* g)"),
            y: Axis::log("relative contact area a_r"),
            y2: Some(Axis::linear("a_r / p0").with_range(0.0, 3.0)),
            series: vec![
                with_gaps,
                Series::xy(
                    "dashed",
                    Style::Dashed,
                    xs.iter().map(|&x| (x, 0.5 * x.sqrt())),
                ),
                Series::with_errors(
                    "points with errors",
                    Style::Points,
                    xs.iter()
                        .step_by(4)
                        .map(|&x| (x, 0.8 * x.sqrt(), 0.3 * x.sqrt())),
                ),
                Series::with_errors(
                    "line and points on the right",
                    Style::LinePoints,
                    // The last point lies above the fixed range: clipped, not drawn.
                    xs.iter().step_by(5).map(|&x| (x, 2.0 + x, 0.1)),
                )
                .on_right(),
                Series::xy("empty", Style::Line, std::iter::empty()),
            ],
        }
    }

    fn png_size(path: &Path) -> (u32, u32) {
        let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        (img.width(), img.height())
    }

    #[test]
    fn figure_writes_svg_with_title_and_png_of_the_right_size() {
        let dir = tempfile::tempdir().unwrap();
        let fig = every_feature();
        let paths = render(&fig, dir.path()).unwrap();
        assert_eq!(
            paths,
            vec![
                dir.path().join("every_feature.svg"),
                dir.path().join("every_feature.png")
            ]
        );
        let svg = std::fs::read_to_string(&paths[0]).unwrap();
        assert!(
            svg.starts_with("<svg"),
            "not an SVG: {}",
            &svg[..80.min(svg.len())]
        );
        // The title is wrapped over two lines; both halves are there as text.
        assert!(svg.contains("Every feature: log x"), "title missing");
        assert!(svg.contains("second line"), "title's second line missing");
        for s in &fig.series {
            assert!(svg.contains(&s.label), "legend entry {} missing", s.label);
        }
        assert!(svg.contains("(right axis)"));
        assert!(svg.contains("a_r / p0"), "right axis label missing");
        let layout = Layout::of(&fig).unwrap();
        assert_eq!(layout.title.len(), 2, "{:?}", layout.title);
        assert_eq!(png_size(&paths[1]), (WIDTH, layout.height()));
        // No temporaries left behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn png_shows_the_series_colours() {
        // A single thick line across a linear chart: its colour must appear in the image.
        let dir = tempfile::tempdir().unwrap();
        let fig = Figure {
            name: "one_line".into(),
            title: "One line".into(),
            x: Axis::linear("x"),
            y: Axis::linear("y"),
            y2: None,
            series: vec![Series::xy("y = x", Style::Line, [(0.0, 0.0), (1.0, 1.0)])],
        };
        let paths = render(&fig, dir.path()).unwrap();
        let img = image::open(&paths[1]).unwrap().to_rgb8();
        let c = COLOURS[0];
        let hits = img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count();
        assert!(hits > 500, "only {hits} pixels of the first series' colour");
    }

    #[test]
    fn degenerate_figures_render() {
        // No series at all; only empty or undrawable series; a constant series; a fixed
        // range that is invalid on a log axis (ignored, the data decide).
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            Figure {
                name: "nothing".into(),
                title: "Nothing".into(),
                x: Axis::linear("x"),
                y: Axis::log("y"),
                y2: None,
                series: vec![],
            },
            Figure {
                name: "undrawable".into(),
                title: "Undrawable".into(),
                x: Axis::log("x"),
                y: Axis::log("y").with_range(-1.0, 1.0),
                y2: None,
                series: vec![
                    Series::xy("negative", Style::Points, [(-1.0, 1.0), (1.0, -1.0)]),
                    Series::xy("nan", Style::Line, [(f64::NAN, 1.0)]),
                ],
            },
            Figure {
                name: "constant".into(),
                title: "Constant".into(),
                x: Axis::linear("x"),
                y: Axis::linear("y"),
                y2: Some(Axis::log("y2")),
                series: vec![Series::xy(
                    "flat",
                    Style::LinePoints,
                    [(1.0, 2.0), (1.0, 2.0)],
                )],
            },
        ];
        for fig in &cases {
            let paths = render(fig, dir.path()).unwrap_or_else(|e| panic!("{}: {e}", fig.name));
            assert!(std::fs::metadata(&paths[0]).unwrap().len() > 0);
            let layout = Layout::of(fig).unwrap();
            assert_eq!(
                png_size(&paths[1]),
                (WIDTH, layout.height()),
                "{}",
                fig.name
            );
        }
    }

    #[test]
    fn bad_names_are_rejected() {
        let dir = tempfile::tempdir().unwrap();
        let mut fig = every_feature();
        fig.name = "../escape".into();
        let e = render(&fig, dir.path()).unwrap_err().to_string();
        assert!(e.contains("figure name") && e.contains("escape"), "{e}");
    }

    #[test]
    fn axes_fit_the_data_and_skip_what_they_cannot_show() {
        let log = AxisCoord::fit(
            &Axis::log("x"),
            [-1.0, 0.0, 0.01, 100.0, f64::NAN].into_iter(),
        );
        assert!(
            log.lo < 0.01 && log.lo > 0.005 && log.hi > 100.0 && log.hi < 200.0,
            "{log:?}"
        );
        let lin = AxisCoord::fit(&Axis::linear("x"), [-1.0, 3.0].into_iter());
        assert_eq!((lin.lo, lin.hi), (-1.2, 3.2));
        let fixed = AxisCoord::fit(&Axis::linear("x").with_range(0.0, 1.0), [5.0].into_iter());
        assert_eq!((fixed.lo, fixed.hi), (0.0, 1.0));
        // Log ticks: decades, filled in when few; nice ticks within one decade.
        let ticks =
            |lo: f64, hi: f64, max: usize| AxisCoord { lo, hi, log: true }.log_ticks(max, false);
        assert_eq!(ticks(1e-3, 1.0, 10), vec![1e-3, 1e-2, 0.1, 1.0]);
        let two = ticks(0.01, 1.0, 10);
        assert!(
            two.len() == 7 && two.contains(&0.02) && two.contains(&0.5),
            "{two:?}"
        );
        let short = ticks(0.19, 0.52, 10);
        assert_eq!(short.len(), 4, "{short:?}");
        assert!((short[0] - 0.2).abs() < 1e-12 && (short[3] - 0.5).abs() < 1e-12);
        let wide = ticks(1e-12, 1.0, 5);
        assert!(wide.len() <= 5 && wide.len() >= 2, "{wide:?}");
        let narrow = ticks(0.3, 0.45, 8);
        assert!(
            narrow.len() >= 2 && narrow.iter().all(|&t| (0.3..=0.8).contains(&t)),
            "{narrow:?}"
        );
    }

    #[test]
    fn lines_are_clipped_to_the_axes_and_broken_at_gaps() {
        let (x, y) = (
            AxisCoord {
                lo: 0.0,
                hi: 1.0,
                log: false,
            },
            AxisCoord {
                lo: 0.0,
                hi: 1.0,
                log: false,
            },
        );
        let frame = Frame { x: &x, y: &y };
        let pts = |v: &[(f64, f64)]| -> Vec<Point> {
            v.iter().map(|&(x, y)| Point { x, y, err: None }).collect()
        };
        // Leaves the box at y = 1 and comes back: two pieces, cut at the edge.
        let lines = frame.polylines(&pts(&[(0.0, 0.0), (0.5, 2.0), (1.0, 0.0)]));
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert_eq!(lines[0], vec![(0.0, 0.0), (0.25, 1.0)]);
        assert_eq!(lines[1], vec![(0.75, 1.0), (1.0, 0.0)]);
        // A NaN breaks the line; a segment wholly outside is dropped.
        let lines = frame.polylines(&pts(&[
            (0.1, 0.1),
            (0.2, 0.2),
            (f64::NAN, 0.3),
            (0.4, 0.4),
            (0.5, 0.5),
            (0.6, 0.6),
            (2.0, 2.0),
            (3.0, 3.0),
        ]));
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert_eq!(lines[1].len(), 4);
        assert_eq!(lines[1][3], (1.0, 1.0));
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(format_tick(0.30000000000000004), "0.3");
        assert_eq!(format_tick(1e-4), "1e-4");
        assert_eq!(format_tick(250000.0), "2.5e5");
        assert_eq!(format_tick(12.5), "12.5");
        assert_eq!(format_tick(0.0), "0");
        assert_eq!(format_tick(-2.0), "-2");
    }

    fn contact_map(n: usize) -> Raster {
        Raster {
            name: "contact_map".into(),
            title: "Contact map".into(),
            n,
            pixels: (0..n * n).map(|k| ((k / n + k % n) % 3) as u8).collect(),
            palette: vec![
                ([255, 255, 255], "no contact".into()),
                ([0, 0, 0], "contact".into()),
                ([213, 94, 0], "re-entered".into()),
            ],
        }
    }

    #[test]
    fn raster_writes_a_png_with_one_square_per_point() {
        let dir = tempfile::tempdir().unwrap();
        let raster = contact_map(32);
        let paths = render_raster(&raster, dir.path()).unwrap();
        assert_eq!(paths, vec![dir.path().join("contact_map.png")]);
        let img = image::open(&paths[0]).unwrap().to_rgb8();
        let scale = 512 / 32;
        assert!(img.width() >= MARGIN + 32 * scale && img.height() >= 32 * scale);
        // The centre of grid point (row 1, column 0) has its palette colour.
        let y0 = title_height(1);
        let at = |row: u32, col: u32| {
            img.get_pixel(
                MARGIN + col * scale + scale / 2,
                y0 + row * scale + scale / 2,
            )
            .0
        };
        assert_eq!(at(0, 0), [255, 255, 255]);
        assert_eq!(at(1, 0), [0, 0, 0]);
        assert_eq!(at(1, 1), [213, 94, 0]);
        assert_eq!(at(31, 31), raster.palette[(62 % 3) as usize].0);
    }

    #[test]
    fn raster_with_bad_pixels_is_rejected() {
        let dir = tempfile::tempdir().unwrap();
        let mut raster = contact_map(8);
        raster.pixels[3] = 7;
        let e = render_raster(&raster, dir.path()).unwrap_err().to_string();
        assert!(e.contains("contact_map.pixels") && e.contains("7"), "{e}");
        raster.pixels.pop();
        let e = render_raster(&raster, dir.path()).unwrap_err().to_string();
        assert!(e.contains("63 values"), "{e}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
