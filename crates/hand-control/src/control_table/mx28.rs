//! MX-28 with Protocol 2.0 firmware — the servo of the grasping paper's hand (Table 4).
//!
//! Source: ROBOTIS e-Manual, "MX-28(2.0)" control table,
//! <https://emanual.robotis.com/docs/en/dxl/mx/mx-28-2/#control-table> (source
//! `docs/en/dxl/mx/mx-28-2.md` of ROBOTIS-GIT/emanual: addresses, sizes,
//! access, initial values and ranges); addresses agree with ROBOTIS' `dynamixel_hardware_interface`
//! `param/dxl_model/mx_28.model`. Units from the same page: position 0.088°/unit (4096 per
//! revolution), velocity 0.229 rev/min, Present Load 0.1 % (−1000…1000), Goal PWM 0.113 %
//! (PWM Limit 885 = 100 %).

use super::{
    Access::*, Area::*, ControlTable, EffortUnit, LimitBy, Register, at, limited, reg, table_size,
};

const R_MIN: i32 = i32::MIN;
const R_MAX: i32 = i32::MAX;

/// The MX-28(2.0) registers, in address order (Indirect Address / Data 168–251, 578–661 omitted).
pub(super) const REGISTERS: &[Register] = &[
    reg("Model Number", 0, 2, false, Eeprom, R, 0, 65535, 30),
    reg("Model Information", 2, 4, false, Eeprom, R, 0, R_MAX, 0),
    reg("Firmware Version", 6, 1, false, Eeprom, R, 0, 255, 0),
    reg("ID", 7, 1, false, Eeprom, Rw, 0, 252, 1),
    reg("Baud Rate", 8, 1, false, Eeprom, Rw, 0, 7, 1),
    reg("Return Delay Time", 9, 1, false, Eeprom, Rw, 0, 254, 250),
    reg("Drive Mode", 10, 1, false, Eeprom, Rw, 0, 5, 0),
    reg("Operating Mode", 11, 1, false, Eeprom, Rw, 0, 16, 3),
    reg(
        "Secondary(Shadow) ID",
        12,
        1,
        false,
        Eeprom,
        Rw,
        0,
        255,
        255,
    ),
    reg("Protocol Version", 13, 1, false, Eeprom, Rw, 1, 2, 2),
    reg(
        "Homing Offset",
        20,
        4,
        true,
        Eeprom,
        Rw,
        -1_044_479,
        1_044_479,
        0,
    ),
    reg("Moving Threshold", 24, 4, false, Eeprom, Rw, 0, 1023, 10),
    reg("Temperature Limit", 31, 1, false, Eeprom, Rw, 0, 100, 80),
    reg("Max Voltage Limit", 32, 2, false, Eeprom, Rw, 95, 160, 160),
    reg("Min Voltage Limit", 34, 2, false, Eeprom, Rw, 95, 160, 95),
    reg("PWM Limit", 36, 2, false, Eeprom, Rw, 0, 885, 885),
    reg(
        "Acceleration Limit",
        40,
        4,
        false,
        Eeprom,
        Rw,
        0,
        32767,
        32767,
    ),
    reg("Velocity Limit", 44, 4, false, Eeprom, Rw, 0, 1023, 380),
    reg(
        "Max Position Limit",
        48,
        4,
        false,
        Eeprom,
        Rw,
        0,
        4095,
        4095,
    ),
    reg("Min Position Limit", 52, 4, false, Eeprom, Rw, 0, 4095, 0),
    reg("Shutdown", 63, 1, false, Eeprom, Rw, 0, 255, 52),
    reg("Torque Enable", 64, 1, false, Ram, Rw, 0, 1, 0),
    reg("LED", 65, 1, false, Ram, Rw, 0, 1, 0),
    reg("Status Return Level", 68, 1, false, Ram, Rw, 0, 2, 2),
    reg("Registered Instruction", 69, 1, false, Ram, R, 0, 1, 0),
    reg("Hardware Error Status", 70, 1, false, Ram, R, 0, 255, 0),
    reg("Velocity I Gain", 76, 2, false, Ram, Rw, 0, 16383, 1920),
    reg("Velocity P Gain", 78, 2, false, Ram, Rw, 0, 16383, 100),
    reg("Position D Gain", 80, 2, false, Ram, Rw, 0, 16383, 0),
    reg("Position I Gain", 82, 2, false, Ram, Rw, 0, 16383, 0),
    reg("Position P Gain", 84, 2, false, Ram, Rw, 0, 16383, 850),
    reg("Feedforward 2nd Gain", 88, 2, false, Ram, Rw, 0, 16383, 0),
    reg("Feedforward 1st Gain", 90, 2, false, Ram, Rw, 0, 16383, 0),
    reg("Bus Watchdog", 98, 1, false, Ram, Rw, 0, 127, 0),
    limited(
        reg("Goal PWM", 100, 2, true, Ram, Rw, -885, 885, 0),
        LimitBy::Symmetric(36),
    ),
    limited(
        reg("Goal Velocity", 104, 4, true, Ram, Rw, -1023, 1023, 0),
        LimitBy::Symmetric(44),
    ),
    reg("Profile Acceleration", 108, 4, false, Ram, Rw, 0, 32767, 0),
    reg("Profile Velocity", 112, 4, false, Ram, Rw, 0, 32767, 0),
    limited(
        reg(
            "Goal Position",
            116,
            4,
            true,
            Ram,
            Rw,
            -1_048_575,
            1_048_575,
            0,
        ),
        LimitBy::Between { min: 52, max: 48 },
    ),
    reg("Realtime Tick", 120, 2, false, Ram, R, 0, 32767, 0),
    reg("Moving", 122, 1, false, Ram, R, 0, 1, 0),
    reg("Moving Status", 123, 1, false, Ram, R, 0, 255, 0),
    reg("Present PWM", 124, 2, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Load", 126, 2, true, Ram, R, -1000, 1000, 0),
    reg("Present Velocity", 128, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Position", 132, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Velocity Trajectory", 136, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Position Trajectory", 140, 4, true, Ram, R, R_MIN, R_MAX, 0),
    reg("Present Input Voltage", 144, 2, false, Ram, R, 0, 65535, 0),
    reg("Present Temperature", 146, 1, false, Ram, R, 0, 255, 0),
];

/// The MX-28 (Protocol 2.0 firmware) control table. Model number 30.
pub const MX_28: ControlTable = ControlTable {
    name: "MX-28(2.0)",
    key: "mx28",
    model_number: 30,
    registers: REGISTERS,
    size: table_size(REGISTERS),
    torque_enable: at(REGISTERS, 64),
    operating_mode: at(REGISTERS, 11),
    position_mode: 3,
    hardware_error_status: at(REGISTERS, 70),
    goal_position: at(REGISTERS, 116),
    goal_effort: at(REGISTERS, 100),
    effort_unit: EffortUnit::Pwm,
    effort_limit: at(REGISTERS, 36),
    present_load: at(REGISTERS, 126),
    present_velocity: at(REGISTERS, 128),
    present_position: at(REGISTERS, 132),
    position_unit_rad: core::f32::consts::TAU / 4096.0,
    // 0.229 rev/min per unit.
    velocity_unit_rad_per_s: 0.229 * core::f32::consts::TAU / 60.0,
    load_full_scale: 1000.0,
};
