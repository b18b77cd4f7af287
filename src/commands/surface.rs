//! `surface`: generate a realization and write its heights.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::engine::fft::Fft2;
use persson_check::engine::scene::check_zeta;
use persson_check::engine::surface::Surface;
use persson_check::error::Result;

use super::{check_out_file, SurfaceArgs};

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
    check_out_file(&args.out)?;
    let (scene, seed) = args.surface.resolve()?;
    let zeta = args.zeta.unwrap_or(scene.surface.zeta_max());
    check_zeta(zeta, scene.surface.zeta_max()).map_err(|e| e.with_field("--zeta"))?;
    let surface = Surface::generate(&scene.surface.params(seed))?;
    let fft = Fft2::new(surface.grid());
    let h = surface.heights_at(zeta, &fft);
    persson_check::io::npy::write_field(&args.out, surface.grid().n(), &h)?;
    Ok(())
}
