//! The grasp hold (seed 000 §6–7): hand-control's grasp loop (fingertip → contact estimate →
//! the paper's Mamdani controller → torque limit) closes the hand and keeps the grip for
//! `hold_s`, its torque limit inside the scene's band. [`run`] opens the scene's real devices;
//! [`hold`], [`summarise`] and [`plots`] take opened ones, so the papers' Table 5 grasp runs the
//! same loop on its simulated rig.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::error::RunError;
use crate::scene::Scene;
use crate::scene::experiment::Grasp;
use crate::{Line, Plot};
use hand_control::grasp_loop::{
    GraspLoop, LoopClock, LoopConfig, RebootableActuator, SETTLE_TOL_RAW, SETTLE_WINDOW_US, Sample,
    TorqueBand,
};
use hand_traits::{PressureFrame, TactileSource};

/// Seconds of each trace the plots show: closing, squeeze, lift at 3 s, start of the hold.
const TRACE_S: f64 = 10.0;
/// Grid of the control-surface plot, points per input.
const SURFACE_STEPS: usize = 21;

/// Runs `[experiment.grasp]` of `scene` on its real fingertip and hand: the sensors open first,
/// so a bus that cannot be opened fails before any servo command.
pub fn run(scene: &Scene, exp: &Grasp, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let config = loop_config(exp)?;
    let band = config.band;
    let tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    let servo = crate::stack::hand::open_scene(scene)?;
    let hold_s = *exp.hold_s.get_ref();
    cx.progress.stage("grasp: hold", 1);
    let log = hold(tip, servo, cx.platform.clock(), config, hold_s)?.log;
    cx.progress.advance(1);
    let mut part = Part::default();
    summarise("grasp", band, None, &log, &mut part);
    part.plots.extend(plots(vec![traces("grasp", &log)])?);
    Ok(part)
}

/// The torque band `lo…hi` as hand-control's, its error naming `what`.
pub fn band(lo: u16, hi: u16, what: &str) -> Result<TorqueBand, RunError> {
    TorqueBand::new(lo, hi).map_err(|e| RunError::Device {
        device: "grasp",
        reason: format!("{what}: {e}"),
    })
}

/// The grasp loop's configuration for `exp`: its torque band and closing goal over
/// hand-control's defaults.
pub fn loop_config(exp: &Grasp) -> Result<LoopConfig, RunError> {
    let [lo, hi] = *exp.torque_band.get_ref();
    let defaults = LoopConfig::new();
    Ok(LoopConfig {
        band: band(lo, hi, "grasp")?,
        goal_rad: exp
            .goal_rad
            .as_ref()
            .map_or(defaults.goal_rad, |g| *g.get_ref()),
        ..defaults
    })
}

/// What a hold leaves: the loop's log and the hand (for its own counters, such as the packets
/// a Protocol 2.0 hand sent).
#[derive(Debug)]
pub struct Held<A> {
    /// Every cycle of the hold.
    pub log: Vec<Sample<3>>,
    /// The hand, handed back.
    pub hand: A,
}

/// One hold: the paper's controller in `config.band` drives `hand` from `tip`'s frames on
/// `clock` until `until_s` (from the loop's start). A fault that sends the loop to its safe
/// state ends the hold with that fault.
pub fn hold<S, A, C>(
    tip: S,
    hand: A,
    clock: C,
    config: LoopConfig,
    until_s: f64,
) -> Result<Held<A>, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    S::Error: core::fmt::Debug,
    A: RebootableActuator,
    A::Error: core::fmt::Debug,
    C: LoopClock,
{
    let band = config.band;
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(band.min_raw(), band.max_raw());
    let mut l = GraspLoop::new(tip, policy, hand, clock, config).map_err(|e| RunError::Device {
        device: "grasp loop",
        reason: e.to_string(),
    })?;
    l.run_until((until_s * 1e6) as u64);
    if let Some(e) = l.events().first() {
        return Err(RunError::Device {
            device: "hand",
            reason: format!("loop went to its safe state: {:?}", e.fault),
        });
    }
    let (_, _, hand, _, log) = l.into_parts();
    Ok(Held { log, hand })
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
        title: "Seed 000 fuzzy grasp controller: control surface (center average)".into(),
        x_label: "pressure error (normalised)".into(),
        y_label: "error rate (normalised)".into(),
        z_label: "torque limit (0…1023)".into(),
        xs,
        ys,
        z,
    })
}
