//! A cell beyond one process (feature `cell`): each part of a scene as a ROS 2 node on Zenoh
//! (hand-zenoh, rmw_zenoh's conventions), and a cell file that starts a router, the nodes as
//! separate processes, and a coordinator that runs seed 002's tap-to-move across them:
//! pad node → contact → coordinator → arm node.
//!
//! ```text
//! handstack node my-arm.toml --part arm --namespace /arm0      # peer of tcp/127.0.0.1:7447
//! handstack cell my-cell.toml                                   # router + nodes + coordinator
//! ```
//!
//! The runners here take devices, never make them: the `handstack` binary opens real ones
//! ([`crate::stack`]); a reproduction hands in simulated ones behind the same interfaces.
//!
//! - [`file`](mod@file): the cell file (`router`, `[[node]]`, `[coordinator.tap_to_move]`);
//! - [`tactile`], [`pad`], [`arm`], [`hand`]: one node per part, each until its [`Stop`];
//! - [`coordinator`]: the tap-to-move across the cell;
//! - [`launch`]: the router, the node processes and the coordinator of a cell file.

pub mod arm;
pub mod cli;
mod commanders;
pub mod coordinator;
mod error;
pub mod file;
pub mod hand;
pub mod launch;
pub mod outcome;
mod pace;
pub mod pad;
pub mod real;
pub mod tactile;

pub use error::CellError;
pub use file::{CellFile, NodeEntry, Part};
pub use pace::{Pacer, Stop};

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
