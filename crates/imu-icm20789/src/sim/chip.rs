//! The chip model on the embedded-hal I2C traits: routes transfers to the IMU (0x68 / 0x69) and,
//! with bypass on, to the barometer (0x63), and clocks every bit on the simulated bus.

use std::boxed::Box;

use embedded_hal::i2c::{ErrorKind, ErrorType, NoAcknowledgeSource, Operation};
use sim_clock::{SimClock, SimDelay};

use crate::baro::BARO_ADDRESS;
use crate::baro::otp::Calibration;
use crate::imu::ImuAddress;
use crate::imu::registers as reg;
use crate::sim::baro_model::{BaroModel, Refusal};
use crate::sim::bus::BusAccount;
use crate::sim::environment::Environment;
use crate::sim::imu_model::ImuModel;
use crate::sim::noise::{NoiseSource, SimNoise};

/// OTP constants of the default model. Synthetic (not read from a part): chosen so that
/// 30…110 kPa fall inside the 24-bit code range with a temperature dependence of a few Pa per
/// 10 °C, as for the sets in the crate's conversion tests.
pub const DEFAULT_OTP: [i16; 4] = [1_850, -780, 2_410, 4_174];

/// Barometer ID word of the model (`& 0x3F` = 0x08).
pub const DEFAULT_BARO_ID: u16 = 0x0148;

/// A bus error of the model: what a real master would see.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SimError(pub ErrorKind);

impl embedded_hal::i2c::Error for SimError {
    fn kind(&self) -> ErrorKind {
        self.0
    }
}

/// embedded-hal's words for the kind (`The peripheral did not acknowledge …`).
impl core::fmt::Display for SimError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Display::fmt(&self.0, f)
    }
}

impl core::error::Error for SimError {}

/// The ICM-20789 as seen from its I2C pins. Give it to the driver as its bus.
///
/// A pressure beyond the codes the calibration can express saturates at the end code, and a
/// temperature beyond −45 … 130 °C at its end code, as the ADC does; a NaN or infinite truth
/// has no code, so the barometer NACKs that read instead of inventing one.
pub struct ChipModel {
    imu_address: u8,
    imu: ImuModel,
    baro: BaroModel,
    env: Box<dyn Environment + Send>,
    noise: NoiseSource,
    sim_noise: SimNoise,
    bus: BusAccount,
}

impl core::fmt::Debug for ChipModel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ChipModel")
            .field("imu_address", &self.imu_address)
            .field("now_ns", &self.bus.clock().now_ns())
            .finish_non_exhaustive()
    }
}

impl ChipModel {
    /// A chip at 0x68 measuring `env`, with default noise seeded by `seed`. `env` is `Send`, so
    /// the chip can stand behind any bus a thread owns (a platform's boxed I2C bus).
    pub fn new(env: impl Environment + Send + 'static, seed: u64) -> Self {
        ChipModel {
            imu_address: ImuAddress::Ad0Low.addr(),
            imu: ImuModel::new(reg::WHO_AM_I_ICM20789),
            baro: BaroModel::new(Calibration::from_otp(DEFAULT_OTP), DEFAULT_BARO_ID),
            env: Box::new(env),
            noise: NoiseSource::new(seed),
            sim_noise: SimNoise::default(),
            bus: BusAccount::default(),
        }
    }

    /// Runs on `clock` (shared with other chip models, their delays or a loop) from now on,
    /// with a fresh bus account on it.
    ///
    /// ```
    /// use imu_icm20789::sim::{ChipModel, SimClock, Truth};
    ///
    /// let clock = SimClock::new();
    /// let chip = ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], 101_325.0), 3)
    ///     .with_clock(clock.clone());
    /// clock.advance_ns(1_000);
    /// assert_eq!(chip.clock().now_ns(), 1_000);
    /// ```
    pub fn with_clock(mut self, clock: SimClock) -> Self {
        self.bus = BusAccount::new(clock);
        self
    }

    /// Uses another noise setting.
    pub fn with_noise(mut self, noise: SimNoise) -> Self {
        self.sim_noise = noise;
        self
    }

    /// Uses other OTP constants.
    pub fn with_calibration(mut self, calibration: Calibration) -> Self {
        self.baro = BaroModel::new(calibration, DEFAULT_BARO_ID);
        self
    }

    /// Answers at another IMU address.
    pub fn with_imu_address(mut self, address: ImuAddress) -> Self {
        self.imu_address = address.addr();
        self
    }

    /// Reports another WHO_AM_I (e.g. 0x02 for rev R1, or a wrong part).
    pub fn with_who_am_i(mut self, who_am_i: u8) -> Self {
        self.imu = ImuModel::new(who_am_i);
        self
    }

    /// Reports another barometer ID word.
    pub fn with_baro_id(mut self, id_word: u16) -> Self {
        let calibration = self.calibration();
        self.baro = BaroModel::new(calibration, id_word);
        self
    }

    /// The calibration in the model's OTP.
    pub fn calibration(&self) -> Calibration {
        self.baro.calibration()
    }

    /// The model's clock (shared: clones see the same time).
    pub fn clock(&self) -> SimClock {
        self.bus.clock().clone()
    }

    /// A delay on the model's clock.
    pub fn delay(&self) -> SimDelay {
        self.bus.clock().delay()
    }

    /// The account of the bits the model's bus carried (shared: clones see the same count).
    pub fn bus(&self) -> BusAccount {
        self.bus.clone()
    }

    fn refuse(refusal: Refusal) -> SimError {
        SimError(ErrorKind::NoAcknowledge(match refusal {
            Refusal::Address => NoAcknowledgeSource::Address,
            Refusal::Data => NoAcknowledgeSource::Data,
        }))
    }

    /// Bits on the wire for one transaction: START, then per run of same-direction operations a
    /// (repeated) START except for the first, address + R/W + ACK, 9 bits per byte, and STOP.
    fn transaction_bits(operations: &[Operation<'_>]) -> u64 {
        let mut bits = 2; // START + STOP
        let mut previous_read = None;
        for op in operations {
            let (is_read, len) = match op {
                Operation::Read(b) => (true, b.len()),
                Operation::Write(b) => (false, b.len()),
            };
            if previous_read != Some(is_read) {
                bits += 9 + u64::from(previous_read.is_some()); // address byte + ACK (+ Sr)
                previous_read = Some(is_read);
            }
            bits += 9 * len as u64;
        }
        bits
    }

    fn imu_transaction(&mut self, operations: &mut [Operation<'_>]) -> Result<(), SimError> {
        let now = self.bus.clock().now_ns();
        self.imu
            .update(now, self.env.as_mut(), &mut self.noise, &self.sim_noise);
        let mut pointer = None;
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    let Some((&first, data)) = bytes.split_first() else {
                        continue;
                    };
                    let mut r = first;
                    for &value in data {
                        self.imu.write(r, value, now);
                        r = r.wrapping_add(1) & 0x7F;
                    }
                    pointer = Some(r);
                }
                Operation::Read(buf) => {
                    let mut r = pointer.unwrap_or(0);
                    for byte in buf.iter_mut() {
                        *byte = self.imu.read(r);
                        if r != reg::FIFO_R_W {
                            r = r.wrapping_add(1) & 0x7F;
                        }
                    }
                    pointer = Some(r);
                }
            }
        }
        Ok(())
    }

    fn baro_transaction(&mut self, operations: &mut [Operation<'_>]) -> Result<(), SimError> {
        if !self.imu.bypass_enabled() {
            return Err(Self::refuse(Refusal::Address)); // not connected to the main bus
        }
        let now = self.bus.clock().now_ns();
        for op in operations {
            match op {
                Operation::Write(bytes) => self.baro.command(bytes, now),
                Operation::Read(buf) => self.baro.read(
                    buf,
                    now,
                    self.env.as_mut(),
                    &mut self.noise,
                    &self.sim_noise,
                ),
            }
            .map_err(Self::refuse)?;
        }
        Ok(())
    }
}

impl ErrorType for ChipModel {
    type Error = SimError;
}

impl embedded_hal::i2c::I2c for ChipModel {
    fn transaction(
        &mut self,
        address: u8,
        operations: &mut [Operation<'_>],
    ) -> Result<(), Self::Error> {
        // The transfer ends before the chip acts on it: clock the bits first.
        self.bus.clock_bits(Self::transaction_bits(operations));
        if address == self.imu_address {
            self.imu_transaction(operations)
        } else if address == BARO_ADDRESS {
            self.baro_transaction(operations)
        } else {
            Err(Self::refuse(Refusal::Address))
        }
    }
}

#[cfg(feature = "async")]
impl embedded_hal_async::i2c::I2c for ChipModel {
    async fn transaction(
        &mut self,
        address: u8,
        operations: &mut [Operation<'_>],
    ) -> Result<(), Self::Error> {
        embedded_hal::i2c::I2c::transaction(self, address, operations)
    }
}
