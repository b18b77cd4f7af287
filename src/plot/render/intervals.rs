//! Rendering of an [`IntervalChart`]: a label column on the left, one row per estimate with
//! its interval as a bar and its value as a dot (an arrow at the axis's end where it lies
//! beyond), a heading row per group, the region right of 0 shaded, and the legend of the
//! kinds at the bottom.

use super::*;
use crate::plot::IntervalChart;

/// Height of one row, pixels.
const ROW: u32 = 18;
/// Width of the label column, pixels.
const LABELS: u32 = 380;
/// The shaded region.
const REGION: RGBColor = RGBColor(225, 240, 225);

/// Renders `chart` into `dir` as `<name>.svg` and `<name>.png`; returns the paths.
pub fn render_intervals(chart: &IntervalChart, dir: &Path) -> Result<Vec<PathBuf>> {
    check_stem("interval chart name", &chart.name)?;
    let (lo, hi) = chart.range;
    if !(lo.is_finite() && hi.is_finite() && lo < 0.0 && hi > 0.0) {
        return Err(Error::invalid(
            &format!("interval chart {}.range", chart.name),
            format!("({lo}, {hi})"),
            "a finite range around 0",
        ));
    }
    if let Some(r) = chart.rows.iter().find(|r| r.kind >= chart.kinds.len()) {
        return Err(Error::invalid(
            &format!("interval chart {}.rows", chart.name),
            format!("{:?} of kind {}", r.label, r.kind),
            format!("a kind below {}", chart.kinds.len()),
        ));
    }
    ensure_fonts()?;
    let title = wrap(
        &font(TITLE_SIZE).style(FontStyle::Bold),
        &chart.title,
        WIDTH - 2 * MARGIN,
    );
    let lines = lines(chart);
    let h = title_height(title.len()) + ROW * lines.len() as u32 + 70 + LEGEND_ROW + MARGIN;
    let drawing = Chart {
        chart,
        title: &title,
        lines: &lines,
    };
    write_svg_and_png(dir, &chart.name, (WIDTH, h), &drawing)
}

/// A line of the chart: a group's heading, or a row (by index).
enum Line<'a> {
    Heading(&'a str),
    Row(usize),
}

fn lines(chart: &IntervalChart) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    for (k, r) in chart.rows.iter().enumerate() {
        if k == 0 || chart.rows[k - 1].group != r.group {
            out.push(Line::Heading(&r.group));
        }
        out.push(Line::Row(k));
    }
    out
}

struct Chart<'a> {
    chart: &'a IntervalChart,
    title: &'a [String],
    lines: &'a [Line<'a>],
}

impl Drawing for Chart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        draw_title(root, self.title)?;
        let top = title_height(self.title.len()) as i32;
        let (lo, hi) = self.chart.range;
        let (x0, x1) = ((MARGIN + LABELS) as i32, (WIDTH - 2 * MARGIN) as i32);
        let x_of = |v: f64| x0 + ((v.clamp(lo, hi) - lo) / (hi - lo) * (x1 - x0) as f64) as i32;
        let bottom = top + (ROW * self.lines.len() as u32) as i32;
        // The region right of 0, the edge at 0, the frame and the ticks.
        root.draw(&Rectangle::new(
            [(x_of(0.0), top), (x1, bottom)],
            REGION.filled(),
        ))?;
        root.draw(&PathElement::new(
            vec![(x_of(0.0), top), (x_of(0.0), bottom)],
            BLACK,
        ))?;
        root.draw(&Rectangle::new([(x0, top), (x1, bottom)], BLACK))?;
        let tick_font = TextStyle::from(font(TICK_SIZE)).pos(Pos::new(HPos::Center, VPos::Top));
        for t in (lo.ceil() as i64)..=(hi.floor() as i64) {
            let x = x_of(t as f64);
            root.draw(&PathElement::new(vec![(x, bottom), (x, bottom + 5)], BLACK))?;
            root.draw(&Text::new(
                t.to_string(),
                (x, bottom + 7),
                tick_font.clone(),
            ))?;
        }
        let label_font =
            TextStyle::from(font(TICK_SIZE - 3.0)).pos(Pos::new(HPos::Left, VPos::Center));
        let heading_font = TextStyle::from(font(TICK_SIZE - 1.0).style(FontStyle::Bold))
            .pos(Pos::new(HPos::Left, VPos::Center));
        for (k, line) in self.lines.iter().enumerate() {
            let y = top + (k as u32 * ROW + ROW / 2) as i32;
            match line {
                Line::Heading(g) => {
                    root.draw(&Text::new(
                        g.to_string(),
                        (MARGIN as i32, y),
                        heading_font.clone(),
                    ))?;
                }
                Line::Row(i) => {
                    let r = &self.chart.rows[*i];
                    let colour = COLOURS[r.kind % COLOURS.len()];
                    root.draw(&Text::new(
                        r.label.clone(),
                        (MARGIN as i32 + 12, y),
                        label_font.clone(),
                    ))?;
                    if r.half > 0.0 && r.half.is_finite() {
                        let (a, b) = (x_of(r.value - r.half), x_of(r.value + r.half));
                        root.draw(&PathElement::new(
                            vec![(a, y), (b, y)],
                            colour.stroke_width(2),
                        ))?;
                    }
                    if r.value < lo || r.value > hi {
                        let x = x_of(r.value);
                        let d = if r.value < lo { 1 } else { -1 };
                        let tip = vec![(x, y), (x + 8 * d, y - 5), (x + 8 * d, y + 5)];
                        root.draw(&Polygon::new(tip, colour.filled()))?;
                    } else {
                        root.draw(&Circle::new((x_of(r.value), y), 4, colour.filled()))?;
                    }
                }
            }
        }
        let axis_font =
            TextStyle::from(font(AXIS_LABEL_SIZE)).pos(Pos::new(HPos::Center, VPos::Top));
        root.draw(&Text::new(
            self.chart.x_label.clone(),
            ((x0 + x1) / 2, bottom + 30),
            axis_font,
        ))?;
        let legend_y = bottom + 70;
        let legend_font =
            TextStyle::from(font(LEGEND_SIZE)).pos(Pos::new(HPos::Left, VPos::Center));
        let mut x = MARGIN as i32;
        for (k, kind) in self.chart.kinds.iter().enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            root.draw(&Circle::new((x + 6, legend_y), 5, colour.filled()))?;
            root.draw(&Text::new(
                kind.clone(),
                (x + 16, legend_y),
                legend_font.clone(),
            ))?;
            x += 32 + text_width(&font(LEGEND_SIZE), kind) as i32;
        }
        Ok(())
    }
}
