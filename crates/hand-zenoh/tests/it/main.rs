//! hand-zenoh's integration tests, one binary: nodes on loopback Zenoh, checked against
//! independent ROS 2 code (rosbags, a Python rmw_zenoh client) and under bad input.

mod cell_latency;
mod common;
mod node_faults;
mod python;
mod ros_client;
mod ros_interop;
