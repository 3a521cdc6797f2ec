//! Where a report's numbers were made: git commit, date, machine.

use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// The report header: which code, when, on what.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    /// `git rev-parse --short=12 HEAD`, with `+dirty` when tracked files differ from it;
    /// `unknown` outside a checkout.
    pub commit: String,
    /// `YYYY-MM-DD HH:MM UTC`.
    pub date_utc: String,
    /// Logical cores the process may use.
    pub cores: usize,
    /// CPU model (from `/proc/cpuinfo`), OS and architecture.
    pub machine: String,
}

impl Provenance {
    /// Reads the commit from the git checkout around the current directory, the clock and
    /// the machine. Never fails: what cannot be read is `unknown`.
    pub fn detect() -> Self {
        let git = |args: &[&str]| {
            Command::new("git")
                .args(args)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        };
        let commit = match git(&["rev-parse", "--short=12", "HEAD"]) {
            Some(hash) => {
                let dirty = git(&["status", "--porcelain", "--untracked-files=no"])
                    .is_some_and(|s| !s.is_empty());
                if dirty { format!("{hash}+dirty") } else { hash }
            }
            None => "unknown".to_owned(),
        };
        let secs = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.trim().to_owned())
            })
            .unwrap_or_else(|| "unknown CPU".to_owned());
        Self {
            commit,
            date_utc: utc_date(secs),
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            machine: format!("{cpu}, {}/{}", std::env::consts::OS, std::env::consts::ARCH),
        }
    }

    /// A fixed header (tests, doc examples): the given commit, the Unix epoch, one core.
    pub fn fixed(commit: &str) -> Self {
        Self {
            commit: commit.to_owned(),
            date_utc: utc_date(0),
            cores: 1,
            machine: "test machine".to_owned(),
        }
    }
}

/// `YYYY-MM-DD HH:MM UTC` of Unix time `secs`.
fn utc_date(secs: u64) -> String {
    let t = UNIX_EPOCH + std::time::Duration::from_secs(secs);
    // RFC 3339 `YYYY-MM-DDTHH:MM:SSZ`: the date, then hours and minutes.
    let stamp = humantime::format_rfc3339_seconds(t).to_string();
    format!("{} {} UTC", &stamp[..10], &stamp[11..16])
}

#[cfg(test)]
mod tests {
    use super::utc_date;

    #[test]
    fn dates_match_known_instants() {
        assert_eq!(utc_date(0), "1970-01-01 00:00 UTC");
        // 2000-02-29 12:34:56 UTC (a leap day in a century leap year).
        assert_eq!(utc_date(951_827_696), "2000-02-29 12:34 UTC");
        // 2026-11-21 20:04:28 UTC.
        assert_eq!(utc_date(1_795_291_468), "2026-11-21 20:04 UTC");
    }
}
