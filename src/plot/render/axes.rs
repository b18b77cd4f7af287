//! Axes: linear and logarithmic coordinates, their ticks and tick labels.

use super::*;

/// One axis as drawn: its range in data units and its scale.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct AxisCoord {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) log: bool,
}

impl AxisCoord {
    /// The axis for `axis` and the values `values` it has to show.
    pub(super) fn fit(axis: &Axis, values: impl Iterator<Item = f64>) -> Self {
        if let Some((lo, hi)) = axis.range {
            let ok = lo.is_finite() && hi.is_finite() && lo < hi && (!axis.log || lo > 0.0);
            if ok {
                return Self {
                    lo,
                    hi,
                    log: axis.log,
                };
            }
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| v.is_finite() && (!axis.log || *v > 0.0)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if axis.log {
            if lo > hi {
                (lo, hi) = (1.0, 10.0);
            } else if hi / lo < 1.0 + 1e-9 {
                (lo, hi) = (lo / 2.0, hi * 2.0);
            } else {
                let pad = (hi / lo).powf(0.04);
                (lo, hi) = (lo / pad, hi * pad);
            }
        } else if lo > hi {
            (lo, hi) = (0.0, 1.0);
        } else if hi - lo <= 1e-12 * lo.abs().max(hi.abs()) {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo, hi) = (lo - d, hi + d);
        } else {
            let pad = 0.05 * (hi - lo);
            (lo, hi) = (lo - pad, hi + pad);
        }
        Self {
            lo,
            hi,
            log: axis.log,
        }
    }

    /// Whether `v` can be drawn on this axis at all.
    pub(super) fn drawable(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// Data value to axis space (`ln v` on a log axis).
    pub(super) fn axis_of(&self, v: f64) -> f64 {
        if self.log {
            v.ln()
        } else {
            v
        }
    }

    pub(super) fn data_of(&self, t: f64) -> f64 {
        if self.log {
            t.exp()
        } else {
            t
        }
    }

    pub(super) fn t_range(&self) -> (f64, f64) {
        (self.axis_of(self.lo), self.axis_of(self.hi))
    }

    pub(super) fn contains(&self, v: f64) -> bool {
        self.drawable(v) && v >= self.lo && v <= self.hi
    }

    pub(super) fn clamp(&self, v: f64) -> f64 {
        v.clamp(self.lo, self.hi)
    }

    /// Tick positions on a logarithmic axis: powers of ten (every k-th decade when there are
    /// many), filled in with 2 and 5 or with every integer multiple when that gives fewer
    /// than four ticks; nice linear ticks when even those give fewer than three.
    pub(super) fn log_ticks(&self, max_points: usize, light: bool) -> Vec<f64> {
        let (lo, hi) = (self.lo, self.hi);
        let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        let decades = (e1 - e0).max(1) as usize;
        let sets: &[&[f64]] = &[&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], &[1.0]];
        let within = |mantissas: &[f64], step: i32| -> Vec<f64> {
            let mut out = Vec::new();
            let mut e = e0;
            while e <= e1 {
                for m in mantissas {
                    let v = m * 10f64.powi(e);
                    if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                        out.push(v);
                    }
                }
                e += step;
            }
            out
        };
        let max = max_points.max(2);
        let powers = within(&[1.0], 1);
        if powers.len() > max {
            let step = decades.div_ceil(max) as i32;
            return within(&[1.0], step.max(1));
        }
        if light {
            return sets
                .iter()
                .map(|set| within(set, 1))
                .find(|t| t.len() <= max)
                .unwrap_or(powers);
        }
        // The sparsest set with at least four ticks, else the densest with three.
        let candidates: Vec<Vec<f64>> = [
            &[1.0][..],
            &[1.0, 2.0, 5.0],
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
        ]
        .iter()
        .map(|set| within(set, 1))
        .filter(|t| t.len() <= max)
        .collect();
        if let Some(t) = candidates.iter().find(|t| t.len() >= 4) {
            return t.clone();
        }
        if let Some(t) = candidates.iter().rev().find(|t| t.len() >= 3) {
            return t.clone();
        }
        // Less than a decade: plain nice ticks.
        RangedCoordf64::from(lo..hi).key_points(max_points)
    }
}

impl Ranged for AxisCoord {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (t0, t1) = self.t_range();
        let frac = (self.axis_of(*value) - t0) / (t1 - t0);
        let px = limit.0 as f64 + frac * (limit.1 - limit.0) as f64;
        px.round().clamp(-1e6, 1e6) as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let light = matches!(hint.weight(), KeyPointWeight::Any);
        if self.log {
            self.log_ticks(hint.max_num_points(), light)
        } else {
            RangedCoordf64::from(self.lo..self.hi).key_points(hint)
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for AxisCoord {
    fn format(value: &f64) -> String {
        format_tick(*value)
    }
}

/// A tick label: at most four significant digits ([`significant`]).
pub(crate) fn format_tick(v: f64) -> String {
    significant(v, 4)
}

/// `x` to `digits` significant digits (at least one), exponent form below 1e-3 and from
/// 1e5, no trailing zeros: `0.3`, `12.5`, `1e-4`, `2.5e5`; zero as `0`, and a value that is
/// not finite as Rust prints it (`NaN`, `inf`, `-inf`).
pub fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let digits = digits.max(1);
    let a = x.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{x:.*e}", digits - 1);
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim_zeros(mantissa));
    }
    let decimals = (digits as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
    trim_zeros(&format!("{x:.decimals$}"))
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}
