//! The details an experiment declares for a scene, once ([`DetailTable`]): each row is a
//! detail's key (with its grid), its label, Persson's and the paper's values, and how its
//! value is read from the run's statistics. Both what a run writes
//! ([`crate::experiments::Experiment::details`]) and what a claim may name
//! ([`crate::experiments::Keys`]) derive from the one table, so they cannot drift apart: a
//! row whose statistic a run lacks (a part of the scene left out, a fit that needs more
//! points) is declared and not written.

use super::findings::Detail;
use super::keys::{DetailKey, Keys};
use crate::stats::Estimate;

/// How a row reads its value from the statistics `S` (`None`: the run has none).
type Read<'s, S> = Box<dyn Fn(&S) -> Option<Estimate> + 's>;

/// One declared detail: everything but the value, and how the value is read.
struct Row<'s, S> {
    key: DetailKey,
    name: String,
    persson: Option<f64>,
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

impl<S> Declared<'_, '_, S> {
    /// With Persson's value.
    pub fn persson(self, v: f64) -> Self {
        self.0.persson = Some(v);
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
        self.rows.push(Row {
            key: key.into(),
            name: name.into(),
            persson: None,
            paper: None,
            grid: None,
            read: Box::new(read),
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
                let value = (r.read)(stats)?;
                let mut d = Detail::new(r.key.clone(), r.name.clone(), value).paper(r.paper);
                d.persson = r.persson;
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
}
