//! ROBOTIS RH-P12-RN gripper (original firmware, DYNAMIXEL-PRO-style table) — the gripper the
//! grasping paper used to press its test contacts (§3, Figure 9).
//!
//! Source: ROBOTIS e-Manual, "RH-P12-RN" control table,
//! <https://emanual.robotis.com/docs/en/platform/rh_p12_rn/#control-table> (source
//! `docs/en/platform/rh_p12_rn/rh_p12_rn.md` of ROBOTIS-GIT/emanual; EEPROM 0–48, RAM
//! 562–892; Current Limit 820 × 4.02 mA; position 0 = open … 1150 = closed; velocity 0.114
//! rev/min). The newer RH-P12-RN(A) firmware (model 35074) uses a different, X-like layout and is
//! not this table. Ranges the page leaves open ("-") are given the register's full width here.

use super::{
    Access::*, Area::*, ControlTable, EffortUnit, LimitBy, Register, at, limited, reg, table_size,
};

const R_MIN: i32 = i32::MIN;
const R_MAX: i32 = i32::MAX;

/// The RH-P12-RN registers (Indirect Address / Data omitted), in address order.
pub(super) const REGISTERS: &[Register] = &[
    reg("Model Number", 0, 2, false, Eeprom, R, 0, 65535, 35073),
    reg("Model Information", 2, 4, false, Eeprom, R, 0, R_MAX, 0),
    reg("Firmware Version", 6, 1, false, Eeprom, R, 0, 255, 0),
    reg("ID", 7, 1, false, Eeprom, Rw, 0, 252, 1),
    reg("Baud Rate", 8, 1, false, Eeprom, Rw, 0, 8, 1),
    reg("Return Delay Time", 9, 1, false, Eeprom, Rw, 0, 254, 250),
    reg("Operating Mode", 11, 1, false, Eeprom, Rw, 0, 5, 5),
    reg("Moving Threshold", 17, 4, false, Eeprom, Rw, 0, R_MAX, 10),
    reg("Temperature Limit", 21, 1, false, Eeprom, Rw, 0, 100, 80),
    reg("Max Voltage Limit", 22, 2, false, Eeprom, Rw, 0, 400, 400),
    reg("Min Voltage Limit", 24, 2, false, Eeprom, Rw, 0, 400, 150),
    reg(
        "Acceleration Limit",
        26,
        4,
        false,
        Eeprom,
        Rw,
        0,
        R_MAX,
        255,
    ),
    reg("Current Limit", 30, 2, false, Eeprom, Rw, 0, 820, 820),
    reg("Velocity Limit", 32, 4, false, Eeprom, Rw, 0, R_MAX, 100),
    reg(
        "Max Position Limit",
        36,
        4,
        false,
        Eeprom,
        Rw,
        0,
        1150,
        1150,
    ),
    reg("Min Position Limit", 40, 4, false, Eeprom, Rw, 0, 1150, 0),
    reg("External Port Mode 1", 44, 1, false, Eeprom, Rw, 0, 3, 0),
    reg("External Port Mode 2", 45, 1, false, Eeprom, Rw, 0, 3, 0),
    reg("External Port Mode 3", 46, 1, false, Eeprom, Rw, 0, 3, 0),
    reg("External Port Mode 4", 47, 1, false, Eeprom, Rw, 0, 3, 0),
    reg("Shutdown", 48, 1, false, Eeprom, Rw, 0, 255, 48),
    reg("Torque Enable", 562, 1, false, Ram, Rw, 0, 1, 0),
    reg("LED Red", 563, 1, false, Ram, Rw, 0, 255, 0),
    reg("LED Green", 564, 1, false, Ram, Rw, 0, 255, 0),
    reg("LED Blue", 565, 1, false, Ram, Rw, 0, 255, 0),
    reg("Position D Gain", 590, 2, false, Ram, Rw, 0, 32767, 0),
    reg("Position I Gain", 592, 2, false, Ram, Rw, 0, 32767, 0),
    reg("Position P Gain", 594, 2, false, Ram, Rw, 0, 32767, 0),
    limited(
        reg("Goal Position", 596, 4, true, Ram, Rw, 0, 1150, 0),
        LimitBy::Between { min: 40, max: 36 },
    ),
    limited(
        reg("Goal Velocity", 600, 4, true, Ram, Rw, R_MIN, R_MAX, 0),
        LimitBy::Symmetric(32),
    ),
    limited(
        reg("Goal Current", 604, 2, true, Ram, Rw, -820, 820, 0),
        LimitBy::Symmetric(30),
    ),
    reg("Goal Acceleration", 606, 4, false, Ram, Rw, 0, R_MAX, 0),
    reg("Moving", 610, 1, false, Ram, R, 0, 1, 0),
    reg("Present Position", 611, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Velocity", 615, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Current", 621, 2, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Input Voltage", 623, 2, false, Ram, R, 0, 65535, 0),
    reg("Present Temperature", 625, 1, false, Ram, R, 0, 255, 0),
    reg("Registered Instruction", 890, 1, false, Ram, R, 0, 1, 0),
    reg("Status Return Level", 891, 1, false, Ram, Rw, 0, 2, 2),
    reg("Hardware Error Status", 892, 1, false, Ram, R, 0, 255, 0),
];

/// The RH-P12-RN control table. Model number 35073; grasps in current-based position mode (5).
pub const RH_P12_RN: ControlTable = ControlTable {
    name: "RH-P12-RN",
    key: "rh_p12_rn",
    model_number: 35073,
    registers: REGISTERS,
    size: table_size(REGISTERS),
    torque_enable: at(REGISTERS, 562),
    operating_mode: at(REGISTERS, 11),
    position_mode: 5,
    hardware_error_status: at(REGISTERS, 892),
    goal_position: at(REGISTERS, 596),
    goal_effort: at(REGISTERS, 604),
    effort_unit: EffortUnit::Current,
    effort_limit: at(REGISTERS, 30),
    present_load: at(REGISTERS, 621),
    present_velocity: at(REGISTERS, 615),
    present_position: at(REGISTERS, 611),
    // 12-bit absolute encoder, 0.088° (e-Manual "Degree of Precision").
    position_unit_rad: core::f32::consts::TAU / 4096.0,
    velocity_unit_rad_per_s: 0.114 * core::f32::consts::TAU / 60.0,
    load_full_scale: 820.0,
};
