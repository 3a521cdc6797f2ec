//! The `handstack node` command on real devices: the part of a scene it names, opened as
//! `handstack run` opens it ([`crate::stack`]), run as a node until stopped.

use super::arm::{self, ArmNodeConfig};
use super::error::CellError;
use super::file::Part;
use super::hand::{self, HandNodeConfig};
use super::pad::{self, PadNodeConfig};
use super::{NodeArgs, tactile};
use crate::scene::NodeScene;
use crate::scene::parts::Locator;
use crate::stack::platform::Platform;
use crate::stop::Stop;
use crate::tap_to_move::TapToMoveConfig;
use hand_zenoh::node::Node;
use hand_zenoh::tactile::TactileInfo;

/// The fingertip's frame rate as a node: the grasp loop's default rate (100 Hz), the rate it
/// reads its fingertips at.
pub const FINGERTIP_RATE_HZ: f32 =
    1e6 / hand_control::grasp_loop::LoopConfig::DEFAULT_PERIOD_US as f32;

/// Runs `args.part` of `scene` on its real device as a node until `stop`; says what it did.
pub fn run_node(
    scene: &NodeScene,
    args: &NodeArgs,
    stop: &Stop,
    platform: &dyn Platform,
) -> Result<String, CellError> {
    let frame_id = super::frames::device_frame(&args.namespace);
    match args.part {
        Part::Arm => {
            let host = scene
                .file
                .arm
                .as_ref()
                .and_then(|a| a.get_ref().host.as_ref())
                .ok_or_else(|| CellError::Device {
                    device: "arm",
                    reason: "the scene's [arm] names no host".into(),
                })?;
            let mut ur = crate::stack::arm::open(host.get_ref())?;
            let node = Node::open(args.options())?;
            let config = ArmNodeConfig {
                frame_id: super::frames::base_frame(&args.namespace),
                ..ArmNodeConfig::default()
            };
            Ok(arm::run(&node, &mut ur, &config, stop)?.to_string())
        }
        Part::Fingertip => {
            let tip = crate::stack::fingertip::open(scene, platform)?;
            let node = Node::open(args.options())?;
            let info = TactileInfo {
                chip: "MS5611".into(),
                rate_hz: FINGERTIP_RATE_HZ,
                frame_id,
            };
            let frames = tactile::run(&node, tip, info, scene.force.clone(), stop)?;
            Ok(format!("{frames} frames"))
        }
        Part::Hand => {
            let (hand, port) = crate::stack::hand::scene_hand(scene)?;
            let grasp = scene
                .file
                .experiment
                .get_ref()
                .0
                .grasp
                .as_ref()
                .map(|g| g.get_ref());
            let config = crate::runs::grasp::loop_config(grasp, hand)?;
            let tip = crate::stack::fingertip::open(scene, platform)?;
            let servo = crate::stack::hand::open(hand, port)?;
            let node = Node::open(args.options())?;
            let hand_config = HandNodeConfig {
                rate_hz: 1e6 / config.period_us as f64,
                frame_id,
                force: scene.force.clone(),
                hand: crate::stack::hand::bus_label(port),
                recover: grasp.and_then(|g| g.recover.as_ref().map(|r| *r.get_ref())),
            };
            let report = hand::run(
                &node,
                tip,
                servo,
                platform.clock(),
                config,
                &hand_config,
                stop,
            )?;
            Ok(report.to_string())
        }
        Part::Pad => {
            let mut source = crate::stack::pad::open_scene(scene, platform)?;
            let node = Node::open(args.options())?;
            // With `cnn` among the scene's locators, each tap's window goes through the scene's
            // contact CNN (its `cnn_weights`, or the built-in paper variant of Al &
            // Martinez-Hernandez, §IV-A), cut where its training windows sat after the trigger.
            let mut cnn = if scene.locators().contains(&Locator::Cnn) {
                Some(scene.contact_cnn().map_err(|e| CellError::Device {
                    device: "estimators.contact",
                    reason: format!("the contact CNN: {e}"),
                })?)
            } else {
                None
            };
            let trigger = cnn.as_ref().map_or_else(
                TapToMoveConfig::default,
                crate::runs::tap_to_move::window_config,
            );
            let config = PadNodeConfig {
                rate_hz: crate::stack::pad::FRAME_RATE_HZ,
                frame_id,
                trigger,
                max_frames: None,
            };
            let mut locate = cnn.as_mut().map(pad::cnn_locator);
            let locate = locate.as_mut().map(|l| l as pad::Locate<'_>);
            let report = pad::run(&node, &mut source, locate, &config, stop)?;
            Ok(report.to_string())
        }
    }
}
