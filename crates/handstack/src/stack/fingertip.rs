//! The fingertip a scene names: three MS5611 on the I2C buses the scene names, one per sensor,
//! or behind a TCA9548A I2C switch on the I2C of an Arduino running Firmata (an MS5611 has two
//! addresses, so three on one bus need the switch), opened through the run's [`Platform`]
//! (Linux device files and firmata-host by default); or the fingertip's own microcontroller,
//! which reads them, on a serial port ([`super::fingertip_mcu`]).
//!
//! Through a board every I2C transfer crosses the serial line, and a frame is 29 of them (per
//! sensor three channel selections, two conversion commands and two ADC reads, each a command
//! and a read; and two round trips that start the conversion waits), so the frame rate is set
//! by the baud rate more than by the OSR: 12–15 frames/s at 57 600 baud and 18–26 at 115 200,
//! under the grasp loop's 100 Hz at every OSR (the handstack README gives the measured rates).

use super::fingertip_mcu::McuLink;
use super::platform::{I2cBus, I2cSwitch, Platform, SwitchError};
use crate::error::RunError;
use crate::scene::SceneOf;
use crate::scene::parts::FingertipWiring;
use baro_drivers::{Address, I2cInterface, Measurement, Ms5611, Osr, Ready, Scheduler};
use embedded_hal::delay::DelayNs;
use fingertip_link::Frame;
use hand_control::grasp_loop::LoopClock;
use hand_traits::{PressureFrame, TactileSource};

type Chip = Ms5611<I2cInterface<I2cBus>, Ready>;

/// Three MS5611 on the platform's buses, read by the driver's scheduler, or the fingertip's
/// microcontroller's frames; frames stamped by the platform's clock (the loop's time).
pub struct RealFingertip {
    source: Source,
    clock: Box<dyn LoopClock + Send>,
}

enum Source {
    Chips {
        sensors: Vec<Chip>,
        scheduler: Scheduler,
        delay: Box<dyn DelayNs + Send>,
    },
    Mcu(Box<McuLink>),
}

/// The error of the fingertip's bus, board or switch at `path` that cannot be opened.
fn cannot_open(path: &str, reason: String) -> RunError {
    RunError::Open {
        device: "sensors.fingertip",
        path: path.to_owned(),
        reason,
    }
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
            let fail = |reason: String| cannot_open(bus, reason);
            let dev = platform.open_i2c(bus).map_err(fail)?;
            let chip = Ms5611::new_with_i2c(dev, address)
                .init(&mut &mut *delay)
                .map_err(|e| fail(format!("MS5611 at {:#04x}: {}", address.addr(), e.error)))?;
            sensors.push(chip);
        }
        Ok(Self::from_chips(platform, sensors, delay, osr))
    }

    /// Opens the Firmata board on `port` at `baud` ([`Platform::open_firmata_i2c`]), checks
    /// that the TCA9548A at `mux_address` on its I2C answers, and on each of `mux_channels`
    /// (three, sensor 1 first) resets the MS5611 at `address` and checks its PROM CRC. A board
    /// that does not answer, a switch that does not, or a sensor that does not is a
    /// [`RunError::Open`] naming the port and what failed.
    ///
    /// ```no_run
    /// use baro_drivers::{Address, Osr};
    /// use handstack::stack::fingertip::RealFingertip;
    /// use handstack::stack::platform::LinuxPlatform;
    /// use hand_traits::TactileSource;
    ///
    /// let platform = LinuxPlatform::new();
    /// let mut tip = RealFingertip::open_firmata(
    ///     &platform, "/dev/ttyACM0", 57_600, 0x70, &[0, 1, 2], Address::CsbLow, Osr::Osr1024,
    /// )?;
    /// let frame = tip.read_frame()?;
    /// println!("{:?} Pa", frame.pressure_pa);
    /// # Ok::<(), handstack::RunError>(())
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub fn open_firmata(
        platform: &dyn Platform,
        port: &str,
        baud: u32,
        mux_address: u8,
        mux_channels: &[u8],
        address: Address,
        osr: Osr,
    ) -> Result<Self, RunError> {
        let fail = |reason: String| cannot_open(port, reason);
        if mux_channels.len() != 3 {
            return Err(fail(format!(
                "{} switch channels named; the fingertip's three MS5611 need three",
                mux_channels.len()
            )));
        }
        let board = platform.open_firmata_i2c(port, baud).map_err(fail)?;
        let switch = I2cSwitch::new(board, mux_address);
        let mut delay: Box<dyn DelayNs + Send> = Box::new(BoardDelay {
            board: I2cSwitch::clone(&switch),
            delay: platform.delay(),
        });
        let mut sensors = Vec::with_capacity(mux_channels.len());
        for (k, &channel) in mux_channels.iter().enumerate() {
            // A round trip to the switch: it answers, and its selection is in place before
            // the chip's reset (a board reports no NACK for a write).
            switch
                .select(channel)
                .map_err(|e| fail(switch_failure(e)))?;
            let dev = switch
                .channel(channel)
                .map_err(|e| fail(switch_failure(e)))?;
            let chip = Ms5611::new_with_i2c(I2cBus::new(dev), address)
                .init(&mut &mut *delay)
                .map_err(|e| {
                    fail(format!(
                        "MS5611 of sensor {} at {:#04x} on switch channel {channel}: {}",
                        k + 1,
                        address.addr(),
                        e.error
                    ))
                })?;
            sensors.push(chip);
        }
        Ok(Self::from_chips(platform, sensors, delay, osr))
    }

    /// Opens the fingertip's microcontroller on the serial port `port` at `baud`
    /// ([`McuLink::open`]); the frames' pressures are stamped by `platform`'s clock.
    pub fn open_mcu(platform: &dyn Platform, port: &str, baud: u32) -> Result<Self, RunError> {
        Ok(Self {
            source: Source::Mcu(Box::new(McuLink::open(port, baud)?)),
            clock: platform.clock(),
        })
    }

    /// The last frame of the fingertip's microcontroller (its force and contact cells);
    /// `None` for chips read by this computer.
    pub fn mcu_frame(&self) -> Option<&Frame> {
        match &self.source {
            Source::Mcu(link) => link.last(),
            Source::Chips { .. } => None,
        }
    }

    /// Opens the fingertip where `wiring` says (a scene's
    /// [`Fingertip::wiring`](crate::scene::parts::Fingertip::wiring)): one I2C bus of
    /// `platform` per sensor, a switch on a Firmata board's I2C, or the fingertip's
    /// microcontroller.
    pub fn open_wired(
        platform: &dyn Platform,
        wiring: FingertipWiring<'_>,
        address: Address,
        osr: Osr,
    ) -> Result<Self, RunError> {
        match wiring {
            FingertipWiring::I2c { buses } => Self::open(platform, buses, address, osr),
            FingertipWiring::Firmata {
                port,
                baud,
                mux_address,
                mux_channels,
            } => Self::open_firmata(
                platform,
                port,
                baud,
                mux_address,
                mux_channels,
                address,
                osr,
            ),
            FingertipWiring::Mcu { port, baud } => Self::open_mcu(platform, port, baud),
        }
    }

    fn from_chips(
        platform: &dyn Platform,
        sensors: Vec<Chip>,
        delay: Box<dyn DelayNs + Send>,
        osr: Osr,
    ) -> Self {
        Self {
            source: Source::Chips {
                sensors,
                scheduler: Scheduler::new(osr),
                delay,
            },
            clock: platform.clock(),
        }
    }
}

/// The drivers' waits on a Firmata board. The board carries out a write when the line brings
/// it, not when the host sends it, and says nothing back; so a conversion the host started
/// behind other queued commands ends later than the host's clock says, and a wait counted from
/// the sending (the driver's scheduler starts three conversions, waits the longest conversion
/// time, then reads) can end before it. Each wait here begins with a round trip to the board
/// (the switch's control byte, read back), so it counts from when everything sent before has
/// been done.
struct BoardDelay {
    board: I2cSwitch<I2cBus>,
    delay: Box<dyn DelayNs + Send>,
}

impl BoardDelay {
    fn settle(&mut self) {
        // A board that fails here fails the transfer after the wait too, which says so.
        let _ = self.board.read_selection();
    }
}

impl DelayNs for BoardDelay {
    fn delay_ns(&mut self, ns: u32) {
        self.settle();
        self.delay.delay_ns(ns);
    }

    fn delay_us(&mut self, us: u32) {
        self.settle();
        self.delay.delay_us(us);
    }

    fn delay_ms(&mut self, ms: u32) {
        self.settle();
        self.delay.delay_ms(ms);
    }
}

/// A switch that cannot be reached, in words: a NACK is a switch that is not there.
fn switch_failure(e: SwitchError<super::platform::BusError>) -> String {
    match e {
        SwitchError::Bus { address, error }
            if matches!(
                embedded_hal::i2c::Error::kind(&error),
                embedded_hal::i2c::ErrorKind::NoAcknowledge(_)
            ) =>
        {
            format!(
                "no TCA9548A I2C switch answers at {address:#04x} (the three MS5611 sit behind \
                 one): {error}"
            )
        }
        e => e.to_string(),
    }
}

impl TactileSource for RealFingertip {
    type Frame = PressureFrame<3>;
    type Error = RunError;

    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        let pressure_pa = match &mut self.source {
            Source::Chips {
                sensors,
                scheduler,
                delay,
            } => {
                let mut out = [Measurement {
                    temperature_centi_celsius: 0,
                    pressure_pa: 0,
                }; 3];
                scheduler
                    .sample_all(sensors, &mut &mut **delay, &mut out)
                    .map_err(|e| RunError::Device {
                        device: "sensors.fingertip",
                        reason: format!("sensor {}: {}", e.sensor + 1, e.error),
                    })?;
                out.map(|m| m.pressure_pa)
            }
            Source::Mcu(link) => {
                let frame = link.next_frame()?;
                if frame.fault {
                    return Err(RunError::Device {
                        device: "sensors.fingertip",
                        reason: "the fingertip's microcontroller reports a failed cycle (a \
                                 sensor that did not answer on its bus)"
                            .into(),
                    });
                }
                frame.pressure_pa
            }
        };
        Ok(PressureFrame {
            t_us: self.clock.now_us(),
            pressure_pa: pressure_pa.map(|p| p as f32),
        })
    }
}

/// The scene's real fingertip, never a simulated one: a scene that drives real servos must read
/// real sensors, so naming neither `i2c_buses` nor `firmata_port` is an error here, as is a
/// bus or board that cannot be opened (both before anything moves).
pub fn open<X>(scene: &SceneOf<X>, platform: &dyn Platform) -> Result<RealFingertip, RunError> {
    let tip = scene_fingertip(scene)?;
    let Some(wiring) = tip.wiring() else {
        return Err(RunError::Device {
            device: "sensors.fingertip",
            reason: "a hardware hand needs the fingertip's `i2c_buses`, `firmata_port` or \
                     `serial_port`: the simulated fingertip is never pressed by a real grasp"
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
    RealFingertip::open_wired(platform, wiring, address, osr)
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
