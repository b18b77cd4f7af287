//! `claims`: the paper's claims, full and reduced scenes side by side, as a Markdown table
//! printed or written between the markers of a file (`docs/claims.md` by default).

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::report::claims::{table, write_between_markers, MARKERS};
use persson_check::report::read_outcomes;

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
    let md = table(
        &read(&args.full, "--full")?,
        &read(&args.reduced, "--reduced")?,
    );
    match args.write {
        None => out!("{md}"),
        Some(path) => {
            write_between_markers(&path, &md)?;
            outln!(
                "wrote the claims into {} (between {} and {})",
                path.display(),
                MARKERS.0,
                MARKERS.1
            );
        }
    }
    Ok(())
}
