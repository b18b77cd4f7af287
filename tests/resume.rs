//! Interrupted runs: a validation killed with SIGKILL at an arbitrary instant resumes
//! (`--resume`) to exactly the numbers of an uninterrupted run, re-running only what is
//! missing, and a checkpoint is never seen half-written.
//!
//! The scene is a reduced re-entry history (64^2, lambda_l = 32, lambda_s = 2: 334 shells a
//! sweep, three realizations at one contact area) that checkpoints every 0.1 s, so that a
//! kill lands mid-sweep. Runs go through the real binary.

#![cfg(unix)]

use std::collections::{BTreeMap, BTreeSet};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::Duration;

use persson_check::io::checkpoint::{Array, Checkpoints};
use serde_json::Value;

use crate::common::{
    definitions_with_reentry, finish, kill_when, outcome_numbers, table_without_wall,
};

/// The reduced re-entry scene of these tests, spliced into the real definition's header.
const SCENE: &str = "[reduced]
n = 64
hurst = 0.8
lambda_l = 32
lambda_s = 2
seeds = [1, 2, 3]
contact_areas = [0.14]
flux_zeta = 12
flux_dzeta = 1
checkpoint_seconds = 0.1
tol = 1e-8

";

/// Seconds added to the `wall_s` of a checkpoint left by a killed run: a job that resumes
/// from it reports at least this wall time, which tells a resumed sweep from a restarted
/// one. Wall times are excluded from every comparison of numbers.
const MARK: f64 = 1e6;

/// A folder holding `c_reentry.toml` with the reduced scene [`SCENE`].
fn definitions() -> tempfile::TempDir {
    definitions_with_reentry(SCENE, &[])
}

/// `persson-check --threads THREADS validate c_reentry --dir DEFS --out OUT [--resume]`.
fn validate(threads: usize, defs: &Path, out: &Path, resume: bool) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_persson-check"));
    cmd.arg("--threads")
        .arg(threads.to_string())
        .args(["validate", "c_reentry", "--solver", "cg", "--dir"])
        .arg(defs)
        .arg("--out")
        .arg(out);
    if resume {
        cmd.arg("--resume");
    }
    cmd
}

/// Where the re-entry family keeps its job results and checkpoints.
fn jobs_dir(out: &Path) -> PathBuf {
    out.join("jobs/reentry/reduced")
}

/// Stored job results: file name -> (bytes, inode).
fn job_files(out: &Path) -> BTreeMap<String, (Vec<u8>, u64)> {
    let Ok(entries) = std::fs::read_dir(jobs_dir(out)) else {
        return BTreeMap::new();
    };
    entries
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            (
                name,
                (std::fs::read(&p).unwrap(), p.metadata().unwrap().ino()),
            )
        })
        .collect()
}

/// Checkpoint folders of the jobs (one per unfinished sweep).
fn checkpoint_dirs(out: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(jobs_dir(out)) else {
        return Vec::new();
    };
    entries
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "checkpoint"))
        .collect()
}

/// The checkpoints on disk, as (folder, generation) of every header.
fn generations(out: &Path) -> BTreeSet<(PathBuf, u64)> {
    checkpoint_dirs(out)
        .into_iter()
        .filter_map(|dir| {
            let bytes = std::fs::read(dir.join("checkpoint.json")).ok()?;
            let header: Value = serde_json::from_slice(&bytes).ok()?;
            Some((dir, header["generation"].as_u64()?))
        })
        .collect()
}

/// Checks that every checkpoint a killed run left is whole (its header and every array it
/// names read back, arrays of the grid's size), adds [`MARK`] to its wall time, and returns
/// the job keys of the marked checkpoints.
fn check_and_mark_checkpoints(out: &Path) -> BTreeSet<String> {
    let mut marked = BTreeSet::new();
    for dir in checkpoint_dirs(out) {
        let mut c = Checkpoints::new(&dir);
        let Some(meta) = c.load_meta::<Value>() else {
            // Killed before the first header of this sweep: nothing to resume.
            continue;
        };
        let points = 64 * 64;
        for name in ["pressure", "displacement"] {
            assert_eq!(c.load_f64(name).unwrap().len(), points, "{dir:?}: {name}");
        }
        for name in ["in_contact", "left_after_first"] {
            assert_eq!(c.load_u8(name).unwrap().len(), points, "{dir:?}: {name}");
        }
        for name in ["left", "returned"] {
            assert_eq!(c.load_u16(name).unwrap().len(), points, "{dir:?}: {name}");
        }
        assert!(meta["step"].as_u64().unwrap() > 0, "{meta}");

        // The header's layout ({generation, arrays, meta: {.., wall_s, ..}}) is the
        // checkpoint module's; the mark needs it.
        let path = dir.join("checkpoint.json");
        let mut header: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        let wall = header["meta"]["wall_s"]
            .as_f64()
            .expect("checkpoint header with meta.wall_s");
        header["meta"]["wall_s"] = (wall + MARK).into();
        std::fs::write(&path, serde_json::to_vec(&header).unwrap()).unwrap();
        let key = dir.file_stem().unwrap().to_string_lossy().to_string();
        marked.insert(key);
    }
    marked
}

/// A stored job result.
fn stored_job(out: &Path, key: &str) -> Value {
    let bytes = std::fs::read(jobs_dir(out).join(format!("{key}.json"))).unwrap();
    serde_json::from_slice(&bytes).unwrap()
}

/// The per-point history, as the contact maps drawn from it.
fn maps(out: &Path) -> Vec<Vec<u8>> {
    ["reentry_map.png", "flux_map.png"]
        .iter()
        .map(|f| std::fs::read(out.join("c_reentry").join(f)).unwrap())
        .collect()
}

/// The uninterrupted run that every interrupted one must reproduce.
struct Reference {
    _defs: tempfile::TempDir,
    out: tempfile::TempDir,
}

fn reference() -> &'static Reference {
    static REFERENCE: OnceLock<Reference> = OnceLock::new();
    REFERENCE.get_or_init(|| {
        let defs = definitions();
        let out = tempfile::tempdir().unwrap();
        finish(validate(2, defs.path(), out.path(), false));
        Reference { _defs: defs, out }
    })
}

/// Statistic, error bar, golden values, details, checks, table and maps equal the
/// uninterrupted run's, exactly.
fn assert_same_as_reference(out: &Path) {
    let r = reference().out.path();
    let (got, want) = (
        outcome_numbers(out, "c_reentry"),
        outcome_numbers(r, "c_reentry"),
    );
    for key in [
        "value",
        "std_error",
        "golden",
        "details",
        "checks",
        "verdict",
    ] {
        assert_eq!(
            got[key], want[key],
            "{key} differs from the uninterrupted run"
        );
    }
    assert_eq!(got, want, "the outcome differs from the uninterrupted run");
    assert_eq!(
        table_without_wall(out, "c_reentry"),
        table_without_wall(r, "c_reentry"),
        "c_reentry.csv"
    );
    assert!(maps(out) == maps(r), "the contact maps differ");
}

#[test]
fn sweeps_killed_mid_sweep_resume_to_the_same_numbers() {
    let defs = definitions();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    let mut marked = BTreeSet::new();
    // Killed twice, each time once this run has written a checkpoint of its own: the
    // second run resumes from the first one's checkpoints.
    for round in 0..2 {
        let before = generations(out);
        kill_when(
            validate(2, defs.path(), out, round > 0),
            "a new checkpoint",
            || !generations(out).is_subset(&before),
        );
        assert!(
            !out.join("c_reentry.json").exists(),
            "killed before the end"
        );
        marked.extend(check_and_mark_checkpoints(out));
    }
    assert!(!marked.is_empty(), "no checkpoint to resume from");
    finish(validate(2, defs.path(), out, true));

    assert_same_as_reference(out);
    for key in &marked {
        // Continued from the checkpoint, not restarted.
        let stored = stored_job(out, key);
        let wall = stored["result"]["wall_s"].as_f64().unwrap();
        assert!(wall >= MARK, "job {key} restarted its sweep");
        // The provenance's wall time counts the killed runs' segments too (up to their
        // last checkpoints), beyond the span of the last one.
        let run = &stored["run"];
        let earlier = run["earlier_s"]
            .as_f64()
            .expect("earlier segments recorded");
        let span = run["span"][1].as_f64().unwrap() - run["span"][0].as_f64().unwrap();
        assert!(earlier > 0.0, "job {key}: {run}");
        assert!(run["wall_s"].as_f64().unwrap() > span, "job {key}: {run}");
    }
    assert!(
        checkpoint_dirs(out).is_empty(),
        "checkpoints left after the results were stored"
    );
}

#[test]
fn an_ensemble_killed_between_jobs_reruns_only_the_missing_ones() {
    let defs = definitions();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    // One thread: the jobs run one after the other; killed once the first is stored.
    kill_when(
        validate(1, defs.path(), out, false),
        "a finished job",
        || !job_files(out).is_empty(),
    );
    let done = job_files(out);
    assert!(
        !done.is_empty() && done.len() < 3,
        "{} of 3 jobs done",
        done.len()
    );
    assert!(!out.join("c_reentry.json").exists());

    // Resumed on two threads (the statistics do not depend on the thread count).
    finish(validate(2, defs.path(), out, true));
    let after = job_files(out);
    assert_eq!(after.len(), 3, "one result per job");
    for (name, (bytes, inode)) in &done {
        // A job re-run would be stored anew: a new file (every write renames a fresh
        // one over the old) with another wall time.
        let (bytes_after, inode_after) = &after[name];
        assert!(
            bytes_after == bytes && inode_after == inode,
            "finished job {name} was run again"
        );
    }
    assert_same_as_reference(out);
}

#[test]
fn a_fresh_run_ignores_the_checkpoints_of_an_interrupted_one() {
    let defs = definitions();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    kill_when(validate(2, defs.path(), out, false), "a checkpoint", || {
        !generations(out).is_empty()
    });
    let marked = check_and_mark_checkpoints(out);
    assert!(!marked.is_empty(), "no checkpoint to ignore");
    // Without --resume every job starts from scratch.
    finish(validate(2, defs.path(), out, false));
    for key in &marked {
        let stored = stored_job(out, key);
        assert!(
            stored["result"]["wall_s"].as_f64().unwrap() < MARK,
            "job {key} continued a stale checkpoint without --resume"
        );
        // Nor does its wall time count the killed run's segment.
        assert!(stored["run"]["earlier_s"].is_null(), "{}", stored["run"]);
    }
    assert_same_as_reference(out);
}

/// Set in the environment of the checkpoint writer ([`checkpoint_writer`]): its folder.
const WRITER_ENV: &str = "PERSSON_CHECK_TEST_CHECKPOINT_WRITER";

/// Elements of the writer's arrays: large enough (6 MB a generation) that a kill often
/// lands in the middle of a write.
const WRITER_LEN: usize = 1 << 18;

/// Not a test: the child process of [`checkpoints_killed_at_any_instant_stay_whole`]. It
/// continues from the last checkpoint in `$PERSSON_CHECK_TEST_CHECKPOINT_WRITER` and saves
/// generation after generation (meta `k`, every array filled with `k`) until killed.
#[test]
#[ignore = "child process of checkpoints_killed_at_any_instant_stay_whole"]
fn checkpoint_writer() {
    let Some(dir) = std::env::var_os(WRITER_ENV) else {
        return;
    };
    let mut c = Checkpoints::new(Path::new(&dir));
    let mut k = c.load_meta::<u64>().unwrap_or(0);
    loop {
        k += 1;
        let x = vec![k as f64; WRITER_LEN];
        let y = vec![k as u16; WRITER_LEN];
        let z = vec![k as u8; WRITER_LEN];
        c.save(
            &k,
            &[
                ("x", Array::F64(&x)),
                ("y", Array::U16(&y)),
                ("z", Array::U8(&z)),
            ],
        )
        .unwrap();
    }
}

#[test]
fn checkpoints_killed_at_any_instant_stay_whole() {
    let dir = tempfile::tempdir().unwrap();
    let ck = dir.path().join("ck");
    let mut last = 0u64;
    for round in 0..12u64 {
        let mut child = Command::new(std::env::current_exe().unwrap())
            .args([
                "resume::checkpoint_writer",
                "--exact",
                "--ignored",
                "--nocapture",
            ])
            .env(WRITER_ENV, &ck)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        // Kill instants spread over a few writes.
        std::thread::sleep(Duration::from_millis(40 + 37 * (round % 7)));
        child.kill().unwrap();
        child.wait().unwrap();

        let mut c = Checkpoints::new(&ck);
        let Some(k) = c.load_meta::<u64>() else {
            assert_eq!(last, 0, "round {round}: the checkpoint vanished");
            continue;
        };
        assert!(
            k >= last,
            "round {round}: generation went back from {last} to {k}"
        );
        assert_eq!(c.load_f64("x").unwrap(), vec![k as f64; WRITER_LEN]);
        assert_eq!(c.load_u16("y").unwrap(), vec![k as u16; WRITER_LEN]);
        assert_eq!(c.load_u8("z").unwrap(), vec![k as u8; WRITER_LEN]);
        last = k;
    }
    assert!(
        last >= 3,
        "only {last} checkpoints written: the test saw too few writes"
    );
}
