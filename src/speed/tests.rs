//! Tests of the speed study.

use super::*;

#[test]
fn tiny_study_produces_every_row_and_its_files() {
    let opts = SpeedOptions::tiny();
    let mut lines = Vec::new();
    let study = run(&opts, &mut |l| lines.push(l.to_string())).unwrap();
    // Sizes 8 and 16 cannot hold lambda_s = 8 < lambda_l = N/2: left out.
    assert_eq!(opts.valid_sizes(), vec![32, 64]);
    let solvers = SOLVERS.len();
    assert_eq!(study.tolerance.len(), solvers * opts.tols.len());
    assert_eq!(study.sizes.len(), solvers * 2);
    assert_eq!(study.threads_study.len(), solvers * 2);
    // The tables list the solvers in the list's order.
    let order: Vec<SolverKind> = study.sizes.iter().map(|r| r.solver).collect();
    assert!(
        order.windows(2).all(|w| w[0].index() <= w[1].index()),
        "{order:?}"
    );
    assert!(
        lines.iter().any(|l| l.starts_with("reference")),
        "{lines:?}"
    );
    tighter_tolerances_are_more_accurate(&study, &opts);
    for fit in &study.fits {
        assert_eq!(fit.points, 2);
        assert!(fit.exponent.unwrap().is_finite());
        assert_eq!(fit.std_error, None, "two points give no error bar");
    }
    assert_eq!(study.threads_study[0].speedup, Some(1.0));
    floor_counts_fft_pairs(&study);
    warm_starts_converge(&study);
    files_hold_every_row(&study);
}

fn tighter_tolerances_are_more_accurate(study: &SpeedStudy, opts: &SpeedOptions) {
    assert!(study.reference.residual <= opts.reference_tol);
    for row in &study.tolerance {
        assert!(row.error.is_none(), "{row:?}");
        let res = row.residual.unwrap();
        assert!(res <= row.tol, "{row:?}");
        // A looser tolerance cannot be closer to the reference than the reference's
        // own accuracy allows, and the energy error is a relative error.
        assert!(row.energy_error.unwrap() < 1.0, "{row:?}");
        assert!(row.wall_s.unwrap() > 0.0);
    }
    // Tighter tolerances are at least as accurate, solver by solver.
    for kind in SOLVERS {
        let e: Vec<f64> = study
            .tolerance
            .iter()
            .filter(|r| r.solver == kind)
            .map(|r| r.energy_error.unwrap())
            .collect();
        assert!(e[1] <= e[0] + 1e-12, "{kind:?}: {e:?}");
        assert!(
            e[1] < 1e-5,
            "{kind:?}: tol 1e-8 gives energy error {}",
            e[1]
        );
    }
}

/// CG uses two FFT pairs an iteration (the preconditioner's and the compliance's) and a
/// third when the contact set changed (u = K^-1 p recomputed); GFMD and FIRE two (the
/// stress and the mass filter); all plus the set-up and the final residual.
fn floor_counts_fft_pairs(study: &SpeedStudy) {
    assert_eq!(study.floor.len(), SOLVERS.len());
    for row in &study.floor {
        assert!(row.error.is_none(), "{row:?}");
        let pairs = row.pairs_per_iteration.unwrap();
        assert!((2.0..=3.2).contains(&pairs), "{row:?}");
        assert!(
            row.overhead.unwrap() > 0.0 && row.fft_pair_s > 0.0,
            "{row:?}"
        );
    }
}

/// A load change and one shell, each solver, converged; after the 1% load change never
/// slower in iterations than a cold solve of the same problem. (On this grid the roughness
/// stops at zeta = 2, so the "one shell" adds half of it: a warm start there is not near
/// the solution, and GFMD's smaller warm step may take a few more iterations than its cold
/// solve.)
fn warm_starts_converge(study: &SpeedStudy) {
    assert_eq!(study.warm.len(), 2 * SOLVERS.len());
    for row in &study.warm {
        assert!(row.error.is_none(), "{row:?}");
        if row.change.starts_with("load") {
            assert!(
                row.warm_iterations.unwrap() <= row.cold_iterations.unwrap(),
                "{row:?}"
            );
        }
    }
    assert!(study
        .warm
        .iter()
        .any(|r| r.change.starts_with("one shell at zeta = ")));
}

/// One table per study, its header from the row type, one line per row; the figures; the
/// JSON read back.
fn files_hold_every_row(study: &SpeedStudy) {
    let dir = tempfile::tempdir().unwrap();
    let written = study.write(dir.path()).unwrap();
    assert!(dir.path().join("speed/speed_error.png").exists());
    assert!(dir.path().join("speed/speed_iterations.svg").exists());
    let table = |name: &str| {
        let path = SpeedStudy::table_path(dir.path(), name);
        assert!(written.contains(&path), "{name} not written");
        std::fs::read_to_string(path).unwrap()
    };
    for (name, header, rows) in [
        ("reference", "solver,tol,residual,iterations,wall_s", 1),
        (
            "tolerance",
            "solver,tol,wall_s,iterations,residual,tamaas",
            study.tolerance.len(),
        ),
        (
            "size",
            "solver,n,iterations,wall_s,residual,error",
            study.sizes.len(),
        ),
        (
            "threads",
            "solver,threads,wall_s,speedup,error",
            study.threads_study.len(),
        ),
        ("floor", "solver,n,fft_pair_s,iterations", study.floor.len()),
        ("warm", "solver,n,change,cold_iterations", study.warm.len()),
    ] {
        let text = table(name);
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].starts_with(header), "{name}: {}", lines[0]);
        assert_eq!(lines.len(), 1 + rows, "{name}:\n{text}");
    }
    for kind in SOLVERS {
        let name = kind.name();
        assert!(table("warm")
            .lines()
            .any(|l| l.starts_with(&format!("{name},32,"))));
        assert!(table("size")
            .lines()
            .any(|l| l.starts_with(&format!("{name},64,"))));
    }
    // serde_json reads floats back to within an ulp or so, not always bit for bit.
    let back = SpeedStudy::read(&dir.path().join("speed.json")).unwrap();
    assert_eq!(back.options, study.options);
    assert_eq!(back.tolerance.len(), study.tolerance.len());
    assert_eq!(back.fits.len(), study.fits.len());
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(
        rel(
            back.reference.elastic_energy,
            study.reference.elastic_energy
        ) < 1e-14
    );
}

#[test]
fn bad_options_name_the_option() {
    let e = SpeedOptions::with_n(16).validate().unwrap_err().to_string();
    assert!(e.contains("speed n") && e.contains("16"), "{e}");
    let e = SpeedOptions {
        repeats: 0,
        ..SpeedOptions::with_n(64)
    }
    .validate()
    .unwrap_err()
    .to_string();
    assert!(e.contains("speed repeats"), "{e}");
}

#[test]
fn exponent_is_the_log_log_slope() {
    let rows: Vec<SizeRow> = [(64, 100), (128, 200), (256, 400)]
        .iter()
        .map(|&(n, it)| SizeRow {
            solver: SolverKind::Cg,
            n,
            iterations: Some(it),
            wall_s: Some(1.0),
            residual: Some(1e-9),
            error: None,
        })
        .collect();
    let fit = fit_exponent(SolverKind::Cg, &rows);
    assert!((fit.exponent.unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(fit.points, 3);
    assert_eq!(fit_exponent(SolverKind::Gfmd, &rows).exponent, None);
}
