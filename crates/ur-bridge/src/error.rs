//! What can go wrong talking to a UR controller.

use std::time::Duration;

use crate::kinematics::KinematicsError;

/// A typed bridge error: Python exceptions from ur_rtde, controller states, and our own checks.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum UrError {
    /// The embedded Python could not load ur_rtde (no venv, wrong interpreter, missing module).
    #[error("python environment: {0}")]
    Python(String),
    /// The controller did not accept a connection (wrong host, unreachable network, timeout).
    #[error("cannot connect to the controller at {host}: {message}")]
    Connect {
        /// The host name or address tried.
        host: String,
        /// ur_rtde's message.
        message: String,
    },
    /// The host refused the connection: it is there, but nothing listens on the port (no
    /// controller software running, or another machine at that address). ur_rtde reports this
    /// as a timeout; the bridge asks the port itself.
    #[error(
        "cannot connect to the controller at {host}: connection refused on port {port} \
         (nothing is listening there: is the controller on, and is this its address?)"
    )]
    ConnectionRefused {
        /// The host name or address tried.
        host: String,
        /// The port that refused (29999 dashboard, 30003 script, 30004 RTDE).
        port: u16,
    },
    /// The controller went to a protective stop (a limit was hit, or the pose is unreachable),
    /// or was in one when the bridge connected.
    #[error(
        "the arm is in a protective stop (safety status bits {safety_status_bits:#06x}): \
         remove its cause, then unlock it on the teach pendant or with the dashboard server's \
         `unlock protective stop` (port 29999), no sooner than 5 s after the stop"
    )]
    ProtectiveStop {
        /// RTDE `safety_status_bits` when the stop was seen.
        safety_status_bits: u32,
    },
    /// The controller is emergency-stopped.
    #[error("emergency stop (safety status bits {safety_status_bits:#06x})")]
    EmergencyStop {
        /// RTDE `safety_status_bits` when the stop was seen.
        safety_status_bits: u32,
    },
    /// The RTDE connection dropped (controller gone, cable pulled).
    #[error("connection to the controller lost")]
    ConnectionLost,
    /// ur_rtde's control script is not running on the controller (stopped by a runtime error).
    #[error("the ur_rtde control script is not running on the controller")]
    ScriptNotRunning,
    /// ur_rtde reported a command as not executed, with no stop or lost link to explain it.
    #[error("command `{0}` was not executed by the controller")]
    Rejected(&'static str),
    /// ur_rtde refused an argument (speed or acceleration out of its range, NaN).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// A bounded wait ran out.
    #[error("timed out after {} s waiting for {what}", after.as_secs_f64())]
    Timeout {
        /// How long we waited.
        after: Duration,
        /// What we waited for.
        what: &'static str,
    },
    /// Any other exception ur_rtde raised.
    #[error("controller error: {0}")]
    Controller(String),
    /// The controller answered with a value of the wrong shape.
    #[error("unexpected reply from {call}: {detail}")]
    BadReply {
        /// The ur_rtde call.
        call: &'static str,
        /// What was wrong.
        detail: String,
    },
    /// A target failed our own kinematic checks before it was sent.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}
