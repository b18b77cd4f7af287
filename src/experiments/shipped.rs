//! The shipped definitions' scenes (`validations/<name>.toml`) for the experiments' unit
//! tests: read, checked, and refused with an error naming the field.

use std::path::Path;

use serde::de::DeserializeOwned;

use super::{Criteria, Experiment};

/// The reduced scene of a shipped definition (`validations/<name>.toml`), for the unit
/// tests of the experiments.
pub(crate) fn shipped_scenes<S: DeserializeOwned>(name: &str) -> (S, S, Criteria) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validations")
        .join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&path).expect("a shipped definition");
    let mut table: toml::Table = toml::from_str(&text).expect("valid TOML");
    let scene = |t: &mut toml::Table, k: &str| -> S {
        t.remove(k)
            .expect("a scene table")
            .try_into()
            .expect("a valid scene")
    };
    let reduced = scene(&mut table, "reduced");
    let full = scene(&mut table, "full");
    let verdict = table["verdict"].as_table().expect("a verdict table");
    let criteria = Criteria {
        name: name.to_string(),
        significance: verdict["significance"].as_float().expect("significance"),
        resolution: verdict["resolution"].as_float().expect("resolution"),
        paper_value: table["paper"].get("value").and_then(|v| v.as_float()),
        paper: table
            .get("claims")
            .and_then(|c| c.as_array())
            .into_iter()
            .flatten()
            .filter_map(|c| {
                let key = c.get("key")?.as_str()?.to_string();
                Some((key, c.get("value")?.as_float()?))
            })
            .collect(),
    };
    (reduced, full, criteria)
}

/// The shipped scenes of `name`, both checked for experiment `E` (the test fails
/// otherwise): the reduced and the full scene.
pub(crate) fn shipped_valid<E: Experiment>(name: &str) -> (E::Scene, E::Scene) {
    let (reduced, full, _) = shipped_scenes::<E::Scene>(name);
    for (scale, scene) in [("reduced", &reduced), ("full", &full)] {
        E::validate(scene).unwrap_or_else(|e| panic!("{name} [{scale}]: {e}"));
    }
    (reduced, full)
}

/// Asserts that `scene` is refused for experiment `E` with an error that names `field`.
pub(crate) fn assert_refused<E: Experiment>(scene: &E::Scene, field: &str) {
    let e = E::validate(scene)
        .expect_err("an invalid scene")
        .to_string();
    assert!(e.contains(field), "{e}");
}
