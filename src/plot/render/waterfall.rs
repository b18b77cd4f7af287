//! Rendering of a [`Waterfall`]: the panels stacked top to bottom on one shared height
//! range, each with the elastic body (orange) filled above its surface, the rough body
//! (blue) filled below its own, the gap white, and marked points as red dots on the rough
//! surface; a legend strip at the bottom.

use super::*;
use crate::plot::Waterfall;

/// Height of one panel, pixels.
const PANEL_HEIGHT: u32 = 190;
/// The elastic body.
const ELASTIC: RGBColor = RGBColor(240, 150, 60);
/// The rough body.
const ROUGH: RGBColor = RGBColor(70, 120, 200);
/// Marked points.
const MARK: RGBColor = RGBColor(220, 30, 30);

/// Renders `waterfall` into `dir` as `<name>.svg` and `<name>.png`; returns the paths.
pub fn render_waterfall(waterfall: &Waterfall, dir: &Path) -> Result<Vec<PathBuf>> {
    check_stem("waterfall name", &waterfall.name)?;
    check_waterfall(waterfall)?;
    ensure_fonts()?;
    let title = wrap(
        &font(TITLE_SIZE).style(FontStyle::Bold),
        &waterfall.title,
        WIDTH - 2 * MARGIN,
    );
    let panels_h = PANEL_HEIGHT * waterfall.panels.len() as u32 + 50;
    let (w, h) = (
        WIDTH,
        title_height(title.len()) + panels_h + LEGEND_ROW + 24,
    );
    let stack = Stack {
        waterfall,
        title: &title,
    };
    write_svg_and_png(dir, &waterfall.name, (w, h), &stack)
}

/// A waterfall with its title lines, drawn on any backend.
struct Stack<'a> {
    waterfall: &'a Waterfall,
    title: &'a [String],
}

impl Drawing for Stack<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        draw(root, self.waterfall, self.title)
    }
}

fn check_waterfall(w: &Waterfall) -> Result<()> {
    let Some(first) = w.panels.first() else {
        return Err(Error::invalid(
            &format!("waterfall {}.panels", w.name),
            "[]",
            "at least one panel",
        ));
    };
    let len = first.upper.len();
    for p in &w.panels {
        if len < 2 || p.upper.len() != len || p.lower.len() != len || p.marked.len() != len {
            return Err(Error::invalid(
                &format!("waterfall {}.panels", w.name),
                format!(
                    "panel {:?} of lengths {}/{}",
                    p.label,
                    p.upper.len(),
                    p.lower.len()
                ),
                format!("upper, lower and marked of one length >= 2 ({len})"),
            ));
        }
        if p.upper.iter().chain(&p.lower).any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                &format!("waterfall {}.panels", w.name),
                format!("panel {:?}", p.label),
                "finite heights",
            ));
        }
    }
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    w: &Waterfall,
    title: &[String],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    draw_title(root, title)?;
    let (_, rest) = root.split_vertically(title_height(title.len()));
    let n_panels = w.panels.len();
    let (stack, legend) = rest.split_vertically(PANEL_HEIGHT * n_panels as u32 + 50);
    let len = w.panels[0].upper.len();
    let x_hi = (len - 1) as f64;
    let all = w.panels.iter().flat_map(|p| p.upper.iter().chain(&p.lower));
    let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
        (a.min(v), b.max(v))
    });
    let pad = 0.12 * (hi - lo).max(f64::MIN_POSITIVE);
    let (y_lo, y_hi) = (lo - pad, hi + pad);
    let mut heights: Vec<u32> = vec![PANEL_HEIGHT; n_panels];
    heights[n_panels - 1] += 50;
    let mut area = stack;
    for (k, panel) in w.panels.iter().enumerate() {
        let (this, below) = area.split_vertically(heights[k]);
        area = below;
        let last = k + 1 == n_panels;
        let mut chart = ChartBuilder::on(&this)
            .margin_left(MARGIN)
            .margin_right(2 * MARGIN)
            .margin_top(6)
            .x_label_area_size(if last { 56 } else { 0 })
            .y_label_area_size(96)
            .build_cartesian_2d(0.0..x_hi, y_lo..y_hi)?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(w.y_label.clone())
            .axis_desc_style(font(TICK_SIZE))
            .label_style(font(TICK_SIZE))
            .y_labels(4)
            .disable_mesh();
        if last {
            mesh.x_desc(w.x_label.clone()).x_labels(10);
        } else {
            mesh.x_labels(0);
        }
        mesh.draw()?;
        let xs = (0..len).map(|i| i as f64);
        let mut top: Vec<(f64, f64)> = vec![(0.0, y_hi)];
        top.extend(xs.clone().zip(panel.upper.iter().copied()));
        top.push((x_hi, y_hi));
        chart.draw_series(std::iter::once(Polygon::new(top, ELASTIC.filled())))?;
        let mut bottom: Vec<(f64, f64)> = vec![(0.0, y_lo)];
        bottom.extend(xs.clone().zip(panel.lower.iter().copied()));
        bottom.push((x_hi, y_lo));
        chart.draw_series(std::iter::once(Polygon::new(bottom, ROUGH.filled())))?;
        chart.draw_series(
            xs.zip(&panel.lower)
                .zip(&panel.marked)
                .filter(|(_, &m)| m)
                .map(|((x, &y), _)| Circle::new((x, y), 4, MARK.filled())),
        )?;
        let label_style = TextStyle::from(font(LEGEND_SIZE).style(FontStyle::Bold))
            .pos(Pos::new(HPos::Left, VPos::Top));
        chart.draw_series(std::iter::once(Text::new(
            panel.label.clone(),
            (0.01 * x_hi, y_hi),
            label_style,
        )))?;
    }
    let items = [
        (ELASTIC, "elastic body (its displacement)".to_string()),
        (ROUGH, "rough body".to_string()),
        (WHITE, "gap".to_string()),
        (MARK, w.mark_label.clone()),
    ];
    let style = TextStyle::from(font(LEGEND_SIZE)).pos(Pos::new(HPos::Left, VPos::Center));
    let mut x = MARGIN as i32;
    for (colour, label) in items {
        let y = 12;
        legend.draw(&Rectangle::new([(x, y), (x + 22, y + 22)], colour.filled()))?;
        legend.draw(&Rectangle::new([(x, y), (x + 22, y + 22)], BLACK))?;
        legend.draw(&Text::new(label.clone(), (x + 30, y + 11), style.clone()))?;
        x += 30 + text_width(&font(LEGEND_SIZE), &label) as i32 + 20;
    }
    Ok(())
}
