//! The sketch: what StandardFirmata 2.5.9 or ConfigurableFirmata 2.10.1 does with each message
//! the host sends and on each pass of its `loop()`, without a serial line (pure: bytes in,
//! bytes out, the time given).

use std::time::Duration;

use embedded_hal::i2c::Operation;
use firmata_host::PinMode;
use firmata_host::protocol::{self as p, BOARD_SYSEX_BUFFER};

use crate::analog::AnalogInputs;
use crate::bus::ChipBus;
use crate::pins::BoardKind;
use crate::stepper::Stepper;

/// Which sketch the simulated board runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FirmwareKind {
    /// StandardFirmata from Firmata 2.5.9 (the Arduino IDE's example): protocol 2.5, firmware
    /// "StandardFirmata" 2.5; ignores sysex it does not know; no steppers.
    Standard,
    /// ConfigurableFirmata 2.10.1 with AccelStepperFirmata: protocol 2.6, firmware
    /// "ConfigurableFirmata" 2.10; answers an unknown sysex with "Unhandled sysex command".
    #[default]
    Configurable,
}

impl FirmwareKind {
    /// The protocol version it reports (`REPORT_VERSION`).
    pub fn protocol_version(self) -> (u8, u8) {
        match self {
            FirmwareKind::Standard => (2, 5),
            FirmwareKind::Configurable => (2, 6),
        }
    }

    /// The firmware name and version it reports (`REPORT_FIRMWARE`): the sketch's file name.
    pub fn firmware(self) -> (&'static str, u8, u8) {
        match self {
            FirmwareKind::Standard => ("StandardFirmata", 2, 5),
            FirmwareKind::Configurable => ("ConfigurableFirmata", 2, 10),
        }
    }

    fn has_steppers(self) -> bool {
        self == FirmwareKind::Configurable
    }
}

/// A message from the host, as the board's parser (`FirmataParser.cpp`, Firmata 2.5.9)
/// delivers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HostMessage<'a> {
    Analog { channel: u8, value: u16 },
    Digital { port: u8, value: u16 },
    ReportAnalog { channel: u8, on: bool },
    ReportDigital { port: u8, on: bool },
    SetPinMode { pin: u8, mode: u8 },
    SetPinValue { pin: u8, value: u8 },
    VersionQuery,
    Reset,
    Sysex { id: u8, argv: &'a [u8] },
}

/// The board's parser: a 64-byte sysex buffer that drops what does not fit, as the firmware's.
#[derive(Debug, Clone)]
pub(crate) struct BoardParser {
    wait: u8,
    command: u8,
    channel: u8,
    data: [u8; 2],
    sysex: bool,
    buf: [u8; BOARD_SYSEX_BUFFER],
    len: usize,
}

impl BoardParser {
    pub(crate) fn new() -> BoardParser {
        BoardParser {
            wait: 0,
            command: 0,
            channel: 0,
            data: [0; 2],
            sysex: false,
            buf: [0; BOARD_SYSEX_BUFFER],
            len: 0,
        }
    }

    fn push(&mut self, byte: u8) -> Option<HostMessage<'_>> {
        if self.sysex {
            if byte == p::END_SYSEX {
                self.sysex = false;
                let (id, argv) = self.buf[..self.len].split_first()?;
                return Some(HostMessage::Sysex { id: *id, argv });
            }
            // As `FirmataParser::parse`: data bytes are buffered (a status byte too: the
            // firmware does not check), and what overflows the buffer is dropped.
            if self.len < self.buf.len() {
                self.buf[self.len] = byte;
                self.len += 1;
            }
            return None;
        }
        if self.wait > 0 && byte < 0x80 {
            self.wait -= 1;
            self.data[usize::from(self.wait)] = byte;
            if self.wait > 0 {
                return None;
            }
            let value = (u16::from(self.data[0]) << 7) | u16::from(self.data[1]);
            let ch = self.channel;
            return Some(match self.command {
                p::ANALOG_MESSAGE => HostMessage::Analog { channel: ch, value },
                p::DIGITAL_MESSAGE => HostMessage::Digital { port: ch, value },
                p::SET_PIN_MODE => HostMessage::SetPinMode {
                    pin: self.data[1],
                    mode: self.data[0],
                },
                p::SET_DIGITAL_PIN_VALUE => HostMessage::SetPinValue {
                    pin: self.data[1],
                    value: self.data[0],
                },
                p::REPORT_ANALOG => HostMessage::ReportAnalog {
                    channel: ch,
                    on: self.data[0] != 0,
                },
                _ => HostMessage::ReportDigital {
                    port: ch,
                    on: self.data[0] != 0,
                },
            });
        }
        let (command, channel) = if byte < 0xF0 {
            (byte & 0xF0, byte & 0x0F)
        } else {
            (byte, 0)
        };
        self.command = command;
        self.channel = channel;
        match command {
            p::ANALOG_MESSAGE | p::DIGITAL_MESSAGE | p::SET_PIN_MODE | p::SET_DIGITAL_PIN_VALUE => {
                self.wait = 2;
            }
            p::REPORT_ANALOG | p::REPORT_DIGITAL => {
                // One data byte: it lands in data[0] (`waitForData` counts down to 0).
                self.wait = 1;
                self.data[1] = 0;
            }
            p::START_SYSEX => {
                self.sysex = true;
                self.len = 0;
            }
            p::REPORT_VERSION => return Some(HostMessage::VersionQuery),
            p::SYSTEM_RESET => {
                self.wait = 0;
                self.sysex = false;
                return Some(HostMessage::Reset);
            }
            _ => {}
        }
        None
    }
}

/// A continuous I2C read (`i2c_device_info`).
#[derive(Debug, Clone, Copy)]
struct Query {
    address: u8,
    register: Option<u8>,
    bytes: u8,
    stop: bool,
}

/// `I2C_MAX_QUERIES`.
const I2C_MAX_QUERIES: usize = 8;
/// `Wire`'s buffer (`BUFFER_LENGTH` of AVR `Wire.h`).
const WIRE_BUFFER: usize = 32;
/// The `Wire` clock: 100 kHz (the library's default; Firmata does not change it).
const I2C_BIT: Duration = Duration::from_micros(10);

/// The sketch's state.
#[derive(Debug)]
pub struct Firmware {
    kind: FirmwareKind,
    board: BoardKind,
    parser: BoardParser,
    modes: Vec<u8>,
    /// Levels the host wrote to output pins, by pin.
    outputs: Vec<bool>,
    analog_report: u16,
    digital_report: u16,
    sampling: Duration,
    last_sample: Duration,
    i2c_enabled: bool,
    i2c_delay_us: u16,
    queries: Vec<Query>,
    /// ConfigurableFirmata's reply buffer, whose stale bytes a short read reports.
    rx_data: [u8; 64],
    steppers: Vec<Option<Stepper>>,
    last_step: Duration,
    /// I2C bus time the last message took, for the line to charge.
    busy: Duration,
}

impl Firmware {
    /// The sketch after `setup()` on `board`.
    pub fn new(kind: FirmwareKind, board: BoardKind) -> Firmware {
        let n = usize::from(board.total_pins());
        let mut fw = Firmware {
            kind,
            board,
            parser: BoardParser::new(),
            modes: vec![0; n],
            outputs: vec![false; n],
            analog_report: 0,
            digital_report: 0,
            sampling: Duration::from_millis(19),
            last_sample: Duration::ZERO,
            i2c_enabled: false,
            i2c_delay_us: 0,
            queries: Vec::new(),
            rx_data: [0; 64],
            steppers: vec![None; usize::from(p::MAX_ACCELSTEPPERS)],
            last_step: Duration::ZERO,
            busy: Duration::ZERO,
        };
        fw.system_reset();
        fw
    }

    /// Which sketch.
    pub fn kind(&self) -> FirmwareKind {
        self.kind
    }

    /// A stepper, if configured.
    pub fn stepper_at(&self, device: u8) -> Option<&Stepper> {
        self.steppers.get(usize::from(device))?.as_ref()
    }

    /// A stepper's position, if configured.
    pub fn stepper_position(&self, device: u8) -> Option<i32> {
        self.steppers
            .get(usize::from(device))?
            .as_ref()
            .map(Stepper::position)
    }

    /// A pin's mode code.
    pub fn pin_mode(&self, pin: u8) -> Option<u8> {
        self.modes.get(usize::from(pin)).copied()
    }

    /// The sampling interval.
    pub fn sampling_interval(&self) -> Duration {
        self.sampling
    }

    /// Takes and clears the I2C bus time the messages since the last call took.
    pub(crate) fn take_busy(&mut self) -> Duration {
        std::mem::take(&mut self.busy)
    }

    /// `systemResetCallback()` (StandardFirmata 2.5.9): analog pins to analog input, the other
    /// digital pins to output, nothing reported, I2C off; ConfigurableFirmata also frees its
    /// steppers.
    pub fn system_reset(&mut self) {
        for pin in 0..self.board.total_pins() {
            let k = usize::from(pin);
            self.modes[k] = if self.board.is_analog(pin) {
                PinMode::Analog.code()
            } else if self.board.is_digital(pin) {
                PinMode::Output.code()
            } else {
                0x7F
            };
            self.outputs[k] = false;
        }
        self.analog_report = 0;
        self.digital_report = 0;
        self.i2c_enabled = false;
        self.queries.clear();
        self.sampling = Duration::from_millis(19);
        for s in &mut self.steppers {
            *s = None;
        }
    }

    /// The start-up reports: `FirmataClass::begin` prints the version, then the firmware.
    pub fn boot_report(&self, out: &mut Vec<u8>) {
        let (major, minor) = self.kind.protocol_version();
        p::encode_version_report(out, major, minor);
        let (name, fmajor, fminor) = self.kind.firmware();
        p::encode_firmware_report(out, fmajor, fminor, name);
    }

    /// Takes bytes from the host; the board's answers go to `out`.
    pub fn receive(
        &mut self,
        bytes: &[u8],
        now: Duration,
        bus: &mut ChipBus,
        analog: &mut dyn AnalogInputs,
        out: &mut Vec<u8>,
    ) {
        for &b in bytes {
            // The parser's borrow ends with the message: copy the sysex out of it first.
            let mut sysex = [0u8; BOARD_SYSEX_BUFFER];
            let message = match self.parser.push(b) {
                Some(HostMessage::Sysex { id, argv }) => {
                    sysex[..argv.len()].copy_from_slice(argv);
                    Some((Some((id, argv.len())), None))
                }
                Some(other) => Some((None, Some(copy_message(other)))),
                None => None,
            };
            match message {
                Some((Some((id, len)), _)) => self.sysex(id, &sysex[..len], now, bus, analog, out),
                Some((None, Some(m))) => self.message(m, now, analog, out),
                _ => {}
            }
        }
    }

    fn message(
        &mut self,
        m: HostMessage<'static>,
        now: Duration,
        analog: &mut dyn AnalogInputs,
        out: &mut Vec<u8>,
    ) {
        match m {
            HostMessage::VersionQuery => {
                let (major, minor) = self.kind.protocol_version();
                p::encode_version_report(out, major, minor);
            }
            HostMessage::Reset => self.system_reset(),
            HostMessage::SetPinMode { pin, mode } => self.set_pin_mode(pin, mode),
            HostMessage::SetPinValue { pin, value } => {
                if let Some(o) = self.outputs.get_mut(usize::from(pin)) {
                    *o = value != 0;
                }
            }
            HostMessage::Digital { port, value } => {
                for bit in 0..8u8 {
                    let pin = usize::from(port) * 8 + usize::from(bit);
                    if let Some(o) = self.outputs.get_mut(pin) {
                        *o = value & (1 << bit) != 0;
                    }
                }
            }
            // Analog write (PWM / servo): nothing here reads it back.
            HostMessage::Analog { .. } => {}
            HostMessage::ReportAnalog { channel, on } => {
                if channel < self.board.analog_channels() {
                    if on {
                        self.analog_report |= 1 << channel;
                        // Since protocol 2.4: the value at once (`reportAnalogCallback`).
                        let counts = counts(analog.volts(channel, now));
                        p::encode_analog(out, channel, counts);
                    } else {
                        self.analog_report &= !(1 << channel);
                    }
                }
            }
            HostMessage::ReportDigital { port, on } => {
                if usize::from(port) * 8 < self.modes.len() {
                    if on {
                        self.digital_report |= 1 << port;
                        p::encode_digital(out, port, self.read_port(port));
                    } else {
                        self.digital_report &= !(1 << port);
                    }
                }
            }
            HostMessage::Sysex { .. } => {}
        }
    }

    /// The input levels of a port's pins: pull-ups read high, other inputs low (nothing is
    /// wired to them yet), outputs as driven.
    fn read_port(&self, port: u8) -> u8 {
        (0..8u8).fold(0, |mask, bit| {
            let pin = usize::from(port) * 8 + usize::from(bit);
            let high = match self.modes.get(pin).copied() {
                Some(m) if m == PinMode::InputPullup.code() => true,
                Some(m) if m == PinMode::Output.code() => self.outputs[pin],
                _ => false,
            };
            mask | (u8::from(high) << bit)
        })
    }

    fn set_pin_mode(&mut self, pin: u8, mode: u8) {
        if pin >= self.board.total_pins() {
            return;
        }
        let supported = self
            .board
            .capabilities(pin, self.kind.has_steppers())
            .iter()
            .any(|(m, _)| m.code() == mode);
        if !supported {
            // StandardFirmata 2.5.9 `setPinModeCallback`: "Unknown pin mode" for the rest.
            return;
        }
        if self.board.is_i2c(pin) && mode != PinMode::I2c.code() && self.i2c_enabled {
            // Leaving I2C turns continuous reads off (`disableI2CPins`).
            self.i2c_enabled = false;
            self.queries.clear();
        }
        self.modes[usize::from(pin)] = mode;
    }

    fn sysex(
        &mut self,
        id: u8,
        argv: &[u8],
        now: Duration,
        bus: &mut ChipBus,
        analog: &mut dyn AnalogInputs,
        out: &mut Vec<u8>,
    ) {
        let _ = analog;
        match id {
            p::REPORT_FIRMWARE => {
                let (name, major, minor) = self.kind.firmware();
                p::encode_firmware_report(out, major, minor, name);
            }
            p::CAPABILITY_QUERY => {
                out.extend_from_slice(&[p::START_SYSEX, p::CAPABILITY_RESPONSE]);
                for pin in 0..self.board.total_pins() {
                    for (mode, resolution) in self.board.capabilities(pin, self.kind.has_steppers())
                    {
                        out.extend_from_slice(&[mode.code(), resolution]);
                    }
                    out.push(0x7F);
                }
                out.push(p::END_SYSEX);
            }
            p::ANALOG_MAPPING_QUERY => {
                out.extend_from_slice(&[p::START_SYSEX, p::ANALOG_MAPPING_RESPONSE]);
                for pin in 0..self.board.total_pins() {
                    out.push(self.board.analog_channel(pin).unwrap_or(127));
                }
                out.push(p::END_SYSEX);
            }
            p::PIN_STATE_QUERY => {
                if let Some(&pin) = argv.first() {
                    if pin < self.board.total_pins() {
                        let state = u8::from(self.outputs[usize::from(pin)]);
                        out.extend_from_slice(&[
                            p::START_SYSEX,
                            p::PIN_STATE_RESPONSE,
                            pin,
                            self.modes[usize::from(pin)],
                            state,
                            p::END_SYSEX,
                        ]);
                    }
                }
            }
            p::SAMPLING_INTERVAL => {
                if argv.len() > 1 {
                    let ms = u64::from(argv[0]) | (u64::from(argv[1]) << 7);
                    // `MINIMUM_SAMPLING_INTERVAL` 1 ms.
                    self.sampling = Duration::from_millis(ms.max(1));
                }
            }
            p::I2C_CONFIG => self.i2c_config(argv),
            p::I2C_REQUEST => {
                if self.kind == FirmwareKind::Configurable && !self.i2c_enabled {
                    // ConfigurableFirmata 2.10.1 `I2CFirmata::handleSysex`: a request before
                    // I2C_CONFIG falls through into the config case (its bytes as the delay).
                    self.i2c_config(argv);
                    return;
                }
                self.i2c_request(argv, now, bus, out);
            }
            p::ACCELSTEPPER_DATA if self.kind.has_steppers() => self.stepper(argv, out),
            _ => {
                if self.kind == FirmwareKind::Configurable {
                    p::encode_string(out, "Unhandled sysex command");
                }
                // StandardFirmata's `sysexCallback` has no default case: silence.
            }
        }
    }

    fn i2c_config(&mut self, argv: &[u8]) {
        let delay = match argv {
            [l, m, ..] => u16::from(*l) | (u16::from(*m) << 7),
            _ => 0,
        };
        if delay > 0 {
            self.i2c_delay_us = delay;
        }
        if !self.i2c_enabled {
            for pin in 0..self.board.total_pins() {
                if self.board.is_i2c(pin) {
                    self.modes[usize::from(pin)] = PinMode::I2c.code();
                }
            }
            self.i2c_enabled = true;
        }
    }

    fn i2c_request(&mut self, argv: &[u8], now: Duration, bus: &mut ChipBus, out: &mut Vec<u8>) {
        let [address, mode_byte, rest @ ..] = argv else {
            return;
        };
        let mode = mode_byte & 0x18;
        if mode_byte & p::I2C_10BIT_MODE != 0 {
            p::encode_string(out, "10-bit addressing not supported");
            return;
        }
        let stop = mode_byte & p::I2C_AUTO_RESTART == 0;
        let word = |k: usize| -> u16 { u16::from(rest[2 * k]) | (u16::from(rest[2 * k + 1]) << 7) };
        // `argc == 6` (address, mode, register pair, count pair) names a register.
        let (register, bytes) = match rest.len() {
            4 => (Some(word(0) as u8), word(1) as u8),
            n if n >= 2 => (None, word(0) as u8),
            _ => (None, 0),
        };
        match mode {
            p::I2C_MODE_WRITE => {
                let mut data = [0u8; WIRE_BUFFER];
                let mut n = 0;
                for pair in rest.chunks_exact(2) {
                    // `Wire.write` drops what overflows its buffer.
                    if n < WIRE_BUFFER {
                        data[n] = (u16::from(pair[0]) | (u16::from(pair[1]) << 7)) as u8;
                        n += 1;
                    }
                }
                // `endTransmission()`'s status is dropped: the host never hears of a NACK.
                let _ = bus.transaction(*address, &mut [Operation::Write(&data[..n])]);
                self.busy += I2C_BIT * (9 * (n as u32 + 1) + 2) + Duration::from_micros(70);
            }
            p::I2C_MODE_READ_ONCE => {
                self.read_and_report(*address, register, bytes, stop, now, bus, out);
            }
            p::I2C_MODE_READ_CONTINUOUSLY => {
                if self.queries.len() >= I2C_MAX_QUERIES {
                    p::encode_string(out, "too many queries");
                } else {
                    self.queries.push(Query {
                        address: *address,
                        register,
                        bytes,
                        stop,
                    });
                }
            }
            _ => {
                // Stop reading: the first query of that address goes.
                if let Some(k) = self.queries.iter().position(|q| q.address == *address) {
                    self.queries.remove(k);
                }
            }
        }
    }

    /// `readAndReportData`.
    #[allow(clippy::too_many_arguments)]
    fn read_and_report(
        &mut self,
        address: u8,
        register: Option<u8>,
        bytes: u8,
        stop: bool,
        now: Duration,
        bus: &mut ChipBus,
        out: &mut Vec<u8>,
    ) {
        let _ = now;
        let asked = usize::from(bytes);
        // `Wire.requestFrom` clamps to its buffer.
        let take = asked.min(WIRE_BUFFER);
        let mut data = [0u8; WIRE_BUFFER];
        let acked = match (register, stop) {
            (Some(r), false) => bus.transaction(
                address,
                &mut [Operation::Write(&[r]), Operation::Read(&mut data[..take])],
            ),
            (Some(r), true) => {
                // The register write's NACK is not checked; the read then finds out.
                let _ = bus.transaction(address, &mut [Operation::Write(&[r])]);
                take == 0 || bus.transaction(address, &mut [Operation::Read(&mut data[..take])])
            }
            (None, _) => {
                take == 0 || bus.transaction(address, &mut [Operation::Read(&mut data[..take])])
            }
        };
        let available = if acked { take } else { 0 };
        let wire_bits = 9 * (available + 1) + if register.is_some() { 9 * 2 } else { 0 } + 4;
        self.busy +=
            I2C_BIT * wire_bits as u32 + Duration::from_micros(u64::from(self.i2c_delay_us));
        let mut n = asked;
        if asked > available {
            p::encode_string(out, "I2C: Too few bytes received");
            if self.kind == FirmwareKind::Standard {
                n = available;
            }
        }
        self.rx_data[..available].copy_from_slice(&data[..available]);
        // StandardFirmata 2.5.9 `i2cRxData[64]` holds address, register and 62 bytes.
        let n = n.min(62);
        p::encode_i2c_reply(
            out,
            address,
            u16::from(register.unwrap_or(0)),
            &self.rx_data[..n],
        );
    }

    fn stepper(&mut self, argv: &[u8], out: &mut Vec<u8>) {
        let [command, device, args @ ..] = argv else {
            return;
        };
        let Some(slot) = self.steppers.get_mut(usize::from(*device)) else {
            return;
        };
        let five = |a: &[u8]| -> Option<i32> {
            let b: [u8; 5] = a.get(..5)?.try_into().ok()?;
            // The firmware's decode keeps 28 bits of magnitude (`decode32BitSignedInteger`).
            let magnitude = p::decode_stepper_i32([b[0], b[1], b[2], b[3], 0]);
            Some(if b[4] & 0x08 != 0 {
                -magnitude
            } else {
                magnitude
            })
        };
        let four = |a: &[u8]| -> Option<f32> {
            let b: [u8; 4] = a.get(..4)?.try_into().ok()?;
            Some(p::decode_custom_float(b))
        };
        match *command {
            p::ACCELSTEPPER_CONFIG => {
                let Some(&interface) = args.first() else {
                    return;
                };
                let wires = (interface & 0x70) >> 4;
                let pins = usize::from(wires.clamp(2, 4));
                for &pin in args.iter().skip(1).take(pins) {
                    if let Some(m) = self.modes.get_mut(usize::from(pin)) {
                        *m = PinMode::Stepper.code();
                    }
                }
                *slot = Some(Stepper::default());
            }
            p::ACCELSTEPPER_ZERO => {
                if let Some(s) = slot {
                    s.zero();
                }
            }
            p::ACCELSTEPPER_STEP => {
                if let (Some(s), Some(n)) = (slot.as_mut(), five(args)) {
                    s.move_by(n);
                }
            }
            p::ACCELSTEPPER_TO => {
                if let (Some(s), Some(n)) = (slot.as_mut(), five(args)) {
                    s.move_to(n);
                }
            }
            p::ACCELSTEPPER_ENABLE => {
                if let (Some(s), Some(&on)) = (slot.as_mut(), args.first()) {
                    s.set_enabled(on != 0);
                }
            }
            p::ACCELSTEPPER_STOP => {
                if let Some(s) = slot {
                    s.stop();
                    p::encode_stepper_position(out, *device, s.position(), true);
                }
            }
            p::ACCELSTEPPER_REPORT_POSITION => {
                if let Some(s) = slot {
                    p::encode_stepper_position(out, *device, s.position(), false);
                }
            }
            p::ACCELSTEPPER_SET_ACCELERATION => {
                if let (Some(s), Some(a)) = (slot.as_mut(), four(args)) {
                    s.set_acceleration(a);
                }
            }
            p::ACCELSTEPPER_SET_SPEED => {
                if let (Some(s), Some(v)) = (slot.as_mut(), four(args)) {
                    s.set_max_speed(v);
                }
            }
            _ => {}
        }
    }

    /// One pass of `loop()` at `now`: steppers move (and report completed moves; `analog`
    /// hears the steps they took); every sampling interval, the enabled analog inputs and the
    /// continuous I2C reads are reported.
    /// The time until the next pass has work, at most.
    pub fn tick(
        &mut self,
        now: Duration,
        bus: &mut ChipBus,
        analog: &mut dyn AnalogInputs,
        out: &mut Vec<u8>,
    ) -> Duration {
        let dt = now.saturating_sub(self.last_step).as_secs_f64();
        self.last_step = now;
        let mut any_running = false;
        for (device, slot) in self.steppers.iter_mut().enumerate() {
            if let Some(s) = slot {
                let before = s.position();
                let done = s.advance(dt);
                let moved = i64::from(s.position()) - i64::from(before);
                if moved != 0 {
                    let moved = moved.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
                    analog.stepper_moved(device as u8, moved, now);
                }
                if done {
                    p::encode_stepper_position(out, device as u8, s.position(), true);
                }
                any_running |= s.running();
            }
        }
        if now.saturating_sub(self.last_sample) > self.sampling {
            self.last_sample += self.sampling;
            // A board that fell far behind (the host was away) does not report a backlog.
            if now.saturating_sub(self.last_sample) > self.sampling * 4 {
                self.last_sample = now;
            }
            for pin in 0..self.board.total_pins() {
                let Some(channel) = self.board.analog_channel(pin) else {
                    continue;
                };
                if self.modes[usize::from(pin)] == PinMode::Analog.code()
                    && self.analog_report & (1 << channel) != 0
                {
                    p::encode_analog(out, channel, counts(analog.volts(channel, now)));
                }
            }
            let queries = self.queries.clone();
            for q in queries {
                self.read_and_report(q.address, q.register, q.bytes, q.stop, now, bus, out);
            }
        }
        let next_sample =
            (self.last_sample + self.sampling + Duration::from_micros(500)).saturating_sub(now);
        if any_running {
            next_sample.min(Duration::from_millis(1))
        } else {
            next_sample
        }
    }
}

/// A message without the parser's borrow (only sysex borrows).
fn copy_message(m: HostMessage<'_>) -> HostMessage<'static> {
    match m {
        HostMessage::Analog { channel, value } => HostMessage::Analog { channel, value },
        HostMessage::Digital { port, value } => HostMessage::Digital { port, value },
        HostMessage::ReportAnalog { channel, on } => HostMessage::ReportAnalog { channel, on },
        HostMessage::ReportDigital { port, on } => HostMessage::ReportDigital { port, on },
        HostMessage::SetPinMode { pin, mode } => HostMessage::SetPinMode { pin, mode },
        HostMessage::SetPinValue { pin, value } => HostMessage::SetPinValue { pin, value },
        HostMessage::VersionQuery => HostMessage::VersionQuery,
        HostMessage::Reset => HostMessage::Reset,
        HostMessage::Sysex { id, .. } => HostMessage::Sysex { id, argv: &[] },
    }
}

/// The AVR's 10-bit ADC code of `volts` against a 5 V reference.
pub fn counts(volts: f32) -> u16 {
    let c = (volts / 5.0 * 1023.0).round();
    if c.is_nan() {
        0
    } else {
        c.clamp(0.0, 1023.0) as u16
    }
}
