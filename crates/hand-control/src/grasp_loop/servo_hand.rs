//! The Dynamixel [`ServoHand`] as the loop's rebootable actuator.

use super::fault::RebootableActuator;
use crate::{Error, ServoHand};

impl RebootableActuator for ServoHand {
    /// Reboots every servo whose Hardware Error Status is set (REBOOT clears the latched
    /// overload with torque off), then enables torque on all of them again.
    fn reboot(&mut self) -> Result<(), Error> {
        self.recover()?;
        self.set_torque(true)
    }

    /// Torque Enable = 1 on every servo.
    fn enable_torque(&mut self) -> Result<(), Error> {
        self.set_torque(true)
    }
}
