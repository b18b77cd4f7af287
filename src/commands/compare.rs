//! `compare BASE NEW`: two folders of outcomes compared statistic by statistic
//! ([`persson_check::report::compare`]). Exit code 0 when nothing moved beyond the
//! threshold and nothing flipped, 1 when something did, 2 when they could not be compared.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::Result;
use persson_check::report::compare::{compare, Z_THRESHOLD};
use persson_check::tasks::check_out_file;

/// Arguments of `compare`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// The folder of outcomes compared against (e.g. the committed results/reduced).
    base: PathBuf,
    /// The folder of outcomes under test (e.g. a fresh `validate --out`).
    new: PathBuf,
    /// The Markdown page; the JSON is written beside it (same name, .json).
    #[arg(long, default_value = "compare.md")]
    out: PathBuf,
    /// A statistic moved by more than this many combined standard errors fails.
    #[arg(long, default_value_t = Z_THRESHOLD, allow_negative_numbers = true)]
    z: f64,
}

/// Compares, writes the page and its JSON, prints what moved; whether nothing did.
pub fn run(args: Args) -> Result<bool> {
    check_out_file(&args.out, &super::FLAGS)?;
    let c = compare(&args.base, &args.new, args.z)?;
    let (md, json) = c.write(&args.out)?;
    outln!("{}", c.summary);
    for s in c.statistics.iter().filter(|s| s.beyond) {
        outln!(
            "moved: {} {}: z = {:+.1}",
            s.outcome,
            s.key,
            s.z.unwrap_or(f64::NAN)
        );
    }
    for f in &c.flips {
        outln!("flipped: {} {}: {} -> {}", f.outcome, f.key, f.base, f.new);
    }
    outln!("wrote {} and {}", md.display(), json.display());
    Ok(c.passed)
}
