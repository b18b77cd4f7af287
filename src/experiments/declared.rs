//! The details an experiment declares for a scene, once ([`DetailTable`]): each row is a
//! detail's key (with its grid), its label, Persson's and the paper's values, and how its
//! value is read from the run's statistics. Both what a run writes
//! ([`crate::experiments::Experiment::details`]) and what a claim may name
//! ([`crate::experiments::Keys`]) derive from the one table, so they cannot drift apart: a
//! row whose statistic a run lacks (a part of the scene left out, a fit that needs more
//! points) is declared and not written. A label that quotes a measured number is read
//! with the value ([`DetailTable::labelled`]), and Persson's value at a measured quantity
//! from the statistics too ([`Declared::persson_of`]); the key never depends on the run.

use super::findings::Detail;
use super::keys::{DetailKey, Keys};
use crate::stats::Estimate;

/// A row's value read from the statistics `S` (`None`: the run has none).
type ReadValue<'s, S> = Box<dyn Fn(&S) -> Option<Estimate> + 's>;

/// A row's label and value read together from the statistics `S`.
type ReadLabelled<'s, S> = Box<dyn Fn(&S) -> Option<(String, Estimate)> + 's>;

/// How a row reads its value from the statistics `S` (`None`: the run has none).
enum Read<'s, S> {
    /// The value alone: the label is the row's.
    Value(ReadValue<'s, S>),
    /// The label with the value: a label that quotes a measured number.
    Labelled(ReadLabelled<'s, S>),
}

/// Persson's value read from the statistics `S`.
type ReadPersson<'s, S> = Box<dyn Fn(&S) -> f64 + 's>;

/// One declared detail: everything but the value, and how the value is read.
struct Row<'s, S> {
    key: DetailKey,
    name: String,
    persson: Option<f64>,
    persson_of: Option<ReadPersson<'s, S>>,
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

/// The row just declared, to give it Persson's or the paper's value or a grid.
pub struct Declared<'t, 's, S>(&'t mut Row<'s, S>);

impl<'s, S> Declared<'_, 's, S> {
    /// With Persson's value.
    pub fn persson(self, v: f64) -> Self {
        self.0.persson = Some(v);
        self
    }

    /// With Persson's value read from the statistics, where it is his prediction at a
    /// measured quantity (as the correction factor at the theory's contact area at the
    /// load a run found).
    pub fn persson_of(self, read: impl Fn(&S) -> f64 + 's) -> Self {
        self.0.persson_of = Some(Box::new(read));
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
        self.push(key.into(), name.into(), Read::Value(Box::new(read)))
    }

    /// Declares the detail `key` whose label quotes a measured number: `read` takes the
    /// label with the value from the statistics (`None` where a run has none).
    pub fn labelled(
        &mut self,
        key: impl Into<DetailKey>,
        read: impl Fn(&S) -> Option<(String, Estimate)> + 's,
    ) -> Declared<'_, 's, S> {
        self.push(key.into(), String::new(), Read::Labelled(Box::new(read)))
    }

    /// Adds a row with no values of Persson, the paper or a grid yet.
    fn push(&mut self, key: DetailKey, name: String, read: Read<'s, S>) -> Declared<'_, 's, S> {
        self.rows.push(Row {
            key,
            name,
            persson: None,
            persson_of: None,
            paper: None,
            grid: None,
            read,
        });
        let last = self.rows.len() - 1;
        Declared(&mut self.rows[last])
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
                let (name, value) = match &r.read {
                    Read::Value(read) => (r.name.clone(), read(stats)?),
                    Read::Labelled(read) => read(stats)?,
                };
                let mut d = Detail::new(r.key.clone(), name, value).paper(r.paper);
                d.persson = r.persson_of.as_ref().map_or(r.persson, |p| Some(p(stats)));
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
    fn a_label_quoting_a_measured_number_is_read_with_the_value() {
        let mut t = DetailTable::default();
        t.labelled("low", |s: &Stats| {
            Some((format!("drift at {:.1} measured", s.low.value), s.low))
        })
        .persson_of(|s: &Stats| 2.0 * s.low.value);
        t.labelled("fit", |s: &Stats| Some((String::from("fit"), s.fit?)))
            .persson(1.0);
        assert_eq!(t.keys().detail_names(), ["low", "fit"]);
        let s = Stats {
            low: Estimate::new(0.5, 0.1),
            fit: None,
        };
        let d = t.details(&s);
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].name, "drift at 0.5 measured");
        assert_eq!((d[0].value, d[0].persson), (s.low, Some(1.0)));
    }
}
