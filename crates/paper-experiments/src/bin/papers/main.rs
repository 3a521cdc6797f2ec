//! `papers`: the reproduction's writers that need the simulator, the learned models or plotters,
//! so that `cargo xtask` links none of them (rust-analyzer's rule: xtask stays thin and runs
//! this binary, `cargo run --profile test -p paper-experiments --no-default-features --bin
//! papers -- …`).
//!
//! - `docs MODEL`: a trained model's plots and its section of `docs/` ([`docs`]);
//! - `fixtures NAME --out DIR`: a generated fixture folder that needs the simulator ([`fixtures`]);
//! - `train MODEL [--epochs N] [--only X] [--dry-run]`: trains a committed model family and
//!   writes its weights and metrics ([`paper_experiments::train`]);
//! - `trade`: the speed / accuracy trade into `docs/trade.md` and `docs/trade/`
//!   ([`paper_experiments::trade`]);
//! - `soak [--seeds N] [--seconds S]`: the grasp loop under random faults, S simulated seconds
//!   (default an hour) per seed 1…N, one after another; the soak section of
//!   `docs/reliability.md` ([`paper_experiments::soak`]).

mod docs;
mod fixtures;

use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage: papers <command> --root ROOT

commands (run by `cargo xtask`; ROOT is the workspace root):
  docs MODEL [--timing ID=MEAN]...
                            draw MODEL's plots and rewrite its section of docs/ from its committed
                            weights and metrics (contact-mlp, force-dnn, softness, contact-cnn);
                            --timing: a criterion mean the section quotes (contact-cnn)
  fixtures NAME --out DIR   write the generated fixture folder NAME into DIR
                            (fingertip-datasets, imu-pad-taps, underactuated)
  train MODEL [--epochs N] [--only X] [--dry-run]
                            train MODEL (contact-mlp, force-dnn, softness, contact-cnn) and write
                            its weights and metrics; --epochs: a quick run (contact-mlp,
                            contact-cnn; writes nothing); --only: protocol rows starting with X
                            (contact-cnn) or optimiser 0 / 1 (softness); --dry-run: write nothing
  trade                     measure cost against accuracy for every knob; write docs/trade.md
                            and docs/trade/
  soak [--seeds N] [--seconds S]
                            the grasp loop under random faults for S simulated seconds (default
                            3600) per seed 1..=N (default 2); write the soak section of
                            docs/reliability.md";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("papers: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// The command line: the command's words, then its options in any order.
#[derive(Debug, Default)]
struct CommandLine {
    words: Vec<String>,
    root: Option<PathBuf>,
    out: Option<PathBuf>,
    timings: docs::Timings,
    train: paper_experiments::train::TrainOptions,
    seeds: Option<u64>,
    seconds: Option<f64>,
}

impl CommandLine {
    fn parse(args: &[String]) -> Result<CommandLine> {
        let mut line = CommandLine::default();
        let mut args = args.iter();
        while let Some(arg) = args.next() {
            let mut value = || args.next().with_context(|| format!("{arg} needs a value"));
            match arg.as_str() {
                "--root" => line.root = Some(value()?.into()),
                "--out" => line.out = Some(value()?.into()),
                "--epochs" => {
                    let n = value()?;
                    line.train.epochs = Some(n.parse().with_context(|| format!("--epochs {n}"))?);
                }
                "--only" => line.train.only = Some(value()?.clone()),
                "--dry-run" => line.train.dry_run = true,
                "--seeds" => {
                    let n = value()?;
                    line.seeds = Some(n.parse().with_context(|| format!("--seeds {n}"))?);
                }
                "--seconds" => {
                    let n = value()?;
                    line.seconds = Some(n.parse().with_context(|| format!("--seconds {n}"))?);
                }
                "--timing" => {
                    let (id, mean) = value()?.split_once('=').context("--timing takes ID=MEAN")?;
                    line.timings.insert(id.to_owned(), mean.to_owned());
                }
                flag if flag.starts_with('-') => bail!("unknown option `{flag}`\n\n{USAGE}"),
                word => line.words.push(word.to_owned()),
            }
        }
        Ok(line)
    }
}

fn run(args: &[String]) -> Result<()> {
    if matches!(args, [a] if a == "help" || a == "-h" || a == "--help") {
        println!("{USAGE}");
        return Ok(());
    }
    let line = CommandLine::parse(args)?;
    let root = || line.root.as_deref().context("--root ROOT is required");
    match &line.words[..] {
        [command, model] if command == "docs" => docs::write(root()?, model, &line.timings),
        [command, name] if command == "fixtures" => {
            let out = line.out.as_deref().context("fixtures needs --out DIR")?;
            fixtures::write(name, out)
        }
        [command, model] if command == "train" => train(root()?, model, &line.train),
        [command] if command == "trade" => trade(root()?),
        [command] if command == "soak" => soak(
            root()?,
            line.seeds.unwrap_or(2),
            line.seconds.unwrap_or(3600.0),
        ),
        _ => bail!("unknown command\n\n{USAGE}"),
    }
}

/// Trains `model` below `root` with `options` and names the files written.
fn train(root: &Path, model: &str, options: &paper_experiments::train::TrainOptions) -> Result<()> {
    let model = paper_experiments::train::Model::from_name(model)?;
    for path in paper_experiments::train::run(root, model, options)? {
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Measures the trade below `root` and writes its report.
fn trade(root: &Path) -> Result<()> {
    let trade = paper_experiments::trade::run(root, |step| eprintln!("trade: {step}"))?;
    for file in paper_experiments::trade::write(root, &trade)? {
        println!("wrote {file}");
    }
    println!("trade run: {:.1} s", trade.wall_s);
    Ok(())
}

/// Soaks seeds 1..=`seeds` for `seconds` each, two at a time, and writes the soak section of
/// `docs/reliability.md`. Fails on any violation (after writing it down).
fn soak(root: &Path, seeds: u64, seconds: f64) -> Result<()> {
    use paper_experiments::soak::{SoakConfig, markdown, soak, summary};
    let configs: Vec<SoakConfig> = (1..=seeds)
        .map(|seed| SoakConfig {
            seconds,
            ..SoakConfig::hour(seed)
        })
        .collect();
    // One seed at a time: a soak is two threads (the loop and the bus simulator) with a
    // wall-clock reply deadline, and a core shared with another soak would show as timeouts
    // the soak did not inject.
    let mut reports = Vec::new();
    for c in &configs {
        let r = soak(c)?;
        println!("{}", summary(&r));
        for v in &r.violations {
            println!("  violation: {v}");
        }
        reports.push(r);
    }
    let c = &configs[0];
    let mut section = format!(
        "`cargo xtask soak` (`papers soak --seeds {seeds} --seconds {seconds}`): per seed, {seconds} s simulated at 100 Hz; a fault window every {} s on average (½…1½ ×), 1…{} cycles long, kind drawn uniformly; the driver's reply allowance {} ms; automatic recovery (100 ms cool-down before a reboot).\n\n",
        c.mean_gap_s,
        c.max_window_cycles,
        c.reply_latency.as_millis()
    );
    for r in &reports {
        section.push_str(&format!("- {}\n", summary(r)));
    }
    section.push('\n');
    section.push_str(&markdown(&reports));
    let path = root.join("docs/reliability.md");
    let doc = std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
    let (begin, end) = ("<!-- soak: papers soak writes this -->\n", "<!-- /soak -->");
    let (Some(a), Some(b)) = (doc.find(begin), doc.find(end)) else {
        bail!("{} has no soak markers", path.display());
    };
    let doc = format!("{}{begin}{section}{}", &doc[..a], &doc[b..]);
    std::fs::write(&path, doc)?;
    println!("wrote {}", path.display());
    let broken: usize = reports.iter().map(|r| r.violations.len()).sum();
    if broken > 0 {
        bail!("{broken} violations");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<CommandLine> {
        CommandLine::parse(&args.iter().map(|a| a.to_string()).collect::<Vec<_>>())
    }

    #[test]
    fn options_come_in_any_order_and_timings_split_at_the_first_equals() -> Result<()> {
        let line = parse(&[
            "docs",
            "--timing",
            "contact_cnn/paper/infer=8.34 µs",
            "contact-cnn",
            "--root",
            "/w",
        ])?;
        assert_eq!(line.words, ["docs", "contact-cnn"]);
        assert_eq!(line.root, Some(PathBuf::from("/w")));
        assert_eq!(line.timings["contact_cnn/paper/infer"], "8.34 µs");
        assert!(parse(&["docs", "--timing", "no-equals"]).is_err());
        assert!(parse(&["docs", "--root"]).is_err());
        assert!(parse(&["docs", "--verbose"]).is_err());
        Ok(())
    }
}
