//! Drawing a figure: the layout (title, chart, legend strip), series and markers.

use plotters::chart::DualCoordChartContext;
use plotters::element::{Drawable, PointCollection};

use super::axes::AxisCoord;
use super::*;

/// What a figure needs besides its data: axes, title lines and legend geometry.
pub(super) struct Layout {
    pub(super) x: AxisCoord,
    pub(super) y: AxisCoord,
    pub(super) y2: Option<AxisCoord>,
    pub(super) title: Vec<String>,
    pub(super) legend_columns: usize,
    pub(super) legend_rows: u32,
}

impl Layout {
    pub(super) fn of(figure: &Figure) -> Result<Self> {
        let right = |s: &crate::plot::Series| s.side == Side::Right && figure.y2.is_some();
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

    pub(super) fn height(&self) -> u32 {
        self.title_height() + CHART_HEIGHT + self.legend_height()
    }
}

fn legend_label(figure: &Figure, s: &crate::plot::Series) -> String {
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

/// The chart: the data axes on the left, and the right axis (the left one again when the
/// figure has none).
type Chart<'a, DB> = DualCoordChartContext<
    'a,
    DB,
    Cartesian2d<AxisCoord, AxisCoord>,
    Cartesian2d<AxisCoord, AxisCoord>,
>;

/// A figure with its layout, drawn on any backend.
pub(super) struct Plot<'a> {
    pub(super) figure: &'a Figure,
    pub(super) layout: &'a Layout,
}

impl Drawing for Plot<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        draw_figure(root, self.figure, self.layout)
    }
}

/// The title, the chart with every series, and the legend strip.
fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    layout: &Layout,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    draw_title(root, &layout.title)?;
    let (_, rest) = root.split_vertically(layout.title_height());
    let (chart_area, legend_area) = rest.split_vertically(CHART_HEIGHT);
    let mut chart = chart(&chart_area, figure, layout)?;
    for (k, series) in figure.series.iter().enumerate() {
        draw_series(root, &mut chart, layout, k, series)?;
    }
    draw_legend(&legend_area, figure, layout)
}

/// The chart on `area`: both axes, their labels and the grid.
fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    figure: &Figure,
    layout: &Layout,
) -> std::result::Result<Chart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let has_y2 = layout.y2.is_some();
    let mut chart = ChartBuilder::on(area)
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
    Ok(chart)
}

/// Series `k`: its lines, then its error bars and markers.
fn draw_series<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &mut Chart<'_, DB>,
    layout: &Layout,
    k: usize,
    series: &crate::plot::Series,
) -> DrawResult<DB> {
    let colour = COLOURS[k % COLOURS.len()];
    let right = series.side == Side::Right && layout.y2.is_some();
    let frame = Frame {
        x: &layout.x,
        y: if right {
            layout.y2.as_ref().expect("checked")
        } else {
            &layout.y
        },
    };
    if matches!(
        series.style,
        Style::Line | Style::Dashed | Style::LinePoints
    ) {
        let line_style = colour.stroke_width(3);
        for line in frame.polylines(&series.points) {
            if series.style == Style::Dashed {
                let dashed = DashedLineSeries::new(line, 12u32, 8u32, line_style);
                draw_on(chart, right, dashed)?;
            } else {
                draw_on(chart, right, LineSeries::new(line, line_style))?;
            }
        }
    }
    if matches!(series.style, Style::Points | Style::LinePoints) {
        let inside: Vec<&Point> = series
            .points
            .iter()
            .filter(|p| frame.x.contains(p.x) && frame.y.contains(p.y))
            .collect();
        let bar_style = colour.stroke_width(2);
        let bars = inside.iter().filter_map(|p| {
            let (x, lo, y, hi) = frame.error_bar(p)?;
            Some(ErrorBar::new_vertical(x, lo, y, hi, bar_style, 10))
        });
        draw_on(chart, right, bars)?;
        // Markers are drawn in pixels on the root area (whose origin is the backend's),
        // so that both axes share one marker code.
        for p in &inside {
            let px = if right {
                chart.secondary_plotting_area().map_coordinate(&(p.x, p.y))
            } else {
                chart.plotting_area().map_coordinate(&(p.x, p.y))
            };
            Marker::of(k).draw(root, px, colour)?;
        }
    }
    Ok(())
}

/// Draws `elements` against the right axis or the left one.
fn draw_on<DB, E, R, S>(chart: &mut Chart<'_, DB>, right: bool, elements: S) -> DrawResult<DB>
where
    DB: DrawingBackend,
    for<'b> &'b E: PointCollection<'b, (f64, f64)>,
    E: Drawable<DB>,
    R: std::borrow::Borrow<E>,
    S: IntoIterator<Item = R>,
{
    if right {
        chart.draw_secondary_series(elements)?;
    } else {
        chart.draw_series(elements)?;
    }
    Ok(())
}

/// The legend strip: a sample of each series' line and marker, and its label.
fn draw_legend<DB: DrawingBackend>(
    legend_area: &DrawingArea<DB, Shift>,
    figure: &Figure,
    layout: &Layout,
) -> DrawResult<DB> {
    let legend_h = layout.legend_height();
    if legend_h == 0 || figure.series.is_empty() {
        return Ok(());
    }
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
            Marker::of(k).draw(legend_area, (x0 + LEGEND_SAMPLE / 2, yc), colour)?;
        }
        legend_area.draw(&Text::new(
            legend_label(figure, series),
            (x0 + LEGEND_SAMPLE + 12, yc),
            text_style.clone(),
        ))?;
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
pub(super) struct Frame<'a> {
    pub(super) x: &'a AxisCoord,
    pub(super) y: &'a AxisCoord,
}

impl Frame<'_> {
    /// The error bar of `p` as (x, low end, y, high end), clamped to the vertical axis
    /// (down to its bottom on a log axis where `y - err` is not positive); `None` without
    /// a finite, positive error.
    fn error_bar(&self, p: &Point) -> Option<(f64, f64, f64, f64)> {
        let e = p.err.filter(|e| e.is_finite() && *e > 0.0)?;
        let lo = if self.y.log && p.y - e <= 0.0 {
            self.y.lo
        } else {
            self.y.clamp(p.y - e)
        };
        Some((p.x, lo, p.y, self.y.clamp(p.y + e)))
    }

    /// The drawable parts of a line through `points`: broken where a point cannot be
    /// drawn, clipped to the axes' ranges.
    pub(super) fn polylines(&self, points: &[Point]) -> Vec<Vec<(f64, f64)>> {
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
