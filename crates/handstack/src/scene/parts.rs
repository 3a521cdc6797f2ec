//! The parts a scene file names: sensors, estimators, controller, hand and arm. A device is
//! real when the scene names its hardware (`i2c_buses`, `i2c_bus`, `firmata_port`,
//! `serial_port`, `host`);
//! a program that simulates devices (the papers' `paper-scenes`) simulates the others, and the
//! `handstack` binary refuses them.

use hand_control::control_table::ControlTable;
use hand_control::grasp_loop::EndAction;
use imu_icm20789::BaroMode;
use serde::Deserialize;
use toml::Spanned;
use underactuated_hand::calibration::{Calibration, FsrLaw, PotMount};
use underactuated_hand::{Drive, Wiring};

/// `[sensors]`: the tactile sensors of the stack.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sensors {
    /// `[sensors.fingertip]`: three MS5611 under the silicone pad (Kim et al. 2020, §2.1).
    pub fingertip: Option<Spanned<Fingertip>>,
    /// `[sensors.imu_pad]`: the ICM-20789 under Ecoflex (Al & Martinez-Hernandez, §III-A–B).
    pub imu_pad: Option<Spanned<ImuPad>>,
    /// `[sensors.underactuated]`: FSR + distal potentiometer per finger (the underactuated-hand
    /// softness paper ("Distinguish the Textures of Grasped Objects…"), §2.2–2.3).
    pub underactuated: Option<Spanned<Underactuated>>,
}

impl Sensors {
    /// Whether the fingertip is read from real chips (it names `i2c_buses`, `firmata_port` or
    /// `serial_port`).
    pub fn real_fingertip(&self) -> bool {
        self.fingertip
            .as_ref()
            .is_some_and(|t| t.get_ref().is_real())
    }
}

/// The barometric fingertip's three MS5611.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fingertip {
    /// Oversampling ratio: 256, 512, 1024, 2048 or 4096 (the speed / noise knob).
    pub osr: Spanned<u16>,
    /// Real chips on the host: one Linux I2C bus per sensor (the MS5611 has two addresses, so
    /// three sensors on one bus need a switch), e.g. `["/dev/i2c-1", "/dev/i2c-3",
    /// "/dev/i2c-4"]`. A scene names this or `firmata_port`; neither: a simulated fingertip
    /// (in a program that simulates one).
    pub i2c_buses: Option<Spanned<Vec<String>>>,
    /// The MS5611's I2C address on each bus or switch channel: 0x76 (CSB high) or 0x77 (CSB
    /// low, default).
    pub address: Option<Spanned<u8>>,
    /// Real chips on an Arduino's I2C: the serial port of the board, which runs
    /// StandardFirmata or ConfigurableFirmata (e.g. `/dev/ttyACM0`); the three sensors sit
    /// behind a TCA9548A I2C switch on its SDA / SCL (`mux_address`, `mux_channels`).
    pub firmata_port: Option<Spanned<String>>,
    /// The Firmata sketch's baud rate (default [`FIRMATA_BAUD`], StandardFirmata's);
    /// only with `firmata_port`.
    pub firmata_baud: Option<Spanned<u32>>,
    /// The TCA9548A's address, 0x70…0x77 (default [`MUX_ADDRESS`], A2…A0 low); only with
    /// `firmata_port`.
    pub mux_address: Option<Spanned<u8>>,
    /// The switch channel of sensors 1, 2 and 3, each 0…7 (default [`MUX_CHANNELS`]); only
    /// with `firmata_port`.
    pub mux_channels: Option<Spanned<Vec<u8>>>,
    /// The fingertip's own microcontroller, on this serial port (e.g. `/dev/ttyUSB0`): the
    /// fingertip firmware reads the three MS5611 and estimates force and contact on the board,
    /// sending one `fingertip-link` frame per cycle. `osr` is then the firmware's, which the
    /// host cannot change.
    pub serial_port: Option<Spanned<String>>,
    /// The serial port's baud rate (default [`fingertip_link::BAUD`], the firmware's); only
    /// with `serial_port`.
    pub baud: Option<Spanned<u32>>,
}

/// The TCA9548A's address with A2…A0 low, the default of `mux_address`.
pub const MUX_ADDRESS: u8 = 0x70;
/// The switch channels of sensors 1, 2 and 3, the default of `mux_channels`.
pub const MUX_CHANNELS: [u8; 3] = [0, 1, 2];

/// Where a real fingertip's three MS5611 are wired, as its scene names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FingertipWiring<'a> {
    /// One I2C bus of the host per sensor (`i2c_buses`).
    I2c {
        /// The buses' device paths, sensor 1 first.
        buses: &'a [String],
    },
    /// Behind a TCA9548A switch on the I2C of a Firmata board (`firmata_port`,
    /// `firmata_baud`, `mux_address`, `mux_channels`).
    Firmata {
        /// The board's serial port.
        port: &'a str,
        /// Its baud rate.
        baud: u32,
        /// The switch's I2C address.
        mux_address: u8,
        /// The switch channel of each sensor, sensor 1 first.
        mux_channels: &'a [u8],
    },
    /// The fingertip's own microcontroller on a serial port (`serial_port`, `baud`).
    Mcu {
        /// The serial port.
        port: &'a str,
        /// Its baud rate.
        baud: u32,
    },
}

impl Fingertip {
    /// Where the chips are wired: its `i2c_buses`, else its `firmata_port` (with the
    /// switch's defaults for keys it leaves out), else its microcontroller's `serial_port`;
    /// `None` when the scene names none (a simulated fingertip, in a program that simulates
    /// one).
    ///
    /// ```
    /// use handstack::scene::NodeScene;
    /// use handstack::scene::parts::FingertipWiring;
    ///
    /// let text = "title = \"tip\"\n[sensors.fingertip]\nosr = 1024\n\
    ///             firmata_port = \"/dev/ttyACM0\"\n";
    /// let scene = NodeScene::parse("tip.toml", text)?;
    /// let tip = scene.file.sensors.fingertip.as_ref().map(|t| t.get_ref());
    /// let wiring = tip.and_then(|t| t.wiring());
    /// assert_eq!(
    ///     wiring,
    ///     Some(FingertipWiring::Firmata {
    ///         port: "/dev/ttyACM0",
    ///         baud: 57_600,
    ///         mux_address: 0x70,
    ///         mux_channels: &[0, 1, 2],
    ///     })
    /// );
    /// # Ok::<(), handstack::scene::SceneError>(())
    /// ```
    pub fn wiring(&self) -> Option<FingertipWiring<'_>> {
        if let Some(buses) = &self.i2c_buses {
            return Some(FingertipWiring::I2c {
                buses: buses.get_ref(),
            });
        }
        if let Some(port) = &self.serial_port {
            return Some(FingertipWiring::Mcu {
                port: port.get_ref(),
                baud: self
                    .baud
                    .as_ref()
                    .map_or(fingertip_link::BAUD, |b| *b.get_ref()),
            });
        }
        self.firmata_port
            .as_ref()
            .map(|port| FingertipWiring::Firmata {
                port: port.get_ref(),
                baud: baud_or_default(self.firmata_baud.as_ref()),
                mux_address: self
                    .mux_address
                    .as_ref()
                    .map_or(MUX_ADDRESS, |a| *a.get_ref()),
                mux_channels: self
                    .mux_channels
                    .as_ref()
                    .map_or(&MUX_CHANNELS[..], |c| c.get_ref()),
            })
    }

    /// Whether the fingertip is read from real chips (it names `i2c_buses`, `firmata_port` or
    /// `serial_port`).
    pub fn is_real(&self) -> bool {
        self.wiring().is_some()
    }
}

/// The ICM-20789 pad.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImuPad {
    /// Barometer mode: `LowPower`, `Normal`, `LowNoise` (the paper's, the default) or
    /// `UltraLowNoise`.
    #[serde(default = "low_noise")]
    pub pressure_mode: BaroMode,
    /// Real chip on the host: the Linux I2C bus (accel / gyro at 0x68, barometer at 0x63).
    pub i2c_bus: Option<Spanned<String>>,
    /// Real chip on an Arduino's I2C: the serial port of the board, which runs StandardFirmata
    /// or ConfigurableFirmata (e.g. `/dev/ttyACM0`). A scene names this or `i2c_bus`.
    pub firmata_port: Option<Spanned<String>>,
    /// The Firmata sketch's baud rate (default [`FIRMATA_BAUD`], StandardFirmata's);
    /// only with `firmata_port`.
    pub firmata_baud: Option<Spanned<u32>>,
}

/// StandardFirmata's baud rate, the default of `firmata_baud`.
pub const FIRMATA_BAUD: u32 = 57_600;

/// A scene's `firmata_baud`, else [`FIRMATA_BAUD`].
fn baud_or_default(baud: Option<&Spanned<u32>>) -> u32 {
    baud.map_or(FIRMATA_BAUD, |b| *b.get_ref())
}

/// Where a real pad's chip is wired, as its scene names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PadWiring<'a> {
    /// On an I2C bus of the host (`i2c_bus`).
    I2c {
        /// The bus's device path.
        bus: &'a str,
    },
    /// On the I2C of a Firmata board (`firmata_port`, `firmata_baud`).
    Firmata {
        /// The board's serial port.
        port: &'a str,
        /// Its baud rate.
        baud: u32,
    },
}

impl PadWiring<'_> {
    /// The bus or port, as errors name it.
    pub fn path(&self) -> &str {
        match self {
            PadWiring::I2c { bus } => bus,
            PadWiring::Firmata { port, .. } => port,
        }
    }
}

impl ImuPad {
    /// Where the chip is wired: its `i2c_bus`, else its `firmata_port`; `None` when the scene
    /// names neither (a simulated pad, in a program that simulates one).
    ///
    /// ```
    /// use handstack::scene::NodeScene;
    /// use handstack::scene::parts::PadWiring;
    ///
    /// let text = "title = \"pad\"\n[sensors.imu_pad]\nfirmata_port = \"/dev/ttyACM0\"\n";
    /// let scene = NodeScene::parse("pad.toml", text)?;
    /// let pad = scene.file.sensors.imu_pad.as_ref().map(|p| p.get_ref());
    /// let wiring = pad.and_then(|p| p.wiring());
    /// assert_eq!(wiring, Some(PadWiring::Firmata { port: "/dev/ttyACM0", baud: 57_600 }));
    /// # Ok::<(), handstack::scene::SceneError>(())
    /// ```
    pub fn wiring(&self) -> Option<PadWiring<'_>> {
        if let Some(bus) = &self.i2c_bus {
            return Some(PadWiring::I2c { bus: bus.get_ref() });
        }
        self.firmata_port.as_ref().map(|port| PadWiring::Firmata {
            port: port.get_ref(),
            baud: baud_or_default(self.firmata_baud.as_ref()),
        })
    }

    /// Whether the pad is read from a real chip (it names `i2c_bus` or `firmata_port`).
    pub fn is_real(&self) -> bool {
        self.wiring().is_some()
    }
}

fn low_noise() -> BaroMode {
    BaroMode::LowNoise
}

/// The underactuated hand's FSRs and potentiometers: their calibration from ADC counts to
/// newtons and degrees (the underactuated-hand softness paper, §3.1, calibrates both; its laws
/// are not published, so the defaults are underactuated-hand's stated model of the SF10-60 strip
/// and a 270° potentiometer on a 5 V, 10-bit ADC). Real when the scene's `[hand]` is an
/// `underactuated4` on a `serial_port`: the sensors are read through that hand's board.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Underactuated {
    /// The ADC's reference and the dividers' supply, V (default 5).
    #[serde(default = "five_volts")]
    pub vref_v: f64,
    /// The FSR divider and law, fingers 1–4 (`{ r_1kgf_ohm, exponent, divider_ohm,
    /// min_force_n, max_force_n }`, each defaulted).
    #[serde(default)]
    pub fsr: FsrLaw,
    /// Each finger's potentiometer mounting (`[{ travel_deg, zero_deg }, …]`, four).
    #[serde(default)]
    pub pot: [PotMount; 4],
}

impl Default for Underactuated {
    fn default() -> Underactuated {
        let c = Calibration::default();
        Underactuated {
            vref_v: c.vref_v,
            fsr: c.fsr,
            pot: c.pot,
        }
    }
}

impl Underactuated {
    /// The calibration it states.
    pub fn calibration(&self) -> Calibration {
        Calibration {
            vref_v: self.vref_v,
            fsr: self.fsr,
            pot: self.pot,
        }
    }
}

fn five_volts() -> f64 {
    Calibration::default().vref_v
}

/// `[estimators]`: what turns readings into force, contact and softness.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Estimators {
    /// `[estimators.force]`: the force / weight DNN (Kim et al. 2020, §2.2).
    pub force: Option<Spanned<Force>>,
    /// `[estimators.contact]`: contact locators.
    pub contact: Option<Spanned<Contact>>,
    /// `[estimators.softness]`: the softness classifier (the underactuated-hand softness paper,
    /// §3.3).
    pub softness: Option<Spanned<Softness>>,
}

/// Which committed force DNN: the models built into tactile-nets, named in a scene file as
/// `sim` or `table1`.
pub use tactile_nets::pretrained::ForceModel;

/// `model = "…"`: one of [`ForceModel::ALL`] by its name.
fn force_model<'de, D: serde::Deserializer<'de>>(d: D) -> Result<ForceModel, D::Error> {
    let name = String::deserialize(d)?;
    ForceModel::from_name(&name).ok_or_else(|| {
        let names: Vec<String> = ForceModel::ALL
            .iter()
            .map(|m| format!("`{}`", m.name()))
            .collect();
        serde::de::Error::custom(format!(
            "unknown variant `{name}`, expected {}",
            names.join(" or ")
        ))
    })
}

/// The force / weight DNN: a built-in model, or the user's own weights file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Force {
    /// A model built into tactile-nets (`sim` or `table1`).
    #[serde(default, deserialize_with = "some_force_model")]
    pub model: Option<ForceModel>,
    /// A weights file, relative to the scene file's directory: the user's own fingertip's model
    /// as `handstack train force` writes it.
    pub weights: Option<Spanned<std::path::PathBuf>>,
}

fn some_force_model<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Option<ForceModel>, D::Error> {
    force_model(d).map(Some)
}

/// A contact locator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Locator {
    /// Arrival-of-Time (Kim et al. 2020, §3, eq. 3), on the 3 × 3 grid (fingertip).
    Aot,
    /// Arrival-of-Time ranging scorer (aot-locate), 3 × 3 (fingertip).
    Ranging,
    /// The contact-area MLP, 4 × 6 (fingertip; Kim et al. 2020, §4).
    Mlp,
    /// The contact CNN, 9 regions (ICM-20789 pad; Al & Martinez-Hernandez, §IV-A).
    Cnn,
}

impl Locator {
    /// Its name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Locator::Aot => "aot",
            Locator::Ranging => "ranging",
            Locator::Mlp => "mlp",
            Locator::Cnn => "cnn",
        }
    }
}

/// The contact locators the stack runs.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// One or more of `aot`, `ranging`, `mlp`, `cnn`.
    pub locators: Spanned<Vec<Locator>>,
    /// The contact CNN's weights file, relative to the scene file's directory: the user's own
    /// pad's model as `handstack train contact-cnn` writes it (without it: the built-in paper
    /// variant).
    pub cnn_weights: Option<Spanned<std::path::PathBuf>>,
    /// The contact MLP's weights file, relative to the scene file's directory: the user's own
    /// fingertip's model as `handstack train contact-mlp` writes it, run on the host over the
    /// frames of the fingertip's microcontroller (without it: the model built into the
    /// fingertip's firmware).
    pub mlp_weights: Option<Spanned<std::path::PathBuf>>,
}

/// The softness classifier.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Softness {
    /// The softness net's weights file, relative to the scene file's directory: the user's
    /// own hand's net as `handstack train softness` writes it (without it: the built-in one).
    pub weights: Option<Spanned<std::path::PathBuf>>,
}

/// `[controller]`: the grasp policy.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Controller {
    /// `grasp`: the Mamdani preset of Kim et al. 2020, §5 (9 MFs NH…PH, 9 × 9 rules, Wang's
    /// center average defuzzifier, as in the paper).
    pub preset: Spanned<String>,
}

/// A hand model: one of hand-control's servo control tables, named by its key (`mx28`,
/// `xm430`, `rh_p12_rn`: the names `dxl-sim --servo` takes too), or the underactuated
/// four-finger hand on an Arduino (`underactuated4`, underactuated-hand).
#[derive(Debug, Clone, Copy)]
pub struct HandModel(Kind);

#[derive(Debug, Clone, Copy)]
enum Kind {
    Servo(&'static ControlTable),
    Underactuated4,
}

impl HandModel {
    /// Two ROBOTIS MX-28 (Protocol 2.0 firmware), the grasping paper's hand.
    pub const MX28: HandModel = HandModel(Kind::Servo(&hand_control::control_table::MX_28));
    /// The tendon-driven underactuated four-finger hand of the softness paper: one stepper, an
    /// FSR and a distal potentiometer per finger, on an Arduino over Firmata.
    pub const UNDERACTUATED4: HandModel = HandModel(Kind::Underactuated4);
    /// Its name in a scene file.
    pub const UNDERACTUATED4_NAME: &'static str = "underactuated4";

    /// The servos' control table (`None` for the underactuated hand, which has no servos).
    pub fn table(self) -> Option<&'static ControlTable> {
        match self.0 {
            Kind::Servo(t) => Some(t),
            Kind::Underactuated4 => None,
        }
    }

    /// Whether it is the underactuated hand on a Firmata board.
    pub fn is_underactuated(self) -> bool {
        matches!(self.0, Kind::Underactuated4)
    }

    /// Its name in a scene file.
    pub fn name(self) -> &'static str {
        match self.0 {
            Kind::Servo(t) => t.key,
            Kind::Underactuated4 => Self::UNDERACTUATED4_NAME,
        }
    }
}

impl PartialEq for HandModel {
    fn eq(&self, other: &HandModel) -> bool {
        match (self.0, other.0) {
            (Kind::Servo(a), Kind::Servo(b)) => a.model_number == b.model_number,
            (Kind::Underactuated4, Kind::Underactuated4) => true,
            _ => false,
        }
    }
}

impl Eq for HandModel {}

impl<'de> Deserialize<'de> for HandModel {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<HandModel, D::Error> {
        let name = String::deserialize(d)?;
        if name == Self::UNDERACTUATED4_NAME {
            return Ok(Self::UNDERACTUATED4);
        }
        ControlTable::by_name(&name)
            .map(|t| HandModel(Kind::Servo(t)))
            .ok_or_else(|| {
                serde::de::Error::custom(format!(
                    "unknown model `{name}`, expected one of {}, {}",
                    ControlTable::keys(),
                    Self::UNDERACTUATED4_NAME
                ))
            })
    }
}

/// `on_end = "…"`: one of [`EndAction::ALL`] by its name.
fn end_action<'de, D: serde::Deserializer<'de>>(d: D) -> Result<EndAction, D::Error> {
    let name = String::deserialize(d)?;
    EndAction::from_name(&name).ok_or_else(|| {
        let names: Vec<String> = EndAction::ALL
            .iter()
            .map(|a| format!("`{}`", a.name()))
            .collect();
        serde::de::Error::custom(format!(
            "unknown variant `{name}`, expected {}",
            names.join(", ")
        ))
    })
}

/// `[hand]`: a Dynamixel servo hand, or the underactuated hand on an Arduino.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hand {
    /// `mx28`, `xm430` or `rh_p12_rn` (the servos on the bus must be this model), or
    /// `underactuated4` (an Arduino running ConfigurableFirmata with AccelStepperFirmata).
    pub model: HandModel,
    /// Servo IDs on the bus (default `[1, 2]`; servo hands).
    #[serde(default = "default_ids")]
    pub ids: Vec<u8>,
    /// Real bus: the serial port of the RS-485 adapter. Absent: a simulated hand.
    pub serial_port: Option<Spanned<String>>,
    /// Baud rate (default: 1 000 000 for servos, the grasping paper's; 57 600 for a Firmata
    /// board, StandardFirmata's and ConfigurableFirmata's).
    pub baud: Option<Spanned<u32>>,
    /// How long to wait for a status packet, ms (default: the servo's 34 ms; USB adapters or
    /// a simulator on a loaded machine may need more).
    pub reply_timeout_ms: Option<u64>,
    /// What the hand is left doing when a run ends, however it ends: `release` (the default:
    /// open to where the run found it, then torque off), `hold` (keep the grip, torque on) or
    /// `torque_off` (at once).
    #[serde(default, deserialize_with = "end_action")]
    pub on_end: EndAction,
    /// The underactuated hand's wiring on its board (default: A0–A3 FSRs, A4–A7
    /// potentiometers, stepper device 0 on STEP D2 / DIR D3).
    pub wiring: Option<Spanned<Wiring>>,
    /// The underactuated hand's steps to tendon (default `{ mm_per_step = 0.01 }`).
    pub drive: Option<Spanned<Drive>>,
}

/// The servo IDs a `[hand]` without `ids` has.
pub(crate) fn default_ids() -> Vec<u8> {
    vec![1, 2]
}

/// `[arm]`: the Universal Robots arm.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arm {
    /// `ur3` (the arm of Al & Martinez-Hernandez, §III-C and §IV-B).
    pub model: Spanned<String>,
    /// The controller's host name or address. Absent: a simulated arm.
    pub host: Option<Spanned<String>>,
}
