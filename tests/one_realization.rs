//! A scene trimmed to one realization: every output (account, checks, CSV, JSON, figures,
//! the scorecard) is free of NaN, the checks say they are not decided instead of failing,
//! the verdicts without an error bar are inconclusive, and the text counts
//! "1 realization", singular.

use std::path::Path;

use persson_check::engine::solver::SolverKind;
use persson_check::report::{write, ReportOptions};
use persson_check::validation::source::sources_in;
use persson_check::validation::{run, Outcome, RunOptions, Scale, Source, Verdict};

use crate::common::{assert_no_nan, validations_dir};

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
flux_zeta = 2
flux_dzeta = 1
checkpoint_seconds = 30
tol = 1e-8
"#;

/// Every validation's `[reduced]` scene trimmed to one seed on a small grid (a few seconds
/// each): the name of the definition and its table.
const ONE_SEED_SCENES: &[(&str, &str)] = &[
    (
        "contact_area",
        "n = 32\nhursts = [0.5, 0.8]\nlambda_l = 16\nlambda_s = 4\nseeds = [1]\n\
         refinements = [1, 2]\nreduced_pressures = [0.01, 0.03, 0.1, 0.3, 0.8]\n\
         low_load = 0.03\nlaw_range = [0.01, 0.9]\nlaw_tolerance = 0.10\ntol = 1e-8\n\n\
         [reduced.scaling]\nns = [16, 32]\nhurst = 0.8\nlambda_s = 4\nseeds = [1]\n\
         reduced_pressure = 0.1\ntol = 1e-8\n\n\
         [reduced.system_size]\nfactor = 2\nhursts = [0.8]\nfrom_load = 0.03\n",
    ),
    ("a_diffusion", TRANSITION_WITH_DISTANCES),
    ("b_drift", TRANSITION),
    (
        "c_flux",
        "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1]\n\
         contact_area = 0.14\nzeta = 4\ndzeta = 0.375\ntol = 1e-8\n\n\
         [reduced.sensitivity]\nn = 32\nlambda_l = 16\nlambda_s = 4\nseeds = [1]\n\
         contact_area = 0.14\nzeta = 2\ntol = 1e-8\nsolver = \"cg\"\ntols = [1e-6, 1e-8]\n\
         step_factors = [1, 4]\nlambda_s_values = [4]\nlambda_l_fractions = [0.5]\n\
         fixed_area = true\nsolvers = [\"cg\"]\n\n\
         [reduced.waterfall]\nseed = 1\nzetas = [2, 8]\ncontact_area = 0.14\n\
         solver = \"cg\"\n",
    ),
    (
        "c_reentry",
        "n = 32\nhurst = 0.8\nlambda_l = 16\nlambda_s = 4\nseeds = [1]\n\
         contact_areas = [0.14, 0.014, 0.88]\nflux_zeta = 2\n\
         flux_dzeta = 1\ncheckpoint_seconds = 30\ntol = 1e-8\n\n\
         [[reduced.variants]]\nname = \"h03\"\nwhat = \"H = 0.3\"\nn = 32\nhurst = 0.3\n\
         lambda_l = 16\nlambda_s = 4\nseeds = [1]\ncontact_areas = [0.14, 0.014, 0.88]\n\
         tol = 1e-8\n\n\
         [[reduced.variants]]\nname = \"shells\"\nwhat = \"shell by shell\"\nn = 32\n\
         hurst = 0.8\nlambda_l = 16\nlambda_s = 4\nseeds = [1]\ncontact_areas = [0.14]\n\
         tol = 1e-8\nrecord_shells = true\n",
    ),
    (
        "d_onset",
        "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1]\n\
         contact_areas = [0.1, 0.9]\nheadline_contact_area = 0.1\ntargets = [2.0]\n\
         band = 0.1\nzeta_start = 1.0\nzeta_end = 8.0\nsteps_per_octave = 2\n\
         onset_ratio = 0.8\nfrozen_from = 2.0\ntol = 1e-8\nnarrow_band = 0.05\n",
    ),
    (
        "e_frozen",
        "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1]\n\
         contact_areas = [0.1, 0.5, 0.9]\nheadline_contact_area = 0.1\n\
         targets = [2.0, 3.0]\nband = 0.1\nzeta_start = 1.0\nzeta_end = 8.0\n\
         steps_per_octave = 2\nonset_ratio = 0.8\nfrozen_from = 2.0\ntol = 1e-8\n",
    ),
    (
        "total_energy",
        "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1]\n\
         low_load_seeds = []\ncontact_areas = [0.01, 0.03, 0.3]\nheadline_contact_area = 0.3\n\
         zeta_start = 1.0\nsteps_per_octave = 2\nincrements_at = [2.0]\nincrements = 3\n\
         tol = 1e-8\n",
    ),
];

/// The transition scene of (a) and (b), one seed, as a literal (for `concat!`).
macro_rules! transition {
    () => {
        "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1]\n\
         contact_area = 0.3\nzeta = 4\ndzeta = 0.2\nbins = 16\nbin_width = 0.25\n\
         low_pressure = 0.5\nhigh_pressure = 1.0\nmin_walkers = 5\ntol = 1e-8\n"
    };
}

/// The transition scenes of (a) and (b), one seed.
const TRANSITION: &str = transition!();

/// [`TRANSITION`] with the walkers' distances to the contact lines, as a_diffusion's
/// reduced scene has them.
const TRANSITION_WITH_DISTANCES: &str = concat!(transition!(), "contact_line_distances = true\n");

/// A folder of the shipped definitions with their `[reduced]` tables replaced by
/// [`ONE_SEED_SCENES`].
fn one_seed_definitions() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, reduced) in ONE_SEED_SCENES {
        let file = format!("{name}.toml");
        let text = std::fs::read_to_string(validations_dir().join(&file)).unwrap();
        let (head, rest) = text.split_at(text.find("[reduced]").expect("a [reduced] table"));
        let full = &rest[rest.find("\n[full]").expect("a [full] table")..];
        let text = format!("{head}[reduced]\n{reduced}{full}");
        std::fs::write(dir.path().join(file), text).unwrap();
    }
    dir
}

/// Every text file under `dir` (outcomes, tables, figures, the scorecard), without the
/// stored job results.
fn text_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n != "jobs") {
                out.extend(text_files(&path));
            }
        } else if path
            .extension()
            .is_some_and(|e| ["json", "csv", "svg", "md"].contains(&e.to_str().unwrap()))
        {
            out.push(path);
        }
    }
    out
}

#[test]
fn every_validation_with_one_realization_writes_no_nan_and_fails_no_check() {
    let definitions = one_seed_definitions();
    let sources = sources_in(definitions.path()).unwrap();
    assert_eq!(sources.len(), ONE_SEED_SCENES.len());
    let out = tempfile::tempdir().unwrap();
    let opts = RunOptions::new(Scale::Reduced, out.path());
    let outcomes: Vec<Outcome> = sources
        .iter()
        .map(|s| run(s, &opts).unwrap_or_else(|e| panic!("{}: {e}", s.path.display())))
        .collect();
    for o in &outcomes {
        for g in &o.guards {
            assert!(g.passed || !g.decided, "{}: {g:?}", o.name);
            if !g.decided {
                assert!(g.detail.starts_with("not decided"), "{}: {g:?}", o.name);
            }
        }
        if o.std_error.is_nan() {
            // No error bar: no verdict, no reproduction, and the account says why.
            assert_eq!(o.verdict, Verdict::Inconclusive, "{}", o.name);
            assert_eq!(o.reproduced, None, "{}", o.name);
            assert!(
                o.account.contains("no error bar with one realization"),
                "{}: {}",
                o.name,
                o.account
            );
        }
        assert!(o.value.is_finite(), "{}: no headline value", o.name);
        assert!(!o.account.contains("1 realizations"), "{}", o.account);
        for study in &o.studies {
            assert_no_nan(&format!("{} notes", o.name), &study.notes.join(" "));
        }
    }
    // The scorecard reads every outcome back (nulls where there is no error bar).
    scorecard(out.path());
    let files = text_files(out.path());
    assert!(files.len() > 3 * outcomes.len(), "{files:?}");
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        assert_no_nan(&path.display().to_string(), &text);
    }
    // Where there is no error bar, the CSV cell is empty.
    let csv = std::fs::read_to_string(out.path().join("d_onset.csv")).unwrap();
    assert!(csv.lines().nth(1).unwrap().contains(",,"), "{csv}");
}

/// Writes the scorecard of the outcomes in `dir` (no speed study there); returns its path.
fn scorecard(dir: &std::path::Path) -> std::path::PathBuf {
    let card = dir.join("scorecard.md");
    write(&ReportOptions {
        from: dir.to_path_buf(),
        out: card.clone(),
        golden: None,
    })
    .unwrap();
    card
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
    for c in &o.claims {
        assert_no_nan(&c.key, &format!("{} {:?}", c.statement, c.why));
    }
    // The headline share has no error bar: nothing is decided.
    assert_eq!(o.verdict, Verdict::Inconclusive);
    assert_eq!(o.reproduced, None);

    let json = std::fs::read_to_string(out.path().join("c_reentry.json")).unwrap();
    assert_no_nan("the JSON outcome", &json);
    let csv = std::fs::read_to_string(out.path().join("c_reentry.csv")).unwrap();
    assert_no_nan("the CSV", &csv);

    let card = scorecard(out.path());
    let text = std::fs::read_to_string(&card).unwrap();
    assert_no_nan("the scorecard", &text);
    assert!(text.contains("one realization: no error bar"), "{text}");
}
