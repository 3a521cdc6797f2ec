//! `handstack`: `train MODEL` and `trade` (the scene runner's `run` arm comes with the
//! scenes branch).

use handstack::train::{Model, TrainOptions};
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "usage:
  handstack train contact-mlp | force-dnn | softness | contact-cnn [--root DIR]
                  [--epochs N] [--only LABEL|INDEX] [--dry-run]
  handstack trade [--root DIR]";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("train") => train(&args[1..]),
        Some("trade") => trade(&args[1..]),
        _ => Err(format!("unknown command\n{USAGE}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("handstack: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `--name VALUE` from `args`.
fn opt(args: &[String], name: &str) -> Option<String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
}

fn root(args: &[String]) -> Result<PathBuf, String> {
    match opt(args, "--root") {
        Some(r) => Ok(PathBuf::from(r)),
        None => std::env::current_dir()
            .ok()
            .and_then(|d| handstack::train::find_root(&d))
            .ok_or_else(|| "no fixtures/models here or above: pass --root".into()),
    }
}

fn train(args: &[String]) -> Result<(), String> {
    let model =
        Model::from_name(args.first().map_or("", String::as_str)).map_err(|e| e.to_string())?;
    let options = TrainOptions {
        epochs: opt(args, "--epochs")
            .map(|s| {
                s.parse()
                    .map_err(|_| format!("--epochs `{s}` is not a count"))
            })
            .transpose()?,
        only: opt(args, "--only"),
        dry_run: args.iter().any(|a| a == "--dry-run"),
    };
    for path in handstack::train::run(&root(args)?, model, &options).map_err(|e| e.to_string())? {
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn trade(args: &[String]) -> Result<(), String> {
    let root = root(args)?;
    let trade = handstack::trade::run(&root, |step| eprintln!("trade: {step}"))
        .map_err(|e| e.to_string())?;
    for file in handstack::trade::write(&root, &trade).map_err(|e| e.to_string())? {
        println!("wrote {file}");
    }
    println!("trade run: {:.1} s", trade.wall_s);
    Ok(())
}
