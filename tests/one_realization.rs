//! A scene trimmed to one realization: every output (account, checks, CSV, JSON, the
//! scorecard) is free of NaN, the checks that need an error bar say they are not decided,
//! and the text counts "1 realization", singular.

use persson_check::engine::solver::SolverKind;
use persson_check::report::{write, ReportOptions, SpeedChoice};
use persson_check::validation::{run, RunOptions, Scale, Source};

/// The re-entry scene on a 32^2 grid (lambda_l = 16, lambda_s = 4: zeta up to 4), one
/// seed, one load.
const ONE_SEED_REENTRY: &str = r#"
name = "c_reentry"
experiment = "reentry"
title = "(c) No re-entry, one realization"
assumption = "(c) p = 0 absorbs"
statistic = "re-entry share"
persson = "share 0"

[verdict]
significance = 3.0
resolution = 0.02

[paper]
finding = "share ~62% at a_r = 0.14"
verdict = "violated"

[reduced]
n = 32
hurst = 0.8
lambda_l = 16
lambda_s = 4
seeds = [1]
contact_areas = [0.14]
paper_shares = [0.62]
flux_zeta = 2
flux_dzeta = 1
checkpoint_seconds = 30
tol = 1e-8

[full]
n = 32
hurst = 0.8
lambda_l = 16
lambda_s = 4
seeds = [1]
contact_areas = [0.14]
paper_shares = [0.62]
flux_zeta = 2
flux_dzeta = 1
checkpoint_seconds = 30
tol = 1e-8
"#;

fn assert_no_nan(what: &str, text: &str) {
    let nan = text
        .split(|c: char| !c.is_ascii_alphanumeric())
        .any(|word| word.eq_ignore_ascii_case("nan"));
    assert!(!nan, "{what} prints NaN:\n{text}");
}

#[test]
fn one_realization_prints_no_nan() {
    let out = tempfile::tempdir().unwrap();
    let source = Source {
        path: "one_seed/c_reentry.toml".into(),
        text: ONE_SEED_REENTRY.into(),
    };
    let mut opts = RunOptions::new(Scale::Reduced, out.path());
    opts.solvers = vec![SolverKind::Cg];
    let o = run(&source, &opts).unwrap();

    assert_no_nan("the account", &o.account);
    assert!(o.account.contains("1 realization "), "{}", o.account);
    assert!(!o.account.contains("1 realizations"), "{}", o.account);
    for c in &o.checks {
        assert_no_nan(&c.key, &format!("{} {}", c.name, c.detail));
    }
    let flux = o
        .checks
        .iter()
        .find(|c| c.key == "flux_in_positive")
        .expect("the flux check");
    assert!(!flux.decided, "{flux:?}");
    assert!(
        flux.detail.contains("not decided with 1 realization"),
        "{flux:?}"
    );
    // Everything else may still decide, but the reproduction cannot be "yes".
    assert_ne!(o.reproduced, Some(true));

    let json = std::fs::read_to_string(out.path().join("c_reentry.json")).unwrap();
    assert_no_nan("the JSON outcome", &json);
    let csv = std::fs::read_to_string(out.path().join("c_reentry.csv")).unwrap();
    assert_no_nan("the CSV", &csv);

    let card = out.path().join("scorecard.md");
    write(
        &ReportOptions {
            from: out.path().to_path_buf(),
            out: card.clone(),
            golden: None,
            speed: SpeedChoice::Skip,
        },
        &mut |_| {},
    )
    .unwrap();
    let text = std::fs::read_to_string(&card).unwrap();
    assert_no_nan("the scorecard", &text);
    assert!(text.contains("not decided (1 realization)"));
}
