//! Job results on disk: `<out>/jobs/<family>/<scale>/<key>.json`, each written atomically
//! as soon as its job finishes, and the job's checkpoint folder beside it
//! (`<key>.checkpoint/`).
//!
//! The key is a short hash of everything that determines a job's result (scale, scene and
//! job), so validations whose scenes are equal share their jobs (assumptions (a) and (b)
//! run the same transitions), and a changed scene never reuses an old result. A job that
//! is another scene's (a reference surface's sweep, another scene of the paper) is keyed
//! as that scene's own job ([`crate::experiments::Jobs::shared_job`]), so it is shared too.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::definition::Scale;
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};

/// The jobs folder of a family at a scale.
pub fn jobs_dir(out: &Path, family: &str, scale: Scale) -> PathBuf {
    out.join("jobs").join(family).join(scale.to_string())
}

/// A short hash of everything that determines a job's result: the scale, the scene, the
/// solver and the job.
pub fn job_key(scale: Scale, scene: &serde_json::Value, solver: SolverKind, job: &str) -> String {
    let mut h = Sha256::new();
    h.update(scale.to_string().as_bytes());
    h.update(scene.to_string().as_bytes());
    h.update(solver.name().as_bytes());
    h.update(job.as_bytes());
    h.finalize()
        .iter()
        .take(8)
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// A job's result as stored on disk.
#[derive(Serialize, Deserialize)]
pub struct Stored<J, R> {
    /// The solver that ran it.
    pub solver: SolverKind,
    /// The job.
    pub job: J,
    /// Its result.
    pub result: R,
    /// Where, when and by which code it ran (absent in results of older versions).
    #[serde(default)]
    pub run: Option<JobRun>,
}

/// The provenance of one stored job result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobRun {
    /// Host name of the machine.
    pub host: String,
    /// Start of the job's last segment (its only one, unless it resumed), RFC 3339 UTC.
    pub start: String,
    /// End, RFC 3339 UTC.
    pub end: String,
    /// Start and end, seconds since the Unix epoch (for spans across shards).
    pub span: (f64, f64),
    /// Wall time of the job, seconds: of every segment of a job resumed from checkpoints
    /// (each earlier one up to its last checkpoint, [`super::segments`]), so more than
    /// `span` then covers.
    pub wall_s: f64,
    /// The part of `wall_s` spent by earlier, interrupted runs of the job; absent for a job
    /// that ran in one go (and in results of older versions, whose `wall_s` is that of the
    /// last segment alone).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub earlier_s: Option<f64>,
    /// The commit of the code (see [`crate::provenance::commit_label`]).
    pub commit: String,
    /// The validation whose run computed it.
    pub definition: String,
    /// The SHA-256 of that validation's definition file.
    pub definition_sha256: String,
    /// The share of a sharded run (`K/N`), if it was one.
    pub shard: Option<String>,
}

/// The provenance part of a stored result, read without knowing the job's types.
#[derive(Deserialize)]
pub struct StoredRun {
    /// The solver that ran it.
    pub solver: SolverKind,
    /// The provenance.
    #[serde(default)]
    pub run: Option<JobRun>,
}

/// The provenance of a stored result at `path`: `None` when there is no readable result
/// (missing, or a damaged file, which is recomputed).
pub fn load_run(path: &Path) -> Option<StoredRun> {
    let bytes = std::fs::read(path).ok()?;
    serde_json::from_slice(&bytes).ok()
}

/// A stored result, if present and readable (a damaged file is recomputed).
pub fn load<J: DeserializeOwned, R: DeserializeOwned>(path: &Path) -> Option<Stored<J, R>> {
    let bytes = std::fs::read(path).ok()?;
    serde_json::from_slice(&bytes).ok()
}

/// Stores a job's result atomically.
pub fn store<J: Serialize, R: Serialize>(path: &Path, stored: &Stored<J, R>) -> Result<()> {
    let bytes = serde_json::to_vec(stored).expect("results serialise");
    crate::io::write_atomic(path, &bytes)
}

/// Removes a job's state folder (its checkpoints), if there is one.
pub fn remove_state(dir: &Path) -> Result<()> {
    match std::fs::remove_dir_all(dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::io(dir, e)),
        _ => Ok(()),
    }
}

/// Job files written by this process: reused without `--resume`, since they hold this
/// run's own results (a job shared by two validations runs once).
static WRITTEN: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// Whether this process wrote `path`.
pub fn written_here(path: &Path) -> bool {
    WRITTEN
        .lock()
        .expect("no panics while holding the lock")
        .as_ref()
        .is_some_and(|set| set.contains(path))
}

/// Notes that this process wrote `path`.
pub fn mark_written(path: PathBuf) {
    WRITTEN
        .lock()
        .expect("no panics while holding the lock")
        .get_or_insert_with(HashSet::new)
        .insert(path);
}
