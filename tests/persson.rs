//! Persson's theory on a realization's own spectrum: normalisation and mean of the pressure
//! distribution, the load limits of the contact area, the corrected theory's reduction to
//! the original and its order of accuracy, the moment inversion, energies, the paper's
//! contact-area law, and a snapshot of one realization.

use std::f64::consts::{PI, SQRT_2};

use persson_check::engine::spectrum::{Shell, ShellSpectrum};
use persson_check::engine::surface::{Amplitudes, Surface, SurfaceModel};
use persson_check::persson::moments::{
    relative_width_estimate, second_moment, width_estimate, width_from_moments,
};
use persson_check::persson::{
    persson_contact_area, reduced_pressure, Broadening, ContactAreaLaw, Correction, Prediction,
    PressureDistribution, Variant,
};
use statrs::function::erf::erfc;

/// The realization of the snapshot: small, but with some 200 shells.
fn params() -> SurfaceModel {
    SurfaceModel::new(128, 0.8, 64.0, 4.0, 1)
}

fn realization() -> (Surface, Broadening) {
    let surface = Surface::generate(&params()).unwrap();
    let broadening = Broadening::new(&surface.shells(), 1.0).unwrap();
    (surface, broadening)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Composite Simpson rule with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> f64 {
    let h = (hi - lo) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(lo + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(lo) + inner + f(hi)) * h / 3.0
}

#[test]
fn distribution_with_its_delta_integrates_to_one_and_has_mean_p0_at_every_zeta() {
    let (_, b) = realization();
    let p0 = 0.05;
    let mut zetas: Vec<f64> = b.shells().iter().map(|s| s.zeta).collect();
    zetas.insert(0, 0.5);
    for variant in [Variant::Original, Variant::Corrected(Correction::default())] {
        let theory = Prediction::new(&b, p0, variant).unwrap();
        let flat = theory.pressure_distribution(0.5);
        assert!(flat.is_flat() && flat.contact_area() == 1.0 && flat.non_contact_area() == 0.0);
        assert_eq!((flat.cdf(p0 * 0.999), flat.cdf(p0)), (0.0, 1.0));
        let mut worst = (0.0f64, 0.0f64);
        for &zeta in &zetas[1..] {
            let d = theory.pressure_distribution(zeta);
            let dp = d.width();
            // 12 widths either side hold all but exp(-72) of each Gaussian.
            let (lo, hi) = ((p0 - 12.0 * dp).max(0.0), p0 + 12.0 * dp);
            let n = 10_000;
            let mass = simpson(|p| d.density(p), lo, hi, n) + d.non_contact_area();
            let mean = simpson(|p| p * d.density(p), lo, hi, n);
            let second = simpson(|p| p * p * d.density(p), lo, hi, n);
            // Simpson with 10^4 intervals over 24 widths: error ~ (24/10^4)^4 / 180 ~ 1e-13.
            assert!(
                (mass - 1.0).abs() < 1e-10,
                "{variant:?} zeta {zeta}: {mass}"
            );
            assert!(rel(mean, p0) < 1e-10, "{variant:?} zeta {zeta}: {mean}");
            assert!(rel(second, d.second_moment()) < 1e-10, "zeta {zeta}");
            // The closed-form cdf against the quadrature up to the mean pressure.
            let below = d.non_contact_area() + simpson(|p| d.density(p), lo, p0.max(lo), n);
            assert!((d.cdf(p0) - below).abs() < 1e-10, "zeta {zeta}");
            // The survival function is the delta-free part above p: a_r at p = 0.
            assert!(rel(d.survival(0.0), d.contact_area()) < 1e-15);
            let tail = simpson(|p| d.density(p), p0, hi, n);
            assert!((d.survival(p0) - tail).abs() < 1e-10, "zeta {zeta}");
            worst = (worst.0.max((mass - 1.0).abs()), worst.1.max(rel(mean, p0)));
        }
        println!(
            "{variant:?}: max |mass - 1| = {:.1e}, max |mean/p0 - 1| = {:.1e}",
            worst.0, worst.1
        );
    }
}

#[test]
fn contact_area_tends_to_one_at_high_load_and_to_sqrt_8_over_pi_p0_at_low_load() {
    let (surface, b) = realization();
    let spectrum = surface.shells();
    let kappa = (8.0 / PI).sqrt();
    for zeta in [1.0, 2.0, 5.0, 16.0] {
        let low = Prediction::original(&b, 1e-7).unwrap();
        let p = reduced_pressure(&spectrum, 1e-7, 1.0, zeta);
        // a_r = erf(sqrt2 p~) = sqrt(8/pi) p~ (1 - 2 p~^2 / 3 + ...).
        assert!(rel(low.contact_area(zeta) / p, kappa) < 1e-9, "zeta {zeta}");
        let high = Prediction::original(&b, 10.0).unwrap();
        assert_eq!(high.contact_area(zeta), 1.0, "zeta {zeta}");
        assert!(high.non_contact_area(zeta) < 1e-80, "zeta {zeta}");
        // 1 - a_r keeps its precision where 1 - erf would round to zero.
        let mid = Prediction::original(&b, 2.0).unwrap();
        let p = reduced_pressure(&spectrum, 2.0, 1.0, zeta);
        assert!(rel(mid.non_contact_area(zeta), erfc(SQRT_2 * p)) < 1e-12);
        assert!(rel(mid.contact_area(zeta), persson_contact_area(p)) < 1e-15);
    }
}

#[test]
fn broadening_is_the_quarter_squared_gradient_of_the_resolved_modes() {
    let (surface, b) = realization();
    for zeta in [0.5, 1.0, 3.3, 9.0, 16.0] {
        let g = surface.rms_gradient(zeta);
        // Two independent sums (over modes and over shells): rounding only.
        assert!((b.total(zeta) - 0.25 * g * g).abs() <= 1e-14, "zeta {zeta}");
    }
    for (zeta, dzeta) in [(1.0, 0.5), (3.0, 0.25), (10.0, 2.0), (15.9, 1.0)] {
        let direct: f64 = b
            .shells()
            .iter()
            .filter(|s| s.zeta > zeta && s.zeta <= zeta + dzeta)
            .map(|s| s.broadening(1.0))
            .sum();
        assert!(direct > 0.0, "({zeta}, {dzeta}] holds no shell");
        assert!(
            rel(b.shell(zeta, dzeta), direct) < 1e-12,
            "({zeta}, +{dzeta}]"
        );
        let d = b.diffusion_coefficient(zeta, dzeta).unwrap();
        assert!(rel(d, direct / dzeta) < 1e-12);
    }
}

#[test]
fn random_phase_shells_carry_the_model_spectrum_exactly() {
    let mut p = params();
    p.amplitudes = Amplitudes::RandomPhase;
    let spectrum = Surface::generate(&p).unwrap().shells();
    let first = &spectrum.shells[0];
    let c = |s: &Shell| s.h2 / (s.modes as f64 * s.zeta.powf(-2.0 * (1.0 + p.hurst)));
    for s in &spectrum.shells {
        assert!(rel(c(s), c(first)) < 1e-12, "k2 = {}", s.k2);
    }
}

#[test]
fn corrected_theory_with_gamma_one_is_the_original_to_the_last_bit() {
    let (_, b) = realization();
    for p0 in [0.005, 0.05, 0.5] {
        let original = Prediction::original(&b, p0).unwrap();
        let unit = Prediction::corrected(&b, p0, Correction::YangPersson { gamma: 1.0 }).unwrap();
        for (o, u) in original.shells().iter().zip(unit.shells()) {
            assert_eq!(o.total_broadening, u.total_broadening, "zeta {}", o.zeta);
            assert_eq!(o.contact_area, u.contact_area);
            assert_eq!(o.energy, u.energy);
            assert_eq!(u.correction, 1.0);
        }
        assert_eq!(original.elastic_energy(16.0), unit.elastic_energy(16.0));
    }
}

#[test]
fn corrected_theory_has_more_contact_and_less_energy_than_the_original() {
    let (_, b) = realization();
    let p0 = 0.05;
    let original = Prediction::original(&b, p0).unwrap();
    for c in [Correction::yang_persson(), Correction::wang_mueser()] {
        let corrected = Prediction::corrected(&b, p0, c).unwrap();
        for (o, k) in original.shells().iter().zip(corrected.shells()) {
            // S < 1 in partial contact: less broadening, more contact.
            assert!(
                k.total_broadening < o.total_broadening,
                "{c:?} zeta {}",
                o.zeta
            );
            assert!(k.contact_area > o.contact_area);
            assert!(k.correction < 1.0 && k.correction >= c.min_factor());
        }
        let (ao, ac) = (original.contact_area(16.0), corrected.contact_area(16.0));
        println!("{c:?}: a_r(16) original {ao:.4}, corrected {ac:.4}");
        assert!(ac > 1.1 * ao);
    }
}

#[test]
fn self_consistent_update_is_second_order_in_the_shell_size() {
    // K equal shells adding a total broadening B; the shell sequence is a trapezoidal
    // discretisation of dV/dB = S(a(V)), here solved with RK4 on 10^5 steps.
    let (p0, total) = (0.3, 1.0);
    let c = Correction::yang_persson();
    let rhs = |v: f64| {
        let a = if v > 0.0 {
            statrs::function::erf::erf(p0 / (2.0 * v).sqrt())
        } else {
            1.0
        };
        c.factor(a)
    };
    let steps = 100_000;
    let h = total / steps as f64;
    let mut v: f64 = 0.0;
    for _ in 0..steps {
        let k1 = rhs(v);
        let k2 = rhs(v + 0.5 * h * k1);
        let k3 = rhs(v + 0.5 * h * k2);
        let k4 = rhs(v + h * k3);
        v += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    }
    let error = |k: usize| {
        let shells = (1..=k)
            .map(|i| Shell {
                k2: (i * i) as u32,
                q: i as f64,
                zeta: i as f64,
                modes: 4,
                h2: 4.0 * total / k as f64 / (i * i) as f64,
                q2h2: 4.0 * total / k as f64,
            })
            .collect();
        let spectrum = ShellSpectrum { q_l: 1.0, shells };
        let b = Broadening::new(&spectrum, 1.0).unwrap();
        let pred = Prediction::corrected(&b, p0, c).unwrap();
        (pred.total_broadening(k as f64) - v).abs()
    };
    // Below some 100 shells the error is not yet asymptotic: a_r leaves 1 steeply, over
    // V ~ p0^2 / 10, and the first few shells straddle that onset.
    let (e1, e2, e3) = (error(200), error(400), error(800));
    println!("trapezoid error: K = 200: {e1:.3e}, 400: {e2:.3e}, 800: {e3:.3e}");
    for ratio in [e1 / e2, e2 / e3] {
        assert!(
            (3.8..4.2).contains(&ratio),
            "error ratio {ratio}, expected 4"
        );
    }
}

#[test]
fn closed_form_start_is_within_three_percent_and_newton_reaches_machine_precision() {
    let mut worst_start = 0.0f64;
    let mut worst_newton = 0.0f64;
    for p in [1.0, 0.37, 250.0] {
        for i in 0..=600 {
            let sigma = 10f64.powf(-3.0 + 6.0 * i as f64 / 600.0);
            let m2 = p * p * (1.0 + sigma * sigma);
            let exact = width_from_moments(p, m2).unwrap();
            let start = width_estimate(p, m2).unwrap();
            worst_start = worst_start.max(rel(start, exact));
            let back = second_moment(p, exact);
            worst_newton = worst_newton.max(rel(back, m2));
            assert!(
                rel(back, m2) < 1e-12,
                "p' {p}, sigma {sigma}: {back} vs {m2}"
            );
        }
    }
    println!(
        "closed form: max error {worst_start:.4}; Newton: max |<p^2>/m2 - 1| {worst_newton:.1e}"
    );
    assert!(worst_start < 0.03, "closed form off by {worst_start}");
    // Where eq. (2ndMoment) is well conditioned, the round trip Dp -> <p^2> -> Dp is exact.
    for dp in [0.1, 0.5, 1.0, 3.0, 40.0, 1e4] {
        let back = width_from_moments(2.0, second_moment(2.0, 2.0 * dp)).unwrap();
        assert!(rel(back, 2.0 * dp) < 1e-12, "Dp/p' = {dp}: {back}");
    }
    // Both limits of eq. (approxDeltaPress) are exact.
    assert!(rel(relative_width_estimate(1e-8), 1e-8) < 1e-7);
    assert!(rel(relative_width_estimate(1e8), (PI / 8.0).sqrt() * 1e16) < 1e-7);
    assert_eq!(width_from_moments(1.5, 2.25).unwrap(), 0.0);
}

#[test]
fn moment_inversion_rejects_bad_input_by_name() {
    for (p, m2, name) in [
        (0.0, 1.0, "p_mean"),
        (-1.0, 1.0, "p_mean"),
        (f64::NAN, 1.0, "p_mean"),
        (f64::INFINITY, 1.0, "p_mean"),
        (1.0, 0.99, "second_moment"),
        (1.0, f64::NAN, "second_moment"),
        (1.0, f64::INFINITY, "second_moment"),
        (1e-300, 1e300, "second_moment"),
    ] {
        for e in [width_from_moments(p, m2), width_estimate(p, m2)] {
            let e = e.unwrap_err().to_string();
            assert!(e.contains(name), "({p}, {m2}): {e}");
        }
    }
}

#[test]
fn mode_energies_sum_to_the_totals_and_reach_full_contact_at_high_load() {
    let (surface, b) = realization();
    let grid = surface.grid();
    let q_l = surface.q_l();
    for variant in [
        Variant::Original,
        Variant::Corrected(Correction::wang_mueser()),
    ] {
        for p0 in [0.01, 0.05, 1e3] {
            let theory = Prediction::new(&b, p0, variant).unwrap();
            for zeta in [1.0, 2.5, 7.0, 16.0] {
                let limit = grid.shell_limit(zeta, surface.lambda_l());
                let by_mode: f64 = surface
                    .modes()
                    .iter()
                    .enumerate()
                    .filter(|(s, _)| grid.k2(*s) <= limit)
                    .map(|(s, h)| grid.weight_of(s) * theory.mode_energy(grid.q(s), h.norm_sqr()))
                    .sum();
                let total = theory.elastic_energy(zeta);
                assert!(
                    rel(by_mode, total) < 1e-12,
                    "{variant:?} p0 {p0} zeta {zeta}"
                );
            }
            for (shell, pred) in b.shells().iter().zip(theory.shells()) {
                // One shell's modes share a_r at zeta = |q| / q_l, the shell included.
                let a = theory.contact_area(shell.q / q_l);
                let expected = 0.25 * shell.q * shell.h2 * a * pred.correction;
                assert!(rel(pred.energy, expected) < 1e-15);
                if p0 == 1e3 {
                    assert_eq!(pred.contact_area, 1.0);
                    assert!(rel(pred.energy, shell.full_contact_energy(1.0)) < 1e-15);
                }
            }
        }
    }
}

#[test]
fn results_are_unchanged_under_a_change_of_the_pressure_unit() {
    let spectrum = realization().0.shells();
    let one = Broadening::new(&spectrum, 1.0).unwrap();
    let three = Broadening::new(&spectrum, 3.0).unwrap();
    for variant in [Variant::Original, Variant::Corrected(Correction::default())] {
        let a = Prediction::new(&one, 0.05, variant).unwrap();
        let b = Prediction::new(&three, 0.15, variant).unwrap();
        for zeta in [1.0, 4.0, 16.0] {
            assert!(rel(b.contact_area(zeta), a.contact_area(zeta)) < 1e-13);
            assert!(rel(b.total_broadening(zeta), 9.0 * a.total_broadening(zeta)) < 1e-13);
            assert!(rel(b.elastic_energy(zeta), 3.0 * a.elastic_energy(zeta)) < 1e-13);
        }
    }
}

#[test]
fn papers_contact_area_law_has_slope_2c1_at_low_load_and_persson_tail_at_high_load() {
    let law = ContactAreaLaw::PAPER;
    assert_eq!(law.kappa(), 2.15);
    for p in [1e-9, 1e-6] {
        // Corrections are O(p~^2).
        assert!(rel(law.contact_area(p) / p, 2.15) < 1e-9, "p~ {p}");
    }
    for p in [2.5, 3.0, 4.0] {
        let tail = erfc(1.025 * SQRT_2 * p);
        // 1 - a_r = erfc(y) [s + (1 + erf y) erfc(c1 sqrt(pi) p~)]: s -> 1, the rest -> 0.
        assert!(rel(law.non_contact_area(p), tail) < 1e-6, "p~ {p}");
    }
    for p in [0.01, 0.1, 0.3, 1.0, 2.0] {
        let sum = law.contact_area(p) + law.non_contact_area(p);
        assert!((sum - 1.0).abs() < 4e-16, "p~ {p}: a + (1 - a) = {sum}");
    }
}

#[test]
fn correction_factors_and_variants_are_named_in_scene_files() {
    #[derive(serde::Deserialize)]
    struct Scene {
        correction: Correction,
    }
    let read = |s: &str| toml::from_str::<Scene>(s).map(|s| s.correction);
    assert_eq!(
        read(r#"correction = { model = "yang_persson" }"#).unwrap(),
        Correction::default()
    );
    assert_eq!(
        read(r#"correction = { model = "wang_mueser" }"#).unwrap(),
        Correction::wang_mueser()
    );
    assert_eq!(
        read(r#"correction = { model = "yang_persson", gamma = 0.5 }"#).unwrap(),
        Correction::YangPersson { gamma: 0.5 }
    );
    assert!(read(r#"correction = { model = "persson" }"#).is_err());
    assert!(read(r#"correction = { model = "wang_mueser", gama = 0.5 }"#).is_err());
    let v: Variant = serde_json::from_str(r#"{"corrected": {"model": "wang_mueser"}}"#).unwrap();
    assert_eq!(v, Variant::Corrected(Correction::wang_mueser()));
    assert_eq!(
        serde_json::from_str::<Variant>(r#""original""#).unwrap(),
        Variant::Original
    );
}

#[test]
fn bad_loads_moduli_and_gammas_are_rejected_by_name() {
    let (surface, b) = realization();
    for p0 in [0.0, -0.1, f64::NAN] {
        let e = Prediction::original(&b, p0).unwrap_err().to_string();
        assert!(e.contains("p0"), "{e}");
    }
    let e = Broadening::new(&surface.shells(), 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("e_star"), "{e}");
    for (p0, dp2, name) in [
        (0.0, 1.0, "p0"),
        (f64::INFINITY, 1.0, "p0"),
        (1.0, -1e-3, "dp2"),
        (1.0, f64::NAN, "dp2"),
    ] {
        let e = PressureDistribution::new(p0, dp2).unwrap_err().to_string();
        assert!(e.contains(name), "({p0}, {dp2}): {e}");
    }
    let bad = Correction::YangPersson { gamma: 1.2 };
    let e = Prediction::corrected(&b, 0.05, bad)
        .unwrap_err()
        .to_string();
    assert!(e.contains("gamma"), "{e}");
}

/// Rounds to 10 significant digits so that the snapshot is the same on every platform.
fn round(x: f64) -> f64 {
    format!("{x:.9e}").parse().unwrap()
}

#[test]
fn snapshot_of_one_realization_at_one_load() {
    let (surface, b) = realization();
    let spectrum = surface.shells();
    let p0 = 0.05;
    let original = Prediction::original(&b, p0).unwrap();
    let corrected = Prediction::corrected(&b, p0, Correction::yang_persson()).unwrap();
    let rows: Vec<serde_json::Value> = [0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0]
        .iter()
        .map(|&zeta| {
            serde_json::json!({
                "zeta": zeta,
                "shells": b.resolved(zeta),
                // Infinite (null) on the flat interface, where g_bar = 0.
                "reduced_pressure": Some(reduced_pressure(&spectrum, p0, 1.0, zeta))
                    .filter(|p| p.is_finite())
                    .map(round),
                "dp_tot": round(original.total_broadening(zeta).sqrt()),
                "a_r": round(original.contact_area(zeta)),
                "energy": round(original.elastic_energy(zeta)),
                "dp_mod_tot": round(corrected.total_broadening(zeta).sqrt()),
                "a_r_corrected": round(corrected.contact_area(zeta)),
                "energy_corrected": round(corrected.elastic_energy(zeta)),
            })
        })
        .collect();
    let value = serde_json::json!({
        "surface": { "n": 128, "hurst": 0.8, "lambda_l": 64.0, "lambda_s": 4.0, "seed": 1 },
        "p0": p0,
        "correction": Correction::yang_persson(),
        "rows": rows,
    });
    insta::with_settings!({snapshot_path => "../golden", prepend_module_to_snapshot => false}, {
        insta::assert_json_snapshot!("persson_theory", value);
    });
}
