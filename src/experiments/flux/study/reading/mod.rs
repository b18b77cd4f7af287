//! Reading the sensitivity study against the paper's one-step flux (paper, figure
//! "reentry_visualization"; the numbers are the definition's claims, [`PaperFlux`]):
//! which rows, in which measure (fraction of the nominal or of the true contact area),
//! give the paper's numbers; how the flux scales with the step; the relative step the
//! paper's magnitude would need; whether the net flow of the paper's two numbers (at fixed
//! load, the fall of the contact area over the step) points to a misprinted parameter.

use super::sensitivity::SensitivityRow;
use crate::experiments::contact_change::net_over_gross;
use crate::experiments::Criteria;
use crate::stats::{decide, Claim, Estimate, LineFit};

mod notes;

pub use self::notes::notes;

/// The claim keys of the paper's flux into and out of contact in its contact-change
/// figure (the experiment declares them: a definition without them is refused).
pub const CLAIM_IN: &str = "flux_in";
/// See [`CLAIM_IN`].
pub const CLAIM_OUT: &str = "flux_out";

/// The settings whose rows test a misprint of the paper's stated parameters.
pub const MISPRINT: [&str; 2] = ["hurst", "contact_area"];

/// The paper's one-step numbers, as the definition's claims state them, and the stated
/// relative step (the headline step's `dzeta / zeta`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperFlux {
    /// Flux into contact, fraction of the nominal area.
    pub flux_in: f64,
    /// Flux out of contact, fraction of the nominal area.
    pub flux_out: f64,
    /// The stated relative step `dzeta / zeta`.
    pub step: f64,
}

impl PaperFlux {
    /// The paper's numbers from the claims of `criteria` (none without both fluxes).
    pub fn of(criteria: &Criteria, step: f64) -> Option<Self> {
        Some(Self {
            flux_in: criteria.paper(CLAIM_IN)?,
            flux_out: criteria.paper(CLAIM_OUT)?,
            step,
        })
    }

    /// The mean one-way flux, `(in + out) / 2`.
    pub fn mean(&self) -> f64 {
        0.5 * (self.flux_in + self.flux_out)
    }

    /// Net over mean one-way flux of the paper's two numbers.
    pub fn net_over_gross(&self) -> f64 {
        net_over_gross(self.flux_in, self.flux_out)
    }

    /// The net flow of the paper's two numbers, `|in - out|`, fraction of the nominal
    /// area: at fixed load the fall of the contact area over its step, read to
    /// non-contact as the text says ([`crate::experiments::flux::net_flow_residual`]).
    pub fn net_flow(&self) -> f64 {
        (self.flux_in - self.flux_out).abs()
    }

    /// Whether `r` is a row of the stated step.
    pub(in crate::experiments::flux) fn is_stated_step(&self, r: &SensitivityRow) -> bool {
        r.parameter == "dzeta_over_zeta" && (r.value / self.step - 1.0).abs() < 1e-9
    }
}

/// A fraction as a percentage with three decimals ("0.675%").
pub(in crate::experiments::flux) fn percent(x: f64) -> String {
    format!("{:.3}%", 100.0 * x)
}

/// Whether `e` matches the paper's `paper` value by the rule of the claims (a claim
/// `near = 0.1`): within 10% of it plus three standard errors, decided only with an error
/// bar ([`crate::validation::claims`]).
pub fn matches(e: Estimate, paper: f64) -> bool {
    let near = Claim::Near {
        target: paper,
        tolerance: 0.1 * paper.abs(),
    };
    decide(e, near, 3.0).passed()
}

/// Which of the paper's two numbers is the inflow. The caption labels red (0.675%) as
/// entering contact and blue (0.597%) as leaving it; the text says the net flux is to
/// non-contact, which makes the larger number the outflow. A row is read both ways.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    /// In 0.675%, out 0.597%, as the caption labels the colours.
    Caption,
    /// In 0.597%, out 0.675%: the net flux to non-contact, as the text says.
    Text,
}

impl Reading {
    /// Both readings, the caption's first.
    pub const BOTH: [Reading; 2] = [Reading::Caption, Reading::Text];

    /// The paper's inflow and outflow under this reading, fractions of the nominal area.
    pub fn paper(self, p: &PaperFlux) -> (f64, f64) {
        match self {
            Reading::Caption => (p.flux_in, p.flux_out),
            Reading::Text => (p.flux_out, p.flux_in),
        }
    }

    /// In words, with the numbers.
    pub fn name(self, p: &PaperFlux) -> String {
        let (i, o) = self.paper(p);
        let whose = match self {
            Reading::Caption => "the caption's labels",
            Reading::Text => "the text's direction",
        };
        format!("{whose} (in {}, out {})", percent(i), percent(o))
    }

    /// Whether a row's inflow and outflow both match the paper's under this reading.
    pub fn matches(self, p: &PaperFlux, flux_in: Estimate, flux_out: Estimate) -> bool {
        let (paper_in, paper_out) = self.paper(p);
        matches(flux_in, paper_in) && matches(flux_out, paper_out)
    }

    /// The deviations of a row's inflow and outflow from the paper's under this reading,
    /// and whether both match: "in -16%, out +11%: no".
    pub fn verdict(self, p: &PaperFlux, flux_in: Estimate, flux_out: Estimate) -> String {
        let (paper_in, paper_out) = self.paper(p);
        let dev = |e: Estimate, paper: f64| format!("{:+.0}%", 100.0 * (e.value / paper - 1.0));
        format!(
            "{}: in {}, out {}: {}",
            self.name(p),
            dev(flux_in, paper_in),
            dev(flux_out, paper_out),
            if self.matches(p, flux_in, flux_out) {
                "matches"
            } else {
                "does not match"
            }
        )
    }
}

/// The rows (with their measure and reading) that reproduce both of the paper's numbers.
pub fn reproducing(rows: &[SensitivityRow], p: &PaperFlux) -> Vec<String> {
    let mut hits = Vec::new();
    for r in rows {
        let net = r.net_over_gross.map_or(String::new(), |e| {
            format!(", net/gross {}", e.text(1.0, 2, ""))
        });
        let measures = [
            ("nominal area", r.flux_in, r.flux_out),
            (
                "true contact area",
                r.flux_in_of_contact,
                r.flux_out_of_contact,
            ),
        ];
        for (measure, flux_in, flux_out) in measures {
            for reading in Reading::BOTH {
                if reading.matches(p, flux_in, flux_out) {
                    hits.push(format!(
                        "{} = {} (of the {measure}: in {}, out {}{net}; read with {})",
                        r.parameter,
                        r.label,
                        flux_in.text(100.0, 3, "%"),
                        flux_out.text(100.0, 3, "%"),
                        reading.name(p)
                    ));
                }
            }
        }
    }
    hits
}

/// How the one-step flux scales with the step actually taken, from the step rows
/// (`dzeta_over_zeta`): log-log fits against the height variance each step adds (not the
/// nominal step: on a coarse grid two nominal steps can add the same shells).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepScaling {
    /// Exponent of the mean one-way flux, `(in + out) / 2 ~ variance^s`.
    pub gross_exponent: Estimate,
    /// Exponent of the net flux, `|out - in| ~ variance^s` (none where it cannot be fitted).
    pub net_exponent: Option<Estimate>,
    /// The added variance that gives the paper's mean one-way flux, over the variance the
    /// stated step adds.
    pub variance_factor: f64,
    /// The relative step `dzeta / zeta` that adds that variance (from a fit of the
    /// variance against the nominal step over the same rows).
    pub step: Option<f64>,
    /// Net over mean one-way flux there, from the two flux fits.
    pub net_over_gross: Option<f64>,
}

/// The step rows with a recorded, non-zero added variance and a flux, in row order.
pub(in crate::experiments::flux) fn step_rows(
    rows: &[SensitivityRow],
) -> Vec<(&SensitivityRow, f64)> {
    rows.iter()
        .filter(|r| r.parameter == "dzeta_over_zeta")
        .filter_map(|r| Some((r, r.variance_added?.value)))
        .filter(|(r, v)| *v > 0.0 && r.flux_in.value + r.flux_out.value > 0.0)
        .collect()
}

/// Fits the step rows (see [`StepScaling`]); none without two distinct added variances or
/// without the stated step among the rows.
pub fn step_scaling(rows: &[SensitivityRow], p: &PaperFlux) -> Option<StepScaling> {
    let steps = step_rows(rows);
    let stated = steps.iter().find(|(r, _)| p.is_stated_step(r))?.1;
    let ln_v: Vec<f64> = steps.iter().map(|(_, v)| v.ln()).collect();
    let gross = |r: &SensitivityRow| 0.5 * (r.flux_in.value + r.flux_out.value);
    let ln_gross: Vec<f64> = steps.iter().map(|(r, _)| gross(r).ln()).collect();
    let fit = LineFit::fit(&ln_v, &ln_gross)?;
    let target = p.mean().ln();
    let ln_v_needed = (target - fit.intercept.value) / fit.slope.value;
    // The net flux, where it is non-zero.
    let (nx, ny): (Vec<f64>, Vec<f64>) = steps
        .iter()
        .map(|(r, v)| (v.ln(), (r.flux_out.value - r.flux_in.value).abs()))
        .filter(|(_, net)| *net > 0.0)
        .map(|(x, net)| (x, net.ln()))
        .unzip();
    let net_fit = LineFit::fit(&nx, &ny);
    let step_fit = LineFit::fit(
        &ln_v,
        &steps.iter().map(|(r, _)| r.value.ln()).collect::<Vec<_>>(),
    );
    let scaling = StepScaling {
        gross_exponent: fit.slope,
        net_exponent: net_fit.map(|f| f.slope),
        variance_factor: (ln_v_needed - stated.ln()).exp(),
        step: step_fit.map(|f| f.at(ln_v_needed).exp()),
        net_over_gross: net_fit.map(|f| f.at(ln_v_needed).exp() / target.exp()),
    };
    (fit.slope.value.is_finite() && scaling.variance_factor.is_finite()).then_some(scaling)
}

#[cfg(test)]
mod tests {
    use super::notes::identity_note;
    use super::*;
    use crate::experiments::flux::study::sensitivity::PlannedRow;
    use crate::experiments::flux::FluxScene;

    /// The paper's numbers as the shipped definition's claims state them, at the stated
    /// step of its full scene.
    fn paper() -> PaperFlux {
        let (_, full, criteria) = crate::experiments::shipped_scenes::<FluxScene>("c_flux");
        PaperFlux::of(&criteria, full.dzeta / full.zeta).expect("the flux claims")
    }

    #[test]
    fn matching_is_within_ten_percent_or_three_errors() {
        let p = 0.00675;
        assert!(matches(Estimate::new(0.0070, 0.0), p));
        assert!(!matches(Estimate::new(0.0028, 0.0001), p));
        assert!(matches(Estimate::new(0.0050, 0.0006), p));
        assert!(!matches(Estimate::new(0.0050, f64::NAN), p));
    }

    #[test]
    fn a_row_is_read_with_either_number_as_the_inflow() {
        let e = |v: f64| Estimate::new(v, 0.0);
        // In 0.63%, out 0.728%: off the caption's pair (out +22%), within 10% of the
        // text's (in +6%, out +8%).
        let p = paper();
        let (fin, fout) = (e(0.0063), e(0.00728));
        assert!(!Reading::Caption.matches(&p, fin, fout));
        assert!(Reading::Text.matches(&p, fin, fout));
        assert_eq!(
            Reading::Text.verdict(&p, fin, fout),
            "the text's direction (in 0.597%, out 0.675%): in +6%, out +8%: matches"
        );
        assert!(Reading::Caption
            .verdict(&p, fin, fout)
            .ends_with("in -7%, out +22%: does not match"));
    }

    fn step_row(factor: f64, variance: f64, flux_in: f64, flux_out: f64) -> SensitivityRow {
        use crate::experiments::flux::study::sensitivity::StudyConfig;
        let e = |v: f64| Estimate::new(v, 0.0);
        SensitivityRow {
            parameter: "dzeta_over_zeta".into(),
            value: factor * paper().step,
            label: format!("{factor} x the headline step"),
            config: StudyConfig {
                n: 64,
                lambda_l: 32.0,
                lambda_s: 4.0,
                contact_area: 0.14,
                zeta: 4.0,
                dzeta: factor * paper().step * 4.0,
                tol: 1e-8,
                solver: crate::engine::solver::SolverKind::Cg,
                fixed_area: false,
                area_tol: None,
                hurst: None,
            },
            realizations: 2,
            flux_in: e(flux_in),
            flux_out: e(flux_out),
            flux_in_of_contact: e(flux_in / 0.14),
            flux_out_of_contact: e(flux_out / 0.14),
            contact_area: e(0.14),
            net_over_gross: Some(e(crate::experiments::contact_change::net_over_gross(
                flux_in, flux_out,
            ))),
            net_flow: Some(e(flux_out - flux_in)),
            net_flow_residual: Some(e(0.0)),
            flux_in_of_noncontact: Some(e(flux_in / 0.86)),
            variance_added: Some(e(variance)),
            modes_added: Some(8.0),
        }
    }

    #[test]
    fn the_step_scaling_is_fitted_against_the_variance_added() {
        // Gross flux 0.002 sqrt(v / v1), net flux 0.0002 (v / v1): the paper's mean
        // one-way 0.636% needs (0.00636 / 0.002)^2 = 10.1 times the stated step's variance.
        let v1 = 1e-3;
        let rows: Vec<SensitivityRow> = [0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|&f: &f64| {
                let v = v1 * f * f; // variance ~ step^2 here
                let gross = 0.002 * f;
                let net = 0.0002 * f * f;
                step_row(f, v, gross - net / 2.0, gross + net / 2.0)
            })
            .collect();
        let p = paper();
        let s = step_scaling(&rows, &p).unwrap();
        assert!((s.gross_exponent.value - 0.5).abs() < 1e-9, "{:?}", s);
        assert!((s.net_exponent.unwrap().value - 1.0).abs() < 1e-9);
        let k = (p.mean() / 0.002f64).powi(2);
        assert!(
            (s.variance_factor / k - 1.0).abs() < 1e-9,
            "{} vs {k}",
            s.variance_factor
        );
        // The step: variance ~ step^2, so sqrt(k) times the stated step.
        assert!((s.step.unwrap() / (k.sqrt() * p.step) - 1.0).abs() < 1e-9);
        // Net/gross there: 0.0002 k / 0.00636.
        let ng = 0.0002 * k / p.mean();
        assert!((s.net_over_gross.unwrap() / ng - 1.0).abs() < 1e-9);
    }

    /// A misprint row (`parameter` at `value`) with the given fluxes, the rest as the
    /// stated step's row.
    fn misprint_row(parameter: &str, value: f64, flux_in: f64, flux_out: f64) -> SensitivityRow {
        let mut r = step_row(1.0, 1e-3, flux_in, flux_out);
        r.parameter = parameter.into();
        r.value = value;
        r.label = match parameter {
            "hurst" => format!("H = {value}"),
            _ => format!("a_r = {value}"),
        };
        match parameter {
            "hurst" => r.config.hurst = Some(value),
            _ => r.config.contact_area = value,
        }
        r
    }

    fn planned_of(rows: &[SensitivityRow]) -> Vec<PlannedRow> {
        rows.iter()
            .map(|r| PlannedRow {
                parameter: MISPRINT
                    .into_iter()
                    .find(|&m| m == r.parameter)
                    .unwrap_or("dzeta_over_zeta"),
                value: r.value,
                label: r.label.clone(),
            })
            .collect()
    }

    #[test]
    fn the_net_flow_note_reads_a_missing_row_as_not_run() {
        let p = paper();
        // Net flows against the paper's 0.078%: stated 0.03% and H = 0.3 0.103% do not
        // match, H = 0.5 and a_r = 0.5 (0.078%) do. The fluxes match (the text's reading)
        // at H = 0.3 and a_r = 0.5: a_r = 0.5 gives both.
        let stated = step_row(1.0, 1e-3, 0.0023, 0.0026);
        let h3 = misprint_row("hurst", 0.3, 0.00625, 0.00728);
        let h5 = misprint_row("hurst", 0.5, 0.0030, 0.00378);
        let a5 = misprint_row("contact_area", 0.5, 0.0063, 0.00708);
        let planned = planned_of(&[stated.clone(), h3.clone(), h5.clone(), a5.clone()]);
        let all_notes = |rows: &[SensitivityRow]| notes(rows, &planned, &p, 0.14, 0.1397);
        let note = |rows: &[SensitivityRow]| {
            all_notes(rows)
                .into_iter()
                .find(|n| n.starts_with("Net flow and the misprint"))
                .expect("the net flow note")
        };
        // Before the campaign computes the H = 0.5 row.
        let before = [stated.clone(), h3.clone(), a5.clone()];
        let text = note(&before);
        for expected in [
            "the paper's two numbers differ by 0.078% of A0",
            "at the stated parameters 0.030% +- 0.000%: does not match",
            "H = 0.3: 0.103% +- 0.000%: does not match",
            "H = 0.5: not run yet",
            "a_r = 0.5: 0.078% +- 0.000%: matches",
            "both the paper's fluxes (either reading) and its net flow: a_r = 0.5; \
             the fluxes but not the net flow: H = 0.3.",
            "consistent with a misprint of its parameter alone",
            "Not run yet: H = 0.5",
        ] {
            assert!(text.contains(expected), "{expected}: {text}");
        }
        let missing = "Misprinted parameter? H = 0.5: not run yet (its jobs have no results).";
        assert!(all_notes(&before).iter().any(|n| n == missing));
        // After.
        let after = note(&[stated, h3, h5, a5]);
        for expected in [
            "H = 0.5: 0.078% +- 0.000%: matches",
            "its net flow: a_r = 0.5; the net flow but not the fluxes: H = 0.5; the fluxes \
             but not the net flow: H = 0.3.",
        ] {
            assert!(after.contains(expected), "{expected}: {after}");
        }
        assert!(!after.contains("not run yet"), "{after}");
        assert!(!after.contains("The stated parameters give"), "{after}");
        // Where the stated step gives the net flow too, the net flow alone is no sign.
        let stated = step_row(1.0, 1e-3, 0.0023, 0.00308);
        let text = note(&[stated]);
        assert!(text.contains("at the stated parameters 0.078%"), "{text}");
        assert!(text.contains("the net flow alone does not point"), "{text}");
    }

    #[test]
    fn the_identity_note_names_a_row_that_breaks_it() {
        let mut rows = vec![
            step_row(1.0, 1e-3, 0.0023, 0.0026),
            misprint_row("hurst", 0.3, 0.00625, 0.00728),
        ];
        let identity = |rows: &[SensitivityRow]| identity_note(rows).expect("fixed-load rows");
        let holds = identity(&rows);
        assert!(holds.contains("holds on every row (2 rows;"), "{holds}");
        assert!(holds.contains("largest |residual| 0 of A0"), "{holds}");
        // One point of a 64^2 grid is 2.4e-4 of A0: a residual of one point breaks it.
        rows[1].net_flow_residual = Some(Estimate::new(1.0 / 4096.0, 0.0));
        let breaks = identity(&rows);
        assert!(breaks.contains("does not hold in 1 of 2 rows"), "{breaks}");
        assert!(
            breaks.contains("hurst = H = 0.3 (2.4e-4 of A0)"),
            "{breaks}"
        );
        // A row without a residual is left out.
        rows[1].net_flow_residual = None;
        let fewer = identity(&rows);
        assert!(fewer.contains("holds on every row (1 row;"), "{fewer}");
    }

    #[test]
    fn steps_that_add_the_same_modes_give_no_fit_without_a_second_variance() {
        let rows = vec![
            step_row(0.25, 1e-3, 0.001, 0.002),
            step_row(1.0, 1e-3, 0.001, 0.002),
        ];
        assert!(step_scaling(&rows, &paper()).is_none());
    }
}
