//! A barometric fingertip as a node: hand-zenoh's [`TactileNode`] (`tactile/raw`, `touch`,
//! `sensor_info`, `tare`; `force` when the scene names a force DNN) read at a fixed rate until
//! stopped.

use super::error::CellError;
use crate::pace::Pacer;
use crate::scene::force::ForceNet;
use crate::stop::Stop;
use hand_control::grasp_loop::LoopConfig;
use hand_traits::{PressureFrame, TactileSource};
use hand_zenoh::node::Node;
use hand_zenoh::tactile::{TactileError, TactileInfo, TactileNode};

/// Frames a fingertip node with a force DNN tares itself over at start, unless the tare
/// service is called first: as many as the grasp loop's tare takes by default.
pub fn startup_tare_frames() -> u32 {
    LoopConfig::new().tare_cycles
}

/// Runs a fingertip node, publishing `force` from `force`'s network when given;
/// returns the frames published.
pub fn run<S, const N: usize>(
    node: &Node,
    source: S,
    info: TactileInfo,
    force: Option<ForceNet>,
    stop: &Stop,
) -> Result<u64, CellError>
where
    S: TactileSource<Frame = PressureFrame<N>>,
{
    let mut pacer = Pacer::new(f64::from(info.rate_hz));
    let mut tactile = TactileNode::new(node, source, info)?;
    if let Some(model) = force {
        tactile = tactile.with_force(node, model, startup_tare_frames())?;
    }
    let mut frames = 0;
    while !stop.is_set() {
        match tactile.step() {
            Ok(_) => frames += 1,
            Err(TactileError::Node(e)) => return Err(e.into()),
            Err(e) => return Err(CellError::device("fingertip", e.to_string())),
        }
        pacer.wait();
    }
    Ok(frames)
}
