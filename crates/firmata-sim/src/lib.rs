//! A simulated Arduino running Firmata on a pseudo-terminal: a board for tests of code that
//! drives one — `firmata-host`, pyfirmata2, your own.
//!
//! [`SimBoard::spawn`] opens a pty pair, keeps the board's end (the master) in a thread and
//! closes the other, whose path ([`SimBoard::path`]) a client opens as it would
//! `/dev/ttyACM0`. Like an Arduino with a USB-serial bridge, the board **resets when the port
//! opens**: the simulator notices the open, stays silent for its boot time (the bootloader;
//! bytes sent then are lost) and starts the sketch, which reports its protocol version and
//! firmware name. Closing the port leaves the board waiting for the next open.
//!
//! The sketch is StandardFirmata 2.5.9 or ConfigurableFirmata 2.10.1 with AccelStepperFirmata
//! ([`FirmwareKind`]) on an Uno or a Mega 2560 pin set ([`BoardKind`]), answering as their
//! sources do: version and firmware reports, capability and analog-mapping responses, pin
//! modes, analog reporting every sampling interval ([`AnalogInputs`] gives the voltages and
//! hears the steppers' steps, so a physics model can close a hand the sensors sit on), digital
//! port reports, I2C on a bus of the drivers' chip models ([`ChipBus`]: three MS5611s behind a
//! TCA9548A, an ICM-20789), and steppers moving in wall-clock time ([`stepper::Stepper`]).
//!
//! The line is paced as a UART at the board's baud rate (10 bits a byte, both ways) and the
//! I2C bus as `Wire` at 100 kHz, so throughput measured through the simulator is what a board
//! would give. A client at another baud rate receives what a UART would make of the bytes
//! (resampled bit by bit), and the board the same of the client's.
//!
//! ```
//! use firmata_host::{Board, Options};
//! use firmata_sim::{SimBoard, SimConfig};
//! use std::time::Duration;
//!
//! let sim = SimBoard::spawn(SimConfig::default().boot_delay(Duration::from_millis(50)))?;
//! sim.volts().set(0, 1.25);
//! let mut board = Board::open(sim.path(), &Options::default())?;
//! assert_eq!(board.firmware().map(|f| f.name.as_str()), Some("ConfigurableFirmata"));
//! let a0 = board.enable_analog(0)?;
//! assert_eq!(a0.counts, 256); // 1.25 V of 5 V in 10 bits
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The README follows (its examples run as this crate's doctests).
//!
#![doc = include_str!("../README.md")]
#![deny(unsafe_code)]

mod analog;
mod bus;
mod firmware;
mod pins;
pub mod stepper;
pub mod uart;

pub use analog::{AnalogInputs, ConstantVolts};
pub use bus::{BaroEnv, ChipBus, ICM20789_ADDRESSES, ImuEnv, MS5611_ADDRESS, MUX_ADDRESS};
pub use firmware::{Firmware, FirmwareKind, counts};
pub use pins::BoardKind;

use std::collections::VecDeque;
use std::os::fd::AsRawFd;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use baro_drivers::sim::Conditions;
use imu_icm20789::sim::TrueState;
use serial2::SerialPort;

/// How to build a simulated board.
pub struct SimConfig {
    /// The pin set.
    pub board: BoardKind,
    /// The sketch.
    pub firmware: FirmwareKind,
    /// The sketch's `Firmata.begin` baud rate.
    pub baud: u32,
    /// From the port opening to the version report: bootloader plus `setup()`.
    pub boot_delay: Duration,
    /// The I2C bus.
    pub bus: ChipBus,
    /// The analog pins; [`SimBoard::volts`] changes them while the board runs.
    pub volts: ConstantVolts,
    /// Another source for the analog pins instead of `volts` (a physics model).
    pub analog: Option<Box<dyn AnalogInputs>>,
}

impl core::fmt::Debug for SimConfig {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SimConfig")
            .field("board", &self.board)
            .field("firmware", &self.firmware)
            .field("baud", &self.baud)
            .field("boot_delay", &self.boot_delay)
            .field("bus", &self.bus)
            .finish_non_exhaustive()
    }
}

/// The resting air pressure at the fingertips, mbar.
pub const REST_MBAR: f64 = 1013.25;

impl Default for SimConfig {
    /// An Uno with ConfigurableFirmata at 57 600 baud, booting in 1.6 s (Optiboot's wait and
    /// `setup()` on a real Uno take about that), three fingertip MS5611s at rest behind the
    /// TCA9548A and an ICM-20789 lying still, all analog pins at 0 V.
    fn default() -> SimConfig {
        let rest = |_: u64| Conditions {
            pressure_mbar: REST_MBAR,
            temperature_celsius: 25.0,
        };
        let still = |_: u64| TrueState {
            accel_mps2: [0.0, 0.0, 9.81],
            gyro_rps: [0.0; 3],
            pressure_pa: REST_MBAR * 100.0,
            temperature_c: 25.0,
        };
        SimConfig {
            board: BoardKind::Uno,
            firmware: FirmwareKind::Configurable,
            baud: 57_600,
            boot_delay: Duration::from_millis(1600),
            bus: ChipBus::empty()
                .with_fingertips([Box::new(rest), Box::new(rest), Box::new(rest)], 1)
                .with_icm20789(Box::new(still), 2),
            volts: ConstantVolts::default(),
            analog: None,
        }
    }
}

impl SimConfig {
    /// With this boot delay.
    pub fn boot_delay(mut self, delay: Duration) -> SimConfig {
        self.boot_delay = delay;
        self
    }

    /// With this sketch.
    pub fn firmware(mut self, kind: FirmwareKind) -> SimConfig {
        self.firmware = kind;
        self
    }

    /// On this pin set.
    pub fn board(mut self, kind: BoardKind) -> SimConfig {
        self.board = kind;
        self
    }

    /// At this baud rate.
    pub fn baud(mut self, baud: u32) -> SimConfig {
        self.baud = baud;
        self
    }

    /// With this I2C bus.
    pub fn bus(mut self, bus: ChipBus) -> SimConfig {
        self.bus = bus;
        self
    }

    /// With the analog pins driven by `inputs` (a physics model) instead of
    /// [`volts`](Self::volts).
    ///
    /// ```
    /// use firmata_host::{Board, Options};
    /// use firmata_sim::{ChipBus, SimBoard, SimConfig};
    /// use std::time::Duration;
    ///
    /// // A0 rises 1 V a second from the board's start.
    /// let ramp = |channel: u8, now: Duration| if channel == 0 { now.as_secs_f32() } else { 0.0 };
    /// let config = SimConfig::default().bus(ChipBus::empty()).analog(ramp);
    /// let sim = SimBoard::spawn(config.boot_delay(Duration::from_millis(50)))?;
    /// let mut board = Board::open(sim.path(), &Options::default())?;
    /// assert!(board.enable_analog(0)?.volts < 1.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn analog(mut self, inputs: impl AnalogInputs + 'static) -> SimConfig {
        self.analog = Some(Box::new(inputs));
        self
    }
}

/// Something to do to the line, for tests of a client's error handling.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Fault {
    /// Send these bytes as they are, at once (noise, an unknown command, a report nobody
    /// asked for).
    Raw(Vec<u8>),
    /// Cut the board's next reply after half its bytes (lost on the line).
    TruncateNextReply,
    /// The sketch restarts at once (a brown-out, a watchdog, a reset button): what it was
    /// sending is lost, pin modes, reporting and steppers start afresh, and it sends its
    /// version and firmware reports again.
    Reset,
}

/// A configured stepper as of the board's last pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepperState {
    /// Its position, steps (AccelStepper's counter).
    pub position: i32,
    /// Whether a move is under way.
    pub running: bool,
    /// Whether the driver's outputs are enabled.
    pub enabled: bool,
}

/// What the simulator shares with its handle.
#[derive(Debug, Default)]
struct Shared {
    faults: VecDeque<Fault>,
    /// Times the sketch started (one per open of the port).
    boots: u64,
    bytes_in: u64,
    bytes_out: u64,
    steppers: [Option<StepperState>; 10],
    client_baud: Option<u32>,
    open: bool,
}

/// A simulated board on a pty; dropping it stops the thread and closes the port.
#[derive(Debug)]
pub struct SimBoard {
    path: PathBuf,
    shared: Arc<Mutex<Shared>>,
    volts: ConstantVolts,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

fn lock(shared: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    shared.lock().unwrap_or_else(|e| e.into_inner())
}

impl SimBoard {
    /// Opens the pty and starts the board (waiting for its port to open).
    pub fn spawn(config: SimConfig) -> std::io::Result<SimBoard> {
        let (master, client) = SerialPort::pair()?;
        let path = std::fs::read_link(format!("/proc/self/fd/{}", client.as_raw_fd()))?;
        // Closed, so that the board sees the open a client makes (the pty hangs up until then).
        drop(client);
        let shared = Arc::new(Mutex::new(Shared::default()));
        let stop = Arc::new(AtomicBool::new(false));
        let volts = config.volts.clone();
        let line = Line {
            master,
            shared: shared.clone(),
            stop: stop.clone(),
            baud: config.baud,
            boot_delay: config.boot_delay,
            firmware: Firmware::new(config.firmware, config.board),
            kind: (config.firmware, config.board),
            bus: config.bus,
            analog: config.analog.unwrap_or_else(|| Box::new(config.volts)),
            start: Instant::now(),
            tx_free: Instant::now(),
            rx_free: Instant::now(),
            out: Vec::with_capacity(1024),
        };
        let thread = std::thread::Builder::new()
            .name("firmata-sim".into())
            .spawn(move || line.run())?;
        Ok(SimBoard {
            path,
            shared,
            volts,
            stop,
            thread: Some(thread),
        })
    }

    /// The port a client opens.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The analog pins' voltages (when the board runs on [`SimConfig::volts`]).
    pub fn volts(&self) -> &ConstantVolts {
        &self.volts
    }

    /// Queues a fault.
    pub fn inject(&self, fault: Fault) {
        lock(&self.shared).faults.push_back(fault);
    }

    /// How many times the sketch started (once per open of the port).
    pub fn boots(&self) -> u64 {
        lock(&self.shared).boots
    }

    /// Bytes received from and sent to the client.
    pub fn bytes(&self) -> (u64, u64) {
        let s = lock(&self.shared);
        (s.bytes_in, s.bytes_out)
    }

    /// A stepper's position as of the board's last pass.
    pub fn stepper_position(&self, device: u8) -> Option<i32> {
        self.stepper(device).map(|s| s.position)
    }

    /// A stepper as of the board's last pass: its position, whether it moves, whether its
    /// outputs are on. The sketch runs on while no client has the port open (as an Arduino's
    /// does when its host closes the port), so a move a client left under way goes on.
    pub fn stepper(&self, device: u8) -> Option<StepperState> {
        lock(&self.shared)
            .steppers
            .get(usize::from(device))
            .copied()
            .flatten()
    }

    /// The baud rate the client's end was set to when the board last looked.
    pub fn client_baud(&self) -> Option<u32> {
        lock(&self.shared).client_baud
    }

    /// Whether the board sees its port open. A close is seen when the pty hangs up, within
    /// a pass of the board's loop; a close and a new open in quicker succession than that can
    /// go unseen, and then the board does not reset (a test that needs the reset waits for
    /// this to turn `false` before it opens again).
    pub fn port_open(&self) -> bool {
        lock(&self.shared).open
    }
}

impl Drop for SimBoard {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// How often a closed port is checked for an open.
const OPEN_POLL: Duration = Duration::from_millis(2);
/// The longest the board waits on input in one pass.
const PASS: Duration = Duration::from_millis(20);

/// The board's end of the line and the board.
struct Line {
    master: SerialPort,
    shared: Arc<Mutex<Shared>>,
    stop: Arc<AtomicBool>,
    baud: u32,
    boot_delay: Duration,
    firmware: Firmware,
    kind: (FirmwareKind, BoardKind),
    bus: ChipBus,
    analog: Box<dyn AnalogInputs>,
    start: Instant,
    /// When the board's transmitter is free (the last byte written has left).
    tx_free: Instant,
    /// When the bytes received so far have arrived at the board's baud rate.
    rx_free: Instant,
    out: Vec<u8>,
}

/// How a read on the master ended.
enum Read {
    Bytes(usize),
    Nothing,
    HungUp,
}

impl Line {
    fn read(&mut self, buf: &mut [u8], timeout: Duration) -> Read {
        if self
            .master
            .set_read_timeout(timeout.max(Duration::from_micros(100)))
            .is_err()
        {
            return Read::HungUp;
        }
        match self.master.read(buf) {
            Ok(0) => Read::HungUp,
            Ok(n) => Read::Bytes(n),
            Err(e) if e.kind() == std::io::ErrorKind::TimedOut => Read::Nothing,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => Read::Nothing,
            Err(_) => Read::HungUp,
        }
    }

    fn run(mut self) {
        let mut buf = [0u8; 256];
        let mut booted = false;
        'closed: while !self.stop.load(Ordering::Relaxed) {
            // Closed: the pty hangs up until a client opens it.
            match self.read(&mut buf, OPEN_POLL) {
                Read::HungUp => {
                    lock(&self.shared).open = false;
                    if booted {
                        // The sketch runs on with no host: its steppers keep moving.
                        self.out.clear();
                        let now = self.start.elapsed();
                        self.firmware
                            .tick(now, &mut self.bus, self.analog.as_mut(), &mut self.out);
                        self.out.clear();
                        self.publish();
                    }
                    std::thread::sleep(OPEN_POLL);
                    continue;
                }
                Read::Bytes(_) | Read::Nothing => lock(&self.shared).open = true,
            }
            // Opened: the reset. The bootloader hears, and drops, what arrives meanwhile.
            let boot_end = Instant::now() + self.boot_delay;
            while Instant::now() < boot_end {
                if self.stop.load(Ordering::Relaxed) {
                    return;
                }
                let left = boot_end.saturating_duration_since(Instant::now());
                if let Read::HungUp = self.read(&mut buf, left.min(PASS)) {
                    continue 'closed;
                }
            }
            self.boot();
            booted = true;
            loop {
                if self.stop.load(Ordering::Relaxed) {
                    return;
                }
                let now = self.start.elapsed();
                self.out.clear();
                let next =
                    self.firmware
                        .tick(now, &mut self.bus, self.analog.as_mut(), &mut self.out);
                self.publish();
                if !self.flush() {
                    continue 'closed;
                }
                match self.read(&mut buf, next.min(PASS)) {
                    Read::HungUp => continue 'closed,
                    Read::Nothing => {}
                    Read::Bytes(n) => {
                        if !self.receive(&buf[..n]) {
                            continue 'closed;
                        }
                    }
                }
            }
        }
    }

    /// The sketch starts: fresh state, the start-up reports.
    fn boot(&mut self) {
        self.firmware = Firmware::new(self.kind.0, self.kind.1);
        {
            let mut s = lock(&self.shared);
            s.boots += 1;
            s.faults.clear();
        }
        self.start = Instant::now();
        self.tx_free = Instant::now();
        self.rx_free = Instant::now();
        self.out.clear();
        self.firmware.boot_report(&mut self.out);
        self.flush();
    }

    /// The client's baud rate, read from the pty's settings (master and client share them):
    /// a client may change it at any time.
    fn client_baud(&self) -> u32 {
        let baud = self
            .master
            .get_configuration()
            .and_then(|c| c.get_baud_rate())
            .ok();
        lock(&self.shared).client_baud = baud;
        baud.unwrap_or(self.baud)
    }

    /// Bytes from the client: they arrive at the line's pace, then the sketch handles them.
    fn receive(&mut self, bytes: &[u8]) -> bool {
        let client = self.client_baud();
        let bytes = if client == self.baud {
            bytes.to_vec()
        } else {
            uart::resample(bytes, client, self.baud)
        };
        lock(&self.shared).bytes_in += bytes.len() as u64;
        let arrived = self.rx_free.max(Instant::now()) + uart::wire_time(bytes.len(), self.baud);
        sleep_until(arrived);
        self.rx_free = arrived;
        self.out.clear();
        let now = self.start.elapsed();
        self.firmware.receive(
            &bytes,
            now,
            &mut self.bus,
            self.analog.as_mut(),
            &mut self.out,
        );
        // The transmitter waits for the I2C transfers the messages made.
        let busy = self.firmware.take_busy();
        self.tx_free = self.tx_free.max(Instant::now()) + busy;
        self.publish();
        self.flush()
    }

    fn publish(&mut self) {
        let mut s = lock(&self.shared);
        for d in 0..10u8 {
            s.steppers[usize::from(d)] = self.firmware.stepper_at(d).map(|st| StepperState {
                position: st.position(),
                running: st.running(),
                enabled: st.enabled(),
            });
        }
    }

    /// Sends `out` (and any injected fault) at the line's pace: each message appears when its
    /// last byte would have arrived. `false` when the client hung up.
    fn flush(&mut self) -> bool {
        let faults: Vec<Fault> = lock(&self.shared).faults.drain(..).collect();
        let mut truncate = false;
        for f in faults {
            match f {
                Fault::Reset => {
                    self.out.clear();
                    // `boot` clears the other faults queued and sends the start-up reports.
                    self.boot();
                    return true;
                }
                Fault::Raw(bytes) => {
                    let mut raw = bytes;
                    raw.extend_from_slice(&self.out);
                    self.out = raw;
                }
                Fault::TruncateNextReply => truncate = true,
            }
        }
        if truncate {
            if self.out.is_empty() {
                // Nothing to cut yet: keep the fault for the next reply.
                lock(&self.shared)
                    .faults
                    .push_back(Fault::TruncateNextReply);
            } else {
                let keep = self.out.len() / 2;
                self.out.truncate(keep);
            }
        }
        if self.out.is_empty() {
            return true;
        }
        let client = self.client_baud();
        let n = self.out.len();
        let done = self.tx_free.max(Instant::now()) + uart::wire_time(n, self.baud);
        sleep_until(done);
        self.tx_free = done;
        let ok = if client == self.baud {
            self.master.write_all(&self.out).is_ok()
        } else {
            let garbled = uart::resample(&self.out, self.baud, client);
            self.master.write_all(&garbled).is_ok()
        };
        lock(&self.shared).bytes_out += n as u64;
        self.out.clear();
        ok
    }
}

fn sleep_until(t: Instant) {
    let now = Instant::now();
    if t > now {
        std::thread::sleep(t - now);
    }
}
