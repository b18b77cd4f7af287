//! Sharded runs: shares of the jobs run by separate processes at the same time over one
//! output folder, then `--merge`, give the outcomes of one process running everything;
//! a merge with a job missing writes nothing and names it; a definition edited outside
//! what a job computes keeps its result valid, an edited scene parameter makes it run
//! again; a share
//! killed mid-job and started again continues; bad share specs are refused.
//!
//! Scenes: the reduced re-entry history of the resume tests (64^2, three realizations,
//! checkpoints every 0.1 s) and the reduced contact-area ensemble, with CG.

#![cfg(unix)]

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

use crate::common::{
    definitions_with_reentry, finish, kill_when, outcome_numbers, table_without_wall,
};

/// The reduced re-entry scene (as in the resume tests).
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

/// The validations of these tests.
const NAMES: [&str; 2] = ["c_reentry", "contact_area"];

/// `persson-check --threads 1 validate NAMES --solver cg --dir DEFS --out OUT EXTRA...`:
/// one thread, as the shares that run at once.
fn validate(defs: &Path, out: &Path, names: &[&str], extra: &[&str]) -> Command {
    validate_on(1, defs, out, names, extra)
}

/// As [`validate`], in a pool of `threads`.
fn validate_on(threads: usize, defs: &Path, out: &Path, names: &[&str], extra: &[&str]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_persson-check"));
    cmd.args(["--threads", &threads.to_string(), "validate"])
        .args(names)
        .args(["--solver", "cg", "--dir"])
        .arg(defs)
        .arg("--out")
        .arg(out)
        .args(extra)
        // A test run under a scheduler must not see its variables.
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SLURM_ARRAY_TASK_MIN")
        .env_remove("SLURM_ARRAY_TASK_COUNT")
        .env_remove("JOB_COMPLETION_INDEX");
    cmd
}

/// Runs `cmd`, expecting failure; returns its stderr.
fn fails(mut cmd: Command) -> String {
    let output = cmd.output().unwrap();
    assert!(!output.status.success(), "{cmd:?} succeeded");
    String::from_utf8_lossy(&output.stderr).to_string()
}

/// Every file under `dir`, relative to it, except job results and checkpoints.
fn outputs(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, dir: &Path, files: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries {
            let path = e.unwrap().path();
            let rel = path.strip_prefix(root).unwrap().to_path_buf();
            if rel.starts_with("jobs") {
                continue;
            }
            if path.is_dir() {
                walk(root, &path, files);
            } else {
                files.push(rel);
            }
        }
    }
    let mut files = Vec::new();
    walk(dir, dir, &mut files);
    files.sort();
    files
}

/// The unsharded run of both validations (two threads).
struct Reference {
    defs: tempfile::TempDir,
    out: tempfile::TempDir,
}

fn reference() -> &'static Reference {
    static REFERENCE: OnceLock<Reference> = OnceLock::new();
    REFERENCE.get_or_init(|| {
        let defs = definitions_with_reentry(SCENE, &["contact_area"]);
        let out = tempfile::tempdir().unwrap();
        // On two threads: outcomes do not depend on the pool's size, the shares' runs on
        // one thread are compared with it, and the tests waiting for it leave no core idle.
        finish(validate_on(2, defs.path(), out.path(), &NAMES, &[]));
        Reference { defs, out }
    })
}

/// The merged outcomes, tables and figures equal the unsharded run's, apart from wall
/// times and provenance.
fn assert_same_as_unsharded(out: &Path, names: &[&str]) {
    let r = reference().out.path();
    for name in names {
        assert_eq!(
            outcome_numbers(out, name),
            outcome_numbers(r, name),
            "{name}: the merged outcome differs from the unsharded run"
        );
        assert_eq!(
            table_without_wall(out, name),
            table_without_wall(r, name),
            "{name}.csv"
        );
    }
    for f in ["reentry_map.png", "flux_map.png"] {
        let (a, b) = (
            std::fs::read(out.join("c_reentry").join(f)).unwrap(),
            std::fs::read(r.join("c_reentry").join(f)).unwrap(),
        );
        assert!(a == b, "{f} differs");
    }
}

/// The merge's provenance of `name`: one record per share.
fn merge_shards(out: &Path, name: &str) -> Vec<serde_json::Value> {
    let bytes = std::fs::read(out.join(format!("{name}.json"))).unwrap();
    let v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
    v["merge"]["shards"]
        .as_array()
        .expect("merge provenance")
        .clone()
}

#[test]
fn three_shares_at_once_merge_to_the_unsharded_outcomes() {
    let defs = reference().defs.path();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    let children: Vec<_> = (1..=3)
        .map(|k| {
            validate(defs, out, &NAMES, &["--shard", &format!("{k}/3")])
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for child in children {
        let output = child.wait_with_output().unwrap();
        assert!(
            output.status.success(),
            "a share failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    assert!(outputs(out).is_empty(), "shares wrote {:?}", outputs(out));
    finish(validate(defs, out, &NAMES, &["--merge"]));
    assert_same_as_unsharded(out, &NAMES);
    let mut shares: Vec<String> = NAMES
        .iter()
        .flat_map(|n| merge_shards(out, n))
        .map(|s| {
            for key in ["host", "start", "end", "jobs", "commit"] {
                assert!(!s[key].is_null(), "share record without {key}: {s}");
            }
            s["shard"].as_str().unwrap().to_string()
        })
        .collect();
    shares.sort();
    shares.dedup();
    assert_eq!(shares, ["1/3", "2/3", "3/3"]);
}

#[test]
fn a_merge_with_a_job_missing_names_it_and_writes_nothing() {
    let defs = reference().defs.path();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    let names = ["c_reentry"];
    // Three histories over three shares: one each. Share 3 never runs.
    for k in 1..=2 {
        finish(validate(defs, out, &names, &["--shard", &format!("{k}/3")]));
    }
    let plan = Command::new(env!("CARGO_BIN_EXE_persson-check"))
        .args(["validate", "c_reentry", "--solver", "cg", "--dir"])
        .arg(defs)
        .args(["--plan", "--shards", "3"])
        .output()
        .unwrap();
    let plan: serde_json::Value = serde_json::from_slice(&plan.stdout).unwrap();
    let missing = plan["jobs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["shard"] == 3)
        .expect("share 3 owns a job");
    let key = missing["key"].as_str().unwrap();
    let err = fails(validate(defs, out, &names, &["--merge"]));
    assert!(err.contains(key), "the missing job is not named: {err}");
    assert!(err.contains("shard 3/3"), "its share is not named: {err}");
    assert!(outputs(out).is_empty(), "wrote {:?}", outputs(out));

    // The last share runs, and the original merges.
    finish(validate(defs, out, &names, &["--shard", "3/3"]));
    finish(validate(defs, out, &names, &["--merge"]));
    assert_same_as_unsharded(out, &names);

    // Edited after the shares ran outside what the jobs compute (a comment, the paper's
    // finding, the other scale's scene): the job keys stand, and the results merge into
    // the same outcome.
    let text = std::fs::read_to_string(defs.join("c_reentry.toml")).unwrap();
    let edited = text
        .replacen(
            "[paper]\n",
            "[paper]\n# the finding as the paper words it\n",
            1,
        )
        .replacen("finding = \"", "finding = \"(edited) ", 1)
        .replacen("[full]\n", "[full]\n# a comment in the other scale\n", 1)
        .replacen("checkpoint_seconds = 60", "checkpoint_seconds = 90", 1);
    assert_ne!(edited, text);
    let changed = tempfile::tempdir().unwrap();
    std::fs::write(
        changed.path().join("c_reentry.toml"),
        format!("# edited after the shares ran\n{edited}"),
    )
    .unwrap();
    let merged = tempfile::tempdir().unwrap();
    copy_dir(&out.join("jobs"), &merged.path().join("jobs"));
    finish(validate(
        changed.path(),
        merged.path(),
        &names,
        &["--merge"],
    ));
    // The finding's text and the definition's hash are the edit itself.
    let numbers = |dir: &Path| {
        let mut v = outcome_numbers(dir, "c_reentry");
        let o = v.as_object_mut().unwrap();
        o.remove("paper");
        o.remove("definition_sha256");
        v
    };
    assert_eq!(
        numbers(merged.path()),
        numbers(out),
        "an edit outside the jobs changed the merged outcome"
    );

    // A parameter of the scene the jobs ran changes their keys: they have no result.
    let retuned = tempfile::tempdir().unwrap();
    let with_tol = edited.replacen("tol = 1e-8", "tol = 1e-9", 1);
    assert_ne!(with_tol, edited);
    std::fs::write(retuned.path().join("c_reentry.toml"), with_tol).unwrap();
    let err = fails(validate(
        retuned.path(),
        merged.path(),
        &names,
        &["--merge"],
    ));
    assert!(err.contains("3 of 3 jobs have no result"), "{err}");
}

/// Copies a folder tree.
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

#[test]
fn a_share_killed_mid_job_continues_and_merges_the_same() {
    let defs = reference().defs.path();
    let out = tempfile::tempdir().unwrap();
    let out = out.path();
    let names = ["c_reentry"];
    let jobs = out.join("jobs/reentry/reduced");
    let checkpointed = || {
        std::fs::read_dir(&jobs).is_ok_and(|mut d| {
            d.any(|e| {
                let p = e.unwrap().path();
                p.extension().is_some_and(|x| x == "checkpoint")
                    && std::fs::read_dir(&p).is_ok_and(|mut c| c.next().is_some())
            })
        })
    };
    kill_when(
        validate(defs, out, &names, &["--shard", "1/2"]),
        "a checkpoint",
        checkpointed,
    );
    finish(validate(defs, out, &names, &["--shard", "2/2"]));
    finish(validate(defs, out, &names, &["--shard", "1/2"]));
    finish(validate(defs, out, &names, &["--merge"]));
    assert_same_as_unsharded(out, &names);
}

#[test]
fn bad_share_specs_are_refused_and_write_nothing() {
    let defs = reference().defs.path();
    let parent = tempfile::tempdir().unwrap();
    let out = parent.path().join("out");
    for spec in ["0/3", "4/3", "3/0", "a/b", "auto"] {
        let err = fails(validate(defs, &out, &["c_reentry"], &["--shard", spec]));
        assert!(err.contains("--shard"), "{spec}: {err}");
        assert!(!out.exists(), "{spec} wrote {}", out.display());
    }
    let err = fails(validate(defs, &out, &["c_reentry"], &["--shard", "auto"]));
    for var in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"] {
        assert!(err.contains(var), "auto does not name {var}: {err}");
    }
}

/// A variant (H = 0.3 on a smaller grid) for [`SCENE`]: an optional part of the scene.
const H03_VARIANT: &str = "[[reduced.variants]]
name = \"h03\"
what = \"H = 0.3\"
n = 32
hurst = 0.3
lambda_l = 16
lambda_s = 2
seeds = [1]
contact_areas = [0.14]
tol = 1e-8

";

#[test]
fn a_partial_merge_leaves_out_a_variant_whose_jobs_are_not_all_in() {
    let defs = definitions_with_reentry(&format!("{SCENE}{H03_VARIANT}"), &[]);
    let defs = defs.path();
    let names = ["c_reentry"];
    let all = tempfile::tempdir().unwrap();
    finish(validate_on(2, defs, all.path(), &names, &[]));

    // The plan names the variant's job as a part of the scene; its result goes missing.
    let plan = Command::new(env!("CARGO_BIN_EXE_persson-check"))
        .args(["validate", "c_reentry", "--solver", "cg", "--dir"])
        .arg(defs)
        .arg("--plan")
        .output()
        .unwrap();
    let plan: serde_json::Value = serde_json::from_slice(&plan.stdout).unwrap();
    let jobs = plan["jobs"].as_array().unwrap();
    let key = |part: Option<&str>| {
        jobs.iter()
            .find(|j| j["part"].as_str() == part)
            .map(|j| j["key"].as_str().unwrap().to_string())
            .unwrap()
    };
    let (variant, headline) = (key(Some("h03")), key(None));
    let out = tempfile::tempdir().unwrap();
    copy_dir(&all.path().join("jobs"), &out.path().join("jobs"));
    let result = |k: &str| out.path().join(format!("jobs/reentry/reduced/{k}.json"));
    std::fs::remove_file(result(&variant)).unwrap();

    // A plain merge refuses; a partial one concludes without the variant and says so.
    let err = fails(validate(defs, out.path(), &names, &["--merge"]));
    assert!(err.contains(&variant), "{err}");
    finish(validate(
        defs,
        out.path(),
        &names,
        &["--merge", "--partial"],
    ));
    let read = |dir: &Path| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(dir.join("c_reentry.json")).unwrap()).unwrap()
    };
    let (partial, whole) = (read(out.path()), read(all.path()));
    let pending = &partial["merge"]["pending"];
    assert_eq!(pending.as_array().unwrap().len(), 1, "{pending}");
    assert_eq!(pending[0]["name"], "h03");
    assert_eq!(
        (pending[0]["jobs"].as_u64(), pending[0]["done"].as_u64()),
        (Some(1), Some(0))
    );
    assert!(pending[0]["core_hours_left"].as_f64().unwrap() > 0.0);
    let measures: Vec<&str> = pending[0]["measures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    // Its share (over another range than the headline's, so no shift from it), and the
    // variants' study, which only it fills.
    assert_eq!(measures, ["detail:h03_share_ar0.14", "study:variants"]);
    assert!(partial["scene"]["variants"]
        .as_array()
        .is_none_or(|v| v.is_empty()));
    assert_eq!(whole["scene"]["variants"].as_array().map(Vec::len), Some(1));
    // Every other statistic is the complete run's.
    let details = |o: &serde_json::Value| -> Vec<serde_json::Value> {
        o["details"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|d| !d["key"].as_str().unwrap().starts_with("h03_"))
            .cloned()
            .collect()
    };
    assert_eq!(details(&partial), details(&whole));
    assert!(details(&whole).len() < whole["details"].as_array().unwrap().len());
    assert_eq!(partial["value"], whole["value"]);
    assert_eq!(
        partial["golden"]["share_0.14"],
        whole["golden"]["share_0.14"]
    );

    // A job of the scene proper has no part: without it nothing merges.
    std::fs::remove_file(result(&headline)).unwrap();
    let err = fails(validate(
        defs,
        out.path(),
        &names,
        &["--merge", "--partial"],
    ));
    assert!(err.contains(&headline), "{err}");
}

/// Each definition with one planned realization added wherever its scene takes
/// `more_seeds` (the headline's `[full]`, each `[[full.variants]]`, `[full.waterfall]`),
/// or the definition as it is where `[full]` refuses them.
fn with_planned_realization(text: &str) -> String {
    let mut out = String::new();
    let mut section = String::new();
    for line in text.lines() {
        out.push_str(line);
        out.push('\n');
        if line.starts_with('[') {
            section = line.trim().to_string();
        }
        let headline = section == "[full]" || section == "[[full.variants]]";
        if (headline && line.starts_with("seeds = ["))
            || (section == "[full.waterfall]" && line.starts_with("seed = "))
        {
            out.push_str("more_seeds = [1001]\n");
        }
    }
    out
}

#[test]
fn planned_realizations_keep_every_stored_key_and_add_only_planned_jobs() {
    let plan = |dir: &Path| -> Vec<serde_json::Value> {
        let out = Command::new(env!("CARGO_BIN_EXE_persson-check"))
            .args(["validate", "--full", "--plan", "--dir"])
            .arg(dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let plan: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        plan["jobs"].as_array().unwrap().clone()
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("validations");
    let planned_dir = tempfile::tempdir().unwrap();
    let mut refused = Vec::new();
    for entry in std::fs::read_dir(&root).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let planned = with_planned_realization(&text);
        let name = path.file_name().unwrap();
        // A scene that takes no planned realizations says so by name, and is planned as
        // it is.
        let one = tempfile::tempdir().unwrap();
        std::fs::write(one.path().join(name), &planned).unwrap();
        let check = Command::new(env!("CARGO_BIN_EXE_persson-check"))
            .args(["validate", "--full", "--plan", "--dir"])
            .arg(one.path())
            .output()
            .unwrap();
        let kept = if check.status.success() {
            planned
        } else {
            let err = String::from_utf8_lossy(&check.stderr).to_string();
            assert!(err.contains("more_seeds"), "{name:?}: {err}");
            refused.push(name.to_owned());
            text
        };
        std::fs::write(planned_dir.path().join(name), kept).unwrap();
    }
    let before = plan(&root);
    let after = plan(planned_dir.path());
    let keys = |jobs: &[serde_json::Value]| -> BTreeSet<String> {
        jobs.iter()
            .map(|j| j["key"].as_str().unwrap().to_string())
            .collect()
    };
    let (old, new) = (keys(&before), keys(&after));
    assert!(old.is_subset(&new), "keys lost: {:?}", old.difference(&new));
    let added: Vec<_> = after
        .iter()
        .filter(|j| !old.contains(j["key"].as_str().unwrap()))
        .collect();
    for j in &added {
        let part = j["part"].as_str().unwrap_or("");
        assert!(part.ends_with("planned"), "an unplanned new job: {j}");
    }
    // Every definition that takes them planned a job of its own for them.
    let planning: BTreeSet<&str> = added
        .iter()
        .map(|j| j["validation"].as_str().unwrap())
        .collect();
    assert!(
        planning.len() + refused.len() >= 9,
        "{planning:?}, refused {refused:?}"
    );
}
