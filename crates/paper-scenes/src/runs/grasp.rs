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

use super::RunContext;
use super::figure::{Target, measured, target};
use crate::Error;
use crate::error::device;
use crate::scene::PaperScene;
use crate::scene::experiments::Grasp;
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use handstack::runs::Part;
use handstack::runs::grasp::{band, hold, plots, summarise, traces};
use paper_experiments::grasp_rig;

const SOURCE: &str = "seed 000 Table 5 (fixtures/paper/seed000_table5_grasp_torque.csv)";

/// Runs the grasp experiment of `scene`.
pub fn run(scene: &PaperScene, exp: &Grasp, cx: &RunContext<'_>) -> Result<Part, Error> {
    let table5 = paper_fixtures::seed000::table5_grasp_torque()?;
    let hardware = scene
        .file
        .hand
        .as_ref()
        .is_some_and(|h| h.get_ref().serial_port.is_some());
    let objects = exp.objects.get_ref();
    let hold_s = *exp.hold_s.get_ref();
    let mut part = Part::default();
    let mut lines = Vec::new();
    cx.progress
        .stage("grasp: Table 5 objects", objects.len() as u64);
    for name in objects {
        let row = table5
            .iter()
            .find(|r| &r.object == name)
            .ok_or_else(|| device("grasp", format!("{name} is not in Table 5")))?;
        let (lo, hi) = (row.torque_min as u16, row.torque_max as u16);
        let band = band(lo, hi, name)?;
        let log = if hardware {
            real_hold(scene, cx, band, hold_s)?
        } else {
            let kind = ObjectKind::from_name(name)
                .ok_or_else(|| device("grasp", format!("no simulated object {name}")))?;
            let object = ObjectParams::calibrated(kind, lo, hi, &RigParams::default())?;
            let (o, l, _) = grasp_rig::hold_for(name, object, band, exp.seed, hold_s)
                .map_err(|e| device("grasp", format!("{name}: {e}")))?;
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
                    &format!("{name}: held {hold_s} s, no slip / crush / drop / fault (1 = yes)"),
                    f64::from(u8::from(held)),
                    "",
                ),
                Target::Between(1.0, 1.0),
            ));
            l.log().to_vec()
        };
        let source = format!("{SOURCE}: {lo}…{hi}, paper column = max");
        summarise(name, band, Some((f64::from(hi), &source)), &log, &mut part);
        lines.push(traces(name, &log));
        cx.progress.advance(1);
    }
    part.plots.extend(plots(lines)?);
    Ok(part)
}

/// One hold on the real hand and fingertip the scene names, on the platform's clock, with the
/// rig's loop configuration in `band`.
fn real_hold(
    scene: &PaperScene,
    cx: &RunContext<'_>,
    band: hand_control::grasp_loop::TorqueBand,
    hold_s: f64,
) -> Result<Vec<hand_control::grasp_loop::Sample<3>>, Error> {
    // The sensors first: a bus that cannot be opened fails before any servo command.
    let tip = handstack::stack::fingertip::open(&scene.scene, &*cx.platform)?;
    let hand = scene.file.hand.as_ref().map(|h| h.get_ref());
    let port = hand
        .and_then(|h| h.serial_port.as_ref())
        .map(|p| p.get_ref());
    let (Some(hand), Some(port)) = (hand, port) else {
        return Err(device("hand", "no serial_port"));
    };
    let servo = handstack::stack::hand::open(hand, port)?;
    Ok(hold(
        tip,
        servo,
        cx.platform.clock(),
        grasp_rig::config(band),
        hold_s,
    )?)
}
