//! Markdown and number formatting for the scorecard.

use std::borrow::Borrow;
use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};

/// Escapes text for Markdown (table cells and paragraphs): characters that start emphasis,
/// strike-through, code, links or HTML, and the table's `|`. Newlines become spaces.
pub fn md(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            '\\' | '`' | '*' | '_' | '~' | '|' | '<' | '>' | '[' | ']' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' => out.push(' '),
            _ => out.push(c),
        }
    }
    out
}

/// Text an outcome carries (its account, notes, checks, the names of its statistics),
/// escaped as [`md`], with any NaN in it said in words ([`no_nan`]).
pub fn prose(text: &str) -> String {
    md(&no_nan(text))
}

/// `text` with every NaN said in words: `x +- NaN` (or `x ± NaN`) as `x (no error bar)`,
/// any other `NaN` as `n/a`. Outcome text formatted by earlier versions prints a missing
/// error bar (one realization) as NaN.
pub fn no_nan(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(k) = rest.find("NaN") {
        let (before, after) = (&rest[..k], &rest[k + 3..]);
        rest = after;
        let word =
            !before.ends_with(char::is_alphanumeric) && !after.starts_with(char::is_alphanumeric);
        if !word {
            out.push_str(before);
            out.push_str("NaN");
        } else if let Some(value) = before
            .strip_suffix("+- ")
            .or_else(|| before.strip_suffix("± "))
        {
            out.push_str(value.trim_end());
            out.push_str(" (no error bar)");
        } else {
            out.push_str(before);
            out.push_str("n/a");
        }
    }
    out.push_str(rest);
    out
}

/// A Markdown table from a header and rows (cells already escaped).
pub fn table<S: Borrow<str>>(header: &[S], rows: &[Vec<String>]) -> String {
    let mut s = format!("| {} |\n", header.join(" | "));
    s.push_str(&format!("|{}\n", "---|".repeat(header.len())));
    for row in rows {
        s.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    s
}

/// A Markdown table and the blank line after it, appended to `s`.
pub fn push_table<S: Borrow<str>>(s: &mut String, header: &[S], rows: &[Vec<String>]) {
    s.push_str(&table(header, rows));
    s.push('\n');
}

/// A Markdown table of one row per item, `row(item)`, under `header`, appended to `s`
/// with the blank line after it.
pub fn push_rows<T>(s: &mut String, header: &[&str], items: &[T], row: impl Fn(&T) -> Vec<String>) {
    let rows: Vec<Vec<String>> = items.iter().map(row).collect();
    push_table(s, header, &rows);
}

/// A cell of a value that may be absent: `shown(value)`, or an em dash.
pub fn or_dash<T>(value: Option<T>, shown: impl FnOnce(T) -> String) -> String {
    value.map_or_else(|| "—".into(), shown)
}

/// The cell of a run that failed: `**failed**: why`.
pub fn failed(why: &str) -> String {
    format!("**failed**: {}", md(why))
}

/// A number to four significant digits (exponent form below 1e-3 and from 1e5), "n/a"
/// for NaN.
pub fn num(x: f64) -> String {
    sig(x, 4)
}

/// A number to `digits` significant digits ([`crate::plot::significant`]), "n/a" for NaN.
pub fn sig(x: f64, digits: usize) -> String {
    if x.is_nan() {
        return "n/a".into();
    }
    crate::plot::significant(x, digits)
}

/// `value ± error`, the error to two significant digits and the value to the same decimal
/// place; the value alone, marked, when there is no error estimate.
pub fn pm(value: f64, error: f64) -> String {
    if !value.is_finite() {
        return num(value);
    }
    if !error.is_finite() {
        return format!("{} (no error estimate)", num(value));
    }
    if error == 0.0 {
        return format!("{} ± 0", num(value));
    }
    let e_exp = error.abs().log10().floor() as i32;
    let decimals = 1 - e_exp;
    if !(0..=6).contains(&decimals) || value.abs() >= 1e5 {
        return format!("{} ± {}", sig(value, 4), sig(error, 2));
    }
    let d = decimals as usize;
    format!("{value:.d$} ± {error:.d$}")
}

/// A duration in seconds: `0.42 s`, `22.5 s`, `3 min 05 s`, `2 h 03 min`.
pub fn duration(s: f64) -> String {
    if !s.is_finite() || s < 0.0 {
        return "n/a".into();
    }
    if s < 60.0 {
        return format!("{} s", sig(s, 3));
    }
    let total = s.round() as u64;
    if total < 3600 {
        format!("{} min {:02} s", total / 60, total % 60)
    } else {
        format!("{} h {:02} min", total / 3600, total % 3600 / 60)
    }
}

/// A list of integers as ranges: `[1, 2, 3, 4, 7]` -> `1-4, 7`.
pub fn ranges(values: &[i64]) -> String {
    let mut v = values.to_vec();
    v.sort_unstable();
    v.dedup();
    let mut parts = Vec::new();
    let mut k = 0;
    while k < v.len() {
        let start = v[k];
        while k + 1 < v.len() && v[k + 1] == v[k] + 1 {
            k += 1;
        }
        parts.push(if v[k] == start {
            start.to_string()
        } else {
            format!("{start}-{}", v[k])
        });
        k += 1;
    }
    parts.join(", ")
}

/// `path` lexically resolved against the current directory (`.` and `..` removed).
pub fn absolute(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = PathBuf::new();
    for c in abs.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// A Markdown link target for `target`, relative to the folder `base`, with `/`
/// separators and spaces and parentheses percent-encoded.
pub fn link(base: &Path, target: &Path) -> String {
    let (base, target) = (absolute(base), absolute(target));
    let b: Vec<Component> = base.components().collect();
    let t: Vec<Component> = target.components().collect();
    let common = b.iter().zip(&t).take_while(|(x, y)| x == y).count();
    let mut parts: Vec<String> = vec!["..".to_string(); b.len() - common];
    parts.extend(
        t[common..]
            .iter()
            .map(|c| c.as_os_str().to_string_lossy().to_string()),
    );
    let joined = if parts.is_empty() {
        ".".to_string()
    } else {
        parts.join("/")
    };
    joined
        .replace('%', "%25")
        .replace(' ', "%20")
        .replace('(', "%28")
        .replace(')', "%29")
}

/// `value` as indented JSON (two spaces, as `serde_json::to_string_pretty`), except that an
/// array of numbers, strings, booleans or nulls stands on one line: a scene's 250 seeds
/// take one line, not 250.
pub fn json(value: &serde_json::Value) -> String {
    let mut s = String::new();
    write_json(&mut s, value, 0);
    s
}

fn write_json(s: &mut String, value: &serde_json::Value, indent: usize) {
    use serde_json::Value;
    let flat = |v: &Value| !matches!(v, Value::Array(_) | Value::Object(_));
    match value {
        Value::Object(map) if !map.is_empty() => {
            let members = map.iter().map(|(k, v)| (Some(k.as_str()), v));
            write_block(s, ('{', '}'), members, indent);
        }
        Value::Array(items) if !items.iter().all(flat) => {
            write_block(s, ('[', ']'), items.iter().map(|v| (None, v)), indent);
        }
        Value::Array(items) => {
            let inline: Vec<String> = items.iter().map(Value::to_string).collect();
            let _ = write!(s, "[{}]", inline.join(", "));
        }
        other => s.push_str(&other.to_string()),
    }
}

/// An object's members (with their keys) or an array's items, one a line, between
/// `brackets`.
fn write_block<'a>(
    s: &mut String,
    (open, close): (char, char),
    members: impl ExactSizeIterator<Item = (Option<&'a str>, &'a serde_json::Value)>,
    indent: usize,
) {
    let count = members.len();
    let _ = writeln!(s, "{open}");
    for (i, (key, v)) in members.enumerate() {
        s.extend(std::iter::repeat_n(' ', indent + 2));
        if let Some(key) = key {
            let _ = write!(s, "{}: ", serde_json::Value::from(key));
        }
        write_json(s, v, indent + 2);
        s.push_str(if i + 1 < count { ",\n" } else { "\n" });
    }
    s.extend(std::iter::repeat_n(' ', indent));
    s.push(close);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_honest() {
        assert_eq!(num(2.2211127811008033), "2.221");
        assert_eq!(num(9.980083908407236e-9), "9.98e-9");
        assert_eq!(num(f64::NAN), "n/a");
        assert_eq!(num(1234567.0), "1.235e6");
        assert_eq!(pm(2.2211127811008033, 0.04666613918698152), "2.221 ± 0.047");
        assert_eq!(pm(0.5, f64::NAN), "0.5 (no error estimate)");
        assert_eq!(pm(12.0, 3.4), "12.0 ± 3.4");
        assert_eq!(pm(1.0e-6, 2.0e-8), "1e-6 ± 2e-8");
        assert_eq!(duration(22.49), "22.5 s");
        assert_eq!(duration(185.0), "3 min 05 s");
        assert_eq!(duration(7390.0), "2 h 03 min");
        assert_eq!(ranges(&[4, 1, 2, 3, 7, 9, 10]), "1-4, 7, 9-10");
    }

    #[test]
    fn nan_in_outcome_text_is_said_in_words() {
        assert_eq!(
            no_nan("D = 1.63 +- NaN times Persson's (z = NaN); 0.5 ± NaN."),
            "D = 1.63 (no error bar) times Persson's (z = n/a); 0.5 (no error bar)."
        );
        assert_eq!(no_nan("NaN"), "n/a");
        assert_eq!(
            no_nan("NaNs and aNaN stay; 1 +- 0.1"),
            "NaNs and aNaN stay; 1 +- 0.1"
        );
        assert_eq!(prose("a_r = NaN"), "a\\_r = n/a");
    }

    #[test]
    fn json_puts_lists_of_scalars_on_one_line_and_reads_back() {
        let v = serde_json::json!({
            "seeds": [1, 2, 3],
            "empty": [],
            "name": "a \"b\"",
            "rows": [{"x": 0.5, "ok": true}, [null]],
            "none": {}
        });
        let text = json(&v);
        assert_eq!(
            text,
            "{\n  \"empty\": [],\n  \"name\": \"a \\\"b\\\"\",\n  \"none\": {},\n  \"rows\": [\n    {\n      \"ok\": true,\n      \"x\": 0.5\n    },\n    [null]\n  ],\n  \"seeds\": [1, 2, 3]\n}"
        );
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), v);
    }

    #[test]
    fn markdown_is_escaped() {
        assert_eq!(md("a_r | p~0 *E*"), "a\\_r \\| p\\~0 \\*E\\*");
        assert_eq!(md("two\nlines"), "two lines");
    }

    #[test]
    fn links_are_relative_to_the_scorecard() {
        let base = Path::new("/w/out");
        assert_eq!(link(base, Path::new("/w/out/a/b.png")), "a/b.png");
        assert_eq!(
            link(Path::new("/w/report"), Path::new("/w/out/a b.png")),
            "../out/a%20b.png"
        );
        assert_eq!(link(base, Path::new("/w/out/./x/../c.csv")), "c.csv");
    }
}
