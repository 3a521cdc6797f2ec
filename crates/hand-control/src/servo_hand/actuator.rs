//! [`GripperActuator`] for [`ServoHand`]: one command = two sync writes, one state = one sync read.

use hand_traits::{GripperActuator, GripperCommand, GripperState, SafeAction};

use super::ServoHand;
use crate::error::Error;

impl GripperActuator for ServoHand {
    type Error = Error;

    /// Validates and sync-writes the goal effort and position to every servo.
    fn command(&mut self, cmd: &GripperCommand) -> Result<(), Error> {
        let goals = self.encode_command(cmd)?;
        self.write_goals(&goals)?;
        self.pending = Some(goals);
        Ok(())
    }

    /// Sync-reads every servo; position and velocity are the servos' means, the load the
    /// largest in magnitude, the faults the union of every alerting servo's hardware errors.
    /// Reads into the hand's own per-servo buffer, so it allocates nothing (`tests/goals_alloc.rs`
    /// measures the fault-free path).
    fn state(&mut self) -> Result<GripperState, Error> {
        let mut states = std::mem::take(&mut self.states);
        let r = self.state_from(&mut states);
        self.states = states;
        r
    }

    /// `TorqueOff`: one broadcast sync write of Torque Enable = 0 (needs no answer).
    /// `HoldLastSafeEffort`: re-sends the last command that a fault-free read confirmed; with
    /// none yet, holds the present position at zero effort.
    fn safe_stop(&mut self, action: SafeAction) -> Result<(), Error> {
        match action {
            SafeAction::TorqueOff => self.torque_off_all(),
            SafeAction::HoldLastSafeEffort => {
                let goals = match self.last_safe.clone() {
                    Some(g) => g,
                    None => {
                        let mut states = std::mem::take(&mut self.states);
                        let read = self.read_states_into(&mut states);
                        let n = read.as_ref().map_or(0, |&n| n);
                        let sum = states
                            .get(..n)
                            .unwrap_or_default()
                            .iter()
                            .map(|s| i64::from(s.position))
                            .sum::<i64>();
                        self.states = states;
                        read?;
                        super::RawGoals {
                            position: (sum / n.max(1) as i64) as i32,
                            effort: 0,
                        }
                    }
                };
                self.pending = None;
                self.write_goals(&goals)
            }
        }
    }
}

impl ServoHand {
    /// [`GripperActuator::state`] with `states` (one per servo) as the read buffer.
    fn state_from(&mut self, states: &mut [super::RawServoState]) -> Result<GripperState, Error> {
        let n = self.read_states_into(states)?;
        let states = &states[..n];
        let faults = self.faults_of(states)?;
        let t = self.table();
        let count = n.max(1) as f32;
        let mean = |f: fn(&super::RawServoState) -> i32| {
            states.iter().map(|s| f(s) as f32).sum::<f32>() / count
        };
        let load = states
            .iter()
            .map(|s| s.load as f32 / t.load_full_scale)
            .fold(0.0f32, |acc, l| if l.abs() > acc.abs() { l } else { acc });
        // A command counts as safe once a read after it shows no fault.
        if faults.is_empty() {
            if let Some(g) = self.pending.take() {
                self.last_safe = Some(g);
            }
        } else {
            self.pending = None;
        }
        Ok(GripperState {
            position_rad: mean(|s| s.position) * t.position_unit_rad,
            velocity_rad_per_s: mean(|s| s.velocity) * t.velocity_unit_rad_per_s,
            load_fraction: load,
            faults,
        })
    }
}
