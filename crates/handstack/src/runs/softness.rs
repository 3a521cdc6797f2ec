//! The softness experiment (the underactuated-hand softness paper, §3.1–3.3) on a real
//! underactuated hand: close at constant velocity, open loop; record the four forces and four
//! distal angles from first contact t₁ for the window (14 s) at 10 Hz; hold (t₂, the
//! actuator's steady state); classify with tactile-nets' built-in softness net.
//!
//! Every way it ends goes through one path: the hand gets the scene's end action
//! (`[hand] on_end`): `release` runs the tendon back to where the run found it, then turns the
//! driver's outputs off; `hold` keeps the stepper where it stopped, powered; `torque_off` stops
//! it and turns the outputs off — in the reading the ending is seen: the end of the window, a
//! [`Stop`](crate::stop::Stop) (a signal), an empty grasp. A board that is lost cannot be told
//! anything: its close is leased (underactuated-hand's `LEASE`), so the stepper stops on its own
//! within half a second.

use super::figure::{Target, measured, target};
use super::{Part, RunContext};
use crate::error::{Ending, RunError};
use crate::record::FingerTopic;
use crate::scene::Scene;
use crate::scene::experiment::{Softness, class_name};
use crate::{Line, Plot};
use hand_control::grasp_loop::EndAction;
use std::time::{Duration, Instant};
use tactile_nets::pretrained::SOFTNESS;
use underactuated_hand::UnderactuatedHand;
use underactuated_hand::grasp::{Phase, Recorder};

/// How long a reading may take before the loop looks at its stop flag again.
const READ_WAIT: Duration = Duration::from_millis(50);
/// The opening speed of a release, as a multiple of the closing speed.
const OPEN_SPEEDUP: f64 = 4.0;
/// What a release may take beyond the travel at its speed.
const OPEN_MARGIN: Duration = Duration::from_secs(5);

/// Runs `[experiment.softness]` of `scene` on its real underactuated hand.
pub fn run(scene: &Scene, exp: &Softness, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let (hand_scene, _) = crate::stack::hand::scene_hand(scene)?;
    let on_end = hand_scene.on_end;
    let plan = exp.plan();
    let mut hand = crate::stack::underactuated::open(scene)?;
    let fault = |e: &underactuated_hand::HandError, at: f64| RunError::Ended {
        ending: Ending::Fault,
        what: format!(
            "hand: {} at {at:.2} s; its close is leased, so the stepper stops within {} ms",
            e,
            underactuated_hand::LEASE.as_millis()
        ),
    };
    cx.progress.stage("softness: closing", 0);
    let start = Instant::now();
    hand.close_at(plan.closing_speed_mm_s)
        .map_err(|e| fault(&e, 0.0))?;
    let mut rec = Recorder::new(plan, hand.now_us());
    let mut fingers = cx.record.map(FingerTopic::new);
    let mut counted = 0;
    let ending = loop {
        if let Some(reason) = cx.stop.reason() {
            break Some((
                Ending::Stopped(reason),
                format!("softness: stopped by {reason}"),
            ));
        }
        let reading = hand
            .next_reading(READ_WAIT)
            .map_err(|e| fault(&e, start.elapsed().as_secs_f64()))?;
        let Some(r) = reading else { continue };
        if let Some(f) = &mut fingers {
            f.record(&r.sample);
        }
        match rec.push(r.t_us, r.sample) {
            Phase::Approaching => {}
            Phase::Recording(n) => {
                if counted == 0 {
                    cx.progress.stage(
                        "softness: recording from first contact",
                        plan.samples() as u64,
                    );
                }
                cx.progress.advance((n - counted) as u64);
                counted = n;
            }
            Phase::Done => break None,
            Phase::Empty => {
                break Some((
                    Ending::Failed,
                    format!(
                        "softness: no finger touched anything within {} s of closing (an empty \
                         hand)",
                        plan.approach_timeout_s
                    ),
                ));
            }
        }
    };
    // t₂ (or the ending): the actuator holds, then the scene's end action.
    let left = finish(&mut hand, on_end, plan.closing_speed_mm_s)
        .map_err(|e| fault(&e, start.elapsed().as_secs_f64()))?;
    if let Some((ending, what)) = ending {
        return Err(RunError::Ended {
            ending,
            what: format!(
                "{what} at {:.2} s; hand {left}",
                start.elapsed().as_secs_f64()
            ),
        });
    }
    let a = SOFTNESS
        .assess(rec.series())
        .map_err(|e| RunError::Device {
            device: "estimators.softness",
            reason: e.to_string(),
        })?;
    if let Some(r) = cx.record {
        record_class(r, &a);
    }
    if let Some(want) = exp.expected().filter(|w| *w != a.class) {
        return Err(RunError::Ended {
            ending: Ending::Failed,
            what: format!(
                "softness: the hand classified the object {} (mean outputs soft {:.3}, moderate \
                 {:.3}, hard {:.3}), the scene expects {}; hand {left}",
                class_name(a.class),
                a.scores[0],
                a.scores[1],
                a.scores[2],
                class_name(want)
            ),
        });
    }
    let mut part = Part::default();
    let t1 = rec.first_contact_us().unwrap_or(0) as f64 * 1e-6;
    part.figures.push(measured(
        "first_contact_s",
        "first contact t₁, from the start of the close",
        t1,
        "s",
    ));
    part.figures.push(measured(
        "samples",
        &format!("samples from t₁ to t₁ + {} s", plan.window_s),
        a.samples as f64,
        "",
    ));
    let index = hand_traits::Softness::ALL
        .iter()
        .position(|c| *c == a.class)
        .unwrap_or(0);
    let class = measured(
        "class",
        &format!(
            "class: {} (0 soft, 1 moderate, 2 hard)",
            class_name(a.class)
        ),
        index as f64,
        "",
    );
    part.figures.push(match exp.expected() {
        Some(want) => {
            let w = hand_traits::Softness::ALL
                .iter()
                .position(|c| *c == want)
                .unwrap_or(0);
            target(class, Target::Within(w as f64, 0.0))
        }
        None => class,
    });
    for (k, c) in hand_traits::Softness::ALL.iter().enumerate() {
        part.figures.push(measured(
            &format!("score_{}", class_name(*c)),
            &format!("mean output, {}", class_name(*c)),
            f64::from(a.scores[k]),
            "",
        ));
    }
    part.figures.push(measured(
        "readings_outside_training_range",
        "readings outside the range the net was trained on",
        a.readings_outside as f64,
        "",
    ));
    part.plots.push(series_plot(rec.series(), plan.sample_hz));
    part.notes.push(format!("hand {left}"));
    Ok(part)
}

/// Records the classification as `/hand0/softness`.
fn record_class(r: &crate::record::Recorder, a: &tactile_nets::softness::Assessment) {
    let level = hand_traits::Softness::ALL
        .iter()
        .position(|c| *c == a.class)
        .unwrap_or(0);
    let topic = r.topic::<hand_zenoh::msg::handstack_msgs::Softness>(&format!(
        "{}/softness",
        crate::record::HAND_NS
    ));
    let t = crate::record::now_ns();
    r.write(
        topic,
        t,
        &hand_zenoh::msg::handstack_msgs::Softness {
            header: hand_zenoh::convert::header(t as i64, crate::record::HAND_FRAME),
            level: level as u8,
            label: class_name(a.class).to_owned(),
            scores: a.scores,
        },
    );
}

/// Applies `on_end` to the hand; what it was left doing, in words.
fn finish(
    hand: &mut UnderactuatedHand,
    on_end: EndAction,
    closing_mm_s: f64,
) -> Result<String, underactuated_hand::HandError> {
    let at = hand.stop()?;
    let mm = hand.config().drive.travel_mm(i64::from(at));
    Ok(match on_end {
        EndAction::Hold => format!("holds at {at} steps ({mm:.2} mm of tendon), stepper powered"),
        EndAction::TorqueOff => {
            hand.disable()?;
            format!("stopped at {at} steps ({mm:.2} mm of tendon), stepper outputs off")
        }
        EndAction::Release => {
            let speed = closing_mm_s * OPEN_SPEEDUP;
            hand.set_speed(speed)?;
            let travel_s = mm.abs() / speed;
            let open_at = hand.open_fully(Duration::from_secs_f64(travel_s) + OPEN_MARGIN)?;
            hand.disable()?;
            format!("released: opened to {open_at} steps from {at}, stepper outputs off")
        }
    })
}

/// The recorded series, forces and angles against time from first contact.
fn series_plot(series: &[f32], sample_hz: f64) -> Plot {
    let names = tactile_nets::softness::VARIABLE_NAMES;
    Plot::Lines {
        title: "Grasp from first contact".into(),
        x_label: "time from t₁ (s)".into(),
        y_label: "force (N) / distal angle (°)".into(),
        lines: (0..8)
            .map(|v| Line {
                label: names[v].to_owned(),
                points: series
                    .chunks_exact(8)
                    .enumerate()
                    .map(|(k, s)| (k as f64 / sample_hz, f64::from(s[v])))
                    .collect(),
            })
            .collect(),
    }
}
