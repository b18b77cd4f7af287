//! The interval a claim is judged with: `value +- z std_error`, where `z` is the
//! significance for four or more realizations and Student's t at the same coverage for
//! two or three ([`interval_z`]), and the realizations that would shrink it within a
//! margin ([`realizations_needed`]).

/// The interval's half width in standard errors for `n` realizations: `z` for four or
/// more (or where the count is not known), and for two or three Student's t with `n - 1`
/// degrees of freedom at the coverage of `+-z` of a normal distribution (with two
/// realizations, +-3 standard errors would hold the mean only about 80% of the time).
pub fn interval_z(z: f64, n: Option<usize>) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
    match n {
        Some(n @ 2..=3) => {
            let coverage = Normal::standard().cdf(z);
            StudentsT::new(0.0, 1.0, (n - 1) as f64)
                .expect("a positive number of degrees of freedom")
                .inverse_cdf(coverage)
        }
        _ => z,
    }
}

/// The normal significance whose coverage Student's t with `n - 1` degrees of freedom
/// has at `t` standard errors: the inverse of [`interval_z`].
pub fn normal_z(t: f64, n: usize) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
    let coverage = StudentsT::new(0.0, 1.0, (n.max(2) - 1) as f64)
        .expect("a positive number of degrees of freedom")
        .cdf(t);
    Normal::standard().inverse_cdf(coverage)
}

/// The fewest realizations whose interval (`interval_z(z, m)` standard errors of
/// `std_error sqrt(n / m)`) fits within `margin`, from `n` now.
pub fn realizations_needed(std_error: f64, n: usize, margin: f64, z: f64) -> usize {
    let half = |m: usize| interval_z(z, Some(m)) * std_error * (n as f64 / m as f64).sqrt();
    let mut m = n.max(2);
    while half(m) > margin && m < 1_000_000 {
        m = if m < 16 { m + 1 } else { m + m / 8 };
    }
    m
}
