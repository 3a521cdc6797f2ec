//! Checks after parsing: values in range and parts that can work together. Each error keeps
//! the span of the offending key.

use super::parts::{Fingertip, Hand, ImuPad, Locator};
use super::{Location, SceneError, SceneFile};
use std::ops::Range;
use toml::Spanned;

/// Baud rates a Dynamixel Protocol 2.0 servo accepts (ROBOTIS e-manual, Baud Rate (8)).
const DXL_BAUDS: [u32; 8] = [
    9_600, 57_600, 115_200, 1_000_000, 2_000_000, 3_000_000, 4_000_000, 4_500_000,
];

/// Where checks report: the file's name and text, so an error names line, column and key.
#[derive(Debug, Clone, Copy)]
pub struct Checker<'a> {
    file: &'a str,
    text: &'a str,
}

impl<'a> Checker<'a> {
    /// Checks of `text`, named `file` in errors.
    pub fn new(file: &'a str, text: &'a str) -> Checker<'a> {
        Checker { file, text }
    }

    /// The scene text.
    pub fn text(&self) -> &'a str {
        self.text
    }

    /// The toml parser's error `e` of the text (a second, narrower parse of the same file).
    pub fn syntax(&self, e: &toml::de::Error) -> SceneError {
        SceneError::syntax(self.file, self.text, e)
    }

    /// An error at `span` of the text: `key` (dotted) `problem`; allowed: `allowed`.
    pub fn err(
        &self,
        span: Range<usize>,
        key: &str,
        problem: impl Into<String>,
        allowed: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            file: self.file.to_owned(),
            at: Location::of(self.text, span.start),
            key: key.to_owned(),
            problem: problem.into(),
            allowed: allowed.into(),
        }
    }
}

/// Baud rates a Firmata sketch is built with: the Arduino core's standard rates
/// (StandardFirmata's is 57 600).
const FIRMATA_BAUDS: [u32; 12] = [
    9_600, 14_400, 19_200, 28_800, 38_400, 57_600, 74_880, 115_200, 230_400, 250_000, 500_000,
    1_000_000,
];

/// The pad's hardware: at most one of `i2c_bus` and `firmata_port` (a program that requires
/// real hardware checks that one is named), and `firmata_baud` only with a board, at a rate a
/// sketch runs at.
fn check_imu_pad(pad: &ImuPad, cx: &Checker<'_>) -> Result<(), SceneError> {
    if let (Some(_), Some(port)) = (&pad.i2c_bus, &pad.firmata_port) {
        return Err(cx.err(
            port.span(),
            "sensors.imu_pad.firmata_port",
            "is named beside `i2c_bus`",
            "one of `i2c_bus` (an I2C bus of this computer) or `firmata_port` (the serial port \
             of a Firmata board the chip is wired to)",
        ));
    }
    check_firmata_baud(
        "sensors.imu_pad",
        pad.firmata_port.is_some(),
        pad.firmata_baud.as_ref(),
        cx,
    )
}

/// A sensor's `firmata_baud` (in `table`): only with a board (`has_port`), at a rate a sketch
/// runs at.
fn check_firmata_baud(
    table: &str,
    has_port: bool,
    baud: Option<&Spanned<u32>>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    let Some(baud) = baud else {
        return Ok(());
    };
    let key = format!("{table}.firmata_baud");
    if !has_port {
        return Err(cx.err(
            baud.span(),
            &key,
            "is named without `firmata_port`",
            "`firmata_baud` only with the board's `firmata_port`",
        ));
    }
    if !FIRMATA_BAUDS.contains(baud.get_ref()) {
        let rates: Vec<String> = FIRMATA_BAUDS.iter().map(u32::to_string).collect();
        return Err(cx.err(
            baud.span(),
            &key,
            format!("is {}", baud.get_ref()),
            format!("a Firmata sketch's baud rate: {}", rates.join(", ")),
        ));
    }
    Ok(())
}

/// The fingertip's hardware: at most one of `i2c_buses` (three) and `firmata_port` (a program
/// that requires real hardware checks that one is named); the board's keys (`firmata_baud`,
/// `mux_address`, `mux_channels`) only with a board; the switch at a TCA9548A's address and
/// three distinct channels of its eight.
fn check_fingertip_wiring(tip: &Fingertip, cx: &Checker<'_>) -> Result<(), SceneError> {
    if let Some(buses) = &tip.i2c_buses {
        if buses.get_ref().len() != 3 {
            return Err(cx.err(
                buses.span(),
                "sensors.fingertip.i2c_buses",
                format!("names {} buses", buses.get_ref().len()),
                "three device paths, one per MS5611",
            ));
        }
        if let Some(port) = &tip.firmata_port {
            return Err(cx.err(
                port.span(),
                "sensors.fingertip.firmata_port",
                "is named beside `i2c_buses`",
                "one of `i2c_buses` (three I2C buses of this computer) or `firmata_port` (the \
                 serial port of a Firmata board the sensors are wired to, behind a TCA9548A \
                 switch)",
            ));
        }
    }
    check_fingertip_mcu(tip, cx)?;
    let has_port = tip.firmata_port.is_some();
    check_firmata_baud("sensors.fingertip", has_port, tip.firmata_baud.as_ref(), cx)?;
    if let Some(a) = &tip.mux_address {
        if !has_port {
            return Err(cx.err(
                a.span(),
                "sensors.fingertip.mux_address",
                "is named without `firmata_port`",
                "`mux_address` only with the board's `firmata_port`",
            ));
        }
        if !(0x70..=0x77).contains(a.get_ref()) {
            return Err(cx.err(
                a.span(),
                "sensors.fingertip.mux_address",
                format!("is {:#04x}", a.get_ref()),
                "0x70…0x77 (TCA9548A pins A2…A0)",
            ));
        }
    }
    if let Some(channels) = &tip.mux_channels {
        let key = "sensors.fingertip.mux_channels";
        if !has_port {
            return Err(cx.err(
                channels.span(),
                key,
                "is named without `firmata_port`",
                "`mux_channels` only with the board's `firmata_port`",
            ));
        }
        let c = channels.get_ref();
        let allowed = "three distinct switch channels 0…7, one per MS5611 (sensor 1 first)";
        if c.len() != 3 {
            return Err(cx.err(
                channels.span(),
                key,
                format!("names {} channels", c.len()),
                allowed,
            ));
        }
        if let Some(bad) = c.iter().find(|&&ch| ch > 7) {
            return Err(cx.err(
                channels.span(),
                key,
                format!("names channel {bad}"),
                allowed,
            ));
        }
        if c[0] == c[1] || c[0] == c[2] || c[1] == c[2] {
            return Err(cx.err(channels.span(), key, "names a channel twice", allowed));
        }
    }
    Ok(())
}

/// The fingertip's own microcontroller: `serial_port` alone (the chips are the board's), and
/// `baud` only with it, a rate a UART runs at.
fn check_fingertip_mcu(tip: &Fingertip, cx: &Checker<'_>) -> Result<(), SceneError> {
    if let Some(port) = &tip.serial_port {
        if tip.i2c_buses.is_some() || tip.firmata_port.is_some() {
            return Err(cx.err(
                port.span(),
                "sensors.fingertip.serial_port",
                "is named beside the chips' own wiring",
                "one of `i2c_buses`, `firmata_port` (the chips, read by this computer) or \
                 `serial_port` (the fingertip's microcontroller, which reads them)",
            ));
        }
    }
    if let Some(baud) = &tip.baud {
        if tip.serial_port.is_none() {
            return Err(cx.err(
                baud.span(),
                "sensors.fingertip.baud",
                "is named without `serial_port`",
                "`baud` only with the microcontroller's `serial_port`",
            ));
        }
        if !(1_200..=4_000_000).contains(baud.get_ref()) {
            return Err(cx.err(
                baud.span(),
                "sensors.fingertip.baud",
                format!("is {}", baud.get_ref()),
                format!(
                    "a UART's rate, 1200…4000000 baud (the fingertip firmware's is {})",
                    fingertip_link::BAUD
                ),
            ));
        }
    }
    Ok(())
}

/// Validates the parts of `scene` (sensors, estimators, controller, hand, arm): each in range,
/// and each estimator with the sensor it reads.
pub(crate) fn check_parts<X>(scene: &SceneFile<X>, cx: &Checker<'_>) -> Result<(), SceneError> {
    let s = &scene.sensors;
    // Sensors: the fingertip.
    if let Some(tip) = &s.fingertip {
        let osr = &tip.get_ref().osr;
        if baro_drivers::Osr::from_ratio(*osr.get_ref()).is_none() {
            return Err(cx.err(
                osr.span(),
                "sensors.fingertip.osr",
                format!("is {}, an OSR the MS5611 does not have", osr.get_ref()),
                "256, 512, 1024, 2048, 4096",
            ));
        }
        if let Some(a) = &tip.get_ref().address {
            if ![0x76, 0x77].contains(a.get_ref()) {
                return Err(cx.err(
                    a.span(),
                    "sensors.fingertip.address",
                    format!("is {:#04x}", a.get_ref()),
                    "0x76 or 0x77 (MS5611 CSB pin)",
                ));
            }
        }
        check_fingertip_wiring(tip.get_ref(), cx)?;
    }

    if let Some(pad) = &s.imu_pad {
        check_imu_pad(pad.get_ref(), cx)?;
    }

    // Estimators.
    let e = &scene.estimators;
    if let Some(f) = &e.force {
        if s.fingertip.is_none() {
            return Err(cx.err(
                f.span(),
                "estimators.force",
                "needs the fingertip's pressures",
                "[sensors.fingertip] with it",
            ));
        }
        let force = f.get_ref();
        if force.model.is_some() == force.weights.is_some() {
            return Err(cx.err(
                f.span(),
                "estimators.force",
                if force.model.is_some() {
                    "names both a built-in `model` and a `weights` file"
                } else {
                    "names no force DNN"
                },
                "`model = \"sim\"` or `\"table1\"` (built in), or `weights = \"FILE\"` (a \
                 weights file `handstack train force` wrote)",
            ));
        }
    }
    if let Some(c) = &e.contact {
        if let Some(w) = &c.get_ref().cnn_weights {
            if !c.get_ref().locators.get_ref().contains(&Locator::Cnn) {
                return Err(cx.err(
                    w.span(),
                    "estimators.contact.cnn_weights",
                    "names a contact CNN the scene does not run",
                    "\"cnn\" among `locators`, or no `cnn_weights`",
                ));
            }
        }
        if let Some(w) = &c.get_ref().mlp_weights {
            if !c.get_ref().locators.get_ref().contains(&Locator::Mlp) {
                return Err(cx.err(
                    w.span(),
                    "estimators.contact.mlp_weights",
                    "names a contact MLP the scene does not run",
                    "\"mlp\" among `locators`, or no `mlp_weights`",
                ));
            }
        }
        let locators = &c.get_ref().locators;
        if locators.get_ref().is_empty() {
            return Err(cx.err(
                locators.span(),
                "estimators.contact.locators",
                "is empty",
                "one or more of \"aot\", \"ranging\", \"mlp\", \"cnn\"",
            ));
        }
        for l in locators.get_ref() {
            let (needs, ok) = match l {
                Locator::Cnn => (
                    "[sensors.imu_pad] (the CNN reads ICM-20789 windows)",
                    s.imu_pad.is_some(),
                ),
                _ => (
                    "[sensors.fingertip] (it reads the three MS5611)",
                    s.fingertip.is_some(),
                ),
            };
            if !ok {
                return Err(cx.err(
                    locators.span(),
                    "estimators.contact.locators",
                    format!("names \"{}\" without its sensor", l.name()),
                    needs,
                ));
            }
        }
    }
    if let Some(u) = &s.underactuated {
        if let Err(why) = u.get_ref().calibration().check() {
            return Err(cx.err(
                u.span(),
                "sensors.underactuated",
                "states a calibration that cannot be",
                why,
            ));
        }
    }
    if let Some(soft) = &e.softness {
        if s.underactuated.is_none() {
            return Err(cx.err(
                soft.span(),
                "estimators.softness",
                "classifies grasps of the underactuated hand the scene does not have",
                "[sensors.underactuated] with it",
            ));
        }
    }

    // Controller, hand, arm.
    if let Some(c) = &scene.controller {
        let c_ref = c.get_ref();
        if c_ref.preset.get_ref() != "grasp" {
            return Err(cx.err(
                c_ref.preset.span(),
                "controller.preset",
                format!("is \"{}\"", c_ref.preset.get_ref()),
                "\"grasp\" (the Mamdani grasp controller of Kim et al. 2020, §5)",
            ));
        }
        if scene.hand.is_none() {
            return Err(cx.err(
                c.span(),
                "controller",
                "is a grasp controller without a hand",
                "[hand] with it",
            ));
        }
    }
    if let Some(h) = &scene.hand {
        check_hand(h, cx)?;
    }
    if let Some(a) = &scene.arm {
        let m = &a.get_ref().model;
        if m.get_ref() != "ur3" {
            return Err(cx.err(
                m.span(),
                "arm.model",
                format!("is \"{}\"", m.get_ref()),
                "\"ur3\" (the arm of Al & Martinez-Hernandez's tap-to-move, §IV-B)",
            ));
        }
    }

    Ok(())
}

/// `[hand]`: the keys of its model, each in range.
fn check_hand(h: &Spanned<Hand>, cx: &Checker<'_>) -> Result<(), SceneError> {
    let hr = h.get_ref();
    if hr.model.is_underactuated() {
        for (key, named) in [
            ("hand.reply_timeout_ms", hr.reply_timeout_ms.is_some()),
            ("hand.ids", hr.ids != super::parts::default_ids()),
        ] {
            if named {
                return Err(cx.err(
                    h.span(),
                    key,
                    "is a servo hand's key",
                    "no servo keys with model = \"underactuated4\"",
                ));
            }
        }
        if let Some(b) = &hr.baud {
            if !FIRMATA_BAUDS.contains(b.get_ref()) {
                let rates: Vec<String> = FIRMATA_BAUDS.iter().map(u32::to_string).collect();
                return Err(cx.err(
                    b.span(),
                    "hand.baud",
                    format!("is {}", b.get_ref()),
                    format!("a Firmata sketch's rate: {}", rates.join(", ")),
                ));
            }
        }
        if let Some(w) = &hr.wiring {
            if let Err(why) = w.get_ref().check() {
                return Err(cx.err(
                    w.span(),
                    "hand.wiring",
                    why,
                    "eight distinct channels A0…A15, stepper device 0…9, STEP ≠ DIR",
                ));
            }
        }
        if let Some(d) = &hr.drive {
            if let Err(why) = d.get_ref().check() {
                return Err(cx.err(d.span(), "hand.drive", why, "mm_per_step in (0, 10]"));
            }
        }
        return Ok(());
    }
    if let Some(key) = [
        ("hand.wiring", hr.wiring.is_some()),
        ("hand.drive", hr.drive.is_some()),
    ]
    .into_iter()
    .find_map(|(k, named)| named.then_some(k))
    {
        return Err(cx.err(
            h.span(),
            key,
            "is the underactuated hand's key",
            "model = \"underactuated4\" with it, or no such key for a servo hand",
        ));
    }
    let mut ids = hr.ids.clone();
    ids.sort_unstable();
    ids.dedup();
    if hr.ids.is_empty() || ids.len() != hr.ids.len() || ids.iter().any(|&i| i > 252) {
        return Err(cx.err(
            h.span(),
            "hand.ids",
            format!(
                "is [{}]",
                hr.ids
                    .iter()
                    .map(u8::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            "one or more distinct IDs 0…252",
        ));
    }
    if let Some(b) = &hr.baud {
        if !DXL_BAUDS.contains(b.get_ref()) {
            return Err(cx.err(
                b.span(),
                "hand.baud",
                format!("is {}", b.get_ref()),
                "9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000, 4500000",
            ));
        }
    }
    Ok(())
}
