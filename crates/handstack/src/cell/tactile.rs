//! A barometric fingertip as a node: hand-zenoh's [`TactileNode`] (`tactile/raw`, `touch`,
//! `sensor_info`, `tare`) read at a fixed rate until stopped.

use super::error::CellError;
use super::pace::{Pacer, Stop};
use hand_traits::{PressureFrame, TactileSource};
use hand_zenoh::node::Node;
use hand_zenoh::tactile::{TactileError, TactileInfo, TactileNode};

/// Runs a fingertip node; returns the frames published.
pub fn run<S, const N: usize>(
    node: &Node,
    source: S,
    info: TactileInfo,
    stop: &Stop,
) -> Result<u64, CellError>
where
    S: TactileSource<Frame = PressureFrame<N>>,
{
    let mut pacer = Pacer::new(f64::from(info.rate_hz));
    let mut tactile = TactileNode::new(node, source, info)?;
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
