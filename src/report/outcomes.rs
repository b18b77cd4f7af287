//! Reading `<name>.json` outcomes back, and the scene facts the scorecard shows.
//!
//! JSON has no NaN: serde_json writes a NaN as `null`, and a writer may leave out a number
//! it does not have. An outcome's numbers can legitimately be missing (the error bar of one
//! realization, a detail or a cross-check without one): the outcome's types read each
//! such float that is `null` or absent as NaN ([`crate::validation::Outcome`]), which the
//! scorecard prints as "n/a" or "no error bar"; anything else missing is an error as usual.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use serde_json::Value;

use super::format::ranges;
use crate::error::{Error, Result};
use crate::validation::Outcome;

/// An outcome and where it was read from.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The outcome.
    pub outcome: Outcome,
    /// Its file.
    pub path: PathBuf,
    /// When the file was last written.
    pub modified: Option<SystemTime>,
}

/// Reads every outcome (`<name>.json` with `name`, `statistic` and `verdict` keys) directly
/// in `dir`, sorted by name. Other JSON files are skipped; an outcome that does not parse,
/// or a `.json` file that is not JSON at all (a damaged outcome must not silently drop out
/// of the scorecard), is an error naming the file.
pub fn read_outcomes(dir: &Path) -> Result<Vec<Loaded>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    let mut out = Vec::new();
    for path in paths {
        let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
        let value: Value = serde_json::from_slice(&bytes).map_err(|e| {
            Error::bad_file(
                &path,
                format!("not valid JSON ({e}); re-run the validation or remove the file"),
            )
        })?;
        if !looks_like_outcome(&value) {
            continue;
        }
        let outcome: Outcome =
            serde_json::from_value(value).map_err(|e| Error::bad_file(&path, e.to_string()))?;
        let modified = std::fs::metadata(&path).and_then(|m| m.modified()).ok();
        out.push(Loaded {
            outcome,
            path,
            modified,
        });
    }
    out.sort_by(|a, b| a.outcome.name.cmp(&b.outcome.name));
    Ok(out)
}

/// Reads one outcome file.
pub fn read_outcome(path: &Path) -> Result<Outcome> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let value: Value =
        serde_json::from_slice(&bytes).map_err(|e| Error::bad_file(path, e.to_string()))?;
    serde_json::from_value(value).map_err(|e| Error::bad_file(path, e.to_string()))
}

fn looks_like_outcome(v: &Value) -> bool {
    ["name", "statistic", "verdict"]
        .iter()
        .all(|k| v.get(k).is_some())
}

/// A key's value in the scene: at the top level, or in a table one level down (scenes
/// of other shapes may group their surface parameters).
fn scene_value<'a>(scene: &'a Value, key: &str) -> Option<&'a Value> {
    scene.get(key).or_else(|| {
        scene
            .as_object()?
            .values()
            .filter(|v| v.is_object())
            .find_map(|v| v.get(key))
    })
}

fn integers(v: &Value) -> Option<Vec<i64>> {
    match v {
        Value::Number(n) => n
            .as_i64()
            .or_else(|| n.as_f64().map(|x| x as i64))
            .map(|x| vec![x]),
        Value::Array(items) => items
            .iter()
            .map(|x| x.as_i64().or_else(|| x.as_f64().map(|f| f as i64)))
            .collect(),
        _ => None,
    }
}

/// The grids a scene ran on (`n`, times each of `refinements` if present), e.g.
/// `128, 256`; `None` when the scene names no grid.
pub fn scene_grids(scene: &Value) -> Option<Vec<i64>> {
    let ns = integers(scene_value(scene, "n")?)?;
    let refine = scene_value(scene, "refinements")
        .and_then(integers)
        .unwrap_or_else(|| vec![1]);
    let mut grids: Vec<i64> = ns
        .iter()
        .flat_map(|n| refine.iter().map(move |r| n * r))
        .collect();
    grids.sort_unstable();
    grids.dedup();
    Some(grids)
}

/// The seeds of a scene (`seeds` list or a single `seed`).
pub fn scene_seeds(scene: &Value) -> Option<Vec<i64>> {
    scene_value(scene, "seeds")
        .or_else(|| scene_value(scene, "seed"))
        .and_then(integers)
}

/// The scorecard's grid cell: `128, 256`, or an em dash.
pub fn grid_cell(scene: &Value) -> String {
    scene_grids(scene)
        .map(|g| {
            g.iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_else(|| "—".into())
}

/// The scorecard's seeds cell: `4 (1-4)`, or an em dash.
pub fn seeds_cell(scene: &Value) -> String {
    scene_seeds(scene)
        .map(|s| format!("{} ({})", s.len(), ranges(&s)))
        .unwrap_or_else(|| "—".into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn grids_and_seeds_are_found_defensively() {
        let area = json!({"n": 128, "refinements": [1, 2], "seeds": [1, 2, 3, 4]});
        assert_eq!(grid_cell(&area), "128, 256");
        assert_eq!(seeds_cell(&area), "4 (1-4)");
        let nested = json!({"surface": {"n": 64, "seed": 7}, "zetas": [1, 2]});
        assert_eq!(grid_cell(&nested), "64");
        assert_eq!(seeds_cell(&nested), "1 (7)");
        let none = json!({"hursts": [0.3], "seeds": "all"});
        assert_eq!(grid_cell(&none), "—");
        assert_eq!(seeds_cell(&none), "—");
        assert_eq!(grid_cell(&json!([1, 2])), "—");
    }
}
