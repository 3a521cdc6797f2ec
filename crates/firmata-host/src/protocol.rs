//! The Firmata wire format: command bytes, sysex IDs, pin modes, 7-bit encodings and the
//! encoders of every message this crate sends (host → board) and of the reports a board sends
//! (board → host, for simulators and tests).
//!
//! Every rule names its source. The sources, and the short names used beside each rule:
//!
//! - **protocol.md 2.6.0**: `firmata/protocol`, tag `2.6.0` (commit `eb9e203`), `protocol.md`;
//! - **i2c.md 2.6.0**: the same tag, `i2c.md`;
//! - **accelStepperFirmata.md 2.6.0**: the same tag, `accelStepperFirmata.md` (two of its
//!   statements disagree with the firmware; the firmware is what a board does, and it is followed
//!   here where the two differ: see [`ACCELSTEPPER_MOVE_COMPLETE`] and [`encode_custom_float`]);
//! - **StandardFirmata 2.5.9**: `firmata/arduino`, tag `2.5.9`,
//!   `examples/StandardFirmata/StandardFirmata.ino`, `FirmataParser.cpp`, `Boards.h`;
//! - **ConfigurableFirmata 2.10.1**: `firmata/ConfigurableFirmata`, tag `2.10.1`,
//!   `src/I2CFirmata.h`, `src/AccelStepperFirmata.{h,cpp}`, `src/FirmataExt.cpp`.
//!
//! The encoders append to a caller's `Vec<u8>`: a buffer the caller clears and reuses does not
//! allocate once it has grown to the longest message.
//!
//! ```
//! use firmata_host::protocol::{self, PinMode};
//! let mut out = Vec::new();
//! protocol::encode_set_pin_mode(&mut out, 3, PinMode::Pwm);
//! assert_eq!(out, [0xF4, 3, 0x03]); // protocol.md 2.6.0, "Set pin mode"
//! ```

// --- MIDI-style commands (protocol.md 2.6.0, "Message Types") ---

/// Analog I/O message, `0xE0 | channel`, then LSB (bits 0–6) and MSB (bits 7–13).
pub const ANALOG_MESSAGE: u8 = 0xE0;
/// Digital I/O message, `0x90 | port`, then pins 0–6 and pin 7 of the port's bitmask.
pub const DIGITAL_MESSAGE: u8 = 0x90;
/// Report analog pin, `0xC0 | channel`, then disable / enable (0 / 1).
pub const REPORT_ANALOG: u8 = 0xC0;
/// Report digital port, `0xD0 | port`, then disable / enable (0 / 1).
pub const REPORT_DIGITAL: u8 = 0xD0;
/// Start of a sysex message.
pub const START_SYSEX: u8 = 0xF0;
/// Set pin mode: pin (0–127), mode.
pub const SET_PIN_MODE: u8 = 0xF4;
/// Set digital pin value (protocol 2.5): pin, value (0 / 1).
pub const SET_DIGITAL_PIN_VALUE: u8 = 0xF5;
/// End of a sysex message.
pub const END_SYSEX: u8 = 0xF7;
/// Protocol version: a request alone, a report with major and minor.
pub const REPORT_VERSION: u8 = 0xF9;
/// System reset.
pub const SYSTEM_RESET: u8 = 0xFF;

// --- Sysex IDs (protocol.md 2.6.0, "Sysex Message Format"; i2c.md 2.6.0) ---

/// AccelStepperFirmata's sysex ID (accelStepperFirmata.md 2.6.0; ConfigurableFirmata 2.10.1
/// `ConfigurableFirmata.h`).
pub const ACCELSTEPPER_DATA: u8 = 0x62;
/// Analog mapping query.
pub const ANALOG_MAPPING_QUERY: u8 = 0x69;
/// Analog mapping response: one byte per pin, the analog channel or 127.
pub const ANALOG_MAPPING_RESPONSE: u8 = 0x6A;
/// Capability query.
pub const CAPABILITY_QUERY: u8 = 0x6B;
/// Capability response: per pin, (mode, resolution) pairs then 0x7F.
pub const CAPABILITY_RESPONSE: u8 = 0x6C;
/// Pin state query.
pub const PIN_STATE_QUERY: u8 = 0x6D;
/// Pin state response.
pub const PIN_STATE_RESPONSE: u8 = 0x6E;
/// Extended analog.
pub const EXTENDED_ANALOG: u8 = 0x6F;
/// A string of 14-bit characters (boards report errors with it).
pub const STRING_DATA: u8 = 0x71;
/// I2C read / write request (i2c.md 2.6.0).
pub const I2C_REQUEST: u8 = 0x76;
/// I2C reply (i2c.md 2.6.0).
pub const I2C_REPLY: u8 = 0x77;
/// I2C config (i2c.md 2.6.0).
pub const I2C_CONFIG: u8 = 0x78;
/// Firmware name and version: a query alone, a report with major, minor and the name.
pub const REPORT_FIRMWARE: u8 = 0x79;
/// Sampling interval, ms, as two 7-bit bytes (default 19 ms).
pub const SAMPLING_INTERVAL: u8 = 0x7A;

// --- I2C request mode bits (i2c.md 2.6.0, byte 3 of the request) ---

/// Bits 4–3 = 00: write.
pub const I2C_MODE_WRITE: u8 = 0b00 << 3;
/// Bits 4–3 = 01: read once.
pub const I2C_MODE_READ_ONCE: u8 = 0b01 << 3;
/// Bits 4–3 = 10: read continuously (at the sampling interval).
pub const I2C_MODE_READ_CONTINUOUSLY: u8 = 0b10 << 3;
/// Bits 4–3 = 11: stop reading continuously.
pub const I2C_MODE_STOP_READING: u8 = 0b11 << 3;
/// Bit 5: 10-bit address mode (StandardFirmata 2.5.9 answers "10-bit addressing not
/// supported").
pub const I2C_10BIT_MODE: u8 = 1 << 5;
/// Bit 6 (protocol 2.5.1): auto restart — a repeated START instead of a STOP between the
/// register write and the read (`Wire.endTransmission(false)` in StandardFirmata 2.5.9).
pub const I2C_AUTO_RESTART: u8 = 1 << 6;

/// The longest read one I2C request can return: the Arduino `Wire` library's 32-byte buffer
/// (`BUFFER_LENGTH` of AVR `Wire.h`), into which StandardFirmata 2.5.9's `readAndReportData`
/// calls `Wire.requestFrom(address, numBytes)`; a longer request comes back short, with the
/// string "I2C: Too few bytes received".
pub const MAX_I2C_READ: usize = 32;

/// The longest I2C write one request carries: the board parses a sysex into a 64-byte buffer
/// (`MAX_DATA_BYTES`, StandardFirmata 2.5.9 `FirmataConstants.h`) that holds the sysex ID, the
/// two address bytes and two 7-bit bytes per data byte, and drops what does not fit:
/// 1 + 2 + 2 × 30 = 63. The whole request is then 65 bytes on the wire, just over the AVR's
/// 64-byte serial receive buffer, which the sketch empties as bytes arrive.
pub const MAX_I2C_WRITE: usize = 30;

/// The longest sysex a board parses (StandardFirmata 2.5.9 `FirmataConstants.h`,
/// `MAX_DATA_BYTES`): ID and payload together; bytes beyond it are dropped.
pub const BOARD_SYSEX_BUFFER: usize = 64;

// --- AccelStepperFirmata (ConfigurableFirmata 2.10.1 `AccelStepperFirmata.h`) ---

/// Stepper config command.
pub const ACCELSTEPPER_CONFIG: u8 = 0x00;
/// Zero the position without moving.
pub const ACCELSTEPPER_ZERO: u8 = 0x01;
/// Relative move by a number of steps.
pub const ACCELSTEPPER_STEP: u8 = 0x02;
/// Absolute move to a position.
pub const ACCELSTEPPER_TO: u8 = 0x03;
/// Enable / disable the driver outputs.
pub const ACCELSTEPPER_ENABLE: u8 = 0x04;
/// Stop; the board answers with a move-complete report.
pub const ACCELSTEPPER_STOP: u8 = 0x05;
/// Position report: the request, and the reply.
pub const ACCELSTEPPER_REPORT_POSITION: u8 = 0x06;
/// Set acceleration (custom float, steps/s²).
pub const ACCELSTEPPER_SET_ACCELERATION: u8 = 0x08;
/// Set (maximum) speed (custom float, steps/s).
pub const ACCELSTEPPER_SET_SPEED: u8 = 0x09;
/// Move complete, sent by the board. accelStepperFirmata.md 2.6.0 says 0x0b; the firmware
/// (ConfigurableFirmata 2.10.1 `AccelStepperFirmata.h`) sends 0x0a, and the document was
/// corrected to 0x0A after 2.6.0 (`firmata/protocol` commit `1192f72`).
pub const ACCELSTEPPER_MOVE_COMPLETE: u8 = 0x0A;
/// A multi-stepper group finished (sent by the board).
pub const MULTISTEPPER_MOVE_COMPLETE: u8 = 0x24;
/// The number of steppers AccelStepperFirmata drives (`MAX_ACCELSTEPPERS`).
pub const MAX_ACCELSTEPPERS: u8 = 10;
/// The largest position or step count the firmware decodes: its
/// `decode32BitSignedInteger` masks the fifth byte's bits away (`(arg5 << 28) & 0x07` is 0), so
/// only 28 bits of magnitude arrive (ConfigurableFirmata 2.10.1 `AccelStepperFirmata.cpp`).
pub const MAX_STEPPER_STEPS: i32 = (1 << 28) - 1;

/// A pin mode (protocol.md 2.6.0, "Supported Modes").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PinMode {
    /// 0x00 digital input.
    Input,
    /// 0x01 digital output.
    Output,
    /// 0x02 analog input.
    Analog,
    /// 0x03 PWM output.
    Pwm,
    /// 0x04 servo.
    Servo,
    /// 0x05 shift.
    Shift,
    /// 0x06 I2C.
    I2c,
    /// 0x07 OneWire.
    OneWire,
    /// 0x08 stepper.
    Stepper,
    /// 0x09 encoder.
    Encoder,
    /// 0x0A serial.
    Serial,
    /// 0x0B input with pull-up.
    InputPullup,
    /// Any other code (0x7F is "ignore" in ConfigurableFirmata).
    Other(u8),
}

impl PinMode {
    /// The mode from its code.
    pub fn from_code(code: u8) -> PinMode {
        match code {
            0x00 => PinMode::Input,
            0x01 => PinMode::Output,
            0x02 => PinMode::Analog,
            0x03 => PinMode::Pwm,
            0x04 => PinMode::Servo,
            0x05 => PinMode::Shift,
            0x06 => PinMode::I2c,
            0x07 => PinMode::OneWire,
            0x08 => PinMode::Stepper,
            0x09 => PinMode::Encoder,
            0x0A => PinMode::Serial,
            0x0B => PinMode::InputPullup,
            other => PinMode::Other(other),
        }
    }

    /// The code on the wire.
    pub fn code(self) -> u8 {
        match self {
            PinMode::Input => 0x00,
            PinMode::Output => 0x01,
            PinMode::Analog => 0x02,
            PinMode::Pwm => 0x03,
            PinMode::Servo => 0x04,
            PinMode::Shift => 0x05,
            PinMode::I2c => 0x06,
            PinMode::OneWire => 0x07,
            PinMode::Stepper => 0x08,
            PinMode::Encoder => 0x09,
            PinMode::Serial => 0x0A,
            PinMode::InputPullup => 0x0B,
            PinMode::Other(c) => c & 0x7F,
        }
    }
}

// --- 7-bit encodings ---

/// A 14-bit value as its two 7-bit bytes, LSB first (protocol.md 2.6.0, "Data Message
/// Expansion"). Bits above 13 are dropped.
///
/// ```
/// assert_eq!(firmata_host::protocol::to_7bit_pair(1023), [0x7F, 0x07]);
/// ```
pub fn to_7bit_pair(value: u16) -> [u8; 2] {
    [(value & 0x7F) as u8, ((value >> 7) & 0x7F) as u8]
}

/// The 14-bit value of two 7-bit bytes, LSB first (bit 7 of each is ignored).
pub fn from_7bit_pair(lsb: u8, msb: u8) -> u16 {
    u16::from(lsb & 0x7F) | (u16::from(msb & 0x7F) << 7)
}

/// The bytes of a payload sent as 7-bit pairs (I2C data, string characters): each pair's
/// value, truncated to a byte; an odd last byte is left out.
pub fn pairs(payload: &[u8]) -> impl Iterator<Item = u8> + '_ {
    payload
        .chunks_exact(2)
        .map(|p| from_7bit_pair(p[0], p[1]) as u8)
}

/// Encodes a stepper position or step count as AccelStepperFirmata's five bytes: sign and
/// magnitude, the sign in bit 3 of the fifth byte (ConfigurableFirmata 2.10.1
/// `encode32BitSignedInteger`; accelStepperFirmata.md 2.6.0 calls it "a 32-bit signed long"
/// without saying it is sign-magnitude). `None` beyond ±[`MAX_STEPPER_STEPS`], which the
/// firmware could not decode.
///
/// ```
/// use firmata_host::protocol::encode_stepper_i32;
/// assert_eq!(encode_stepper_i32(200), Some([0x48, 0x01, 0, 0, 0]));
/// assert_eq!(encode_stepper_i32(-1), Some([0x01, 0, 0, 0, 0x08]));
/// assert_eq!(encode_stepper_i32(1 << 28), None);
/// ```
pub fn encode_stepper_i32(value: i32) -> Option<[u8; 5]> {
    if !(-MAX_STEPPER_STEPS..=MAX_STEPPER_STEPS).contains(&value) {
        return None;
    }
    Some(stepper_bytes(value))
}

/// The five bytes of any `i32` as the firmware's encoder writes them (a board reports
/// positions up to 31 bits of magnitude).
fn stepper_bytes(value: i32) -> [u8; 5] {
    let m = value.unsigned_abs();
    let mut b = [0u8; 5];
    for (k, byte) in b.iter_mut().enumerate() {
        *byte = ((m >> (7 * k)) & 0x7F) as u8;
    }
    if value < 0 {
        b[4] |= 0x08;
    }
    b
}

/// Decodes a position a board reports (ConfigurableFirmata 2.10.1 `reportPosition` writes
/// `encode32BitSignedInteger`): magnitude from bits 0–30, sign from bit 3 of the fifth byte.
///
/// ```
/// use firmata_host::protocol::decode_stepper_i32;
/// assert_eq!(decode_stepper_i32([0x48, 0x01, 0, 0, 0]), 200);
/// assert_eq!(decode_stepper_i32([0x01, 0, 0, 0, 0x08]), -1);
/// ```
pub fn decode_stepper_i32(b: [u8; 5]) -> i32 {
    let m = u32::from(b[0] & 0x7F)
        | (u32::from(b[1] & 0x7F) << 7)
        | (u32::from(b[2] & 0x7F) << 14)
        | (u32::from(b[3] & 0x7F) << 21)
        | (u32::from(b[4] & 0x07) << 28);
    let m = m as i32; // at most 31 bits: never negative
    if b[4] & 0x08 != 0 { -m } else { m }
}

/// The largest significand of the custom float (23 bits).
const FLOAT_SIGNIFICAND_MAX: u32 = (1 << 23) - 1;

/// Encodes AccelStepperFirmata's custom float: a 23-bit significand, a base-10 exponent biased
/// by −11 (4 bits) and a sign. `None` for values it cannot carry (not finite, or above
/// 8 388 607 × 10⁴).
///
/// The layout is the firmware's (ConfigurableFirmata 2.10.1 `decodeCustomFloat`): significand
/// in bits 0–22, exponent in bits 23–26, sign in bit 27 — which the document's worked examples
/// follow (accelStepperFirmata.md 2.6.0: 1 step per hour is `31 45 29 05`, 100 steps/s is
/// `01 00 00 34`), while its bit table (sign in bit 21) does not. Like the examples, the
/// significand is truncated, not rounded, and written with its trailing zeros moved into the
/// exponent.
///
/// ```
/// use firmata_host::protocol::encode_custom_float;
/// assert_eq!(encode_custom_float(1.0 / 3600.0), Some([0x31, 0x45, 0x29, 0x05]));
/// assert_eq!(encode_custom_float(100.0), Some([0x01, 0x00, 0x00, 0x34]));
/// ```
pub fn encode_custom_float(value: f32) -> Option<[u8; 4]> {
    if !value.is_finite() {
        return None;
    }
    let v = f64::from(value).abs();
    let (mut significand, mut exponent) = (0u32, 0i32);
    if v > 0.0 {
        // The smallest exponent whose significand fits 23 bits: the most digits kept.
        exponent = (v / f64::from(FLOAT_SIGNIFICAND_MAX))
            .log10()
            .ceil()
            .max(-11.0) as i32;
        loop {
            if exponent > 4 {
                return None;
            }
            // A relative nudge of 1e-12 keeps 0.1 / 1e-7 (999 999.999…) from truncating a digit.
            let s = (v / 10f64.powi(exponent) * (1.0 + 1e-12)).floor();
            if s <= f64::from(FLOAT_SIGNIFICAND_MAX) {
                significand = s as u32;
                break;
            }
            exponent += 1;
        }
        while significand != 0 && significand % 10 == 0 && exponent < 4 {
            significand /= 10;
            exponent += 1;
        }
    }
    let biased = (exponent + 11) as u32; // 0 ..= 15
    let sign = u32::from(value.is_sign_negative() && significand != 0);
    let word = significand | (biased << 23) | (sign << 27);
    Some([
        (word & 0x7F) as u8,
        ((word >> 7) & 0x7F) as u8,
        ((word >> 14) & 0x7F) as u8,
        ((word >> 21) & 0x7F) as u8,
    ])
}

/// Decodes AccelStepperFirmata's custom float as the firmware does (ConfigurableFirmata
/// 2.10.1 `decodeCustomFloat`).
///
/// ```
/// use firmata_host::protocol::decode_custom_float;
/// assert_eq!(decode_custom_float([0x01, 0x00, 0x00, 0x34]), 100.0);
/// assert!((decode_custom_float([0x31, 0x45, 0x29, 0x05]) - 1.0 / 3600.0).abs() < 1e-9);
/// ```
pub fn decode_custom_float(b: [u8; 4]) -> f32 {
    let b3 = u32::from(b[3] & 0x7F);
    let significand = u32::from(b[0] & 0x7F)
        | (u32::from(b[1] & 0x7F) << 7)
        | (u32::from(b[2] & 0x7F) << 14)
        | ((b3 & 0x03) << 21);
    let exponent = ((b3 >> 2) & 0x0F) as i32 - 11;
    let magnitude = (f64::from(significand) * 10f64.powi(exponent)) as f32;
    if (b3 >> 6) & 1 != 0 {
        -magnitude
    } else {
        magnitude
    }
}

// --- host → board encoders ---

/// Protocol version request: `F9` (protocol.md 2.6.0, "Request version report").
pub fn encode_version_query(out: &mut Vec<u8>) {
    out.push(REPORT_VERSION);
}

/// A sysex with no payload: `F0 id F7` (firmware, capability and analog mapping queries).
pub fn encode_sysex_query(out: &mut Vec<u8>, id: u8) {
    out.extend_from_slice(&[START_SYSEX, id & 0x7F, END_SYSEX]);
}

/// Set pin mode: `F4 pin mode` (protocol.md 2.6.0, "Set pin mode").
pub fn encode_set_pin_mode(out: &mut Vec<u8>, pin: u8, mode: PinMode) {
    out.extend_from_slice(&[SET_PIN_MODE, pin & 0x7F, mode.code()]);
}

/// Set digital pin value: `F5 pin value` (protocol.md 2.6.0, added in 2.5).
pub fn encode_set_digital_pin_value(out: &mut Vec<u8>, pin: u8, high: bool) {
    out.extend_from_slice(&[SET_DIGITAL_PIN_VALUE, pin & 0x7F, u8::from(high)]);
}

/// Toggle analog reporting for channel 0–15: `C0|ch on` (protocol.md 2.6.0).
pub fn encode_report_analog(out: &mut Vec<u8>, channel: u8, on: bool) {
    out.extend_from_slice(&[REPORT_ANALOG | (channel & 0x0F), u8::from(on)]);
}

/// Toggle digital reporting for port 0–15 (pins 8·port … 8·port + 7): `D0|port on`.
pub fn encode_report_digital(out: &mut Vec<u8>, port: u8, on: bool) {
    out.extend_from_slice(&[REPORT_DIGITAL | (port & 0x0F), u8::from(on)]);
}

/// Sampling interval in ms: `F0 7A lsb msb F7` (protocol.md 2.6.0, "Sampling Interval").
pub fn encode_sampling_interval(out: &mut Vec<u8>, ms: u16) {
    let [l, m] = to_7bit_pair(ms);
    out.extend_from_slice(&[START_SYSEX, SAMPLING_INTERVAL, l, m, END_SYSEX]);
}

/// I2C config with a read delay in µs: `F0 78 lsb msb F7` (i2c.md 2.6.0, "I2C config").
pub fn encode_i2c_config(out: &mut Vec<u8>, delay_us: u16) {
    let [l, m] = to_7bit_pair(delay_us);
    out.extend_from_slice(&[START_SYSEX, I2C_CONFIG, l, m, END_SYSEX]);
}

/// An I2C request (i2c.md 2.6.0, "I2C read/write request"): 7-bit `address`, the mode bits
/// (`I2C_MODE_*`, optionally `| I2C_AUTO_RESTART`), then each of `words` as a 7-bit pair —
/// the bytes to write, or for a read the register (when given) and the byte count.
pub fn encode_i2c_request(out: &mut Vec<u8>, address: u8, mode: u8, words: &[u16]) {
    out.extend_from_slice(&[START_SYSEX, I2C_REQUEST, address & 0x7F, mode & 0x78]);
    for &w in words {
        out.extend_from_slice(&to_7bit_pair(w));
    }
    out.push(END_SYSEX);
}

/// An I2C write of `data` (at most [`MAX_I2C_WRITE`] bytes; the caller checks).
pub fn encode_i2c_write(out: &mut Vec<u8>, address: u8, data: &[u8]) {
    out.extend_from_slice(&[START_SYSEX, I2C_REQUEST, address & 0x7F, I2C_MODE_WRITE]);
    for &b in data {
        out.extend_from_slice(&to_7bit_pair(u16::from(b)));
    }
    out.push(END_SYSEX);
}

/// An AccelStepperFirmata message: `F0 62 command device payload… F7`.
pub fn encode_stepper(out: &mut Vec<u8>, command: u8, device: u8, payload: &[u8]) {
    out.extend_from_slice(&[
        START_SYSEX,
        ACCELSTEPPER_DATA,
        command & 0x7F,
        device & 0x7F,
    ]);
    out.extend(payload.iter().map(|b| b & 0x7F));
    out.push(END_SYSEX);
}

// --- board → host encoders (what a board sends; simulators and tests use them) ---

/// Protocol version report: `F9 major minor`.
pub fn encode_version_report(out: &mut Vec<u8>, major: u8, minor: u8) {
    out.extend_from_slice(&[REPORT_VERSION, major & 0x7F, minor & 0x7F]);
}

/// Firmware report: `F0 79 major minor name-as-14-bit-chars F7` (protocol.md 2.6.0, "Query
/// Firmware Name and Version").
pub fn encode_firmware_report(out: &mut Vec<u8>, major: u8, minor: u8, name: &str) {
    out.extend_from_slice(&[START_SYSEX, REPORT_FIRMWARE, major & 0x7F, minor & 0x7F]);
    for b in name.bytes() {
        out.extend_from_slice(&to_7bit_pair(u16::from(b)));
    }
    out.push(END_SYSEX);
}

/// A string message: `F0 71 chars-as-14-bit F7`.
pub fn encode_string(out: &mut Vec<u8>, text: &str) {
    out.extend_from_slice(&[START_SYSEX, STRING_DATA]);
    for b in text.bytes() {
        out.extend_from_slice(&to_7bit_pair(u16::from(b)));
    }
    out.push(END_SYSEX);
}

/// Analog message for channel 0–15: `E0|ch lsb msb`.
pub fn encode_analog(out: &mut Vec<u8>, channel: u8, value: u16) {
    let [l, m] = to_7bit_pair(value);
    out.extend_from_slice(&[ANALOG_MESSAGE | (channel & 0x0F), l, m]);
}

/// Digital message for port 0–15: `90|port pins0-6 pin7`.
pub fn encode_digital(out: &mut Vec<u8>, port: u8, mask: u8) {
    out.extend_from_slice(&[DIGITAL_MESSAGE | (port & 0x0F), mask & 0x7F, mask >> 7]);
}

/// I2C reply: `F0 77 address register data-as-7-bit-pairs F7` (i2c.md 2.6.0, "I2C reply").
pub fn encode_i2c_reply(out: &mut Vec<u8>, address: u8, register: u16, data: &[u8]) {
    out.extend_from_slice(&[START_SYSEX, I2C_REPLY]);
    out.extend_from_slice(&to_7bit_pair(u16::from(address)));
    out.extend_from_slice(&to_7bit_pair(register));
    for &b in data {
        out.extend_from_slice(&to_7bit_pair(u16::from(b)));
    }
    out.push(END_SYSEX);
}

/// A stepper's position report or move-complete report (`complete`), as
/// ConfigurableFirmata 2.10.1 `reportPosition` writes it.
pub fn encode_stepper_position(out: &mut Vec<u8>, device: u8, position: i32, complete: bool) {
    let command = if complete {
        ACCELSTEPPER_MOVE_COMPLETE
    } else {
        ACCELSTEPPER_REPORT_POSITION
    };
    out.extend_from_slice(&[START_SYSEX, ACCELSTEPPER_DATA, command, device & 0x7F]);
    out.extend_from_slice(&stepper_bytes(position));
    out.push(END_SYSEX);
}
