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
use crate::collect::Sessions;
use crate::error::{Ending, RunError};
use crate::prompt::Unanswered;
use crate::record::{FingerTopic, Labelled};
use crate::scene::Scene;
use crate::scene::experiment::{Softness as SoftnessScene, class_name};
use crate::{Line, Plot};
use hand_control::grasp_loop::EndAction;
use hand_traits::Softness;
use std::time::{Duration, Instant};
use tactile_nets::softness::SoftnessNet;
use underactuated_hand::UnderactuatedHand;
use underactuated_hand::grasp::{Phase, Recorder};

/// How long a reading may take before the loop looks at its stop flag again.
const READ_WAIT: Duration = Duration::from_millis(50);
/// The opening speed of a release, as a multiple of the closing speed.
const OPEN_SPEEDUP: f64 = 4.0;
/// What a release may take beyond the travel at its speed.
const OPEN_MARGIN: Duration = Duration::from_secs(5);

/// The experiment's name in a collect session's labels.
pub const EXPERIMENT: &str = "softness";
/// The label of a grasp's window, its value the class asked for (0 soft, 1 moderate, 2 hard).
pub const CLASS: &str = "class";

/// How a grasp ended when it did not fill its window: the run's ending and what happened.
type Cut = (Ending, String);

/// One grasp's window.
struct Grasped {
    /// The series from first contact, flat: eight readings per sample.
    series: Vec<f32>,
    /// First contact t₁, s from the start of the close.
    first_contact_s: f64,
    /// The bag times of the first and last reading in the window, ns since the Unix epoch.
    start_ns: u64,
    end_ns: u64,
}

/// The hand, what ends a run on it, and where its readings are recorded.
struct Run<'a> {
    hand: UnderactuatedHand,
    plan: underactuated_hand::grasp::GraspPlan,
    cx: &'a RunContext<'a>,
    fingers: Option<FingerTopic<'a>>,
    start: Instant,
}

impl Run<'_> {
    fn fault(&self, e: &underactuated_hand::HandError) -> RunError {
        RunError::Ended {
            ending: Ending::Fault,
            what: format!(
                "hand: {} at {:.2} s; its close is leased, so the stepper stops within {} ms",
                e,
                self.start.elapsed().as_secs_f64(),
                underactuated_hand::LEASE.as_millis()
            ),
        }
    }

    /// Closes at the plan's speed and records the window from first contact: `Err(cut)` when
    /// a stop or an empty hand ended it first. The stepper keeps closing either way.
    fn grasp(&mut self) -> Result<Result<Grasped, Cut>, RunError> {
        let plan = self.plan;
        let cx = self.cx;
        cx.progress.stage("softness: closing", 0);
        let close_us = self.hand.now_us();
        self.hand
            .close_at(plan.closing_speed_mm_s)
            .map_err(|e| self.fault(&e))?;
        let mut rec = Recorder::new(plan, self.hand.now_us());
        let (mut counted, mut start_ns) = (0, 0);
        loop {
            if let Some(reason) = cx.stop.reason() {
                return Ok(Err((
                    Ending::Stopped(reason),
                    format!("softness: stopped by {reason}"),
                )));
            }
            let reading = self
                .hand
                .next_reading(READ_WAIT)
                .map_err(|e| self.fault(&e))?;
            let Some(r) = reading else { continue };
            let t_ns = match &mut self.fingers {
                Some(f) => f.record(&r.sample),
                None => crate::record::now_ns(),
            };
            match rec.push(r.t_us, r.sample) {
                Phase::Approaching => {}
                Phase::Recording(n) => {
                    if counted == 0 {
                        start_ns = t_ns;
                        cx.progress.stage(
                            "softness: recording from first contact",
                            plan.samples() as u64,
                        );
                    }
                    cx.progress.advance((n - counted) as u64);
                    counted = n;
                }
                Phase::Done => {
                    let t1 = rec.first_contact_us().unwrap_or(0);
                    return Ok(Ok(Grasped {
                        series: rec.series().to_vec(),
                        first_contact_s: t1.saturating_sub(close_us) as f64 * 1e-6,
                        start_ns: if counted == 0 { t_ns } else { start_ns },
                        end_ns: t_ns,
                    }));
                }
                Phase::Empty => {
                    return Ok(Err((
                        Ending::Failed,
                        format!(
                            "softness: no finger touched anything within {} s of closing (an \
                             empty hand)",
                            plan.approach_timeout_s
                        ),
                    )));
                }
            }
        }
    }

    /// Ends the run with `cut` after the scene's end action.
    fn cut(&mut self, on_end: EndAction, (ending, what): Cut) -> RunError {
        match finish(&mut self.hand, on_end, self.plan.closing_speed_mm_s) {
            Ok(left) => RunError::Ended {
                ending,
                what: format!(
                    "{what} at {:.2} s; hand {left}",
                    self.start.elapsed().as_secs_f64()
                ),
            },
            Err(e) => self.fault(&e),
        }
    }

    /// Asks for object `i` (from 0) of `n`, of `class`: Enter once it is in the open hand.
    fn ask(
        &mut self,
        on_end: EndAction,
        class: Softness,
        i: usize,
        n: usize,
    ) -> Result<(), RunError> {
        self.cx.progress.say(&format!(
            "Put a {} object in the hand ({} of {n}), then press Enter.",
            class_name(class),
            i + 1
        ));
        match self.cx.prompter.answer(&self.cx.stop) {
            Ok(_) => Ok(()),
            Err(Unanswered::Stopped(reason)) => Err(self.cut(
                on_end,
                (
                    Ending::Stopped(reason),
                    format!("softness: stopped by {reason} at object {} of {n}", i + 1),
                ),
            )),
            Err(Unanswered::Closed) => Err(self.cut(
                on_end,
                (
                    Ending::Failed,
                    format!(
                        "softness: the input ended at object {} of {n}, before it was answered",
                        i + 1
                    ),
                ),
            )),
        }
    }
}

/// Runs `[experiment.softness]` of `scene` on its real underactuated hand: one grasp of what
/// it holds, or each of its `objects` asked for in turn; in a collect session
/// ([`RunContext::collect`]), the objects still to collect, each grasp labelled with its class.
pub fn run(scene: &Scene, exp: &SoftnessScene, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let (hand_scene, _) = crate::stack::hand::scene_hand(scene)?;
    let on_end = hand_scene.on_end;
    let objects = exp.objects();
    let collecting = match (&cx.collect, cx.record) {
        (Some(sessions), Some(recorder)) => Some((to_collect(&objects, sessions), recorder)),
        _ => None,
    };
    let mut run = Run {
        hand: crate::stack::underactuated::open(scene)?,
        plan: exp.plan(),
        cx,
        fingers: cx.record.map(FingerTopic::new),
        start: Instant::now(),
    };
    let net = scene.softness_net();
    if let Some((asked, recorder)) = collecting {
        return collect(&mut run, on_end, &asked, recorder);
    }
    if objects.is_empty() {
        return one(&mut run, on_end, net, exp.expected());
    }
    let n = objects.len();
    let mut rows = Vec::with_capacity(n);
    for (i, &class) in objects.iter().enumerate() {
        run.ask(on_end, class, i, n)?;
        let g = match run.grasp()? {
            Ok(g) => g,
            Err(cut) => return Err(run.cut(on_end, cut)),
        };
        let got = classify(net, &g.series, cx)?;
        cx.progress.say(&format!(
            "  object {} of {n}: {} classified {}",
            i + 1,
            class_name(class),
            class_name(got.class)
        ));
        rows.push((class, got.class));
        if i + 1 < n {
            release(&mut run.hand, run.plan.closing_speed_mm_s).map_err(|e| run.fault(&e))?;
        }
    }
    let left =
        finish(&mut run.hand, on_end, run.plan.closing_speed_mm_s).map_err(|e| run.fault(&e))?;
    let hits = rows.iter().filter(|(a, b)| a == b).count();
    let mut part = Part::default();
    part.figures
        .push(measured("objects", "objects grasped", n as f64, ""));
    part.figures.push(measured(
        "classified_pct",
        "objects classified as asked",
        100.0 * hits as f64 / n as f64,
        "%",
    ));
    part.notes.push(format!(
        "asked → classified: {}",
        rows.iter()
            .map(|(a, b)| format!("{} → {}", class_name(*a), class_name(*b)))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    part.notes.push(format!("hand {left}"));
    Ok(part)
}

/// The objects of `objects` without those `sessions` recorded already.
pub fn to_collect(objects: &[Softness], sessions: &Sessions) -> Vec<Softness> {
    sessions.left(objects, EXPERIMENT, CLASS, |c| class_index(c) as f64)
}

/// A class's index: 0 soft, 1 moderate, 2 hard (the net's output order).
pub fn class_index(class: Softness) -> usize {
    Softness::ALL.iter().position(|c| *c == class).unwrap_or(0)
}

/// The collect session: each object asked for and grasped, its window labelled with its class.
fn collect(
    run: &mut Run<'_>,
    on_end: EndAction,
    asked: &[Softness],
    recorder: &crate::record::Recorder,
) -> Result<Part, RunError> {
    let n = asked.len();
    for (i, &class) in asked.iter().enumerate() {
        run.ask(on_end, class, i, n)?;
        let g = match run.grasp()? {
            Ok(g) => g,
            Err(cut) => return Err(run.cut(on_end, cut)),
        };
        recorder.label(
            crate::record::HAND_FRAME,
            &Labelled {
                experiment: EXPERIMENT,
                name: CLASS,
                value: class_index(class) as f64,
                start_ns: g.start_ns,
                end_ns: g.end_ns,
            },
        );
        run.cx.progress.say(&format!(
            "  grasp {} of {n}: {} recorded",
            i + 1,
            class_name(class)
        ));
        if i + 1 < n {
            release(&mut run.hand, run.plan.closing_speed_mm_s).map_err(|e| run.fault(&e))?;
        }
    }
    let left =
        finish(&mut run.hand, on_end, run.plan.closing_speed_mm_s).map_err(|e| run.fault(&e))?;
    let mut part = Part::default();
    part.figures.push(measured(
        "grasps_collected",
        "grasps collected",
        n as f64,
        "",
    ));
    part.notes.push(format!(
        "{n} grasps recorded into {}; hand {left}",
        recorder.dir().display()
    ));
    Ok(part)
}

/// `net`'s class of `series`.
fn classify(
    net: &SoftnessNet,
    series: &[f32],
    cx: &RunContext<'_>,
) -> Result<tactile_nets::softness::Assessment, RunError> {
    let a = net.assess(series).map_err(|e| RunError::Device {
        device: "estimators.softness",
        reason: e.to_string(),
    })?;
    if let Some(r) = cx.record {
        record_class(r, &a);
    }
    Ok(a)
}

/// One grasp of what the hand holds, classified, checked against `expected`.
fn one(
    run: &mut Run<'_>,
    on_end: EndAction,
    net: &SoftnessNet,
    expected: Option<Softness>,
) -> Result<Part, RunError> {
    let cx = run.cx;
    let g = run.grasp()?;
    // t₂ (or the ending): the actuator holds, then the scene's end action.
    let g = match g {
        Ok(g) => g,
        Err(cut) => return Err(run.cut(on_end, cut)),
    };
    let left =
        finish(&mut run.hand, on_end, run.plan.closing_speed_mm_s).map_err(|e| run.fault(&e))?;
    let plan = run.plan;
    let a = classify(net, &g.series, cx)?;
    if let Some(want) = expected.filter(|w| *w != a.class) {
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
    part.figures.push(measured(
        "first_contact_s",
        "first contact t₁, from the start of the close",
        g.first_contact_s,
        "s",
    ));
    part.figures.push(measured(
        "samples",
        &format!("samples from t₁ to t₁ + {} s", plan.window_s),
        a.samples as f64,
        "",
    ));
    let class = measured(
        "class",
        &format!(
            "class: {} (0 soft, 1 moderate, 2 hard)",
            class_name(a.class)
        ),
        class_index(a.class) as f64,
        "",
    );
    part.figures.push(match expected {
        Some(want) => target(class, Target::Within(class_index(want) as f64, 0.0)),
        None => class,
    });
    for (k, c) in Softness::ALL.iter().enumerate() {
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
    part.plots.push(series_plot(&g.series, plan.sample_hz));
    part.notes.push(format!("hand {left}"));
    Ok(part)
}

/// Records the classification as `/hand0/softness`.
fn record_class(r: &crate::record::Recorder, a: &tactile_nets::softness::Assessment) {
    let level = class_index(a.class);
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
            let open_at = release(hand, closing_mm_s)?;
            hand.disable()?;
            format!("released: opened to {open_at} steps from {at}, stepper outputs off")
        }
    })
}

/// Stops the close and runs the tendon back to open at [`OPEN_SPEEDUP`] times the closing
/// speed (the stepper stays powered); the position it reached.
fn release(
    hand: &mut UnderactuatedHand,
    closing_mm_s: f64,
) -> Result<i32, underactuated_hand::HandError> {
    let at = hand.stop()?;
    let mm = hand.config().drive.travel_mm(i64::from(at));
    let speed = closing_mm_s * OPEN_SPEEDUP;
    hand.set_speed(speed)?;
    let travel_s = mm.abs() / speed;
    hand.open_fully(Duration::from_secs_f64(travel_s) + OPEN_MARGIN)
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
