//! The details an experiment declares for a scene, once ([`DetailTable`]): each row is a
//! detail's key (with its grid), its label, Persson's and the paper's values, and how its
//! value is read from the run's statistics. Both what a run writes (its conclusion's
//! details) and what a claim may name ([`crate::experiments::keys_of`]) derive from the one
//! table, so they cannot drift apart: a row whose statistic a run lacks (a part of the
//! scene left out, a fit that needs more points) is declared and not written. A row whose
//! label (or Persson's value) holds a measured number reads it from the statistics with its
//! value ([`DetailTable::row_labelled`], [`Declared::persson_from`]); its key stays the
//! scene's.

use super::findings::Detail;
use super::keys::{DetailKey, Keys};
use crate::stats::Estimate;

/// How a row reads its value from the statistics `S`, with its label where that holds a
/// measured number (`None`: the run has no value).
type Read<'s, S> = Box<dyn Fn(&S) -> Option<(Option<String>, Estimate)> + 's>;

/// How a row reads Persson's value from the statistics `S` (`None`: it has none).
type ReadPersson<'s, S> = Box<dyn Fn(&S) -> Option<f64> + 's>;

/// One declared detail: everything but the value, and how the value is read.
struct Row<'s, S> {
    key: DetailKey,
    /// The label (of a row labelled by its reading, the one read instead).
    name: String,
    persson: ReadPersson<'s, S>,
    paper: Option<f64>,
    grid: Option<usize>,
    read: Read<'s, S>,
}

/// The details a run of one scene can have, in the order a run writes them.
pub struct DetailTable<'s, S> {
    rows: Vec<Row<'s, S>>,
}

impl<S> Default for DetailTable<'_, S> {
    fn default() -> Self {
        Self { rows: Vec::new() }
    }
}

/// The value paired with `x` in a statistic kept per load, exponent or grid (`None`: that
/// member is not in the run), as a row of a family reads its own.
pub fn value_at<X: PartialEq + Copy, V: Copy>(entries: &[(X, V)], x: X) -> Option<V> {
    entries.iter().find(|&&(y, _)| y == x).map(|&(_, v)| v)
}

/// The row just declared, to give it Persson's or the paper's value or a grid.
pub struct Declared<'t, 's, S>(&'t mut Row<'s, S>);

impl<'s, S> Declared<'_, 's, S> {
    /// With Persson's value.
    pub fn persson(self, v: f64) -> Self {
        self.0.persson = Box::new(move |_: &S| Some(v));
        self
    }

    /// With Persson's value read from the statistics, where it depends on a measured
    /// number (as a correction factor of the measured contact area); `None`: none.
    pub fn persson_from(self, read: impl Fn(&S) -> Option<f64> + 's) -> Self {
        self.0.persson = Box::new(read);
        self
    }

    /// With the paper's value (if any).
    pub fn paper(self, v: Option<f64>) -> Self {
        self.0.paper = v;
        self
    }

    /// Measured on the `n x n` grid (one step of a resolution study).
    pub fn on_grid(self, n: usize) -> Self {
        self.0.grid = Some(n);
        self
    }
}

impl<'s, S> DetailTable<'s, S> {
    /// Declares the detail `key`, labelled `name`, whose value `read` takes from the
    /// statistics (`None` where a run has none).
    pub fn row(
        &mut self,
        key: impl Into<DetailKey>,
        name: impl Into<String>,
        read: impl Fn(&S) -> Option<Estimate> + 's,
    ) -> Declared<'_, 's, S> {
        let read = move |s: &S| read(s).map(|v| (None, v));
        self.push(key.into(), name.into(), Box::new(read))
    }

    /// Declares the detail `key` whose label holds a measured number: `read` takes the
    /// label with the value from the statistics (`None` where a run has none).
    pub fn row_labelled(
        &mut self,
        key: impl Into<DetailKey>,
        read: impl Fn(&S) -> Option<(String, Estimate)> + 's,
    ) -> Declared<'_, 's, S> {
        let read = move |s: &S| read(s).map(|(name, v)| (Some(name), v));
        self.push(key.into(), String::new(), Box::new(read))
    }

    /// Declares the detail `key` that every run has: `read` always gives a value.
    pub fn always(
        &mut self,
        key: impl Into<DetailKey>,
        name: impl Into<String>,
        read: impl Fn(&S) -> Estimate + 's,
    ) -> Declared<'_, 's, S> {
        self.row(key, name, move |s| Some(read(s)))
    }

    /// Adds the row `key` labelled `name` (unless `read` gives the label) and returns it.
    fn push(&mut self, key: DetailKey, name: String, read: Read<'s, S>) -> Declared<'_, 's, S> {
        self.rows.push(Row {
            key,
            name,
            persson: Box::new(|_: &S| None),
            paper: None,
            grid: None,
            read,
        });
        let last = self.rows.len() - 1;
        Declared(&mut self.rows[last])
    }

    /// The declared keys, each with its grid, added to `keys`.
    pub fn declare(&self, keys: &mut Keys) {
        for r in &self.rows {
            match r.grid {
                Some(n) => keys.on_grid(r.key.clone(), n),
                None => keys.detail(r.key.clone()),
            }
        }
    }

    /// The declared keys alone.
    pub fn keys(&self) -> Keys {
        let mut keys = Keys::default();
        self.declare(&mut keys);
        keys
    }

    /// The details of a run with statistics `stats`: every row it has a value for, in
    /// the order declared.
    pub fn details(&self, stats: &S) -> Vec<Detail> {
        self.rows
            .iter()
            .filter_map(|r| {
                let (name, value) = (r.read)(stats)?;
                let name = name.unwrap_or_else(|| r.name.clone());
                let mut d = Detail::new(r.key.clone(), name, value).paper(r.paper);
                d.persson = (r.persson)(stats);
                d.grid = r.grid;
                Some(d)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Stats {
        low: Estimate,
        fit: Option<Estimate>,
    }

    fn table(loads: &[f64]) -> DetailTable<'_, Stats> {
        let mut t = DetailTable::default();
        t.always("mu_low", "drift at low pressure", |s: &Stats| s.low)
            .persson(0.0);
        for &a in loads {
            t.row(
                DetailKey::new("fit").at(super::super::keys::Tag::ContactArea, a),
                format!("fit at a_r = {a}"),
                |s: &Stats| s.fit,
            )
            .on_grid(128);
        }
        t
    }

    #[test]
    fn the_keys_and_the_details_come_from_the_same_rows() {
        let t = table(&[0.1]);
        let keys = t.keys();
        assert_eq!(keys.detail_names(), ["mu_low", "fit_ar0.1@128"]);
        let with = Stats {
            low: Estimate::new(0.5, 0.1),
            fit: Some(Estimate::new(2.0, 0.0)),
        };
        let d = t.details(&with);
        assert_eq!(d.len(), 2);
        assert_eq!(d[0].key, "mu_low");
        assert_eq!(d[0].persson, Some(0.0));
        assert_eq!((d[1].grid, d[1].value.value), (Some(128), 2.0));
        // A row the run has no value for is declared, not written.
        let without = Stats { fit: None, ..with };
        assert_eq!(t.details(&without).len(), 1);
        assert_eq!(t.keys().detail_names().len(), 2);
    }

    #[test]
    fn a_labelled_row_reads_its_label_and_persson_from_the_statistics() {
        let mut t = DetailTable::default();
        t.row_labelled("fit", |s: &Stats| {
            let fit = s.fit?;
            Some((format!("fit, measured low {}", s.low.value), fit))
        })
        .persson_from(|s: &Stats| Some(2.0 * s.low.value))
        .paper(Some(3.0));
        assert_eq!(t.keys().detail_names(), ["fit"]);
        let with = Stats {
            low: Estimate::new(0.5, 0.1),
            fit: Some(Estimate::new(2.0, 0.0)),
        };
        let d = t.details(&with);
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].name, "fit, measured low 0.5");
        assert_eq!((d[0].persson, d[0].paper), (Some(1.0), Some(3.0)));
        assert_eq!(d[0].value.value, 2.0);
        // No value: declared, not written.
        let without = Stats { fit: None, ..with };
        assert!(t.details(&without).is_empty());
    }
}
