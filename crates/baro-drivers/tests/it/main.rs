//! baro-drivers' integration tests, one binary: the datasheet's worked example and CRC-4, every
//! byte on I2C and SPI, compensation properties, and the blocking and async drivers and
//! scheduler against the chip model.

mod async_driver;
mod commands_i2c;
mod commands_spi;
mod compensation_props;
mod datasheet_example;
mod round_trip;
mod scheduler;
