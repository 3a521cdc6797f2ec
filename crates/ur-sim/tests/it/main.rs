//! ur-sim's integration tests, one binary: the real ur_rtde (through ur-bridge's `UrArm`)
//! against the simulated controller, the `ur-sim` program running the README's CI job, and the
//! simulator under many, vanishing and garbage-sending clients.

mod abuse;
mod grid;
mod sim_bridge;
mod ur_sim_binary;
