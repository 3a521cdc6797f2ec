//! hand-zenoh: a tactile hand stack on Zenoh, following ROS 2's rmw_zenoh conventions, so a
//! ROS 2 node with `RMW_IMPLEMENTATION=rmw_zenoh_cpp` sees our topics and calls our services
//! without a bridge.
//!
//! - [`msg`]: the messages (standard ROS 2 types where they fit, `handstack_msgs` for ours),
//!   each declared once with its CDR encoding ([`cdr`]) and type description ([`types`]);
//! - [`types`]: RIHS01 type hashes (REP 2011) and DDS type names; [`HashMode::Humble`]
//!   writes `TypeHashNotSupported` for ROS 2 Humble;
//! - [`keys`], [`attachment`]: rmw_zenoh's key expressions, liveliness tokens, GIDs and the
//!   sequence number / timestamp / GID attachment;
//! - [`force`]: a force estimator's output as the device's `force` topic;
//! - [`node`]: nodes, publishers, subscriptions, services and clients over a Zenoh session
//!   ([`config`]: peer of a router on `tcp/127.0.0.1:7447`, multicast scouting off, TCP only).
//!
//! Feature `node` (default) is the Zenoh layer: [`node`], [`config`], [`force`], [`tactile`].
//! Without it the crate is the messages alone — their CDR, type hashes, `ros2msg` definitions
//! ([`msg::definition`]) and conversions — with no Zenoh to build (a recorder writing these
//! messages to a file needs no network).
//!
//! The README lists the topic layout and shows a ROS 2 user how to see the topics.
#![cfg_attr(feature = "node", doc = include_str!("../README.md"))]
#![forbid(unsafe_code)]

pub mod attachment;
pub mod cdr;
#[cfg(feature = "node")]
pub mod config;
pub mod convert;
mod error;
#[cfg(feature = "node")]
pub mod force;
pub mod keys;
pub mod msg;
#[cfg(feature = "node")]
pub mod node;
#[cfg(feature = "node")]
pub mod tactile;
pub mod types;

pub use error::NodeError;
pub use types::HashMode;
