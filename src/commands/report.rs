//! `report`: the scorecard of the outcomes in a folder (conventions, section 7, in the
//! library's docs). It only reads `--from` (the speed study shows when `speed --out` has
//! written one there) and writes the scorecard and its figures beside `--out`.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::report::{write, ReportOptions};
use persson_check::tasks::check_out_file;

/// Arguments of `report`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Folder of the outcomes (<name>.json), as written by `validate --out`, and of the
    /// speed study if `speed --out` wrote one there; only read.
    #[arg(long, default_value = "out")]
    from: PathBuf,
    /// The scorecard file (Markdown); its figures are drawn beside it.
    #[arg(long)]
    out: PathBuf,
    /// Folder of golden snapshots (<name>.snap) to compare golden values with (default:
    /// `golden` if it exists, else the source tree's golden/ if present).
    #[arg(long)]
    golden: Option<PathBuf>,
    /// History of the headlines, one JSON line per night: records these outcomes' headlines
    /// as tonight's line (created when missing) and adds the trend figure of the last
    /// nights to the scorecard.
    #[arg(long)]
    history: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    if !args.from.is_dir() {
        return Err(Error::invalid(
            "--from",
            args.from.display(),
            "an existing folder of outcomes (<name>.json), as written by `validate --out`",
        ));
    }
    check_out_file(&args.out, &super::FLAGS)?;
    let golden = match args.golden {
        Some(dir) if dir.is_dir() => Some(dir),
        Some(dir) => {
            return Err(Error::invalid(
                "--golden",
                dir.display(),
                "an existing folder of <name>.snap files",
            ))
        }
        None => [
            PathBuf::from("golden"),
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden"),
        ]
        .into_iter()
        .find(|d| d.is_dir()),
    };
    let opts = ReportOptions {
        from: args.from,
        out: args.out,
        golden,
    };
    let summary = write(&opts)?;
    if let Some(history) = &args.history {
        persson_check::report::trend::append(&opts.out, &opts.from, history)?;
        outln!("recorded the headlines in {}", history.display());
    }
    outln!(
        "wrote {} ({} validation{})",
        summary.path.display(),
        summary.validations.len(),
        if summary.validations.len() == 1 {
            ""
        } else {
            "s"
        }
    );
    outln!("{}", summary.headlines);
    outln!("the paper's claims: {}", summary.claims);
    for line in &summary.attention {
        outln!("attention: {line}");
    }
    Ok(())
}
