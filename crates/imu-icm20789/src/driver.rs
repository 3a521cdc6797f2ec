//! The driver: one device value that owns the bus and talks to both the IMU and the barometer.
//!
//! Written once as async code; `maybe-async-cfg` generates the blocking [`Icm20789`] (always)
//! and [`Icm20789Async`] (feature `async`) from it.

use crate::baro::conversion::RawSample;
use crate::baro::frame::{self, FRAME_LEN};
use crate::baro::mode::{BaroMode, FrameOrder};
use crate::baro::otp::{self, Calibration};
use crate::baro::{self as baro_cmd, BARO_ADDRESS};
use crate::crc8;
use crate::error::Error;
use crate::imu::config::{AccelDlpf, AccelScale, GyroDlpf, GyroScale, imu_temperature_c};
use crate::imu::registers as reg;
use crate::imu::{BURST_LEN, ImuAddress, ImuSample, RawImu};
use embedded_hal::{delay::DelayNs as SyncDelayNs, i2c::I2c as SyncI2c};
#[cfg(feature = "async")]
use embedded_hal_async::{delay::DelayNs as AsyncDelayNs, i2c::I2c as AsyncI2c};

/// A started barometer conversion: what to wait for and how to decode it.
///
/// Returned by `start_pressure`; hand it to `read_pressure` after
/// [`BaroConversion::wait_us`] microseconds. The IMU can be read in between.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[must_use = "a started conversion must be read with read_pressure"]
pub struct BaroConversion {
    /// The mode the conversion runs in.
    pub mode: BaroMode,
    /// The order of the results in the frame.
    pub order: FrameOrder,
}

impl BaroConversion {
    /// Worst-case conversion time, µs: reading earlier may be NACKed.
    pub const fn wait_us(&self) -> u32 {
        self.mode.conversion_time_max_us()
    }
}

/// One barometer result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaroSample {
    /// The raw codes (feed them to [`Calibration::pressure_milli_pa`] for the integer path).
    pub raw: RawSample,
    /// Pressure, Pa (float path).
    pub pressure_pa: f32,
    /// Barometer die temperature, °C.
    pub temperature_c: f32,
}

/// One frame of the whole chip: an IMU burst read while a barometer conversion ran, and that
/// conversion's result ([`Icm20789::read_frame`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChipFrame {
    /// Accelerometer, gyroscope and die temperature.
    pub imu: ImuSample,
    /// Pressure and barometer temperature.
    pub baro: BaroSample,
}

/// The IMU settings applied in one call ([`Icm20789::configure_imu`]): the full scales and the
/// gyro low-pass, chosen by the application (a tactile pad, say, takes the finest scales).
///
/// ```
/// use imu_icm20789::{AccelScale, GyroDlpf, GyroScale, ImuSettings};
/// // Small taps: the finest scales, and a gyro low-pass above a 30 Hz frame rate's band.
/// let pad = ImuSettings {
///     accel_scale: AccelScale::G2,
///     gyro_scale: GyroScale::Dps250,
///     gyro_dlpf: GyroDlpf::Hz41,
/// };
/// # let _ = pad;
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImuSettings {
    /// Accelerometer full scale.
    pub accel_scale: AccelScale,
    /// Gyroscope full scale.
    pub gyro_scale: GyroScale,
    /// Gyroscope low-pass filter.
    pub gyro_dlpf: GyroDlpf,
}

/// CONFIG, GYRO_CONFIG, ACCEL_CONFIG, ACCEL_CONFIG2 (0x1A…0x1D) as last written, so that a
/// setting change is one write, not a read-modify-write. All zero after DEVICE_RESET.
type Shadow = [u8; 4];

/// ICM-20789 driver over an embedded-hal I2C bus (blocking: `Icm20789`; async: `Icm20789Async`).
#[maybe_async_cfg::maybe(
    idents(
        I2cBus(sync = "SyncI2c", async = "AsyncI2c"),
        Delay(sync = "SyncDelayNs", async = "AsyncDelayNs")
    ),
    sync(keep_self),
    async(feature = "async", self = "Icm20789Async")
)]
#[derive(Debug)]
pub struct Icm20789<I2C> {
    i2c: I2C,
    address: u8,
    accel_scale: AccelScale,
    gyro_scale: GyroScale,
    shadow: Shadow,
    calibration: Option<Calibration>,
}

#[maybe_async_cfg::maybe(
    idents(
        I2cBus(sync = "SyncI2c", async = "AsyncI2c"),
        Delay(sync = "SyncDelayNs", async = "AsyncDelayNs")
    ),
    sync(keep_self),
    async(feature = "async", self = "Icm20789Async")
)]
impl<I2C: I2cBus> Icm20789<I2C> {
    /// A driver for the IMU at 0x68 (AD0 low). Nothing is sent on the bus.
    pub fn new_with_i2c(i2c: I2C) -> Self {
        Self::new_with_i2c_address(i2c, ImuAddress::Ad0Low)
    }

    /// A driver for the IMU at the given address. Nothing is sent on the bus.
    pub fn new_with_i2c_address(i2c: I2C, address: ImuAddress) -> Self {
        Self {
            i2c,
            address: address.addr(),
            accel_scale: AccelScale::G2,
            gyro_scale: GyroScale::Dps250,
            shadow: [0; 4],
            calibration: None,
        }
    }

    /// Gives the bus back.
    pub fn destroy(self) -> I2C {
        self.i2c
    }

    /// The barometer calibration, once [`Self::init_barometer`] has read it.
    pub fn calibration(&self) -> Option<Calibration> {
        self.calibration
    }

    /// The accelerometer full scale in use.
    pub fn accel_scale(&self) -> AccelScale {
        self.accel_scale
    }

    /// The gyroscope full scale in use.
    pub fn gyro_scale(&self) -> GyroScale {
        self.gyro_scale
    }

    async fn write_reg(&mut self, register: u8, value: u8) -> Result<(), Error<I2C::Error>> {
        self.i2c
            .write(self.address, &[register, value])
            .await
            .map_err(Error::I2c)
    }

    async fn read_regs(&mut self, register: u8, buf: &mut [u8]) -> Result<(), Error<I2C::Error>> {
        self.i2c
            .write_read(self.address, &[register], buf)
            .await
            .map_err(Error::I2c)
    }

    async fn baro_command(&mut self, bytes: &[u8]) -> Result<(), Error<I2C::Error>> {
        self.i2c
            .write(BARO_ADDRESS, bytes)
            .await
            .map_err(Error::I2c)
    }

    async fn baro_read(&mut self, buf: &mut [u8]) -> Result<(), Error<I2C::Error>> {
        self.i2c.read(BARO_ADDRESS, buf).await.map_err(Error::I2c)
    }

    /// Reads WHO_AM_I and returns it if it is an ICM-20789 (0x03) or its rev R1 (0x02).
    pub async fn who_am_i(&mut self) -> Result<u8, Error<I2C::Error>> {
        let mut id = [0];
        self.read_regs(reg::WHO_AM_I, &mut id).await?;
        match id[0] {
            reg::WHO_AM_I_ICM20789 | reg::WHO_AM_I_ICM20789_R1 => Ok(id[0]),
            other => Err(Error::WrongImuId(other)),
        }
    }

    /// Checks the ID, resets the IMU, waits 100 ms and wakes it (auto clock, all axes on).
    /// Settings return to ±2 g, ±250 °/s, DLPF 0, divider 0.
    pub async fn init<D: Delay>(&mut self, delay: &mut D) -> Result<u8, Error<I2C::Error>> {
        let id = self.who_am_i().await?;
        self.write_reg(reg::PWR_MGMT_1, reg::DEVICE_RESET).await?;
        delay.delay_us(reg::RESET_TIME_US).await;
        self.shadow = [0; 4];
        self.accel_scale = AccelScale::G2;
        self.gyro_scale = GyroScale::Dps250;
        self.calibration = None;
        self.write_reg(reg::PWR_MGMT_1, reg::CLKSEL_AUTO).await?;
        self.write_reg(reg::PWR_MGMT_2, 0).await?;
        Ok(id)
    }

    /// Replaces the `mask` bits of a shadowed configuration register with `bits`.
    async fn write_field(
        &mut self,
        register: u8,
        mask: u8,
        bits: u8,
    ) -> Result<(), Error<I2C::Error>> {
        let slot = usize::from(register - reg::CONFIG);
        let value = (self.shadow[slot] & !mask) | (bits & mask);
        self.write_reg(register, value).await?;
        self.shadow[slot] = value;
        Ok(())
    }

    /// Sets the accelerometer full scale.
    pub async fn set_accel_scale(&mut self, scale: AccelScale) -> Result<(), Error<I2C::Error>> {
        self.write_field(reg::ACCEL_CONFIG, 0b1_1000, scale.bits() << 3)
            .await?;
        self.accel_scale = scale;
        Ok(())
    }

    /// Sets the gyroscope full scale.
    pub async fn set_gyro_scale(&mut self, scale: GyroScale) -> Result<(), Error<I2C::Error>> {
        self.write_field(reg::GYRO_CONFIG, 0b1_1000, scale.bits() << 3)
            .await?;
        self.gyro_scale = scale;
        Ok(())
    }

    /// Sets the gyro / temperature low-pass filter (FCHOICE_B stays 0 so the DLPF is used).
    pub async fn set_gyro_dlpf(&mut self, dlpf: GyroDlpf) -> Result<(), Error<I2C::Error>> {
        self.write_field(reg::CONFIG, 0b111, dlpf.bits()).await
    }

    /// Sets the accelerometer low-pass filter (ACCEL_FCHOICE_B stays 0).
    pub async fn set_accel_dlpf(&mut self, dlpf: AccelDlpf) -> Result<(), Error<I2C::Error>> {
        self.write_field(reg::ACCEL_CONFIG2, 0b1111, dlpf.bits())
            .await
    }

    /// Sets SMPLRT_DIV: output rate 1 kHz / (1 + `divider`) for DLPF settings 1…6.
    pub async fn set_sample_rate_divider(&mut self, divider: u8) -> Result<(), Error<I2C::Error>> {
        self.write_reg(reg::SMPLRT_DIV, divider).await
    }

    /// Reads accel, temperature and gyro in one 14-byte burst, as counts.
    pub async fn read_imu_raw(&mut self) -> Result<RawImu, Error<I2C::Error>> {
        let mut bytes = [0; BURST_LEN];
        self.read_regs(reg::ACCEL_XOUT_H, &mut bytes).await?;
        Ok(RawImu::from_bytes(&bytes))
    }

    /// Reads accel, temperature and gyro in one 14-byte burst, in m/s², rad/s and °C.
    pub async fn read_imu(&mut self) -> Result<ImuSample, Error<I2C::Error>> {
        let raw = self.read_imu_raw().await?;
        Ok(ImuSample {
            accel_mps2: raw.accel.map(|c| self.accel_scale.to_mps2(c)),
            gyro_rps: raw.gyro.map(|c| self.gyro_scale.to_rps(c)),
            temperature_c: imu_temperature_c(raw.temp),
        })
    }

    /// Empties the FIFO and starts filling it with accel + gyro records (12 bytes each).
    pub async fn enable_fifo(&mut self) -> Result<(), Error<I2C::Error>> {
        self.write_reg(reg::FIFO_EN, reg::FIFO_ACCEL_GYRO).await?;
        self.write_reg(reg::USER_CTRL, reg::USER_FIFO_EN | reg::FIFO_RST)
            .await
    }

    /// Bytes waiting in the FIFO.
    pub async fn fifo_count(&mut self) -> Result<u16, Error<I2C::Error>> {
        let mut count = [0; 2];
        self.read_regs(reg::FIFO_COUNTH, &mut count).await?;
        Ok(u16::from_be_bytes(count) & 0x1FFF)
    }

    /// Pops one accel + gyro record from the FIFO (temperature is not in the FIFO: NaN).
    /// Call only when [`Self::fifo_count`] reports at least 12 bytes.
    pub async fn read_fifo_record(&mut self) -> Result<ImuSample, Error<I2C::Error>> {
        let mut bytes = [0; reg::FIFO_RECORD_LEN];
        self.read_regs(reg::FIFO_R_W, &mut bytes).await?;
        let w = |i: usize| i16::from_be_bytes([bytes[2 * i], bytes[2 * i + 1]]);
        Ok(ImuSample {
            accel_mps2: [w(0), w(1), w(2)].map(|c| self.accel_scale.to_mps2(c)),
            gyro_rps: [w(3), w(4), w(5)].map(|c| self.gyro_scale.to_rps(c)),
            temperature_c: f32::NAN,
        })
    }

    /// Sets INT_PIN_CFG.BYPASS_EN so that the barometer at 0x63 is reachable.
    pub async fn enable_bypass(&mut self) -> Result<(), Error<I2C::Error>> {
        self.write_reg(reg::INT_PIN_CFG, reg::BYPASS_EN).await
    }

    /// Reads and checks the barometer's ID word (`id & 0x3F == 0x08`).
    pub async fn barometer_id(&mut self) -> Result<u16, Error<I2C::Error>> {
        self.baro_command(&baro_cmd::READ_ID).await?;
        let mut bytes = [0; 3];
        self.baro_read(&mut bytes).await?;
        let id = crc8::decode_word(bytes)
            .map_err(|(received, computed)| Error::Crc { received, computed })?;
        if id & 0x3F == baro_cmd::BARO_ID {
            Ok(id)
        } else {
            Err(Error::WrongBaroId(id))
        }
    }

    /// Reads the four OTP calibration words, each CRC-checked.
    pub async fn read_otp(&mut self) -> Result<Calibration, Error<I2C::Error>> {
        self.baro_command(&otp::OTP_SETUP).await?;
        let mut reads = [[0_u8; 3]; 4];
        for read in reads.iter_mut() {
            self.baro_command(&otp::OTP_READ_NEXT).await?;
            self.baro_read(read).await?;
        }
        Calibration::from_otp_reads(reads)
    }

    /// Bypass on, barometer soft reset, 10 ms wait, ID check, OTP read. Keeps and returns
    /// the calibration.
    pub async fn init_barometer<D: Delay>(
        &mut self,
        delay: &mut D,
    ) -> Result<Calibration, Error<I2C::Error>> {
        self.enable_bypass().await?;
        self.baro_command(&baro_cmd::SOFT_RESET).await?;
        delay.delay_us(baro_cmd::SOFT_RESET_TIME_US).await;
        self.barometer_id().await?;
        let calibration = self.read_otp().await?;
        self.calibration = Some(calibration);
        Ok(calibration)
    }

    /// Starts a pressure + temperature conversion; read it with [`Self::read_pressure`] after
    /// [`BaroConversion::wait_us`].
    pub async fn start_pressure(
        &mut self,
        mode: BaroMode,
        order: FrameOrder,
    ) -> Result<BaroConversion, Error<I2C::Error>> {
        self.baro_command(&mode.command(order).to_be_bytes())
            .await?;
        Ok(BaroConversion { mode, order })
    }

    /// Reads a finished conversion's raw codes (CRC-checked).
    pub async fn read_pressure_raw(
        &mut self,
        conversion: BaroConversion,
    ) -> Result<RawSample, Error<I2C::Error>> {
        let mut bytes = [0; FRAME_LEN];
        self.baro_read(&mut bytes).await?;
        frame::decode_frame(&bytes, conversion.order)
    }

    /// Reads a finished conversion and converts it with `calibration` (float path).
    pub async fn read_pressure_with(
        &mut self,
        conversion: BaroConversion,
        calibration: &Calibration,
    ) -> Result<BaroSample, Error<I2C::Error>> {
        let raw = self.read_pressure_raw(conversion).await?;
        let pressure_pa = calibration.pressure_pa(raw)? as f32;
        Ok(BaroSample {
            raw,
            pressure_pa,
            temperature_c: crate::baro::conversion::temperature_c(raw.t_lsb),
        })
    }

    /// Reads a finished conversion and converts it with the calibration read by
    /// [`Self::init_barometer`]; [`Error::BaroNotInitialised`] before that.
    pub async fn read_pressure(
        &mut self,
        conversion: BaroConversion,
    ) -> Result<BaroSample, Error<I2C::Error>> {
        let calibration = self.calibration.ok_or(Error::BaroNotInitialised)?;
        self.read_pressure_with(conversion, &calibration).await
    }

    /// Applies `settings` (full scales and the gyro low-pass): three register writes.
    pub async fn configure_imu(&mut self, settings: &ImuSettings) -> Result<(), Error<I2C::Error>> {
        self.set_accel_scale(settings.accel_scale).await?;
        self.set_gyro_scale(settings.gyro_scale).await?;
        self.set_gyro_dlpf(settings.gyro_dlpf).await
    }

    /// One frame of the whole chip, as a multimodal tactile pad reads it (Al &
    /// Martinez-Hernandez, "Multimodal barometric and inertial measurement unit based tactile
    /// sensor for robot control", §III): start a pressure conversion in `mode` (pressure first), read the IMU burst while it runs, wait the conversion's
    /// worst-case time, read the pressure. Needs [`Self::init_barometer`] first.
    pub async fn read_frame<D: Delay>(
        &mut self,
        mode: BaroMode,
        delay: &mut D,
    ) -> Result<ChipFrame, Error<I2C::Error>> {
        let conversion = self.start_pressure(mode, FrameOrder::PressureFirst).await?;
        let imu = self.read_imu().await?;
        delay.delay_us(conversion.wait_us()).await;
        let baro = self.read_pressure(conversion).await?;
        Ok(ChipFrame { imu, baro })
    }

    /// Start, wait the worst-case conversion time, read: one blocking pressure measurement.
    pub async fn measure_pressure<D: Delay>(
        &mut self,
        mode: BaroMode,
        order: FrameOrder,
        delay: &mut D,
    ) -> Result<BaroSample, Error<I2C::Error>> {
        let conversion = self.start_pressure(mode, order).await?;
        delay.delay_us(conversion.wait_us()).await;
        self.read_pressure(conversion).await
    }
}
