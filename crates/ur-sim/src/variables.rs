//! The RTDE variable table the simulator serves: names and types from Universal Robots' RTDE
//! guide (CB3 3.15 / e-Series), values from the kinematic controller.
//!
//! What the kinematic model does not simulate (currents, torques, temperatures, voltages,
//! I/O) reads as the quiescent value of a powered, unloaded arm on a bench (0 A, 0 N, …),
//! named in [`quiescent`].

use super::controller::Controller;
use super::wire::{Value, VarType};

fn register_index(name: &str, prefix: &str, range: core::ops::Range<usize>) -> Option<usize> {
    let n: usize = name.strip_prefix(prefix)?.parse().ok()?;
    range.contains(&n).then_some(n)
}

/// The type of an output (controller → client) variable, or `None` for `NOT_FOUND`.
pub(crate) fn output_type(name: &str) -> Option<VarType> {
    use VarType::*;
    if register_index(name, "output_int_register_", 0..48).is_some()
        || register_index(name, "input_int_register_", 0..48).is_some()
    {
        return Some(Int32);
    }
    if register_index(name, "output_double_register_", 0..48).is_some()
        || register_index(name, "input_double_register_", 0..48).is_some()
    {
        return Some(Double);
    }
    if register_index(name, "output_bit_register_", 64..128).is_some()
        || register_index(name, "input_bit_register_", 64..128).is_some()
    {
        return Some(Bool);
    }
    Some(match name {
        "timestamp"
        | "actual_execution_time"
        | "speed_scaling"
        | "target_speed_fraction"
        | "actual_momentum"
        | "actual_main_voltage"
        | "actual_robot_voltage"
        | "actual_robot_current"
        | "standard_analog_input0"
        | "standard_analog_input1"
        | "standard_analog_output0"
        | "standard_analog_output1"
        | "io_current"
        | "tool_analog_input0"
        | "tool_analog_input1"
        | "tool_output_current"
        | "tool_temperature"
        | "tcp_force_scalar"
        | "payload" => Double,
        "target_q"
        | "target_qd"
        | "target_qdd"
        | "target_current"
        | "target_moment"
        | "actual_q"
        | "actual_qd"
        | "actual_current"
        | "joint_control_output"
        | "actual_TCP_pose"
        | "actual_TCP_speed"
        | "actual_TCP_force"
        | "target_TCP_pose"
        | "target_TCP_speed"
        | "joint_temperatures"
        | "actual_joint_voltage"
        | "ft_raw_wrench"
        | "payload_inertia" => Vector6d,
        "actual_digital_input_bits" | "actual_digital_output_bits" => Uint64,
        "robot_mode" | "safety_mode" | "safety_status" | "tool_output_voltage" => Int32,
        "joint_mode" => Vector6Int32,
        "actual_tool_accelerometer" | "elbow_position" | "elbow_velocity" | "payload_cog" => {
            Vector3d
        }
        "runtime_state"
        | "robot_status_bits"
        | "safety_status_bits"
        | "analog_io_types"
        | "tool_mode"
        | "tool_analog_input_types"
        | "output_bit_registers0_to_31"
        | "output_bit_registers32_to_63"
        | "input_bit_registers0_to_31"
        | "input_bit_registers32_to_63"
        | "script_control_line" => Uint32,
        _ => return None,
    })
}

/// The type of an input (client → controller) variable, or `None` for `NOT_FOUND`.
pub(crate) fn input_type(name: &str) -> Option<VarType> {
    use VarType::*;
    if register_index(name, "input_int_register_", 0..48).is_some() {
        return Some(Int32);
    }
    if register_index(name, "input_double_register_", 0..48).is_some() {
        return Some(Double);
    }
    if register_index(name, "input_bit_register_", 64..128).is_some() {
        return Some(Bool);
    }
    Some(match name {
        "speed_slider_mask" | "input_bit_registers0_to_31" | "input_bit_registers32_to_63" => {
            Uint32
        }
        "speed_slider_fraction" | "standard_analog_output_0" | "standard_analog_output_1" => Double,
        "standard_digital_output_mask"
        | "standard_digital_output"
        | "configurable_digital_output_mask"
        | "configurable_digital_output"
        | "tool_digital_output_mask"
        | "tool_digital_output"
        | "standard_analog_output_mask"
        | "standard_analog_output_type" => Uint8,
        "external_force_torque" => Vector6d,
        _ => return None,
    })
}

/// Variables the kinematic model does not simulate; they read as a quiescent bench arm.
pub(crate) fn quiescent(ty: VarType) -> Value {
    match ty {
        VarType::Bool => Value::Bool(false),
        VarType::Uint8 => Value::Uint8(0),
        VarType::Uint32 => Value::Uint32(0),
        VarType::Uint64 => Value::Uint64(0),
        VarType::Int32 => Value::Int32(0),
        VarType::Double => Value::Double(0.0),
        VarType::Vector3d => Value::Vector3d([0.0; 3]),
        VarType::Vector6d => Value::Vector6d([0.0; 6]),
        VarType::Vector6Int32 => Value::Vector6Int32([0; 6]),
    }
}

/// `joint_mode` of a running joint (RTDE guide: JOINT_RUNNING_MODE).
const JOINT_RUNNING_MODE: i32 = 253;
/// `joint_mode` of an unpowered joint (JOINT_POWER_OFF_MODE).
const JOINT_POWER_OFF_MODE: i32 = 239;
/// `joint_mode` of a powered joint with its brake on (JOINT_IDLE_MODE).
const JOINT_IDLE_MODE: i32 = 255;

/// The value of output variable `name` (of type `ty`) in the controller's present state.
pub(crate) fn output_value(c: &Controller, name: &str, ty: VarType) -> Value {
    if let Some(i) = register_index(name, "output_int_register_", 0..48) {
        return Value::Int32(c.out_int[i]);
    }
    if let Some(i) = register_index(name, "input_int_register_", 0..48) {
        return Value::Int32(c.in_int[i]);
    }
    if let Some(i) = register_index(name, "output_double_register_", 0..48) {
        return Value::Double(c.out_double[i]);
    }
    if let Some(i) = register_index(name, "input_double_register_", 0..48) {
        return Value::Double(c.in_double[i]);
    }
    match name {
        "timestamp" => Value::Double(c.time_s),
        "actual_q" | "target_q" => Value::Vector6d(c.q),
        "actual_qd" | "target_qd" => Value::Vector6d(c.qd),
        "actual_TCP_pose" | "target_TCP_pose" => Value::Vector6d(c.tcp_vector()),
        "actual_TCP_speed" | "target_TCP_speed" => Value::Vector6d(c.tcp_speed()),
        "robot_mode" => Value::Int32(c.robot_mode),
        "safety_mode" | "safety_status" => Value::Int32(c.safety_mode),
        "safety_status_bits" => Value::Uint32(c.safety_status_bits),
        "robot_status_bits" => Value::Uint32(c.robot_status_bits()),
        "runtime_state" => Value::Uint32(c.runtime_state),
        "speed_scaling" | "target_speed_fraction" => Value::Double(c.speed_fraction),
        "elbow_position" => Value::Vector3d(c.elbow_position()),
        "joint_mode" => Value::Vector6Int32(
            [match c.robot_mode {
                ur_bridge::status::robot_mode::RUNNING => JOINT_RUNNING_MODE,
                ur_bridge::status::robot_mode::IDLE => JOINT_IDLE_MODE,
                _ => JOINT_POWER_OFF_MODE,
            }; 6],
        ),
        _ => quiescent(ty),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn types_follow_the_rtde_guide() {
        assert_eq!(output_type("actual_TCP_pose"), Some(VarType::Vector6d));
        assert_eq!(output_type("runtime_state"), Some(VarType::Uint32));
        assert_eq!(output_type("robot_mode"), Some(VarType::Int32));
        assert_eq!(
            output_type("actual_digital_input_bits"),
            Some(VarType::Uint64)
        );
        assert_eq!(output_type("output_int_register_47"), Some(VarType::Int32));
        assert_eq!(output_type("output_int_register_48"), None);
        assert_eq!(output_type("no_such_variable"), None);
        assert_eq!(
            input_type("input_double_register_23"),
            Some(VarType::Double)
        );
        assert_eq!(input_type("external_force_torque"), Some(VarType::Vector6d));
        assert_eq!(input_type("actual_q"), None);
    }
}
