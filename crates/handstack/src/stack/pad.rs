//! A real ICM-20789 pad on an I2C bus of the run's [`Platform`]: opened and identified
//! (WHO_AM_I, barometer OTP) when a scene names `i2c_bus`, so a wrong bus or a missing chip is a
//! typed error before any experiment starts.

use super::platform::{I2cBus, Platform};
use crate::error::RunError;
use imu_icm20789::Icm20789;

/// Opens `bus` on `platform` and initialises the ICM-20789's IMU and barometer on it.
pub fn open(platform: &dyn Platform, bus: &str) -> Result<Icm20789<I2cBus>, RunError> {
    let fail = |reason: String| RunError::Open {
        device: "sensors.imu_pad",
        path: bus.to_owned(),
        reason,
    };
    let dev = platform.open_i2c(bus).map_err(fail)?;
    let mut delay = platform.delay();
    let mut chip = Icm20789::new_with_i2c(dev);
    chip.init(&mut &mut *delay)
        .map_err(|e| fail(format!("ICM-20789: {e:?}")))?;
    chip.init_barometer(&mut &mut *delay)
        .map_err(|e| fail(format!("ICM-20789 barometer: {e:?}")))?;
    Ok(chip)
}
