//! imu-icm20789's integration tests, one binary: the barometer conversion and its properties,
//! every register access on a mock bus, and the drivers against the chip model.

mod common;
mod conversion;
mod conversion_props;
mod mock_bus;
mod sim_round_trip;
