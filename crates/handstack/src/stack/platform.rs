//! Where the stack opens hardware. [`LinuxPlatform`], the default, opens Linux I2C device files
//! through linux-embedded-hal, sleeps for a driver's delays and stamps frames with the wall
//! clock; every platform reaches the I2C of an Arduino running Firmata on a serial port
//! ([`Platform::open_firmata_i2c`]). Another platform (a USB–I2C bridge, another OS, or a
//! test's substitute bus) supplies its own buses, delay and clock; the stack holds every bus as
//! an [`I2cBus`], so the drivers above it and the runners above them never know which platform
//! they are on.
//!
//! ```no_run
//! use handstack::stack::platform::{LinuxPlatform, Platform};
//!
//! let platform = LinuxPlatform::new();
//! let bus = platform.open_i2c("/dev/i2c-1")?; // any embedded-hal `I2c`, errors as text
//! // An Arduino's I2C, through StandardFirmata at its 57 600 baud.
//! let board = platform.open_firmata_i2c("/dev/ttyACM0", 57_600)?;
//! # Ok::<(), String>(())
//! ```

use embedded_hal::delay::DelayNs;
use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, Operation, SevenBitAddress};
use hand_control::grasp_loop::{LoopClock, StdClock};

/// A bus error, as the bus described it. Its `Debug` is its words too: drivers generic over
/// their bus can only print a bus error's `Debug`, and their messages reach users.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[error("{detail}")]
pub struct BusError {
    /// embedded-hal's classification (NACK, arbitration loss, …).
    pub kind: ErrorKind,
    /// The bus's own error, formatted.
    pub detail: String,
}

impl core::fmt::Debug for BusError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.detail)
    }
}

impl embedded_hal::i2c::Error for BusError {
    fn kind(&self) -> ErrorKind {
        self.kind
    }
}

/// Any embedded-hal I2C bus, its errors as [`BusError`]: what a [`Platform`] hands the stack.
pub struct I2cBus(Box<dyn I2c<Error = BusError> + Send>);

impl I2cBus {
    /// Wraps `bus`; its errors' texts are their `Display`.
    pub fn new<B>(bus: B) -> I2cBus
    where
        B: I2c + Send + 'static,
        B::Error: core::fmt::Display,
    {
        I2cBus(Box::new(Erased(bus)))
    }
}

impl core::fmt::Debug for I2cBus {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("I2cBus")
    }
}

impl ErrorType for I2cBus {
    type Error = BusError;
}

impl I2c for I2cBus {
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), BusError> {
        self.0.transaction(address, operations)
    }
}

/// A bus whose errors become [`BusError`]s (formatting only on the error path).
struct Erased<B>(B);

impl<B: I2c> ErrorType for Erased<B> {
    type Error = BusError;
}

impl<B: I2c> I2c for Erased<B>
where
    B::Error: core::fmt::Display,
{
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), BusError> {
        self.0
            .transaction(address, operations)
            .map_err(|e| BusError {
                kind: embedded_hal::i2c::Error::kind(&e),
                detail: e.to_string(),
            })
    }
}

/// What the stack opens hardware through.
pub trait Platform {
    /// Opens the I2C bus at `path` (a device file such as `/dev/i2c-1` on Linux); the error
    /// says why it cannot be opened.
    fn open_i2c(&self, path: &str) -> Result<I2cBus, String>;
    /// Opens the I2C bus of the Arduino on the serial port `port`, running StandardFirmata or
    /// ConfigurableFirmata at `baud`: through the reset the board makes when its port opens,
    /// to its version report (firmata-host). The error says what the board did not do. The
    /// default is [`open_firmata_i2c`], on any serial port serial2 opens.
    fn open_firmata_i2c(&self, port: &str, baud: u32) -> Result<I2cBus, String> {
        open_firmata_i2c(port, baud)
    }
    /// A delay for the drivers' conversion waits.
    fn delay(&self) -> Box<dyn DelayNs + Send>;
    /// A clock for the devices' frame stamps and the loops. Every clock a platform hands out
    /// shares one epoch, so a frame's stamp and the loop reading it agree.
    fn clock(&self) -> Box<dyn LoopClock + Send>;
}

/// The I2C bus of the Firmata board on `port` at `baud`, opened with firmata-host's defaults
/// otherwise (5 s for the board's reset, 1 s per reply); a board that does not answer, or
/// answers with something other than Firmata, is an error in words:
///
/// ```no_run
/// let bus = handstack::stack::platform::open_firmata_i2c("/dev/ttyACM0", 57_600)?;
/// # Ok::<(), String>(())
/// ```
pub fn open_firmata_i2c(port: &str, baud: u32) -> Result<I2cBus, String> {
    let options = firmata_host::Options {
        baud,
        ..firmata_host::Options::default()
    };
    match firmata_host::Board::open(port, &options) {
        Ok(board) => Ok(I2cBus::new(board)),
        Err(e) => Err(match e.kind {
            firmata_host::ErrorKind::Timeout { .. } => format!(
                "Firmata board: {} (at {baud} baud; is StandardFirmata or ConfigurableFirmata \
                 running on it?)",
                e.kind
            ),
            kind => format!("Firmata board: {kind}"),
        }),
    }
}

/// Linux: I2C through `/dev/i2c-*` (linux-embedded-hal), delays by sleeping, the wall clock
/// from when the platform was made.
#[derive(Debug, Clone, Copy, Default)]
pub struct LinuxPlatform {
    clock: StdClock,
}

impl LinuxPlatform {
    /// The platform, its clock's epoch now.
    pub fn new() -> LinuxPlatform {
        LinuxPlatform::default()
    }
}

impl Platform for LinuxPlatform {
    fn open_i2c(&self, path: &str) -> Result<I2cBus, String> {
        linux_embedded_hal::I2cdev::new(path)
            .map(I2cBus::new)
            .map_err(|e| e.to_string())
    }

    fn delay(&self) -> Box<dyn DelayNs + Send> {
        Box::new(linux_embedded_hal::Delay)
    }

    fn clock(&self) -> Box<dyn LoopClock + Send> {
        Box::new(self.clock)
    }
}
