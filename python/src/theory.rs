//! Persson's theory on the spectrum of a surface (`theory`, returning a [`Theory`] to ask
//! at any magnification), and the paper's empirical contact-area law.

use numpy::{PyArray1, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use persson_check::persson::{Prediction, ShellPrediction, Variant};
use persson_check::tasks::theory::{self as task};
use persson_check::tasks::{parse, surface as surfaces, Keywords};

use crate::conversions::field;
use crate::errors::OrRaise;

/// Persson's theory at one load on the spectrum of one surface.
#[pyclass(frozen, module = "persson_check")]
pub struct Theory {
    prediction: Prediction,
    zeta_max: f64,
}

impl Theory {
    fn at(&self, zeta: Option<f64>) -> f64 {
        zeta.unwrap_or(self.zeta_max)
    }
}

#[pymethods]
impl Theory {
    /// Mean pressure p0.
    #[getter]
    fn p0(&self) -> f64 {
        self.prediction.p0()
    }

    /// "original", or "corrected" (with the correction's gamma in `gamma`).
    #[getter]
    fn variant(&self) -> &'static str {
        match self.prediction.variant() {
            Variant::Original => "original",
            Variant::Corrected(_) => "corrected",
        }
    }

    /// Magnification of the finest shell (the default zeta of every method).
    #[getter]
    fn zeta_max(&self) -> f64 {
        self.zeta_max
    }

    /// Relative contact area a_r at magnification zeta (default: zeta_max).
    #[pyo3(signature = (zeta=None))]
    fn contact_area(&self, zeta: Option<f64>) -> f64 {
        self.prediction.contact_area(self.at(zeta))
    }

    /// 1 - a_r at zeta (computed with erfc: precise near full contact).
    #[pyo3(signature = (zeta=None))]
    fn non_contact_area(&self, zeta: Option<f64>) -> f64 {
        self.prediction.non_contact_area(self.at(zeta))
    }

    /// Total pressure broadening Dp_tot^2 (original) or Dp_mod,tot^2 (corrected) at zeta.
    #[pyo3(signature = (zeta=None))]
    fn total_broadening(&self, zeta: Option<f64>) -> f64 {
        self.prediction.total_broadening(self.at(zeta))
    }

    /// Correction factor S(a_r) at zeta (1 for the original theory).
    #[pyo3(signature = (zeta=None))]
    fn correction_factor(&self, zeta: Option<f64>) -> f64 {
        self.prediction.correction_factor(self.at(zeta))
    }

    /// Elastic energy per unit area of the modes resolved at zeta.
    #[pyo3(signature = (zeta=None))]
    fn elastic_energy(&self, zeta: Option<f64>) -> f64 {
        self.prediction.elastic_energy(self.at(zeta))
    }

    /// The pressure distribution's density Pr(p, zeta) at each of `p` (the delta function of
    /// weight 1 - a_r at p = 0 is not included; see non_contact_area).
    #[pyo3(signature = (p, zeta=None))]
    fn pressure_density<'py>(
        &self,
        py: Python<'py>,
        p: Vec<f64>,
        zeta: Option<f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        let d = self.prediction.pressure_distribution(self.at(zeta));
        PyArray1::from_vec(py, p.iter().map(|&x| d.density(x)).collect())
    }

    /// The cumulative distribution P(pressure <= p) at each of `p`, the delta at 0 included.
    #[pyo3(signature = (p, zeta=None))]
    fn pressure_cdf<'py>(
        &self,
        py: Python<'py>,
        p: Vec<f64>,
        zeta: Option<f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        let d = self.prediction.pressure_distribution(self.at(zeta));
        PyArray1::from_vec(py, p.iter().map(|&x| d.cdf(x)).collect())
    }

    /// The theory shell by shell, as a dict of equal-length numpy arrays: zeta, q,
    /// broadening, added_broadening, total_broadening, contact_area, non_contact_area,
    /// correction, energy, full_contact_energy.
    fn shells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.prediction.shells();
        let d = PyDict::new(py);
        let col =
            |f: fn(&ShellPrediction) -> f64| PyArray1::from_vec(py, s.iter().map(f).collect());
        d.set_item("zeta", col(|x| x.zeta))?;
        d.set_item("q", col(|x| x.q))?;
        d.set_item("broadening", col(|x| x.broadening))?;
        d.set_item("added_broadening", col(|x| x.added_broadening))?;
        d.set_item("total_broadening", col(|x| x.total_broadening))?;
        d.set_item("contact_area", col(|x| x.contact_area))?;
        d.set_item("non_contact_area", col(|x| x.non_contact_area))?;
        d.set_item("correction", col(|x| x.correction))?;
        d.set_item("energy", col(|x| x.energy))?;
        d.set_item("full_contact_energy", col(|x| x.full_contact_energy))?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Theory(variant={:?}, p0={:.6e}, shells={}, contact_area={:.6})",
            self.variant(),
            self.p0(),
            self.prediction.shells().len(),
            self.contact_area(None)
        )
    }
}

/// Persson's theory at mean pressure `p0` on the spectrum of `heights` (its modes grouped
/// into shells of equal |q|): contact area, pressure distribution, broadening and elastic
/// energy at every magnification. `variant` is "original", "yang_persson" (corrected,
/// gamma = 0.42) or "wang_mueser" (corrected, gamma = 5/9). `lambda_l` defines
/// zeta = |q| / q_l (default: the box size; pass the surface's lambda_l for a generated
/// surface).
#[pyfunction]
#[pyo3(signature = (heights, p0, variant="original", lambda_l=None, e_star=1.0))]
pub fn theory(
    py: Python<'_>,
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: f64,
    variant: &str,
    lambda_l: Option<f64>,
    e_star: f64,
) -> PyResult<Theory> {
    parse::check_load(Some(p0), None, &Keywords).or_raise()?;
    parse::check_lambda_l(lambda_l, &Keywords).or_raise()?;
    let correction = parse::theory_variant(variant).or_raise()?;
    let (n, values) = field(&heights)?;
    let theory = py
        .detach(|| {
            let surface = surfaces::from_heights(n, values, lambda_l)?;
            task::theory(&surface, p0, correction, e_star)
        })
        .or_raise()?;
    Ok(Theory {
        prediction: theory.prediction,
        zeta_max: theory.zeta_max,
    })
}

/// The empirical contact-area law, eq. (contactArea) of the paper, at reduced pressure
/// p0 / (E* g_bar).
#[pyfunction]
pub fn contact_area_law(p_reduced: f64) -> f64 {
    persson_check::persson::persson_contact_area(p_reduced)
}
