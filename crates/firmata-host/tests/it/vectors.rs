//! Byte-level vectors, each from the document or source named beside it.

use firmata_host::PinMode;
use firmata_host::parser::{Event, parse_stream};
use firmata_host::protocol::*;

fn bytes(f: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut out = Vec::new();
    f(&mut out);
    out
}

fn events(stream: &[u8]) -> Vec<String> {
    let mut out = Vec::new();
    parse_stream(stream, |r| out.push(format!("{r:?}")));
    out
}

/// protocol.md 2.6.0, "Message Types" and "Control Messages Expansion".
#[test]
fn core_messages_host_to_board() {
    assert_eq!(bytes(encode_version_query), [0xF9]);
    assert_eq!(
        bytes(|o| encode_sysex_query(o, REPORT_FIRMWARE)),
        [0xF0, 0x79, 0xF7]
    );
    assert_eq!(
        bytes(|o| encode_sysex_query(o, CAPABILITY_QUERY)),
        [0xF0, 0x6B, 0xF7]
    );
    assert_eq!(
        bytes(|o| encode_sysex_query(o, ANALOG_MAPPING_QUERY)),
        [0xF0, 0x69, 0xF7]
    );
    // Set pin mode: 0xF4, pin, mode (INPUT/OUTPUT/ANALOG/PWM/SERVO/I2C/… = 0/1/2/3/4/6/…).
    assert_eq!(
        bytes(|o| encode_set_pin_mode(o, 13, PinMode::Output)),
        [0xF4, 13, 1]
    );
    assert_eq!(
        bytes(|o| encode_set_pin_mode(o, 18, PinMode::I2c)),
        [0xF4, 18, 6]
    );
    assert_eq!(
        bytes(|o| encode_set_pin_mode(o, 2, PinMode::InputPullup)),
        [0xF4, 2, 0x0B]
    );
    // Set digital pin value (2.5): 0xF5, pin, value.
    assert_eq!(
        bytes(|o| encode_set_digital_pin_value(o, 13, true)),
        [0xF5, 13, 1]
    );
    // Toggle analogIn reporting: 0xC0-0xCF, enable; digital port: 0xD0-0xDF ("0xD1 is port 1").
    assert_eq!(bytes(|o| encode_report_analog(o, 2, true)), [0xC2, 1]);
    assert_eq!(bytes(|o| encode_report_digital(o, 1, true)), [0xD1, 1]);
    assert_eq!(bytes(|o| encode_report_digital(o, 1, false)), [0xD1, 0]);
    // Sampling interval: F0 7A LSB MSB F7; the default 19 ms.
    assert_eq!(
        bytes(|o| encode_sampling_interval(o, 19)),
        [0xF0, 0x7A, 19, 0, 0xF7]
    );
    assert_eq!(
        bytes(|o| encode_sampling_interval(o, 1000)),
        [0xF0, 0x7A, 0x68, 0x07, 0xF7]
    );
    assert_eq!(SYSTEM_RESET, 0xFF);
}

/// protocol.md 2.6.0, "Data Message Expansion" and "Query Firmware Name and Version".
#[test]
fn core_messages_board_to_host() {
    // Analog 14-bit: E0|pin, LSB, MSB. "0x92 is the third port, port 2".
    assert_eq!(
        events(&[0xE0, 0x7F, 0x07]),
        ["Ok(Analog { channel: 0, value: 1023 })"]
    );
    assert_eq!(
        events(&[0x92, 0x05, 0x01]),
        ["Ok(Digital { port: 2, mask: 133 })"]
    );
    assert_eq!(
        events(&[0xF9, 0x02, 0x06]),
        ["Ok(Version { major: 2, minor: 6 })"]
    );
    // Firmware: major, minor, then each character as LSB, MSB.
    let fw = bytes(|o| encode_firmware_report(o, 2, 5, "StandardFirmata"));
    assert_eq!(&fw[..6], [0xF0, 0x79, 2, 5, b'S', 0]);
    assert_eq!(fw.len(), 4 + 2 * 15 + 1);
    let mut name = String::new();
    parse_stream(&fw, |r| {
        if let Ok(Event::Firmware {
            major: 2,
            minor: 5,
            name: n,
        }) = r
        {
            name = pairs(n).map(char::from).collect();
        }
    });
    assert_eq!(name, "StandardFirmata");
    assert_eq!(bytes(|o| encode_version_report(o, 2, 5)), [0xF9, 2, 5]);
    assert_eq!(bytes(|o| encode_digital(o, 1, 0x85)), [0x91, 0x05, 0x01]);
}

/// protocol.md 2.6.0, "Capability Query" / "Analog Mapping Query" response layouts, with an Uno
/// pin 14 (A0) as StandardFirmata 2.5.9 lists it: INPUT 1, PULLUP 1, OUTPUT 1, ANALOG 10, SERVO 14.
#[test]
fn capability_and_mapping_responses() {
    let response = [
        0xF0, 0x6C, 0x7F, 0x7F, 0x00, 0x01, 0x0B, 0x01, 0x01, 0x01, 0x02, 0x0A, 0x04, 0x0E, 0x7F,
        0xF7,
    ];
    let mut pins = Vec::new();
    parse_stream(&response, |r| {
        if let Ok(Event::Capabilities(p)) = r {
            pins = firmata_host::parse_capabilities(p);
        }
    });
    assert_eq!(pins.len(), 3);
    assert_eq!(pins[2].resolution(PinMode::Analog), Some(10));
    assert_eq!(pins[2].resolution(PinMode::Servo), Some(14));
    assert_eq!(pins[2].resolution(PinMode::InputPullup), Some(1));
    assert_eq!(
        events(&[0xF0, 0x6A, 0x7F, 0x7F, 0x00, 0x01, 0xF7]),
        ["Ok(AnalogMapping([127, 127, 0, 1]))"]
    );
}

/// i2c.md 2.6.0: request, reply and config layouts; mode bits of byte 3.
#[test]
fn i2c_messages() {
    // Read once, 7-bit address 0x77, register 0xA2, 2 bytes; auto-restart bit 6 (2.5.1).
    let read =
        bytes(|o| encode_i2c_request(o, 0x77, I2C_MODE_READ_ONCE | I2C_AUTO_RESTART, &[0xA2, 2]));
    assert_eq!(
        read,
        [0xF0, 0x76, 0x77, 0b0100_1000, 0x22, 0x01, 0x02, 0x00, 0xF7]
    );
    // Write 0x1E (MS5611 reset): data as LSB / MSB.
    assert_eq!(
        bytes(|o| encode_i2c_write(o, 0x77, &[0x1E])),
        [0xF0, 0x76, 0x77, 0x00, 0x1E, 0x00, 0xF7]
    );
    assert_eq!(
        bytes(|o| encode_i2c_write(o, 0x70, &[0x80])),
        [0xF0, 0x76, 0x70, 0x00, 0x00, 0x01, 0xF7]
    );
    // Read continuously, stop reading: bits 4-3 = 10, 11.
    assert_eq!(I2C_MODE_READ_CONTINUOUSLY, 0b0001_0000);
    assert_eq!(I2C_MODE_STOP_READING, 0b0001_1000);
    assert_eq!(I2C_10BIT_MODE, 0b0010_0000);
    // Config: delay µs LSB MSB.
    assert_eq!(
        bytes(|o| encode_i2c_config(o, 200)),
        [0xF0, 0x78, 0x48, 0x01, 0xF7]
    );
    // Reply: address, register, data as pairs.
    let reply = bytes(|o| encode_i2c_reply(o, 0x77, 0xA2, &[0x9C, 0xBF]));
    assert_eq!(
        reply,
        [
            0xF0, 0x77, 0x77, 0x00, 0x22, 0x01, 0x1C, 0x01, 0x3F, 0x01, 0xF7
        ]
    );
    let mut got = Vec::new();
    parse_stream(&reply, |r| {
        if let Ok(Event::I2cReply {
            address,
            register,
            data,
        }) = r
        {
            got.push((address, register, pairs(data).collect::<Vec<_>>()));
        }
    });
    assert_eq!(got, [(0x77, 0xA2, vec![0x9C, 0xBF])]);
    assert_eq!(
        (MAX_I2C_READ, MAX_I2C_WRITE, BOARD_SYSEX_BUFFER),
        (32, 30, 64)
    );
}

/// accelStepperFirmata.md 2.6.0 and ConfigurableFirmata 2.10.1 `AccelStepperFirmata.cpp`.
#[test]
fn accel_stepper_messages() {
    // The document's custom-float examples, both ways.
    assert_eq!(
        encode_custom_float(1.0 / 3600.0),
        Some([0x31, 0x45, 0x29, 0x05])
    );
    assert_eq!(encode_custom_float(100.0), Some([0x01, 0x00, 0x00, 0x34]));
    assert!((decode_custom_float([0x31, 0x45, 0x29, 0x05]) - 2.777777e-4).abs() < 1e-10);
    assert_eq!(decode_custom_float([0x01, 0x00, 0x00, 0x34]), 100.0);
    // Sign in bit 6 of the fourth byte (the firmware's `(l4 >> 6) & 0x01`).
    assert_eq!(encode_custom_float(-100.0), Some([0x01, 0x00, 0x00, 0x74]));
    assert_eq!(encode_custom_float(0.0), Some([0, 0, 0, 11 << 2]));
    assert_eq!(encode_custom_float(1e12), None);
    // Stepper to 2000: F0 62 03 dev pos×5 F7, sign-magnitude.
    let to = bytes(|o| encode_stepper(o, ACCELSTEPPER_TO, 0, &encode_stepper_i32(2000).unwrap()));
    assert_eq!(
        to,
        [0xF0, 0x62, 0x03, 0x00, 0x50, 0x0F, 0x00, 0x00, 0x00, 0xF7]
    );
    assert_eq!(
        encode_stepper_i32(-2000),
        Some([0x50, 0x0F, 0x00, 0x00, 0x08])
    );
    // Move complete is 0x0A (the firmware; the 2.6.0 document's 0x0b was corrected later).
    let done = bytes(|o| encode_stepper_position(o, 1, -2000, true));
    assert_eq!(
        done,
        [0xF0, 0x62, 0x0A, 0x01, 0x50, 0x0F, 0x00, 0x00, 0x08, 0xF7]
    );
    assert_eq!(
        events(&done),
        ["Ok(StepperMoveComplete { device: 1, position: -2000 })"]
    );
    let report = bytes(|o| encode_stepper_position(o, 0, 123_456_789, false));
    assert_eq!(
        events(&report),
        ["Ok(StepperPosition { device: 0, position: 123456789 })"]
    );
    // Config of a step + direction driver on pins 2, 3: interface 001 000 0, pins, invert.
    assert_eq!(
        firmata_host::StepperConfig::driver(2, 3).interface_byte(),
        0x10
    );
}
