//! `cargo xtask fuzz`: coverage-guided fuzzing of `crates/handstack-fuzz`'s targets with
//! libFuzzer through cargo-fuzz (`fuzz/`, its own workspace).
//!
//! - `fuzz --seed`: writes the seed corpora (`fuzz/seeds/TARGET/`) from the fixtures, the
//!   trained models and captures of the simulators.
//! - `fuzz TARGET|--all [--seconds N]`: fuzzes each target N seconds (default 1800), growing
//!   its corpus from the seeds, then minimises that corpus (`cargo fuzz cmin`) and appends the
//!   run's figures (executions, edges, features, corpus, findings) to `fuzz/runs.tsv`, and
//!   rewrites the fuzzing section of `docs/reliability.md` from that file (`fuzz --doc`: only
//!   that). A crash stops the target's run; its input is under `fuzz/artifacts/TARGET/`, and
//!   after the fix it is committed to `fuzz/regressions/TARGET/`, which the replay test
//!   (`cargo xtask test`) runs for good.
//!
//! A corpus is committed as one archive, `fuzz/corpus/TARGET.tar.gz`. A run unpacks it into
//! the work folder `target/fuzz-corpus/TARGET/`, fuzzes and minimises there, and packs the
//! folder back into the archive (deterministically: an unchanged corpus gives the same bytes),
//! all through handstack-fuzz's `fuzz-corpus` binary, so xtask links no archive code. Inputs a
//! run that did not finish left in the work folder, and a loose `fuzz/corpus/TARGET/` folder
//! (what a hand `cargo fuzz run TARGET` grows), join the next run's corpus.
//!
//! It installs cargo-fuzz (crates.io, pinned below) if it is missing and says so. The builds
//! use the workspace's stable toolchain with `RUSTC_BOOTSTRAP=1` for libFuzzer's `-Z`
//! sanitizer flags, not a nightly: dfdx 0.13 (tactile-nets' training) switches on its nightly
//! features when it sees a nightly rustc, and those no longer compile on today's nightly.

use anyhow::{Context, Result, bail};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::msrv::ensure_toolchain;
use crate::run::{cargo, step};

/// The cargo-fuzz release xtask installs.
pub const CARGO_FUZZ_VERSION: &str = "0.13.2";
/// The toolchain the fuzz builds use (see the module docs for why not a nightly).
const TOOLCHAIN: &str = "stable";
/// A run's length when `--seconds` is not given: 30 minutes a target.
pub const DEFAULT_SECONDS: u64 = 1800;
/// Longest input libFuzzer makes: the largest seed (a model file) fits.
const MAX_LEN: usize = 1 << 18;

/// Where each target's corpus is committed: `fuzz/corpus/TARGET.tar.gz`.
pub fn archive(root: &Path, target: &str) -> PathBuf {
    root.join("fuzz/corpus").join(format!("{target}.tar.gz"))
}

/// The folder a run grows and minimises a target's corpus in, `target/fuzz-corpus/TARGET/`:
/// inside the repository, on the file system of `fuzz/`, since `cargo fuzz cmin` minimises into
/// a temporary folder there and renames it over this one.
pub fn work_dir(root: &Path, target: &str) -> PathBuf {
    root.join("target/fuzz-corpus").join(target)
}

/// The targets: `fuzz/fuzz_targets/NAME.rs`.
pub fn targets(root: &Path) -> Result<Vec<String>> {
    let dir = root.join("fuzz/fuzz_targets");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "rs").then(|| p.file_stem()?.to_str().map(str::to_owned))?
        })
        .collect();
    names.sort();
    Ok(names)
}

/// `cargo xtask fuzz ARGS`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    if args == ["--doc"] {
        return write_doc(root);
    }
    if args == ["--seed"] {
        return step(
            "fuzz seeds (fuzz/seeds/)",
            fuzz_bin(root, "fuzz-seeds").arg(root),
        );
    }
    let known = targets(root)?;
    let mut seconds = DEFAULT_SECONDS;
    let mut chosen = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--seconds" => {
                seconds = it
                    .next()
                    .and_then(|s| s.parse().ok())
                    .context("--seconds takes a whole number")?;
            }
            "--all" => chosen.extend(known.iter().cloned()),
            t if known.iter().any(|k| k == t) => chosen.push(t.to_owned()),
            other => bail!(
                "unknown fuzz target or flag `{other}`; targets: {}",
                known.join(", ")
            ),
        }
    }
    if chosen.is_empty() {
        bail!(
            "usage: cargo xtask fuzz --seed | TARGET… | --all [--seconds N]; targets: {}",
            known.join(", ")
        );
    }
    ensure_tools()?;
    // Every chosen target runs; the findings are listed at the end.
    let mut found = Vec::new();
    for t in &chosen {
        if let Err(e) = fuzz_one(root, t, seconds) {
            eprintln!("xtask: {e:#}");
            found.push(t.as_str());
        }
    }
    write_doc(root)?;
    if !found.is_empty() {
        bail!("fuzzing found something in: {}", found.join(", "));
    }
    Ok(())
}

/// The fuzzing section of `docs/reliability.md`, from `fuzz/runs.tsv`: per target, the time
/// fuzzed in all, and its latest run's figures.
pub fn doc_section(runs_tsv: &str) -> String {
    let rows: Vec<Vec<&str>> = runs_tsv
        .lines()
        .skip(1)
        .map(|l| l.split('\t').collect())
        .filter(|r: &Vec<&str>| r.len() >= 9)
        .collect();
    let mut targets: Vec<&str> = rows.iter().map(|r| r[2]).collect();
    targets.sort_unstable();
    targets.dedup();
    let mut out = String::from(
        "| target | fuzzed in all | runs | latest run | its executions | exec/s | edges | features | corpus after cmin | finding |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for t in targets {
        let mine: Vec<&Vec<&str>> = rows.iter().filter(|r| r[2] == t).collect();
        let total: u64 = mine.iter().filter_map(|r| r[3].parse::<u64>().ok()).sum();
        let Some(last) = mine.last() else { continue };
        let secs: f64 = last[3].parse().unwrap_or(0.0);
        let execs: f64 = last[4].parse().unwrap_or(0.0);
        out.push_str(&format!(
            "| `{t}` | {:.1} min | {} | {} at {} ({} s) | {} | {:.0} | {} | {} | {} | {} |\n",
            total as f64 / 60.0,
            mine.len(),
            &last[0][..last[0].len().min(10)],
            last[1],
            last[3],
            last[4],
            if secs > 0.0 { execs / secs } else { 0.0 },
            last[5],
            last[6],
            last[7],
            last[8],
        ));
    }
    out
}

/// Rewrites the fuzzing section of `docs/reliability.md` from `fuzz/runs.tsv`.
fn write_doc(root: &Path) -> Result<()> {
    let runs = std::fs::read_to_string(root.join("fuzz/runs.tsv")).unwrap_or_default();
    let path = root.join("docs/reliability.md");
    let doc = std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
    let (begin, end) = (
        "<!-- fuzz: cargo xtask fuzz writes this from fuzz/runs.tsv -->\n",
        "<!-- /fuzz -->",
    );
    let (Some(a), Some(b)) = (doc.find(begin), doc.find(end)) else {
        bail!("{} has no fuzz markers", path.display());
    };
    let doc = format!("{}{begin}{}{}", &doc[..a], doc_section(&runs), &doc[b..]);
    std::fs::write(&path, doc)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// `rustup run stable cargo …` in `fuzz/` with `RUSTC_BOOTSTRAP=1`, with nothing of the
/// `cargo xtask` process leaking in.
fn fuzz_cargo(root: &Path) -> Command {
    let mut cmd = Command::new("rustup");
    cmd.current_dir(root.join("fuzz"))
        .args(["run", TOOLCHAIN, "cargo"])
        .env("RUSTC_BOOTSTRAP", "1")
        .env_remove("RUSTC")
        .env_remove("RUSTUP_TOOLCHAIN")
        .env_remove("CARGO");
    cmd
}

/// Installs cargo-fuzz where missing.
fn ensure_tools() -> Result<()> {
    ensure_toolchain(TOOLCHAIN)?;
    let has_fuzz = Command::new("cargo")
        .args(["fuzz", "--version"])
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).contains(CARGO_FUZZ_VERSION));
    if !has_fuzz {
        println!(
            "xtask: installing cargo-fuzz {CARGO_FUZZ_VERSION} (crates.io) for cargo xtask fuzz"
        );
        step(
            "cargo install cargo-fuzz",
            Command::new("cargo").args([
                "install",
                "cargo-fuzz",
                "--locked",
                "--version",
                CARGO_FUZZ_VERSION,
            ]),
        )?;
    }
    Ok(())
}

/// What one libFuzzer run printed at its end.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct RunStats {
    /// Inputs executed.
    pub executions: u64,
    /// Edges covered (`cov:`).
    pub edges: u64,
    /// Features (`ft:`).
    pub features: u64,
    /// The corpus size at the end (`corp:`).
    pub corpus: u64,
    /// Whether it stopped on a crash, a leak, a timeout or out of memory.
    pub finding: Option<String>,
}

/// Reads libFuzzer's output: the last status line's counters, `-print_final_stats` and the
/// kind of finding, if any.
pub fn parse_stats(output: &str) -> RunStats {
    let mut s = RunStats::default();
    let number = |line: &str, key: &str| -> Option<u64> {
        let rest = &line[line.find(key)? + key.len()..];
        rest.split_whitespace()
            .next()?
            .split('/')
            .next()?
            .parse()
            .ok()
    };
    for line in output.lines() {
        if line.starts_with('#') {
            s.edges = number(line, "cov:").unwrap_or(s.edges);
            s.features = number(line, "ft:").unwrap_or(s.features);
            s.corpus = number(line, "corp:").unwrap_or(s.corpus);
        }
        if let Some(n) = number(line, "stat::number_of_executed_units:") {
            s.executions = n;
        }
        for kind in [
            "deadly signal",
            "Timeout",
            "out-of-memory",
            "LeakSanitizer",
            "panicked at",
        ] {
            if s.finding.is_none() && line.contains(kind) {
                s.finding = Some(line.trim().to_owned());
            }
        }
    }
    s
}

/// `cargo run` of handstack-fuzz's binary `name` under the `test` profile (built by the tests
/// already), its arguments to follow.
fn fuzz_bin(root: &Path, name: &str) -> Command {
    let mut cmd = cargo(root);
    cmd.args([
        "run",
        "--quiet",
        "--profile",
        "test",
        "-p",
        "handstack-fuzz",
    ])
    .args(["--bin", name, "--"]);
    cmd
}

/// `fuzz-corpus pack|unpack FROM TO` (handstack-fuzz's binary).
fn fuzz_corpus(root: &Path, command: &str, from: &Path, to: &Path) -> Result<()> {
    step(
        &format!("fuzz-corpus {command} {}", from.display()),
        fuzz_bin(root, "fuzz-corpus").arg(command).arg(from).arg(to),
    )
}

/// Copies the files of `from` (if it is a folder) into `into` where `into` has no file of that
/// name (libFuzzer names an input by its bytes' SHA-1), and returns how many it copied.
pub fn fold(from: &Path, into: &Path) -> Result<usize> {
    if !from.is_dir() {
        return Ok(0);
    }
    let mut copied = 0;
    for entry in std::fs::read_dir(from).with_context(|| format!("reading {}", from.display()))? {
        let entry = entry?;
        let to = into.join(entry.file_name());
        if entry.file_type()?.is_file() && !to.exists() {
            std::fs::copy(entry.path(), &to).with_context(|| {
                format!("copying {} to {}", entry.path().display(), to.display())
            })?;
            copied += 1;
        }
    }
    Ok(copied)
}

/// Unpacks `target`'s archive (if it has one yet) into its work folder, with the inputs of an
/// unfinished run's work folder and of a loose `fuzz/corpus/TARGET/` folder joined in; returns
/// the work folder.
fn unpack_corpus(root: &Path, target: &str) -> Result<PathBuf> {
    let (archive, work) = (archive(root, target), work_dir(root, target));
    let fresh = work.with_extension("unpacking");
    if fresh.exists() {
        std::fs::remove_dir_all(&fresh)?;
    }
    if archive.exists() {
        fuzz_corpus(root, "unpack", &archive, &fresh)?;
    } else {
        println!(
            "xtask: {target} has no corpus yet; this run starts {}",
            archive.display()
        );
        std::fs::create_dir_all(&fresh)?;
    }
    let left = fold(&work, &fresh)?;
    if left > 0 {
        println!(
            "xtask: {left} inputs an unfinished run left in {} join the corpus",
            work.display()
        );
    }
    let loose = root.join("fuzz/corpus").join(target);
    let joined = fold(&loose, &fresh)?;
    if joined > 0 {
        println!(
            "xtask: {joined} inputs of the loose folder {} join the corpus, which goes into {} \
             after the run: delete the folder then",
            loose.display(),
            archive.display()
        );
    }
    if work.exists() {
        std::fs::remove_dir_all(&work)?;
    }
    std::fs::rename(&fresh, &work)?;
    Ok(work)
}

fn fuzz_one(root: &Path, target: &str, seconds: u64) -> Result<()> {
    let corpus = unpack_corpus(root, target)?;
    let seeds = root.join("fuzz/seeds").join(target);
    println!("==> fuzz {target} for {seconds} s");
    let mut child = fuzz_cargo(root)
        .args(["fuzz", "run", target])
        .arg(&corpus)
        .arg(&seeds)
        .arg("--")
        .arg(format!("-max_total_time={seconds}"))
        .arg(format!("-max_len={MAX_LEN}"))
        .args(["-print_final_stats=1", "-timeout=10", "-rss_limit_mb=4096"])
        .stderr(Stdio::piped())
        .spawn()
        .context("starting cargo fuzz run")?;
    let mut output = String::new();
    // Fuzzing time from libFuzzer's first line (after any build) to its end: a run that stops
    // on a finding is shorter than asked.
    let mut started = None;
    if let Some(err) = child.stderr.take() {
        for line in BufReader::new(err).lines() {
            let line = line?;
            if started.is_none() && line.starts_with("INFO: Seed:") {
                started = Some(std::time::Instant::now());
            }
            // libFuzzer's status lines come often: show the pulses and the end.
            if !line.contains("\tNEW ") && !line.contains("\tREDUCE ") {
                eprintln!("{line}");
            }
            output.push_str(&line);
            output.push('\n');
        }
    }
    let status = child.wait()?;
    let fuzzed_s = started.map_or(0, |t| t.elapsed().as_secs().min(seconds));
    let stats = parse_stats(&output);
    if stats.finding.is_none() && status.success() {
        step(
            &format!("cargo fuzz cmin {target}"),
            fuzz_cargo(root).args(["fuzz", "cmin", target]).arg(&corpus),
        )?;
    }
    let files = std::fs::read_dir(&corpus)?.count();
    record(root, target, fuzzed_s, &stats, files)?;
    // Packed even after a finding: the corpus grown until then is kept, as it is.
    fuzz_corpus(root, "pack", &corpus, &archive(root, target))?;
    std::fs::remove_dir_all(&corpus)?;
    println!(
        "    {target}: {} executions, {} edges, {} features, corpus {files} after cmin, finding: {}",
        stats.executions,
        stats.edges,
        stats.features,
        stats.finding.as_deref().unwrap_or("none")
    );
    if !status.success() || stats.finding.is_some() {
        bail!(
            "fuzz {target} found something: its input is in {} ({status})",
            root.join("fuzz/artifacts").join(target).display()
        );
    }
    Ok(())
}

/// Appends one run to `fuzz/runs.tsv`: `seconds` is the time it fuzzed.
fn record(root: &Path, target: &str, seconds: u64, s: &RunStats, files: usize) -> Result<()> {
    let path: PathBuf = root.join("fuzz/runs.tsv");
    let new = !path.exists();
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)?;
    if new {
        writeln!(
            f,
            "date\tcommit\ttarget\tseconds\texecutions\tedges\tfeatures\tcorpus_after_cmin\tfinding"
        )?;
    }
    let date = humantime::format_rfc3339_seconds(std::time::SystemTime::now());
    let commit = Command::new("git")
        .current_dir(root)
        .args(["rev-parse", "--short", "HEAD"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_default();
    writeln!(
        f,
        "{date}\t{commit}\t{target}\t{seconds}\t{}\t{}\t{}\t{files}\t{}",
        s.executions,
        s.edges,
        s.features,
        s.finding.as_deref().unwrap_or("none").replace('\t', " ")
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_doc_section_sums_each_targets_runs_and_shows_the_latest() {
        let tsv = "date\tcommit\ttarget\tseconds\texecutions\tedges\tfeatures\tcorpus_after_cmin\tfinding\n\
                   2026-11-26T13:00:00Z\tabc\tcdr\t60\t600\t10\t20\t5\tnone\n\
                   2026-11-26T14:00:00Z\tdef\tcdr\t120\t2400\t12\t25\t6\tnone\n";
        let s = doc_section(tsv);
        assert!(s.contains("| `cdr` | 3.0 min | 2 | 2026-11-26 at def (120 s) | 2400 | 20 | 12 | 25 | 6 | none |"), "{s}");
    }

    #[test]
    fn folding_copies_only_the_inputs_not_there_yet() {
        let tmp = std::env::temp_dir().join(format!("xtask-fold-{}", std::process::id()));
        let (from, into) = (tmp.join("from"), tmp.join("into"));
        std::fs::create_dir_all(&from).unwrap();
        std::fs::create_dir_all(&into).unwrap();
        std::fs::write(from.join("a"), "new").unwrap();
        std::fs::write(from.join("b"), "from").unwrap();
        std::fs::write(into.join("b"), "kept").unwrap();
        assert_eq!(fold(&from, &into).unwrap(), 1);
        assert_eq!(std::fs::read_to_string(into.join("a")).unwrap(), "new");
        assert_eq!(std::fs::read_to_string(into.join("b")).unwrap(), "kept");
        assert_eq!(fold(&tmp.join("missing"), &into).unwrap(), 0);
        std::fs::remove_dir_all(&tmp).unwrap();
    }

    #[test]
    fn reads_libfuzzers_end_of_run() {
        let out = "INFO: Seed: 1\n#2\tINITED cov: 120 ft: 130 corp: 9/2Kb exec/s: 0 rss: 40Mb\n\
                   #4096\tpulse  cov: 351 ft: 902 corp: 77/9Kb lim: 43 exec/s: 2048 rss: 60Mb\n\
                   Done 5000 runs in 2 second(s)\nstat::number_of_executed_units: 5000\n";
        let s = parse_stats(out);
        assert_eq!(
            (s.executions, s.edges, s.features, s.corpus),
            (5000, 351, 902, 77)
        );
        assert_eq!(s.finding, None);
        let crash = "thread '<unnamed>' panicked at src/x.rs:1:1:\nboom\n==1== ERROR: libFuzzer: deadly signal\n";
        assert!(parse_stats(crash).finding.unwrap().contains("panicked at"));
    }
}
