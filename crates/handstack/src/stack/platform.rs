//! Where the stack opens hardware. [`LinuxPlatform`], the default, opens Linux I2C device files
//! through linux-embedded-hal, sleeps for a driver's delays and stamps frames with the wall
//! clock; every platform reaches the I2C of an Arduino running Firmata on a serial port
//! ([`Platform::open_firmata_i2c`]). Another platform (a USB–I2C bridge, another OS, or a
//! test's substitute bus) supplies its own buses, delay and clock; the stack holds every bus as
//! an [`I2cBus`], so the drivers above it and the runners above them never know which platform
//! they are on.
//!
//! Chips that share an address (three MS5611 have two between them) share one bus behind a
//! TCA9548A switch: [`I2cSwitch`] turns the bus into one [`SwitchChannel`] per chip, each an
//! owned, `Send` embedded-hal `I2c` that selects its channel before its transfers.
//!
//! ```no_run
//! use handstack::stack::platform::{I2cBus, I2cSwitch, LinuxPlatform, Platform};
//!
//! let platform = LinuxPlatform::new();
//! let bus = platform.open_i2c("/dev/i2c-1")?; // any embedded-hal `I2c`, errors as text
//! // An Arduino's I2C, through StandardFirmata at its 57 600 baud.
//! let board = platform.open_firmata_i2c("/dev/ttyACM0", 57_600)?;
//! // A TCA9548A at 0x70 on the board: one bus per channel, each as the stack holds buses.
//! let switch = I2cSwitch::new(board, 0x70);
//! let first: I2cBus = I2cBus::new(switch.channel(0).map_err(|e| e.to_string())?);
//! # Ok::<(), String>(())
//! ```

use embedded_hal::delay::DelayNs;
use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, Operation, SevenBitAddress};
use hand_control::grasp_loop::{LoopClock, StdClock};
use std::sync::{Arc, Mutex, MutexGuard};

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

// The switch lives here, beside `I2cBus`, rather than in firmata-host or baro-drivers: it
// needs nothing of Firmata (a Linux bus or a USB–I2C bridge takes one the same way), and it
// shares its bus through `std`'s `Arc<Mutex<…>>` so that each channel is an owned `Send +
// 'static` bus, as the stack holds buses, where baro-drivers is `no_std` and the `xca9548a`
// driver's channels borrow the switch (`I2cSlave<'a, …>` over a `RefCell`, neither `'static`
// nor `Send`).

/// A TCA9548A I2C switch (or a PCA9548A, TCA9546A, TCA9543A: any whose one control byte is the
/// mask of the channels it connects) at `address` on `bus`, shared by handles to its channels.
/// Each [`SwitchChannel`] connects its own channel alone before its transfers, writing the
/// control byte only when another channel (or none yet) is connected; so chips at one address,
/// one per channel, are read as if each had a bus of its own.
///
/// ```
/// use embedded_hal::i2c::{ErrorType, I2c, Operation};
/// use handstack::stack::platform::I2cSwitch;
/// use std::sync::{Arc, Mutex};
///
/// /// A bus that logs who it was asked for (a test's stand-in for a real one).
/// #[derive(Clone, Default)]
/// struct Log(Arc<Mutex<Vec<u8>>>);
/// impl ErrorType for Log {
///     type Error = core::convert::Infallible;
/// }
/// impl I2c for Log {
///     fn transaction(&mut self, a: u8, _: &mut [Operation<'_>]) -> Result<(), Self::Error> {
///         self.0.lock().unwrap().push(a);
///         Ok(())
///     }
/// }
///
/// let log = Log::default();
/// let switch = I2cSwitch::new(log.clone(), 0x70);
/// let (mut a, mut b) = (switch.channel(0)?, switch.channel(1)?);
/// a.write(0x77, &[0x1E])?; // selects channel 0, then the write
/// a.write(0x77, &[0x48])?; // channel 0 is still connected
/// b.write(0x77, &[0x48])?; // selects channel 1
/// assert_eq!(*log.0.lock().unwrap(), [0x70, 0x77, 0x77, 0x70, 0x77]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct I2cSwitch<B> {
    shared: Arc<Mutex<Switched<B>>>,
    address: u8,
}

impl<B> core::fmt::Debug for I2cSwitch<B> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "I2cSwitch({:#04x})", self.address)
    }
}

/// Another handle to the same switch on the same bus.
impl<B> Clone for I2cSwitch<B> {
    fn clone(&self) -> I2cSwitch<B> {
        I2cSwitch {
            shared: Arc::clone(&self.shared),
            address: self.address,
        }
    }
}

/// The bus behind a switch, and the channel mask the switch was last told.
struct Switched<B> {
    bus: B,
    /// `None` until a selection is known (first use, or after a failed write to the switch).
    selected: Option<u8>,
}

/// Locks the switch's bus. A thread that panicked holding it leaves the bus usable but the
/// switch's state unknown: the next transfer selects its channel again.
fn lock<B>(shared: &Mutex<Switched<B>>) -> MutexGuard<'_, Switched<B>> {
    shared.lock().unwrap_or_else(|poisoned| {
        shared.clear_poison();
        let mut s = poisoned.into_inner();
        s.selected = None;
        s
    })
}

/// What failed on a switch: its channel number, or the bus when it was told or asked which
/// channel to connect.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SwitchError<E> {
    /// A channel the switch does not have (it has eight, 0…7).
    #[error("I2C switch channel {0}: a TCA9548A has channels 0…7")]
    NoChannel(u8),
    /// The bus failed writing or reading the switch's control byte (a NACK: no switch there).
    #[error("I2C switch at {address:#04x}: {error}")]
    Bus {
        /// The switch's address.
        address: u8,
        /// The bus's error.
        error: E,
    },
    /// The control byte read back is not the mask just written: another device at the
    /// address, or a switch with fewer channels.
    #[error(
        "I2C switch at {address:#04x}: connecting channel {channel} (mask {wrote:#04x}) reads \
         back {read:#04x}; is a TCA9548A at that address?"
    )]
    Readback {
        /// The switch's address.
        address: u8,
        /// The channel asked for.
        channel: u8,
        /// The mask written.
        wrote: u8,
        /// The byte read back.
        read: u8,
    },
}

impl<B: I2c> I2cSwitch<B> {
    /// The switch at `address` (0x70…0x77 for a TCA9548A) on `bus`, its selection unknown.
    pub fn new(bus: B, address: u8) -> I2cSwitch<B> {
        I2cSwitch {
            shared: Arc::new(Mutex::new(Switched {
                bus,
                selected: None,
            })),
            address,
        }
    }

    /// Its address.
    pub fn address(&self) -> u8 {
        self.address
    }

    /// A bus through channel `channel` (0…7). Handles may be made for any channel, in any
    /// number; they share the bus and take turns on it.
    pub fn channel(&self, channel: u8) -> Result<SwitchChannel<B>, SwitchError<B::Error>> {
        if channel > 7 {
            return Err(SwitchError::NoChannel(channel));
        }
        Ok(SwitchChannel {
            shared: Arc::clone(&self.shared),
            switch: self.address,
            mask: 1 << channel,
        })
    }

    /// Connects channel `channel` and reads the control byte back: a check that a switch
    /// answers at the address and took the selection. Through a bus that reports no NACK on a
    /// write (a Firmata board), this read is the only way to know the switch is there.
    pub fn select(&self, channel: u8) -> Result<(), SwitchError<B::Error>> {
        if channel > 7 {
            return Err(SwitchError::NoChannel(channel));
        }
        let mask = 1u8 << channel;
        let address = self.address;
        let mut s = lock(&self.shared);
        s.selected = None;
        let mut read = [0u8];
        s.bus
            .write(address, &[mask])
            .and_then(|()| s.bus.read(address, &mut read))
            .map_err(|error| SwitchError::Bus { address, error })?;
        if read[0] != mask {
            return Err(SwitchError::Readback {
                address,
                channel,
                wrote: mask,
                read: read[0],
            });
        }
        s.selected = Some(mask);
        Ok(())
    }
}

impl<B: I2c> I2cSwitch<B> {
    /// Reads the control byte: the mask of the channels connected now. Through a bus that
    /// queues its writes (a Firmata board), its answer also says that everything sent before
    /// has been carried out.
    pub fn read_selection(&self) -> Result<u8, SwitchError<B::Error>> {
        let address = self.address;
        let mut s = lock(&self.shared);
        let mut read = [0u8];
        s.bus
            .read(address, &mut read)
            .map_err(|error| SwitchError::Bus { address, error })?;
        s.selected = Some(read[0]);
        Ok(read[0])
    }
}

/// One channel of an [`I2cSwitch`]: an embedded-hal `I2c` (`Send + 'static` when its bus is)
/// whose transactions go to the devices on that channel alone. Its errors are the bus's.
pub struct SwitchChannel<B> {
    shared: Arc<Mutex<Switched<B>>>,
    switch: u8,
    mask: u8,
}

impl<B> core::fmt::Debug for SwitchChannel<B> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "SwitchChannel({:#04x} channel {})",
            self.switch,
            self.channel()
        )
    }
}

impl<B> SwitchChannel<B> {
    /// Its channel, 0…7.
    pub fn channel(&self) -> u8 {
        self.mask.trailing_zeros() as u8
    }
}

impl<B: I2c> ErrorType for SwitchChannel<B> {
    type Error = B::Error;
}

impl<B: I2c> I2c for SwitchChannel<B> {
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), B::Error> {
        let mut s = lock(&self.shared);
        if s.selected != Some(self.mask) {
            // Unknown until the write is known to have gone out.
            s.selected = None;
            s.bus.write(self.switch, &[self.mask])?;
            s.selected = Some(self.mask);
        }
        let result = s.bus.transaction(address, operations);
        if address == self.switch {
            // A transfer to the switch itself through a channel may change its selection.
            s.selected = None;
        }
        result
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

#[cfg(test)]
mod tests {
    use super::{I2cBus, I2cSwitch, SwitchChannel, SwitchError};
    use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock, SimError, Tca9548aSim};
    use baro_drivers::{Address, Measurement, Ms5611, Osr, Scheduler};
    use embedded_hal::i2c::{ErrorType, I2c, Operation};
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Arc, Mutex};

    type Chip = Ms5611Sim<Conditions>;

    /// A bus that counts the transfers to the switch's address (0x70) it passes on.
    struct Counting<B> {
        bus: B,
        selects: Arc<AtomicUsize>,
    }

    impl<B: I2c> ErrorType for Counting<B> {
        type Error = B::Error;
    }

    impl<B: I2c> I2c for Counting<B> {
        fn transaction(&mut self, a: u8, ops: &mut [Operation<'_>]) -> Result<(), B::Error> {
            if a == 0x70 {
                self.selects.fetch_add(1, Ordering::Relaxed);
            }
            self.bus.transaction(a, ops)
        }
    }

    /// Three MS5611 chip models at 0x77 behind a TCA9548A model at 0x70, on channels 0, 1
    /// and 2 (at 1000, 1010 and 1020 mbar), as one bus that counts the switch's transfers.
    fn fingertip(clock: &SimClock) -> (Counting<Tca9548aSim<Chip>>, Arc<AtomicUsize>) {
        let mut mux = Tca9548aSim::new(0x70, clock.clone(), BusTiming::default());
        for (channel, mbar) in [(0u8, 1000.0), (1, 1010.0), (2, 1020.0)] {
            let air = Conditions {
                pressure_mbar: mbar,
                temperature_celsius: 21.0,
            };
            mux = mux.attach(
                channel,
                Ms5611Sim::new(air, clock.clone()).with_noise(false),
            );
        }
        let selects = Arc::new(AtomicUsize::new(0));
        let bus = Counting {
            bus: mux,
            selects: Arc::clone(&selects),
        };
        (bus, selects)
    }

    #[test]
    fn each_channel_reads_its_own_chip_and_selects_only_when_the_channel_changes() {
        let clock = SimClock::new();
        let (bus, selects) = fingertip(&clock);
        let switch = I2cSwitch::new(bus, 0x70);
        let mut delay = clock.delay();
        let mut chips = Vec::new();
        for channel in 0..3 {
            let chip = Ms5611::new_with_i2c(switch.channel(channel).unwrap(), Address::CsbLow)
                .init(&mut delay)
                .map_err(|e| e.error)
                .unwrap();
            chips.push(chip);
        }
        // Opening: one selection per chip, however many transfers its reset and PROM took.
        assert_eq!(selects.load(Ordering::Relaxed), 3);
        let mut out = [Measurement {
            temperature_centi_celsius: 0,
            pressure_pa: 0,
        }; 3];
        Scheduler::new(Osr::Osr1024)
            .sample_all(&mut chips, &mut delay, &mut out)
            .unwrap();
        for (k, m) in out.iter().enumerate() {
            let want = 100_000 + 1000 * k as i32;
            assert!((m.pressure_pa - want).abs() <= 5, "sensor {k}: {m:?}");
        }
        // A cycle visits the sensors in turn three times (D2 start; D2 read + D1 start; D1
        // read): three selections each time, none between a sensor's read and its next start.
        assert_eq!(selects.load(Ordering::Relaxed), 3 + 9);
        // The same channel again: no selection.
        chips[2].measure(&mut delay, Osr::Osr256).unwrap();
        assert_eq!(selects.load(Ordering::Relaxed), 3 + 9);
    }

    #[test]
    fn select_reads_the_selection_back_and_names_what_is_missing() {
        let clock = SimClock::new();
        let (bus, selects) = fingertip(&clock);
        let switch = I2cSwitch::new(bus, 0x70);
        switch.select(2).unwrap();
        // A channel handle for the channel just selected does not select it again.
        let mut c2 = switch.channel(2).unwrap();
        let mut prom = [0u8; 2];
        c2.write_read(0x77, &[0xA2], &mut prom).unwrap();
        assert_eq!(
            selects.load(Ordering::Relaxed),
            2,
            "the write and the read back"
        );
        assert!(matches!(switch.select(8), Err(SwitchError::NoChannel(8))));
        assert!(switch.channel(8).is_err());
        assert_eq!(switch.channel(5).unwrap().channel(), 5);

        // No switch at 0x71: the read back is not acknowledged.
        let (bus, _) = fingertip(&clock);
        let e = I2cSwitch::new(bus, 0x71).select(0).unwrap_err();
        assert_eq!(
            e,
            SwitchError::Bus {
                address: 0x71,
                error: SimError::NoAcknowledgeAddress(0x71)
            }
        );
        assert_eq!(
            e.to_string(),
            "I2C switch at 0x71: no acknowledge at address 0x71"
        );
    }

    /// A device at the switch's address that always reads 0xFF.
    struct NotASwitch;

    impl ErrorType for NotASwitch {
        type Error = core::convert::Infallible;
    }

    impl I2c for NotASwitch {
        fn transaction(&mut self, _: u8, ops: &mut [Operation<'_>]) -> Result<(), Self::Error> {
            for op in ops {
                if let Operation::Read(buf) = op {
                    buf.fill(0xFF);
                }
            }
            Ok(())
        }
    }

    #[test]
    fn another_device_at_the_address_is_not_taken_for_a_switch() {
        let e = I2cSwitch::new(NotASwitch, 0x70).select(1).unwrap_err();
        assert_eq!(
            e.to_string(),
            "I2C switch at 0x70: connecting channel 1 (mask 0x02) reads back 0xff; is a \
             TCA9548A at that address?"
        );
    }

    /// A bus that logs each transfer's address and panics in its second (a bug in a bus
    /// beneath the switch, after the switch took its selection).
    struct PanicsOnce {
        calls: usize,
        log: Arc<Mutex<Vec<u8>>>,
    }

    impl ErrorType for PanicsOnce {
        type Error = core::convert::Infallible;
    }

    impl I2c for PanicsOnce {
        fn transaction(&mut self, a: u8, _: &mut [Operation<'_>]) -> Result<(), Self::Error> {
            self.calls += 1;
            if self.calls == 2 {
                panic!("a bus bug");
            }
            self.log.lock().unwrap().push(a);
            Ok(())
        }
    }

    #[test]
    fn a_thread_that_panicked_on_the_bus_leaves_it_usable_and_the_selection_redone() {
        let log = Arc::new(Mutex::new(Vec::new()));
        let bus = PanicsOnce {
            calls: 0,
            log: Arc::clone(&log),
        };
        let switch = I2cSwitch::new(bus, 0x70);
        let mut a = switch.channel(0).unwrap();
        let mut b = switch.channel(0).unwrap();
        std::thread::spawn(move || a.write(0x77, &[0x1E]))
            .join()
            .expect_err("the bus panicked");
        // The switch's selection is unknown after the panic: channel 0 is selected again.
        b.write(0x77, &[0x48]).unwrap();
        b.write(0x77, &[0x58]).unwrap();
        assert_eq!(*log.lock().unwrap(), [0x70, 0x70, 0x77, 0x77]);
    }

    #[test]
    fn a_channel_of_a_stack_bus_is_a_stack_bus() {
        fn owned_and_sendable<T: Send + 'static>() {}
        owned_and_sendable::<SwitchChannel<I2cBus>>();
        let clock = SimClock::new();
        let (bus, _) = fingertip(&clock);
        let switch = I2cSwitch::new(I2cBus::new(bus), 0x70);
        let mut tip = I2cBus::new(switch.channel(1).unwrap());
        let mut c1 = [0u8; 2];
        tip.write_read(0x77, &[0xA2], &mut c1).unwrap();
        assert_ne!(u16::from_be_bytes(c1), 0);
    }
}
