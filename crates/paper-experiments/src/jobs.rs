//! The training commands' bodies: train a model family on its committed dataset and write its
//! weights and metrics below the workspace root: the body of `papers train MODEL`, which
//! `cargo xtask train MODEL` runs before `papers docs MODEL` draws the plots and the docs
//! sections from what these write.
//!
//! Each job prints one line per model (under a progress bar where training is long) and
//! returns the files it wrote (empty for a quick run, which writes nothing).

use crate::cnn_eval::{self, Augmented, Case, Grouping, Job, NOISY_COPIES, Protocol, SNR_DB};
use crate::contact_eval::{self, Mlp, SELECTION_FILE, SELECTION_OSR};
use crate::data::{fingertip, imu_pad, underactuated, weights};
use crate::force_eval;
use crate::softness_eval::{self, OPTIMISERS, SEEDS};
use hand_sim::records::DatasetError;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;
use tactile_nets::NetError;
use tactile_nets::contact_cnn::Variant;
use tactile_nets::metrics::MetricsFile;
use tactile_nets::softness_features::Features;
use tactile_nets::train::TrainConfig;

/// Why a training job stopped.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// A committed dataset could not be read.
    #[error("dataset: {0}")]
    Data(#[from] DatasetError),
    /// Training, evaluating or writing failed.
    #[error(transparent)]
    Net(#[from] NetError),
    /// A simulated training set could not be generated.
    #[error("simulated training set: {0}")]
    Sim(#[from] hand_sim::SimError),
}

/// Writing a file failed: a [`JobError::Net`], as the models' own writing reports it.
impl From<std::io::Error> for JobError {
    fn from(e: std::io::Error) -> Self {
        JobError::Net(NetError::Io(e))
    }
}

/// Trains the contact-area MLP on the committed fingertip taps: the validation search at
/// [`SELECTION_OSR`] (repeat 0 only), then per OSR the paper's recipe (both heads) and the
/// chosen configuration; writes the weights, `metrics.json` and `selection.json` to
/// [`contact_eval::MODEL_DIR`]. `epochs` (quick experiments): no search, paper recipe only
/// at that many epochs, nothing written.
///
/// Errors: the dataset ([`JobError::Data`]), training or writing ([`JobError::Net`]).
pub fn contact_mlp(root: &Path, epochs: Option<usize>) -> Result<Vec<PathBuf>, JobError> {
    let records = fingertip::load(root)?.records();
    let seed = contact_eval::SEED;
    let start = Instant::now();
    let mut selection = None;
    let mut off_selections = Vec::new();
    let trained = match epochs {
        None => {
            let (chosen, results) = contact_eval::select(&records, SELECTION_OSR, seed, true)?;
            for (c, e) in &results {
                println!(
                    "validation osr {SELECTION_OSR} {:<32} area {:>6.2} %  exact {:>6.2} %",
                    c.label(),
                    100.0 * e.area_accuracy(),
                    100.0 * e.exact_accuracy()
                );
            }
            println!("chosen: {}", chosen.label());
            selection = Some(contact_eval::selection_file(&results, chosen, seed));
            let mut trained = contact_eval::train_all(&records, Some(chosen), seed, true)?;
            let draws = jittered_draws(&contact_eval::OFF_LATTICE_TRAIN_SEEDS)?;
            let validation = jittered_draws(&contact_eval::OFF_LATTICE_VALIDATION_SEEDS)?;
            for (kind, grid, file) in [
                (
                    Mlp::OffLattice,
                    contact_eval::off_lattice_grid(),
                    contact_eval::OFF_LATTICE_SELECTION_FILE,
                ),
                (
                    Mlp::OffLatticeCentroid,
                    contact_eval::off_lattice_centroid_grid(),
                    contact_eval::OFF_LATTICE_CENTROID_SELECTION_FILE,
                ),
            ] {
                let (off, search) = off_lattice(kind, grid, &records, &draws, &validation, seed)?;
                trained.extend(off);
                off_selections.push((file, search));
            }
            trained
        }
        Some(n) => contact_eval::train_all_with(&records, None, seed, true, |c| c.epochs = n)?,
    };
    let seconds = start.elapsed().as_secs_f64();
    for t in &trained {
        let e = &t.evaluation;
        println!(
            "osr {:>4} {:<14} area {:>6.2} %  exact {:>6.2} %  cell err {:.3}  centroid err {:.3}  final loss {:.4}",
            t.osr,
            t.label(),
            100.0 * e.area_accuracy(),
            100.0 * e.exact_accuracy(),
            e.mean_cell_error(),
            e.mean_centroid_error(),
            t.log.epoch_loss.last().copied().unwrap_or(f32::NAN),
        );
    }
    println!("training time: {seconds:.1} s for {} models", trained.len());
    let mut written = Vec::new();
    if epochs.is_none() {
        let dir = root.join(contact_eval::MODEL_DIR);
        written = contact_eval::save_all(&dir, &trained, seed)?;
        let searches = selection
            .map(|s| (SELECTION_FILE, s))
            .into_iter()
            .chain(off_selections);
        for (file, selection) in searches {
            let path = dir.join(file);
            std::fs::write(&path, selection.to_json()?)?;
            written.push(path);
        }
    }
    Ok(written)
}

/// The records of hand-sim's jittered draws of `seeds` (every OSR), in order.
fn jittered_draws(seeds: &[u64]) -> Result<Vec<fingertip::TapRecord>, JobError> {
    let mut records = Vec::new();
    for &seed in seeds {
        let (taps, series) = hand_sim::fingertip::dataset::jittered_taps(seed)?;
        records.extend(fingertip::parse(&taps, &series)?.records());
    }
    Ok(records)
}

/// The off-lattice model `kind` ([`Mlp::OffLattice`], [`Mlp::OffLatticeCentroid`]): its
/// search over `grid` at [`SELECTION_OSR`] on the `validation` draw, then one model per OSR
/// trained on the lattice's training repeat and the jittered training `draws`.
fn off_lattice(
    kind: Mlp,
    grid: Vec<contact_eval::Candidate>,
    lattice: &[fingertip::TapRecord],
    draws: &[fingertip::TapRecord],
    validation: &[fingertip::TapRecord],
    seed: u64,
) -> Result<(Vec<contact_eval::Trained>, MetricsFile), JobError> {
    let (chosen, results) = contact_eval::select_off_lattice(
        grid,
        lattice,
        draws,
        validation,
        SELECTION_OSR,
        seed,
        true,
    )?;
    for (c, e) in &results {
        println!(
            "off-lattice validation osr {SELECTION_OSR} {:<28} single-cell {:>6.2} %  every tap {:>6.2} %",
            c.label(),
            100.0 * e.area_accuracy(),
            100.0 * e.centroid_cell_accuracy()
        );
    }
    println!("off-lattice chosen: {}", chosen.label());
    let search = contact_eval::off_lattice_selection_file(kind, &results, chosen, seed);
    let trained = contact_eval::train_off_lattice(kind, lattice, draws, chosen, seed, true)?;
    Ok((trained, search))
}

/// Trains the force / weight DNN (the Table 1 fit on `table1` = Table 1's `(weight gf,
/// pressures hPa)` rows, its leave-one-out models, the simulated-series model) and writes the
/// weights, metrics and training curves to [`force_eval::MODEL_DIR`].
///
/// Errors: the dataset ([`JobError::Data`]), training or writing ([`JobError::Net`]).
pub fn force_dnn(root: &Path, table1: &[(f64, [f64; 3])]) -> Result<Vec<PathBuf>, JobError> {
    let seed = force_eval::SEED;
    let table = weights::tared_table(table1)?;
    let frames = weights::load_series(root)?;
    let start = Instant::now();
    let models = force_eval::train_all(&table, &frames, seed, true)?;
    let seconds = start.elapsed().as_secs_f64();
    let metrics = force_eval::metrics_file(&models, &table, &frames, seed)?;
    for row in &metrics.rows {
        let v = |k: &str| row.values.get(k).copied().unwrap_or(f64::NAN);
        println!(
            "{:<14} mean |err| {:>7.3} gf  max |err| {:>7.3} gf  rmse {:>7.3} gf",
            row.label,
            v("mean_abs_error_gf"),
            v("max_abs_error_gf"),
            v("rmse_gf")
        );
    }
    println!(
        "training time: {seconds:.1} s for {} models",
        models.loo.len() + 2
    );
    Ok(force_eval::save_all(
        &root.join(force_eval::MODEL_DIR),
        &models,
        &table,
        &metrics,
    )?)
}

/// Trains the softness classifier (seed 001) with Levenberg–Marquardt and with Adam, one model
/// per seed, on the committed underactuated-hand grasps, and writes the weights,
/// `metrics.json` and `training.json` to [`softness_eval::MODEL_DIR`]. `only` (an index into
/// [`OPTIMISERS`]) trains one optimiser; `dry_run` writes nothing.
///
/// Errors: the dataset ([`JobError::Data`]), training or writing ([`JobError::Net`]).
pub fn softness(root: &Path, only: Option<usize>, dry_run: bool) -> Result<Vec<PathBuf>, JobError> {
    let grasps = underactuated::load(root)?;
    let bar = ProgressBar::new((OPTIMISERS.len() * SEEDS.len()) as u64);
    if let Ok(style) =
        ProgressStyle::with_template("{prefix:>12} [{bar:30}] {pos}/{len} models {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix("softness");
    let mut runs = Vec::new();
    for optimiser in OPTIMISERS
        .into_iter()
        .skip(only.unwrap_or(0))
        .take(if only.is_some() { 1 } else { 2 })
    {
        for seed in SEEDS {
            bar.set_message(format!("{} seed {seed}", optimiser().name()));
            let run = softness_eval::train_one(&grasps, optimiser(), seed)?;
            let e = &run.evaluation;
            let stop = run.report.as_ref().map_or("", |r| r.stop.name());
            bar.suspend(|| println!(
                "{:<4} seed {seed}: train {:>5.1} %  regular {:>5.1} %  irregular {:>5.1} % / 1000: {:>5.1} %  mse {:.4}  {:>6.2} s  ({stop}, {} evaluations)",
                run.optimiser,
                100.0 * e.train.accuracy(),
                100.0 * e.regular.accuracy(),
                100.0 * e.irregular.accuracy(),
                100.0 * e.irregular_1000.accuracy(),
                e.train_mse,
                run.seconds,
                run.report.as_ref().map_or(0, |r| r.curve.len()),
            ));
            runs.push(run);
            bar.inc(1);
        }
    }
    bar.finish();
    // Our variant: more household training objects, inputs chosen on validation objects of
    // their own; both drawn now, from streams no committed set uses.
    let draw = |name: &str, n: usize| -> Result<Vec<underactuated::Grasp>, JobError> {
        let specs = hand_sim::underactuated::dataset::household_draw(underactuated::SEED, name, n)?;
        Ok(underactuated::from_sim(
            &hand_sim::underactuated::dataset::run_all(&specs)?,
        )?)
    };
    let extra = draw(softness_eval::TRAIN_DRAW, softness_eval::EXTRA_TRAINING)?;
    let held = draw(
        softness_eval::VALIDATION_DRAW,
        softness_eval::VALIDATION_OBJECTS,
    )?;
    let mut validation = Vec::new();
    for features in Features::ALL {
        let acc = softness_eval::validate_features(&grasps, &extra, &held, features)?;
        println!("validation {:<16} {:>5.1} %", features.name(), 100.0 * acc);
        validation.push((features.name().to_owned(), acc));
    }
    let chosen = Features::CANDIDATES
        .into_iter()
        .fold(None::<(Features, f64)>, |best, f| {
            let acc = validation
                .iter()
                .find(|(n, _)| n == f.name())
                .map_or(0.0, |v| v.1);
            match best {
                Some((_, b)) if b >= acc => best,
                _ => Some((f, acc)),
            }
        })
        .map(|(f, _)| f)
        .ok_or_else(|| NetError::Training("no candidate feature set".into()))?;
    let mut ours = Vec::new();
    for seed in SEEDS {
        let run = softness_eval::train_ours(&grasps, &extra, chosen, seed)?;
        let e = &run.evaluation;
        println!(
            "ours {} seed {seed}: train {:>5.1} %  regular {:>5.1} %  irregular {:>5.1} % / 1000: {:>5.1} %  mse {:.4}  {:>6.2} s",
            chosen.name(),
            100.0 * e.train.accuracy(),
            100.0 * e.regular.accuracy(),
            100.0 * e.irregular.accuracy(),
            100.0 * e.irregular_1000.accuracy(),
            e.train_mse,
            run.seconds,
        );
        ours.push(run);
    }
    if dry_run {
        return Ok(Vec::new());
    }
    let dir = root.join(softness_eval::MODEL_DIR);
    let mut written = softness_eval::save_all(&dir, &runs)?;
    written.extend(softness_eval::save_ours(&dir, &ours, &validation)?);
    Ok(written)
}

/// The (variant, grouping) pairs the contact CNN protocol runs.
pub const CNN_RUNS: [(Variant, Grouping); 6] = [
    (Variant::Paper, Grouping::Samples),
    (Variant::Paper, Grouping::Taps),
    (Variant::Small, Grouping::Samples),
    (Variant::Small, Grouping::Taps),
    (Variant::Wide, Grouping::Samples),
    (Variant::Wide, Grouping::Taps),
];
/// Threads the contact CNN protocol runs on.
pub const CNN_THREADS: usize = 2;

/// Runs seed 002 §IV-A's protocol for the contact CNN on the committed ICM-20789 pad taps
/// (every variant and grouping of [`CNN_RUNS`], 10 × 80/20 trials and 5 folds per depth and
/// for all depths), trains the committed models, and writes [`cnn_eval::MODEL_DIR`] (weights +
/// `metrics.json`). `epochs` and `only` (a row-label prefix,
/// `VARIANT/GROUPING/PROTOCOL/CASE`) are for quick experiments: they write nothing. Jobs run
/// on [`CNN_THREADS`] threads; each is seeded by what it is, so results do not depend on the
/// thread count or order.
///
/// Errors: the dataset ([`JobError::Data`]), a training job or writing ([`JobError::Net`]).
pub fn contact_cnn(
    root: &Path,
    epochs: Option<usize>,
    only: Option<&str>,
) -> Result<Vec<PathBuf>, JobError> {
    let seed = cnn_eval::SEED;
    let quick = epochs.is_some() || only.is_some();
    let taps = imu_pad::load(root)?;
    let cases = Case::all(&taps);
    let data: Vec<(Case, Augmented)> = cases
        .iter()
        .map(|&c| {
            (
                c,
                cnn_eval::augment(&taps, &c.taps(&taps), NOISY_COPIES, SNR_DB, seed),
            )
        })
        .collect();
    let mut jobs = Vec::new();
    for (variant, grouping) in CNN_RUNS {
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
                    if only.is_none_or(|o| label.starts_with(o)) {
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
    let bar = ProgressBar::new(jobs.len() as u64);
    let results: Mutex<Vec<(Job, f64, f64)>> = Mutex::new(Vec::new());
    let next = Mutex::new(0usize);
    let failure: Mutex<Option<String>> = Mutex::new(None);
    std::thread::scope(|s| {
        for _ in 0..CNN_THREADS {
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
                    match cnn_eval::run_job(job, d, seed, &adjust) {
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
        return Err(NetError::Training(e).into());
    }
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    let protocol_seconds = start.elapsed().as_secs_f64();
    let mut rows = Vec::new();
    for (variant, grouping) in CNN_RUNS {
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
        return Ok(Vec::new());
    }
    let dir = root.join(cnn_eval::MODEL_DIR);
    std::fs::create_dir_all(&dir)?;
    let mut written = Vec::new();
    for which in cnn_eval::COMMITTED {
        let job = which.job();
        let Some((_, d)) = data.iter().find(|(c, _)| *c == job.case) else {
            continue;
        };
        let t = Instant::now();
        let (_, model) = cnn_eval::run_job(job, d, seed, &|_| {})?;
        let secs = t.elapsed().as_secs_f64();
        let path = dir.join(which.file());
        // The file says where its training windows sit after a tap's trigger, so that a pad
        // node cuts the windows it learned from.
        model
            .with_trigger_offset(cnn_eval::training_centre_frames())?
            .save(&path)?;
        // The row comes from the saved file, exactly as the drift test will re-create it.
        let (acc, conf) = cnn_eval::evaluate_committed(root, &taps, which)?;
        println!(
            "{:<24} {}, leak-free trial 0: {:.2} %  (trained in {secs:.1} s)",
            which.label(),
            which.case.name(),
            100.0 * acc,
        );
        rows.push(cnn_eval::committed_row(which, acc, &conf));
        written.push(path);
    }
    written.push(cnn_eval::save_metrics(
        &dir,
        &cnn_eval::metrics_file(rows, seed),
    )?);
    println!("total {:.1} s", start.elapsed().as_secs_f64());
    Ok(written)
}
