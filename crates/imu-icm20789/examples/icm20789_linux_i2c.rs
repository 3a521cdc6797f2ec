//! An ICM-20789 on a Linux I2C bus: `cargo run --example icm20789_linux_i2c -- /dev/i2c-1` prints ten
//! IMU samples, each with a low-noise pressure reading taken while the IMU was read.

use embedded_hal::delay::DelayNs as _;
use imu_icm20789::{BaroMode, FrameOrder, Icm20789};
use linux_embedded_hal::{Delay, I2cdev};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let bus = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "/dev/i2c-1".into());
    let i2c = I2cdev::new(&bus).map_err(|e| format!("{bus}: {e}"))?;
    let mut delay = Delay;
    let mut icm = Icm20789::new_with_i2c(i2c);
    icm.init(&mut delay)
        .map_err(|e| format!("ICM-20789 on {bus}: {e:?}"))?;
    icm.init_barometer(&mut delay)
        .map_err(|e| format!("ICM-20789 barometer on {bus}: {e:?}"))?;
    for _ in 0..10 {
        let conversion = icm
            .start_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst)
            .map_err(|e| format!("{e:?}"))?;
        let imu = icm.read_imu().map_err(|e| format!("{e:?}"))?;
        delay.delay_us(conversion.wait_us());
        let baro = icm
            .read_pressure(conversion)
            .map_err(|e| format!("{e:?}"))?;
        println!(
            "accel {:?} m/s², gyro {:?} rad/s, {:.1} Pa at {:.2} °C",
            imu.accel_mps2, imu.gyro_rps, baro.pressure_pa, baro.temperature_c
        );
    }
    Ok(())
}
