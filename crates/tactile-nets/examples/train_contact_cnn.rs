//! Runs seed 002 §IV-A's protocol for the contact CNN on the committed ICM-20789 pad taps
//! (every variant and grouping, 10 × 80/20 trials and 5 folds per depth and for all depths),
//! trains the committed models, and writes `fixtures/models/contact_cnn/` (weights +
//! `metrics.json`).
//!
//! Run through `cargo xtask train contact-cnn` (which also draws the plots and the docs
//! section); arguments: `[WORKSPACE_ROOT] [--epochs N] [--only VARIANT/GROUPING/PROTOCOL/CASE]`
//! (`--epochs` and `--only` are for quick experiments: they write nothing).
//! Jobs run on two threads; each is seeded by what it is, so the results do not depend on
//! the thread count or order.

mod common;

use std::sync::Mutex;
use std::time::Instant;
use tactile_nets::cnn_eval::{
    self, Augmented, Case, Grouping, Job, MODEL_DIR, NOISY_COPIES, Protocol, SEED, SNR_DB,
};
use tactile_nets::contact_cnn::Variant;
use tactile_nets::data::imu_pad;
use tactile_nets::train::TrainConfig;

/// The (variant, grouping) pairs the protocol runs.
const RUNS: [(Variant, Grouping); 3] = [
    (Variant::Paper, Grouping::Samples),
    (Variant::Paper, Grouping::Taps),
    (Variant::Small, Grouping::Samples),
];
const THREADS: usize = 2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = common::workspace_root(&args);
    let opt = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let epochs: Option<usize> = opt("--epochs").and_then(|s| s.parse().ok());
    let only = opt("--only");
    let quick = epochs.is_some() || only.is_some();
    let taps = imu_pad::load(&root)?;
    let cases = Case::all(&taps);
    let data: Vec<(Case, Augmented)> = cases
        .iter()
        .map(|&c| {
            (
                c,
                cnn_eval::augment(&c.taps(&taps), NOISY_COPIES, SNR_DB, SEED),
            )
        })
        .collect();
    let mut jobs = Vec::new();
    for (variant, grouping) in RUNS {
        for protocol in Protocol::ALL {
            for &case in &cases {
                for run in 0..protocol.runs() {
                    let job = Job {
                        variant,
                        case,
                        protocol,
                        grouping,
                        run,
                    };
                    let label = cnn_eval::row_label(variant, grouping, protocol, case);
                    if only.as_deref().is_none_or(|o| label.starts_with(o)) {
                        jobs.push(job);
                    }
                }
            }
        }
    }
    // The all-depth jobs are the longest: start them first so the threads finish together.
    jobs.sort_by_key(|j| (j.case != Case::All, j.variant as u8));
    let adjust = move |c: &mut TrainConfig| {
        if let Some(n) = epochs {
            c.epochs = n;
        }
    };
    let start = Instant::now();
    let bar = indicatif::ProgressBar::new(jobs.len() as u64);
    let results: Mutex<Vec<(Job, f64, f64)>> = Mutex::new(Vec::new());
    let next = Mutex::new(0usize);
    let failure: Mutex<Option<String>> = Mutex::new(None);
    std::thread::scope(|s| {
        for _ in 0..THREADS {
            s.spawn(|| {
                loop {
                    let i = {
                        let mut n = next.lock().unwrap_or_else(|e| e.into_inner());
                        *n += 1;
                        *n - 1
                    };
                    let Some(&job) = jobs.get(i) else { break };
                    let Some((_, d)) = data.iter().find(|(c, _)| *c == job.case) else {
                        break;
                    };
                    let t = Instant::now();
                    match cnn_eval::run_job(job, d, SEED, &adjust) {
                        Ok((acc, _)) => results.lock().unwrap_or_else(|e| e.into_inner()).push((
                            job,
                            acc,
                            t.elapsed().as_secs_f64(),
                        )),
                        Err(e) => {
                            *failure.lock().unwrap_or_else(|e| e.into_inner()) =
                                Some(format!("{job:?}: {e}"));
                            break;
                        }
                    }
                    bar.inc(1);
                }
            });
        }
    });
    bar.finish();
    if let Some(e) = failure.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(e.into());
    }
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    let protocol_seconds = start.elapsed().as_secs_f64();
    let mut rows = Vec::new();
    for (variant, grouping) in RUNS {
        for protocol in Protocol::ALL {
            for &case in &cases {
                let mut runs: Vec<(usize, f64, f64)> = results
                    .iter()
                    .filter(|(j, ..)| {
                        (j.variant, j.grouping, j.protocol, j.case)
                            == (variant, grouping, protocol, case)
                    })
                    .map(|(j, a, t)| (j.run, *a, *t))
                    .collect();
                if runs.is_empty() {
                    continue;
                }
                runs.sort_by_key(|r| r.0);
                let acc: Vec<f64> = runs.iter().map(|r| r.1).collect();
                let label = cnn_eval::row_label(variant, grouping, protocol, case);
                let (m, sd) = cnn_eval::mean_std_pct(&acc);
                let secs = runs.iter().map(|r| r.2).sum::<f64>() / runs.len() as f64;
                println!("{label:<32} {m:6.2} % ± {sd:5.2}   ({secs:.1} s per training)");
                rows.push(cnn_eval::protocol_row(label, &acc));
            }
        }
    }
    println!(
        "protocol: {} trainings in {protocol_seconds:.1} s",
        results.len()
    );
    if quick {
        return Ok(());
    }
    let dir = root.join(MODEL_DIR);
    std::fs::create_dir_all(&dir)?;
    for variant in Variant::ALL {
        let job = cnn_eval::committed_job(variant);
        let Some((_, d)) = data.iter().find(|(c, _)| *c == job.case) else {
            continue;
        };
        let t = Instant::now();
        let (_, model) = cnn_eval::run_job(job, d, SEED, &|_| {})?;
        let secs = t.elapsed().as_secs_f64();
        let path = dir.join(cnn_eval::model_file(variant));
        model.save(&path)?;
        // The row comes from the saved file, exactly as the drift test will re-create it.
        let (acc, conf) = cnn_eval::evaluate_committed(&root, &taps, variant)?;
        println!(
            "committed {:<6} all depths, leak-free trial 0: {:.2} %  (trained in {secs:.1} s)  wrote {}",
            variant.name(),
            100.0 * acc,
            path.display()
        );
        rows.push(cnn_eval::committed_row(variant, acc, &conf));
    }
    let path = cnn_eval::save_metrics(&dir, &cnn_eval::metrics_file(rows, SEED))?;
    println!(
        "wrote {}; total {:.1} s",
        path.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
