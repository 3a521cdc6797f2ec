//! `handstack train force SESSIONS… --out FILE`: the force DNN of the user's own fingertip from
//! `[experiment.weight]` collect sessions.
//!
//! Each weight's frames are tared on the `tare` label before it; every frame averaged for a weight
//! is a training row, with three times as many rows mixed between neighbouring weights
//! (tactile-nets' [`mixup`] and [`session_recipe`]: Adam in minibatches of 16). Of the weights sorted lightest first, every fourth from the third is held out and
//! never trained on — never the lightest or the heaviest, which bound the range the model is
//! rated for: the model is scored on those as Table 1 scores it, the settled mean of each
//! weight against the weight, and so is the built-in `sim` model beside it. The weights file
//! written is the model so scored.

use super::{HOLD_OUT_EVERY, TrainError, Trained, cost_ns, held_out_at};
use crate::record::read::ReadError;
use crate::record::{LABELS, raw_topic};
use crate::runs::figure::{Target, measured, paper, target};
use crate::runs::weight::{EXPERIMENT, PAPER_MAX_ERROR_GF, PAPER_SOURCE, TARE, WEIGHT_GF};
use crate::{Line, Outcome, Plot};
use hand_zenoh::msg::handstack_msgs::{Label, PressureFrame};
use std::path::PathBuf;
use tactile_nets::force_dnn::{ForceDnn, WeightSample, mixup, session_recipe};
use tactile_nets::pretrained::ForceModel;

/// Rows mixed between neighbouring weights per frame trained on (tactile-nets' [`mixup`]).
pub const MIXED_PER_FRAME: usize = 3;

/// `handstack train force`'s arguments.
#[derive(clap::Args)]
pub struct ForceArgs {
    #[command(flatten)]
    common: super::SessionArgs,
    /// The largest held-out error the model should meet, gf (the weight experiment's default).
    #[arg(long, default_value_t = 2.0)]
    tolerance_gf: f64,
}

impl ForceArgs {
    /// Reads the sessions, trains, writes the weights and metrics.
    pub(super) fn run(&self) -> Result<(Outcome, bool), TrainError> {
        let c = &self.common;
        let kind = super::Kind {
            name: "force",
            what: "Force DNN of your fingertip",
            scene_key: "[estimators.force] weights",
        };
        c.run(
            &kind,
            steps,
            |steps| train(steps, c.seed, self.tolerance_gf, !c.json),
            |m, p| m.save(p),
        )
    }
}

/// One weight of a session: the weight placed and the tared rise of each frame averaged, hPa.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The session's bag.
    pub bag: PathBuf,
    /// The weight placed, gf.
    pub weight_gf: f64,
    /// The rise of each sensor over the session's tare, per frame, hPa.
    pub rises_hpa: Vec<[f32; 3]>,
}

impl Step {
    /// The mean rise over the step's frames (Table 1's "average measured values").
    pub fn mean_hpa(&self) -> [f32; 3] {
        let n = self.rises_hpa.len().max(1) as f64;
        core::array::from_fn(|k| {
            (self.rises_hpa.iter().map(|r| f64::from(r[k])).sum::<f64>() / n) as f32
        })
    }
}

/// Every weight step of `bags`. A session that recorded no label (stopped at its first
/// question) is skipped; any other bag without weight labels is an error.
///
/// Errors: a bag that cannot be read, has no labels or frames, labels of another experiment,
/// no tare, frames of another device, or a label that covers no frame — each naming the file
/// and the topic.
pub fn steps(bags: &[PathBuf]) -> Result<Vec<Step>, ReadError> {
    let raw = raw_topic();
    let read = super::labelled::<PressureFrame>(
        bags,
        EXPERIMENT,
        "placed",
        &raw,
        "the fingertip's frames",
    )?;
    let mut out = Vec::new();
    for b in &read {
        out.extend(bag_steps(b)?);
    }
    Ok(out)
}

fn bag_steps(b: &super::LabelledBag<PressureFrame>) -> Result<Vec<Step>, ReadError> {
    let (bag, frames, raw) = (&b.bag, &b.messages, raw_topic());
    let path = b.rec.path().to_owned();
    let ours: Vec<&Label> = b.labels.iter().collect();
    let content = |topic: &str, problem: String| ReadError::Content {
        path: path.clone(),
        topic: topic.to_owned(),
        problem,
    };
    if let Some((_, f)) = frames.iter().find(|(_, f)| f.pressure_pa.len() != 3) {
        return Err(content(
            &raw,
            format!(
                "frames of {} pressures, not the fingertip's 3: the bag is another device's",
                f.pressure_pa.len()
            ),
        ));
    }
    let window = |l: &Label| -> Result<Vec<[f64; 3]>, ReadError> {
        let (a, b) = (l.start.as_nanos(), l.end.as_nanos());
        let w: Vec<[f64; 3]> = frames
            .iter()
            .filter(|(t, _)| (a..=b).contains(t))
            .map(|(_, f)| core::array::from_fn(|k| f64::from(f.pressure_pa[k])))
            .collect();
        if w.is_empty() {
            return Err(content(
                LABELS,
                format!("label `{}` = {} covers no {raw} frame", l.name, l.value),
            ));
        }
        Ok(w)
    };
    // Each weight counts from the tare before it (a collect session tares before each weight,
    // so the sensors' drift over the session stays out of the rises).
    let mut ours = ours;
    ours.sort_by_key(|l| l.start.as_nanos());
    let mut zero: Option<[f64; 3]> = None;
    let mut out = Vec::new();
    for l in ours {
        if l.name == TARE {
            let tare = window(l)?;
            let n = tare.len() as f64;
            zero = Some(core::array::from_fn(|k| {
                tare.iter().map(|p| p[k]).sum::<f64>() / n
            }));
        } else if l.name == WEIGHT_GF {
            let zero = zero.ok_or_else(|| {
                content(
                    LABELS,
                    format!(
                        "`{WEIGHT_GF}` = {} has no `{TARE}` label before it: its frames cannot \
                         be tared",
                        l.value
                    ),
                )
            })?;
            out.push(Step {
                bag: bag.to_owned(),
                weight_gf: l.value,
                rises_hpa: window(l)?
                    .iter()
                    .map(|p| core::array::from_fn(|k| ((p[k] - zero[k]) / 100.0) as f32))
                    .collect(),
            });
        }
    }
    Ok(out)
}

/// Trains on `steps` (every [`HOLD_OUT_EVERY`]th weight, lightest first, held out) with
/// `seed`, scores the held-out weights against `tolerance_gf`.
///
/// Errors: fewer than [`HOLD_OUT_EVERY`] weights, or a failed fit.
pub fn train(
    steps: &[Step],
    seed: u64,
    tolerance_gf: f64,
    progress: bool,
) -> Result<Trained<ForceDnn>, TrainError> {
    if steps.len() < HOLD_OUT_EVERY {
        return Err(TrainError::TooFew {
            what: "weights".into(),
            found: steps.len(),
            needed: HOLD_OUT_EVERY,
            rule: "training holds every fourth out (never the lightest or the heaviest) to test \
                   the model on",
        });
    }
    let mut sorted: Vec<&Step> = steps.iter().collect();
    sorted.sort_by(|a, b| a.weight_gf.total_cmp(&b.weight_gf));
    let n = sorted.len();
    let (held, fit): (Vec<_>, Vec<_>) = sorted
        .into_iter()
        .enumerate()
        .partition(|&(i, _)| held_out_at(i, n));
    let mut samples: Vec<WeightSample> = fit
        .iter()
        .flat_map(|(_, s)| {
            s.rises_hpa.iter().map(|&rise_hpa| WeightSample {
                rise_hpa,
                weight_gf: s.weight_gf as f32,
            })
        })
        .collect();
    let fit_frames = samples.len();
    let neighbours: Vec<(f32, &[[f32; 3]])> = fit
        .iter()
        .map(|(_, s)| (s.weight_gf as f32, s.rises_hpa.as_slice()))
        .collect();
    samples.extend(mixup(&neighbours, MIXED_PER_FRAME, seed));
    let lightest = steps
        .iter()
        .map(|s| s.weight_gf)
        .fold(f64::INFINITY, f64::min);
    let heaviest = steps
        .iter()
        .map(|s| s.weight_gf)
        .fold(f64::NEG_INFINITY, f64::max);
    let range = [lightest as f32, heaviest as f32];
    let (dnn, log) = ForceDnn::train(&samples, range, &session_recipe(seed, progress, "force"))?;

    let builtin = ForceModel::Sim.dnn();
    let (mut ours, mut theirs, mut frame_sq, mut frames) = (Vec::new(), Vec::new(), 0.0, 0usize);
    for (_, s) in &held {
        let mean = s.mean_hpa();
        ours.push((s.weight_gf, f64::from(dnn.estimate_gf(&mean)?)));
        theirs.push((
            s.weight_gf,
            f64::from(
                builtin
                    .estimate_gf(&mean)
                    .map_err(tactile_nets::NetError::from)?,
            ),
        ));
        for r in &s.rises_hpa {
            frame_sq += (f64::from(dnn.estimate_gf(r)?) - s.weight_gf).powi(2);
            frames += 1;
        }
    }
    let max_err =
        |pairs: &[(f64, f64)]| pairs.iter().map(|(w, e)| (e - w).abs()).fold(0.0, f64::max);
    let probe = held.first().map_or([0.0; 3], |(_, s)| s.mean_hpa());
    let ns = cost_ns(|| {
        std::hint::black_box(dnn.estimate_gf(std::hint::black_box(&probe)).ok());
    });

    let mut figures = vec![
        measured("weights", "weights recorded", steps.len() as f64, ""),
        measured("train_frames", "frames trained on", fit_frames as f64, ""),
        measured("heldout_weights", "weights held out", held.len() as f64, ""),
    ];
    let f = measured(
        "heldout_max_abs_error_gf",
        "held out: max |error|",
        max_err(&ours),
        "gf",
    );
    figures.push(target(
        paper(f, PAPER_MAX_ERROR_GF, PAPER_SOURCE),
        Target::AtMost(tolerance_gf),
    ));
    figures.push(measured(
        "heldout_mean_abs_error_gf",
        "held out: mean |error|",
        ours.iter().map(|(w, e)| (e - w).abs()).sum::<f64>() / ours.len() as f64,
        "gf",
    ));
    figures.push(measured(
        "heldout_frame_rmse_gf",
        "held out: RMSE per frame",
        (frame_sq / frames.max(1) as f64).sqrt(),
        "gf",
    ));
    figures.push(measured(
        "builtin_max_abs_error_gf",
        "built-in `sim` model, same weights: max |error|",
        max_err(&theirs),
        "gf",
    ));
    figures.push(measured(
        "estimate_ns",
        "cost per estimate (this machine, median)",
        ns,
        "ns",
    ));
    let points = |pairs: &[(f64, f64)]| pairs.to_vec();
    let plots = vec![
        Plot::Lines {
            title: "Held-out weights: estimate against weight".into(),
            x_label: "weight placed (gf)".into(),
            y_label: "estimate (gf)".into(),
            lines: vec![
                Line {
                    label: "your model".into(),
                    points: points(&ours),
                },
                Line {
                    label: "built-in sim model".into(),
                    points: points(&theirs),
                },
            ],
        },
        super::loss_plot(
            "Training loss",
            "epoch",
            "mean squared error (sigmoid output)",
            1,
            log.epoch_loss.iter().map(|l| f64::from(*l)),
        ),
    ];
    let held_out: Vec<String> = held
        .iter()
        .map(|(_, s)| crate::summary::number(s.weight_gf))
        .collect();
    let notes = vec![format!(
        "held out (never trained on): {} gf; rated range {}…{} gf",
        held_out.join(", "),
        crate::summary::number(lightest),
        crate::summary::number(heaviest)
    )];
    Ok(Trained {
        model: dnn,
        figures,
        plots,
        notes,
    })
}
