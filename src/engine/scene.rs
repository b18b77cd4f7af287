//! Scene files: TOML descriptions of a surface and of a solve ([`crate::conventions`], section 7).
//!
//! ```toml
//! [surface]
//! n = 256            # points per side
//! hurst = 0.8        # H in (0, 1)
//! lambda_l = 128     # long-wavelength cutoff, <= L
//! lambda_s = 4       # short-wavelength cutoff, >= 2 grid spacings
//! seed = 1
//! # lambda_r = 256   # optional roll-off plateau up to lambda_r
//! # amplitudes = "gaussian" | "random_phase"
//! # rms_gradient = 1.0
//!
//! [solve]            # optional; command-line flags take precedence
//! zeta = 16          # magnification in [1, lambda_l / lambda_s]
//! contact_area = 0.1 # or p0 = 0.05
//! solver = "cg"      # any name of SolverKind::ALL: "gfmd", "cg", "fire"
//! tol = 1e-8
//! ```
//!
//! Unknown keys, missing fields, wrong types and values out of range are errors that name
//! the file, the field and the allowed range.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::engine::solver::SolveOptions;
use crate::engine::solver::SolverKind;
use crate::engine::surface::SurfaceModel;
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::{check_open, check_positive, Error, Result};

/// The `[solve]` table: load, magnification and solver settings.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveScene {
    /// Magnification.
    pub zeta: Option<f64>,
    /// Mean pressure.
    pub p0: Option<f64>,
    /// Target relative contact area (instead of `p0`).
    pub contact_area: Option<f64>,
    /// Solver.
    pub solver: Option<SolverKind>,
    /// Residual tolerance.
    pub tol: Option<f64>,
    /// Effective modulus.
    pub e_star: Option<f64>,
}

impl SolveScene {
    /// Checks every range given, with `zeta_max` the surface's largest magnification;
    /// errors name the key as `solve.KEY`.
    ///
    /// # Errors
    ///
    /// If a value given is out of range, or both `p0` and `contact_area` are given; the
    /// error names the key as `solve.KEY`.
    pub fn validate(&self, zeta_max: f64) -> Result<()> {
        if let Some(zeta) = self.zeta {
            check_zeta(zeta, zeta_max).map_err(|e| e.with_field("solve.zeta"))?;
        }
        if let Some(p0) = self.p0 {
            check_positive("solve.p0", p0)?;
        }
        if let Some(a) = self.contact_area {
            check_open("solve.contact_area", a, 0.0, 1.0)?;
        }
        if self.p0.is_some() && self.contact_area.is_some() {
            return Err(Error::invalid(
                "solve",
                "both p0 and contact_area",
                "one of p0 or contact_area",
            ));
        }
        if let Some(tol) = self.tol {
            SolveOptions::with_tol(tol)
                .validate()
                .map_err(|e| e.with_field("solve.tol"))?;
        }
        match self.e_star {
            Some(e_star) => check_positive("solve.e_star", e_star),
            None => Ok(()),
        }
    }
}

/// A scene file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The surface (the `[surface]` table).
    pub surface: SurfaceModel,
    /// The solve.
    #[serde(default)]
    pub solve: SolveScene,
}

impl Scene {
    /// Checks every range: the surface's, then the solve's against the surface's
    /// `zeta_max`.
    ///
    /// # Errors
    ///
    /// As [`SurfaceModel::validate`] and [`SolveScene::validate`].
    pub fn validate(&self) -> Result<()> {
        self.surface.validate()?;
        self.solve.validate(self.surface.zeta_max())
    }
}

/// Reads and checks a scene file.
///
/// # Errors
///
/// If the file cannot be read ([`Error::Io`]), or as [`parse_scene`].
pub fn read_scene(path: &Path) -> Result<Scene> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_scene(&text, path)
}

/// Parses and checks the text of a scene file; errors name `origin` (the file).
///
/// # Errors
///
/// If the text is not a scene's TOML or a value is out of range ([`Error::BadFile`],
/// naming `origin`).
pub fn parse_scene(text: &str, origin: &Path) -> Result<Scene> {
    let scene = parse_toml::<Scene>(origin, text)?;
    scene
        .validate()
        .map_err(|e| Error::bad_file(origin, e.to_string()))?;
    Ok(scene)
}

/// Parses TOML text into `T`, naming the file in the error.
///
/// # Errors
///
/// If the text is not TOML of `T`'s shape ([`Error::BadFile`], naming `path` and the
/// line).
pub fn parse_toml<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| Error::bad_file(path, toml_message(text, &e)))
}

/// The `toml` crate's error on one line: where (line number and that line's text, which
/// names the key), then what is wrong and what was expected.
fn toml_message(text: &str, e: &toml::de::Error) -> String {
    let message = e.message().trim_end().replace('\n', " ");
    let Some(span) = e.span() else {
        return message;
    };
    let start = span.start.min(text.len());
    let line = text.as_bytes()[..start]
        .iter()
        .filter(|&&b| b == b'\n')
        .count();
    let source: String = text
        .lines()
        .nth(line)
        .unwrap_or("")
        .trim()
        .chars()
        .take(60)
        .map(|c| if c.is_control() { '\u{fffd}' } else { c })
        .collect();
    if source.is_empty() {
        format!("line {}: {message}", line + 1)
    } else {
        format!("line {}: `{source}`: {message}", line + 1)
    }
}

/// Checks a magnification against `[1, zeta_max]`.
///
/// # Errors
///
/// If `zeta` is not finite or outside `[1, zeta_max]`.
pub fn check_zeta(zeta: f64, zeta_max: f64) -> Result<()> {
    if zeta.is_finite() && (1.0..=zeta_max * (1.0 + ZETA_SLACK)).contains(&zeta) {
        Ok(())
    } else {
        Err(Error::invalid(
            "zeta",
            zeta,
            format!("in [1, zeta_max = {zeta_max}]"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Scene> {
        parse_scene(text, Path::new("scene.toml"))
    }

    #[test]
    fn reads_a_scene_and_names_bad_fields() {
        let ok = "[surface]\nn = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseed = 3\n";
        let s = parse(ok).unwrap();
        assert_eq!(s.surface.seed, Some(3));
        let e = parse(&ok.replace("seed = 3", "sead = 3"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("scene.toml") && e.contains("sead"), "{e}");
        let e = parse(&ok.replace("hurst = 0.8", "hurst = 1.2"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("hurst") && e.contains("(0, 1)"), "{e}");
        let e = parse(&ok.replace("lambda_s = 4", "lambda_s = 1"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("lambda_s") && e.contains("2 grid spacings"),
            "{e}"
        );
        let e = parse(&ok.replace("lambda_l = 32", "lambda_l = 128"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("lambda_l") && e.contains("L = 64"), "{e}");
        let e = parse(&ok.replace("n = 64\n", "")).unwrap_err().to_string();
        assert!(e.contains("missing field") && e.contains("n"), "{e}");
        let e = parse(&ok.replace("n = 64", "n = \"big\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("invalid type"), "{e}");
    }

    #[test]
    fn zeta_range() {
        assert!(check_zeta(1.0, 8.0).is_ok());
        assert!(check_zeta(8.0, 8.0).is_ok());
        let e = check_zeta(0.5, 8.0).unwrap_err().to_string();
        assert!(e.contains("zeta") && e.contains("[1, zeta_max = 8]"), "{e}");
    }
}
