//! One reduced validation end to end: `d_onset` (assumption (d), mode onset), the fastest
//! of the built-in validations, through [`persson_check::validation::run`].
//!
//! This is what `persson-check validate` and `cargo test` pay per validation: surface
//! generation, the load searches and magnification sweeps of every realization (in
//! parallel), the reduction to a verdict, and writing the outcome, tables and figures. It
//! catches slow-downs outside the solvers (sweeps, statistics, plotting, I/O) that the
//! solve benchmarks miss.
//!
//! Every iteration writes into a fresh temporary directory (created and removed outside the
//! timing), so no iteration reuses the job results of another.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, SamplingMode};
use persson_check::validation::source::{builtin_sources, select};
use persson_check::validation::{run, RunOptions, Scale};

/// The validation timed.
const NAME: &str = "d_onset";

fn reduced(c: &mut Criterion) {
    let source = select(builtin_sources(), &[NAME.to_string()])
        .expect("built-in validation")
        .remove(0);
    let mut group = c.benchmark_group("validation");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(15));
    group.bench_function(NAME, |b| {
        b.iter_batched(
            || {
                let dir = tempfile::tempdir().expect("temporary directory");
                let opts = RunOptions::new(Scale::Reduced, dir.path());
                (dir, opts)
            },
            |(dir, opts)| {
                let outcome = run(black_box(&source), &opts).expect("validation runs");
                // The directory is removed when dropped, after the timing.
                (dir, outcome)
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(benches, reduced);
criterion_main!(benches);
