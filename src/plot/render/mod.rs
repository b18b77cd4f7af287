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

mod axes;
mod draw;
mod intervals;
#[cfg(test)]
mod tests;
mod waterfall;

pub use self::axes::significant;
use self::draw::{Layout, Plot};
pub use self::intervals::render_intervals;
pub use self::waterfall::render_waterfall;
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
    let plot = Plot {
        figure,
        layout: &layout,
    };
    write_svg_and_png(dir, &figure.name, (WIDTH, layout.height()), &plot)
}

/// The result of drawing on a backend.
type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Something drawn by the same code on every backend (SVG and bitmap).
trait Drawing {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// Draws `drawing` on `w x h` pixels to `<name>.svg` and `<name>.png` in `dir`, each
/// rendered in memory and written atomically; returns the paths.
fn write_svg_and_png(
    dir: &Path,
    name: &str,
    (w, h): (u32, u32),
    drawing: &impl Drawing,
) -> Result<Vec<PathBuf>> {
    let fail = |path: &Path, e: String| Error::bad_file(path, format!("rendering: {e}"));

    let svg_path = dir.join(format!("{name}.svg"));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        drawing
            .draw(&root)
            .map_err(|e| fail(&svg_path, e.to_string()))?;
        root.present().map_err(|e| fail(&svg_path, e.to_string()))?;
    }
    crate::io::write_atomic(&svg_path, svg.as_bytes())?;

    let png_path = dir.join(format!("{name}.png"));
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        drawing
            .draw(&root)
            .map_err(|e| fail(&png_path, e.to_string()))?;
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
