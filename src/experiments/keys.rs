//! The measures an experiment declares for a scene ([`Keys`]): the keys of the details a
//! run of it can have (with the grid, for a detail measured on several grids) and its
//! studies with their columns. A claim names its measure through these keys
//! ([`crate::validation::claims`]): a definition whose claim names a key that its
//! experiment does not declare for the scene is refused when it loads, so a mistyped key
//! is an error, never "not measured".
//!
//! A detail's key is typed ([`DetailKey`]): a stem and the values that pick one member of
//! a family of details, each with its quantity ([`Tag`]: the load, the resolving
//! magnification, ...), as `share` at `a_r = 0.14`. It is written `share_ar0.14` (the
//! value as Rust prints an `f64`, its shortest exact decimal), and read back to the same
//! values, so that a definition naming `share_ar0.140` names the same detail, and the text
//! a key prints is the one it was stored with.
//!
//! Each family of keys is built by one function (or constant) of its experiment, called
//! both where the detail is written and where it is declared, so the two cannot drift.

use std::fmt;
use std::hash::{Hash, Hasher};

use serde::{Deserialize, Serialize};

/// The quantity a value of a [`DetailKey`] gives, with the letters that write it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Tag {
    /// The relative contact area `a_r` that sets the load (`ar`).
    ContactArea,
    /// The reduced pressure `p0 / E*` (`p`).
    Pressure,
    /// The magnification at which a mode is resolved, `zeta_t` (`zt`).
    ZetaT,
    /// A magnification `zeta` (`zeta`).
    Zeta,
    /// A window, in bins or realizations (`window`).
    Window,
    /// The Hurst exponent (`H`).
    Hurst,
    /// The contact area of a step of the zero-pressure source (`a`).
    StepArea,
    /// The magnification of a step of the zero-pressure source (`z`).
    StepZeta,
}

impl Tag {
    /// Every tag, the longest letters first (so that `zeta` is not read as `z`).
    pub const ALL: [Tag; 8] = [
        Tag::Window,
        Tag::Zeta,
        Tag::ContactArea,
        Tag::ZetaT,
        Tag::Hurst,
        Tag::Pressure,
        Tag::StepArea,
        Tag::StepZeta,
    ];

    /// The letters that write the tag in a key.
    pub fn letters(self) -> &'static str {
        match self {
            Tag::ContactArea => "ar",
            Tag::Pressure => "p",
            Tag::ZetaT => "zt",
            Tag::Zeta => "zeta",
            Tag::Window => "window",
            Tag::Hurst => "H",
            Tag::StepArea => "a",
            Tag::StepZeta => "z",
        }
    }

    /// The tag and value a segment of a key writes (`ar0.14`), if it is one: the letters
    /// of a tag followed by a plain decimal number (digits with at most one point).
    fn read(segment: &str) -> Option<(Tag, f64)> {
        Tag::ALL.into_iter().find_map(|tag| {
            let digits = segment.strip_prefix(tag.letters())?;
            let plain = !digits.is_empty()
                && digits.starts_with(|c: char| c.is_ascii_digit())
                && digits.chars().all(|c| c.is_ascii_digit() || c == '.')
                && digits.matches('.').count() <= 1;
            plain
                .then(|| digits.parse().ok())
                .flatten()
                .map(|v| (tag, v))
        })
    }
}

/// The key of a detail: a stem, and the values that pick one member of a family of
/// details (`share` at `a_r = 0.14`, written `share_ar0.14`). The stem is at least the
/// first `_`-separated segment; the values are the trailing segments that are a tag and a
/// number. Two keys are equal when their stems are and their values are, tag by tag and
/// in order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(from = "String", into = "String")]
pub struct DetailKey {
    stem: String,
    at: Vec<(Tag, f64)>,
}

impl DetailKey {
    /// The key `stem` with no values.
    pub fn new(stem: impl Into<String>) -> Self {
        Self {
            stem: stem.into(),
            at: Vec::new(),
        }
    }

    /// The key with the value `value` of `tag` after those it has.
    pub fn at(mut self, tag: Tag, value: f64) -> Self {
        assert!(
            value.is_finite() && value >= 0.0,
            "a key's value is a finite number >= 0, got {value}"
        );
        self.at.push((tag, value));
        self
    }

    /// The stem: what the key names before its values.
    pub fn stem(&self) -> &str {
        &self.stem
    }

    /// The value of `tag`, if the key has one.
    pub fn value(&self, tag: Tag) -> Option<f64> {
        self.at.iter().find(|(t, _)| *t == tag).map(|&(_, v)| v)
    }

    /// The key's values as compared: `-0` is `0`.
    fn bits(&self) -> impl Iterator<Item = (Tag, u64)> + '_ {
        self.at.iter().map(|&(t, v)| (t, (v + 0.0).to_bits()))
    }
}

impl PartialEq for DetailKey {
    fn eq(&self, other: &Self) -> bool {
        self.stem == other.stem && self.bits().eq(other.bits())
    }
}

impl Eq for DetailKey {}

impl Hash for DetailKey {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.stem.hash(state);
        for v in self.bits() {
            v.hash(state);
        }
    }
}

impl PartialEq<str> for DetailKey {
    fn eq(&self, text: &str) -> bool {
        let other = DetailKey::from(text);
        self.eq(&other)
    }
}

impl PartialEq<&str> for DetailKey {
    fn eq(&self, text: &&str) -> bool {
        let other = DetailKey::from(*text);
        self.eq(&other)
    }
}

impl From<&str> for DetailKey {
    /// Reads a key as it is written (never fails: a text with no values is a stem).
    fn from(text: &str) -> Self {
        let segments: Vec<&str> = text.split('_').collect();
        let mut at = Vec::new();
        let mut end = segments.len();
        while end > 1 {
            match Tag::read(segments[end - 1]) {
                Some(v) => at.push(v),
                None => break,
            }
            end -= 1;
        }
        at.reverse();
        Self {
            stem: segments[..end].join("_"),
            at,
        }
    }
}

impl From<&DetailKey> for DetailKey {
    fn from(key: &DetailKey) -> Self {
        key.clone()
    }
}

impl From<String> for DetailKey {
    fn from(text: String) -> Self {
        DetailKey::from(text.as_str())
    }
}

impl From<DetailKey> for String {
    fn from(k: DetailKey) -> String {
        k.to_string()
    }
}

impl fmt::Display for DetailKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.stem)?;
        for (tag, v) in &self.at {
            write!(f, "_{}{v}", tag.letters())?;
        }
        Ok(())
    }
}

/// The detail keys and studies a run of a scene can have: every one its jobs can give,
/// those of jobs merged in later (a study's, a variant's) included.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Keys {
    /// Detail keys, each with the grid it is measured on where it is one step of a
    /// resolution study.
    details: Vec<(DetailKey, Option<usize>)>,
    /// Study keys with their column keys.
    studies: Vec<(String, Vec<String>)>,
}

impl Keys {
    /// Declares the detail `key`.
    pub fn detail(&mut self, key: impl Into<DetailKey>) {
        self.details.push((key.into(), None));
    }

    /// Declares the details `keys`.
    pub fn details<K: Into<DetailKey>>(&mut self, keys: impl IntoIterator<Item = K>) {
        for k in keys {
            self.detail(k);
        }
    }

    /// Declares the detail `key` measured on the `n x n` grid.
    pub fn on_grid(&mut self, key: impl Into<DetailKey>, n: usize) {
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
    pub fn has_detail(&self, key: &DetailKey, grid: Option<usize>) -> bool {
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
                None => k.to_string(),
            })
            .collect()
    }

    /// The declared detail keys, each once per grid it is declared on.
    pub fn detail_keys(&self) -> impl Iterator<Item = &DetailKey> {
        self.details.iter().map(|(k, _)| k)
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
        let key = |t: &str| DetailKey::from(t);
        assert!(k.has_detail(&key("share_ar0.14"), None));
        assert!(k.has_detail(&key("share_ar0.140"), None));
        assert!(!k.has_detail(&key("share_ar0.15"), None));
        assert!(!k.has_detail(&key("share_ar0.14"), Some(128)));
        assert!(k.has_detail(&key("kappa_on_grid"), None));
        assert!(k.has_detail(&key("kappa_on_grid"), Some(128)));
        assert!(!k.has_detail(&key("kappa_on_grid"), Some(256)));
        assert_eq!(k.detail_names(), ["share_ar0.14", "kappa_on_grid@128"]);
    }

    #[test]
    fn a_key_reads_its_trailing_values_and_prints_as_written() {
        let k = DetailKey::from("onset_ar0.87_zt16");
        assert_eq!(k.stem(), "onset");
        assert_eq!(k.value(Tag::ContactArea), Some(0.87));
        assert_eq!(k.value(Tag::ZetaT), Some(16.0));
        assert_eq!(
            k,
            DetailKey::new("onset")
                .at(Tag::ContactArea, 0.87)
                .at(Tag::ZetaT, 16.0)
        );
        for text in [
            "onset_ar0.87_zt16",
            "n1024_s_tilde_shift_ar0.03",
            "eps16_share_ar0.014",
            "s_tilde_ar0.1_window4",
            "corrected_ar0.2_zeta8",
            "corrected_start_p0.1",
            "size_kappa_change_H0.8",
            "non_contact_H0.5_a0.01_z63",
            "k1",
            "p0",
            "r2_x_minus_r2_ar",
            "change_full_contact_max",
            "share_ar.5",
        ] {
            assert_eq!(DetailKey::from(text).to_string(), text);
        }
        // The first segment is always the stem's; a value is a plain decimal number.
        assert_eq!(DetailKey::from("p0").stem(), "p0");
        assert_eq!(DetailKey::from("share_ar1e-3").stem(), "share_ar1e-3");
        assert_eq!(DetailKey::from("x_zeta2").value(Tag::Zeta), Some(2.0));
        assert_eq!(DetailKey::from("x_z2").value(Tag::StepZeta), Some(2.0));
        // The same value written otherwise is the same key, printed the one way.
        assert_eq!(DetailKey::from("share_ar0.140").to_string(), "share_ar0.14");
        assert_ne!(
            DetailKey::from("share_ar0.14"),
            DetailKey::from("share_after_ar0.14")
        );
        assert_ne!(
            DetailKey::from("onset_ar0.87_zt16"),
            DetailKey::from("onset_zt16_ar0.87")
        );
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
