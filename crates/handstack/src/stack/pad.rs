//! A real ICM-20789 pad on a Linux I2C bus: opened and identified (WHO_AM_I, barometer OTP)
//! when a scene names `i2c_bus`, so a wrong bus or a missing chip is a typed error before any
//! experiment starts.

use crate::error::RunError;
use imu_icm20789::Icm20789;
use linux_embedded_hal::{Delay, I2cdev};

/// Opens `bus` and initialises the ICM-20789's IMU and barometer on it.
pub fn open(bus: &str) -> Result<Icm20789<I2cdev>, RunError> {
    let fail = |reason: String| RunError::Open {
        device: "sensors.imu_pad",
        path: bus.to_owned(),
        reason,
    };
    let dev = I2cdev::new(bus).map_err(|e| fail(e.to_string()))?;
    let mut chip = Icm20789::new_with_i2c(dev);
    chip.init(&mut Delay)
        .map_err(|e| fail(format!("ICM-20789: {e:?}")))?;
    chip.init_barometer(&mut Delay)
        .map_err(|e| fail(format!("ICM-20789 barometer: {e:?}")))?;
    Ok(chip)
}
