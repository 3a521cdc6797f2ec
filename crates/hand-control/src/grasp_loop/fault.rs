//! What can go wrong in a cycle, typed per part, and the actuator's reboot.

use hand_traits::{Faults, GripperActuator};

use super::estimate::EstimateError;

/// What the loop needs to leave its safe state: an actuator whose latched hardware errors are
/// cleared by a reboot (Dynamixel: the REBOOT instruction) and whose torque can be switched on
/// again after a [`SafeAction::TorqueOff`](hand_traits::SafeAction::TorqueOff).
pub trait RebootableActuator: GripperActuator {
    /// Reboots the actuator and leaves its torque on (a Dynamixel comes back with torque off).
    fn reboot(&mut self) -> Result<(), Self::Error>;
    /// Switches torque on again (commands alone do not).
    fn enable_torque(&mut self) -> Result<(), Self::Error>;
}

/// One fault, with the part's own error inside. It reads in words when the parts' errors do
/// (`actuator state: servo 2: no answer (timeout)`).
#[derive(Debug, Clone, PartialEq)]
pub enum LoopFault<SE: core::fmt::Debug, PE: core::fmt::Debug, AE: core::fmt::Debug> {
    /// The tactile source failed to give a frame (bus NACK, CRC, timeout…).
    Source(SE),
    /// The frame was unusable.
    Estimate(EstimateError),
    /// The policy could not choose an effort.
    Policy(PE),
    /// The actuator refused or lost a command (lost status packet, CRC error, range error…).
    Command(AE),
    /// The actuator's state could not be read.
    State(AE),
    /// The actuator reports hardware-error bits (overload, overheat, voltage…).
    Hardware(Faults),
    /// Going to the safe state itself failed (it is retried every cycle).
    SafeStop(AE),
    /// A recovery reboot or torque enable failed.
    Reboot(AE),
}

impl<SE, PE, AE> core::fmt::Display for LoopFault<SE, PE, AE>
where
    SE: core::fmt::Debug + core::fmt::Display,
    PE: core::fmt::Debug + core::fmt::Display,
    AE: core::fmt::Debug + core::fmt::Display,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LoopFault::Source(e) => write!(f, "tactile source: {e}"),
            LoopFault::Estimate(e) => write!(f, "estimate: {e}"),
            LoopFault::Policy(e) => write!(f, "grasp policy: {e}"),
            LoopFault::Command(e) => write!(f, "actuator command: {e}"),
            LoopFault::State(e) => write!(f, "actuator state: {e}"),
            LoopFault::Hardware(faults) => write!(f, "actuator hardware error: {faults}"),
            LoopFault::SafeStop(e) => write!(f, "safe stop: {e}"),
            LoopFault::Reboot(e) => write!(f, "recovery: {e}"),
        }
    }
}

impl<SE, PE, AE> std::error::Error for LoopFault<SE, PE, AE>
where
    SE: core::fmt::Debug + core::fmt::Display,
    PE: core::fmt::Debug + core::fmt::Display,
    AE: core::fmt::Debug + core::fmt::Display,
{
}

/// The kind of a [`LoopFault`], without the payload: what the per-cycle log keeps.
///
/// ```
/// use hand_control::grasp_loop::FaultKind;
/// assert_eq!(FaultKind::Command.to_string(), "command refused or lost");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaultKind {
    /// See [`LoopFault::Source`].
    Source,
    /// See [`LoopFault::Estimate`].
    Estimate,
    /// See [`LoopFault::Policy`].
    Policy,
    /// See [`LoopFault::Command`].
    Command,
    /// See [`LoopFault::State`].
    State,
    /// See [`LoopFault::Hardware`].
    Hardware(Faults),
    /// See [`LoopFault::SafeStop`].
    SafeStop,
    /// See [`LoopFault::Reboot`].
    Reboot,
}

/// In words: `tactile source failed`, `hardware error: overload`, …
impl core::fmt::Display for FaultKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FaultKind::Source => f.write_str("tactile source failed"),
            FaultKind::Estimate => f.write_str("unusable frame"),
            FaultKind::Policy => f.write_str("policy chose no effort"),
            FaultKind::Command => f.write_str("command refused or lost"),
            FaultKind::State => f.write_str("actuator state unreadable"),
            FaultKind::Hardware(faults) => write!(f, "hardware error: {faults}"),
            FaultKind::SafeStop => f.write_str("safe stop failed"),
            FaultKind::Reboot => f.write_str("recovery reboot failed"),
        }
    }
}

impl<SE: core::fmt::Debug, PE: core::fmt::Debug, AE: core::fmt::Debug> LoopFault<SE, PE, AE> {
    /// The fault's kind.
    pub fn kind(&self) -> FaultKind {
        match self {
            LoopFault::Source(_) => FaultKind::Source,
            LoopFault::Estimate(_) => FaultKind::Estimate,
            LoopFault::Policy(_) => FaultKind::Policy,
            LoopFault::Command(_) => FaultKind::Command,
            LoopFault::State(_) => FaultKind::State,
            LoopFault::Hardware(f) => FaultKind::Hardware(*f),
            LoopFault::SafeStop(_) => FaultKind::SafeStop,
            LoopFault::Reboot(_) => FaultKind::Reboot,
        }
    }
}

/// A fault as reported: when, in which cycle, and the typed error.
#[derive(Debug, Clone, PartialEq)]
pub struct FaultEvent<SE: core::fmt::Debug, PE: core::fmt::Debug, AE: core::fmt::Debug> {
    /// The cycle it happened in.
    pub cycle: u64,
    /// The cycle's scheduled time, µs.
    pub t_us: u64,
    /// What went wrong.
    pub fault: LoopFault<SE, PE, AE>,
}
