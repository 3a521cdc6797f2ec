//! dxl-sim's integration tests, one binary: `hand-control`'s driver against the simulated bus
//! on a pty, the bus under arbitrary well-framed packets, and the official ROBOTIS SDK and the
//! README's CI job against the simulator and the `dxl-sim` binary.

mod bus_fuzz;
mod driver_vs_sim;
mod sdk_python;
