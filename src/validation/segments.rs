//! The wall time of a job that ran in segments: killed and resumed from its checkpoints.
//!
//! A resumed job has spent, besides its last run, the time of each earlier run up to that
//! run's last checkpoint (the work after it was lost and is done again). The runner keeps
//! the sum in the job's state folder, beside the checkpoints, as [`FILE`]:
//!
//! ```text
//! earlier_s(k+1) = earlier_s(k) + max(0, t_checkpoint(k) - t_start(k))
//! ```
//!
//! where `t_start(k)` is when segment `k` started and `t_checkpoint(k)` the modification
//! time of the newest file it left in the folder. The stored result then reports
//! `wall_s = earlier_s + the last segment's time` ([`super::store::JobRun`]), the time its
//! result took rather than that of its last segment alone.
//!
//! Checkpoints copied to another folder or machine take new modification times; a
//! checkpoint left by a version without this record counts from 0. Both only affect the
//! time reported, never a result.

use std::path::Path;
use std::time::SystemTime;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::provenance::epoch_seconds;

/// The record's file name in a job's state folder (no checkpoint uses it).
pub const FILE: &str = "segments.json";

/// What the state folder keeps between segments.
#[derive(Debug, Serialize, Deserialize)]
struct Record {
    /// Wall time of the segments before the current one, each up to its last checkpoint.
    earlier_s: f64,
    /// When the current segment started, seconds since the Unix epoch.
    started: f64,
}

/// The newest modification time of the files under `dir` other than [`FILE`], seconds
/// since the Unix epoch; `None` if there is none.
fn newest_file(dir: &Path) -> Option<f64> {
    let mut newest: Option<f64> = None;
    for entry in std::fs::read_dir(dir).ok()?.flatten() {
        let path = entry.path();
        let t = if path.is_dir() {
            newest_file(&path)
        } else if entry.file_name() == FILE {
            None
        } else {
            entry.metadata().ok()?.modified().ok().map(epoch_seconds)
        };
        newest = match (newest, t) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
    }
    newest
}

/// Starts a segment of the job whose state folder is `dir`, at `now`: returns the wall
/// time of its earlier segments up to their last checkpoints (0 for a job with no record),
/// and records the start of this one.
pub fn start(dir: &Path, now: SystemTime) -> Result<f64> {
    let path = dir.join(FILE);
    let earlier_s = std::fs::read(&path)
        .ok()
        .and_then(|b| serde_json::from_slice::<Record>(&b).ok())
        .map_or(0.0, |r| {
            let last = newest_file(dir).map_or(0.0, |t| (t - r.started).max(0.0));
            r.earlier_s + last
        });
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let record = Record {
        earlier_s,
        started: epoch_seconds(now),
    };
    let bytes = serde_json::to_vec(&record).expect("segment records serialise");
    crate::io::write_atomic(&path, &bytes)?;
    Ok(earlier_s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, UNIX_EPOCH};

    /// A file under `dir` last modified at `t`.
    fn touch(dir: &Path, name: &str, t: SystemTime) {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        let f = std::fs::File::create(&path).unwrap();
        f.set_modified(t).unwrap();
    }

    #[test]
    fn earlier_segments_count_up_to_their_last_checkpoint() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("job.checkpoint");
        let t0 = UNIX_EPOCH + Duration::from_secs(1_800_000_000);
        let at = |s: u64| t0 + Duration::from_secs(s);
        // A fresh job: nothing earlier.
        assert_eq!(start(&dir, at(0)).unwrap(), 0.0);
        // Checkpoints at 2 s and 5 s, killed, resumed at 10 s: 5 s before.
        touch(&dir, "checkpoint.json", at(2));
        touch(&dir, "pressure.1.npy", at(5));
        assert_eq!(start(&dir, at(10)).unwrap(), 5.0);
        // A checkpoint at 13 s (in a subfolder), resumed at 20 s: 5 + 3.
        touch(&dir, "variant/checkpoint.json", at(13));
        assert_eq!(start(&dir, at(20)).unwrap(), 8.0);
        // Killed before any new checkpoint: the files are older than the segment's start.
        assert_eq!(start(&dir, at(30)).unwrap(), 8.0);
    }

    #[test]
    fn checkpoints_without_a_record_count_from_zero() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("job.checkpoint");
        let t0 = UNIX_EPOCH + Duration::from_secs(1_800_000_000);
        touch(&dir, "checkpoint.json", t0);
        assert_eq!(start(&dir, t0 + Duration::from_secs(60)).unwrap(), 0.0);
        // The record is written, and read by the next segment.
        assert!(dir.join(FILE).exists());
        touch(&dir, "checkpoint.json", t0 + Duration::from_secs(70));
        assert_eq!(start(&dir, t0 + Duration::from_secs(80)).unwrap(), 10.0);
    }
}
