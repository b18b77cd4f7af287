//! `claims`: the paper's claims, full and reduced scenes side by side, as a Markdown table
//! printed or written between the markers of a file (`docs/claims.md` by default); with
//! `--register`, the register of the claims' rules brought up to date
//! (`validations/register.json`).

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::report::claims::{chart, page, write_between_markers, CHART, MARKERS};
use persson_check::report::read_outcomes;
use persson_check::validation::register::{Register, REGISTER_FILE};
use persson_check::validation::source::{builtin_sources, claims_of};

/// The file that holds the committed claims table, relative to the repository's root.
pub const CLAIMS_FILE: &str = "docs/claims.md";

/// Arguments of `claims`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Folder of the full scenes' outcomes (<name>.json).
    #[arg(long, default_value = "results/full")]
    full: PathBuf,
    /// Folder of the reduced scenes' outcomes.
    #[arg(long, default_value = "results/reduced")]
    reduced: PathBuf,
    /// A Markdown file to write the table into, between its `<!-- paper-claims -->` and
    /// `<!-- /paper-claims -->` lines; `--write` alone writes `docs/claims.md` (without
    /// `--write`: print the table).
    #[arg(long, value_name = "FILE.md", num_args = 0..=1, default_missing_value = CLAIMS_FILE)]
    write: Option<PathBuf>,
    /// Register the shipped definitions' claims in the register of rules (a new claim, or
    /// a rule changed with its amendment) and record the verdicts of the committed
    /// outcomes under each rule; `--register` alone writes `validations/register.json`.
    #[arg(long, value_name = "FILE.json", num_args = 0..=1, default_missing_value = REGISTER_FILE)]
    register: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    let read = |dir: &PathBuf, flag: &str| -> Result<Vec<_>> {
        if !dir.is_dir() {
            return Err(Error::invalid(
                flag,
                dir.display(),
                "an existing folder of outcomes (<name>.json)",
            ));
        }
        Ok(read_outcomes(dir)?.into_iter().map(|l| l.outcome).collect())
    };
    let (full, reduced) = (
        read(&args.full, "--full")?,
        read(&args.reduced, "--reduced")?,
    );
    if let Some(path) = &args.register {
        let mut register = if path.exists() {
            Register::read(path)?
        } else {
            Register {
                about: REGISTER_ABOUT.into(),
                ..Register::default()
            }
        };
        let day = persson_check::provenance::now_utc();
        let done = register.update(
            &claims_of(&builtin_sources())?,
            (&day[..10], persson_check::provenance::COMMIT),
            &full,
            &reduced,
        )?;
        register.write(path)?;
        for line in &done {
            outln!("{line}");
        }
        outln!(
            "{}: {} claims, {} registered or amended now",
            path.display(),
            register.claims.len(),
            done.len()
        );
        return Ok(());
    }
    let register = Register::read(std::path::Path::new(REGISTER_FILE)).ok();
    match args.write {
        None => out!("{}", page(&full, &reduced, register.as_ref(), None)),
        Some(path) => {
            // The chart beside the page: figures/claims.svg (and .png) in its folder.
            let dir = path
                .parent()
                .unwrap_or(std::path::Path::new("."))
                .join("figures");
            std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
            let outcomes: Vec<_> = full.iter().collect();
            persson_check::plot::render_intervals(&chart(&outcomes), &dir)?;
            let md = page(
                &full,
                &reduced,
                register.as_ref(),
                Some(&format!("figures/{CHART}.svg")),
            );
            write_between_markers(&path, &md)?;
            outln!(
                "wrote the claims into {} (between {} and {}) and their chart into {}",
                path.display(),
                MARKERS.0,
                MARKERS.1,
                dir.join(format!("{CHART}.svg")).display()
            );
        }
    }
    Ok(())
}

/// What the register's file says of itself.
const REGISTER_ABOUT: &str = "Every rule each claim of validations/*.toml has been decided \
under, oldest first: the hash of the rule as it decides (phrase, measure, region, alternative, \
significance, kind, reading), the day and commit it was registered, and the verdicts of the \
committed outcomes under it. Written by `persson-check claims --register`; a rule changed \
after an outcome exists is an amendment, stated with its reason in the claim.";
