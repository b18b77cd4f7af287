//! `report`: the scorecard of the outcomes in a folder (conventions, section 7, in the library's docs), with the
//! speed-against-error study.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::report::{write, ReportOptions, SpeedChoice};
use persson_check::speed::SpeedOptions;
use persson_check::tasks::check_out_file;

/// Arguments of `report`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Folder of the outcomes (<name>.json), as written by `validate --out`; the speed
    /// study's files are written here too.
    #[arg(long, default_value = "out")]
    from: PathBuf,
    /// The scorecard file (Markdown).
    #[arg(long)]
    out: PathBuf,
    /// Folder of golden snapshots (<name>.snap) to compare golden values with (default:
    /// `golden` if it exists, else the source tree's golden/ if present).
    #[arg(long)]
    golden: Option<PathBuf>,
    /// Do not run the speed-against-error study (an earlier speed.json is shown, marked).
    #[arg(long = "no-speed")]
    no_speed: bool,
    /// Points per side of the speed study's grid (its size study uses N/4 ... 2N).
    #[arg(long = "speed-n", default_value_t = 256, allow_negative_numbers = true)]
    speed_n: usize,
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
    let speed = if args.no_speed {
        SpeedChoice::Skip
    } else {
        let opts = SpeedOptions::with_n(args.speed_n);
        // Everything the study's options hold derives from --speed-n.
        opts.validate().map_err(|e| e.with_field("--speed-n"))?;
        SpeedChoice::Run(opts)
    };
    let opts = ReportOptions {
        from: args.from,
        out: args.out,
        golden,
        speed,
    };
    let summary = write(&opts, &mut |line| eprintln!("speed study: {line}"))?;
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
    match summary.speed_error {
        None => Ok(()),
        Some(e) => Err(Error::invalid(
            "speed study",
            e,
            "to finish (the scorecard was written and says so)",
        )),
    }
}
