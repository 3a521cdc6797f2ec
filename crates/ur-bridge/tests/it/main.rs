//! ur-bridge's integration tests, one binary (feature `sim`): the real ur_rtde through the
//! bridge against the simulated controller, the `ur-sim` binary and the README's CI job, and the
//! simulator under many, vanishing and garbage-sending clients.

mod abuse;
mod sim_bridge;
mod ur_sim_binary;
