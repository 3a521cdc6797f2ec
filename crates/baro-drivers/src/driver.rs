//! The MS5611 driver: construction, reset, PROM, split-phase conversions and `measure`.
//!
//! One source gives both the blocking [`Ms5611`] (embedded-hal) and, with the `async`
//! feature, `Ms5611Async` (embedded-hal-async).

use crate::command;
use crate::compensation::{Calibration, Measurement};
use crate::error::{Error, ModeChangeError};
use crate::interface::{Address, I2cInterface, SpiInterface};
use crate::mode::{Ready, Uninit};
use crate::osr::Osr;
use crate::prom::Prom;

/// Which quantity an ADC conversion measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Channel {
    /// D1, the uncompensated pressure code.
    Pressure,
    /// D2, the uncompensated temperature code.
    Temperature,
}

/// One raw 24-bit ADC result and what produced it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RawSample {
    /// D1 or D2.
    pub channel: Channel,
    /// The ratio it was converted at.
    pub osr: Osr,
    /// The code, 1 … 2^24 − 1.
    pub code: u32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Pending {
    channel: Channel,
    osr: Osr,
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async")
)]
/// An MS5611 reached through `DI` (an [`I2cInterface`] or [`SpiInterface`]), in mode `S`
/// ([`Uninit`] until its PROM passed the CRC, then [`Ready`]).
#[derive(Debug)]
pub struct Ms5611<DI, S> {
    iface: DI,
    state: S,
    pending: Option<Pending>,
    last_d2: Option<u32>,
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<I2C> Ms5611<I2cInterface<I2C>, Uninit> {
    /// A driver for the chip at `address` on `i2c`. Nothing is sent until `init`.
    pub fn new_with_i2c(i2c: I2C, address: Address) -> Self {
        Self::with_interface(I2cInterface {
            i2c,
            address: address.addr(),
        })
    }
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<SPI> Ms5611<SpiInterface<SPI>, Uninit> {
    /// A driver for the chip behind the chip select of `spi`. Nothing is sent until `init`.
    pub fn new_with_spi(spi: SPI) -> Self {
        Self::with_interface(SpiInterface { spi })
    }
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<DI> Ms5611<DI, Uninit> {
    /// A driver over any [`Transport`](crate::Transport) implementation.
    pub fn with_interface(iface: DI) -> Self {
        Self {
            iface,
            state: Uninit,
            pending: None,
            last_d2: None,
        }
    }
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<I2C, S> Ms5611<I2cInterface<I2C>, S> {
    /// Gives the I2C bus back.
    pub fn destroy(self) -> I2C {
        self.iface.i2c
    }
}

#[maybe_async_cfg::maybe(
    idents(Ms5611(sync, async = "Ms5611Async")),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<SPI, S> Ms5611<SpiInterface<SPI>, S> {
    /// Gives the SPI device back.
    pub fn destroy(self) -> SPI {
        self.iface.spi
    }
}

#[maybe_async_cfg::maybe(
    idents(
        Ms5611(sync, async = "Ms5611Async"),
        Transport(sync, async = "AsyncTransport"),
        hal(sync = "embedded_hal", async = "embedded_hal_async")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<DI, E, S> Ms5611<DI, S>
where
    DI: crate::Transport<Error = E>,
{
    /// Sends the reset command and waits the 2.8 ms the chip needs to reload its PROM.
    /// Any conversion in flight is lost.
    pub async fn reset<D: hal::delay::DelayNs>(&mut self, delay: &mut D) -> Result<(), Error<E>> {
        self.pending = None;
        self.iface
            .command(command::RESET)
            .await
            .map_err(Error::Comm)?;
        delay.delay_ns(command::RESET_TIME_NS).await;
        Ok(())
    }

    /// Reads the eight PROM words as they are, without checking them.
    pub async fn read_prom(&mut self) -> Result<Prom, Error<E>> {
        let mut words = [0u16; 8];
        for (index, word) in (0u8..).zip(words.iter_mut()) {
            let mut buf = [0u8; 2];
            self.iface
                .command_read(command::prom_read(index), &mut buf)
                .await
                .map_err(Error::Comm)?;
            *word = u16::from_be_bytes(buf);
        }
        Ok(Prom::from_words(words))
    }
}

#[maybe_async_cfg::maybe(
    idents(
        Ms5611(sync, async = "Ms5611Async"),
        Transport(sync, async = "AsyncTransport"),
        hal(sync = "embedded_hal", async = "embedded_hal_async")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<DI, E> Ms5611<DI, Uninit>
where
    DI: crate::Transport<Error = E>,
{
    /// Resets the chip, reads its PROM and checks the CRC-4. On failure the device comes back
    /// unchanged inside the error, so the bus is never lost.
    pub async fn init<D: hal::delay::DelayNs>(
        mut self,
        delay: &mut D,
    ) -> Result<Ms5611<DI, Ready>, ModeChangeError<Error<E>, Self>> {
        let calibration = match self.read_checked_prom(delay).await {
            Ok(c) => c,
            Err(error) => return Err(ModeChangeError { error, dev: self }),
        };
        Ok(Ms5611 {
            iface: self.iface,
            state: Ready { calibration },
            pending: None,
            last_d2: None,
        })
    }

    async fn read_checked_prom<D: hal::delay::DelayNs>(
        &mut self,
        delay: &mut D,
    ) -> Result<Calibration, Error<E>> {
        self.reset(delay).await?;
        Ok(self.read_prom().await?.calibration()?)
    }
}

#[maybe_async_cfg::maybe(
    idents(
        Ms5611(sync, async = "Ms5611Async"),
        Transport(sync, async = "AsyncTransport"),
        hal(sync = "embedded_hal", async = "embedded_hal_async")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<DI, E> Ms5611<DI, Ready>
where
    DI: crate::Transport<Error = E>,
{
    /// The coefficients read from the PROM.
    pub fn calibration(&self) -> &Calibration {
        &self.state.calibration
    }

    /// Starts a D1 (pressure) conversion; read it with `read_result` after
    /// [`Osr::conversion_time_max_ns`]. Other sensors can convert meanwhile.
    pub async fn start_pressure(&mut self, osr: Osr) -> Result<(), Error<E>> {
        self.start(Channel::Pressure, osr).await
    }

    /// Starts a D2 (temperature) conversion; read it with `read_result` after
    /// [`Osr::conversion_time_max_ns`].
    pub async fn start_temperature(&mut self, osr: Osr) -> Result<(), Error<E>> {
        self.start(Channel::Temperature, osr).await
    }

    async fn start(&mut self, channel: Channel, osr: Osr) -> Result<(), Error<E>> {
        let byte = match channel {
            Channel::Pressure => command::convert_d1(osr),
            Channel::Temperature => command::convert_d2(osr),
        };
        // A failed command may or may not have reached the chip: forget the old conversion.
        self.pending = None;
        self.iface.command(byte).await.map_err(Error::Comm)?;
        self.pending = Some(Pending { channel, osr });
        Ok(())
    }

    /// Reads the result of the conversion last started. A temperature code is also kept for
    /// [`compensate`](Self::compensate). Reading early gives [`Error::AdcNotReady`] and, as on
    /// the real chip, loses that conversion.
    pub async fn read_result(&mut self) -> Result<RawSample, Error<E>> {
        let pending = self.pending.take().ok_or(Error::NoConversionStarted)?;
        let mut buf = [0u8; 3];
        self.iface
            .command_read(command::ADC_READ, &mut buf)
            .await
            .map_err(Error::Comm)?;
        let code = u32::from_be_bytes([0, buf[0], buf[1], buf[2]]);
        if code == 0 {
            return Err(Error::AdcNotReady);
        }
        if pending.channel == Channel::Temperature {
            self.last_d2 = Some(code);
        }
        Ok(RawSample {
            channel: pending.channel,
            osr: pending.osr,
            code,
        })
    }

    /// The last temperature code (D2) read, if any.
    pub fn latest_temperature_code(&self) -> Option<u32> {
        self.last_d2
    }

    /// Compensates a pressure code `d1` with the last temperature code read. Temperature
    /// drifts slowly, so a fast loop may convert D2 only every few D1. A `d1` above 24 bits
    /// (not one [`read_result`](Self::read_result) gave) is
    /// [`Error::Compensation`] with
    /// [`CompensationError::CodeOutOfRange`](crate::CompensationError::CodeOutOfRange).
    pub fn compensate(&self, d1: u32) -> Result<Measurement, Error<E>> {
        let d2 = self.last_d2.ok_or(Error::NoTemperature)?;
        Ok(self.state.calibration.compensate(d1, d2)?)
    }

    /// Converts D2 then D1 at `osr`, waiting the maximum conversion time for each, and
    /// compensates: the simple blocking way, 2 × conversion time per call.
    pub async fn measure<D: hal::delay::DelayNs>(
        &mut self,
        delay: &mut D,
        osr: Osr,
    ) -> Result<Measurement, Error<E>> {
        self.start_temperature(osr).await?;
        delay.delay_ns(osr.conversion_time_max_ns()).await;
        self.read_result().await?;
        self.start_pressure(osr).await?;
        delay.delay_ns(osr.conversion_time_max_ns()).await;
        let d1 = self.read_result().await?.code;
        self.compensate(d1)
    }
}
