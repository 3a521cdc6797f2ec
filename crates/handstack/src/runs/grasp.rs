//! The grasp hold (Kim et al. 2020, §5 and §7): hand-control's grasp loop (fingertip → contact
//! estimate → the paper's Mamdani controller → torque limit) closes the hand and keeps the grip
//! for `hold_s` from its first command, its torque limit inside the scene's band. [`run`] opens
//! the scene's real devices; [`hold`], [`summarise`] and [`plots`] take opened ones, so a
//! reproduction of the paper's Table 5 runs the same loop on its simulated rig.
//!
//! Every way a hold ends goes through one path: the hand gets the scene's end action
//! (`[hand] on_end`, hand-control's [`GraspLoop::end`]) in the cycle the ending is seen —
//! the end of the hold, a [`Stop`] (a signal), the first fault the scene's recovery does not
//! clear, a device lost, a hold that never commanded or never saw contact, a panic in a cycle
//! (caught, then the end action) — and a panic anywhere else between, through the loop's drop
//! guard (torque off).

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::error::{Ending, RunError};
use crate::record::grasp::GraspTopics;
use crate::record::{HAND_FRAME, Recorder};
use crate::scene::Scene;
use crate::scene::experiment::{Grasp, Recover};
use crate::scene::parts::Hand;
use crate::stop::Stop;
use crate::{Line, Plot};
use hand_control::grasp_loop::{
    EndReport, FaultKind, GraspLoop, LoopClock, LoopConfig, LoopFault, Mode, RELEASE_TOLERANCE_RAD,
    RebootableActuator, Recovery, SETTLE_TOL_RAW, SETTLE_WINDOW_US, Sample, TorqueBand,
};
use hand_traits::{GripperActuator, PressureFrame, SafeAction, TactileSource};

/// Seconds of each trace the plots show: closing, squeeze, lift at 3 s, start of the hold.
const TRACE_S: f64 = 10.0;
/// Grid of the control-surface plot, points per input.
const SURFACE_STEPS: usize = 21;
/// How long the loop may take to send its first command (its tare is 10 cycles, 0.1 s).
pub const FIRST_COMMAND_WITHIN_US: u64 = 2_000_000;
/// Time in the safe state before a recovery reboot.
pub const RECOVERY_COOLDOWN_US: u64 = 500_000;

/// Runs `[experiment.grasp]` of `scene` on its real fingertip and hand: the sensors open first,
/// so a bus that cannot be opened fails before any servo command.
pub fn run(scene: &Scene, exp: &Grasp, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let (hand, port) = crate::stack::hand::scene_hand(scene)?;
    let config = loop_config(Some(exp), hand)?;
    let band = config.band;
    let tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    let servo = crate::stack::hand::open(hand, port)?;
    let hold_s = *exp.hold_s.get_ref();
    cx.progress.stage("grasp: hold", 1);
    let label = crate::stack::hand::bus_label(port);
    let plan = Plan {
        hold: HoldFor::FirstCommand(hold_s),
        recover: exp.recover.as_ref().map(|r| *r.get_ref()),
        stop: &cx.stop,
        hand: &label,
        record: cx.record,
    };
    let held = hold(tip, servo, cx.platform.clock(), config, &plan)?;
    cx.progress.advance(1);
    let mut part = Part::default();
    summarise("grasp", band, None, &held.log, &mut part);
    part.plots.extend(plots(vec![traces("grasp", &held.log)])?);
    part.notes.push(format!("hand {}", held.left));
    Ok(part)
}

/// The torque band `lo…hi` as hand-control's, its error naming `what`.
pub fn band(lo: u16, hi: u16, what: &str) -> Result<TorqueBand, RunError> {
    TorqueBand::new(lo, hi).map_err(|e| RunError::Device {
        device: "grasp",
        reason: format!("{what}: {e}"),
    })
}

/// The grasp loop's configuration for `hand` and its grasp `exp` (none: a hand node's
/// defaults): the torque band, the closing goal and the end action over hand-control's
/// defaults (the recovery comes with the hold's [`Plan`]).
pub fn loop_config(exp: Option<&Grasp>, hand: &Hand) -> Result<LoopConfig, RunError> {
    let defaults = LoopConfig {
        end_action: hand.on_end,
        ..LoopConfig::new()
    };
    let Some(exp) = exp else {
        return Ok(defaults);
    };
    let [lo, hi] = *exp.torque_band.get_ref();
    Ok(LoopConfig {
        band: band(lo, hi, "grasp")?,
        goal_rad: exp
            .goal_rad
            .as_ref()
            .map_or(defaults.goal_rad, |g| *g.get_ref()),
        ..defaults
    })
}

/// The loop's recovery for a scene's `recover` (none: manual, so the first fault ends the run).
pub fn recovery(recover: Option<Recover>) -> Recovery {
    recover.map_or(Recovery::Manual, |r| Recovery::Automatic {
        cooldown_us: RECOVERY_COOLDOWN_US,
        max_reboots: r.attempts,
    })
}

/// How long a hold lasts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HoldFor {
    /// Seconds from the first command the loop sends (a scene's `hold_s`: the time spent
    /// opening devices and taring is not counted).
    FirstCommand(f64),
    /// Until this many seconds after the loop started (a simulated world's own schedule, such
    /// as Table 5's lift at 3 s).
    FromStart(f64),
}

/// What a hold is told besides the loop's configuration.
#[derive(Debug, Clone)]
pub struct Plan<'a> {
    /// How long it lasts.
    pub hold: HoldFor,
    /// The scene's recovery (`None`: the first fault ends the hold).
    pub recover: Option<Recover>,
    /// Ends the hold, checked every cycle.
    pub stop: &'a Stop,
    /// What the hand is called in messages (`servo bus /dev/ttyUSB0`).
    pub hand: &'a str,
    /// Where each cycle is recorded as it happens, if anywhere.
    pub record: Option<&'a Recorder>,
}

/// What a hold leaves: the loop's log, the hand (for its own counters, such as the packets
/// a Protocol 2.0 hand sent) and what the hand was left doing.
#[derive(Debug)]
pub struct Held<A> {
    /// Every cycle of the hold.
    pub log: Vec<Sample<3>>,
    /// The hand, handed back.
    pub hand: A,
    /// What the hand's end action left it doing, in words (`released (…), then torque off`).
    pub left: String,
}

/// The part a fault of `kind` came from, as a scene names it.
pub fn fault_device(kind: FaultKind) -> &'static str {
    match kind {
        FaultKind::Source | FaultKind::Estimate => "sensors.fingertip",
        FaultKind::Policy => "controller",
        _ => "hand",
    }
}

/// The I/O error `e` is, or was caused by: the link to the device is gone (a closed port, an
/// unplugged adapter), and no recovery can bring it back.
fn link_lost<'e>(e: &'e (dyn std::error::Error + 'static)) -> Option<&'e std::io::Error> {
    let mut cause = Some(e);
    while let Some(c) = cause {
        if let Some(io) = c.downcast_ref::<std::io::Error>() {
            return Some(io);
        }
        cause = c.source();
    }
    None
}

/// The actuator's own error inside a loop fault, if the fault is the actuator's.
fn actuator_error<SE, PE, AE>(fault: &LoopFault<SE, PE, AE>) -> Option<&AE>
where
    SE: core::fmt::Debug,
    PE: core::fmt::Debug,
    AE: core::fmt::Debug,
{
    match fault {
        LoopFault::Command(e)
        | LoopFault::State(e)
        | LoopFault::SafeStop(e)
        | LoopFault::Reboot(e) => Some(e),
        _ => None,
    }
}

/// A hand on the loop that gets `SafeAction::TorqueOff` if it is dropped before its end
/// action was sent (a panic in the run's own code unwinding through the hold).
struct Guarded<A: RebootableActuator> {
    hand: Option<A>,
}

impl<A: RebootableActuator> Drop for Guarded<A> {
    fn drop(&mut self) {
        if let Some(hand) = &mut self.hand {
            let _ = hand.safe_stop(SafeAction::TorqueOff);
        }
    }
}

impl<A: RebootableActuator> Guarded<A> {
    fn hand(&mut self) -> &mut A {
        // Taken only by `disarm`, which consumes the guard.
        self.hand
            .as_mut()
            .expect("the guarded hand is present until disarmed")
    }

    fn disarm(mut self) -> A {
        self.hand
            .take()
            .expect("the guarded hand is present until disarmed")
    }
}

impl<A: RebootableActuator> GripperActuator for Guarded<A> {
    type Error = A::Error;
    fn command(&mut self, cmd: &hand_traits::GripperCommand) -> Result<(), A::Error> {
        self.hand().command(cmd)
    }
    fn state(&mut self) -> Result<hand_traits::GripperState, A::Error> {
        self.hand().state()
    }
    fn safe_stop(&mut self, action: SafeAction) -> Result<(), A::Error> {
        self.hand().safe_stop(action)
    }
}

impl<A: RebootableActuator> RebootableActuator for Guarded<A> {
    fn reboot(&mut self) -> Result<(), A::Error> {
        self.hand().reboot()
    }
    fn enable_torque(&mut self) -> Result<(), A::Error> {
        self.hand().enable_torque()
    }
}

/// What an end action left the hand doing, in words: `released (…), then torque off`, or,
/// when it did not reach the hand, that, why (unless the link to it is gone: the run's own
/// error said so) and what the hand last had.
pub fn left_text<E: std::error::Error + 'static>(
    report: &EndReport<E>,
    last_torque_raw: Option<u16>,
) -> String {
    match (&report.state, &report.error) {
        (Some(state), _) => format!("{state}"),
        (None, error) => {
            let why = match error {
                Some(e) if link_lost(e).is_none() => format!(" ({e})"),
                _ => String::new(),
            };
            let last = last_torque_raw
                .map_or_else(String::new, |t| format!(", torque limit {t} of 0…1023"));
            format!(
                "end action `{}` did not reach it{why}: its servos keep their last command{last}",
                report.action.name()
            )
        }
    }
}

/// One hold: the paper's controller in `config.band` drives `hand` from `tip`'s frames on
/// `clock` for `plan.hold` (recovering as `plan.recover` says), then the hand gets
/// `config.end_action`. It ends early — the hand
/// getting its end action in that cycle — on `plan.stop`, on the first fault (or, with
/// `plan.recover`, a fault not cleared within its time, or the reboots used up), on a lost link,
/// when no command was sent within [`FIRST_COMMAND_WITHIN_US`], or when the hand reached its
/// closing goal without the fingertip seeing contact (nothing in the hand); each is a
/// [`RunError::Ended`] saying what happened, when and what the hand was left doing.
pub fn hold<S, A, C>(
    tip: S,
    hand: A,
    clock: C,
    config: LoopConfig,
    plan: &Plan<'_>,
) -> Result<Held<A>, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    S::Error: core::fmt::Debug + core::fmt::Display,
    A: RebootableActuator,
    A::Error: std::error::Error + 'static,
    C: LoopClock,
{
    let config = LoopConfig {
        recovery: recovery(plan.recover),
        ..config
    };
    let band = config.band;
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(band.min_raw(), band.max_raw());
    let guarded = Guarded { hand: Some(hand) };
    let mut l =
        GraspLoop::new(tip, policy, guarded, clock, config).map_err(|e| RunError::Device {
            device: "grasp loop",
            reason: e.to_string(),
        })?;
    // A panic in a cycle (a bug in the run's own code or a part's) ends the hold like any other
    // ending: the hand still gets the scene's end action.
    let ended = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        watch(&mut l, &config, plan)
    })) {
        Ok(ended) => ended,
        Err(payload) => {
            let first = l.log().first().map_or(0, |s| s.t_us);
            let at = l.log().last().map_or(0, |s| s.t_us.saturating_sub(first));
            Some((
                Ending::Bug,
                format!("a bug in handstack: {}", panic_text(payload.as_ref())),
                at,
            ))
        }
    };
    // The one shutdown path: whatever ended the hold, the end action in this cycle.
    let report = l.end();
    let last_torque = l.log().iter().rev().find_map(|s| s.torque_raw);
    let left = left_text(&report, last_torque);
    let (_, _, guarded, _, log) = l.into_parts();
    let hand = guarded.disarm();
    match ended {
        None => Ok(Held { log, hand, left }),
        Some((ending, what, at_us)) => Err(RunError::Ended {
            ending,
            what: format!(
                "{what} at {:.2} s of the grasp; hand {left}",
                at_us as f64 * 1e-6
            ),
        }),
    }
}

/// A panic's message, as `panic!` was given it.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned())
}

/// Runs `l`'s cycles until its hold ends; `None` at its planned end, else how it ended, what
/// happened and when (µs from the loop's start).
fn watch<S, P, A, C>(
    l: &mut GraspLoop<S, P, A, C, 3>,
    config: &LoopConfig,
    plan: &Plan<'_>,
) -> Option<(Ending, String, u64)>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    S::Error: core::fmt::Debug + core::fmt::Display,
    P: hand_traits::GraspPolicy,
    P::Error: core::fmt::Display,
    A: RebootableActuator,
    A::Error: std::error::Error + 'static,
    C: LoopClock,
{
    let t0 = l.clock_mut().now_us();
    let mut until = match plan.hold {
        HoldFor::FromStart(s) => Some(t0 + (s * 1e6) as u64),
        HoldFor::FirstCommand(_) => None,
    };
    let mut contact = false;
    let mut faults = FaultWatch::new(plan.recover, plan.hand);
    let mut topics = plan.record.map(GraspTopics::new);
    loop {
        if let Some(reason) = plan.stop.reason() {
            let at = l.log().last().map_or(t0, |s| s.t_us);
            return Some((
                Ending::Stopped(reason),
                format!("stopped by {reason}"),
                at - t0,
            ));
        }
        let s = *l.cycle();
        let at = s.t_us - t0;
        if let (Some(topics), Some(r)) = (&mut topics, plan.record) {
            topics.record(&s);
            if let Some(kind) = s.fault {
                // The cycle's first fault, in its part's words; whether it ends the run is
                // recorded with the run's ending.
                let what = l
                    .events()
                    .iter()
                    .rev()
                    .take_while(|e| e.cycle == s.cycle)
                    .last()
                    .map_or_else(|| kind_text(kind), |e| fault_text(&e.fault));
                r.fault(HAND_FRAME, fault_device(kind), &what, false);
            }
        }
        contact |= s.estimate.is_some_and(|e| e.in_contact);
        if let (None, Some(_), HoldFor::FirstCommand(hold_s)) = (until, s.torque_raw, plan.hold) {
            until = Some(s.t_us + (hold_s * 1e6) as u64);
        }
        if let Some(what) = faults.check(l, &s) {
            return Some((Ending::Fault, what, at));
        }
        if until.is_none() && at > FIRST_COMMAND_WITHIN_US {
            return Some((
                Ending::Failed,
                format!(
                    "grasp: the loop sent no command in {:.1} s (its tare did not finish)",
                    FIRST_COMMAND_WITHIN_US as f64 * 1e-6
                ),
                at,
            ));
        }
        let at_goal = s
            .goal_rad
            .zip(s.state)
            .is_some_and(|(g, st)| (st.position_rad - g).abs() <= RELEASE_TOLERANCE_RAD);
        if at_goal && !contact {
            return Some((
                Ending::Failed,
                "grasp: the hand closed to its goal without the fingertip seeing contact \
                 (nothing in the hand?)"
                    .to_owned(),
                at,
            ));
        }
        if until.is_some_and(|u| s.t_us + config.period_us >= u) {
            if matches!(s.mode, Mode::Safe | Mode::Halted) {
                return Some((
                    Ending::Fault,
                    format!(
                        "hand: {}: still in its safe state at the end of the hold",
                        plan.hand
                    ),
                    at,
                ));
            }
            if !contact {
                return Some((
                    Ending::Failed,
                    "grasp: the fingertip saw no contact during the hold (nothing in the hand?)"
                        .to_owned(),
                    at,
                ));
            }
            return None;
        }
    }
}

/// Decides, cycle by cycle, whether a loop's faults end its run: at once without a recovery
/// (or when the link to a device is lost), else when the loop is still not back to grasping
/// `within_s` after a fault, or its reboots are used up.
#[derive(Debug, Clone)]
pub struct FaultWatch<'a> {
    recover: Option<Recover>,
    hand: &'a str,
    unrecovered_since: Option<u64>,
}

impl<'a> FaultWatch<'a> {
    /// Watches with the scene's `recover`; `hand` names the hand in messages.
    pub fn new(recover: Option<Recover>, hand: &'a str) -> FaultWatch<'a> {
        FaultWatch {
            recover,
            hand,
            unrecovered_since: None,
        }
    }

    /// After cycle `s` of `l`: what ends the run, in words (`hand: servo bus …: …`), if
    /// something does.
    pub fn check<S, P, A, C>(
        &mut self,
        l: &GraspLoop<S, P, A, C, 3>,
        s: &Sample<3>,
    ) -> Option<String>
    where
        S: TactileSource<Frame = PressureFrame<3>>,
        S::Error: core::fmt::Debug + core::fmt::Display,
        P: hand_traits::GraspPolicy,
        P::Error: core::fmt::Display,
        A: RebootableActuator,
        A::Error: std::error::Error + 'static,
        C: LoopClock,
    {
        if let Some(kind) = s.fault {
            // This cycle's events, newest first; the last of them is what went wrong first.
            let events = || l.events().iter().rev().take_while(|e| e.cycle == s.cycle);
            if let Some(io) = events().find_map(|e| link_lost(actuator_error(&e.fault)?)) {
                return Some(format!("hand: {} lost: {io}", self.hand));
            }
            if self.recover.is_none() {
                let detail = events()
                    .last()
                    .map_or_else(|| kind_text(kind), |e| fault_text(&e.fault));
                return Some(match (kind, fault_device(kind)) {
                    // The fingertip's own errors name it.
                    (FaultKind::Source, _) => detail,
                    (_, "hand") => format!("hand: {}: {detail}", self.hand),
                    (_, device) => format!("{device}: {detail}"),
                });
            }
            self.unrecovered_since.get_or_insert(s.t_us);
        }
        match (s.mode, self.unrecovered_since, self.recover) {
            (Mode::Grasp | Mode::Tare, _, _) => self.unrecovered_since = None,
            (Mode::Halted, _, Some(r)) => {
                return Some(format!(
                    "hand: {}: still faulted after {} recovery reboots",
                    self.hand, r.attempts
                ));
            }
            (_, Some(since), Some(r)) if s.t_us - since > (r.within_s * 1e6) as u64 => {
                return Some(format!(
                    "hand: {}: not recovered within {} s of its fault",
                    self.hand, r.within_s
                ));
            }
            _ => {}
        }
        None
    }
}

/// A fault kind in words, for a fault whose event was not kept.
fn kind_text(kind: FaultKind) -> String {
    match kind {
        FaultKind::Source => "sensors.fingertip: no frame".to_owned(),
        FaultKind::Estimate => "the frame could not be used".to_owned(),
        FaultKind::Policy => "the controller chose no effort".to_owned(),
        FaultKind::Command => "a command was not taken".to_owned(),
        FaultKind::State => "the servos' state could not be read".to_owned(),
        FaultKind::Hardware(f) => format!("servo hardware error: {f}"),
        FaultKind::SafeStop => "the safe stop was not taken".to_owned(),
        FaultKind::Reboot => "a recovery reboot failed".to_owned(),
    }
}

/// A loop fault in words: the part's own error text, or the hardware faults the servos
/// report.
fn fault_text<SE, PE, AE>(fault: &LoopFault<SE, PE, AE>) -> String
where
    SE: core::fmt::Debug + core::fmt::Display,
    PE: core::fmt::Debug + core::fmt::Display,
    AE: core::fmt::Debug + core::fmt::Display,
{
    match fault {
        LoopFault::Source(e) => e.to_string(),
        LoopFault::Hardware(f) => format!("servo hardware error: {f}"),
        other => other.to_string(),
    }
}

/// The settled torque of one hold (target: inside `band`; `paper`: the published value and its
/// source), its window and the settling time, as figures named `{name}_…`.
pub fn summarise(
    name: &str,
    band: TorqueBand,
    paper_value: Option<(f64, &str)>,
    log: &[Sample<3>],
    part: &mut Part,
) {
    let window_us = SETTLE_WINDOW_US.min(log.last().map_or(0, |s| s.t_us) / 2);
    let Some(st) = hand_control::grasp_loop::settling(log, window_us, SETTLE_TOL_RAW) else {
        part.figures.push(measured(
            &format!("{name}_commands"),
            &format!("{name}: torque commands sent"),
            0.0,
            "",
        ));
        return;
    };
    let (lo, hi) = (f64::from(band.min_raw()), f64::from(band.max_raw()));
    let mut f = measured(
        &format!("{name}_settled_torque"),
        &format!(
            "{name}: settled torque limit (last {:.0} s)",
            window_us as f64 * 1e-6
        ),
        f64::from(st.settled_raw),
        "",
    );
    if let Some((value, source)) = paper_value {
        f = paper(f, value, source);
    }
    part.figures.push(target(f, Target::Between(lo, hi)));
    part.figures.push(measured(
        &format!("{name}_settling_time_s"),
        &format!("{name}: settling time (±{SETTLE_TOL_RAW} counts)"),
        st.settling_time_us as f64 * 1e-6,
        "s",
    ));
    part.figures.push(measured(
        &format!("{name}_window_min"),
        &format!("{name}: least torque in the window"),
        f64::from(st.window_raw.0),
        "",
    ));
    part.figures.push(measured(
        &format!("{name}_window_max"),
        &format!("{name}: greatest torque in the window"),
        f64::from(st.window_raw.1),
        "",
    ));
}

/// One hold's first seconds as plot lines labelled `label`: (torque limit sent, mean pressure
/// rise).
pub fn traces(label: &str, log: &[Sample<3>]) -> (Line, Line) {
    let t = |s: &Sample<3>| s.t_us as f64 * 1e-6;
    let early = || log.iter().filter(|s| t(s) <= TRACE_S);
    (
        Line {
            label: label.to_owned(),
            points: early()
                .filter_map(|s| Some((t(s), f64::from(s.torque_raw?))))
                .collect(),
        },
        Line {
            label: label.to_owned(),
            points: early()
                .filter_map(|s| Some((t(s), f64::from(s.estimate?.pressure_pa))))
                .collect(),
        },
    )
}

/// The plots of a grasp experiment: the holds' torque and pressure traces and the
/// controller's surface.
pub fn plots(traces: Vec<(Line, Line)>) -> Result<Vec<Plot>, RunError> {
    let (torque, pressure) = traces.into_iter().unzip();
    Ok(vec![
        Plot::Lines {
            title: "Grasp: torque limit sent (lift at 3 s)".into(),
            x_label: "time (s)".into(),
            y_label: "torque limit (0…1023)".into(),
            lines: torque,
        },
        Plot::Lines {
            title: "Grasp: mean pad pressure rise".into(),
            x_label: "time (s)".into(),
            y_label: "pressure rise (Pa)".into(),
            lines: pressure,
        },
        surface()?,
    ])
}

/// The paper's controller surface: torque limit over (pressure error, its rate), normalised.
fn surface() -> Result<Plot, RunError> {
    let engine = fuzzy_mamdani::grasp_engine::<f64>();
    let grid = fuzzy_mamdani::surface(&engine, SURFACE_STEPS).map_err(|e| RunError::Device {
        device: "controller",
        reason: e.to_string(),
    })?;
    let xs: Vec<f64> = grid.iter().step_by(SURFACE_STEPS).map(|p| p.0).collect();
    let ys: Vec<f64> = grid.iter().take(SURFACE_STEPS).map(|p| p.1).collect();
    // surface() is x-major (z for x_i is grid[i * n + j]); Plot::Surface wants z[iy][ix].
    let z = (0..SURFACE_STEPS)
        .map(|j| {
            (0..SURFACE_STEPS)
                .map(|i| grid[i * SURFACE_STEPS + j].2)
                .collect()
        })
        .collect();
    Ok(Plot::Surface {
        title: "Fuzzy grasp controller (Kim et al. 2020, §5): control surface (center average)"
            .into(),
        x_label: "pressure error (normalised)".into(),
        y_label: "error rate (normalised)".into(),
        z_label: "torque limit (0…1023)".into(),
        xs,
        ys,
        z,
    })
}
