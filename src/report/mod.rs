//! The scorecard (SPEC section 7): `report [--from DIR] --out FILE.md`.
//!
//! Reads every outcome (`<name>.json`) in a folder and writes one Markdown file a reviewer
//! can read in a minute: a summary that names every inconclusive verdict and every finding
//! not reproduced, one table row per validation, a section per validation (account,
//! secondary statistics, checks, figures, the scene as run), the statistics measured on
//! several grids (discretisation error), the speed-against-error study ([`crate::speed`]),
//! and the provenance needed to reproduce any row.
//!
//! The report formats outcomes and computes no physics: every number in it comes from an
//! outcome file, a golden snapshot (`golden/<name>.snap`, see [`GoldenMatch`]) or the speed
//! study. Links to figures and tables are relative to the scorecard's folder. The file is
//! written atomically.

mod format;
mod golden;
mod outcomes;

pub use golden::{read_snapshot, GoldenMatch};
pub use outcomes::{read_outcome, read_outcomes, scene_grids, scene_seeds, Loaded};

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use self::format::{duration, link, md, num, pm, sig, table};
use self::outcomes::{grid_cell, seeds_cell};
use crate::error::{Error, Result};
use crate::plot::{Axis, Figure, Series, Style};
use crate::provenance::{self, Machine};
use crate::speed::{SpeedOptions, SpeedStudy, SOLVERS};
use crate::validation::{Detail, Outcome, Scale, Verdict};

/// Whether `report` runs the speed study.
#[derive(Debug, Clone, PartialEq)]
pub enum SpeedChoice {
    /// Run it with these options and write its files into the outcomes' folder.
    Run(SpeedOptions),
    /// Do not run it; a `speed.json` already in the folder is shown, marked as earlier.
    Skip,
}

/// What `report` reads and writes.
#[derive(Debug, Clone)]
pub struct ReportOptions {
    /// Folder of the outcomes (`<name>.json`).
    pub from: PathBuf,
    /// The scorecard file (Markdown).
    pub out: PathBuf,
    /// Folder of golden snapshots (`<name>.snap`), if any.
    pub golden: Option<PathBuf>,
    /// The speed study.
    pub speed: SpeedChoice,
}

/// What `report` did.
#[derive(Debug, Clone)]
pub struct ReportSummary {
    /// The scorecard.
    pub path: PathBuf,
    /// Validations in it.
    pub validations: Vec<String>,
    /// One line per inconclusive verdict, finding not reproduced, or golden mismatch.
    pub attention: Vec<String>,
    /// Files written besides the scorecard (speed study, resolution figures).
    pub files: Vec<PathBuf>,
    /// The speed study's error, if it was run and failed.
    pub speed_error: Option<String>,
}

/// The speed study as the scorecard shows it.
#[derive(Debug, Clone)]
enum SpeedSection {
    Fresh(Box<SpeedStudy>),
    Earlier(Box<SpeedStudy>),
    Skipped,
    Failed(String),
}

/// Secondary statistics of one validation measured on several grids.
#[derive(Debug, Clone)]
struct Resolution {
    validation: String,
    /// Groups of details that differ only in their numbers (one statistic, several grids),
    /// each sorted by grid.
    groups: Vec<(String, Vec<(usize, Detail)>)>,
    figure: Option<PathBuf>,
}

/// Writes the scorecard; `progress` receives a line per step of the speed study.
pub fn write(opts: &ReportOptions, progress: &mut dyn FnMut(&str)) -> Result<ReportSummary> {
    let loaded = read_outcomes(&opts.from)?;
    if loaded.is_empty() {
        return Err(Error::bad_file(
            &opts.from,
            "no outcomes (<name>.json) here; run `persson-check validate --out DIR` first",
        ));
    }
    let mut files = Vec::new();
    let speed = match &opts.speed {
        SpeedChoice::Run(speed_opts) => match crate::speed::run(speed_opts, progress) {
            Ok(study) => {
                files.extend(study.write(&opts.from)?);
                SpeedSection::Fresh(Box::new(study))
            }
            Err(e) => SpeedSection::Failed(e.to_string()),
        },
        SpeedChoice::Skip => {
            let path = opts.from.join(SpeedStudy::JSON);
            if path.exists() {
                match SpeedStudy::read(&path) {
                    Ok(study) => SpeedSection::Earlier(Box::new(study)),
                    Err(e) => SpeedSection::Failed(format!("earlier study unreadable: {e}")),
                }
            } else {
                SpeedSection::Skipped
            }
        }
    };
    let mut resolution = resolution_studies(&loaded);
    for r in &mut resolution {
        let fig = resolution_figure(r);
        let paths = crate::plot::render(&fig, &opts.from.join("resolution"))?;
        r.figure = paths
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == "png"))
            .cloned();
        files.extend(paths);
    }
    let golden: Vec<GoldenMatch> = loaded
        .iter()
        .map(|l| GoldenMatch::of(&l.outcome, opts.golden.as_deref()))
        .collect();
    let base = format::absolute(&opts.out)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let attention = attention(&loaded, &golden);
    let text = Scorecard {
        loaded: &loaded,
        golden: &golden,
        base: &base,
        opts,
        speed: &speed,
        resolution: &resolution,
        attention: &attention,
        generated_at: provenance::now_utc(),
        machine: Machine::detect(),
    }
    .markdown();
    crate::io::write_atomic(&opts.out, text.as_bytes())?;
    Ok(ReportSummary {
        path: opts.out.clone(),
        validations: loaded.iter().map(|l| l.outcome.name.clone()).collect(),
        attention,
        files,
        speed_error: match speed {
            SpeedSection::Failed(e) => Some(e),
            _ => None,
        },
    })
}

/// Plain statements of what needs a reviewer's eye.
fn attention(loaded: &[Loaded], golden: &[GoldenMatch]) -> Vec<String> {
    let mut lines = Vec::new();
    for (l, g) in loaded.iter().zip(golden) {
        let o = &l.outcome;
        if o.verdict == Verdict::Inconclusive {
            lines.push(format!(
                "{}: the verdict is INCONCLUSIVE: {} = {} does not separate \"holds\" from \
                 \"violated\" at z = {} with resolution {}; the paper's finding is therefore \
                 neither reproduced nor refuted.",
                o.name,
                o.statistic,
                pm(o.value, o.std_error),
                sig(o.rule.significance, 3),
                sig(o.rule.resolution, 3)
            ));
        }
        if o.reproduced == Some(false) {
            let failed: Vec<String> = o
                .checks
                .iter()
                .filter(|c| !c.passed)
                .map(|c| format!("{} ({})", c.name, c.detail))
                .collect();
            let why = if o.verdict != o.paper_verdict {
                format!(
                    "this run finds the assumption {} where the paper finds it {}",
                    o.verdict, o.paper_verdict
                )
            } else if !failed.is_empty() {
                format!("failed checks: {}", failed.join("; "))
            } else {
                format!(
                    "the measurement lies outside the range that reproduces the paper (paper: {})",
                    o.paper_value.map_or_else(|| "no value stated".into(), num)
                )
            };
            lines.push(format!(
                "{}: the paper's finding is NOT reproduced: {why}.",
                o.name
            ));
        }
        if let GoldenMatch::Differ(d, path) = g {
            lines.push(format!(
                "{}: {} golden value(s) differ from {}: {}.",
                o.name,
                d.len(),
                path.display(),
                d.join("; ")
            ));
        }
    }
    lines
}

/// Details with a grid, grouped by their name without its numbers.
fn resolution_studies(loaded: &[Loaded]) -> Vec<Resolution> {
    let mut out = Vec::new();
    for l in loaded {
        let mut groups: Vec<(String, Vec<(usize, Detail)>)> = Vec::new();
        for d in &l.outcome.details {
            let Some(n) = d.grid else { continue };
            let key = strip_numbers(&d.name);
            match groups.iter_mut().find(|(k, _)| *k == key) {
                Some((_, rows)) => rows.push((n, d.clone())),
                None => groups.push((key, vec![(n, d.clone())])),
            }
        }
        for (_, rows) in &mut groups {
            rows.sort_by_key(|(n, _)| *n);
        }
        if !groups.is_empty() {
            out.push(Resolution {
                validation: l.outcome.name.clone(),
                groups,
                figure: None,
            });
        }
    }
    out
}

/// The name with every number replaced by `#` ("kappa on the #x# grid").
fn strip_numbers(name: &str) -> String {
    let mut out = String::new();
    let mut chars = name.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_ascii_digit() {
            while chars
                .peek()
                .is_some_and(|d| d.is_ascii_digit() || *d == '.')
            {
                chars.next();
            }
            out.push('#');
        } else {
            out.push(c);
        }
    }
    out
}

fn resolution_figure(r: &Resolution) -> Figure {
    let mut fig = Figure {
        name: format!("resolution_{}", r.validation),
        title: format!(
            "{}: statistics measured on several grids (# marks the numbers that change)",
            r.validation
        ),
        x: Axis::log("points per side N"),
        y: Axis::linear("measured value"),
        y2: None,
        series: Vec::new(),
    };
    let single = r.groups.len() == 1;
    for (key, rows) in &r.groups {
        fig.series.push(Series::with_errors(
            format!("measured: {key}"),
            Style::LinePoints,
            rows.iter()
                .map(|(n, d)| (*n as f64, d.value.value, d.value.std_error)),
        ));
        let (lo, hi) = (rows[0].0 as f64, rows[rows.len() - 1].0 as f64);
        let common = |f: fn(&Detail) -> Option<f64>| -> Option<f64> {
            let first = f(&rows[0].1)?;
            rows.iter()
                .all(|(_, d)| f(d) == Some(first))
                .then_some(first)
        };
        let label = |who: &str| {
            if single {
                who.to_string()
            } else {
                format!("{who}: {key}")
            }
        };
        if let Some(p) = common(|d| d.persson) {
            fig.series.push(Series::xy(
                label("Persson"),
                Style::Dashed,
                [(lo, p), (hi, p)],
            ));
        }
        if let Some(p) = common(|d| d.paper) {
            fig.series
                .push(Series::xy(label("paper"), Style::Line, [(lo, p), (hi, p)]));
        }
    }
    fig
}

/// Everything the Markdown is made from.
struct Scorecard<'a> {
    loaded: &'a [Loaded],
    golden: &'a [GoldenMatch],
    /// The scorecard's folder (absolute), for relative links.
    base: &'a Path,
    opts: &'a ReportOptions,
    speed: &'a SpeedSection,
    resolution: &'a [Resolution],
    attention: &'a [String],
    generated_at: String,
    machine: Machine,
}

fn verdict_cell(v: Verdict) -> String {
    match v {
        Verdict::Inconclusive => "**inconclusive**".into(),
        v => v.to_string(),
    }
}

fn reproduced_cell(r: Option<bool>) -> String {
    match r {
        Some(true) => "yes".into(),
        Some(false) => "**NO**".into(),
        None => "**undecided** (verdict inconclusive)".into(),
    }
}

fn anchor(name: &str) -> String {
    format!(
        "v-{}",
        name.chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
            .collect::<String>()
    )
}

impl Scorecard<'_> {
    fn markdown(&self) -> String {
        let mut s = String::new();
        self.header(&mut s);
        self.table(&mut s);
        for (l, g) in self.loaded.iter().zip(self.golden) {
            self.validation(&mut s, l, g);
        }
        self.resolution_section(&mut s);
        self.speed_section(&mut s);
        self.provenance(&mut s);
        s
    }

    fn link_to(&self, path: &Path) -> String {
        link(self.base, path)
    }

    fn header(&self, s: &mut String) {
        let n = self.loaded.len();
        let count = |v: Verdict| {
            self.loaded
                .iter()
                .filter(|l| l.outcome.verdict == v)
                .count()
        };
        let names = |f: &dyn Fn(&Outcome) -> bool| -> Vec<String> {
            self.loaded
                .iter()
                .filter(|l| f(&l.outcome))
                .map(|l| format!("`{}`", l.outcome.name))
                .collect()
        };
        let reproduced = names(&|o| o.reproduced == Some(true));
        let not_reproduced = names(&|o| o.reproduced == Some(false));
        let undecided = names(&|o| o.reproduced.is_none());
        let _ = writeln!(s, "# Scorecard: Persson's assumptions against simulation\n");
        let _ = writeln!(
            s,
            "Written {} from the outcomes in `{}` by persson-check {} (commit `{}`). \
             The paper: Dapp, Prodanov & Müser, J. Phys.: Condens. Matter 26, 355002 (2014).\n",
            self.generated_at,
            self.opts.from.display(),
            provenance::VERSION,
            provenance::commit_label()
        );
        let _ = writeln!(
            s,
            "**Summary.** {n} validation{}: {} hold{}, {} violated, {} inconclusive. \
             The paper's finding is reproduced in {} ({}), NOT reproduced in {} ({}), \
             undecided in {} ({}).\n",
            if n == 1 { "" } else { "s" },
            count(Verdict::Holds),
            if count(Verdict::Holds) == 1 { "s" } else { "" },
            count(Verdict::Violated),
            count(Verdict::Inconclusive),
            reproduced.len(),
            list_or_none(&reproduced),
            not_reproduced.len(),
            list_or_none(&not_reproduced),
            undecided.len(),
            list_or_none(&undecided),
        );
        if self.attention.is_empty() {
            let _ = writeln!(
                s,
                "No verdict is inconclusive, every finding is reproduced, and no golden value \
                 differs.\n"
            );
        } else {
            let _ = writeln!(s, "**Needs attention:**\n");
            for line in self.attention {
                let _ = writeln!(s, "- {}", md(line));
            }
            s.push('\n');
        }
    }

    fn table(&self, s: &mut String) {
        let _ = writeln!(s, "## Scorecard\n");
        let rows: Vec<Vec<String>> = self
            .loaded
            .iter()
            .zip(self.golden)
            .map(|(l, g)| {
                let o = &l.outcome;
                let scale = if o.scale == Scale::Full {
                    " (full)"
                } else {
                    ""
                };
                vec![
                    format!("[{}](#{}){scale}", md(&o.name), anchor(&o.name)),
                    md(&o.assumption),
                    md(&o.statistic),
                    num(o.persson),
                    pm(o.value, o.std_error),
                    format!(
                        "{} ({})",
                        o.paper_value.map_or_else(|| "—".into(), num),
                        o.paper_verdict
                    ),
                    verdict_cell(o.verdict),
                    reproduced_cell(o.reproduced),
                    md(&g.cell()),
                    grid_cell(&o.scene),
                    seeds_cell(&o.scene),
                    duration(o.wall_s),
                    num(o.max_residual),
                ]
            })
            .collect();
        s.push_str(&table(
            &[
                "validation",
                "assumption",
                "statistic",
                "Persson",
                "measured ± error",
                "paper (verdict)",
                "verdict",
                "reproduced",
                "golden match",
                "grid",
                "seeds",
                "wall time",
                "solver residual",
            ],
            &rows,
        ));
        let _ = writeln!(
            s,
            "\nVerdict rule (per validation: significance z, resolution r): **violated** when \
             |measured − Persson| > z · error; **holds** when the whole interval measured ± \
             z · error lies within Persson ± r; **inconclusive** otherwise. \"Reproduced\" \
             requires the paper's verdict, the paper's range and every check of the paper's \
             finding; it is undecided when the verdict is inconclusive. \"Grid\" lists points \
             per side (all refinements); \"solver residual\" is the largest residual of all \
             solves.\n"
        );
    }

    fn validation(&self, s: &mut String, l: &Loaded, g: &GoldenMatch) {
        let o = &l.outcome;
        let _ = writeln!(s, "<a id=\"{}\"></a>\n", anchor(&o.name));
        let _ = writeln!(s, "## {}: {}\n", md(&o.name), md(&o.title));
        let golden = match g {
            GoldenMatch::Yes(k, path) => format!("yes: {k} values match {}", path.display()),
            GoldenMatch::Differ(d, path) => {
                format!(
                    "**no**: {} differ from {}: {}",
                    d.len(),
                    path.display(),
                    d.join("; ")
                )
            }
            GoldenMatch::FullScene => "n/a: full scenes have no snapshot".into(),
            GoldenMatch::NotChecked(why) => format!("not checked ({why})"),
        };
        let rows = vec![
            vec!["Assumption".into(), md(&o.assumption)],
            vec!["Statistic".into(), md(&o.statistic)],
            vec![
                "Persson predicts".into(),
                format!("{} (value {})", md(&o.persson_text), num(o.persson)),
            ],
            vec![
                "The paper finds".into(),
                format!(
                    "{} (value {}; the paper's verdict: {})",
                    md(&o.paper),
                    o.paper_value.map_or_else(|| "not stated".into(), num),
                    o.paper_verdict
                ),
            ],
            vec![
                "Measured".into(),
                format!("{} ({} scene)", pm(o.value, o.std_error), o.scale),
            ],
            vec![
                "Verdict".into(),
                format!(
                    "{} (z = {}, resolution {})",
                    verdict_cell(o.verdict),
                    sig(o.rule.significance, 3),
                    sig(o.rule.resolution, 3)
                ),
            ],
            vec![
                "The paper's finding reproduced".into(),
                reproduced_cell(o.reproduced),
            ],
            vec!["Golden values".into(), md(&golden)],
            vec![
                "Run".into(),
                format!(
                    "grid {}, seeds {}, {} threads, {}, largest solver residual {}",
                    grid_cell(&o.scene),
                    seeds_cell(&o.scene),
                    o.threads,
                    duration(o.wall_s),
                    num(o.max_residual)
                ),
            ],
        ];
        s.push_str(&table(&["", ""], &rows));
        s.push('\n');
        if !o.account.trim().is_empty() {
            let _ = writeln!(s, "{}\n", md(o.account.trim()));
        }
        if !o.details.is_empty() {
            let _ = writeln!(s, "**Secondary statistics**\n");
            let rows: Vec<Vec<String>> = o
                .details
                .iter()
                .map(|d| {
                    vec![
                        md(&d.name),
                        pm(d.value.value, d.value.std_error),
                        d.persson.map_or_else(|| "—".into(), num),
                        d.paper.map_or_else(|| "—".into(), num),
                        d.grid.map_or_else(|| "—".into(), |n| n.to_string()),
                    ]
                })
                .collect();
            s.push_str(&table(
                &["statistic", "measured ± error", "Persson", "paper", "grid"],
                &rows,
            ));
            s.push('\n');
        }
        if !o.checks.is_empty() {
            let _ = writeln!(s, "**Checks of the paper's finding**\n");
            let rows: Vec<Vec<String>> = o
                .checks
                .iter()
                .map(|c| {
                    vec![
                        md(&c.name),
                        if c.passed {
                            "passed".into()
                        } else {
                            "**FAILED**".into()
                        },
                        md(&c.detail),
                    ]
                })
                .collect();
            s.push_str(&table(&["check", "result", "numbers"], &rows));
            s.push('\n');
        }
        self.files(s, o);
        let scene = serde_json::to_string_pretty(&o.scene).unwrap_or_default();
        let _ = writeln!(
            s,
            "<details><summary>Scene as run</summary>\n\n```json\n{scene}\n```\n\n</details>\n"
        );
    }

    /// Figures (PNG shown, SVG linked) and tables of an outcome; missing files are named.
    fn files(&self, s: &mut String, o: &Outcome) {
        let from = &self.opts.from;
        let mut figures = Vec::new();
        let mut others = Vec::new();
        let mut missing = Vec::new();
        for f in &o.files {
            let path = from.join(f);
            if !path.exists() {
                missing.push(f.clone());
                continue;
            }
            match path.extension().and_then(|e| e.to_str()) {
                Some("png") => figures.push(path),
                Some("svg") if path.with_extension("png").exists() => {}
                _ => others.push(path),
            }
        }
        if !figures.is_empty() {
            let _ = writeln!(s, "**Figures**\n");
            for png in &figures {
                let stem = png
                    .file_stem()
                    .map(|x| x.to_string_lossy().to_string())
                    .unwrap_or_default();
                let svg = png.with_extension("svg");
                let svg_link = if svg.exists() {
                    format!(" ([SVG]({}))", self.link_to(&svg))
                } else {
                    String::new()
                };
                let _ = writeln!(s, "![{}]({}){svg_link}\n", md(&stem), self.link_to(png));
            }
        }
        if !others.is_empty() {
            let links: Vec<String> = others
                .iter()
                .map(|p| {
                    let label = p.strip_prefix(from).unwrap_or(p).display().to_string();
                    format!("[{}]({})", md(&label), self.link_to(p))
                })
                .collect();
            let _ = writeln!(s, "**Tables**: {}\n", links.join(", "));
        }
        if !missing.is_empty() {
            let _ = writeln!(
                s,
                "**Missing files** (listed in the outcome, not found in `{}`): {}\n",
                from.display(),
                missing.iter().map(|m| md(m)).collect::<Vec<_>>().join(", ")
            );
        }
    }

    fn resolution_section(&self, s: &mut String) {
        let _ = writeln!(s, "## Statistic against grid resolution\n");
        if self.resolution.is_empty() {
            let _ = writeln!(
                s,
                "No validation reports a statistic on more than one grid, so the \
                 discretisation error is not shown.\n"
            );
            return;
        }
        let _ = writeln!(
            s,
            "Secondary statistics measured on several grids (same realizations, all lengths \
             scaled with the grid): the change from one grid to the next is the \
             discretisation error the headline values carry or extrapolate away.\n"
        );
        let mut rows = Vec::new();
        for r in self.resolution {
            for (_, group) in &r.groups {
                let mut prev: Option<f64> = None;
                for (n, d) in group {
                    rows.push(vec![
                        md(&r.validation),
                        md(&d.name),
                        n.to_string(),
                        pm(d.value.value, d.value.std_error),
                        prev.map_or_else(|| "—".into(), |p| num(d.value.value - p)),
                        d.persson.map_or_else(|| "—".into(), num),
                        d.paper.map_or_else(|| "—".into(), num),
                    ]);
                    prev = Some(d.value.value);
                }
            }
        }
        s.push_str(&table(
            &[
                "validation",
                "statistic",
                "grid",
                "measured ± error",
                "change from the previous grid",
                "Persson",
                "paper",
            ],
            &rows,
        ));
        s.push('\n');
        for r in self.resolution {
            if let Some(png) = &r.figure {
                let _ = writeln!(
                    s,
                    "![{} against grid resolution]({})\n",
                    md(&r.validation),
                    self.link_to(png)
                );
            }
        }
    }

    fn speed_section(&self, s: &mut String) {
        let _ = writeln!(s, "## Speed against error\n");
        let study = match self.speed {
            SpeedSection::Fresh(study) => study,
            SpeedSection::Earlier(study) => {
                let _ = writeln!(
                    s,
                    "**Not run for this scorecard** (`--no-speed`); shown from an earlier run \
                     started {} (`{}`).\n",
                    study.started_at,
                    self.opts.from.join(SpeedStudy::JSON).display()
                );
                study
            }
            SpeedSection::Skipped => {
                let _ = writeln!(s, "Not run (`--no-speed`), and no earlier study found.\n");
                return;
            }
            SpeedSection::Failed(e) => {
                let _ = writeln!(s, "**The speed study failed:** {}\n", md(e));
                return;
            }
        };
        let o = &study.options;
        let r = &study.reference;
        let _ = writeln!(
            s,
            "One scene: H = {}, N = {}, lambda\\_l = N/2 = {}, lambda\\_s = {}, p0 = {}, \
             seed {}; cold solves, the fastest of {} per row. Reference: {} at tol {} \
             (residual {}, {} iterations, {}): a\\_r = {}, E = {}.\n",
            sig(o.hurst, 3),
            o.n,
            o.n / 2,
            sig(o.lambda_s, 3),
            sig(o.p0, 3),
            o.seed,
            o.repeats,
            r.solver.name(),
            sig(r.tol, 2),
            num(r.residual),
            r.iterations,
            duration(r.wall_s),
            sig(r.contact_area, 6),
            sig(r.elastic_energy, 6)
        );
        let _ = writeln!(
            s,
            "**Times are from one run on a shared machine**: {}, a pool of {} threads, \
             started {}, commit `{}`, {} in all. Ratios between rows mean more than the \
             absolute times.\n",
            md(&study.machine.summary()),
            study.threads,
            study.started_at,
            study.commit,
            duration(study.wall_s)
        );
        let opt_num = |v: Option<f64>| v.map_or_else(|| "—".into(), num);
        let rows: Vec<Vec<String>> = study
            .tolerance
            .iter()
            .map(|t| {
                let mut row = vec![
                    t.solver.name().to_string(),
                    sig(t.tol, 2),
                    t.wall_s.map_or_else(|| "—".into(), duration),
                    t.iterations.map_or_else(|| "—".into(), |i| i.to_string()),
                    opt_num(t.residual),
                    opt_num(t.tamaas),
                    opt_num(t.area_error),
                    opt_num(t.energy_error),
                ];
                if let Some(e) = &t.error {
                    row[2] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "tol",
                "wall time",
                "iterations",
                "residual reached",
                "tamaas error",
                "abs. a\\_r error",
                "rel. energy error",
            ],
            &rows,
        ));
        s.push('\n');

        let grids: Vec<usize> = {
            let mut g: Vec<usize> = study.sizes.iter().map(|r| r.n).collect();
            g.sort_unstable();
            g.dedup();
            g
        };
        let _ = writeln!(
            s,
            "**Iterations against grid size** (tol {}, lambda\\_l = N/2, lambda\\_s = {}). The \
             paper's argument for GFMD in reciprocal space: mass weighting lowers critical \
             slowing-down from O(L^2) (plain damped dynamics) to O(L^(1/2)), i.e. an exponent \
             of 1/2.\n",
            sig(o.size_tol, 2),
            sig(o.lambda_s, 3)
        );
        let mut header: Vec<String> = vec!["solver".into()];
        header.extend(grids.iter().map(|n| format!("N = {n}")));
        header.push("exponent k (iterations ~ N^k)".into());
        let rows: Vec<Vec<String>> = SOLVERS
            .iter()
            .map(|&kind| {
                let mut row = vec![kind.name().to_string()];
                for n in &grids {
                    let cell = study
                        .sizes
                        .iter()
                        .find(|r| r.solver == kind && r.n == *n)
                        .map(|r| match (&r.iterations, &r.error) {
                            (Some(i), _) => {
                                format!("{i} ({})", r.wall_s.map_or_else(|| "—".into(), duration))
                            }
                            (None, Some(e)) => format!("**failed**: {}", md(e)),
                            _ => "—".into(),
                        })
                        .unwrap_or_else(|| "—".into());
                    row.push(cell);
                }
                let fit = study.fits.iter().find(|f| f.solver == kind);
                row.push(match fit {
                    Some(f) => match (f.exponent, f.std_error) {
                        (Some(k), Some(e)) => format!("{} ({} grids)", pm(k, e), f.points),
                        (Some(k), None) => {
                            format!("{} ({} grids, no error bar)", sig(k, 3), f.points)
                        }
                        _ => "n/a (fewer than two grids converged)".into(),
                    },
                    None => "—".into(),
                });
                row
            })
            .collect();
        let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
        s.push_str(&table(&header_refs, &rows));
        s.push('\n');

        let pools: Vec<usize> = {
            let mut p: Vec<usize> = study.threads_study.iter().map(|t| t.threads).collect();
            p.sort_unstable();
            p.dedup();
            p
        };
        let _ = writeln!(
            s,
            "**Thread scaling** (N = {}, tol {}; wall time and speed-up against one thread).\n",
            o.n,
            sig(o.size_tol, 2)
        );
        let mut header: Vec<String> = vec!["solver".into()];
        header.extend(
            pools
                .iter()
                .map(|k| format!("{k} thread{}", if *k == 1 { "" } else { "s" })),
        );
        let rows: Vec<Vec<String>> = SOLVERS
            .iter()
            .map(|&kind| {
                let mut row = vec![kind.name().to_string()];
                for k in &pools {
                    let cell = study
                        .threads_study
                        .iter()
                        .find(|t| t.solver == kind && t.threads == *k)
                        .map(|t| match (t.wall_s, &t.error) {
                            (Some(w), _) => match t.speedup {
                                Some(x) => format!("{} (× {})", duration(w), sig(x, 3)),
                                None => duration(w),
                            },
                            (None, Some(e)) => format!("**failed**: {}", md(e)),
                            _ => "—".into(),
                        })
                        .unwrap_or_else(|| "—".into());
                    row.push(cell);
                }
                row
            })
            .collect();
        let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
        s.push_str(&table(&header_refs, &rows));
        s.push('\n');

        self.floor_table(s, study);
        self.warm_table(s, study);

        let dir = self.opts.from.join(SpeedStudy::FIGURES);
        for name in ["speed_error", "speed_iterations"] {
            let png = dir.join(format!("{name}.png"));
            if png.exists() {
                let _ = writeln!(s, "![{name}]({})\n", self.link_to(&png));
            }
        }
        let csv = self.opts.from.join(SpeedStudy::CSV);
        if csv.exists() {
            let _ = writeln!(s, "All rows: [speed.csv]({}).\n", self.link_to(&csv));
        }
    }

    /// The cost of a cold solve in FFT pairs, grid by grid.
    fn floor_table(&self, s: &mut String, study: &SpeedStudy) {
        if study.floor.is_empty() {
            return;
        }
        let _ = writeln!(
            s,
            "**The floor** (tol {}): one forward + inverse 2D FFT pair bounds the cost of an \
             iteration from below. \"Pairs / iteration\" counts the transforms each solve \
             made (set-up and the final residual included); \"iteration in pairs\" is the \
             solve's wall time over (iterations × pair); \"each pair\" is its wall time over \
             (pairs used × pair), 1 meaning nothing but transforms.\n",
            sig(study.options.size_tol, 2)
        );
        let rows: Vec<Vec<String>> = study
            .floor
            .iter()
            .map(|r| {
                let opt = |v: Option<f64>| v.map_or_else(|| "—".into(), |x| sig(x, 3));
                let mut row = vec![
                    r.solver.name().to_string(),
                    r.n.to_string(),
                    duration(r.fft_pair_s),
                    r.iterations.map_or_else(|| "—".into(), |i| i.to_string()),
                    r.wall_s.map_or_else(|| "—".into(), duration),
                    opt(r.pairs_per_iteration),
                    opt(r.iteration_in_pairs),
                    opt(r.overhead),
                ];
                if let Some(e) = &r.error {
                    row[4] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "N",
                "FFT pair",
                "iterations",
                "cold solve",
                "pairs / iteration",
                "iteration in pairs",
                "each pair",
            ],
            &rows,
        ));
        s.push('\n');
    }

    /// Warm re-solves against cold solves of the same problem.
    fn warm_table(&self, s: &mut String, study: &SpeedStudy) {
        if study.warm.is_empty() {
            return;
        }
        let _ = writeln!(
            s,
            "**Warm starts** (tol {}): a re-solve from a converged solution after a 1% load \
             change, and after adding one magnification shell (from the solution one shell \
             lower), against a cold solve of the same problem.\n",
            sig(study.options.size_tol, 2)
        );
        let rows: Vec<Vec<String>> = study
            .warm
            .iter()
            .map(|r| {
                let it = |v: Option<usize>| v.map_or_else(|| "—".into(), |i| i.to_string());
                let t = |v: Option<f64>| v.map_or_else(|| "—".into(), duration);
                let mut row = vec![
                    r.solver.name().to_string(),
                    r.n.to_string(),
                    md(&r.change),
                    format!("{} ({})", t(r.cold_wall_s), it(r.cold_iterations)),
                    format!("{} ({})", t(r.warm_wall_s), it(r.warm_iterations)),
                    r.ratio.map_or_else(|| "—".into(), |x| sig(x, 3)),
                ];
                if let Some(e) = &r.error {
                    row[4] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "N",
                "change",
                "cold (iterations)",
                "warm (iterations)",
                "warm / cold",
            ],
            &rows,
        ));
        s.push('\n');
    }

    fn provenance(&self, s: &mut String) {
        let _ = writeln!(s, "## Provenance\n");
        let golden = self
            .opts
            .golden
            .as_ref()
            .map_or_else(|| "none".into(), |g| format!("`{}`", g.display()));
        let _ = writeln!(
            s,
            "- Scorecard written: {} (UTC)\n\
             - Code: persson-check {}, commit `{}`\n\
             - Machine: {}\n\
             - Threads of this process: {}\n\
             - Outcomes read from: `{}`; golden snapshots: {golden}\n\
             - Outcome files record the definition's SHA-256, the scene, the seeds and the \
             threads, but not the commit that computed them: the commit above is the one \
             that wrote this scorecard. To reproduce a row, check out that commit and run \
             the command in the last column; the definition hash identifies the validation \
             file.\n",
            self.generated_at,
            provenance::VERSION,
            provenance::commit_label(),
            md(&self.machine.summary()),
            rayon::current_num_threads(),
            self.opts.from.display(),
        );
        let rows: Vec<Vec<String>> = self
            .loaded
            .iter()
            .map(|l| {
                let o = &l.outcome;
                let seeds = scene_seeds(&o.scene).map_or_else(
                    || "—".into(),
                    |v| {
                        v.iter()
                            .map(|x| x.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    },
                );
                let full = if o.scale == Scale::Full {
                    " --full"
                } else {
                    ""
                };
                vec![
                    md(&o.name),
                    o.scale.to_string(),
                    format!("`{}`", o.definition_sha256),
                    seeds,
                    o.threads.to_string(),
                    duration(o.wall_s),
                    l.modified
                        .map_or_else(|| "—".into(), provenance::rfc3339_utc),
                    format!(
                        "`persson-check validate {}{full} --out {}`",
                        o.name,
                        self.opts.from.display()
                    ),
                ]
            })
            .collect();
        s.push_str(&table(
            &[
                "validation",
                "scale",
                "definition SHA-256",
                "seeds",
                "threads",
                "wall time",
                "outcome written (UTC)",
                "reproduce with",
            ],
            &rows,
        ));
    }
}

fn list_or_none(items: &[String]) -> String {
    if items.is_empty() {
        "none".into()
    } else {
        items.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::Estimate;
    use crate::validation::{Check, VerdictRule};
    use serde_json::json;
    use std::collections::BTreeMap;

    fn detail(name: &str, value: f64, err: f64, grid: Option<usize>) -> Detail {
        Detail {
            key: name.into(),
            name: name.into(),
            value: Estimate::new(value, err),
            persson: Some(1.0),
            paper: Some(2.0),
            grid,
        }
    }

    fn outcome(name: &str, verdict: Verdict, reproduced: Option<bool>, scale: Scale) -> Outcome {
        Outcome {
            name: name.into(),
            title: format!("Title of {name}"),
            assumption: format!("assumption of {name}"),
            statistic: "slope kappa = a_r / p~0".into(),
            value: 2.5,
            std_error: if verdict == Verdict::Inconclusive {
                f64::NAN
            } else {
                0.05
            },
            persson: 1.0,
            persson_text: "kappa = 1".into(),
            paper: "kappa ~ 2".into(),
            paper_value: Some(2.0),
            paper_verdict: Verdict::Violated,
            verdict,
            reproduced,
            rule: VerdictRule {
                significance: 3.0,
                resolution: 0.1,
            },
            scale,
            scene: json!({"n": 64, "refinements": [1, 2], "seeds": [1, 2, 3], "tol": 1e-8}),
            definition_sha256: format!("{:0>64}", name.len()),
            wall_s: 12.5,
            max_residual: 3e-9,
            details: vec![
                detail("kappa on the 64x64 grid", 2.9, 0.1, Some(64)),
                detail("kappa on the 128x128 grid", 2.7, 0.1, Some(128)),
                detail("largest deviation", 0.08, f64::NAN, None),
            ],
            checks: vec![Check {
                key: "check".into(),
                name: format!("check of {name}"),
                passed: reproduced != Some(false),
                detail: "numbers behind it".into(),
            }],
            account: format!("Account of {name}: kappa = 2.5 +- 0.05."),
            golden: BTreeMap::from([("kappa".to_string(), 2.5)]),
            files: vec![
                format!("{name}.csv"),
                format!("{name}/fig.svg"),
                format!("{name}/fig.png"),
            ],
            threads: 2,
            solver: "gfmd".into(),
            cross_check: None,
            merge: None,
        }
    }

    /// Outcomes of every kind in `root/out`, their files, and snapshots in `root/golden`.
    fn fixture(root: &Path) -> (PathBuf, PathBuf) {
        let from = root.join("out");
        let golden = root.join("golden");
        std::fs::create_dir_all(&golden).unwrap();
        let outcomes = [
            outcome("a_holds", Verdict::Holds, Some(true), Scale::Reduced),
            outcome("b_violated", Verdict::Violated, Some(false), Scale::Reduced),
            outcome(
                "c_inconclusive",
                Verdict::Inconclusive,
                None,
                Scale::Reduced,
            ),
            outcome("d_full", Verdict::Violated, Some(true), Scale::Full),
        ];
        for o in &outcomes {
            for f in &o.files {
                crate::io::write_atomic(&from.join(f), b"content").unwrap();
            }
            let json = serde_json::to_vec_pretty(o).unwrap();
            crate::io::write_atomic(&from.join(format!("{}.json", o.name)), &json).unwrap();
        }
        // One listed file is missing; a JSON file that is not an outcome is skipped.
        std::fs::remove_file(from.join("d_full.csv")).unwrap();
        std::fs::write(from.join("summary.json"), b"{\"n\": 3}").unwrap();
        let snap = |body: &str| {
            format!("---\nsource: tests/validations.rs\nexpression: outcome.golden\n---\n{body}\n")
        };
        std::fs::write(golden.join("a_holds.snap"), snap("{\n  \"kappa\": 2.5\n}")).unwrap();
        std::fs::write(
            golden.join("b_violated.snap"),
            snap("{\n  \"kappa\": 2.6\n}"),
        )
        .unwrap();
        std::fs::write(golden.join("d_full.snap"), snap("{\n  \"kappa\": 9.9\n}")).unwrap();
        (from, golden)
    }

    /// The table row of validation `name`, split into cells.
    fn row<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
        let escaped = md(name);
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("| [{escaped}]")))
            .unwrap_or_else(|| panic!("no row for {name}"));
        line.trim_matches('|').split(" | ").map(str::trim).collect()
    }

    /// Relative link targets in the Markdown (images and files, not anchors).
    fn links(text: &str) -> Vec<String> {
        let mut out = Vec::new();
        let mut rest = text;
        while let Some(k) = rest.find("](") {
            rest = &rest[k + 2..];
            let end = rest.find(')').unwrap();
            let target = &rest[..end];
            if !target.starts_with('#') {
                out.push(target.replace("%20", " "));
            }
        }
        out
    }

    fn tiny_speed() -> SpeedOptions {
        SpeedOptions {
            tols: vec![1e-4, 1e-8],
            reference_tol: 1e-11,
            threads: vec![1, 2],
            floor_sizes: vec![32],
            repeats: 1,
            ..SpeedOptions::with_n(32)
        }
    }

    #[test]
    fn scorecard_states_every_verdict_and_links_existing_files() {
        let root = tempfile::tempdir().unwrap();
        let (from, golden) = fixture(root.path());
        // The scorecard lives in another folder: links must climb out of it.
        let out = root.path().join("review").join("scorecard.md");
        let opts = ReportOptions {
            from: from.clone(),
            out: out.clone(),
            golden: Some(golden),
            speed: SpeedChoice::Run(tiny_speed()),
        };
        let summary = write(&opts, &mut |_| {}).unwrap();
        assert_eq!(
            summary.validations,
            ["a_holds", "b_violated", "c_inconclusive", "d_full"]
        );
        assert_eq!(summary.speed_error, None);
        let text = std::fs::read_to_string(&out).unwrap();

        // Columns: validation, assumption, statistic, Persson, measured, paper, verdict,
        // reproduced, golden match, grid, seeds, wall time, solver residual.
        let a = row(&text, "a_holds");
        assert_eq!(a.len(), 13, "{a:?}");
        assert_eq!(
            &a[3..],
            [
                "1",
                "2.500 ± 0.050",
                "2 (violated)",
                "holds",
                "yes",
                "yes",
                "64, 128",
                "3 (1-3)",
                "12.5 s",
                "3e-9"
            ]
        );
        let b = row(&text, "b_violated");
        assert_eq!(b[6], "violated");
        assert_eq!(b[7], "**NO**");
        assert_eq!(b[8], "no (1 differ: kappa = 2.5, snapshot 2.6)");
        let c = row(&text, "c_inconclusive");
        assert_eq!(c[4], "2.5 (no error estimate)", "NaN read back from null");
        assert_eq!(c[6], "**inconclusive**");
        assert_eq!(c[7], "**undecided** (verdict inconclusive)");
        assert_eq!(c[8], "not checked");
        let d = row(&text, "d_full");
        assert!(d[0].ends_with("(full)"), "{d:?}");
        assert_eq!(d[8], "n/a (full scene)", "full scenes are not compared");

        // The summary says plainly what is inconclusive or not reproduced.
        assert!(
            text.contains("1 holds, 2 violated, 1 inconclusive"),
            "{}",
            &text[..600]
        );
        assert!(text.contains("NOT reproduced in 1 (`b_violated`)"));
        assert!(text.contains("c\\_inconclusive: the verdict is INCONCLUSIVE"));
        assert!(text.contains("b\\_violated: the paper's finding is NOT reproduced: failed checks: check of b\\_violated (numbers behind it)"));
        assert_eq!(summary.attention.len(), 3, "{:?}", summary.attention);
        assert!(text.contains("| check of b\\_violated | **FAILED** | numbers behind it |"));

        // Sections: account, details, resolution study.
        assert!(text.contains("## a\\_holds: Title of a\\_holds"));
        assert!(text.contains("Account of a\\_holds: kappa = 2.5 +- 0.05."));
        assert!(text.contains("| largest deviation | 0.08 (no error estimate) | 1 | 2 | — |"));
        assert!(text.contains("## Statistic against grid resolution"));
        assert!(
            text.contains(
                "| a\\_holds | kappa on the 128x128 grid | 128 | 2.70 ± 0.10 | -0.2 | 1 | 2 |"
            ),
            "resolution row"
        );
        assert!(from.join("resolution/resolution_a_holds.png").exists());
        assert!(text.contains("**Missing files**") && text.contains("d\\_full.csv"));

        // Every relative link points at an existing file, images included.
        let targets = links(&text);
        let base = out.parent().unwrap();
        assert!(
            targets.iter().any(|t| t == "../out/a_holds/fig.png"),
            "{targets:?}"
        );
        assert!(targets.iter().any(|t| t.ends_with("speed/speed_error.png")));
        assert!(targets
            .iter()
            .any(|t| t.ends_with("resolution/resolution_b_violated.png")));
        for t in &targets {
            assert!(base.join(t).exists(), "link to missing file {t}");
        }

        // The speed section and the provenance block.
        assert!(text.contains("## Speed against error"));
        assert!(text.contains("**Times are from one run on a shared machine**"));
        assert!(text.contains("exponent k (iterations ~ N^k)"));
        assert!(text.contains("| cg | 1e-4 |") && text.contains("| gfmd | 1e-8 |"));
        assert!(text.contains("**The floor**") && text.contains("| pairs / iteration |"));
        assert!(text.contains("**Warm starts**") && text.contains("| load +1% |"));
        assert!(from.join("speed.csv").exists() && from.join("speed.json").exists());
        assert!(text.contains("## Provenance"));
        assert!(text.contains(&format!("commit `{}", provenance::COMMIT)));
        assert!(text.contains("- Machine: "));
        assert!(
            text.contains(&format!("`{:0>64}`", 7)),
            "definition hash of a_holds"
        );
        assert!(text.contains(&format!(
            "`persson-check validate d_full --full --out {}`",
            from.display()
        )));
        assert!(
            text.contains("| a\\_holds | reduced |") && text.contains("| 1, 2, 3 | 2 | 12.5 s |")
        );
        // Written atomically: nothing else in the scorecard's folder.
        assert_eq!(std::fs::read_dir(base).unwrap().count(), 1);
    }

    #[test]
    fn skipped_speed_study_is_said_or_shown_as_earlier() {
        let root = tempfile::tempdir().unwrap();
        let (from, _) = fixture(root.path());
        let out = from.join("scorecard.md");
        let opts = ReportOptions {
            from: from.clone(),
            out: out.clone(),
            golden: None,
            speed: SpeedChoice::Skip,
        };
        write(&opts, &mut |_| {}).unwrap();
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.contains("Not run (`--no-speed`), and no earlier study found."));
        assert_eq!(row(&text, "a_holds")[8], "not checked", "no golden folder");
        // Links from a scorecard inside the outcomes' folder are plain relative paths.
        assert!(text.contains("](a_holds/fig.png)"));

        let study = crate::speed::run(&tiny_speed(), &mut |_| {}).unwrap();
        study.write(&from).unwrap();
        write(&opts, &mut |_| {}).unwrap();
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text
            .contains("**Not run for this scorecard** (`--no-speed`); shown from an earlier run"));
        assert!(text.contains(&study.started_at));
    }

    #[test]
    fn unreadable_outcomes_and_empty_folders_are_errors() {
        let root = tempfile::tempdir().unwrap();
        let opts = ReportOptions {
            from: root.path().to_path_buf(),
            out: root.path().join("s.md"),
            golden: None,
            speed: SpeedChoice::Skip,
        };
        let e = write(&opts, &mut |_| {}).unwrap_err().to_string();
        assert!(e.contains("no outcomes"), "{e}");
        std::fs::write(
            root.path().join("broken.json"),
            br#"{"name": "broken", "statistic": "s", "verdict": "maybe"}"#,
        )
        .unwrap();
        let e = write(&opts, &mut |_| {}).unwrap_err().to_string();
        assert!(e.contains("broken.json") && e.contains("maybe"), "{e}");
        assert!(!root.path().join("s.md").exists());
    }

    #[test]
    fn attention_names_the_reason_a_finding_is_not_reproduced() {
        let mut o = outcome("e_holds", Verdict::Holds, Some(false), Scale::Reduced);
        o.checks.clear();
        let loaded = |o: Outcome| Loaded {
            outcome: o,
            path: PathBuf::from("e_holds.json"),
            modified: None,
        };
        let lines = attention(&[loaded(o.clone())], &[GoldenMatch::FullScene]);
        assert_eq!(lines.len(), 1);
        assert!(
            lines[0].contains("finds the assumption holds where the paper finds it violated"),
            "{lines:?}"
        );
        o.verdict = Verdict::Violated;
        let lines = attention(&[loaded(o)], &[GoldenMatch::FullScene]);
        assert!(lines[0].contains("outside the range"), "{lines:?}");
    }

    #[test]
    fn numbers_in_names_are_masked_for_grouping() {
        assert_eq!(
            strip_numbers("kappa on the 128x128 grid (lambda_s = 4.5 grid spacings)"),
            "kappa on the #x# grid (lambda_s = # grid spacings)"
        );
    }
}
