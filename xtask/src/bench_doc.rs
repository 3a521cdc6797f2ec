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

/// The wall-time targets: workload, target (ns), the figure of the unoptimised build
/// (`docs/benchmarks.md` at `daae243`, a 2-core Intel Xeon VM; the MLP and CNN figures there are
/// the `cycle_contact/mlp` and `cycle_tap/policy` stages).
const TARGETS: [(&str, f64, f64); 3] = [
    ("kernel/contact_mlp", 2_000.0, 19_320.0),
    ("kernel/contact_cnn", 3_000.0, 10_550.0),
    ("cycle_full_hand/full", 15_000.0, 35_870.0),
];

/// The targets against this run.
fn target_rows(measurements: &[Measurement]) -> String {
    let mut out = String::from(
        "| workload | target | committed at daae243 (Intel Xeon) | this run | met |\n\
         |---|---:|---:|---:|---|\n",
    );
    for (id, target, before) in TARGETS {
        let now = measurements.iter().find(|m| m.id == id).map(|m| m.mean_ns);
        let _ = writeln!(
            out,
            "| {id} | ≤ {} | {} | {} | {} |",
            human(target),
            human(before),
            now.map_or_else(|| "not run".to_string(), human),
            match now {
                Some(n) if n <= target => "yes",
                Some(_) => "**no**",
                None => "—",
            }
        );
    }
    out
}

/// Where `cargo xtask bench --bless` keeps the instruction counts (and each kernel's arithmetic).
pub const INSTRUCTIONS: &str = "benches/baselines/instructions.tsv";
/// The calibration workload: multiply-adds at the core's best, in portable code.
const FMA_LOOP: &str = "kernel/fma_loop";

/// One line of [`INSTRUCTIONS`]: id, instructions per call, multiply-adds per call (kernels).
fn instruction_lines(tsv: &str) -> Vec<(&str, f64, Option<f64>)> {
    tsv.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .filter_map(|l| {
            let mut c = l.split('\t');
            let id = c.next()?;
            let instructions = c.next()?.trim().parse().ok()?;
            let mul_adds = c.next().and_then(|v| v.trim().parse().ok());
            Some((id, instructions, mul_adds))
        })
        .collect()
}

/// Every workload's wall time beside its instructions per call and, for kernels, the roofline:
/// its multiply-adds timed at the rate of the FMA loop measured in the same run.
fn instruction_rows(measurements: &[Measurement], tsv: &str) -> String {
    let lines = instruction_lines(tsv);
    let wall = |id: &str| measurements.iter().find(|m| m.id == id).map(|m| m.mean_ns);
    let ns_per_mul_add = lines
        .iter()
        .find(|l| l.0 == FMA_LOOP)
        .and_then(|l| Some(wall(FMA_LOOP)? / l.2?));
    let mut out = String::from(
        "| workload | wall (mean) | instructions / call | multiply-adds / call | instructions / multiply-add | floor: its multiply-adds at the FMA loop's rate | wall / floor |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for (id, instructions, mul_adds) in lines {
        let floor = mul_adds.zip(ns_per_mul_add).map(|(m, r)| m * r);
        let dash = || "—".to_string();
        let _ = writeln!(
            out,
            "| {id} | {} | {instructions:.0} | {} | {} | {} | {} |",
            wall(id).map_or_else(dash, human),
            mul_adds.map_or_else(dash, |m| format!("{m:.0}")),
            mul_adds.map_or_else(dash, |m| format!("{:.2}", instructions / m)),
            floor.map_or_else(dash, human),
            wall(id)
                .zip(floor)
                .map_or_else(dash, |(w, f)| format!("{:.1} ×", w / f)),
        );
    }
    out
}

/// The whole document; `instructions` is [`INSTRUCTIONS`]' text when there is one.
pub fn document(
    command: &str,
    machine: &Machine,
    measurements: &[Measurement],
    instructions: Option<&str>,
) -> String {
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
    if TARGETS
        .iter()
        .any(|t| measurements.iter().any(|m| m.id == t.0))
    {
        let _ = writeln!(
            s,
            "## Targets\n\n\
             Per call of the contact MLP (features, network and catalogue decode), of the paper \
             CNN (standardise, conv, dense head, softmax) and of the full-hand cycle, in this \
             run; beside them the figures of the unoptimised build (`daae243`), measured on \
             another machine.\n\n{}",
            target_rows(measurements)
        );
    }
    if let Some(tsv) = instructions {
        let _ = writeln!(
            s,
            "## Instructions and the compute floor (`cargo xtask bench --check`)\n\n\
             Instructions per call are callgrind's counts of the same calls in the `test` \
             profile (opt-level 2 with overflow checks: the build `cargo xtask test` gates on, \
             `{INSTRUCTIONS}`), so they run a little above a release build's. For the compute \
             kernels the useful arithmetic is counted (a dense layer `I → O` is `I · O` \
             multiply-adds) and timed at the rate of `{FMA_LOOP}` — 32 independent multiply-add \
             chains on data in registers, portable code — measured in this same run: the \
             floor is what those multiply-adds cost at that rate, and wall / floor says how far \
             a kernel is from it. The stages without a count (decode: the simulated chips \
             answering the real drivers; encode; estimate: filters and windows) move data \
             rather than compute. Why the two nets sit where they do: the contact MLP's \
             arithmetic is small (3.4 k multiply-adds) beside its fixed costs — one `exp` per \
             catalogue contact in the decode, the input checks and standardisation, a 9-wide \
             first layer whose rows are too short to vectorise well — so it stays several \
             times above its floor; the CNN skips the zeros of its ReLU inputs and runs its \
             dense kernel on 8 AVX lanes where the CPU has them (the floor is portable \
             4-lane code, so it can sit at or under 1 ×), and is then bound by streaming its \
             184 KB of dense-layer weights from L2 each call.\n\n{}",
            instruction_rows(measurements, tsv)
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
    fn instruction_rows_time_each_kernel_at_the_fma_loops_rate() {
        let tsv = "# header\nkernel/fma_loop\t1404.0\t4096\t0\nkernel/net\t20000.0\t8192\t68\ncycle_x/decode\t500.0\t\t\n";
        let ms = [m("kernel/fma_loop", 409.6), m("kernel/net", 4_096.0)];
        let rows = instruction_rows(&ms, tsv);
        // 0.1 ns per multiply-add: the net's 8192 take 819.2 ns, its 4.096 µs is 5 × that.
        assert!(
            rows.contains("| kernel/net | 4.10 µs | 20000 | 8192 | 2.44 | 819.2 ns | 5.0 × |"),
            "{rows}"
        );
        assert!(
            rows.contains("| cycle_x/decode | — | 500 | — | — | — | — |"),
            "{rows}"
        );
    }

    #[test]
    fn target_rows_say_met_or_not() {
        let ms = [
            m("kernel/contact_mlp", 1_500.0),
            m("kernel/contact_cnn", 3_500.0),
        ];
        let rows = target_rows(&ms);
        assert!(
            rows.contains("| kernel/contact_mlp | ≤ 2.00 µs | 19.32 µs | 1.50 µs | yes |"),
            "{rows}"
        );
        assert!(
            rows.contains("| kernel/contact_cnn | ≤ 3.00 µs | 10.55 µs | 3.50 µs | **no** |"),
            "{rows}"
        );
        assert!(
            rows.contains("| cycle_full_hand/full | ≤ 15.00 µs | 35.87 µs | not run | — |"),
            "{rows}"
        );
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
