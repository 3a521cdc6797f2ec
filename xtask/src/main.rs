//! `cargo xtask`: the handstack workspace's developer commands (see the `xtask` library docs).

use std::process::ExitCode;
use xtask::{
    architecture, bench, cell_doc, consumer, demo, firmware, fixtures, fuzz, package, run, test,
    trade, train, venv, workspace_root,
};

const USAGE: &str = "usage: cargo xtask <command>

commands:
  test                      set up .venv and chromium, then fmt, clippy, every test, docs, fixtures --check
                            (and once more with numpy's widest SIMD kernels off)
  architecture [--check]    draw the crate graph (cargo metadata) into docs/architecture.md, then check
                            the architecture rules (--check: fail if the drawn graph differs instead)
  fixtures [--check]        regenerate the generated fixtures, or check the committed ones (third-party
                            float output by value within a tolerance: fixtures/README.md)
  fixtures --check --numpy-narrowed
                            check the value-compared ones regenerated with numpy's widest SIMD kernels off
  bench [FILTER] [--write] [-- ARGS]
                            run the criterion benches (names containing FILTER), print a summary;
                            --write: also write docs/benchmarks.md (`bench cycles --write`)
  bench --check | --bless   instructions per call of every workload (callgrind) against
                            benches/baselines/instructions.tsv: --check fails on a count > 1 %
                            above its baseline, --bless rewrites the baselines
  train contact-mlp [--docs-only]
                            train the contact-area MLP, write its weights, metrics, plot and the
                            generated sections of docs/contact-location.md (--docs-only: those alone)
  train force-dnn           train the force / weight DNN, write its weights, metrics, curve, docs
  train softness [--docs-only]
                            train the softness classifier (LM, Adam, our variant), write weights,
                            metrics, report (--docs-only: redraw from the committed files)
  train contact-cnn [--docs-only]
                            run the contact CNN's Table I protocol, write weights, metrics, plots,
                            docs (--docs-only: redraw plots and docs from the committed metrics)
  package                   cargo package every published crate (verified), then run every README's
                            examples against the packages from a scratch crate (the consumer test)
  firmware [--write]        link the fingertip firmware for its three boards, run it on the host;
                            --write: regenerate docs/embedded.md (sizes, callgrind counts)
  trade                     measure every speed / accuracy knob, write docs/trade.md (+ docs/trade/)
  demo [--screenshot]       run every scene (fixtures/scenes/) into target/demo/report.html
                            (--screenshot: and its full-page picture, docs/demo-report.png)
  demo tap-to-move          seed 002 §IV-B on the simulated UR3 via ur_rtde, into docs/arm-tap-to-move.md
  cell-doc [--seconds S] [--rounds R]
                            measure the Zenoh cell on loopback (hand-zenoh's cell_latency), into docs/cell.md
  soak [--seeds N] [--seconds S]
                            the grasp loop under random faults, S simulated s (default 3600) per
                            seed 1..=N (default 2): the soak section of docs/reliability.md
  fuzz --seed               write the fuzz targets' seed corpora (fuzz/seeds/) from fixtures, models, captures
  fuzz TARGET... | --all [--seconds N]
                            fuzz each target N s (default 1800) with libFuzzer (installs
                            cargo-fuzz), growing its corpus fuzz/corpus/TARGET.tar.gz (unpacked into
                            target/fuzz-corpus/TARGET, minimised, packed back), append the figures to
                            fuzz/runs.tsv and rewrite the fuzzing section of docs/reliability.md (--doc:
                            that alone)";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = workspace_root();
    let result = match args.first().map(String::as_str) {
        Some("test") if args.len() == 1 => test::run(&root),
        Some("architecture") => match &args[1..] {
            [] => architecture::run(&root, false),
            [flag] if flag == "--check" => architecture::run(&root, true),
            _ => usage_error(),
        },
        Some("fixtures") => match &args[1..] {
            [] => fixtures::run(&root, fixtures::Mode::Write),
            [flag] if flag == "--check" => fixtures::run(&root, fixtures::Mode::Check),
            [check, narrowed] if check == "--check" && narrowed == "--numpy-narrowed" => {
                fixtures::check_with_numpy_narrowed(&root)
            }
            _ => usage_error(),
        },
        Some("bench") => bench::run(&root, &args[1..]),
        Some("train") => train::run(&root, &args[1..]),
        Some("demo") => demo::run(&root, &args[1..]),
        Some("cell-doc") => cell_doc::run(&root, &args[1..]),
        Some("fuzz") => fuzz::run(&root, &args[1..]),
        // `papers soak` takes the same flags: --seeds N, --seconds S.
        Some("soak") => {
            run::PAPERS.run(&root, "soak", &[&["soak".to_owned()], &args[1..]].concat())
        }
        Some("trade") if args.len() == 1 => trade::run(&root),
        Some("firmware") if args.len() == 1 => firmware::check(&root),
        Some("firmware") if args.len() == 2 && args[1] == "--write" => firmware::write(&root),
        Some("package") if args.len() == 1 => package::run(&root)
            .and_then(|()| venv::ensure(&root))
            .and_then(|python| consumer::run(&root, &python)),
        Some("help" | "-h" | "--help") => {
            println!("{USAGE}");
            Ok(())
        }
        _ => usage_error(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn usage_error() -> anyhow::Result<()> {
    anyhow::bail!("unknown command\n\n{USAGE}")
}
