//! One forward and one inverse real 2D FFT ([`Fft2::forward`] then
//! [`Fft2::inverse_in_place`]) on `N x N` grids, `N = 256, 512, 1024`.
//!
//! Every iteration of every solver applies the elastic Green's function in Fourier space,
//! so one transform pair is the floor of an iteration's cost: a solve cannot take less than
//! (iterations) x (this time). Comparing it with the solve benchmarks (`benches/solve.rs`)
//! shows how much of a solve is transforms and how much is the pointwise work around them.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use persson_check::engine::fft::Fft2;
use persson_check::engine::grid::Grid;

/// Grid sizes.
const SIZES: [usize; 3] = [256, 512, 1024];

/// A smooth, non-trivial real field (the values do not change the cost of a transform).
fn field(n: usize) -> Vec<f64> {
    let k = 2.0 * std::f64::consts::PI / n as f64;
    (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            (3.0 * k * x).sin() + 0.5 * (7.0 * k * (x + 2.0 * y)).cos()
        })
        .collect()
}

fn fft_pair(c: &mut Criterion) {
    let mut group = c.benchmark_group("fft_pair");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for n in SIZES {
        let grid = Grid::new(n, 1.0).expect("valid grid");
        let fft = Fft2::new(&grid);
        let input = field(n);
        let mut spec = fft.new_spectrum();
        let mut output = vec![0.0; n * n];
        group.throughput(Throughput::Elements((n * n) as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                fft.forward(black_box(&input), &mut spec);
                fft.inverse_in_place(&mut spec, &mut output);
                black_box(&output);
            })
        });
    }
    group.finish();
}

criterion_group!(benches, fft_pair);
criterion_main!(benches);
