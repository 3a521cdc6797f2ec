//! Control tables as data: a model is its registers (address, width, access, range) and the
//! units that turn raw values into physical ones — in the spirit of `dynamixel2`, not a type
//! per model.
//!
//! Addresses, widths, access and initial values follow the ROBOTIS e-Manual control-table pages
//! cited on each table (checked against the pages' sources in ROBOTIS-GIT/emanual) and agree with
//! ROBOTIS' own `dynamixel_hardware_interface` model files (`param/dxl_model/*.model`). Value
//! ranges come from the e-Manual's per-register descriptions; where a page leaves a range open
//! ("-"), the register's full width is used. Indirect Address / Data blocks are omitted.

mod mx28;
mod rh_p12_rn;
mod xm430_w350;

pub use mx28::MX_28;
pub use rh_p12_rn::RH_P12_RN;
pub use xm430_w350::XM430_W350;

/// Every control table this crate knows, for identifying a servo by its model number.
pub const MODELS: [&ControlTable; 3] = [&MX_28, &XM430_W350, &RH_P12_RN];

/// Where a register lives: EEPROM (kept over power cycles, locked while torque is on) or RAM.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Area {
    /// Non-volatile; writable only while torque is disabled.
    Eeprom,
    /// Volatile; reset to defaults on reboot.
    Ram,
}

/// Access rights of a register.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Read only.
    R,
    /// Read and write.
    Rw,
}

/// A range that another register sets (checked on write, "Data Limit Error" when violated).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitBy {
    /// No run-time limit beyond the register's own range.
    None,
    /// `-limit ..= limit`, where `limit` is the register at this address.
    Symmetric(u16),
    /// `min ..= max`, read from the registers at these two addresses.
    Between {
        /// Address of the lower-limit register.
        min: u16,
        /// Address of the upper-limit register.
        max: u16,
    },
}

/// One register of a control table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Register {
    /// The e-Manual's name.
    pub name: &'static str,
    /// Byte address.
    pub address: u16,
    /// Width in bytes: 1, 2 or 4 (little-endian on the wire).
    pub width: u8,
    /// Whether the raw value is two's-complement signed.
    pub signed: bool,
    /// EEPROM or RAM.
    pub area: Area,
    /// Read-only or read-write.
    pub access: Access,
    /// Smallest value the e-Manual allows ("Data Range Error" below it).
    pub min: i32,
    /// Largest value the e-Manual allows.
    pub max: i32,
    /// Factory default (0 where the e-Manual gives "-").
    pub default: i32,
    /// A run-time limit set by other registers.
    pub limit: LimitBy,
}

impl Register {
    /// The register's value from its little-endian bytes (sign-extended when signed).
    ///
    /// ```
    /// use hand_control::control_table::MX_28;
    /// let load = MX_28.present_load;
    /// assert_eq!(load.decode(&(-250i16).to_le_bytes()), Some(-250));
    /// assert_eq!(load.decode(&[1]), None); // too short
    /// ```
    pub fn decode(&self, bytes: &[u8]) -> Option<i32> {
        let b = bytes.get(..usize::from(self.width))?;
        Some(match (self.width, self.signed) {
            (1, false) => i32::from(b[0]),
            (1, true) => i32::from(b[0] as i8),
            (2, false) => i32::from(u16::from_le_bytes([b[0], b[1]])),
            (2, true) => i32::from(i16::from_le_bytes([b[0], b[1]])),
            // 4-byte unsigned registers never exceed i32::MAX in these tables.
            _ => i32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
    }

    /// The little-endian bytes of `value`, `width` of them (the rest of the array is zero).
    pub fn encode(&self, value: i32) -> [u8; 4] {
        let mut out = value.to_le_bytes();
        out[usize::from(self.width)..].fill(0);
        out
    }

    /// Whether `value` lies within the register's own range.
    pub fn in_range(&self, value: i32) -> bool {
        (self.min..=self.max).contains(&value)
    }

    /// One past the last byte address.
    pub fn end(&self) -> u16 {
        self.address + u16::from(self.width)
    }
}

/// How a model limits its grasp effort.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EffortUnit {
    /// Goal PWM (output voltage duty) caps the torque, as the paper's torque limit did.
    Pwm,
    /// Goal Current caps the torque (current-based position control).
    Current,
}

/// A model's control table: its registers, the roles the driver needs, and unit conversions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControlTable {
    /// Model name, as ROBOTIS writes it (`MX-28(2.0)`).
    pub name: &'static str,
    /// What a scene file or a command line calls it (`mx28`, `xm430`, `rh_p12_rn`).
    pub key: &'static str,
    /// The value of the Model Number register (and of a PING reply).
    pub model_number: u16,
    /// Every register, in address order.
    pub registers: &'static [Register],
    /// Bytes the table spans (highest address + width).
    pub size: u16,
    /// Torque Enable (1 byte, 0 / 1).
    pub torque_enable: Register,
    /// Operating Mode.
    pub operating_mode: Register,
    /// The operating-mode value for position control under the effort limit.
    pub position_mode: i32,
    /// Hardware Error Status.
    pub hardware_error_status: Register,
    /// Goal Position.
    pub goal_position: Register,
    /// The register that caps the effort (Goal PWM or Goal Current).
    pub goal_effort: Register,
    /// Whether `goal_effort` is a PWM or a current.
    pub effort_unit: EffortUnit,
    /// The EEPROM limit of `goal_effort` (PWM Limit or Current Limit): effort 1.0 maps to its default.
    pub effort_limit: Register,
    /// Present Load (MX) or Present Current (X, RH-P12-RN).
    pub present_load: Register,
    /// Present Velocity.
    pub present_velocity: Register,
    /// Present Position.
    pub present_position: Register,
    /// Radians per Present / Goal Position unit.
    pub position_unit_rad: f32,
    /// Radians per second per Present Velocity unit.
    pub velocity_unit_rad_per_s: f32,
    /// Raw Present Load / Current that means full load (100 %).
    pub load_full_scale: f32,
}

impl ControlTable {
    /// The table whose model number is `model_number`, among [`MODELS`].
    ///
    /// ```
    /// use hand_control::control_table::{ControlTable, MX_28};
    /// assert_eq!(ControlTable::by_model_number(30).map(|t| t.name), Some(MX_28.name));
    /// assert!(ControlTable::by_model_number(12345).is_none());
    /// ```
    pub fn by_model_number(model_number: u16) -> Option<&'static ControlTable> {
        MODELS
            .iter()
            .copied()
            .find(|t| t.model_number == model_number)
    }

    /// The table a person names: its [`key`](Self::key) (`mx28`, `xm430`, `rh_p12_rn`, as
    /// scene files and `dxl-sim` spell it), or its name without the firmware suffix, in any
    /// case, with or without the dashes (`MX-28`, `xm430-w350`), among [`MODELS`].
    ///
    /// ```
    /// use hand_control::control_table::{ControlTable, RH_P12_RN, XM430_W350};
    /// assert_eq!(ControlTable::by_name("mx28").map(|t| t.name), Some("MX-28(2.0)"));
    /// assert_eq!(ControlTable::by_name("xm430").map(|t| t.name), Some(XM430_W350.name));
    /// assert_eq!(ControlTable::by_name("XM430-W350").map(|t| t.name), Some(XM430_W350.name));
    /// assert_eq!(ControlTable::by_name("rh_p12_rn").map(|t| t.name), Some(RH_P12_RN.name));
    /// assert!(ControlTable::by_name("ax12").is_none());
    /// ```
    pub fn by_name(name: &str) -> Option<&'static ControlTable> {
        // "MX-28(2.0)" → "mx28": the firmware suffix is not part of what people call it.
        fn plain(name: &str) -> String {
            let base = name.split('(').next().unwrap_or(name);
            base.chars()
                .filter(char::is_ascii_alphanumeric)
                .map(|c| c.to_ascii_lowercase())
                .collect()
        }
        let wanted = plain(name);
        MODELS
            .iter()
            .copied()
            .find(|t| plain(t.key) == wanted || plain(t.name) == wanted)
    }

    /// The keys of [`MODELS`], for a message that lists them (`mx28, xm430, rh_p12_rn`).
    pub fn keys() -> String {
        MODELS.iter().map(|t| t.key).collect::<Vec<_>>().join(", ")
    }

    /// The register at exactly `address`.
    pub fn register_at(&self, address: u16) -> Option<&'static Register> {
        self.registers.iter().find(|r| r.address == address)
    }

    /// The register named `name` (as the e-Manual spells it).
    pub fn register(&self, name: &str) -> Option<&'static Register> {
        self.registers.iter().find(|r| r.name == name)
    }

    /// The contiguous block `(address, length)` covering Present Load / Current, Velocity and
    /// Position: one sync read fetches a servo's whole state.
    ///
    /// ```
    /// use hand_control::control_table::{MX_28, RH_P12_RN};
    /// assert_eq!(MX_28.state_block(), (126, 10));
    /// assert_eq!(RH_P12_RN.state_block(), (611, 12));
    /// ```
    pub fn state_block(&self) -> (u16, u16) {
        let regs = [
            self.present_load,
            self.present_velocity,
            self.present_position,
        ];
        let start = regs.iter().map(|r| r.address).min().unwrap_or(0);
        let end = regs.iter().map(Register::end).max().unwrap_or(0);
        (start, end - start)
    }

    /// The raw goal-effort value for an effort fraction in `0.0..=1.0` (of the factory limit).
    ///
    /// The paper's MX-28 torque limit 0…1023 is a fraction of full output; on Protocol 2.0
    /// firmware that fraction caps Goal PWM (0…885) or Goal Current (0…Current Limit).
    ///
    /// ```
    /// use hand_control::control_table::{MX_28, XM430_W350};
    /// assert_eq!(MX_28.effort_raw(400.0 / 1023.0), 346); // paper's 400 → PWM 346 of 885
    /// assert_eq!(XM430_W350.effort_raw(1.0), 1193);
    /// ```
    pub fn effort_raw(&self, fraction: f32) -> i32 {
        let full = self.effort_limit.default as f32;
        (fraction.clamp(0.0, 1.0) * full).round() as i32
    }
}

/// Shorthand for the tables' register literals.
#[allow(clippy::too_many_arguments)]
const fn reg(
    name: &'static str,
    address: u16,
    width: u8,
    signed: bool,
    area: Area,
    access: Access,
    min: i32,
    max: i32,
    default: i32,
) -> Register {
    Register {
        name,
        address,
        width,
        signed,
        area,
        access,
        min,
        max,
        default,
        limit: LimitBy::None,
    }
}

/// A register with a run-time limit.
const fn limited(r: Register, limit: LimitBy) -> Register {
    Register { limit, ..r }
}

/// The registers' extent: highest address + width.
const fn table_size(regs: &[Register]) -> u16 {
    let mut i = 0;
    let mut end = 0;
    while i < regs.len() {
        let e = regs[i].address + regs[i].width as u16;
        if e > end {
            end = e;
        }
        i += 1;
    }
    end
}

/// Finds a register by address at compile time (the roles above point into `registers`).
const fn at(regs: &[Register], address: u16) -> Register {
    let mut i = 0;
    while i < regs.len() {
        if regs[i].address == address {
            return regs[i];
        }
        i += 1;
    }
    panic!("control table: no register at that address");
}

/// Hardware Error Status bits shared by MX (2.0), X and RH-P12-RN firmware (e-Manual,
/// "Hardware Error Status(70)").
pub mod hardware_error {
    /// Input voltage out of the Min / Max Voltage Limit range.
    pub const INPUT_VOLTAGE: u8 = 1 << 0;
    /// Internal temperature above the Temperature Limit.
    pub const OVERHEATING: u8 = 1 << 2;
    /// Motor encoder malfunction.
    pub const MOTOR_ENCODER: u8 = 1 << 3;
    /// Electrical shock on the circuit / insufficient power.
    pub const ELECTRICAL_SHOCK: u8 = 1 << 4;
    /// Persistent load beyond the maximum output.
    pub const OVERLOAD: u8 = 1 << 5;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registers_are_sorted_disjoint_and_defaults_in_range() {
        for t in MODELS {
            for w in t.registers.windows(2) {
                assert!(
                    w[0].end() <= w[1].address,
                    "{}: {} overlaps {}",
                    t.name,
                    w[0].name,
                    w[1].name
                );
            }
            for r in t.registers {
                assert!(matches!(r.width, 1 | 2 | 4), "{} {}", t.name, r.name);
                assert!(
                    r.in_range(r.default),
                    "{} {} default {}",
                    t.name,
                    r.name,
                    r.default
                );
            }
            assert_eq!(
                t.register("Model Number").map(|r| r.default),
                Some(i32::from(t.model_number))
            );
        }
    }

    #[test]
    fn decode_encode_round_trip_signed_and_unsigned() {
        let pos = MX_28.present_position;
        assert_eq!(pos.decode(&pos.encode(-4095)), Some(-4095));
        let te = MX_28.torque_enable;
        assert_eq!(te.encode(1), [1, 0, 0, 0]);
        assert_eq!(MX_28.hardware_error_status.decode(&[0xA0]), Some(0xA0));
    }
}
