//! Robot and safety status as RTDE reports them (RTDE guide: `robot_mode`, `safety_mode`,
//! `safety_status_bits`, `robot_status_bits`, `runtime_state`).

/// `safety_status_bits` bit: normal mode.
pub const SAFETY_NORMAL: u32 = 1 << 0;
/// `safety_status_bits` bit: reduced mode.
pub const SAFETY_REDUCED: u32 = 1 << 1;
/// `safety_status_bits` bit: protective stopped.
pub const SAFETY_PROTECTIVE_STOPPED: u32 = 1 << 2;
/// `safety_status_bits` bit: system emergency stopped.
pub const SAFETY_SYSTEM_EMERGENCY_STOPPED: u32 = 1 << 5;
/// `safety_status_bits` bit: robot emergency stopped.
pub const SAFETY_ROBOT_EMERGENCY_STOPPED: u32 = 1 << 6;
/// `safety_status_bits` bit: emergency stopped.
pub const SAFETY_EMERGENCY_STOPPED: u32 = 1 << 7;
/// `safety_status_bits` bit: stopped due to safety.
pub const SAFETY_STOPPED_DUE_TO_SAFETY: u32 = 1 << 10;

/// `robot_status_bits` bit: power on.
pub const STATUS_POWER_ON: u32 = 1 << 0;
/// `robot_status_bits` bit: a program is running.
pub const STATUS_PROGRAM_RUNNING: u32 = 1 << 1;

/// `robot_mode` values.
pub mod robot_mode {
    /// No controller.
    pub const NO_CONTROLLER: i32 = -1;
    /// Disconnected.
    pub const DISCONNECTED: i32 = 0;
    /// Confirm safety.
    pub const CONFIRM_SAFETY: i32 = 1;
    /// Booting.
    pub const BOOTING: i32 = 2;
    /// Power off.
    pub const POWER_OFF: i32 = 3;
    /// Power on.
    pub const POWER_ON: i32 = 4;
    /// Idle: powered, brakes engaged.
    pub const IDLE: i32 = 5;
    /// Backdrive.
    pub const BACKDRIVE: i32 = 6;
    /// Running: brakes released, ready to move.
    pub const RUNNING: i32 = 7;
}

/// `safety_mode` values.
pub mod safety_mode {
    /// Normal.
    pub const NORMAL: i32 = 1;
    /// Reduced.
    pub const REDUCED: i32 = 2;
    /// Protective stop.
    pub const PROTECTIVE_STOP: i32 = 3;
}

/// `runtime_state` values.
pub mod runtime_state {
    /// Stopping.
    pub const STOPPING: u32 = 0;
    /// Stopped.
    pub const STOPPED: u32 = 1;
    /// Playing.
    pub const PLAYING: u32 = 2;
    /// Pausing.
    pub const PAUSING: u32 = 3;
    /// Paused.
    pub const PAUSED: u32 = 4;
}

/// A snapshot of the controller's state words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmStatus {
    /// `robot_mode` (see [`robot_mode`]).
    pub robot_mode: i32,
    /// `safety_mode` (see [`safety_mode`]).
    pub safety_mode: i32,
    /// `safety_status_bits`.
    pub safety_status_bits: u32,
    /// `robot_status_bits`.
    pub robot_status_bits: u32,
    /// `runtime_state` (see [`runtime_state`]).
    pub runtime_state: u32,
}

impl ArmStatus {
    /// Whether the arm is in a protective stop.
    ///
    /// ```
    /// # use ur_bridge::status::*;
    /// let s = ArmStatus { robot_mode: robot_mode::RUNNING, safety_mode: safety_mode::PROTECTIVE_STOP,
    ///     safety_status_bits: SAFETY_PROTECTIVE_STOPPED, robot_status_bits: STATUS_POWER_ON,
    ///     runtime_state: runtime_state::PAUSED };
    /// assert!(s.is_protective_stopped() && !s.is_emergency_stopped() && !s.is_program_running());
    /// ```
    pub fn is_protective_stopped(&self) -> bool {
        self.safety_status_bits & SAFETY_PROTECTIVE_STOPPED != 0
    }

    /// Whether any emergency stop is active.
    pub fn is_emergency_stopped(&self) -> bool {
        self.safety_status_bits
            & (SAFETY_EMERGENCY_STOPPED
                | SAFETY_ROBOT_EMERGENCY_STOPPED
                | SAFETY_SYSTEM_EMERGENCY_STOPPED)
            != 0
    }

    /// Whether a program (ur_rtde's control script) is playing.
    pub fn is_program_running(&self) -> bool {
        self.runtime_state == runtime_state::PLAYING
    }
}
