//! One module per subcommand; each parses nothing itself (clap does) and writes its
//! outputs only once everything has been computed.

pub mod report;
pub mod solve;
pub mod surface;
pub mod validate;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::scene::{read_scene, Scene, SurfaceScene};
use persson_check::surface::{Amplitudes, Surface};
use std::path::PathBuf;

/// Surface given on the command line or by a scene file.
#[derive(ClapArgs, Debug, Clone)]
pub struct SurfaceArgs {
    /// Scene file (TOML) with a [surface] table.
    #[arg(long, conflicts_with_all = ["n", "hurst", "lambda_l", "lambda_s"])]
    pub scene: Option<PathBuf>,
    /// Points per side.
    #[arg(long)]
    pub n: Option<usize>,
    /// Hurst exponent, in (0, 1).
    #[arg(long)]
    pub hurst: Option<f64>,
    /// Long-wavelength cutoff (grid units), at most N.
    #[arg(long = "lambda-l")]
    pub lambda_l: Option<f64>,
    /// Short-wavelength cutoff (grid units), at least 2.
    #[arg(long = "lambda-s")]
    pub lambda_s: Option<f64>,
    /// Seed of the realization (overrides the scene's).
    #[arg(long)]
    pub seed: Option<u64>,
}

impl SurfaceArgs {
    /// The scene (from file or flags), with its seed.
    pub fn resolve(&self) -> Result<(Scene, u64)> {
        let mut scene = match &self.scene {
            Some(path) => read_scene(path)?,
            None => {
                let missing = |name: &str| {
                    Error::invalid(name, "missing", "given (or use --scene FILE.toml)")
                };
                let surface = SurfaceScene {
                    n: self.n.ok_or_else(|| missing("--n"))?,
                    hurst: self.hurst.ok_or_else(|| missing("--hurst"))?,
                    lambda_l: self.lambda_l.ok_or_else(|| missing("--lambda-l"))?,
                    lambda_s: self.lambda_s.ok_or_else(|| missing("--lambda-s"))?,
                    lambda_r: None,
                    amplitudes: Amplitudes::Gaussian,
                    rms_gradient: 1.0,
                    seed: None,
                };
                surface.validate()?;
                Scene {
                    surface,
                    solve: Default::default(),
                }
            }
        };
        let seed = self.seed.or(scene.surface.seed).ok_or_else(|| {
            Error::invalid(
                "seed",
                "missing",
                "given (--seed K or seed = K in the scene)",
            )
        })?;
        scene.surface.seed = Some(seed);
        Ok((scene, seed))
    }

    /// The generated surface.
    pub fn generate(&self) -> Result<(Scene, Surface)> {
        let (scene, seed) = self.resolve()?;
        let surface = Surface::generate(&scene.surface.params(seed))?;
        Ok((scene, surface))
    }
}
