//! `speed`: the speed-against-error study, its own step of the main job: `speed --out DIR`
//! writes `DIR/speed.json`, one CSV per study and the figures (each file atomically), and
//! `report --from DIR` shows it.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::speed::{run as run_study, SpeedOptions};

use persson_check::tasks::check_out_dir;

use super::FLAGS;

/// Arguments of `speed`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Points per side of the tolerance and thread studies (the size study uses N/4 ... 2N).
    #[arg(long, default_value_t = 256, allow_negative_numbers = true)]
    n: usize,
    /// Grids of the floor (FFT pair) and warm-start studies (default: N and 2N).
    #[arg(long = "floor-n", num_args = 1..)]
    floor_n: Vec<usize>,
    /// Timed solves per row; the fastest counts.
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Output folder: speed.json, and under speed/ one CSV per study and the figures.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let mut opts = SpeedOptions::with_n(args.n);
    if !args.floor_n.is_empty() {
        opts.floor_sizes = args.floor_n;
    }
    opts.repeats = args.repeats;
    opts.validate().map_err(|e| match &e {
        Error::InvalidInput { field, .. } => {
            let flag = match field.as_str() {
                // The grid's own check names it `n`.
                "n" | "speed n" => "--n",
                "speed floor sizes" => "--floor-n",
                "speed repeats" => "--repeats",
                other => other,
            }
            .to_string();
            e.with_field(&flag)
        }
        _ => e,
    })?;
    check_out_dir(&args.out, &FLAGS)?;
    let study = run_study(&opts, &mut |line| eprintln!("speed: {line}"))?;
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, e))?;
    for path in study.write(&args.out)? {
        outln!("wrote {}", path.display());
    }
    for r in &study.floor {
        outln!(
            "floor {:>4} N = {:>5}: FFT pair {:.3e} s, {} iterations in {} s, \
             {} pairs/iteration, iteration = {} pairs, each pair used = {} pairs",
            r.solver.name(),
            r.n,
            r.fft_pair_s,
            count(r.iterations),
            shown(r.wall_s, |x| format!("{x:.3e}")),
            shown(r.pairs_per_iteration, |x| format!("{x:.2}")),
            shown(r.iteration_in_pairs, |x| format!("{x:.2}")),
            shown(r.overhead, |x| format!("{x:.2}")),
        );
    }
    for r in &study.warm {
        outln!(
            "warm  {:>4} N = {:>5}, {}: cold {} it {} s, warm {} it {} s, ratio {}",
            r.solver.name(),
            r.n,
            r.change,
            count(r.cold_iterations),
            shown(r.cold_wall_s, |x| format!("{x:.3e}")),
            count(r.warm_iterations),
            shown(r.warm_wall_s, |x| format!("{x:.3e}")),
            shown(r.ratio, |x| format!("{x:.3}")),
        );
    }
    Ok(())
}

/// A value of a row, or "n/a" where the solve failed.
fn shown(value: Option<f64>, format: impl Fn(f64) -> String) -> String {
    value.map_or_else(|| "n/a".into(), format)
}

/// A count of a row, or "n/a" where the solve failed.
fn count(value: Option<usize>) -> String {
    value.map_or_else(|| "n/a".into(), |n| n.to_string())
}
