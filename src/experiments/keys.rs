//! The measures an experiment declares for a scene ([`Keys`]): the keys of the details a
//! run of it can have (with the grid, for a detail measured on several grids) and its
//! studies with their columns. A claim names its measure through these keys
//! ([`crate::validation::claims`]): a definition whose claim names a key that its
//! experiment does not declare for the scene is refused when it loads, so a mistyped key
//! is an error, never "not measured".
//!
//! Each family of keys is built by one function (or constant) of its experiment, called
//! both where the detail is written and where it is declared, so the two cannot drift.

/// The detail keys and studies a run of a scene can have: every one its jobs can give,
/// those of jobs merged in later (a study's, a variant's) included.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Keys {
    /// Detail keys, each with the grid it is measured on where it is one step of a
    /// resolution study.
    details: Vec<(String, Option<usize>)>,
    /// Study keys with their column keys.
    studies: Vec<(String, Vec<String>)>,
}

impl Keys {
    /// Declares the detail `key`.
    pub fn detail(&mut self, key: impl Into<String>) {
        self.details.push((key.into(), None));
    }

    /// Declares the details `keys`.
    pub fn details<K: Into<String>>(&mut self, keys: impl IntoIterator<Item = K>) {
        for k in keys {
            self.detail(k);
        }
    }

    /// Declares the detail `key` measured on the `n x n` grid.
    pub fn on_grid(&mut self, key: impl Into<String>, n: usize) {
        self.details.push((key.into(), Some(n)));
    }

    /// Declares the study `key` with `columns` (as [`super::study::Study::new`] takes them).
    pub fn study(&mut self, key: &str, columns: &[(&str, &str)]) {
        self.studies.push((
            key.to_string(),
            columns.iter().map(|(c, _)| c.to_string()).collect(),
        ));
    }

    /// Whether the detail `key` is declared, on the `n x n` grid if `grid` names one (on
    /// any grid, or none, otherwise).
    pub fn has_detail(&self, key: &str, grid: Option<usize>) -> bool {
        self.details
            .iter()
            .any(|(k, g)| k == key && (grid.is_none() || *g == grid))
    }

    /// The declared details as a claim names them: `KEY`, or `KEY@N` on the `N x N` grid.
    pub fn detail_names(&self) -> Vec<String> {
        self.details
            .iter()
            .map(|(k, g)| match g {
                Some(n) => format!("{k}@{n}"),
                None => k.clone(),
            })
            .collect()
    }

    /// The declared study keys.
    pub fn study_names(&self) -> Vec<String> {
        self.studies.iter().map(|(k, _)| k.clone()).collect()
    }

    /// The column keys of the study `key`, if it is declared.
    pub fn study_columns(&self, key: &str) -> Option<&[String]> {
        self.studies
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, c)| c.as_slice())
    }
}

/// The names among `declared` closest to `name`, at most eight: those that share the
/// longest beginning with it first (at least a few characters), or the first of them all
/// when none does.
pub fn closest(name: &str, declared: &[String]) -> Vec<String> {
    const MAX: usize = 8;
    let shared = |d: &str| {
        name.chars()
            .zip(d.chars())
            .take_while(|(a, b)| a == b)
            .count()
    };
    let mut close: Vec<(usize, &String)> = declared.iter().map(|d| (shared(d), d)).collect();
    if close.iter().any(|&(n, _)| n >= 3) {
        close.retain(|&(n, _)| n >= 3);
    }
    close.sort_by(|a, b| b.0.cmp(&a.0).then_with(|| a.1.cmp(b.1)));
    close.dedup_by(|a, b| a.1 == b.1);
    close
        .into_iter()
        .take(MAX)
        .map(|(_, d)| d.clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn details_are_found_with_or_without_their_grid() {
        let mut k = Keys::default();
        k.detail("share_ar0.14");
        k.on_grid("kappa_on_grid", 128);
        assert!(k.has_detail("share_ar0.14", None));
        assert!(!k.has_detail("share_ar0.14", Some(128)));
        assert!(k.has_detail("kappa_on_grid", None));
        assert!(k.has_detail("kappa_on_grid", Some(128)));
        assert!(!k.has_detail("kappa_on_grid", Some(256)));
        assert_eq!(k.detail_names(), ["share_ar0.14", "kappa_on_grid@128"]);
    }

    #[test]
    fn the_closest_names_share_the_longest_beginning() {
        let d: Vec<String> = ["share_ar0.14", "share_ar0.014", "shells", "flux_in"]
            .map(String::from)
            .to_vec();
        assert_eq!(
            closest("share_ar0.15", &d),
            ["share_ar0.14", "share_ar0.014"]
        );
        assert_eq!(closest("share_ar1", &d), ["share_ar0.014", "share_ar0.14"]);
        assert_eq!(closest("zzz", &d).len(), 4);
    }
}
