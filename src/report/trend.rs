//! The headlines over the last nights: a history of one JSON line per night, and the
//! scorecard's trend figure drawn from it (`report --history FILE`).
//!
//! A line is a [`Night`]: its date (UTC), when it was recorded, the commit, and every
//! headline (value and standard error) keyed `<scale>/<name>`. Recording a night whose date
//! is the history's last one merges its headlines into that line, so that the reduced and
//! the full scorecard of one night make one line. The figure shows, for each headline of
//! the scorecard's outcomes over the last [`WINDOW`] nights, its value less the latest
//! night's in the latest night's standard errors,
//!
//! `(x_night - x_latest) / s_latest`,
//!
//! so that every headline shares one axis and a move of a few standard errors stands out;
//! a headline without an error bar on the latest night is listed in the table only.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use serde::{Deserialize, Serialize};

use super::format::{link, md, pm, push_table};
use super::read_outcomes;
use crate::error::{Error, Result};
use crate::plot::{Axis, Figure, Series, Style};

/// Nights shown in the trend.
pub const WINDOW: usize = 30;

/// A headline as the history keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Headline {
    /// Its value (`None`: not measured).
    pub value: Option<f64>,
    /// Its standard error (`None`: no error bar).
    pub std_error: Option<f64>,
}

/// One line of the history.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Night {
    /// The date, UTC (`YYYY-MM-DD`).
    pub night: String,
    /// When it was recorded, seconds since the Unix epoch.
    pub unix: f64,
    /// The commit of the code.
    pub commit: String,
    /// Every headline, keyed `<scale>/<name>`.
    pub headlines: BTreeMap<String, Headline>,
}

/// The history in `path`: every line, oldest first (none when the file does not exist).
pub fn read_history(path: &Path) -> Result<Vec<Night>> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(Error::io(path, e)),
    };
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(k, l)| {
            serde_json::from_str(l)
                .map_err(|e| Error::bad_file(path, format!("line {}: not a night ({e})", k + 1)))
        })
        .collect()
}

/// Writes the history to `path`, one line per night.
pub fn write_history(path: &Path, nights: &[Night]) -> Result<()> {
    let mut text = String::new();
    for n in nights {
        text.push_str(&serde_json::to_string(n).expect("nights serialise"));
        text.push('\n');
    }
    crate::io::write_atomic(path, text.as_bytes())
}

/// Tonight's line: the headlines of the outcomes in `from`, at `unix` seconds.
pub fn night_of(from: &Path, unix: f64) -> Result<Night> {
    let finite = |x: f64| x.is_finite().then_some(x);
    let headlines = read_outcomes(from)?
        .into_iter()
        .map(|l| {
            let o = l.outcome;
            (
                format!("{}/{}", o.scale, o.name),
                Headline {
                    value: finite(o.value),
                    std_error: finite(o.std_error),
                },
            )
        })
        .collect();
    Ok(Night {
        night: crate::provenance::rfc3339_utc(
            UNIX_EPOCH + std::time::Duration::from_secs_f64(unix),
        )[..10]
            .to_string(),
        unix,
        commit: crate::provenance::commit_label(),
        headlines,
    })
}

/// Records `night` in `nights`: merged into the last line when it has the same date,
/// appended otherwise.
pub fn record(nights: &mut Vec<Night>, night: Night) {
    match nights.last_mut() {
        Some(last) if last.night == night.night => {
            last.unix = night.unix;
            last.commit = night.commit;
            last.headlines.extend(night.headlines);
        }
        _ => nights.push(night),
    }
}

/// The trend figure of the headlines `keys` over `nights` (the window, oldest first).
pub fn trend_figure(nights: &[Night], keys: &[String]) -> Figure {
    let first = nights.first().map_or(0.0, |n| n.unix);
    let latest = nights.last();
    let series = keys
        .iter()
        .filter_map(|key| {
            let last = latest?.headlines.get(key)?;
            let (x0, s0) = (last.value?, last.std_error.filter(|s| *s > 0.0)?);
            let points = nights.iter().filter_map(|n| {
                let h = n.headlines.get(key)?;
                Some(((n.unix - first) / 86_400.0, (h.value? - x0) / s0))
            });
            Some(Series::xy(key.clone(), Style::LinePoints, points))
        })
        .collect();
    Figure {
        name: "trend".into(),
        title: "Headlines over the last nights, against the latest night".into(),
        x: Axis::linear("days since the first night shown"),
        y: Axis::linear("value less the latest night's, in its standard errors"),
        y2: None,
        series,
    }
}

/// The largest move of `key` from one night to the next, in the later night's standard
/// errors (`None` without two nights with error bars).
fn largest_step(nights: &[Night], key: &str) -> Option<f64> {
    let values: Vec<Headline> = nights
        .iter()
        .filter_map(|n| n.headlines.get(key).copied())
        .collect();
    values
        .windows(2)
        .filter_map(|w| Some((w[1].value? - w[0].value?) / w[1].std_error?))
        .filter(|z| z.is_finite())
        .fold(None, |m: Option<f64>, z| {
            Some(m.map_or(z, |m| if z.abs() > m.abs() { z } else { m }))
        })
}

/// The trend section of the scorecard: the figure (`figure`, linked relative to `base`)
/// and one row per headline of `keys`.
pub fn section(
    nights: &[Night],
    keys: &[String],
    history: &Path,
    figure: &Path,
    base: &Path,
) -> String {
    let mut s = String::from("## Trend of the headlines\n\n");
    let (Some(first), Some(last)) = (nights.first(), nights.last()) else {
        return s;
    };
    let _ = writeln!(
        s,
        "The last {} night{} of `{}` ({} to {}): each headline less its value on the latest \
         night, in that night's standard errors.\n\n![trend]({})\n",
        nights.len(),
        if nights.len() == 1 { "" } else { "s" },
        md(&history.display().to_string()),
        first.night,
        last.night,
        link(base, figure)
    );
    let shown = |h: Option<&Headline>| {
        h.map_or("n/a".into(), |h| {
            pm(h.value.unwrap_or(f64::NAN), h.std_error.unwrap_or(f64::NAN))
        })
    };
    let rows: Vec<Vec<String>> = keys
        .iter()
        .map(|key| {
            let seen: Vec<&Night> = nights
                .iter()
                .filter(|n| n.headlines.contains_key(key))
                .collect();
            vec![
                format!("`{key}`"),
                seen.len().to_string(),
                seen.first().map_or("n/a".into(), |n| {
                    format!("{} ({})", shown(n.headlines.get(key)), n.night)
                }),
                shown(last.headlines.get(key)),
                largest_step(nights, key).map_or("n/a".into(), |z| format!("{z:+.1}")),
            ]
        })
        .collect();
    push_table(
        &mut s,
        &[
            "headline",
            "nights",
            "first shown",
            "latest",
            "largest move from one night to the next (standard errors)",
        ],
        &rows,
    );
    s
}

/// Records the headlines of the outcomes in `from` as tonight's line of `history` (created
/// when missing), draws the trend of the last [`WINDOW`] nights into `trend/` beside the
/// scorecard `scorecard` (`from` is only read) and appends its section to the scorecard;
/// the files drawn.
pub fn append(scorecard: &Path, from: &Path, history: &Path) -> Result<Vec<PathBuf>> {
    let now = crate::provenance::epoch_seconds(SystemTime::now());
    let tonight = night_of(from, now)?;
    let keys: Vec<String> = tonight.headlines.keys().cloned().collect();
    let mut nights = read_history(history)?;
    record(&mut nights, tonight);
    write_history(history, &nights)?;
    let window = &nights[nights.len().saturating_sub(WINDOW)..];
    let base = super::format::absolute(scorecard)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let files = crate::plot::render(&trend_figure(window, &keys), &base.join("trend"))?;
    let png = files
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "png"))
        .cloned()
        .unwrap_or_default();
    let mut text = std::fs::read_to_string(scorecard).map_err(|e| Error::io(scorecard, e))?;
    text.push('\n');
    text.push_str(&section(window, &keys, history, &png, &base));
    crate::io::write_atomic(scorecard, text.as_bytes())?;
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn night(date: &str, day: f64, values: &[(&str, f64, f64)]) -> Night {
        Night {
            night: date.into(),
            unix: day * 86_400.0,
            commit: "c".into(),
            headlines: values
                .iter()
                .map(|(k, v, e)| {
                    (
                        k.to_string(),
                        Headline {
                            value: Some(*v),
                            std_error: Some(*e),
                        },
                    )
                })
                .collect(),
        }
    }

    #[test]
    fn one_line_per_night_and_moves_in_standard_errors() {
        let mut nights = Vec::new();
        record(
            &mut nights,
            night("2026-11-01", 0.0, &[("reduced/a", 1.0, 0.1)]),
        );
        record(
            &mut nights,
            night("2026-11-01", 0.1, &[("full/a", 2.0, 0.5)]),
        );
        assert_eq!(nights.len(), 1, "the same night merges");
        assert_eq!(nights[0].headlines.len(), 2);
        record(
            &mut nights,
            night("2026-11-02", 1.0, &[("reduced/a", 1.5, 0.1)]),
        );
        assert_eq!(nights.len(), 2);
        let keys = vec!["reduced/a".to_string(), "full/a".to_string()];
        let f = trend_figure(&nights, &keys);
        // Only reduced/a is on the latest night.
        assert_eq!(f.series.len(), 1);
        let p = &f.series[0].points;
        assert!((p[0].y + 5.0).abs() < 1e-9 && p[1].y == 0.0, "{p:?}");
        assert!((p[1].x - (1.0 - 0.1)).abs() < 1e-9);
        assert!((largest_step(&nights, "reduced/a").unwrap() - 5.0).abs() < 1e-9);
        assert_eq!(largest_step(&nights, "full/a"), None);
    }

    #[test]
    fn history_reads_back_and_names_a_bad_line() {
        let dir = std::env::temp_dir().join(format!("trend-test-{}", std::process::id()));
        let path = dir.join("history.jsonl");
        assert!(read_history(&path).unwrap().is_empty());
        let nights = vec![night("2026-11-01", 0.0, &[("reduced/a", 1.0, 0.1)])];
        write_history(&path, &nights).unwrap();
        assert_eq!(read_history(&path).unwrap(), nights);
        std::fs::write(&path, "{\"night\": 1}\n").unwrap();
        let e = read_history(&path).unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
