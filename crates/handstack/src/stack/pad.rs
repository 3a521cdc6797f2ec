//! A real ICM-20789 pad on an I2C bus of the run's [`Platform`], or on the I2C of an Arduino
//! running Firmata: opened and identified (WHO_AM_I, barometer OTP) when a scene names
//! `i2c_bus` or `firmata_port`, so a wrong bus, a board that does not answer or a missing chip
//! is a typed error before any experiment starts; then read one frame per call (an IMU burst
//! during a barometer conversion), over I2C as Al & Martinez-Hernandez read theirs (§III-A).
//!
//! Through a Firmata board each I2C transfer is a round trip over the serial line, so the
//! frame rate depends on the board's baud rate: in the paper's `LowNoise` mode it stays under
//! [`FRAME_RATE_HZ`] at 57 600 and at 115 200 baud, while `Normal` passes it at either (the
//! handstack README gives the measured rates).

use super::platform::{I2cBus, Platform};
use crate::error::RunError;
use crate::scene::SceneOf;
use crate::scene::parts::PadWiring;
use embedded_hal::delay::DelayNs;
use hand_control::grasp_loop::LoopClock;
use hand_traits::{ImuFrame, TactileSource};
use imu_icm20789::{AccelScale, BaroMode, GyroDlpf, GyroScale, Icm20789, ImuSettings};

/// Frames per second a real pad is read at: Al & Martinez-Hernandez's ("Multimodal
/// barometric and inertial measurement unit based tactile sensor for robot control", §III-C:
/// 30 Hz, in Low Noise mode).
pub const FRAME_RATE_HZ: f64 = 30.0;

/// The IMU settings a real pad is configured with (the paper names none; ours): ±2 g and
/// ±250 °/s, the finest scales, since a 0.2–1.6 mm tap moves the pad by far less than either;
/// a 41 Hz gyro low-pass, above the [`FRAME_RATE_HZ`] frame rate's 15 Hz Nyquist band and well
/// below the 1 kHz output rate.
pub const IMU_SETTINGS: ImuSettings = ImuSettings {
    accel_scale: AccelScale::G2,
    gyro_scale: GyroScale::Dps250,
    gyro_dlpf: GyroDlpf::Hz41,
};

/// The ICM-20789 on the platform's bus, configured as the tap pad ([`IMU_SETTINGS`]); frames
/// stamped by the platform's clock.
pub struct RealPad {
    chip: Icm20789<I2cBus>,
    mode: BaroMode,
    delay: Box<dyn DelayNs + Send>,
    clock: Box<dyn LoopClock + Send>,
}

/// Opens `bus` on `platform`, initialises the ICM-20789's IMU (with the tap pad's settings) and
/// barometer on it; its frames' pressures are converted in `mode`.
pub fn open(platform: &dyn Platform, bus: &str, mode: BaroMode) -> Result<RealPad, RunError> {
    open_wired(platform, PadWiring::I2c { bus }, mode)
}

/// The pad `scene` names, opened through `platform`: an error names what the scene lacks (the
/// pad, its `i2c_bus` or `firmata_port`) or what failed opening it.
pub fn open_scene<X>(scene: &SceneOf<X>, platform: &dyn Platform) -> Result<RealPad, RunError> {
    let missing = |reason: &str| RunError::Device {
        device: "sensors.imu_pad",
        reason: reason.to_owned(),
    };
    let pad = scene
        .file
        .sensors
        .imu_pad
        .as_ref()
        .map(|p| p.get_ref())
        .ok_or_else(|| missing("the scene has no [sensors.imu_pad]"))?;
    let wiring = pad
        .wiring()
        .ok_or_else(|| missing("the scene's [sensors.imu_pad] names no i2c_bus or firmata_port"))?;
    open_wired(platform, wiring, pad.pressure_mode)
}

/// Opens the pad where `wiring` says (a scene's
/// [`ImuPad::wiring`](crate::scene::parts::ImuPad::wiring)): an I2C bus of `platform`, or the
/// I2C of the Firmata board on a serial port ([`Platform::open_firmata_i2c`]); then as
/// [`open`]. An error names the bus or port and what failed.
///
/// ```no_run
/// use handstack::scene::parts::PadWiring;
/// use handstack::stack::{pad, platform::LinuxPlatform};
/// use imu_icm20789::BaroMode;
///
/// let wiring = PadWiring::Firmata { port: "/dev/ttyACM0", baud: 115_200 };
/// let mut pad = pad::open_wired(&LinuxPlatform::new(), wiring, BaroMode::LowNoise)?;
/// # Ok::<(), handstack::RunError>(())
/// ```
pub fn open_wired(
    platform: &dyn Platform,
    wiring: PadWiring<'_>,
    mode: BaroMode,
) -> Result<RealPad, RunError> {
    let fail = |reason: String| RunError::Open {
        device: "sensors.imu_pad",
        path: wiring.path().to_owned(),
        reason,
    };
    let dev = match wiring {
        PadWiring::I2c { bus } => platform.open_i2c(bus),
        PadWiring::Firmata { port, baud } => platform.open_firmata_i2c(port, baud),
    }
    .map_err(fail)?;
    let mut delay = platform.delay();
    let mut chip = Icm20789::new_with_i2c(dev);
    chip.init(&mut &mut *delay)
        .map_err(|e| fail(format!("ICM-20789: {e}")))?;
    chip.configure_imu(&IMU_SETTINGS)
        .map_err(|e| fail(format!("ICM-20789 settings: {e}")))?;
    chip.init_barometer(&mut &mut *delay)
        .map_err(|e| fail(format!("ICM-20789 barometer: {e}")))?;
    Ok(RealPad {
        chip,
        mode,
        delay,
        clock: platform.clock(),
    })
}

impl TactileSource for RealPad {
    type Frame = ImuFrame;
    type Error = RunError;

    /// One frame ([`Icm20789::read_frame`]); a bus error or a CRC mismatch is a typed
    /// [`RunError::Device`] and the next call reads afresh.
    fn read_frame(&mut self) -> Result<ImuFrame, RunError> {
        let t_us = self.clock.now_us();
        let f = self
            .chip
            .read_frame(self.mode, &mut &mut *self.delay)
            .map_err(|e| RunError::Device {
                device: "sensors.imu_pad",
                reason: e.to_string(),
            })?;
        Ok(ImuFrame {
            t_us,
            accel_mps2: f.imu.accel_mps2,
            gyro_rps: f.imu.gyro_rps,
            pressure_pa: Some(f.baro.pressure_pa),
        })
    }
}
