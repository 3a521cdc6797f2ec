//! A cell beyond one process (feature `cell`): each part of a scene as a ROS 2 node on Zenoh
//! (hand-zenoh, rmw_zenoh's conventions), and a cell file that starts a router, the nodes as
//! separate processes, and a coordinator that runs tap-to-move (Al & Martinez-Hernandez,
//! §IV-B) across them:
//! pad node → contact → coordinator → arm node.
//!
//! ```text
//! handstack node my-hand.toml                                  # its stack: /hand0, /pad0, /arm0
//! handstack node my-arm.toml --part arm --namespace /arm0      # peer of tcp/127.0.0.1:7447
//! handstack cell my-cell.toml                                   # router + nodes + coordinator
//! ```
//!
//! The runners here take devices, never make them: the `handstack` binary opens real ones
//! ([`crate::stack`]); a reproduction hands in simulated ones behind the same interfaces.
//!
//! - [`file`](mod@file): the cell file (`router`, `[[node]]`, `[coordinator.tap_to_move]`);
//! - [`tactile`], [`pad`], [`arm`], [`hand`]: one node per part, each until its [`Stop`];
//!   [`scene_parts`]: the parts a scene's stack runs;
//! - [`coordinator`]: the tap-to-move across the cell;
//! - [`launch`]: the router, the node processes and the coordinator of a cell file.

pub mod arm;
pub mod cli;
mod commanders;
pub mod coordinator;
mod error;
pub mod file;
pub mod frames;
pub mod hand;
pub mod launch;
pub mod outcome;
pub mod pad;
pub mod real;
pub mod tactile;
mod unreadable;

pub use crate::pace::Pacer;
pub use crate::stop::Stop;
pub use error::CellError;
pub use file::{CellFile, NodeEntry, Part};

use crate::scene::SceneOf;
use hand_zenoh::HashMode;
use hand_zenoh::config::SessionConfig;
use hand_zenoh::node::NodeOptions;

/// How a node process joins: the `node` command's options.
#[derive(Debug, Clone)]
pub struct NodeArgs {
    /// The part of the scene it runs.
    pub part: Part,
    /// Its namespace (`/arm0`).
    pub namespace: String,
    /// The router to connect to.
    pub connect: String,
    /// ROS domain id.
    pub domain_id: u32,
    /// Humble's `TypeHashNotSupported` keys instead of hashed ones.
    pub humble: bool,
}

impl NodeArgs {
    /// The node's options: named after its part, in its namespace, a peer of the router.
    pub fn options(&self) -> NodeOptions {
        let mut o = NodeOptions::new(&self.namespace, self.part.node_name());
        o.domain_id = self.domain_id;
        o.session = SessionConfig::peer(&self.connect);
        o.hash_mode = if self.humble {
            HashMode::Humble
        } else {
            HashMode::Rihs01
        };
        o
    }
}

/// The parts of `scene` a node runs when no part is named: its hand (servos and fingertip) or,
/// without one, its fingertip; its pad; its arm. (A `handstack` scene names the hardware of
/// every part it has, so each of these can be opened.)
pub fn scene_parts<X>(scene: &SceneOf<X>) -> Vec<Part> {
    let f = &scene.file;
    let mut parts = Vec::new();
    if f.hand.is_some() {
        parts.push(Part::Hand);
    } else if f.sensors.fingertip.is_some() {
        parts.push(Part::Fingertip);
    }
    if f.sensors.imu_pad.is_some() {
        parts.push(Part::Pad);
    }
    if f.arm.is_some() {
        parts.push(Part::Arm);
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::{Part, scene_parts};
    use crate::scene::NodeScene as Scene;

    #[test]
    fn a_scenes_parts_are_the_devices_it_names() {
        let tip = "title = \"t\"\n[sensors.fingertip]\nosr = 1024\n\
                   i2c_buses = [\"/dev/i2c-1\", \"/dev/i2c-2\", \"/dev/i2c-3\"]\n";
        // A node's scene: an arm, no experiment needed.
        let rest = "[arm]\nmodel = \"ur3\"\nhost = \"192.168.0.10\"\n";
        let scene = Scene::parse("t.toml", &format!("{tip}{rest}")).unwrap();
        assert_eq!(scene_parts(&scene), [Part::Fingertip, Part::Arm]);
        let pad = "[sensors.imu_pad]\ni2c_bus = \"/dev/i2c-4\"\n";
        let scene = Scene::parse("t.toml", &format!("{tip}{pad}{rest}")).unwrap();
        assert_eq!(scene_parts(&scene), [Part::Fingertip, Part::Pad, Part::Arm]);
    }
}
