//! The MS5611 chip model: command decoding, PROM, timed conversions, noise.

use std::vec::Vec;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::environment::Environment;
use super::error::SimError;
use super::inverse::{pressure_code, temperature_code};
use super::timing::BusTiming;
use crate::command::{self, Decoded};
use crate::compensation::Calibration;
use crate::interface::Address;
use crate::osr::Osr;
use crate::prom::Prom;
use sim_clock::SimClock;

/// The coefficients of the datasheet's worked example (MS5611-01BA03, p. 7), which the model
/// holds unless given another PROM.
pub const DATASHEET_COEFFICIENTS: [u16; 6] = [40127, 36924, 23317, 23282, 33464, 28312];

/// Which datasheet conversion time the model takes (the real one lies between typical and
/// maximum). `Max` is the default: a driver that waits less than the maximum fails.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ConversionTime {
    /// The typical time.
    Typical,
    /// The maximum time.
    #[default]
    Max,
}

#[derive(Debug, Clone, Copy)]
struct Conversion {
    code: u32,
    ready_at_ns: u64,
}

/// A simulated MS5611 answering the real command set over embedded-hal I2C (at its address)
/// or SPI (as one `SpiDevice`, i.e. behind its own chip select).
///
/// * PROM: the datasheet example coefficients with a valid CRC-4, or any [`Prom`].
/// * Conversions take their datasheet time on the shared [`SimClock`]; an ADC read before
///   the end returns 0 and loses the conversion, as on the chip.
/// * Codes come from inverting the datasheet compensation for the [`Environment`]'s true
///   pressure and temperature, plus seeded Gaussian noise of the OSR's datasheet RMS. Beyond
///   the codes' range they saturate, as the ADC does; NaN or infinite conditions have no code,
///   so the conversion command is refused with [`SimError::NonFiniteConditions`].
#[derive(Debug)]
pub struct Ms5611Sim<Env> {
    pub(super) env: Env,
    pub(super) clock: SimClock,
    pub(super) timing: BusTiming,
    pub(super) address: u8,
    prom: Prom,
    calibration: Option<Calibration>,
    conversion_time: ConversionTime,
    noise: bool,
    rng: ChaCha8Rng,
    pending: Option<Conversion>,
    answer: [u8; 3],
    answer_len: usize,
    answer_pos: usize,
    commands: Vec<u8>,
    /// Whether `commands` records (off for long runs: an unbounded log grows the heap).
    log_commands: bool,
}

impl<Env: Environment> Ms5611Sim<Env> {
    /// A chip at I2C address 0x77 with the datasheet PROM, noise on (seed 0), maximum
    /// conversion times and default bus timing.
    pub fn new(env: Env, clock: SimClock) -> Self {
        let prom = Prom::with_crc(0, DATASHEET_COEFFICIENTS, 0x5A5);
        Self {
            env,
            clock,
            timing: BusTiming::default(),
            address: Address::CsbLow.addr(),
            calibration: prom.calibration().ok(),
            prom,
            conversion_time: ConversionTime::Max,
            noise: true,
            rng: ChaCha8Rng::seed_from_u64(0),
            pending: None,
            answer: [0; 3],
            answer_len: 0,
            answer_pos: 0,
            commands: Vec::new(),
            log_commands: true,
        }
    }

    /// Holds `prom` instead (a bad CRC is allowed: that is what the driver must catch).
    pub fn with_prom(mut self, prom: Prom) -> Self {
        // The model still needs coefficients to make codes; a corrupt image uses its words
        // as they are.
        let w = prom.words();
        self.calibration = Some(
            prom.calibration()
                .unwrap_or(Calibration::new([w[1], w[2], w[3], w[4], w[5], w[6]])),
        );
        self.prom = prom;
        self
    }

    /// Answers at `address` on I2C.
    pub fn with_address(mut self, address: Address) -> Self {
        self.address = address.addr();
        self
    }

    /// Seeds the noise generator.
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.rng = ChaCha8Rng::seed_from_u64(seed);
        self
    }

    /// Switches the datasheet RMS noise on or off.
    pub fn with_noise(mut self, on: bool) -> Self {
        self.noise = on;
        self
    }

    /// Uses `timing` for bus transfers.
    pub fn with_timing(mut self, timing: BusTiming) -> Self {
        self.timing = timing;
        self
    }

    /// Takes the typical or the maximum conversion time.
    pub fn with_conversion_time(mut self, t: ConversionTime) -> Self {
        self.conversion_time = t;
        self
    }

    /// The environment, e.g. to change conditions between samples.
    pub fn environment_mut(&mut self) -> &mut Env {
        &mut self.env
    }

    /// The clock the chip runs on.
    pub fn clock(&self) -> &SimClock {
        &self.clock
    }

    /// Records every command byte for [`commands`](Self::commands) (on by default), or not:
    /// a control loop that runs for hours turns it off so the model's heap stays constant.
    ///
    /// ```
    /// # use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
    /// use baro_drivers::Ms5611;
    /// let clock = SimClock::new();
    /// let air = Conditions { pressure_mbar: 1000.0, temperature_celsius: 20.0 };
    /// let chip = Ms5611Sim::new(air, clock.clone()).with_command_log(false);
    /// let baro = Ms5611::new_with_spi(chip).init(&mut clock.delay()).map_err(|e| e.error)?;
    /// assert!(baro.destroy().commands().is_empty()); // reset and PROM reads went unrecorded
    /// # Ok::<(), baro_drivers::Error<baro_drivers::sim::SimError>>(())
    /// ```
    pub fn with_command_log(mut self, on: bool) -> Self {
        self.log_commands = on;
        self
    }

    /// Every command byte received so far, in order (empty with the log off).
    pub fn commands(&self) -> &[u8] {
        &self.commands
    }

    fn set_answer(&mut self, bytes: &[u8]) {
        self.answer[..bytes.len()].copy_from_slice(bytes);
        self.answer_len = bytes.len();
        self.answer_pos = 0;
    }

    /// Executes one command byte.
    pub(super) fn command(&mut self, byte: u8) -> Result<(), SimError> {
        let decoded = command::decode(byte).ok_or(SimError::UnknownCommand(byte))?;
        if self.log_commands {
            self.commands.push(byte);
        }
        self.set_answer(&[]);
        match decoded {
            Decoded::Reset => self.pending = None,
            Decoded::PromRead(index) => {
                let word = self.prom.words()[usize::from(index)];
                self.set_answer(&word.to_be_bytes());
            }
            Decoded::ConvertD1(osr) => self.start(osr, true)?,
            Decoded::ConvertD2(osr) => self.start(osr, false)?,
            Decoded::AdcRead => {
                let now = self.clock.now_ns();
                // Early or repeated reads answer 0; an early read spoils the conversion.
                let code = match self.pending.take() {
                    Some(c) if now >= c.ready_at_ns => c.code,
                    _ => 0,
                };
                self.set_answer(&code.to_be_bytes()[1..]);
            }
        }
        Ok(())
    }

    /// The next byte of the answer to the last command (0 once it is exhausted).
    pub(super) fn answer_byte(&mut self) -> u8 {
        if self.answer_pos < self.answer_len {
            self.answer_pos += 1;
            self.answer[self.answer_pos - 1]
        } else {
            0
        }
    }

    fn gaussian(&mut self, sigma: f64) -> f64 {
        if !self.noise {
            return 0.0;
        }
        Normal::new(0.0, sigma).map_or(0.0, |n| n.sample(&mut self.rng))
    }

    /// Starts a conversion; an environment with no finite truth refuses it (a code made up
    /// for NaN would read as a plausible pressure).
    fn start(&mut self, osr: Osr, pressure: bool) -> Result<(), SimError> {
        let now = self.clock.now_ns();
        let truth = self.env.conditions(now);
        let code = match self.calibration {
            None => Some(0),
            Some(cal) => {
                // D1 depends on the die's true temperature; only the reading is noisy.
                let d2_true = temperature_code(&cal, truth.temperature_celsius * 100.0);
                if pressure {
                    let noise = self.gaussian(f64::from(osr.pressure_noise_rms_mbar()));
                    d2_true.and_then(|d2| {
                        pressure_code(&cal, d2, (truth.pressure_mbar + noise) * 100.0)
                    })
                } else {
                    let noise = self.gaussian(f64::from(osr.temperature_noise_rms_celsius()));
                    d2_true.and(temperature_code(
                        &cal,
                        (truth.temperature_celsius + noise) * 100.0,
                    ))
                }
            }
        };
        let Some(code) = code else {
            self.pending = None;
            return Err(SimError::NonFiniteConditions);
        };
        let duration = match self.conversion_time {
            ConversionTime::Typical => osr.conversion_time_typ_ns(),
            ConversionTime::Max => osr.conversion_time_max_ns(),
        };
        self.pending = Some(Conversion {
            code,
            ready_at_ns: now + u64::from(duration),
        });
        Ok(())
    }
}
