//! `docs/benchmarks.md`: the table `cargo xtask bench … --write` writes from criterion's
//! estimates — the machine and its load, the date and commit, the control cycle of every
//! scene against the 10 ms (100 Hz) loop budget with its stages, and every bench measured.

use crate::bench::{Measurement, human, summary_table};
use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;
use std::time::SystemTime;

/// Where the table goes, below the workspace root.
pub const DOC: &str = "docs/benchmarks.md";
/// The control loop period the cycles are compared with, ns (100 Hz).
pub const BUDGET_NS: f64 = 10_000_000.0;
/// The stages of a cycle bench group, in cycle order (ids `<scene>/<stage>`).
const STAGES: [&str; 6] = ["decode", "estimate", "aot", "mlp", "policy", "encode"];

/// What the run ran on.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// `model name` of /proc/cpuinfo.
    pub cpu: String,
    /// Logical processors.
    pub cores: usize,
    /// 1-minute load average when the run started and ended.
    pub load: (String, String),
    /// UTC date of the run, `YYYY-MM-DD`.
    pub date: String,
    /// `git rev-parse --short HEAD`, `+dirty` with uncommitted changes.
    pub commit: String,
}

impl Machine {
    /// CPU, cores, load and date now (the commit is read at the end).
    pub fn probe() -> Machine {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let cpu = cpuinfo
            .lines()
            .find_map(|l| l.strip_prefix("model name")?.split_once(':').map(|x| x.1))
            .map_or_else(|| "unknown CPU".to_string(), |m| m.trim().to_string());
        let cores = std::thread::available_parallelism().map_or(0, usize::from);
        Machine {
            cpu,
            cores,
            load: (load_average(), String::new()),
            date: utc_date(SystemTime::now()),
            commit: String::new(),
        }
    }

    /// The end-of-run load and the commit measured.
    pub fn finish(mut self, root: &Path) -> Machine {
        self.load.1 = load_average();
        let git = |args: &[&str]| {
            Command::new("git")
                .args(args)
                .current_dir(root)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        };
        let head = git(&["rev-parse", "--short", "HEAD"]).unwrap_or_else(|| "unknown".into());
        let dirty =
            git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
        self.commit = if dirty { format!("{head}+dirty") } else { head };
        self
    }
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

/// `YYYY-MM-DD` (UTC) of `t`.
pub fn utc_date(t: SystemTime) -> String {
    humantime::format_rfc3339_seconds(t).to_string()[..10].to_owned()
}

/// Group prefix of the control-cycle benches (`benches/benches/cycles.rs`).
const CYCLE_GROUP: &str = "cycle_";
/// Function name of a whole cycle within its group.
const FULL: &str = "/full";

/// One scene's cycle and stages, from ids `cycle_<scene>/full` and `cycle_<scene>/<stage>`.
fn scene_rows(measurements: &[Measurement]) -> String {
    let mut out = String::from(
        "| scene | cycle (mean) | 95 % CI | share of the 10 ms budget | stages (mean) | stages summed |\n\
         |---|---:|---:|---:|---|---:|\n",
    );
    let cycles = measurements
        .iter()
        .filter(|m| m.id.starts_with(CYCLE_GROUP) && m.id.ends_with(FULL));
    for cycle in cycles {
        let group = cycle.id.trim_end_matches(FULL);
        let scene = group.trim_start_matches(CYCLE_GROUP);
        let stages: Vec<(&str, &Measurement)> = STAGES
            .iter()
            .filter_map(|&s| {
                let id = format!("{group}/{s}");
                measurements.iter().find(|m| m.id == id).map(|m| (s, m))
            })
            .collect();
        let split = stages
            .iter()
            .map(|(s, m)| format!("{s} {}", human(m.mean_ns)))
            .collect::<Vec<_>>()
            .join(" + ");
        let sum: f64 = stages.iter().map(|(_, m)| m.mean_ns).sum();
        let _ = writeln!(
            out,
            "| {scene} | {} | {} … {} | {:.3} % (1 : {:.0}) | {} | {} |",
            human(cycle.mean_ns),
            human(cycle.ci_ns.0),
            human(cycle.ci_ns.1),
            100.0 * cycle.mean_ns / BUDGET_NS,
            BUDGET_NS / cycle.mean_ns,
            if split.is_empty() {
                "—".into()
            } else {
                split
            },
            if stages.is_empty() {
                "—".into()
            } else {
                human(sum)
            },
        );
    }
    out
}

/// The whole document.
pub fn document(command: &str, machine: &Machine, measurements: &[Measurement]) -> String {
    let mut s = String::from("# Benchmarks\n\n");
    let _ = writeln!(
        s,
        "Written by `{command}` from criterion's estimates of that run (mean per iteration and \
         its 95 % confidence interval); do not edit by hand.\n\n\
         - machine: {} × {} (logical cores) of a shared virtual machine — 1-minute load \
         average {} at the start, {} at the end (the bench itself adds about 1; other tenants of \
         the host do not show in it): compare rows with each other, not with another machine;\n- date: {} (UTC); commit: `{}`.\n",
        machine.cores, machine.cpu, machine.load.0, machine.load.1, machine.date, machine.commit
    );
    if measurements
        .iter()
        .any(|m| m.id.starts_with(CYCLE_GROUP) && m.id.ends_with(FULL))
    {
        let _ = writeln!(
            s,
            "## Control cycles (`benches/`, `cargo xtask bench cycles`)\n\n\
             One full control cycle per scene with in-process simulated devices (no pty, socket \
             or Python): decode (the chip models answering the real drivers, so it includes \
             simulating the device) → estimate → policy → encode; the crate docs of \
             `handstack-benches` say what each stage of each scene runs. A stage benched alone \
             replays the inputs it saw inside the cycle, including the cycles where it had \
             nothing to do, so its mean is its share of an average cycle and the stages add up \
             to about the cycle. The budget is the 10 ms period of a 100 Hz loop; host time \
             only — the sensors' conversion time (simulated, e.g. 2 × 2.28 ms per MS5611 frame \
             at OSR 1024) is on top of it in a real loop.\n\n{}",
            scene_rows(measurements)
        );
    }
    let _ = writeln!(
        s,
        "## Every bench of the run\n\n{}",
        summary_table(measurements)
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::UNIX_EPOCH;

    fn m(id: &str, ns: f64) -> Measurement {
        Measurement {
            id: id.into(),
            mean_ns: ns,
            ci_ns: (ns * 0.9, ns * 1.1),
        }
    }

    #[test]
    fn dates_are_civil_utc() {
        assert_eq!(utc_date(UNIX_EPOCH), "1970-01-01");
        let leap = UNIX_EPOCH + std::time::Duration::from_secs(951_782_400); // 2000-02-29
        assert_eq!(utc_date(leap), "2000-02-29");
        let later = UNIX_EPOCH + std::time::Duration::from_secs(1_795_219_200);
        assert_eq!(utc_date(later), "2026-11-21");
    }

    #[test]
    fn scene_rows_put_each_cycle_against_the_budget_with_its_stages() {
        let ms = [
            m("cycle_grasp/full", 20_000.0),
            m("cycle_grasp/decode", 12_000.0),
            m("cycle_grasp/encode", 1_000.0),
            m("cycle_grasp/estimate", 2_000.0),
            m("cycle_grasp/policy", 4_000.0),
            m("cycle_tap/full", 1_000_000.0),
            m("grasp_cycle/full", 5.0),
        ];
        let rows = scene_rows(&ms);
        assert!(rows.contains(
            "| grasp | 20.00 µs | 18.00 µs … 22.00 µs | 0.200 % (1 : 500) | decode 12.00 µs + \
             estimate 2.00 µs + policy 4.00 µs + encode 1.00 µs | 19.00 µs |"
        ));
        assert!(
            rows.contains("| tap | 1.00 ms | 900.00 µs … 1.10 ms | 10.000 % (1 : 10) | — | — |")
        );
        assert!(
            !rows.contains("5.0 ns"),
            "a bench outside the cycle groups: {rows}"
        );
    }
}
