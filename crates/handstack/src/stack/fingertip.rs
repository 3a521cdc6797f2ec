//! The fingertip a scene names: hand-sim's pad with three MS5611 chip models behind the real
//! driver, or three real MS5611 on Linux I2C buses (linux-embedded-hal), one per sensor.

use crate::error::RunError;
use crate::scene::Scene;
use baro_drivers::{Address, I2cInterface, Measurement, Ms5611, Osr, Ready, Scheduler};
use hand_traits::{PressureFrame, TactileSource};
use linux_embedded_hal::{Delay, I2cdev};
use std::time::Instant;

type Chip = Ms5611<I2cInterface<I2cdev>, Ready>;

/// Three real MS5611 read by the driver's scheduler; frames stamped with the wall clock.
pub struct RealFingertip {
    sensors: Vec<Chip>,
    scheduler: Scheduler,
    start: Instant,
}

impl RealFingertip {
    /// Opens each of `buses`, resets the MS5611 at `address` and checks its PROM CRC.
    pub fn open(buses: &[String], address: Address, osr: Osr) -> Result<Self, RunError> {
        let mut sensors = Vec::with_capacity(buses.len());
        for bus in buses {
            let fail = |reason: String| RunError::Open {
                device: "sensors.fingertip",
                path: bus.clone(),
                reason,
            };
            let dev = I2cdev::new(bus).map_err(|e| fail(e.to_string()))?;
            let chip = Ms5611::new_with_i2c(dev, address)
                .init(&mut Delay)
                .map_err(|e| fail(format!("MS5611 at {:#04x}: {:?}", address.addr(), e.error)))?;
            sensors.push(chip);
        }
        Ok(Self {
            sensors,
            scheduler: Scheduler::new(osr),
            start: Instant::now(),
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
            .sample_all(&mut self.sensors, &mut Delay, &mut out)
            .map_err(|e| RunError::Device {
                device: "sensors.fingertip",
                reason: format!("sensor {}: {:?}", e.sensor + 1, e.error),
            })?;
        Ok(PressureFrame {
            t_us: self.start.elapsed().as_micros() as u64,
            pressure_pa: out.map(|m| m.pressure_pa as f32),
        })
    }
}

/// The scene's fingertip as a boxed source: real when it names `i2c_buses`, else hand-sim's.
pub fn open(
    scene: &Scene,
) -> Result<Box<dyn TactileSource<Frame = PressureFrame<3>, Error = RunError>>, RunError> {
    let Some(tip) = &scene.file.sensors.fingertip else {
        return Err(RunError::Device {
            device: "sensors.fingertip",
            reason: "the scene names no fingertip".into(),
        });
    };
    let tip = tip.get_ref();
    let osr = hand_sim::fingertip::model::osr_from_ratio(*tip.osr.get_ref())?;
    match &tip.i2c_buses {
        Some(buses) => {
            let address = match tip.address.as_ref().map(|a| *a.get_ref()) {
                Some(0x76) => Address::CsbHigh,
                _ => Address::CsbLow,
            };
            Ok(Box::new(RealFingertip::open(
                buses.get_ref(),
                address,
                osr,
            )?))
        }
        None => {
            let config = scene.sim.fingertip.clone().unwrap_or_default();
            let sim = hand_sim::fingertip::Fingertip::new(&config, scene.seed())?;
            Ok(Box::new(SimSource(sim)))
        }
    }
}

/// hand-sim's fingertip with its errors as run errors.
struct SimSource(hand_sim::fingertip::Fingertip);

impl TactileSource for SimSource {
    type Frame = PressureFrame<3>;
    type Error = RunError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        Ok(self.0.read_frame()?)
    }
}
