//! Named validations: each of Persson's assumptions as a reduced experiment with a verdict
//! (SPEC section 5).
//!
//! A validation is a declarative file (`validations/<name>.toml`, see [`Definition`]) that
//! names an *experiment* (the code that runs it), the statistic, Persson's prediction, the
//! paper's finding and the rule for the verdict, and holds two scenes: `reduced` (small,
//! run by `cargo test`) and `full` (paper scale, run from the command line).
//!
//! An [`Experiment`] splits its scene into independent jobs (usually one per realization),
//! runs them in parallel, and reduces their results to a [`Conclusion`]: the headline
//! statistic with its standard error, Persson's value for it, secondary statistics,
//! checks of the paper's finding, tables and figures. The runner ([`run`]) turns a
//! conclusion into an [`Outcome`] with a verdict computed from the data
//! ([`VerdictRule::judge`]) and writes `<name>.json`, `<name>.csv` and the figures.
//!
//! Every finished job is written to disk at once (atomically), so an interrupted ensemble
//! resumes where it stopped (`--resume`), and re-runs only what is missing. Job results are
//! filed under the experiment's family and a hash of scene and job, so validations that
//! draw different statistics from the same runs (assumptions (a) and (b)) run them once.

pub mod builtin;
mod runner;

pub use runner::{run, run_all, RunOptions};

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::plot::{Figure, Raster};
use crate::stats::Estimate;

/// The verdict on an assumption.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The measurement agrees with Persson's prediction to within the stated resolution.
    Holds,
    /// The measurement differs from Persson's prediction beyond the stated significance.
    Violated,
    /// The experiment's error bar is too wide to tell.
    Inconclusive,
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Verdict::Holds => "holds",
            Verdict::Violated => "violated",
            Verdict::Inconclusive => "inconclusive",
        })
    }
}

/// How a verdict is reached from `value +- std_error` and Persson's prediction.
///
/// With `z` the significance (in standard errors) and `resolution` the smallest deviation
/// from Persson's value that matters:
///
/// * **violated** when `|value - persson| > z std_error` (the prediction lies outside the
///   confidence interval);
/// * **holds** when the whole interval `value +- z std_error` lies within
///   `persson +- resolution` (an equivalence test);
/// * **inconclusive** otherwise: the interval contains the prediction but is too wide to
///   exclude a deviation of the size that matters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerdictRule {
    /// Significance `z`, in standard errors (e.g. 3).
    pub significance: f64,
    /// Smallest deviation from Persson's prediction that matters (absolute, in the
    /// statistic's units).
    pub resolution: f64,
}

impl VerdictRule {
    /// The verdict for `measured` against Persson's `persson`.
    pub fn judge(&self, measured: Estimate, persson: f64) -> Verdict {
        let half = self.significance * measured.std_error;
        if !(measured.value.is_finite() && half.is_finite()) {
            return Verdict::Inconclusive;
        }
        let dev = (measured.value - persson).abs();
        if dev > half {
            Verdict::Violated
        } else if dev + half <= self.resolution {
            Verdict::Holds
        } else {
            Verdict::Inconclusive
        }
    }

    fn validate(&self) -> Result<()> {
        if !(self.significance.is_finite() && self.significance > 0.0) {
            return Err(Error::invalid(
                "verdict.significance",
                self.significance,
                "a number of standard errors > 0",
            ));
        }
        if !(self.resolution.is_finite() && self.resolution > 0.0) {
            return Err(Error::invalid(
                "verdict.resolution",
                self.resolution,
                "a deviation > 0",
            ));
        }
        Ok(())
    }
}

/// What the paper found, and how to tell whether a run reproduces it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperFinding {
    /// The finding in words (with the paper's numbers).
    pub finding: String,
    /// The paper's verdict on the assumption.
    pub verdict: Verdict,
    /// The paper's value of the headline statistic, if it states one.
    #[serde(default)]
    pub value: Option<f64>,
    /// The range of the headline statistic that counts as reproducing the paper.
    #[serde(default)]
    pub range: Option<(f64, f64)>,
}

/// A validation file: the header, and a scene of type `S` at two scales.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Definition<S> {
    /// Unique name (the file stem), e.g. `c_reentry`.
    pub name: String,
    /// The experiment that runs it (see [`builtin::EXPERIMENTS`]).
    pub experiment: String,
    /// Short title.
    pub title: String,
    /// Persson's assumption under test.
    pub assumption: String,
    /// The headline statistic in words.
    pub statistic: String,
    /// Persson's prediction in words.
    pub persson: String,
    /// Verdict rule.
    pub verdict: VerdictRule,
    /// The paper's finding.
    pub paper: PaperFinding,
    /// Small scene for `cargo test`.
    pub reduced: S,
    /// Paper-scale scene for the command line.
    pub full: S,
}

/// Which of a definition's scenes to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// The reduced scene.
    Reduced,
    /// The full scene.
    Full,
}

impl fmt::Display for Scale {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Scale::Reduced => "reduced",
            Scale::Full => "full",
        })
    }
}

/// A secondary statistic, shown in the validation's section of the scorecard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detail {
    /// Name.
    pub name: String,
    /// Measurement.
    pub value: Estimate,
    /// Persson's value, if any.
    pub persson: Option<f64>,
    /// The paper's value, if any.
    pub paper: Option<f64>,
    /// Points per side of the grid the value was measured on, when the detail is one step
    /// of a resolution study (statistic against grid resolution).
    #[serde(default)]
    pub grid: Option<usize>,
}

/// A check of the paper's finding; all must pass for the finding to count as reproduced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// What is checked.
    pub name: String,
    /// Whether it passed.
    pub passed: bool,
    /// The numbers behind it.
    pub detail: String,
}

/// A table of numbers, written as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// File stem.
    pub name: String,
    /// Column names.
    pub columns: Vec<String>,
    /// Rows (one value per column).
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with `columns`.
    pub fn new(name: impl Into<String>, columns: &[&str]) -> Self {
        Self {
            name: name.into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.columns.len());
        self.rows.push(row);
    }

    /// Writes the table as CSV to `path`, atomically.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut w = csv::Writer::from_writer(Vec::new());
        let to_io = |e: csv::Error| Error::io(path, std::io::Error::other(e));
        w.write_record(&self.columns).map_err(to_io)?;
        for row in &self.rows {
            w.write_record(row.iter().map(|v| format!("{v}")))
                .map_err(to_io)?;
        }
        let bytes = w
            .into_inner()
            .map_err(|e| Error::io(path, std::io::Error::other(e.to_string())))?;
        crate::io::write_atomic(path, &bytes)
    }
}

/// What an experiment concludes from its jobs.
#[derive(Debug, Clone, Default)]
pub struct Conclusion {
    /// The headline statistic.
    pub measured: Option<Estimate>,
    /// Persson's prediction of the headline statistic.
    pub persson: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Checks of the paper's finding beyond the headline verdict and range.
    pub checks: Vec<Check>,
    /// A short account, generated from the numbers.
    pub account: String,
    /// Values kept as golden snapshots (rounded by the experiment).
    pub golden: BTreeMap<String, f64>,
    /// Tables; the first is written as `<name>.csv`.
    pub tables: Vec<Table>,
    /// Figures.
    pub figures: Vec<Figure>,
    /// Raster images (contact maps).
    pub rasters: Vec<Raster>,
    /// Largest solver residual over all solves.
    pub max_residual: f64,
}

/// Where a run writes, and what it needs to know about the scene.
#[derive(Debug, Clone)]
pub struct JobContext {
    /// The validation's name.
    pub name: String,
    /// The scale being run.
    pub scale: Scale,
    /// Directory for per-job state that must survive interruption (checkpoints). The
    /// runner empties it before a run without `--resume` and removes it once the job's
    /// result is stored; a job only reads and writes it.
    pub state_dir: PathBuf,
}

/// The code behind a family of validations.
pub trait Experiment {
    /// Name of the job family: experiments that share a family share job results (two
    /// validations that differ only in the statistic they draw from the same runs).
    const FAMILY: &'static str;

    /// The scene (the `reduced` and `full` tables of a definition).
    type Scene: Serialize + DeserializeOwned + Sync + fmt::Debug;
    /// One independent unit of work (usually one realization).
    type Job: Serialize + DeserializeOwned + Clone + Send + Sync + fmt::Debug;
    /// A job's result (kept on disk for resuming).
    type JobResult: Serialize + DeserializeOwned + Send;

    /// Checks the scene's ranges; errors name the field.
    fn validate(scene: &Self::Scene) -> Result<()>;

    /// The jobs of a scene.
    fn jobs(scene: &Self::Scene) -> Vec<Self::Job>;

    /// Runs one job.
    fn run_job(scene: &Self::Scene, job: &Self::Job, ctx: &JobContext) -> Result<Self::JobResult>;

    /// Reduces all jobs' results (in job order) to a conclusion.
    fn conclude(
        def: &Definition<Self::Scene>,
        scene: &Self::Scene,
        results: &[(Self::Job, Self::JobResult)],
    ) -> Result<Conclusion>;
}

/// The record of one validation run: `<name>.json` (SPEC section 7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Name.
    pub name: String,
    /// Title.
    pub title: String,
    /// Assumption under test.
    pub assumption: String,
    /// The headline statistic in words.
    pub statistic: String,
    /// The measured headline statistic.
    pub value: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Persson's prediction of the statistic.
    pub persson: f64,
    /// Persson's prediction in words.
    pub persson_text: String,
    /// The paper's finding in words.
    pub paper: String,
    /// The paper's value, if stated.
    pub paper_value: Option<f64>,
    /// The paper's verdict.
    pub paper_verdict: Verdict,
    /// The verdict of this run.
    pub verdict: Verdict,
    /// Whether the run reproduces the paper's finding (`None` when inconclusive).
    pub reproduced: Option<bool>,
    /// The verdict rule used.
    pub rule: VerdictRule,
    /// Scale of the scene.
    pub scale: Scale,
    /// The scene, as run.
    pub scene: serde_json::Value,
    /// Hash of the definition file (SHA-256, hex).
    pub definition_sha256: String,
    /// Wall time of the whole validation, seconds.
    pub wall_s: f64,
    /// Largest solver residual over all solves.
    pub max_residual: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Checks of the paper's finding.
    pub checks: Vec<Check>,
    /// Account generated from the numbers.
    pub account: String,
    /// Golden values.
    pub golden: BTreeMap<String, f64>,
    /// Files written (tables, figures), relative to the output directory.
    pub files: Vec<String>,
    /// Worker threads used.
    pub threads: usize,
}

/// A definition's text and where it came from.
#[derive(Debug, Clone)]
pub struct Source {
    /// File path (or `builtin:<name>`).
    pub path: PathBuf,
    /// TOML text.
    pub text: String,
}

impl Source {
    /// Reads a definition file.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            text,
        })
    }

    /// The `name` and `experiment` keys, read before the file is parsed in full.
    pub fn header(&self) -> Result<(String, String)> {
        let table: toml::Table = crate::engine::scene::parse_toml(&self.path, &self.text)?;
        let get = |key: &str| -> Result<String> {
            match table.get(key) {
                Some(toml::Value::String(s)) => Ok(s.clone()),
                Some(other) => Err(Error::bad_file(
                    &self.path,
                    format!("{key} must be a string, found {}", other.type_str()),
                )),
                None => Err(Error::bad_file(
                    &self.path,
                    format!("missing field `{key}`"),
                )),
            }
        };
        Ok((get("name")?, get("experiment")?))
    }

    /// Parses the whole definition with scene type `S`, checking the header's ranges.
    pub fn parse<S: DeserializeOwned>(&self) -> Result<Definition<S>> {
        let def: Definition<S> = crate::engine::scene::parse_toml(&self.path, &self.text)?;
        def.verdict
            .validate()
            .map_err(|e| Error::bad_file(&self.path, e.to_string()))?;
        let stem = self
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string());
        if let Some(stem) = stem {
            if !self.path.to_string_lossy().starts_with("builtin:") && stem != def.name {
                return Err(Error::bad_file(
                    &self.path,
                    format!(
                        "name = \"{}\" must match the file name \"{stem}\"",
                        def.name
                    ),
                ));
            }
        }
        Ok(def)
    }

    /// SHA-256 of the text, hex.
    pub fn sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        let digest = Sha256::digest(self.text.as_bytes());
        digest.iter().map(|b| format!("{b:02x}")).collect()
    }
}
