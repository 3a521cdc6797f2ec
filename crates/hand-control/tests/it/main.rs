//! hand-control's integration tests, one binary: the driver against the simulated bus on a pty,
//! the status parser under arbitrary bytes, and the official ROBOTIS SDK and the README's CI job
//! against the simulator. (`tests/goals_alloc.rs` is apart: it installs a counting global
//! allocator.)

mod driver_vs_sim;
mod parser_fuzz;
mod sdk_python;
