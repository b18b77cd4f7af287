//! `surface`: generate a realization and write its heights.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::Result;
use persson_check::tasks::{check_out_file, surface};

use super::{SurfaceArgs, FLAGS};

/// Arguments of `surface`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    #[command(flatten)]
    surface: SurfaceArgs,
    /// Magnification: keep modes with |q| <= zeta q_l (default: full resolution).
    #[arg(long, allow_negative_numbers = true)]
    zeta: Option<f64>,
    /// Output .npy file (float64, N x N).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    check_out_file(&args.out, &FLAGS)?;
    let scene = args.surface.resolve()?;
    let h = surface::generate(&scene, args.zeta, &FLAGS)?;
    persson_check::io::npy::write_field(&args.out, scene.surface.n, &h)?;
    Ok(())
}
