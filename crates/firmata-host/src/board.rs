//! A board on a serial port: open (through its reset), query, configure, and keep the latest
//! of everything it reports.

use std::path::Path;
use std::time::{Duration, Instant};

use serial2::SerialPort;

use crate::error::{Error, ErrorKind};
use crate::parser::{Event, FrameError, Parser};
use crate::protocol::{self, PinMode};

/// How to open a board.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Serial baud rate: StandardFirmata's `Firmata.begin(57600)` (StandardFirmata 2.5.9).
    pub baud: u32,
    /// How long to wait for the version report a board sends when it starts. An Arduino with
    /// an FTDI / 16U2 USB bridge resets when its port opens (DTR) and reports after its
    /// bootloader and `setup()`; a board that does not reset stays silent, and is asked instead
    /// once this passes. Bytes sent during the bootloader would go to the bootloader, so the
    /// host waits first.
    pub boot_wait: Duration,
    /// How long a request waits for its reply.
    pub reply_timeout: Duration,
    /// The analog reference (V) that full scale stands for: 5 V on an Uno or Mega (AREF
    /// default), 3.3 V on 3.3 V boards.
    pub reference_volts: f32,
}

impl Default for Options {
    /// 57600 baud, 5 s for the reset, 1 s per reply, 5 V reference.
    fn default() -> Options {
        Options {
            baud: 57_600,
            boot_wait: Duration::from_secs(5),
            reply_timeout: Duration::from_secs(1),
            reference_volts: 5.0,
        }
    }
}

/// The firmware's name and version (its `REPORT_FIRMWARE` answer).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Firmware {
    /// Name, e.g. `StandardFirmata` (the sketch's file name).
    pub name: String,
    /// Major version.
    pub major: u8,
    /// Minor version.
    pub minor: u8,
}

/// A pin's modes and their resolutions, from the capability response.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PinCapabilities {
    /// (mode, resolution) pairs in the board's order.
    pub modes: Vec<(PinMode, u8)>,
}

impl PinCapabilities {
    /// The resolution of `mode` on this pin, if it supports it.
    pub fn resolution(&self, mode: PinMode) -> Option<u8> {
        self.modes.iter().find(|(m, _)| *m == mode).map(|(_, r)| *r)
    }
}

/// Parses a capability response payload into one entry per pin (protocol.md 2.6.0,
/// "Capabilities response": pairs per pin, each pin closed by 0x7F).
///
/// ```
/// use firmata_host::{parse_capabilities, PinMode};
/// let pins = parse_capabilities(&[0x7F, 0x00, 0x01, 0x02, 0x0A, 0x7F]);
/// assert_eq!(pins.len(), 2);
/// assert!(pins[0].modes.is_empty()); // pin 0: RX, not for Firmata
/// assert_eq!(pins[1].resolution(PinMode::Analog), Some(10));
/// ```
pub fn parse_capabilities(payload: &[u8]) -> Vec<PinCapabilities> {
    let mut pins = Vec::new();
    let mut current = PinCapabilities::default();
    let mut k = 0;
    while k < payload.len() {
        if payload[k] == 0x7F {
            pins.push(std::mem::take(&mut current));
            k += 1;
        } else if k + 1 < payload.len() {
            current
                .modes
                .push((PinMode::from_code(payload[k]), payload[k + 1]));
            k += 2;
        } else {
            break; // a mode without its resolution: the response was cut
        }
    }
    pins
}

/// One analog input's latest report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalogReading {
    /// ADC counts (0 … 1023 on a 10-bit AVR).
    pub counts: u16,
    /// Counts as volts: `counts / (2^bits − 1) × reference`.
    pub volts: f32,
    /// When it arrived.
    pub at: Instant,
}

/// The latest reply seen for one I2C (address, register).
#[derive(Debug, Clone, Copy)]
struct I2cSlot {
    address: u8,
    register: u16,
    len: usize,
    data: [u8; protocol::MAX_I2C_READ],
    seq: u64,
}

/// Slots for distinct (address, register) replies: one per continuous read the firmware keeps
/// (`I2C_MAX_QUERIES` = 8 in StandardFirmata 2.5.9) plus one-shot reads.
const I2C_SLOTS: usize = 12;

#[derive(Debug, Clone, Copy, Default)]
struct StepperSlot {
    position: i32,
    position_seq: u64,
    complete_position: i32,
    complete_seq: u64,
}

/// The last string the board sent, kept without allocating.
#[derive(Debug, Clone, Copy)]
struct Text {
    bytes: [u8; 64],
    len: usize,
    seq: u64,
}

impl Text {
    fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..self.len]).unwrap_or("(not UTF-8)")
    }
}

/// What the parser has seen that was not a Firmata message.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LinkStats {
    /// Messages delivered.
    pub messages: u64,
    /// Framing errors (stray bytes, truncated or malformed messages, unknown commands).
    pub frame_errors: u64,
    /// The latest framing error.
    pub last_frame_error: Option<FrameError>,
    /// Analog reports for channels this host did not enable (kept, and counted here).
    pub unrequested_analog: u64,
    /// Bytes read in all.
    pub bytes: u64,
}

/// A Firmata board on a serial port.
///
/// ```no_run
/// use firmata_host::{Board, Options};
/// let mut board = Board::open("/dev/ttyACM0", &Options::default())?;
/// println!("{:?} speaks Firmata {:?}", board.firmware(), board.protocol_version());
/// board.enable_analog(0)?;
/// let a0 = board.wait_analog(0, std::time::Duration::from_secs(1))?;
/// println!("A0 = {} counts, {:.3} V", a0.counts, a0.volts);
/// # Ok::<(), firmata_host::Error>(())
/// ```
#[derive(Debug)]
pub struct Board {
    port: SerialPort,
    name: String,
    options: Options,
    parser: Parser,
    rx: Box<[u8; 512]>,
    tx: Vec<u8>,
    seq: u64,
    version: Option<(u8, u8)>,
    version_seq: u64,
    version_reports: u64,
    firmware: Option<Firmware>,
    firmware_seq: u64,
    capabilities: Option<Vec<PinCapabilities>>,
    capabilities_seq: u64,
    analog_mapping: Option<Vec<u8>>,
    analog_mapping_seq: u64,
    analog: [Option<AnalogReading>; 16],
    analog_enabled: u16,
    analog_bits: u8,
    digital: [u8; 16],
    digital_seq: [u64; 16],
    i2c: [Option<I2cSlot>; I2C_SLOTS],
    i2c_enabled: bool,
    steppers: [StepperSlot; protocol::MAX_ACCELSTEPPERS as usize],
    text: Option<Text>,
    stats: LinkStats,
    /// Non-Firmata bytes seen while opening, for the error's sample.
    sample: Vec<u8>,
}

impl Board {
    /// Opens the board on `path`, waits through its reset for the version report (asks for
    /// it if none comes within `boot_wait`) and reads its firmware name.
    pub fn open(path: impl AsRef<Path>, options: &Options) -> Result<Board, Error> {
        let name = path.as_ref().display().to_string();
        let port = SerialPort::open(path.as_ref(), options.baud)
            .map_err(|e| Error::new(name.clone(), ErrorKind::Io(e)))?;
        Board::with_port(port, name, options)
    }

    /// The same on a port already open (e.g. one end of `SerialPort::pair()`), named `name`
    /// in errors.
    pub fn with_port(port: SerialPort, name: String, options: &Options) -> Result<Board, Error> {
        let mut board = Board {
            port,
            name,
            options: options.clone(),
            parser: Parser::new(),
            rx: Box::new([0; 512]),
            tx: Vec::with_capacity(80),
            seq: 0,
            version: None,
            version_seq: 0,
            version_reports: 0,
            firmware: None,
            firmware_seq: 0,
            capabilities: None,
            capabilities_seq: 0,
            analog_mapping: None,
            analog_mapping_seq: 0,
            analog: [None; 16],
            analog_enabled: 0,
            analog_bits: 10,
            digital: [0; 16],
            digital_seq: [0; 16],
            i2c: [None; I2C_SLOTS],
            i2c_enabled: false,
            steppers: [StepperSlot::default(); protocol::MAX_ACCELSTEPPERS as usize],
            text: None,
            stats: LinkStats::default(),
            sample: Vec::new(),
        };
        // Bytes from before the reset belong to the previous session.
        let _ = board.port.discard_input_buffer();
        board.handshake()?;
        Ok(board)
    }

    fn handshake(&mut self) -> Result<(), Error> {
        let boot_wait = self.options.boot_wait;
        let reply = self.options.reply_timeout;
        let booted = self.wait(boot_wait, "protocol version report", |b| {
            b.version.map(|_| Ok(()))
        });
        match booted {
            Ok(()) => {}
            Err(e) if matches!(e.kind, ErrorKind::Timeout { .. }) => {
                // No reset (or a board that was already running): ask.
                self.tx.clear();
                protocol::encode_version_query(&mut self.tx);
                protocol::encode_sysex_query(&mut self.tx, protocol::REPORT_FIRMWARE);
                self.send()?;
                let asked = self.wait(reply, "protocol version report", |b| {
                    b.version.map(|_| Ok(()))
                });
                if let Err(e) = asked {
                    if matches!(e.kind, ErrorKind::Timeout { .. }) && self.stats.bytes > 0 {
                        return Err(self.error(ErrorKind::NotFirmata {
                            baud: self.options.baud,
                            bytes: self.stats.bytes,
                            sample: sample_text(&self.sample),
                        }));
                    }
                    return Err(e);
                }
            }
            Err(e) => return Err(e),
        }
        self.sample = Vec::new();
        // The firmware report follows the version at start-up (ConfigurableFirmata 2.10.1
        // `FirmataClass::begin`: printVersion, then printFirmwareVersion); ask if it did not.
        if self.firmware.is_none() {
            let got = self.wait(
                reply.min(Duration::from_millis(200)),
                "firmware report",
                |b| b.firmware.as_ref().map(|_| Ok(())),
            );
            if got.is_err() {
                self.query_firmware()?;
            }
        }
        Ok(())
    }

    /// The port's name, as errors give it.
    pub fn port_name(&self) -> &str {
        &self.name
    }

    /// The options it was opened with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The protocol version the board reported.
    pub fn protocol_version(&self) -> Option<(u8, u8)> {
        self.version
    }

    /// How many protocol version reports have arrived since the port opened. A sketch sends
    /// one when it starts, and otherwise only when asked ([`query_version`](Self::query_version)):
    /// a count that rises without being asked means the board restarted (a reset, a brown-out,
    /// a watchdog), losing its pin modes, reporting and steppers.
    pub fn version_reports(&self) -> u64 {
        self.version_reports
    }

    /// The firmware name and version the board reported.
    pub fn firmware(&self) -> Option<&Firmware> {
        self.firmware.as_ref()
    }

    /// What the link has carried so far.
    pub fn stats(&self) -> LinkStats {
        self.stats
    }

    /// The last string message the board sent (firmware errors come this way).
    pub fn last_text(&self) -> Option<&str> {
        self.text.as_ref().map(Text::as_str)
    }

    fn error(&self, kind: ErrorKind) -> Error {
        Error::new(self.name.clone(), kind)
    }

    /// Writes the transmit buffer.
    fn send(&mut self) -> Result<(), Error> {
        use std::io::ErrorKind as Io;
        match self.port.write_all(&self.tx) {
            Ok(()) => Ok(()),
            Err(e) if matches!(e.kind(), Io::BrokenPipe) || e.raw_os_error() == Some(5) => {
                Err(self.error(ErrorKind::Disconnected))
            }
            Err(e) => Err(self.error(ErrorKind::Io(e))),
        }
    }

    /// Reads what the board has sent within `timeout` and takes in every message.
    /// Returns whether anything arrived.
    pub fn poll(&mut self, timeout: Duration) -> Result<bool, Error> {
        self.port
            .set_read_timeout(timeout.max(Duration::from_micros(100)))
            .map_err(|e| self.error(ErrorKind::Io(e)))?;
        let n = match self.port.read(&mut self.rx[..]) {
            Ok(0) => return Err(self.error(ErrorKind::Disconnected)),
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::TimedOut => return Ok(false),
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => return Ok(false),
            // A signal arrived meanwhile (the host's own Ctrl-C handler): nothing read.
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => return Ok(false),
            // EIO: the other end of the line is gone (a pty's master closed, a USB unplug).
            Err(e) if e.raw_os_error() == Some(5) => {
                return Err(self.error(ErrorKind::Disconnected));
            }
            Err(e) => return Err(self.error(ErrorKind::Io(e))),
        };
        self.stats.bytes += n as u64;
        for k in 0..n {
            let byte = self.rx[k];
            self.take(byte);
        }
        Ok(true)
    }

    /// Feeds one byte through the parser into the board's state.
    fn take(&mut self, byte: u8) {
        let Some(result) = self.parser.push(byte) else {
            return;
        };
        self.seq += 1;
        let seq = self.seq;
        let event = match result {
            Ok(event) => event,
            Err(e) => {
                self.stats.frame_errors += 1;
                self.stats.last_frame_error = Some(e);
                if self.version.is_none() && self.sample.len() < 32 {
                    self.sample.push(byte);
                }
                return;
            }
        };
        self.stats.messages += 1;
        match event {
            Event::Analog { channel, value } => {
                let ch = usize::from(channel);
                if self.analog_enabled & (1 << ch) == 0 {
                    self.stats.unrequested_analog += 1;
                }
                let full = f32::from(((1u32 << self.analog_bits) - 1) as u16);
                self.analog[ch] = Some(AnalogReading {
                    counts: value,
                    volts: f32::from(value) / full * self.options.reference_volts,
                    at: Instant::now(),
                });
            }
            Event::Digital { port, mask } => {
                self.digital[usize::from(port)] = mask;
                self.digital_seq[usize::from(port)] = seq;
            }
            Event::Version { major, minor } => {
                self.version = Some((major, minor));
                self.version_seq = seq;
                self.version_reports += 1;
            }
            Event::Firmware { major, minor, name } => {
                let name: String = protocol::pairs(name).map(char::from).collect();
                self.firmware = Some(Firmware { name, major, minor });
                self.firmware_seq = seq;
            }
            Event::Capabilities(payload) => {
                let pins = parse_capabilities(payload);
                self.capabilities = Some(pins);
                self.capabilities_seq = seq;
            }
            Event::AnalogMapping(map) => {
                self.analog_mapping = Some(map.to_vec());
                self.analog_mapping_seq = seq;
            }
            Event::I2cReply {
                address,
                register,
                data,
            } => {
                let mut slot = I2cSlot {
                    address,
                    register,
                    len: 0,
                    data: [0; protocol::MAX_I2C_READ],
                    seq,
                };
                for (dst, b) in slot.data.iter_mut().zip(protocol::pairs(data)) {
                    *dst = b;
                    slot.len += 1;
                }
                self.store_i2c(slot);
            }
            Event::Text(chars) => {
                let mut text = Text {
                    bytes: [0; 64],
                    len: 0,
                    seq,
                };
                for (dst, b) in text.bytes.iter_mut().zip(protocol::pairs(chars)) {
                    *dst = b;
                    text.len += 1;
                }
                self.text = Some(text);
            }
            Event::StepperPosition { device, position } => {
                if let Some(s) = self.steppers.get_mut(usize::from(device)) {
                    s.position = position;
                    s.position_seq = seq;
                }
            }
            Event::StepperMoveComplete { device, position } => {
                if let Some(s) = self.steppers.get_mut(usize::from(device)) {
                    s.position = position;
                    s.position_seq = seq;
                    s.complete_position = position;
                    s.complete_seq = seq;
                }
            }
            // Nothing here waits for these.
            Event::PinState { .. } | Event::MultiStepperComplete { .. } | Event::Sysex { .. } => {}
        }
    }

    fn store_i2c(&mut self, slot: I2cSlot) {
        let same = self.i2c.iter().position(|s| {
            s.is_some_and(|s| s.address == slot.address && s.register == slot.register)
        });
        let at = same.unwrap_or_else(|| {
            // A free slot, else the oldest.
            self.i2c
                .iter()
                .enumerate()
                .min_by_key(|(_, s)| s.map_or(0, |s| s.seq))
                .map_or(0, |(k, _)| k)
        });
        self.i2c[at] = Some(slot);
    }

    /// Polls until `done` gives an answer or `timeout` passes; `what` names the wait in the
    /// timeout error.
    fn wait<T>(
        &mut self,
        timeout: Duration,
        what: &str,
        mut done: impl FnMut(&Board) -> Option<Result<T, ErrorKind>>,
    ) -> Result<T, Error> {
        let deadline = Instant::now() + timeout;
        let errors_before = self.stats.frame_errors;
        loop {
            if let Some(answer) = done(self) {
                return answer.map_err(|k| self.error(k));
            }
            let now = Instant::now();
            if now >= deadline {
                return Err(self.error(ErrorKind::Timeout {
                    waiting_for: what.to_owned(),
                    timeout_ms: timeout.as_millis() as u64,
                    frame_errors: self.stats.frame_errors - errors_before,
                }));
            }
            self.poll(deadline - now)?;
        }
    }

    /// A refusal the firmware sent as a string since `since`, for a request named `request`.
    fn refusal(&self, since: u64, request: &str) -> Option<ErrorKind> {
        let text = self.text.as_ref().filter(|t| t.seq > since)?;
        let message = text.as_str();
        // ConfigurableFirmata 2.10.1 `FirmataExt.cpp`: a sysex no feature handles.
        (message == "Unhandled sysex command"
            || message.starts_with("10-bit addressing")
            || message == "too many queries")
            .then(|| ErrorKind::Refused {
                request: request.to_owned(),
                message: message.to_owned(),
            })
    }

    // --- queries ---

    /// Asks for the protocol version again and waits for it.
    pub fn query_version(&mut self) -> Result<(u8, u8), Error> {
        let since = self.seq;
        self.tx.clear();
        protocol::encode_version_query(&mut self.tx);
        self.send()?;
        self.wait(self.options.reply_timeout, "protocol version report", |b| {
            (b.version_seq > since).then(|| Ok(b.version.unwrap_or_default()))
        })
    }

    /// Asks for the firmware name and version (`REPORT_FIRMWARE`) and waits for it.
    pub fn query_firmware(&mut self) -> Result<Firmware, Error> {
        let since = self.seq;
        self.tx.clear();
        protocol::encode_sysex_query(&mut self.tx, protocol::REPORT_FIRMWARE);
        self.send()?;
        self.wait_sysex(since, "firmware report", protocol::REPORT_FIRMWARE, |b| {
            (b.firmware_seq > since)
                .then(|| b.firmware.clone())
                .flatten()
        })
    }

    /// Waits for a sysex reply, failing early when the awaited sysex arrives garbled or the
    /// firmware refuses the request.
    fn wait_sysex<T>(
        &mut self,
        since: u64,
        what: &str,
        id: u8,
        mut got: impl FnMut(&Board) -> Option<T>,
    ) -> Result<T, Error> {
        let errors = self.stats.frame_errors;
        self.wait(self.options.reply_timeout, what, |b| {
            if let Some(t) = got(b) {
                return Some(Ok(t));
            }
            if b.stats.frame_errors > errors {
                if let Some(e) = b.stats.last_frame_error {
                    let ours = match e {
                        FrameError::TruncatedSysex { id: got, .. } => got == Some(id),
                        FrameError::Malformed { id: got, .. }
                        | FrameError::SysexOverflow { id: got } => got == id,
                        _ => false,
                    };
                    if ours {
                        return Some(Err(ErrorKind::Garbled(e)));
                    }
                }
            }
            b.refusal(since, what).map(Err)
        })
    }

    /// Asks for every pin's modes and resolutions (`CAPABILITY_QUERY`) and waits for them.
    /// The analog resolution found is used for volts from then on.
    pub fn capabilities(&mut self) -> Result<&[PinCapabilities], Error> {
        let since = self.seq;
        self.tx.clear();
        protocol::encode_sysex_query(&mut self.tx, protocol::CAPABILITY_QUERY);
        self.send()?;
        self.wait_sysex(
            since,
            "capability response",
            protocol::CAPABILITY_RESPONSE,
            |b| (b.capabilities_seq > since).then_some(()),
        )?;
        let pins = self.capabilities.as_deref().unwrap_or_default();
        if let Some(bits) = pins.iter().find_map(|p| p.resolution(PinMode::Analog)) {
            self.analog_bits = bits.clamp(1, 16);
        }
        Ok(self.capabilities.as_deref().unwrap_or_default())
    }

    /// Asks which pin each analog channel is (`ANALOG_MAPPING_QUERY`): per pin, its channel
    /// or 127.
    pub fn analog_mapping(&mut self) -> Result<&[u8], Error> {
        let since = self.seq;
        self.tx.clear();
        protocol::encode_sysex_query(&mut self.tx, protocol::ANALOG_MAPPING_QUERY);
        self.send()?;
        self.wait_sysex(
            since,
            "analog mapping response",
            protocol::ANALOG_MAPPING_RESPONSE,
            |b| (b.analog_mapping_seq > since).then_some(()),
        )?;
        Ok(self.analog_mapping.as_deref().unwrap_or_default())
    }

    // --- pins and reporting ---

    fn check_pin(&self, pin: u8) -> Result<(), Error> {
        if pin > 127 {
            return Err(self.error(ErrorKind::OutOfRange {
                what: "pin",
                value: pin.to_string(),
                range: "0 ..= 127",
            }));
        }
        Ok(())
    }

    /// Sets a pin's mode (`SET_PIN_MODE`). Nothing comes back: the board ignores a mode the
    /// pin lacks (check [`capabilities`](Self::capabilities) first).
    pub fn set_pin_mode(&mut self, pin: u8, mode: PinMode) -> Result<(), Error> {
        self.check_pin(pin)?;
        self.tx.clear();
        protocol::encode_set_pin_mode(&mut self.tx, pin, mode);
        self.send()
    }

    /// Drives a digital output pin (`SET_DIGITAL_PIN_VALUE`).
    pub fn digital_write(&mut self, pin: u8, high: bool) -> Result<(), Error> {
        self.check_pin(pin)?;
        self.tx.clear();
        protocol::encode_set_digital_pin_value(&mut self.tx, pin, high);
        self.send()
    }

    fn check_channel(&self, what: &'static str, n: u8) -> Result<(), Error> {
        if n > 15 {
            return Err(self.error(ErrorKind::OutOfRange {
                what,
                value: n.to_string(),
                range: "0 ..= 15",
            }));
        }
        Ok(())
    }

    /// Turns analog reporting of `channel` (A0 = 0) on or off (`REPORT_ANALOG`). Since
    /// protocol 2.4 a board reports the value at once when enabled, then every sampling
    /// interval.
    pub fn report_analog(&mut self, channel: u8, on: bool) -> Result<(), Error> {
        self.check_channel("analog channel", channel)?;
        self.tx.clear();
        protocol::encode_report_analog(&mut self.tx, channel, on);
        self.send()?;
        if on {
            self.analog_enabled |= 1 << channel;
        } else {
            self.analog_enabled &= !(1 << channel);
            self.analog[usize::from(channel)] = None;
        }
        Ok(())
    }

    /// Enables analog `channel` and waits for its first report.
    pub fn enable_analog(&mut self, channel: u8) -> Result<AnalogReading, Error> {
        let since = Instant::now();
        self.report_analog(channel, true)?;
        let timeout = self.options.reply_timeout;
        self.wait(timeout, &format!("analog report of A{channel}"), |b| {
            b.analog[usize::from(channel)]
                .filter(|r| r.at >= since)
                .map(Ok)
        })
    }

    /// Turns digital reporting of `port` (pins 8·port … 8·port + 7) on or off
    /// (`REPORT_DIGITAL`).
    pub fn report_digital(&mut self, port: u8, on: bool) -> Result<(), Error> {
        self.check_channel("digital port", port)?;
        self.tx.clear();
        protocol::encode_report_digital(&mut self.tx, port, on);
        self.send()
    }

    /// The latest levels reported for `port`, if any report came.
    pub fn digital_port(&self, port: u8) -> Option<u8> {
        let p = usize::from(port & 0x0F);
        (self.digital_seq[p] > 0).then_some(self.digital[p])
    }

    /// Sets how often the board samples analog inputs and continuous I2C reads, ms
    /// (`SAMPLING_INTERVAL`; StandardFirmata 2.5.9 keeps at least 1 ms, default 19 ms).
    pub fn set_sampling_interval(&mut self, ms: u16) -> Result<(), Error> {
        if ms > 0x3FFF {
            return Err(self.error(ErrorKind::OutOfRange {
                what: "sampling interval (ms)",
                value: ms.to_string(),
                range: "0 ..= 16383",
            }));
        }
        self.tx.clear();
        protocol::encode_sampling_interval(&mut self.tx, ms);
        self.send()
    }

    /// The latest report of analog `channel`, if one came since it was enabled.
    pub fn analog(&self, channel: u8) -> Option<AnalogReading> {
        self.analog.get(usize::from(channel)).copied().flatten()
    }

    /// Polls until a report of `channel` newer than now arrives.
    pub fn wait_analog(&mut self, channel: u8, timeout: Duration) -> Result<AnalogReading, Error> {
        let since = Instant::now();
        self.wait(timeout, &format!("analog report of A{channel}"), |b| {
            b.analog(channel).filter(|r| r.at >= since).map(Ok)
        })
    }

    /// The analog channels this host enabled (bit k = A`k`).
    pub fn analog_enabled(&self) -> u16 {
        self.analog_enabled
    }

    // --- I2C ---

    /// Enables I2C on the board (`I2C_CONFIG`) with a delay (µs) between a register write
    /// and the read that follows (0: none).
    pub fn i2c_config(&mut self, delay_us: u16) -> Result<(), Error> {
        self.tx.clear();
        protocol::encode_i2c_config(&mut self.tx, delay_us & 0x3FFF);
        self.send()?;
        self.i2c_enabled = true;
        Ok(())
    }

    fn ensure_i2c(&mut self) -> Result<(), Error> {
        if !self.i2c_enabled {
            self.i2c_config(0)?;
        }
        Ok(())
    }

    fn check_address(&self, address: u8) -> Result<(), Error> {
        if address > 0x7F {
            return Err(self.error(ErrorKind::I2cUnsupported(
                "10-bit addresses (StandardFirmata answers \"10-bit addressing not supported\")",
            )));
        }
        Ok(())
    }

    /// Writes `data` to the device at `address` (I2C write request). The board reports no
    /// NACK for a write.
    pub fn i2c_write(&mut self, address: u8, data: &[u8]) -> Result<(), Error> {
        self.check_address(address)?;
        if data.len() > protocol::MAX_I2C_WRITE {
            return Err(self.error(ErrorKind::I2cTooLong {
                what: "write",
                len: data.len(),
                max: protocol::MAX_I2C_WRITE,
            }));
        }
        self.ensure_i2c()?;
        self.tx.clear();
        protocol::encode_i2c_write(&mut self.tx, address, data);
        self.send()
    }

    /// Reads `buf.len()` bytes from the device at `address` once, after writing `register`
    /// when given (with a repeated START when `restart`, else a STOP between), and waits for
    /// the `I2C_REPLY`.
    pub fn i2c_read(
        &mut self,
        address: u8,
        register: Option<u8>,
        restart: bool,
        buf: &mut [u8],
    ) -> Result<(), Error> {
        self.check_address(address)?;
        if buf.len() > protocol::MAX_I2C_READ {
            return Err(self.error(ErrorKind::I2cTooLong {
                what: "read",
                len: buf.len(),
                max: protocol::MAX_I2C_READ,
            }));
        }
        self.ensure_i2c()?;
        let since = self.seq;
        let mode = protocol::I2C_MODE_READ_ONCE
            | if restart {
                protocol::I2C_AUTO_RESTART
            } else {
                0
            };
        self.tx.clear();
        let n = buf.len() as u16;
        match register {
            Some(r) => {
                protocol::encode_i2c_request(&mut self.tx, address, mode, &[u16::from(r), n])
            }
            None => protocol::encode_i2c_request(&mut self.tx, address, mode, &[n]),
        }
        self.send()?;
        let reg = u16::from(register.unwrap_or(0));
        let asked = buf.len();
        let what = format!("I2C reply from {address:#04x}");
        let slot = self.wait_sysex(since, &what, protocol::I2C_REPLY, |b| {
            b.i2c
                .iter()
                .flatten()
                .find(|s| s.address == address && s.register == reg && s.seq > since)
                .copied()
        })?;
        // StandardFirmata 2.5.9 sends "I2C: Too few bytes received" and a short reply;
        // ConfigurableFirmata 2.10.1 sends the string and a full-length reply of stale bytes.
        let too_few = self
            .text
            .as_ref()
            .is_some_and(|t| t.seq > since && t.seq < slot.seq && t.as_str().contains("Too few"));
        if slot.len < asked || too_few {
            return Err(self.error(ErrorKind::I2cNack {
                address,
                asked,
                // A full-length reply after the string holds stale bytes: none came.
                got: if slot.len < asked { slot.len } else { 0 },
            }));
        }
        buf.copy_from_slice(&slot.data[..asked]);
        Ok(())
    }

    /// Starts continuous reads of `len` bytes (from `register` when given) at the sampling
    /// interval; each reply is kept, read it with [`i2c_latest`](Self::i2c_latest).
    pub fn i2c_read_continuously(
        &mut self,
        address: u8,
        register: Option<u8>,
        len: usize,
    ) -> Result<(), Error> {
        self.check_address(address)?;
        if len > protocol::MAX_I2C_READ {
            return Err(self.error(ErrorKind::I2cTooLong {
                what: "read",
                len,
                max: protocol::MAX_I2C_READ,
            }));
        }
        self.ensure_i2c()?;
        self.tx.clear();
        let mode = protocol::I2C_MODE_READ_CONTINUOUSLY;
        match register {
            Some(r) => protocol::encode_i2c_request(
                &mut self.tx,
                address,
                mode,
                &[u16::from(r), len as u16],
            ),
            None => protocol::encode_i2c_request(&mut self.tx, address, mode, &[len as u16]),
        }
        self.send()
    }

    /// Stops the continuous reads of `address`.
    pub fn i2c_stop_reading(&mut self, address: u8) -> Result<(), Error> {
        self.check_address(address)?;
        self.tx.clear();
        protocol::encode_i2c_request(&mut self.tx, address, protocol::I2C_MODE_STOP_READING, &[]);
        self.send()
    }

    /// The latest reply from `address` / `register` (0 for reads without one) copied into
    /// `buf`: its length, or `None` if none came.
    pub fn i2c_latest(&self, address: u8, register: u16, buf: &mut [u8]) -> Option<usize> {
        let slot = self
            .i2c
            .iter()
            .flatten()
            .find(|s| s.address == address && s.register == register)?;
        let n = slot.len.min(buf.len());
        buf[..n].copy_from_slice(&slot.data[..n]);
        Some(n)
    }

    /// Polls until a reply from `address` / `register` newer than now arrives; its length.
    pub fn i2c_wait_next(
        &mut self,
        address: u8,
        register: u16,
        buf: &mut [u8],
        timeout: Duration,
    ) -> Result<usize, Error> {
        let since = self.seq;
        let what = format!("I2C reply from {address:#04x}");
        self.wait(timeout, &what, |b| {
            b.i2c
                .iter()
                .flatten()
                .any(|s| s.address == address && s.register == register && s.seq > since)
                .then_some(Ok(()))
        })?;
        Ok(self.i2c_latest(address, register, buf).unwrap_or(0))
    }

    // --- AccelStepperFirmata ---

    fn check_device(&self, device: u8) -> Result<(), Error> {
        if device >= protocol::MAX_ACCELSTEPPERS {
            return Err(self.error(ErrorKind::OutOfRange {
                what: "stepper device",
                value: device.to_string(),
                range: "0 ..= 9",
            }));
        }
        Ok(())
    }

    fn stepper(&mut self, command: u8, device: u8, payload: &[u8]) -> Result<(), Error> {
        self.check_device(device)?;
        self.tx.clear();
        protocol::encode_stepper(&mut self.tx, command, device, payload);
        self.send()
    }

    /// Configures stepper `device` (0–9) with its interface and pins (accelStepperFirmata.md
    /// 2.6.0, "Stepper configuration"). Send before any other stepper message.
    pub fn stepper_config(&mut self, device: u8, config: &StepperConfig) -> Result<(), Error> {
        let mut payload = [0u8; 7];
        let mut n = 0;
        let mut push = |b: u8| {
            payload[n] = b;
            n += 1;
        };
        push(config.interface_byte());
        let (pins, count) = config.pins();
        for &p in &pins[..count] {
            push(p);
        }
        if let Some(e) = config.enable_pin {
            push(e);
        }
        push(config.invert & 0x1F);
        for &p in &payload[1..n - 1] {
            self.check_pin(p)?;
        }
        self.stepper(protocol::ACCELSTEPPER_CONFIG, device, &payload[..n])
    }

    /// Sets the current position as zero without moving.
    pub fn stepper_zero(&mut self, device: u8) -> Result<(), Error> {
        self.stepper(protocol::ACCELSTEPPER_ZERO, device, &[])
    }

    fn steps(&self, what: &'static str, value: i32) -> Result<[u8; 5], Error> {
        protocol::encode_stepper_i32(value).ok_or_else(|| {
            self.error(ErrorKind::OutOfRange {
                what,
                value: value.to_string(),
                range: "-268435455 ..= 268435455 (28 bits: what the firmware decodes)",
            })
        })
    }

    /// Moves by `steps` (relative).
    pub fn stepper_step(&mut self, device: u8, steps: i32) -> Result<(), Error> {
        let b = self.steps("steps", steps)?;
        self.stepper(protocol::ACCELSTEPPER_STEP, device, &b)
    }

    /// Moves to `position` (absolute, steps from zero).
    pub fn stepper_to(&mut self, device: u8, position: i32) -> Result<(), Error> {
        let b = self.steps("position", position)?;
        self.stepper(protocol::ACCELSTEPPER_TO, device, &b)
    }

    fn float(&self, what: &'static str, value: f32) -> Result<[u8; 4], Error> {
        protocol::encode_custom_float(value).ok_or_else(|| {
            self.error(ErrorKind::OutOfRange {
                what,
                value: value.to_string(),
                range: "finite, |value| ≤ 8388607e4",
            })
        })
    }

    /// Sets the (maximum) speed, steps/s.
    pub fn stepper_set_speed(&mut self, device: u8, steps_per_s: f32) -> Result<(), Error> {
        let b = self.float("speed (steps/s)", steps_per_s)?;
        self.stepper(protocol::ACCELSTEPPER_SET_SPEED, device, &b)
    }

    /// Sets the acceleration, steps/s² (0: none — the firmware then accelerates at 10⁶
    /// steps/s², reaching full speed on the first step).
    pub fn stepper_set_acceleration(&mut self, device: u8, steps_per_s2: f32) -> Result<(), Error> {
        let b = self.float("acceleration (steps/s²)", steps_per_s2)?;
        self.stepper(protocol::ACCELSTEPPER_SET_ACCELERATION, device, &b)
    }

    /// Enables or disables the driver's outputs (drivers with an enable pin).
    pub fn stepper_enable(&mut self, device: u8, on: bool) -> Result<(), Error> {
        self.stepper(protocol::ACCELSTEPPER_ENABLE, device, &[u8::from(on)])
    }

    /// Stops the stepper; the board answers with a move-complete report at the stop position
    /// (ConfigurableFirmata 2.10.1 `AccelStepperFirmata.cpp`, `ACCELSTEPPER_STOP`), returned.
    pub fn stepper_stop(&mut self, device: u8) -> Result<i32, Error> {
        let since = self.seq;
        self.stepper(protocol::ACCELSTEPPER_STOP, device, &[])?;
        self.wait_stepper_complete_since(device, since, self.options.reply_timeout)
    }

    /// Asks for the position and waits for the report.
    pub fn stepper_position(&mut self, device: u8) -> Result<i32, Error> {
        let since = self.seq;
        self.stepper(protocol::ACCELSTEPPER_REPORT_POSITION, device, &[])?;
        let what = format!("position report of stepper {device}");
        self.wait_sysex(since, &what, protocol::ACCELSTEPPER_DATA, |b| {
            let s = b.steppers[usize::from(device)];
            (s.position_seq > since).then_some(s.position)
        })
    }

    /// Marks now as the start of a move: [`wait_stepper_complete`](Self::wait_stepper_complete)
    /// waits for a report after the mark.
    pub fn mark(&self) -> u64 {
        self.seq
    }

    /// Waits for the move-complete report of `device` after `mark` (from [`mark`](Self::mark)
    /// before the move was sent); the final position.
    pub fn wait_stepper_complete(
        &mut self,
        device: u8,
        mark: u64,
        timeout: Duration,
    ) -> Result<i32, Error> {
        self.check_device(device)?;
        self.wait_stepper_complete_since(device, mark, timeout)
    }

    fn wait_stepper_complete_since(
        &mut self,
        device: u8,
        since: u64,
        timeout: Duration,
    ) -> Result<i32, Error> {
        let what = format!("move-complete report of stepper {device}");
        self.wait(timeout, &what, |b| {
            let s = b.steppers[usize::from(device)];
            if s.complete_seq > since {
                return Some(Ok(s.complete_position));
            }
            b.refusal(since, "the stepper command").map(Err)
        })
    }

    /// The latest position any report gave for `device`.
    pub fn stepper_last_position(&self, device: u8) -> Option<i32> {
        let s = self.steppers.get(usize::from(device))?;
        (s.position_seq > 0).then_some(s.position)
    }

    /// Sends raw bytes (a message this crate has no method for).
    pub fn send_raw(&mut self, bytes: &[u8]) -> Result<(), Error> {
        self.tx.clear();
        self.tx.extend_from_slice(bytes);
        self.send()
    }

    /// The serial port back, closing nothing.
    pub fn into_port(self) -> SerialPort {
        self.port
    }
}

/// How a stepper is wired (accelStepperFirmata.md 2.6.0, "Stepper configuration", byte 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepperInterface {
    /// A step + direction driver (`001`).
    Driver {
        /// Step pin.
        step: u8,
        /// Direction pin.
        direction: u8,
    },
    /// Two wires (`010`).
    TwoWire([u8; 2]),
    /// Three wires, whole or half steps (`011`).
    ThreeWire([u8; 3]),
    /// Four wires, whole or half steps (`100`).
    FourWire([u8; 4]),
}

/// A stepper's configuration message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepperConfig {
    /// Wiring and pins.
    pub interface: StepperInterface,
    /// Step size 1/2^n (0 whole, 1 half, …): bits 3–1 of the interface byte.
    pub step_size: u8,
    /// An enable pin, if the driver has one.
    pub enable_pin: Option<u8>,
    /// Pins to invert: bit 0 motor pin 1 … bit 3 motor pin 4, bit 4 the enable pin.
    pub invert: u8,
}

impl StepperConfig {
    /// A step + direction driver, whole steps, no enable pin, nothing inverted.
    pub fn driver(step: u8, direction: u8) -> StepperConfig {
        StepperConfig {
            interface: StepperInterface::Driver { step, direction },
            step_size: 0,
            enable_pin: None,
            invert: 0,
        }
    }

    /// The interface byte: wire count in bits 6–4, step size in bits 3–1, enable in bit 0.
    ///
    /// ```
    /// use firmata_host::StepperConfig;
    /// assert_eq!(StepperConfig::driver(2, 3).interface_byte(), 0b001_000_0);
    /// ```
    pub fn interface_byte(&self) -> u8 {
        let wires = match self.interface {
            StepperInterface::Driver { .. } => 1,
            StepperInterface::TwoWire(_) => 2,
            StepperInterface::ThreeWire(_) => 3,
            StepperInterface::FourWire(_) => 4,
        };
        (wires << 4) | ((self.step_size & 0x07) << 1) | u8::from(self.enable_pin.is_some())
    }

    /// The motor pins in message order, and how many there are.
    fn pins(&self) -> ([u8; 4], usize) {
        match self.interface {
            StepperInterface::Driver { step, direction } => ([step, direction, 0, 0], 2),
            StepperInterface::TwoWire([a, b]) => ([a, b, 0, 0], 2),
            StepperInterface::ThreeWire([a, b, c]) => ([a, b, c, 0], 3),
            StepperInterface::FourWire(p) => (p, 4),
        }
    }
}

/// The first bytes as text where printable, else hex.
fn sample_text(bytes: &[u8]) -> String {
    if !bytes.is_empty()
        && bytes
            .iter()
            .all(|b| b.is_ascii_graphic() || *b == b' ' || *b == b'\n' || *b == b'\r')
    {
        format!("{:?}", String::from_utf8_lossy(bytes))
    } else {
        bytes
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect::<Vec<_>>()
            .join(" ")
    }
}
