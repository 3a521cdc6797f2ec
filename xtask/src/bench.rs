//! `cargo xtask bench`: runs every criterion bench of the workspace (each by name, so
//! criterion's options never reach a library's test harness) and prints one summary table.

use crate::run::{cargo, step};
use crate::test_binaries::{Executable, test_build};
use anyhow::{Context, Result, bail};
use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::SystemTime;

/// One bench target: a package and the name of its `[[bench]]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BenchTarget {
    /// The package that holds it.
    pub package: String,
    /// The bench target's name.
    pub name: String,
}

/// One measured benchmark, as criterion recorded it.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// Criterion's full id, `group/function/parameter`.
    pub id: String,
    /// Mean time per iteration, in nanoseconds.
    pub mean_ns: f64,
    /// The 95 % confidence interval of the mean, in nanoseconds.
    pub ci_ns: (f64, f64),
}

/// `args`: an optional FILTER (bench targets whose name contains it) and `--write` (also write
/// `docs/benchmarks.md` from this run), then `--` and arguments passed to every criterion bench
/// (e.g. `-- --quick`).
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    match args {
        [a] if a == "--check" => return instructions(root, "check"),
        [a] if a == "--bless" => return instructions(root, "bless"),
        _ => {}
    }
    let (ours, passthrough) = match args.iter().position(|a| a == "--") {
        Some(i) => (&args[..i], &args[i + 1..]),
        None => (args, &[][..]),
    };
    let write = ours.iter().any(|a| a == "--write");
    let ours: Vec<&String> = ours.iter().filter(|a| *a != "--write").collect();
    let filter = match ours[..] {
        [] => None,
        [f] => Some(f.as_str()),
        _ => bail!("bench takes at most one FILTER (and --write) before `--`"),
    };
    let machine = write.then(crate::bench_doc::Machine::probe);
    let (target_dir, targets) = bench_targets(root)?;
    let targets: Vec<_> = targets
        .into_iter()
        .filter(|t| filter.is_none_or(|f| t.name.contains(f)))
        .collect();
    if targets.is_empty() {
        println!("bench: no criterion bench targets match");
        return Ok(());
    }
    // File times come from a coarse kernel clock that can lag `now()`: start a second early.
    let started = SystemTime::now() - std::time::Duration::from_secs(1);
    for t in &targets {
        step(
            &format!("bench {}/{}", t.package, t.name),
            cargo(root)
                .args(["bench", "-p", &t.package, "--bench", &t.name, "--"])
                .args(passthrough),
        )?;
    }
    let measurements = collect(&target_dir.join("criterion"), started)?;
    let table = summary_table(&measurements);
    println!("\n{table}");
    let out = target_dir.join("bench-summary.md");
    std::fs::write(&out, &table).with_context(|| format!("writing {}", out.display()))?;
    println!("bench: summary written to {}", out.display());
    crate::fuzzy_peers::write_report(root, &measurements)?;
    if let Some(machine) = machine {
        let command = std::iter::once("cargo xtask bench")
            .chain(args.iter().map(String::as_str))
            .collect::<Vec<_>>()
            .join(" ");
        let tsv = std::fs::read_to_string(root.join(crate::bench_doc::INSTRUCTIONS)).ok();
        let doc = crate::bench_doc::document(
            &command,
            &machine.finish(root),
            &measurements,
            tsv.as_deref(),
        );
        let out = root.join(crate::bench_doc::DOC);
        std::fs::write(&out, doc).with_context(|| format!("writing {}", out.display()))?;
        println!("bench: wrote {}", crate::bench_doc::DOC);
    }
    Ok(())
}

/// `--check` / `--bless`: every workload's instructions per call under callgrind
/// (`benches/tests/instructions.rs`), compared with or written to
/// `benches/baselines/instructions.tsv`. It runs the test binary `cargo xtask test` builds
/// (same profile and features), so in CI it adds the valgrind runs only; valgrind is installed
/// with `apt-get` when missing.
pub fn instructions(root: &Path, mode: &str) -> Result<()> {
    let mut cmd = test_build(root, &[]);
    cmd.args(["--test", INSTRUCTIONS.1]);
    instructions_with(cmd, mode)
}

/// [`instructions`] through `exe`, the test build's `instructions` binary, run directly (no
/// cargo, so no lock on the build directory): what `cargo xtask test` runs beside its tests.
pub fn instructions_of(exe: &Executable, mode: &str) -> Result<()> {
    instructions_with(exe.command(), mode)
}

/// The test build's instruction-count test: its package and name.
pub const INSTRUCTIONS: (&str, &str) = ("handstack-benches", "instructions");

/// Runs `cmd` (the instruction-count test) in `mode`.
fn instructions_with(mut cmd: Command, mode: &str) -> Result<()> {
    crate::firmware::ensure_apt("valgrind", "valgrind", "the instruction-count benchmarks")?;
    step(
        &format!("bench --{mode} (instructions per call, callgrind)"),
        cmd.env("HANDSTACK_INSTRUCTIONS", mode),
    )
}

/// The workspace's target directory and every bench target of its members, from `cargo metadata`.
pub fn bench_targets(root: &Path) -> Result<(PathBuf, Vec<BenchTarget>)> {
    let output = cargo(root)
        .args(["metadata", "--no-deps", "--format-version", "1"])
        .output()?;
    if !output.status.success() {
        bail!(
            "cargo metadata failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let meta: Value = serde_json::from_slice(&output.stdout)?;
    let target_dir = meta["target_directory"]
        .as_str()
        .context("metadata has no target_directory")?;
    let mut targets = Vec::new();
    for package in meta["packages"]
        .as_array()
        .context("metadata has no packages")?
    {
        for target in package["targets"].as_array().into_iter().flatten() {
            let is_bench = target["kind"]
                .as_array()
                .is_some_and(|k| k.iter().any(|k| k == "bench"));
            if is_bench {
                targets.push(BenchTarget {
                    package: package["name"].as_str().unwrap_or_default().to_string(),
                    name: target["name"].as_str().unwrap_or_default().to_string(),
                });
            }
        }
    }
    Ok((PathBuf::from(target_dir), targets))
}

/// Every benchmark criterion wrote below `criterion_dir` since `since`, sorted by id.
pub fn collect(criterion_dir: &Path, since: SystemTime) -> Result<Vec<Measurement>> {
    let mut found = Vec::new();
    let mut stack = vec![criterion_dir.to_path_buf()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries {
            let path = entry?.path();
            if !path.is_dir() {
                continue;
            }
            let estimates = path.join("new").join("estimates.json");
            let fresh = std::fs::metadata(&estimates)
                .and_then(|m| m.modified())
                .is_ok_and(|t| t >= since);
            if fresh {
                found.push(read_measurement(&path.join("new"))?);
            } else if path
                .file_name()
                .is_none_or(|n| n != "new" && n != "base" && n != "report")
            {
                stack.push(path);
            }
        }
    }
    found.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(found)
}

fn read_measurement(new_dir: &Path) -> Result<Measurement> {
    let read = |name: &str| -> Result<Value> {
        let file = new_dir.join(name);
        let text = std::fs::read_to_string(&file)
            .with_context(|| format!("reading {}", file.display()))?;
        serde_json::from_str(&text).with_context(|| format!("parsing {}", file.display()))
    };
    let bench = read("benchmark.json")?;
    let est = read("estimates.json")?;
    let mean = &est["mean"];
    let number = |v: &Value| v.as_f64().context("estimates.json: a number is missing");
    Ok(Measurement {
        id: bench["full_id"]
            .as_str()
            .context("benchmark.json has no full_id")?
            .to_string(),
        mean_ns: number(&mean["point_estimate"])?,
        ci_ns: (
            number(&mean["confidence_interval"]["lower_bound"])?,
            number(&mean["confidence_interval"]["upper_bound"])?,
        ),
    })
}

/// A Markdown table of the measurements, times in readable units.
pub fn summary_table(measurements: &[Measurement]) -> String {
    let mut out = String::from("| benchmark | mean | 95 % CI |\n|---|---:|---:|\n");
    for m in measurements {
        let _ = writeln!(
            out,
            "| {} | {} | {} … {} |",
            m.id,
            human(m.mean_ns),
            human(m.ci_ns.0),
            human(m.ci_ns.1)
        );
    }
    out
}

/// A duration in nanoseconds, in the unit that keeps 3–4 significant digits.
pub fn human(ns: f64) -> String {
    match ns {
        n if n < 1e3 => format!("{n:.1} ns"),
        n if n < 1e6 => format!("{:.2} µs", n / 1e3),
        n if n < 1e9 => format!("{:.2} ms", n / 1e6),
        n => format!("{:.2} s", n / 1e9),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_print_in_a_readable_unit() {
        assert_eq!(human(12.34), "12.3 ns");
        assert_eq!(human(3_456.0), "3.46 µs");
        assert_eq!(human(2.5e6), "2.50 ms");
        assert_eq!(human(7.0e9), "7.00 s");
    }

    #[test]
    fn collect_reads_fresh_criterion_output_and_skips_stale() {
        let dir = std::env::temp_dir().join(format!("handstack-bench-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let stale = dir.join("group/stale/new");
        std::fs::create_dir_all(&stale).unwrap();
        std::fs::write(stale.join("estimates.json"), "{}").unwrap();
        let epoch = SystemTime::UNIX_EPOCH;
        let old = std::fs::File::options()
            .write(true)
            .open(stale.join("estimates.json"))
            .unwrap();
        old.set_modified(epoch + std::time::Duration::from_secs(10))
            .unwrap();
        let since = epoch + std::time::Duration::from_secs(1000);
        let fresh = dir.join("group/fresh/new");
        std::fs::create_dir_all(&fresh).unwrap();
        std::fs::write(fresh.join("benchmark.json"), r#"{"full_id":"group/fresh"}"#).unwrap();
        let est = r#"{"mean":{"point_estimate":1500.0,"confidence_interval":{"lower_bound":1400.0,"upper_bound":1600.0}}}"#;
        std::fs::write(fresh.join("estimates.json"), est).unwrap();
        let found = collect(&dir, since).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(
            found,
            [Measurement {
                id: "group/fresh".into(),
                mean_ns: 1500.0,
                ci_ns: (1400.0, 1600.0)
            }]
        );
        assert!(summary_table(&found).contains("| group/fresh | 1.50 µs | 1.40 µs … 1.60 µs |"));
    }
}
