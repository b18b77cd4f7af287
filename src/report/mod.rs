//! The scorecard ([`crate::conventions`], section 7): `report [--from DIR] --out FILE.md`.
//!
//! Reads every outcome (`<name>.json`) in a folder and writes one Markdown file a reviewer
//! can read in a minute: a summary that names every inconclusive verdict and every finding
//! not reproduced, the paper's claims one row each ([`claims`]), one table row per
//! validation, a section per validation (account,
//! secondary statistics, checks, figures, the scene as run), the statistics measured on
//! several grids (discretisation error), the speed-against-error study ([`crate::speed`]),
//! and the provenance needed to reproduce any row.
//!
//! The report formats outcomes and computes no physics: every number in it comes from an
//! outcome file, a golden snapshot (`golden/<name>.snap`, see [`GoldenMatch`]) or the speed
//! study. Links to figures and tables are relative to the scorecard's folder. The file is
//! written atomically.

mod attention;
pub mod claims;
mod format;
mod golden;
mod outcomes;
mod provenance_section;
mod resolution;
mod speed_section;
mod study;
mod table;
#[cfg(test)]
mod tests;
mod validation;

pub use golden::{read_snapshot, GoldenMatch};
pub use outcomes::{read_outcome, read_outcomes, scene_grids, scene_seeds, Loaded};

pub mod compare;
pub mod trend;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use self::format::{link, md};
use self::resolution::{resolution_figure, resolution_studies, Resolution};
use crate::error::{Error, Result};
use crate::provenance::{self, Machine};
use crate::speed::{SpeedOptions, SpeedStudy};
use crate::validation::{Outcome, Verdict};

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
    /// The headline verdicts against the paper's, in words.
    pub headlines: String,
    /// The claims counted by result, in words.
    pub claims: String,
    /// One line per inconclusive verdict, headline verdict not the paper's, failed guard,
    /// disagreeing solver or golden mismatch.
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
    let speed = prepare_speed(opts, progress, &mut files)?;
    let resolution = resolution_figures(&loaded, &opts.from, &mut files)?;
    let golden: Vec<GoldenMatch> = loaded
        .iter()
        .map(|l| GoldenMatch::of(&l.outcome, opts.golden.as_deref()))
        .collect();
    let base = format::absolute(&opts.out)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let attention = attention::attention(&loaded, &golden);
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
    let outcomes: Vec<&Outcome> = loaded.iter().map(|l| &l.outcome).collect();
    Ok(ReportSummary {
        path: opts.out.clone(),
        validations: loaded.iter().map(|l| l.outcome.name.clone()).collect(),
        headlines: claims::headlines(&outcomes),
        claims: claims::counts(&outcomes),
        attention,
        files,
        speed_error: match speed {
            SpeedSection::Failed(e) => Some(e),
            _ => None,
        },
    })
}

/// Runs the speed study, or reads an earlier one; adds the files written to `files`.
fn prepare_speed(
    opts: &ReportOptions,
    progress: &mut dyn FnMut(&str),
    files: &mut Vec<PathBuf>,
) -> Result<SpeedSection> {
    Ok(match &opts.speed {
        SpeedChoice::Run(speed_opts) => match crate::speed::run(speed_opts, progress) {
            Ok(study) => {
                files.extend(study.write(&opts.from)?);
                SpeedSection::Fresh(Box::new(study))
            }
            Err(e) => SpeedSection::Failed(e.to_string()),
        },
        SpeedChoice::Skip => {
            let path = opts.from.join(SpeedStudy::JSON);
            if !path.exists() {
                SpeedSection::Skipped
            } else {
                match SpeedStudy::read(&path) {
                    Ok(study) => SpeedSection::Earlier(Box::new(study)),
                    Err(e) => SpeedSection::Failed(format!("earlier study unreadable: {e}")),
                }
            }
        }
    })
}

/// The statistics measured on several grids, each with its figure drawn under
/// `from/resolution`; adds the files written to `files`.
fn resolution_figures(
    loaded: &[Loaded],
    from: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<Resolution>> {
    let mut resolution = resolution_studies(loaded);
    for r in &mut resolution {
        let paths = crate::plot::render(&resolution_figure(r), &from.join("resolution"))?;
        r.figure = paths
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == "png"))
            .cloned();
        files.extend(paths);
    }
    Ok(resolution)
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

fn reproduced_cell(o: &Outcome) -> String {
    match o.reproduced {
        Some(true) => "as the paper".into(),
        Some(false) => "**not as the paper**".into(),
        None => "inconclusive".into(),
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
        let outcomes: Vec<&Outcome> = self.loaded.iter().map(|l| &l.outcome).collect();
        claims::section(&mut s, &outcomes);
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
        let outcomes: Vec<&Outcome> = self.loaded.iter().map(|l| &l.outcome).collect();
        let _ = writeln!(
            s,
            "**Summary.** {n} validation{}: {}. The paper's claims: {} (each judged once, \
             by its rule; none makes a validation's headline).\n",
            if n == 1 { "" } else { "s" },
            claims::headlines(&outcomes),
            claims::counts(&outcomes),
        );
        if self.attention.is_empty() {
            let _ = writeln!(
                s,
                "No verdict is inconclusive, every headline verdict is the paper's, no guard \
                 fails, the solvers agree, and no golden value differs.\n"
            );
        } else {
            let _ = writeln!(s, "**Needs attention:**\n");
            for line in self.attention {
                let _ = writeln!(s, "- {}", md(line));
            }
            s.push('\n');
        }
    }
}
