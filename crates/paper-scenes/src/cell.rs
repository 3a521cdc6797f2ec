//! The papers' scenes as cell nodes (feature `cell`): `paper-scenes node SCENE --part P`
//! runs a part of a paper scene on its simulated device (the pad of seed 002 with the committed
//! CNN, the UR3 simulator through the real ur_rtde, the fingertip) with handstack's node
//! runners, and `paper-scenes cell CELL.toml` runs a cell of them (`handstack::cell`). The
//! nodes cannot tell these devices from hardware: only this module knows.

use crate::devices;
use crate::runs::RunContext;
use crate::scene::PaperScene;
use crate::scene::experiments::WindowPlacement;

use hand_zenoh::node::Node;
use hand_zenoh::tactile::TactileInfo;
use handstack::Outcome;
use handstack::cell::arm::{self, ArmNodeConfig};
use handstack::cell::hand::{self, HandNodeConfig};
use handstack::cell::launch::CellRun;
use handstack::cell::pad::{self, PadNodeConfig};
use handstack::cell::{CellError, CellFile, NodeArgs, Part, Stop, tactile};
use handstack::tap_to_move::TapToMoveConfig;
use paper_experiments::tap_run::{self, TAPS_PER_REGION};
use std::path::Path;
use tactile_nets::contact_cnn::ContactCnn;

use handstack::cell::real::FINGERTIP_RATE_HZ;

fn failed(device: &'static str, e: impl ToString) -> CellError {
    CellError::Device {
        device,
        reason: e.to_string(),
    }
}

/// The taps a pad scene schedules, and where its window sits.
fn tap_plan(scene: &PaperScene) -> (usize, WindowPlacement) {
    scene
        .tap()
        .map_or((TAPS_PER_REGION, WindowPlacement::Aligned), |t| {
            (*t.taps_per_region.get_ref(), t.window)
        })
}

/// Runs `args.part` of `scene` on its simulated device as a node until `stop`, its frames
/// read `sim_speed` × faster than real time.
pub fn run_node(
    scene: &PaperScene,
    args: &NodeArgs,
    sim_speed: f64,
    cx: &RunContext<'_>,
    stop: &Stop,
) -> Result<String, CellError> {
    let frame_id = handstack::cell::frames::device_frame(&args.namespace);
    match args.part {
        Part::Pad => {
            let (per_region, window) = tap_plan(scene);
            let taps = devices::pad::schedule(scene, per_region);
            let mut source = devices::pad::open(scene, taps).map_err(|e| failed("pad", e))?;
            let model = tap_run::locator_path(&cx.root);
            let mut cnn = ContactCnn::load(&model).map_err(|e| failed("contact CNN", e))?;
            let rate = scene.sim.imu_pad.clone().unwrap_or_default().sample_rate_hz;
            let config = PadNodeConfig {
                rate_hz: rate * sim_speed,
                frame_id,
                trigger: match window {
                    WindowPlacement::Aligned => tap_run::training_aligned(),
                    WindowPlacement::Trigger => TapToMoveConfig::default(),
                },
                max_frames: None,
            };
            let node = Node::open(args.options())?;
            let mut locate = pad::cnn_locator(&mut cnn);
            let report = pad::run(&node, &mut source, Some(&mut locate), &config, stop)?;
            Ok(report.to_string())
        }
        Part::Arm => {
            let mut stack = devices::arm::open(scene)?;
            let node = Node::open(args.options())?;
            let config = ArmNodeConfig {
                frame_id: handstack::cell::frames::base_frame(&args.namespace),
                ..ArmNodeConfig::default()
            };
            let report = arm::run(&node, &mut stack.arm, &config, stop)?;
            Ok(format!("{report} (arm at {})", stack.host))
        }
        Part::Fingertip => {
            let tip = devices::fingertip::open(scene, &*cx.stack.platform)
                .map_err(|e| failed("fingertip", e))?;
            let node = Node::open(args.options())?;
            let info = TactileInfo {
                chip: "MS5611".into(),
                rate_hz: FINGERTIP_RATE_HZ * sim_speed as f32,
                frame_id,
            };
            let force = scene.force.clone();
            Ok(format!(
                "{} frames",
                tactile::run(&node, tip, info, force, stop)?
            ))
        }
        Part::Hand => {
            // The first object of the scene's Table 5 grasp, in its Table 5 torque band.
            let exp = scene
                .file
                .experiment
                .get_ref()
                .grasp
                .as_ref()
                .ok_or_else(|| {
                    failed(
                        "hand",
                        "the scene has no [experiment.grasp] to take the object from",
                    )
                })?;
            let exp = exp.get_ref();
            let object = exp.objects.get_ref().first().cloned().unwrap_or_default();
            let table5 =
                paper_fixtures::seed000::table5_grasp_torque().map_err(|e| failed("Table 5", e))?;
            let row = table5
                .iter()
                .find(|r| r.object == object)
                .ok_or_else(|| failed("hand", format!("{object} is not in Table 5")))?;
            let band = handstack::runs::grasp::band(
                row.torque_min as u16,
                row.torque_max as u16,
                &object,
            )?;
            let stack = devices::grasp::open(scene, cx, &object, band, exp.seed)
                .map_err(|e| failed("hand", e))?;
            let config = HandNodeConfig {
                rate_hz: 1e6 / stack.config.period_us as f64 * sim_speed,
                frame_id,
                force: scene.force.clone(),
                hand: "simulated servo bus".to_owned(),
                recover: None,
            };
            let node = Node::open(args.options())?;
            let report = hand::run(
                &node,
                stack.tip,
                stack.hand,
                stack.clock,
                stack.config,
                &config,
                stop,
            )?;
            Ok(format!("{report} ({object})"))
        }
    }
}

/// The outcome of a cell run: handstack's figures, and how many of the taps the CNN located
/// in the region the pad node's scene tapped (its schedule, in order).
pub fn outcome(path: &Path, run: &CellRun) -> Outcome {
    let name = path.file_stem().unwrap_or_default().to_string_lossy();
    let mut o = handstack::cell::outcome::outcome(&name, run);
    if let Some(tapped) = tapped_regions(&run.cell) {
        let rows = &run.report.rows;
        // A contact's sequence number says which tap of the schedule it was.
        let right = rows
            .iter()
            .filter(|r| {
                usize::try_from(r.seq - 1)
                    .ok()
                    .and_then(|i| tapped.get(i))
                    .is_some_and(|t| *t == r.region)
            })
            .count();
        o.figures.push(handstack::runs::figure::measured(
            "tap_accuracy_pct",
            &format!("CNN region accuracy across processes, {} taps", rows.len()),
            100.0 * right as f64 / rows.len().max(1) as f64,
            "%",
        ));
    }
    o
}

/// The regions the pad node's scene taps, in order (`None` when it cannot be read).
pub fn tapped_regions(cell: &CellFile) -> Option<Vec<u16>> {
    let pad = &cell.coordinator.tap_to_move.pad;
    let entry = cell
        .nodes
        .iter()
        .find(|n| &n.namespace == pad && n.part == Part::Pad)?;
    let scene = PaperScene::load(&entry.scene).ok()?;
    let (per_region, _) = tap_plan(&scene);
    tap_run::schedule(scene.seed(), per_region)
        .iter()
        .map(|t| t.position().ok().map(|p| u16::from(p.region())))
        .collect()
}
