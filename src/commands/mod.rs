//! One module per subcommand; each parses nothing itself (clap does), calls the library's
//! [`persson_check::tasks`] for the work the Python package offers too, and writes its
//! outputs only once everything has been computed. Standard output goes through
//! [`outln!`] and [`out!`]: a reader that closes the pipe early (`| head`) ends the
//! command quietly, with the status a shell gives a process its pipe closed (141).

/// `println!` for the command's standard output, ending quietly on a closed pipe.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::commands::write_stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` for the command's standard output, ending quietly on a closed pipe.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::commands::write_stdout(format_args!($($arg)*))
    };
}

pub mod audit;
pub mod check_surface;
pub mod claims;
pub mod compare;
pub mod report;
pub mod solve;
pub mod speed;
pub mod surface;
pub mod validate;

use clap::Args as ClapArgs;
use persson_check::error::Result;
use persson_check::tasks::surface::{Scene, SurfaceArgs as SurfaceRequest};
use persson_check::tasks::Flags;
use std::path::PathBuf;

/// Surface given on the command line or by a scene file.
#[derive(ClapArgs, Debug, Clone)]
pub struct SurfaceArgs {
    /// Scene file (TOML) with a [surface] table.
    #[arg(long, conflicts_with_all = ["n", "hurst", "lambda_l", "lambda_s"])]
    pub scene: Option<PathBuf>,
    /// Points per side.
    #[arg(long, allow_negative_numbers = true)]
    pub n: Option<usize>,
    /// Hurst exponent, in (0, 1).
    #[arg(long, allow_negative_numbers = true)]
    pub hurst: Option<f64>,
    /// Long-wavelength cutoff (grid units), at most N.
    #[arg(long = "lambda-l", allow_negative_numbers = true)]
    pub lambda_l: Option<f64>,
    /// Short-wavelength cutoff (grid units), at least 2.
    #[arg(long = "lambda-s", allow_negative_numbers = true)]
    pub lambda_s: Option<f64>,
    /// Seed of the realization (overrides the scene's).
    #[arg(long, allow_negative_numbers = true)]
    pub seed: Option<u64>,
}

impl SurfaceArgs {
    /// The scene (from file or flags, checked), with its seed.
    pub fn resolve(&self) -> Result<Scene> {
        SurfaceRequest {
            scene: self.scene.as_deref(),
            n: self.n,
            hurst: self.hurst,
            lambda_l: self.lambda_l,
            lambda_s: self.lambda_s,
            seed: self.seed,
        }
        .resolve(&FLAGS, "given (or use --scene FILE.toml)")
    }
}

/// The command line's spelling of parameters: `contact_area` is `--contact-area`.
pub const FLAGS: Flags<'static> = Flags { renamed: &[] };

/// The status of a process whose output pipe was closed: 128 + SIGPIPE (13), what a shell
/// reports for a Unix tool killed by it.
const CLOSED_PIPE_STATUS: i32 = 141;

/// Writes to standard output. A reader that has gone (a closed pipe) ends the process
/// with [`CLOSED_PIPE_STATUS`] and no message: the reader asked for no more. Any other
/// failure to write ends it with a message and status 1, as `println!` would have, but
/// without a panic.
pub fn write_stdout(args: std::fmt::Arguments) {
    use std::io::{ErrorKind, Write};
    let mut stdout = std::io::stdout().lock();
    if let Err(e) = stdout.write_fmt(args).and_then(|()| stdout.flush()) {
        if e.kind() == ErrorKind::BrokenPipe {
            std::process::exit(CLOSED_PIPE_STATUS);
        }
        eprintln!("error: writing to standard output: {e}");
        std::process::exit(1);
    }
}
