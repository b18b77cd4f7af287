//! The scorecard ([`crate::conventions`], section 7): `report [--from DIR] --out FILE.md`.
//!
//! Reads every outcome (`<name>.json`) in a folder and writes one Markdown file a reviewer
//! can read in a minute: a summary that names every inconclusive verdict and every finding
//! not reproduced, the paper's claims one row each ([`claims`]), one table row per
//! validation, a section per validation (account,
//! secondary statistics, checks, figures, the scene as run), the statistics measured on
//! several grids (discretisation error), the speed-against-error study ([`crate::speed`])
//! when the folder holds one (`speed.json`, written by `persson-check speed --out DIR`),
//! and the provenance needed to reproduce any row.
//!
//! The report only reads and formats: it runs nothing and computes no physics. Every
//! number in it comes from an outcome file, a golden snapshot (`golden/<name>.snap`, see
//! [`GoldenMatch`]) or the speed study's file. It reads the outcomes' folder (`from`) and
//! writes nothing there: the scorecard, atomically, and its own figures (the resolution
//! figures, under `resolution/`) go to the scorecard's folder. Links to figures and tables
//! are relative to the scorecard's folder.

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
use crate::speed::SpeedStudy;
use crate::validation::{Outcome, Verdict};

/// What `report` reads and writes.
#[derive(Debug, Clone)]
pub struct ReportOptions {
    /// Folder of the outcomes (`<name>.json`).
    pub from: PathBuf,
    /// The scorecard file (Markdown).
    pub out: PathBuf,
    /// Folder of golden snapshots (`<name>.snap`), if any.
    pub golden: Option<PathBuf>,
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
    /// Files written besides the scorecard (the resolution figures), in its folder.
    pub files: Vec<PathBuf>,
}

/// The speed study as the scorecard shows it: the one in the outcomes' folder, none, or
/// one that could not be read.
#[derive(Debug, Clone)]
enum SpeedSection {
    Found(Box<SpeedStudy>),
    Absent,
    Unreadable(String),
}

/// Writes the scorecard of the outcomes in `opts.from` to `opts.out`, with its figures
/// beside it; reads `from` only.
///
/// # Errors
///
/// If `from` holds no outcome or an unreadable one, or a file cannot be written.
pub fn write(opts: &ReportOptions) -> Result<ReportSummary> {
    let loaded = read_outcomes(&opts.from)?;
    if loaded.is_empty() {
        return Err(Error::bad_file(
            &opts.from,
            "no outcomes (<name>.json) here; run `persson-check validate --out DIR` first",
        ));
    }
    let base = format::absolute(&opts.out)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut files = Vec::new();
    let speed = read_speed(&opts.from);
    let resolution = resolution_figures(&loaded, &base, &mut files)?;
    let golden: Vec<GoldenMatch> = loaded
        .iter()
        .map(|l| GoldenMatch::of(&l.outcome, opts.golden.as_deref()))
        .collect();
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
    })
}

/// The speed study in `from` (`speed.json`), if there is one.
fn read_speed(from: &Path) -> SpeedSection {
    let path = from.join(SpeedStudy::JSON);
    if !path.exists() {
        return SpeedSection::Absent;
    }
    match SpeedStudy::read(&path) {
        Ok(study) => SpeedSection::Found(Box::new(study)),
        Err(e) => SpeedSection::Unreadable(e.to_string()),
    }
}

/// The statistics measured on several grids, each with its figure drawn under
/// `dir/resolution` (`dir`: the scorecard's folder); adds the files written to `files`.
fn resolution_figures(
    loaded: &[Loaded],
    dir: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<Resolution>> {
    let mut resolution = resolution_studies(loaded);
    for r in &mut resolution {
        let paths = crate::plot::render(&resolution_figure(r), &dir.join("resolution"))?;
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
