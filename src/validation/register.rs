//! The register of the claims' rules (`validations/register.json`): every rule a claim has
//! been decided under, in order, each with the hash of the rule as it decides
//! ([`ClaimSpec::rule_sha256`]: phrase, measure, region, alternative, significance, kind and
//! reading), the day and commit it was registered, and the verdicts the committed outcomes
//! gave under it. Rules are fixed from the paper's text before the data; a rule changed
//! after an outcome exists is an amendment: the claim states it (`amendments`, with the
//! reason), and the register keeps the earlier rule and its verdicts, which the page shows
//! beside the new one.
//!
//! [`Register::problems`] is the suite's check: every claim's current rule is the last one
//! registered for it, and every earlier one has its amendment. [`Register::update`]
//! registers new claims and amended rules (refusing a changed rule without an amendment)
//! and fills in the verdicts of the committed outcomes (`claims --register`).

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::claims::{ClaimResult, ClaimSpec};
use super::outcome::Outcome;
use crate::error::{Error, Result};
use crate::stats::Estimate;

/// The file of the register, relative to the repository's root.
pub const REGISTER_FILE: &str = "validations/register.json";

/// The register: every claim's rules, by `<validation>.<claim>`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Register {
    /// What the file is.
    pub about: String,
    /// Each claim's rules, oldest first.
    pub claims: BTreeMap<String, Vec<Registered>>,
}

/// One rule of a claim, as registered.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Registered {
    /// [`ClaimSpec::rule_sha256`].
    pub sha256: String,
    /// The rule as it decides ([`ClaimSpec::decisive`]).
    pub rule: serde_json::Value,
    /// The day it was registered (UTC, YYYY-MM-DD).
    pub registered: String,
    /// The commit it was registered at (the one before the registering commit).
    pub commit: String,
    /// The verdict of the committed full-scale outcome under this rule, once known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub full: Option<Verdicted>,
    /// The verdict of the committed reduced-scale outcome under this rule, once known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reduced: Option<Verdicted>,
}

/// A claim's result under one rule, with the measurement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Verdicted {
    /// The result.
    pub result: ClaimResult,
    /// The measurement, where there was one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<Estimate>,
}

/// The register's name of a claim: `<validation>.<claim>`.
pub fn claim_id(validation: &str, key: &str) -> String {
    format!("{validation}.{key}")
}

impl Register {
    /// Reads the register at `path`.
    ///
    /// # Errors
    ///
    /// An unreadable file, or one that is not a register.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::parse(&text).map_err(|e| Error::bad_file(path, e))
    }

    /// Parses a register's text.
    ///
    /// # Errors
    ///
    /// Text that is not a register, in words.
    pub fn parse(text: &str) -> std::result::Result<Self, String> {
        serde_json::from_str(text).map_err(|e| e.to_string())
    }

    /// Writes the register to `path`, atomically.
    ///
    /// # Errors
    ///
    /// The file cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        let mut text = serde_json::to_string_pretty(self).expect("a register serialises");
        text.push('\n');
        crate::io::write_atomic(path, text.as_bytes())
    }

    /// The rules registered for `id`, oldest first.
    pub fn rules(&self, id: &str) -> &[Registered] {
        self.claims.get(id).map_or(&[], Vec::as_slice)
    }

    /// What does not hold of the register against the definitions' claims (`claims`: each
    /// validation's name with its claims): an unregistered claim, a current rule that is
    /// not the last registered, an earlier rule without its amendment (in order), an
    /// amendment that names no earlier rule, a registered claim no definition holds.
    pub fn problems(&self, claims: &[(String, Vec<ClaimSpec>)]) -> Vec<String> {
        let mut problems = Vec::new();
        let mut seen = Vec::new();
        for (validation, specs) in claims {
            for c in specs {
                let id = claim_id(validation, &c.key);
                seen.push(id.clone());
                problems.extend(self.problems_of(&id, c));
            }
        }
        for id in self.claims.keys().filter(|id| !seen.contains(id)) {
            problems.push(format!(
                "{id}: registered, but no definition holds it (a claim is withdrawn by an \
                 amendment of its rule, not by deleting it)"
            ));
        }
        problems
    }

    fn problems_of(&self, id: &str, c: &ClaimSpec) -> Vec<String> {
        let rules = self.rules(id);
        let Some(last) = rules.last() else {
            return vec![format!(
                "{id}: not registered (run `persson-check claims --register`)"
            )];
        };
        let mut problems = Vec::new();
        let sha = c.rule_sha256();
        if last.sha256 != sha {
            problems.push(format!(
                "{id}: the rule changed since it was registered ({} -> {}); a rule changed \
                 after an outcome exists is an amendment: add `amendments = [{{ from = \"{}\", \
                 reason = \"...\" }}]` to the claim and run `persson-check claims --register`",
                short(&last.sha256),
                short(&sha),
                short(&last.sha256)
            ));
        }
        let earlier = &rules[..rules.len() - 1];
        if c.amendments.len() != earlier.len() {
            problems.push(format!(
                "{id}: {} earlier rule(s) registered, {} amendment(s) stated; each earlier rule \
                 needs its amendment, in order",
                earlier.len(),
                c.amendments.len()
            ));
        }
        for (a, r) in c.amendments.iter().zip(earlier) {
            if a.from.len() < 8 || !r.sha256.starts_with(&a.from) {
                problems.push(format!(
                    "{id}: the amendment \"{}\" names {}, the earlier rule registered is {}",
                    a.reason,
                    a.from,
                    short(&r.sha256)
                ));
            }
            if a.reason.trim().is_empty() {
                problems.push(format!("{id}: an amendment without a reason"));
            }
        }
        problems
    }

    /// Registers the definitions' claims (`claims`) on `day` at `commit`: a new claim with
    /// its rule, an amended rule after the earlier ones; then fills in, for each rule
    /// without them, the verdicts of the committed outcomes decided under it (`full` and
    /// `reduced`: an outcome's claim records the hash of its rule; an outcome without hashes
    /// was decided under the last rule registered before it). Returns what it did, a line
    /// each.
    ///
    /// # Errors
    ///
    /// A changed rule without an amendment naming the last registered one, naming the
    /// claim.
    pub fn update(
        &mut self,
        claims: &[(String, Vec<ClaimSpec>)],
        (day, commit): (&str, &str),
        full: &[Outcome],
        reduced: &[Outcome],
    ) -> Result<Vec<String>> {
        let mut done = Vec::new();
        for (validation, specs) in claims {
            for c in specs {
                let id = claim_id(validation, &c.key);
                let sha = c.rule_sha256();
                let rules = self.claims.entry(id.clone()).or_default();
                // The verdicts under the rule registered so far, before a new one is added.
                fill(rules, validation, &c.key, full, reduced);
                match rules.last() {
                    Some(last) if last.sha256 == sha => continue,
                    Some(last) => {
                        let amended = c.amendments.len() == rules.len()
                            && c.amendments.last().is_some_and(|a| {
                                a.from.len() >= 8 && last.sha256.starts_with(&a.from)
                            });
                        if !amended {
                            return Err(Error::invalid(
                                &format!("claims.{}.amendments", c.key),
                                format!("{} amendment(s)", c.amendments.len()),
                                format!(
                                    "the rule of {id} changed after it was registered: an \
                                     amendment {{ from = \"{}\", reason = \"...\" }} last",
                                    short(&last.sha256)
                                ),
                            ));
                        }
                        done.push(format!("{id}: amended ({})", short(&sha)));
                    }
                    None => done.push(format!("{id}: registered ({})", short(&sha))),
                }
                rules.push(Registered {
                    sha256: sha,
                    rule: c.decisive(),
                    registered: day.to_string(),
                    commit: commit.to_string(),
                    full: None,
                    reduced: None,
                });
                fill(rules, validation, &c.key, full, reduced);
            }
        }
        Ok(done)
    }
}

/// Fills in the verdicts of the outcomes' claim `key` of `validation` for the rules
/// decided under: the rule whose hash the outcome's claim records, or, where it records
/// none (an outcome written before the register), the last rule registered.
fn fill(
    rules: &mut [Registered],
    validation: &str,
    key: &str,
    full: &[Outcome],
    reduced: &[Outcome],
) {
    let of = |outcomes: &[Outcome]| {
        outcomes
            .iter()
            .find(|o| o.name == validation)?
            .claims
            .iter()
            .find(|c| c.key == key)
            .cloned()
    };
    for (outcome, reduced_scale) in [(of(full), false), (of(reduced), true)] {
        let Some(o) = outcome else { continue };
        let target = match &o.rule_sha256 {
            Some(sha) => rules.iter_mut().find(|r| &r.sha256 == sha),
            None => rules.last_mut(),
        };
        let Some(r) = target else { continue };
        let slot = if reduced_scale {
            &mut r.reduced
        } else {
            &mut r.full
        };
        if slot.is_none() {
            *slot = Some(Verdicted {
                result: o.result,
                measured: o.measured,
            });
        }
    }
}

fn short(sha: &str) -> &str {
    &sha[..sha.len().min(12)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::claims::{Amendment, Phrase, Rule, Unit};

    fn claim(rule: Rule) -> ClaimSpec {
        toml::from_str::<ClaimSpec>(
            r#"
key = "k"
statement = "s"
place = "tex 1"
paper = "~0"
phrase = "negligible"
unit = "ratio"
value = 0.0
measure = "headline"
rule = { within = [-0.05, 0.05] }
"#,
        )
        .map(|c| ClaimSpec { rule, ..c })
        .unwrap()
    }

    fn specs(c: &ClaimSpec) -> Vec<(String, Vec<ClaimSpec>)> {
        vec![("v".to_string(), vec![c.clone()])]
    }

    #[test]
    fn a_changed_rule_needs_an_amendment_and_keeps_the_earlier_one() {
        let mut register = Register::default();
        let first = claim(Rule::Within((-0.05, 0.05)));
        assert_eq!(first.phrase, Phrase::Negligible);
        assert_eq!(first.unit, Unit::Ratio);
        let done = register
            .update(&specs(&first), ("2026-12-04", "abc"), &[], &[])
            .unwrap();
        assert_eq!(done.len(), 1);
        assert!(register.problems(&specs(&first)).is_empty());
        // Widened without an amendment: the suite's check fails, the register refuses.
        let mut wider = claim(Rule::Within((-0.1, 0.1)));
        let problems = register.problems(&specs(&wider));
        assert!(
            problems.iter().any(|p| p.contains("rule changed")),
            "{problems:?}"
        );
        let e = register
            .clone()
            .update(&specs(&wider), ("2026-12-05", "def"), &[], &[])
            .unwrap_err()
            .to_string();
        assert!(e.contains("claims.k.amendments"), "{e}");
        // With its amendment: registered after the first, which stays.
        wider.amendments = vec![Amendment {
            from: first.rule_sha256()[..12].to_string(),
            reason: "a reason".into(),
        }];
        register
            .update(&specs(&wider), ("2026-12-05", "def"), &[], &[])
            .unwrap();
        assert_eq!(register.rules("v.k").len(), 2);
        assert!(register.problems(&specs(&wider)).is_empty());
        // An amendment that names another rule, or a claim deleted, is a problem.
        let mut wrong = wider.clone();
        wrong.amendments[0].from = "0123456789ab".into();
        assert!(!register.problems(&specs(&wrong)).is_empty());
        assert!(!register.problems(&[]).is_empty());
    }

    #[test]
    fn the_hash_is_the_rule_as_it_decides() {
        let a = claim(Rule::Within((-0.05, 0.05)));
        let mut b = a.clone();
        b.statement = "another wording of the statement".into();
        b.place = "tex 2".into();
        assert_eq!(a.rule_sha256(), b.rule_sha256());
        b.reading = Some("another reading".into());
        assert_ne!(a.rule_sha256(), b.rule_sha256());
        let c = claim(Rule::Within((-0.05, 0.06)));
        assert_ne!(a.rule_sha256(), c.rule_sha256());
    }
}
