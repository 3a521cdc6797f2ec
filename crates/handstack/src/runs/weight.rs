//! The Table 1 protocol of Kim et al. 2020 (§2.2) on the user's own fingertip: the pad is
//! tared unloaded, then each weight is placed when the run asks for it, its pressures settle
//! and are averaged (the paper's "average measured values"), and the force DNN's estimate of
//! the average rise is compared with the weight.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::error::{Ending, RunError};
use crate::prompt::Unanswered;
use crate::record::grasp::RawTopic;
use crate::record::now_ns;
use crate::scene::Scene;
use crate::scene::experiment::{WeighPlan, Weight};
use crate::{Line, Plot};
use hand_traits::{PressureFrame, TactileSource};
use tactile_nets::force_dnn::StaticForceDnn;

/// The heaviest weight an answer may name, gf (the scene's own limit).
const MAX_ANSWER_GF: f64 = 1000.0;
/// Answers that are not a weight before the run gives up on a question.
const MAX_TRIES: usize = 10;
/// The paper's largest Table 1 deviation, gf: Expect. Weight 118.83 on the 120 gf row.
const PAPER_MAX_ERROR_GF: f64 = 1.17;
const PAPER_SOURCE: &str = "Kim et al. 2020, Table 1 (Expect. Weight − weight, 120 gf row)";

/// Runs `[experiment.weight]` of `scene` on its real fingertip with its force DNN.
pub fn run(scene: &Scene, exp: &Weight, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let model = scene.force_model().ok_or_else(|| RunError::Device {
        device: "estimators.force",
        reason: "the scene names no force DNN".into(),
    })?;
    let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    weigh(&mut tip, &model.dnn(), &exp.plan(), cx)
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
    dnn: &StaticForceDnn,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
) -> Result<Part, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let mut raw = cx.record.map(RawTopic::new);
    let n = plan.weights_gf.len();
    cx.progress.stage("weight: tare", 0);
    ask(
        cx,
        "Clear the fingertip: nothing on the pad. Then press Enter.",
        None,
        0,
        n,
    )?;
    let tare = settled_mean(source, plan, cx, &mut raw, 0, n)?;
    cx.progress.stage("weight: series", n as u64);
    let mut series = Vec::with_capacity(n);
    for (i, &asked) in plan.weights_gf.iter().enumerate() {
        let question = format!(
            "Place {asked} gf on the fingertip, then press Enter (or type the weight you \
             placed, gf)."
        );
        let placed_gf = ask(cx, &question, Some(asked), i + 1, n)?;
        let mean = settled_mean(source, plan, cx, &mut raw, i + 1, n)?;
        let rise_hpa: [f32; 3] = core::array::from_fn(|k| ((mean[k] - tare[k]) / 100.0) as f32);
        let estimate_gf = f64::from(dnn.estimate_gf(&rise_hpa).map_err(|e| RunError::Device {
            device: "estimators.force",
            reason: e.to_string(),
        })?);
        cx.progress.say(&format!(
            "  weight {} of {n}: {placed_gf} gf placed, {estimate_gf:.2} gf estimated (rises \
             {:.3}, {:.3}, {:.3} hPa)",
            i + 1,
            rise_hpa[0],
            rise_hpa[1],
            rise_hpa[2]
        ));
        cx.progress.advance(1);
        series.push(Weighed {
            placed_gf,
            estimate_gf,
        });
    }
    Ok(part(&series, plan.tolerance_gf))
}

/// Asks `question` until it is answered: Enter takes `default` (a weight) or just goes on
/// (`None`, the tare); a number is the weight placed. At question `i` of `n` (0: the tare).
fn ask(
    cx: &RunContext<'_>,
    question: &str,
    default: Option<f64>,
    i: usize,
    n: usize,
) -> Result<f64, RunError> {
    let at = if i == 0 {
        "at the tare".to_owned()
    } else {
        format!("at weight {i} of {n}")
    };
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

/// The mean pressure of each sensor, Pa, over `plan.average_s` after `plan.settle_s` from the
/// first frame read (up to the first frame at or past the window's end).
fn settled_mean<S>(
    source: &mut S,
    plan: &WeighPlan,
    cx: &RunContext<'_>,
    raw: &mut Option<RawTopic<'_>>,
    i: usize,
    n: usize,
) -> Result<[f64; 3], RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    let (mut t0, mut sum, mut frames) = (None, [0.0f64; 3], 0u32);
    loop {
        if let Some(reason) = cx.stop.reason() {
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!("weight: stopped by {reason} while weight {i} of {n} settled"),
            });
        }
        let frame = source.read_frame()?;
        if let Some(raw) = raw {
            raw.record(now_ns(), &frame.pressure_pa);
        }
        let since_s = frame.t_us.saturating_sub(*t0.get_or_insert(frame.t_us)) as f64 * 1e-6;
        if since_s >= plan.settle_s {
            for (s, p) in sum.iter_mut().zip(frame.pressure_pa) {
                *s += f64::from(p);
            }
            frames += 1;
        }
        if frames > 0 && since_s >= plan.settle_s + plan.average_s {
            return Ok(sum.map(|s| s / f64::from(frames)));
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
