//! The barometer half of the chip model: the command state machine at 0x63.

use crate::baro::conversion;
use crate::baro::frame::{self, FRAME_LEN};
use crate::baro::mode::{BaroMode, FrameOrder};
use crate::baro::otp::{self, Calibration};
use crate::baro::{READ_ID, SOFT_RESET};
use crate::crc8;
use crate::sim::environment::Environment;
use crate::sim::noise::{NoiseSource, SimNoise};

/// What the next read returns.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Output {
    Nothing,
    Word([u8; 3]),
    Conversion {
        mode: BaroMode,
        order: FrameOrder,
        ready_ns: u64,
    },
}

/// Why the model refused a transfer (the bus sees a NACK).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// The chip does not acknowledge its address (busy converting, or nothing to send).
    Address,
    /// The chip does not acknowledge a command byte.
    Data,
}

#[derive(Debug)]
pub(crate) struct BaroModel {
    calibration: Calibration,
    id_word: u16,
    otp_index: Option<usize>,
    output: Output,
}

impl BaroModel {
    pub(crate) fn new(calibration: Calibration, id_word: u16) -> Self {
        BaroModel {
            calibration,
            id_word,
            otp_index: None,
            output: Output::Nothing,
        }
    }

    pub(crate) fn calibration(&self) -> Calibration {
        self.calibration
    }

    /// A write transfer: one command, perhaps with parameters.
    pub(crate) fn command(&mut self, bytes: &[u8], now_ns: u64) -> Result<(), Refusal> {
        if matches!(self.output, Output::Conversion { ready_ns, .. } if now_ns < ready_ns) {
            return Err(Refusal::Address); // busy converting
        }
        match bytes {
            b if b == SOFT_RESET => {
                self.otp_index = None;
                self.output = Output::Nothing;
            }
            b if b == READ_ID => self.output = Output::Word(crc8::encode_word(self.id_word)),
            b if b == otp::OTP_SETUP => self.otp_index = Some(0),
            b if b == otp::OTP_READ_NEXT => {
                let i = self.otp_index.ok_or(Refusal::Data)?;
                let word = *self.calibration.otp_reads().get(i).ok_or(Refusal::Data)?;
                self.otp_index = Some(i + 1);
                self.output = Output::Word(word);
            }
            [hi, lo] => {
                let (mode, order) =
                    BaroMode::from_command(u16::from_be_bytes([*hi, *lo])).ok_or(Refusal::Data)?;
                self.output = Output::Conversion {
                    mode,
                    order,
                    ready_ns: now_ns + u64::from(mode.conversion_time_typ_us()) * 1_000,
                };
            }
            _ => return Err(Refusal::Data),
        }
        Ok(())
    }

    /// A read transfer of `buf.len()` bytes.
    pub(crate) fn read(
        &mut self,
        buf: &mut [u8],
        now_ns: u64,
        env: &mut dyn Environment,
        noise: &mut NoiseSource,
        sim: &SimNoise,
    ) -> Result<(), Refusal> {
        let frame: [u8; FRAME_LEN];
        let bytes: &[u8] = match self.output {
            Output::Nothing => return Err(Refusal::Address),
            Output::Word(ref w) => w,
            Output::Conversion { ready_ns, .. } if now_ns < ready_ns => {
                return Err(Refusal::Address);
            }
            Output::Conversion {
                mode,
                order,
                ready_ns,
            } => {
                // The chip samples at the end of its conversion.
                let truth = env.state(ready_ns / 1_000);
                let sigma = f64::from(mode.noise_pa_rms() * sim.pressure_noise_scale);
                let pressure = truth.pressure_pa + noise.gaussian(sigma);
                if !(pressure.is_finite() && truth.temperature_c.is_finite()) {
                    // No code stands for NaN or infinity: refuse the read rather than make
                    // one up that converts to a plausible pressure.
                    self.output = Output::Nothing;
                    return Err(Refusal::Address);
                }
                // The temperature ADC saturates at its end codes (about −45 … 130 °C).
                let celsius = conversion::temperature_c(conversion::t_lsb_for(truth.temperature_c));
                let raw = self
                    .calibration
                    .raw_for(pressure, celsius)
                    .unwrap_or_else(|_| {
                        // Outside the codes this calibration can express: the ADC saturates.
                        let t = conversion::t_lsb_for(truth.temperature_c);
                        let high = pressure > 80_000.0;
                        crate::RawSample {
                            p_lsb: if high { 0xFF_FFFF } else { 0 },
                            t_lsb: t,
                        }
                    });
                frame = frame::encode_frame(raw, order);
                &frame
            }
        };
        for (dst, src) in buf
            .iter_mut()
            .zip(bytes.iter().chain(core::iter::repeat(&0xFF)))
        {
            *dst = *src;
        }
        self.output = Output::Nothing;
        Ok(())
    }
}
