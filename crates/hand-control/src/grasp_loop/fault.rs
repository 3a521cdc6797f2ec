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

/// One fault, with the part's own error inside.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LoopFault<SE: core::fmt::Debug, PE: core::fmt::Debug, AE: core::fmt::Debug> {
    /// The tactile source failed to give a frame (bus NACK, CRC, timeout…).
    #[error("tactile source: {0:?}")]
    Source(SE),
    /// The frame was unusable.
    #[error("estimate: {0}")]
    Estimate(EstimateError),
    /// The policy could not choose an effort.
    #[error("grasp policy: {0:?}")]
    Policy(PE),
    /// The actuator refused or lost a command (lost status packet, CRC error, range error…).
    #[error("actuator command: {0:?}")]
    Command(AE),
    /// The actuator's state could not be read.
    #[error("actuator state: {0:?}")]
    State(AE),
    /// The actuator reports hardware-error bits (overload, overheat, voltage…).
    #[error("actuator hardware error {0:?}")]
    Hardware(Faults),
    /// Going to the safe state itself failed (it is retried every cycle).
    #[error("safe stop: {0:?}")]
    SafeStop(AE),
    /// A recovery reboot or torque enable failed.
    #[error("recovery: {0:?}")]
    Reboot(AE),
}

/// The kind of a [`LoopFault`], without the payload: what the per-cycle log keeps.
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
