//! Tests of the rendering.

use super::axes::{format_tick, AxisCoord};
use super::draw::Frame;
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
