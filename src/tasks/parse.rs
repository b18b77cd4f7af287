//! The parsers of what a user gives: solver and theory names, the load (a mean pressure
//! `p0` or a target contact area), and the ranges checked before any work (a
//! magnification's lower bound before the surface gives its upper one, integer counts).
//! Errors name the parameter through the front end's [`Spelling`].

use crate::engine::solver::SolverKind;
use crate::error::{check_open, check_positive, Error, Result};
use crate::persson::Correction;

use super::Spelling;

/// Most worker threads a front end starts.
pub const MAX_THREADS: u64 = 1024;

/// Most shares a run of the validations is split into.
pub const MAX_SHARDS: u64 = 100_000;

/// The solver named `name`, one of [`SolverKind::NAMES`].
///
/// # Errors
///
/// If `name` is none of [`SolverKind::NAMES`].
pub fn solver(name: &str) -> Result<SolverKind> {
    SolverKind::from_name(name)
        .ok_or_else(|| Error::invalid("solver", format!("{name:?}"), SolverKind::listed()))
}

/// The variant of Persson's theory named `name`: `"original"` (no correction),
/// `"yang_persson"` or `"corrected"` (gamma = 0.42), `"wang_mueser"` (gamma = 5/9).
///
/// # Errors
///
/// If `name` is none of the variants above.
pub fn theory_variant(name: &str) -> Result<Option<Correction>> {
    match name {
        "original" => Ok(None),
        "yang_persson" | "corrected" => Ok(Some(Correction::yang_persson())),
        "wang_mueser" => Ok(Some(Correction::wang_mueser())),
        other => Err(Error::invalid(
            "variant",
            format!("{other:?}"),
            "\"original\", \"yang_persson\" or \"wang_mueser\"",
        )),
    }
}

/// The load of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// A mean pressure `p0` (units of `E*`).
    Pressure(f64),
    /// A target relative contact area, in (0, 1): `p0` is found by root finding.
    Area(f64),
}

/// Checks the ranges of the loads given: `p0 > 0`, `0 < contact_area < 1`.
///
/// # Errors
///
/// If `p0` is not positive and finite, or `contact_area` is outside (0, 1); the error
/// names the parameter as `s` spells it.
pub fn check_load(p0: Option<f64>, contact_area: Option<f64>, s: &dyn Spelling) -> Result<()> {
    if let Some(p0) = p0 {
        check_positive(&s.name("p0"), p0)?;
    }
    if let Some(a) = contact_area {
        check_open(&s.name("contact_area"), a, 0.0, 1.0)?;
    }
    Ok(())
}

/// The load: `p0` or `contact_area`, exactly one of them; when neither is given, the
/// scene's (`scene` is `Some` where a scene file may give the load, already checked when
/// it was read). The values given are checked after the choice.
///
/// # Errors
///
/// If both loads are chosen, neither is, or the one given is out of range
/// ([`check_load`]).
pub fn load(
    p0: Option<f64>,
    contact_area: Option<f64>,
    scene: Option<(Option<f64>, Option<f64>)>,
    s: &dyn Spelling,
) -> Result<Load> {
    let chosen = if p0.is_some() || contact_area.is_some() {
        (p0, contact_area)
    } else {
        scene.unwrap_or((None, None))
    };
    let load = match chosen {
        (Some(p0), None) => Load::Pressure(p0),
        (None, Some(a)) => Load::Area(a),
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                "load",
                "both p0 and contact_area",
                format!("one of {} or {}", s.name("p0"), s.name("contact_area")),
            ))
        }
        (None, None) => {
            let elsewhere = match scene {
                Some(_) => " (or in the scene's [solve] table)",
                None => "",
            };
            return Err(Error::invalid(
                "load",
                "missing",
                format!(
                    "{} or {}{elsewhere}",
                    s.given("p0", "P"),
                    s.given("contact_area", "A")
                ),
            ));
        }
    };
    check_load(p0, contact_area, s)?;
    Ok(load)
}

/// Checks a magnification given before the surface is known: finite and at least 1 (its
/// upper bound, `zeta_max`, comes with the surface).
///
/// # Errors
///
/// If `zeta` is given and is not finite or below 1.
pub fn check_zeta_floor(zeta: Option<f64>, s: &dyn Spelling) -> Result<()> {
    match zeta {
        Some(z) if !(z.is_finite() && z >= 1.0) => Err(Error::invalid(
            &s.name("zeta"),
            z,
            "in [1, zeta_max = lambda_l / lambda_s]",
        )),
        _ => Ok(()),
    }
}

/// Checks the wavelength `lambda_l` that defines `zeta = |q| / q_l` for given heights:
/// finite and positive (its upper bound, the box, comes with the heights).
///
/// # Errors
///
/// If `lambda_l` is given and is not positive and finite.
pub fn check_lambda_l(lambda_l: Option<f64>, s: &dyn Spelling) -> Result<()> {
    match lambda_l {
        Some(l) => check_positive(&s.name("lambda_l"), l),
        None => Ok(()),
    }
}

/// An integer given as a signed number, checked against `[lo, hi]`.
///
/// # Errors
///
/// If `value` is negative or outside `[lo, hi]`.
pub fn integer(key: &str, value: i64, lo: u64, hi: u64, s: &dyn Spelling) -> Result<u64> {
    match u64::try_from(value) {
        Ok(v) if (lo..=hi).contains(&v) => Ok(v),
        _ => Err(Error::invalid(
            &s.name(key),
            value,
            format!("an integer in [{lo}, {hi}]"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Flags, Keywords};
    use super::*;

    #[test]
    fn solvers_by_name() {
        for kind in SolverKind::ALL {
            assert_eq!(solver(kind.name()).unwrap(), kind);
        }
        assert_eq!(solver("cg").unwrap(), SolverKind::Cg);
        assert!(solver("CG").is_err(), "names are case-sensitive");
        let e = solver("fem").unwrap_err().to_string();
        assert!(e.starts_with("invalid solver = \"fem\": must be \""), "{e}");
        for name in SolverKind::NAMES {
            assert!(e.contains(&format!("{name:?}")), "{name} missing from {e}");
        }
    }

    #[test]
    fn one_load_of_two_named_as_each_front_end_writes_it() {
        assert_eq!(
            load(Some(0.1), None, None, &Keywords).unwrap(),
            Load::Pressure(0.1)
        );
        // A load given replaces the scene's.
        assert_eq!(
            load(None, Some(0.2), Some((Some(0.1), None)), &Flags::default()).unwrap(),
            Load::Area(0.2)
        );
        assert_eq!(
            load(None, None, Some((Some(0.1), None)), &Flags::default()).unwrap(),
            Load::Pressure(0.1)
        );
        assert_eq!(
            load(None, None, None, &Keywords).unwrap_err().to_string(),
            "invalid load = missing: must be p0=P or contact_area=A"
        );
        assert_eq!(
            load(None, None, Some((None, None)), &Flags::default())
                .unwrap_err()
                .to_string(),
            "invalid load = missing: must be --p0 P or --contact-area A (or in the scene's \
             [solve] table)"
        );
        assert_eq!(
            load(Some(-1.0), Some(0.1), None, &Keywords)
                .unwrap_err()
                .to_string(),
            "invalid load = both p0 and contact_area: must be one of p0 or contact_area"
        );
        assert_eq!(
            load(Some(-1.0), None, None, &Flags::default())
                .unwrap_err()
                .to_string(),
            "invalid --p0 = -1: must be a finite number > 0"
        );
    }

    #[test]
    fn ranges() {
        assert!(check_zeta_floor(Some(1.0), &Keywords).is_ok());
        assert_eq!(
            check_zeta_floor(Some(0.5), &Flags::default())
                .unwrap_err()
                .to_string(),
            "invalid --zeta = 0.5: must be in [1, zeta_max = lambda_l / lambda_s]"
        );
        assert_eq!(integer("shards", 3, 1, MAX_SHARDS, &Keywords).unwrap(), 3);
        assert_eq!(
            integer("max_iter", -1, 0, u64::MAX, &Keywords)
                .unwrap_err()
                .to_string(),
            format!(
                "invalid max_iter = -1: must be an integer in [0, {}]",
                u64::MAX
            )
        );
    }
}
