//! Provenance: which code, on which machine, at what time produced a result.
//!
//! The commit and the dirty flag are embedded at build time by `build.rs` (from
//! `git rev-parse HEAD` and `git status --porcelain`; "unknown" when the crate was built
//! without git or outside its repository). The machine is read from `/proc/cpuinfo` and
//! `/etc/os-release` where they exist, with the standard library's view as the fallback.
//! Times are UTC in RFC 3339 form.

use std::time::{SystemTime, UNIX_EPOCH};

use serde::{Deserialize, Serialize};

/// The git commit this binary was built from (40 hex digits), or "unknown".
pub const COMMIT: &str = env!("PERSSON_CHECK_COMMIT");

/// Whether the working tree had changes to tracked files at build time: "yes", "no" or
/// "unknown".
pub const DIRTY: &str = env!("PERSSON_CHECK_DIRTY");

/// The crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The build's commit in words: the hash, marked when the tree had local changes.
pub fn commit_label() -> String {
    match DIRTY {
        "yes" => format!("{COMMIT} (with uncommitted changes)"),
        "no" => COMMIT.to_string(),
        _ => format!("{COMMIT} (working-tree state unknown)"),
    }
}

/// The machine a computation ran on.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Machine {
    /// CPU model (e.g. from `/proc/cpuinfo`), or the architecture when unknown.
    pub cpu: String,
    /// Logical CPUs of the machine.
    pub logical_cpus: usize,
    /// CPUs this process may use (affinity and quotas).
    pub available_cpus: usize,
    /// Operating system (distribution and kernel where known).
    pub os: String,
}

impl Machine {
    /// The machine this process runs on.
    pub fn detect() -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let available = std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1);
        let (cpu, logical) = parse_cpuinfo(&cpuinfo);
        let cpu = cpu.unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let logical = if logical == 0 { available } else { logical };
        let distro = std::fs::read_to_string("/etc/os-release")
            .ok()
            .and_then(|t| os_release_name(&t));
        let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease")
            .ok()
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty());
        let mut os = distro.unwrap_or_else(|| std::env::consts::OS.to_string());
        if let Some(k) = kernel {
            os.push_str(&format!(", kernel {k}"));
        }
        os.push_str(&format!(", {}", std::env::consts::ARCH));
        Self {
            cpu,
            logical_cpus: logical,
            available_cpus: available,
            os,
        }
    }

    /// One line: `CPU model, N logical CPUs (M available), OS`.
    pub fn summary(&self) -> String {
        let avail = if self.available_cpus != self.logical_cpus {
            format!(" ({} available to the process)", self.available_cpus)
        } else {
            String::new()
        };
        format!(
            "{}, {} logical CPUs{avail}, {}",
            self.cpu, self.logical_cpus, self.os
        )
    }
}

/// The CPU model and the number of logical CPUs listed in `/proc/cpuinfo` text.
fn parse_cpuinfo(text: &str) -> (Option<String>, usize) {
    let mut model = None;
    let mut count = 0;
    for line in text.lines() {
        let Some((key, value)) = line.split_once(':') else {
            continue;
        };
        let (key, value) = (key.trim(), value.trim());
        if key == "processor" {
            count += 1;
        }
        // x86 names the model "model name"; some ARM kernels name it "Hardware" or
        // "Model".
        if model.is_none()
            && ["model name", "Hardware", "Model"].contains(&key)
            && !value.is_empty()
        {
            model = Some(value.split_whitespace().collect::<Vec<_>>().join(" "));
        }
    }
    (model, count)
}

/// `PRETTY_NAME` (or `NAME`) from `/etc/os-release` text.
fn os_release_name(text: &str) -> Option<String> {
    let get = |key: &str| {
        text.lines().find_map(|l| {
            let (k, v) = l.split_once('=')?;
            (k.trim() == key).then(|| v.trim().trim_matches('"').to_string())
        })
    };
    get("PRETTY_NAME")
        .or_else(|| get("NAME"))
        .filter(|s| !s.is_empty())
}

/// `t` as an RFC 3339 UTC timestamp, to the second (`2024-02-29T13:05:09Z`).
pub fn rfc3339_utc(t: SystemTime) -> String {
    let secs = match t.duration_since(UNIX_EPOCH) {
        Ok(d) => d.as_secs() as i64,
        Err(e) => -(e.duration().as_secs_f64().ceil() as i64),
    };
    let days = secs.div_euclid(86_400);
    let rem = secs.rem_euclid(86_400);
    let (y, m, d) = civil_from_days(days);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// `t` in seconds since the Unix epoch (0 before it).
pub fn epoch_seconds(t: SystemTime) -> f64 {
    t.duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

/// The current time, RFC 3339 UTC.
pub fn now_utc() -> String {
    rfc3339_utc(SystemTime::now())
}

/// The proleptic Gregorian date `(year, month, day)` of the day `days` after 1970-01-01.
///
/// Counts in 400-year eras of 146097 days, with years starting on 1 March so that the leap
/// day ends a year.
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    // Days from 0000-03-01 to 1970-01-01.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let day_of_era = z.rem_euclid(146_097); // [0, 146096]
    let year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_from_march = (5 * day_of_year + 2) / 153; // [0, 11]
    let day = (day_of_year - (153 * month_from_march + 2) / 5 + 1) as u32;
    let month = if month_from_march < 10 {
        month_from_march + 3
    } else {
        month_from_march - 9
    } as u32;
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn at(secs: i64) -> String {
        let t = if secs >= 0 {
            UNIX_EPOCH + Duration::from_secs(secs as u64)
        } else {
            UNIX_EPOCH - Duration::from_secs((-secs) as u64)
        };
        rfc3339_utc(t)
    }

    #[test]
    fn timestamps_match_known_dates() {
        assert_eq!(at(0), "1970-01-01T00:00:00Z");
        assert_eq!(at(-1), "1969-12-31T23:59:59Z");
        // Leap days of a year divisible by 400 and by 4, and a century that is not leap.
        assert_eq!(at(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(at(1_709_211_909), "2024-02-29T13:05:09Z");
        assert_eq!(at(4_107_456_000), "2100-02-28T00:00:00Z");
        assert_eq!(at(4_107_542_400), "2100-03-01T00:00:00Z");
        assert_eq!(at(1_735_689_599), "2024-12-31T23:59:59Z");
    }

    #[test]
    fn days_round_trip_over_centuries() {
        // Consecutive days advance the date by exactly one calendar day.
        let mut prev = civil_from_days(-800_000);
        for days in -799_999..800_000 {
            let (y, m, d) = civil_from_days(days);
            let (py, pm, pd) = prev;
            let next_ok = (y == py && m == pm && d == pd + 1)
                || (y == py && m == pm + 1 && d == 1)
                || (y == py + 1 && m == 1 && d == 1 && pm == 12 && pd == 31);
            assert!(next_ok, "{prev:?} -> {:?}", (y, m, d));
            prev = (y, m, d);
        }
    }

    #[test]
    fn cpuinfo_and_os_release_are_parsed() {
        let cpu = "processor\t: 0\nmodel name\t: AMD EPYC  7763 64-Core Processor\n\n\
                   processor\t: 1\nmodel name\t: AMD EPYC  7763 64-Core Processor\n";
        assert_eq!(
            parse_cpuinfo(cpu),
            (Some("AMD EPYC 7763 64-Core Processor".to_string()), 2)
        );
        assert_eq!(parse_cpuinfo(""), (None, 0));
        let os = "NAME=\"Ubuntu\"\nPRETTY_NAME=\"Ubuntu 24.04 LTS\"\n";
        assert_eq!(os_release_name(os).as_deref(), Some("Ubuntu 24.04 LTS"));
        let m = Machine::detect();
        assert!(m.logical_cpus >= 1 && m.available_cpus >= 1 && !m.cpu.is_empty());
        assert!(m.summary().contains("logical CPUs"));
    }

    #[test]
    fn commit_is_a_hash_or_unknown() {
        assert!(
            COMMIT == "unknown"
                || (COMMIT.len() == 40 && COMMIT.chars().all(|c| c.is_ascii_hexdigit())),
            "{COMMIT}"
        );
        assert!(["yes", "no", "unknown"].contains(&DIRTY), "{DIRTY}");
    }
}
