//! Seed 000 §7, Table 5: the six objects grasped by the fuzzy loop. hand-control's grasp loop
//! (tactile source → contact estimate → the paper's Mamdani controller → torque limit) closes on
//! each object, the arm lifts at 3 s, the hold lasts `hold_s`.
//!
//! Simulated (no `serial_port`): the Table 5 world (`paper_experiments::grasp_rig`): the
//! Dynamixel driver speaking Protocol 2.0 to the servo-bus simulator, whose MX-28 drives
//! hand-sim's grasp physics, and the fingertip's three MS5611 chip models read by the real
//! driver, in simulated time — the code path of docs/grasping. With `[hand] serial_port`: the
//! real `ServoHand` on that port and the real MS5611s on the fingertip's `i2c_buses` (required:
//! a hardware grasp never reads a simulated fingertip), opened through the run's platform and
//! on its clock (Linux: the wall clock), `hold_s` per object.

use super::figure::{Target, measured, paper, target};
use super::{Part, RunContext};
use crate::error::RunError;
use crate::scene::Scene;
use crate::scene::experiment::Grasp;
use crate::{Line, Plot};
use hand_control::grasp_loop::{GraspLoop, LoopConfig, Sample, TorqueBand};
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use paper_experiments::grasp_rig::{self, SETTLE_TOL_RAW, SETTLE_WINDOW_US};

/// Seconds of each trace the plots show: closing, squeeze, lift at 3 s, start of the hold.
const TRACE_S: f64 = 10.0;
/// Grid of the control-surface plot, points per input.
const SURFACE_STEPS: usize = 21;
const SOURCE: &str = "seed 000 Table 5 (fixtures/paper/seed000_table5_grasp_torque.csv)";

/// Runs the grasp experiment of `scene`.
pub fn run(scene: &Scene, exp: &Grasp, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let table5 = paper_fixtures::seed000::table5_grasp_torque()?;
    let hand = scene.file.hand.as_ref().map(|h| h.get_ref().clone());
    let port = hand
        .as_ref()
        .and_then(|h| h.serial_port.as_ref().map(|p| p.get_ref().clone()));
    let objects = exp.objects.get_ref();
    let hold_s = *exp.hold_s.get_ref();
    let mut part = Part::default();
    let (mut torque_lines, mut pressure_lines) = (Vec::new(), Vec::new());
    cx.progress
        .stage("grasp: Table 5 objects", objects.len() as u64);
    for name in objects {
        let row = table5
            .iter()
            .find(|r| &r.object == name)
            .ok_or_else(|| RunError::Device {
                device: "grasp",
                reason: format!("{name} is not in Table 5"),
            })?;
        let (lo, hi) = (row.torque_min as u16, row.torque_max as u16);
        let band = TorqueBand::new(lo, hi).map_err(|e| RunError::Device {
            device: "grasp",
            reason: format!("{name}: {e}"),
        })?;
        let log =
            match (&hand, &port) {
                (Some(h), Some(port)) => real_hold(scene, cx, h, port, band, hold_s)?,
                _ => {
                    let kind = ObjectKind::from_name(name).ok_or_else(|| RunError::Device {
                        device: "grasp",
                        reason: format!("no simulated object {name}"),
                    })?;
                    let object = ObjectParams::calibrated(kind, lo, hi, &RigParams::default())?;
                    let (o, l, _) = grasp_rig::hold_for(name, object, band, exp.seed, hold_s)
                        .map_err(|e| RunError::Device {
                            device: "grasp",
                            reason: format!("{name}: {e}"),
                        })?;
                    let held = !(o.slipped || o.damaged || o.dropped) && o.faults == 0;
                    for (what, n) in [("sent", o.packets.sent), ("received", o.packets.received)] {
                        part.figures.push(measured(
                            &format!("{name}_packets_{what}"),
                            &format!("{name}: Protocol 2.0 packets {what} by the driver"),
                            n as f64,
                            "",
                        ));
                    }
                    part.figures.push(measured(
                        &format!("{name}_peak_force_n"),
                        &format!("{name}: peak pad force (sim truth)"),
                        o.peak_force_n,
                        "N",
                    ));
                    part.figures.push(target(
                        measured(
                            &format!("{name}_held"),
                            &format!(
                                "{name}: held {hold_s} s, no slip / crush / drop / fault (1 = yes)"
                            ),
                            f64::from(u8::from(held)),
                            "",
                        ),
                        Target::Between(1.0, 1.0),
                    ));
                    l.log().to_vec()
                }
            };
        summarise(name, (lo, hi), &log, &mut part);
        let t = |s: &Sample<3>| s.t_us as f64 * 1e-6;
        let early = || log.iter().filter(|s| t(s) <= TRACE_S);
        torque_lines.push(Line {
            label: name.clone(),
            points: early()
                .filter_map(|s| Some((t(s), f64::from(s.torque_raw?))))
                .collect(),
        });
        pressure_lines.push(Line {
            label: name.clone(),
            points: early()
                .filter_map(|s| Some((t(s), f64::from(s.estimate?.pressure_pa))))
                .collect(),
        });
        cx.progress.advance(1);
    }
    part.plots.push(Plot::Lines {
        title: "Grasp: torque limit sent (lift at 3 s)".into(),
        x_label: "time (s)".into(),
        y_label: "torque limit (0…1023)".into(),
        lines: torque_lines,
    });
    part.plots.push(Plot::Lines {
        title: "Grasp: mean pad pressure rise".into(),
        x_label: "time (s)".into(),
        y_label: "pressure rise (Pa)".into(),
        lines: pressure_lines,
    });
    part.plots.push(surface()?);
    Ok(part)
}

/// Settled torque (target: inside the Table 5 band), its window and the settling time.
fn summarise(name: &str, band: (u16, u16), log: &[Sample<3>], part: &mut Part) {
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
    let (lo, hi) = (f64::from(band.0), f64::from(band.1));
    let f = measured(
        &format!("{name}_settled_torque"),
        &format!(
            "{name}: settled torque limit (last {:.0} s)",
            window_us as f64 * 1e-6
        ),
        f64::from(st.settled_raw),
        "",
    );
    let f = paper(f, hi, &format!("{SOURCE}: {lo}…{hi}, paper column = max"));
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

/// One hold on the real hand: the loop on the platform's clock for `hold_s`.
fn real_hold(
    scene: &Scene,
    cx: &RunContext<'_>,
    hand: &crate::scene::parts::Hand,
    port: &str,
    band: TorqueBand,
    hold_s: f64,
) -> Result<Vec<Sample<3>>, RunError> {
    // The sensors first: a bus that cannot be opened fails before any servo command.
    let tip = crate::stack::fingertip::open_hardware(scene, &*cx.platform)?;
    let servo = crate::stack::hand::open(hand, port)?;
    let config = LoopConfig {
        band,
        ..grasp_rig::config(band)
    };
    let policy = fuzzy_mamdani::grasp_controller().with_torque_band(band.min_raw(), band.max_raw());
    let clock = cx.platform.clock();
    let mut l =
        GraspLoop::new(tip, policy, servo, clock, config).map_err(|e| RunError::Device {
            device: "grasp loop",
            reason: e.to_string(),
        })?;
    l.run_until((hold_s * 1e6) as u64);
    if let Some(e) = l.events().first() {
        return Err(RunError::Device {
            device: "hand",
            reason: format!("loop went to its safe state: {:?}", e.fault),
        });
    }
    Ok(l.log().to_vec())
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
