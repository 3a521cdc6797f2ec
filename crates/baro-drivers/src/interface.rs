//! The two ways to reach the chip: I2C (0x76 / 0x77) and SPI (one `SpiDevice`, i.e. one chip
//! select, per sensor). The driver sees both through [`Transport`].

/// I2C address, set by the CSB pin (datasheet p. 10: address `111011C`, C = complement of CSB).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Address {
    /// CSB tied low: 0x77 (the default on most boards).
    #[default]
    CsbLow,
    /// CSB tied high: 0x76.
    CsbHigh,
}

impl Address {
    /// The 7-bit address.
    pub const fn addr(self) -> u8 {
        match self {
            Address::CsbLow => 0x77,
            Address::CsbHigh => 0x76,
        }
    }
}

/// An MS5611 on an I2C bus.
#[derive(Debug)]
pub struct I2cInterface<I2C> {
    pub(crate) i2c: I2C,
    pub(crate) address: u8,
}

/// An MS5611 on an SPI bus, behind its own chip select.
#[derive(Debug)]
pub struct SpiInterface<SPI> {
    pub(crate) spi: SPI,
}

/// How the driver talks to one chip: send a command byte, optionally read the answer.
/// Implemented for [`I2cInterface`] and [`SpiInterface`]; implement it for any other link.
#[maybe_async_cfg::maybe(sync(keep_self), async(feature = "async", self = "AsyncTransport"))]
#[allow(async_fn_in_trait)]
pub trait Transport {
    /// The bus error.
    type Error;
    /// Sends one command byte.
    async fn command(&mut self, command: u8) -> Result<(), Self::Error>;
    /// Sends one command byte and reads `answer.len()` bytes of answer.
    async fn command_read(&mut self, command: u8, answer: &mut [u8]) -> Result<(), Self::Error>;
}

#[maybe_async_cfg::maybe(
    idents(
        hal(sync = "embedded_hal", async = "embedded_hal_async"),
        Transport(sync, async = "AsyncTransport")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<I2C: hal::i2c::I2c> Transport for I2cInterface<I2C> {
    type Error = I2C::Error;

    async fn command(&mut self, command: u8) -> Result<(), Self::Error> {
        self.i2c.write(self.address, &[command]).await
    }

    // Two messages, write then read, as the datasheet's I2C figures show (no repeated start).
    async fn command_read(&mut self, command: u8, answer: &mut [u8]) -> Result<(), Self::Error> {
        self.i2c.write(self.address, &[command]).await?;
        self.i2c.read(self.address, answer).await
    }
}

#[maybe_async_cfg::maybe(
    idents(
        hal(sync = "embedded_hal", async = "embedded_hal_async"),
        Transport(sync, async = "AsyncTransport")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl<SPI: hal::spi::SpiDevice> Transport for SpiInterface<SPI> {
    type Error = SPI::Error;

    async fn command(&mut self, command: u8) -> Result<(), Self::Error> {
        self.spi.write(&[command]).await
    }

    // Command and answer inside one chip-select assertion.
    async fn command_read(&mut self, command: u8, answer: &mut [u8]) -> Result<(), Self::Error> {
        self.spi
            .transaction(&mut [
                hal::spi::Operation::Write(&[command]),
                hal::spi::Operation::Read(answer),
            ])
            .await
    }
}
