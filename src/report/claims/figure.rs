//! The chart beside the claims page: each evidence claim's measurement against its rule's
//! region, in units of the rule's tolerance.

use super::CHART;
use crate::plot::{IntervalChart, IntervalRow};
use crate::stats::Region;
use crate::validation::claims::ClaimKind;
use crate::validation::{ClaimOutcome, ClaimResult, Outcome};

/// A claim's position for the chart: its measurement's distance into the rule's region in
/// units of the tolerance (the rule's edge at 0, inside positive; a two-sided region's
/// centre at 1) and its interval's half width in those units.
pub fn position(c: &ClaimOutcome, resolution: f64) -> Option<(f64, f64)> {
    let (e, region) = (c.judged()?, c.region()?);
    if !(e.value.is_finite() && e.has_error()) {
        return None;
    }
    let half = c.interval_z.unwrap_or(3.0) * e.std_error;
    let band = c.unit.map_or(resolution, |u| u.band_width(resolution));
    Some(match region {
        Region::Interval { lo, hi, .. } if lo.is_finite() && hi.is_finite() => {
            let w = 0.5 * (hi - lo);
            let centre = 0.5 * (hi + lo);
            ((w - (e.value - centre).abs()) / w, half / w)
        }
        Region::Interval { lo, .. } if lo.is_finite() => ((e.value - lo) / band, half / band),
        Region::Interval { hi, .. } => ((hi - e.value) / band, half / band),
        Region::Outside(lo, hi) => {
            let w = 0.5 * (hi - lo);
            (((e.value - 0.5 * (hi + lo)).abs() - w) / w, half / w)
        }
        Region::Except(t) => ((e.value - t).abs() / band, half / band),
    })
}

/// The chart of the evidence claims of `outcomes` measured with an error bar: each
/// claim's position against its rule ([`position`], a number of a measure's own unit in
/// units of its validation's resolution), grouped by validation, coloured by result.
pub fn chart(outcomes: &[&Outcome]) -> IntervalChart {
    let kinds = ["reproduced", "contradicted", "not established"];
    let rows = outcomes
        .iter()
        .flat_map(|o| {
            o.claims
                .iter()
                .filter(|c| c.kind == ClaimKind::Evidence)
                .filter_map(move |c| {
                    let kind = match c.result {
                        ClaimResult::Reproduced => 0,
                        ClaimResult::Contradicted => 1,
                        ClaimResult::NotEstablished => 2,
                        _ => return None,
                    };
                    let (value, half) = position(c, o.rule.resolution)?;
                    Some(IntervalRow {
                        group: o.name.clone(),
                        label: c.key.clone(),
                        value,
                        half,
                        kind,
                    })
                })
        })
        .collect();
    IntervalChart {
        name: CHART.into(),
        title: "The paper's claims against their rules".into(),
        x_label: "distance into the rule's region, in units of its tolerance (0: the edge)".into(),
        range: (-6.0, 2.0),
        kinds: kinds.iter().map(|k| k.to_string()).collect(),
        rows,
    }
}
