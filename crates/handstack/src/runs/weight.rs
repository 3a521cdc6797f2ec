//! The Table 1 protocol of Kim et al. 2020 (§2.2) on the user's own fingertip: the pad is
//! tared unloaded, then each weight is placed when the run asks for it, its pressures settle
//! and are averaged (the paper's "average measured values"), and the force DNN's estimate of
//! the average rise is compared with the weight.
//!
//! Collecting (`handstack collect`), the same questions record the training data of the
//! user's own force DNN instead: the tare and each weight as a label over the frames averaged,
//! only the weights no earlier session in the directory recorded.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::collect::Sessions;
use crate::error::{Ending, RunError};
use crate::prompt::Unanswered;
use crate::record::grasp::RawTopic;
use crate::record::{HAND_FRAME, Labelled, Recorder, now_ns};
use crate::scene::Scene;
use crate::scene::experiment::{WeighPlan, Weight};
use crate::scene::force::ForceNet;
use crate::{Line, Plot};
use hand_traits::{PressureFrame, TactileSource};

/// The heaviest weight an answer may name, gf (the scene's own limit).
const MAX_ANSWER_GF: f64 = 1000.0;
/// Answers that are not a weight before the run gives up on a question.
const MAX_TRIES: usize = 10;
/// The paper's largest Table 1 deviation, gf: Expect. Weight 118.83 on the 120 gf row.
pub(crate) const PAPER_MAX_ERROR_GF: f64 = 1.17;
pub(crate) const PAPER_SOURCE: &str =
    "Kim et al. 2020, Table 1 (Expect. Weight − weight, 120 gf row)";

/// The experiment's name in a collect session's labels.
pub const EXPERIMENT: &str = "weight";
/// The label of the unloaded pad's frames.
pub const TARE: &str = "tare";
/// The label of a weight's frames, its value the weight placed (gf).
pub const WEIGHT_GF: &str = "weight_gf";

/// Runs `[experiment.weight]` of `scene` on its real fingertip with its force DNN, or, in a
/// collect session ([`RunContext::collect`]), records the weights still to collect.
pub fn run(scene: &Scene, exp: &Weight, cx: &RunContext<'_>) -> Result<Part, RunError> {
    if let (Some(sessions), Some(recorder)) = (&cx.collect, cx.record) {
        let plan = to_collect(&exp.plan(), sessions);
        let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
        return collect(&mut tip, &plan, recorder, cx);
    }
    let model = scene.force.as_ref().ok_or_else(|| RunError::Device {
        device: "estimators.force",
        reason: "the scene names no force DNN".into(),
    })?;
    let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    weigh(&mut tip, model, &exp.plan(), cx)
}

/// `plan` without the weights `sessions` recorded already.
pub fn to_collect(plan: &WeighPlan, sessions: &Sessions) -> WeighPlan {
    WeighPlan {
        weights_gf: plan
            .weights_gf
            .iter()
            .copied()
            .filter(|&w| !sessions.has(EXPERIMENT, WEIGHT_GF, w))
            .collect(),
        ..plan.clone()
    }
}

/// The collect session: the tare before each weight of `plan` and the weight, each asked
/// for, settled, and labelled in `recorder` over the frames averaged.
pub fn collect<S>(
    source: &mut S,
    plan: &WeighPlan,
    recorder: &Recorder,
    cx: &RunContext<'_>,
) -> Result<Part, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let label = |name: &str, value: f64, s: &Settled| {
        recorder.label(
            HAND_FRAME,
            &Labelled {
                experiment: EXPERIMENT,
                name,
                value,
                start_ns: s.start_ns,
                end_ns: s.end_ns,
            },
        );
    };
    let plan = WeighPlan {
        tare_each_weight: true,
        ..plan.clone()
    };
    let n = plan.weights_gf.len();
    let mut raw = Some(RawTopic::new(recorder));
    walk(source, &plan, cx, &mut raw, "collect", |step| {
        match step {
            Step::Tare(t) => label(TARE, 0.0, t),
            Step::Weight {
                i, placed_gf, at, ..
            } => {
                label(WEIGHT_GF, placed_gf, at);
                cx.progress
                    .say(&format!("  weight {i} of {n}: {placed_gf} gf recorded"));
            }
        }
        Ok(())
    })?;
    let mut part = Part::default();
    part.figures.push(measured(
        "weights_collected",
        "weights collected",
        n as f64,
        "",
    ));
    part.notes.push(format!(
        "{n} weights recorded into {}",
        recorder.dir().display()
    ));
    Ok(part)
}

/// One weight of the series: what was placed and what the DNN made of it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Weighed {
    /// The weight placed, gf (the one asked for, or the one the answer named).
    placed_gf: f64,
    /// The DNN's estimate, gf.
    estimate_gf: f64,
}

/// The protocol on any fingertip of three sensors (`source`), estimated by `dnn`: the
/// questions go to `cx.progress` and are answered by `cx.prompter`; a stop at a question or
/// while the pad settles ends the run with that stop.
pub fn weigh<S>(
    source: &mut S,
    dnn: &ForceNet,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
) -> Result<Part, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let mut raw = cx.record.map(RawTopic::new);
    let n = plan.weights_gf.len();
    let mut series = Vec::with_capacity(n);
    walk(source, plan, cx, &mut raw, "series", |step| {
        let Step::Weight {
            i,
            placed_gf,
            tare,
            at,
        } = step
        else {
            return Ok(());
        };
        let rise_hpa: [f32; 3] =
            core::array::from_fn(|k| ((at.mean[k] - tare.mean[k]) / 100.0) as f32);
        let estimate_gf = f64::from(dnn.estimate_gf(&rise_hpa).map_err(|e| RunError::Device {
            device: "estimators.force",
            reason: e.to_string(),
        })?);
        cx.progress.say(&format!(
            "  weight {i} of {n}: {placed_gf} gf placed, {estimate_gf:.2} gf estimated (rises \
             {:.3}, {:.3}, {:.3} hPa)",
            rise_hpa[0], rise_hpa[1], rise_hpa[2]
        ));
        series.push(Weighed {
            placed_gf,
            estimate_gf,
        });
        Ok(())
    })?;
    Ok(part(&series, plan.tolerance_gf))
}

/// What [`walk`] has read.
enum Step<'a> {
    /// The unloaded pad, settled.
    Tare(&'a Settled),
    /// Weight `i` (1-based), placed and settled, and the tare it counts from.
    Weight {
        i: usize,
        placed_gf: f64,
        tare: &'a Settled,
        at: &'a Settled,
    },
}

/// Walks `plan`: asks for the tare (and, with `plan.tare_each_weight`, again before each
/// weight) and each weight, reads each settled window and hands it to `each`.
fn walk<S>(
    source: &mut S,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
    raw: &mut Option<RawTopic<'_>>,
    stage: &str,
    mut each: impl FnMut(Step<'_>) -> Result<(), RunError>,
) -> Result<(), RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let n = plan.weights_gf.len();
    cx.progress.stage("weight: tare", 0);
    let mut tare = tare_at(source, plan, cx, raw, 0)?;
    each(Step::Tare(&tare))?;
    cx.progress.stage(&format!("weight: {stage}"), n as u64);
    for (i, &asked) in plan.weights_gf.iter().enumerate() {
        if plan.tare_each_weight && i > 0 {
            tare = tare_at(source, plan, cx, raw, i)?;
            each(Step::Tare(&tare))?;
        }
        let question = format!(
            "Place {asked} gf on the fingertip, then press Enter (or type the weight you \
             placed, gf)."
        );
        let at = format!("weight {} of {n}", i + 1);
        let placed_gf = ask(cx, &question, Some(asked), &format!("at {at}"))?;
        let settled = settled_mean(source, plan, cx, raw, &at)?;
        each(Step::Weight {
            i: i + 1,
            placed_gf,
            tare: &tare,
            at: &settled,
        })?;
        cx.progress.advance(1);
    }
    Ok(())
}

/// Asks for the pad cleared before weight `i` (0-based; 0: the series' first tare) and reads
/// it settled.
fn tare_at<S>(
    source: &mut S,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
    raw: &mut Option<RawTopic<'_>>,
    i: usize,
) -> Result<Settled, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let (question, what) = if i == 0 {
        (
            "Clear the fingertip: nothing on the pad. Then press Enter.",
            "the tare".to_owned(),
        )
    } else {
        (
            "Lift the weight off: nothing on the pad. Then press Enter.",
            format!(
                "the tare before weight {} of {}",
                i + 1,
                plan.weights_gf.len()
            ),
        )
    };
    ask(cx, question, None, &format!("at {what}"))?;
    settled_mean(source, plan, cx, raw, &what)
}

/// Asks `question` until it is answered: Enter takes `default` (a weight) or just goes on
/// (`None`, a tare); a number is the weight placed. `at` says where in the series, for the
/// error of a question not answered (`at weight 3 of 13`).
fn ask(
    cx: &RunContext<'_>,
    question: &str,
    default: Option<f64>,
    at: &str,
) -> Result<f64, RunError> {
    cx.progress.say(question);
    for _ in 0..MAX_TRIES {
        let line = cx.prompter.answer(&cx.stop).map_err(|u| match u {
            Unanswered::Stopped(reason) => RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!("weight: stopped by {reason} {at}"),
            },
            Unanswered::Closed => RunError::Ended {
                ending: Ending::Failed,
                what: format!("weight: the input ended {at}, before it was answered"),
            },
        })?;
        let Some(asked) = default else {
            return Ok(0.0);
        };
        if line.is_empty() {
            return Ok(asked);
        }
        match line.parse::<f64>() {
            Ok(g) if g.is_finite() && (0.0..=MAX_ANSWER_GF).contains(&g) => return Ok(g),
            _ => cx.progress.say(&format!(
                "\"{line}\" is not a weight in gf (0…{MAX_ANSWER_GF}): press Enter for \
                 {asked} gf, or type the weight you placed."
            )),
        }
    }
    Err(RunError::Ended {
        ending: Ending::Failed,
        what: format!("weight: {MAX_TRIES} answers {at} and none a weight in gf"),
    })
}

/// A settled window: the mean pressure of each sensor, Pa, and the bag times of its first and
/// last frame.
struct Settled {
    mean: [f64; 3],
    start_ns: u64,
    end_ns: u64,
}

/// The mean pressure of each sensor over `plan.average_s` after `plan.settle_s` from the
/// first frame read (up to the first frame at or past the window's end); `what` settles (`the
/// tare`, `weight 3 of 13`), for the error of a stop.
fn settled_mean<S>(
    source: &mut S,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
    raw: &mut Option<RawTopic<'_>>,
    what: &str,
) -> Result<Settled, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let (mut t0, mut sum, mut frames) = (None, [0.0f64; 3], 0u32);
    let mut window = (0, 0);
    loop {
        if let Some(reason) = cx.stop.reason() {
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!("weight: stopped by {reason} while {what} settled"),
            });
        }
        let frame = source.read_frame()?;
        let t_ns = now_ns();
        if let Some(raw) = raw {
            raw.record(t_ns, &frame.pressure_pa);
        }
        let since_s = frame.t_us.saturating_sub(*t0.get_or_insert(frame.t_us)) as f64 * 1e-6;
        if since_s >= plan.settle_s {
            for (s, p) in sum.iter_mut().zip(frame.pressure_pa) {
                *s += f64::from(p);
            }
            if frames == 0 {
                window.0 = t_ns;
            }
            window.1 = t_ns;
            frames += 1;
        }
        if frames > 0 && since_s >= plan.settle_s + plan.average_s {
            return Ok(Settled {
                mean: sum.map(|s| s / f64::from(frames)),
                start_ns: window.0,
                end_ns: window.1,
            });
        }
    }
}

/// The series' figures and plot.
fn part(series: &[Weighed], tolerance_gf: f64) -> Part {
    let mut part = Part::default();
    part.figures.push(measured(
        "weights",
        "weights placed",
        series.len() as f64,
        "",
    ));
    for (i, w) in series.iter().enumerate() {
        let f = measured(
            &format!("weight{}_estimate_gf", i + 1),
            &format!("weight {} ({} gf): estimate", i + 1, w.placed_gf),
            w.estimate_gf,
            "gf",
        );
        part.figures
            .push(target(f, Target::Within(w.placed_gf, tolerance_gf)));
    }
    let errors: Vec<f64> = series
        .iter()
        .map(|w| (w.estimate_gf - w.placed_gf).abs())
        .collect();
    let worst = errors.iter().copied().fold(0.0, f64::max);
    let f = measured("max_abs_error_gf", "max |error|", worst, "gf");
    let f = paper(f, PAPER_MAX_ERROR_GF, PAPER_SOURCE);
    part.figures.push(target(f, Target::AtMost(tolerance_gf)));
    part.figures.push(measured(
        "mean_abs_error_gf",
        "mean |error|",
        errors.iter().sum::<f64>() / errors.len().max(1) as f64,
        "gf",
    ));
    let placed: Vec<f64> = series.iter().map(|w| w.placed_gf).collect();
    part.plots.push(Plot::Lines {
        title: "Weights on the fingertip: estimate against weight".into(),
        x_label: "weight placed (gf)".into(),
        y_label: "estimate (gf)".into(),
        lines: vec![
            Line {
                label: "weight placed".into(),
                points: placed.iter().map(|&g| (g, g)).collect(),
            },
            Line {
                label: "force DNN".into(),
                points: series
                    .iter()
                    .map(|w| (w.placed_gf, w.estimate_gf))
                    .collect(),
            },
        ],
    });
    part
}
