//! Seed 000 §7, Table 5: the six objects grasped by the fuzzy loop. hand-control's grasp loop
//! (tactile source → contact estimate → the paper's Mamdani controller → torque limit) closes on
//! each object, the arm lifts at 3 s, the hold lasts `hold_s`.
//!
//! The runner asks `devices::grasp` for each object's stack (fingertip, hand, clock, loop
//! configuration) and runs handstack's hold on it: the same loop whether the stack is the
//! Table 5 world (docs/grasping's code path) or the scene's real devices. Where the stack has a
//! world to observe, the object's fate (peak force, slipped / crushed / dropped) is reported
//! beside the loop's own figures.

use super::RunContext;
use super::figure::{Target, measured, target};
use crate::Error;
use crate::devices::grasp;
use crate::error::device;
use crate::scene::PaperScene;
use crate::scene::experiments::Grasp;
use hand_control::grasp_loop::EndAction;
use handstack::runs::Part;
use handstack::runs::grasp::{HoldFor, Plan, band, hold, plots, summarise, traces};
use paper_experiments::grasp_rig::LIFT_AT_S;

const SOURCE: &str = "seed 000 Table 5 (fixtures/paper/seed000_table5_grasp_torque.csv)";

/// Runs the grasp experiment of `scene`: per object, close, lift at 3 s, hold `hold_s`.
pub fn run(scene: &PaperScene, exp: &Grasp, cx: &RunContext<'_>) -> Result<Part, Error> {
    let table5 = paper_fixtures::seed000::table5_grasp_torque()?;
    let objects = exp.objects.get_ref();
    let hold_s = *exp.hold_s.get_ref();
    let mut part = Part::default();
    let mut lines = Vec::new();
    let label = scene
        .file
        .hand
        .as_ref()
        .and_then(|h| h.get_ref().serial_port.as_ref())
        .map_or_else(
            || "simulated servo bus".to_owned(),
            |p| handstack::stack::hand::bus_label(p.get_ref()),
        );
    cx.progress
        .stage("grasp: Table 5 objects", objects.len() as u64);
    for name in objects {
        let row = table5
            .iter()
            .find(|r| &r.object == name)
            .ok_or_else(|| device("grasp", format!("{name} is not in Table 5")))?;
        let (lo, hi) = (row.torque_min as u16, row.torque_max as u16);
        let band = band(lo, hi, name)?;
        let stack = grasp::open(scene, cx, name, band, exp.seed)?;
        // The Table 5 protocol ends holding: the object's fate is judged at the hold's end
        // (lift at 3 s from the world's start, then `hold_s`).
        let plan = Plan {
            hold: HoldFor::FromStart(LIFT_AT_S + hold_s),
            recover: None,
            stop: &cx.stop,
            hand: &label,
            record: None,
        };
        let config = hand_control::grasp_loop::LoopConfig {
            end_action: EndAction::Hold,
            ..stack.config
        };
        let held = hold(stack.tip, stack.hand, stack.clock, config, &plan)?;
        let packets = held.hand.packet_counts();
        for (what, n) in [("sent", packets.sent), ("received", packets.received)] {
            part.figures.push(measured(
                &format!("{name}_packets_{what}"),
                &format!("{name}: Protocol 2.0 packets {what} by the driver"),
                n as f64,
                "",
            ));
        }
        if let Some(env) = &stack.environment {
            let fate = env.fate()?;
            part.figures.push(measured(
                &format!("{name}_peak_force_n"),
                &format!("{name}: peak pad force (sim truth)"),
                fate.peak_force_n,
                "N",
            ));
            part.figures.push(target(
                measured(
                    &format!("{name}_held"),
                    &format!("{name}: held {hold_s} s, no slip / crush / drop / fault (1 = yes)"),
                    f64::from(u8::from(!fate.lost)),
                    "",
                ),
                Target::Between(1.0, 1.0),
            ));
        }
        let source = format!("{SOURCE}: {lo}…{hi}, paper column = max");
        summarise(
            name,
            band,
            Some((f64::from(hi), &source)),
            &held.log,
            &mut part,
        );
        lines.push(traces(name, &held.log));
        cx.progress.advance(1);
    }
    part.plots.extend(plots(lines)?);
    Ok(part)
}
