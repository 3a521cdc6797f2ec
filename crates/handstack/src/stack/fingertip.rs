//! The fingertip a scene names: three MS5611 on the I2C buses the scene names, one per sensor,
//! opened through the run's [`Platform`] (Linux device files by default).

use super::platform::{I2cBus, Platform};
use crate::error::RunError;
use crate::scene::SceneOf;
use baro_drivers::{Address, I2cInterface, Measurement, Ms5611, Osr, Ready, Scheduler};
use embedded_hal::delay::DelayNs;
use hand_control::grasp_loop::LoopClock;
use hand_traits::{PressureFrame, TactileSource};

type Chip = Ms5611<I2cInterface<I2cBus>, Ready>;

/// Three MS5611 on the platform's buses, read by the driver's scheduler; frames stamped by the
/// platform's clock (the loop's time).
pub struct RealFingertip {
    sensors: Vec<Chip>,
    scheduler: Scheduler,
    delay: Box<dyn DelayNs + Send>,
    clock: Box<dyn LoopClock + Send>,
}

impl RealFingertip {
    /// Opens each of `buses` on `platform`, resets the MS5611 at `address` and checks its PROM
    /// CRC.
    pub fn open(
        platform: &dyn Platform,
        buses: &[String],
        address: Address,
        osr: Osr,
    ) -> Result<Self, RunError> {
        let mut delay = platform.delay();
        let mut sensors = Vec::with_capacity(buses.len());
        for bus in buses {
            let fail = |reason: String| RunError::Open {
                device: "sensors.fingertip",
                path: bus.clone(),
                reason,
            };
            let dev = platform.open_i2c(bus).map_err(fail)?;
            let chip = Ms5611::new_with_i2c(dev, address)
                .init(&mut &mut *delay)
                .map_err(|e| fail(format!("MS5611 at {:#04x}: {}", address.addr(), e.error)))?;
            sensors.push(chip);
        }
        Ok(Self {
            sensors,
            scheduler: Scheduler::new(osr),
            delay,
            clock: platform.clock(),
        })
    }
}

impl TactileSource for RealFingertip {
    type Frame = PressureFrame<3>;
    type Error = RunError;

    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        let mut out = [Measurement {
            temperature_centi_celsius: 0,
            pressure_pa: 0,
        }; 3];
        self.scheduler
            .sample_all(&mut self.sensors, &mut &mut *self.delay, &mut out)
            .map_err(|e| RunError::Device {
                device: "sensors.fingertip",
                reason: format!("sensor {}: {}", e.sensor + 1, e.error),
            })?;
        Ok(PressureFrame {
            t_us: self.clock.now_us(),
            pressure_pa: out.map(|m| m.pressure_pa as f32),
        })
    }
}

/// The scene's real fingertip, never a simulated one: a scene that drives real servos must read
/// real sensors, so naming no `i2c_buses` is an error here, as is a bus that cannot be opened
/// (both before anything moves).
pub fn open<X>(scene: &SceneOf<X>, platform: &dyn Platform) -> Result<RealFingertip, RunError> {
    let tip = scene_fingertip(scene)?;
    let Some(buses) = &tip.i2c_buses else {
        return Err(RunError::Device {
            device: "sensors.fingertip",
            reason: "a hardware hand needs the fingertip's `i2c_buses`: the simulated fingertip \
                     is never pressed by a real grasp"
                .into(),
        });
    };
    let osr = Osr::from_ratio(*tip.osr.get_ref()).ok_or_else(|| RunError::Device {
        device: "sensors.fingertip",
        reason: format!("OSR {} is not the MS5611's", tip.osr.get_ref()),
    })?;
    let address = match tip.address.as_ref().map(|a| *a.get_ref()) {
        Some(0x76) => Address::CsbHigh,
        _ => Address::CsbLow,
    };
    RealFingertip::open(platform, buses.get_ref(), address, osr)
}

fn scene_fingertip<X>(scene: &SceneOf<X>) -> Result<&crate::scene::parts::Fingertip, RunError> {
    scene
        .file
        .sensors
        .fingertip
        .as_ref()
        .map(|t| t.get_ref())
        .ok_or_else(|| RunError::Device {
            device: "sensors.fingertip",
            reason: "the scene names no fingertip".into(),
        })
}
