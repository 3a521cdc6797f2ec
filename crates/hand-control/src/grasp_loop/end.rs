//! How a grasp ends: what the hand is left doing when its loop stops, for whatever reason (the
//! end of a hold, an operator's stop, a fault, a signal).

use hand_traits::{Effort, GripperCommand, SafeAction};

use super::clock::{FixedRate, LoopClock};
use super::fault::RebootableActuator;
use super::runner::GraspLoop;
use hand_traits::{GraspPolicy, PressureFrame, TactileSource};

/// How close to its opening position a released hand must come, rad.
pub const RELEASE_TOLERANCE_RAD: f32 = 0.05;

/// What the hand does when its loop ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EndAction {
    /// Let go, then power down: open back to where the loop found the hand (its first state
    /// read) under the band's greatest torque limit, wait until it is there (at most
    /// [`LoopConfig::release_timeout_us`](super::LoopConfig::release_timeout_us)), then torque
    /// off. Nothing stays powered, nothing is left squeezed.
    #[default]
    Release,
    /// Keep the grip: the last command a fault-free read confirmed (re-sent if the loop has
    /// sent another since, or faulted); torque stays on.
    Hold,
    /// Torque off at once: nothing is crushed, but a held object may fall.
    TorqueOff,
}

impl EndAction {
    /// Every action, in the order a scene file lists them.
    pub const ALL: [EndAction; 3] = [EndAction::Release, EndAction::Hold, EndAction::TorqueOff];

    /// Its name in a scene file (`release`, `hold`, `torque_off`).
    pub fn name(self) -> &'static str {
        match self {
            EndAction::Release => "release",
            EndAction::Hold => "hold",
            EndAction::TorqueOff => "torque_off",
        }
    }

    /// The action named `name`.
    ///
    /// ```
    /// use hand_control::grasp_loop::EndAction;
    /// assert_eq!(EndAction::from_name("torque_off"), Some(EndAction::TorqueOff));
    /// assert_eq!(EndAction::from_name("drop"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<EndAction> {
        EndAction::ALL.into_iter().find(|a| a.name() == name)
    }
}

/// What the hand was left doing, as far as it confirmed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndState {
    /// Opened to `position_rad`, then torque off.
    Released {
        /// Where it stopped, rad.
        position_rad: f32,
    },
    /// Did not reach its opening position in time (blocked, or faulted); torque off.
    NotOpened {
        /// Where it was last read, rad (`None`: not read).
        position_rad: Option<f32>,
        /// Where it was sent, rad.
        open_rad: f32,
    },
    /// Holding its last safe effort, torque on.
    Holding,
    /// Torque off.
    TorqueOff,
}

impl core::fmt::Display for EndState {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            EndState::Released { position_rad } => {
                write!(
                    f,
                    "released (opened to {position_rad:.2} rad), then torque off"
                )
            }
            EndState::NotOpened {
                position_rad: Some(p),
                open_rad,
            } => write!(
                f,
                "not opened (at {p:.2} rad, sent to {open_rad:.2} rad), then torque off"
            ),
            EndState::NotOpened {
                position_rad: None,
                open_rad,
            } => write!(f, "sent to open at {open_rad:.2} rad, then torque off"),
            EndState::Holding => f.write_str("holding its last safe effort (torque on)"),
            EndState::TorqueOff => f.write_str("torque off"),
        }
    }
}

/// What [`GraspLoop::end`] did: the state the hand confirmed, and the first error on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct EndReport<E> {
    /// The action asked for.
    pub action: EndAction,
    /// What the hand was left doing (`None`: nothing reached it).
    pub state: Option<EndState>,
    /// The first error the actuator gave.
    pub error: Option<E>,
}

impl<S, P, A, C, const N: usize> GraspLoop<S, P, A, C, N>
where
    S: TactileSource<Frame = PressureFrame<N>>,
    P: GraspPolicy,
    A: RebootableActuator,
    C: LoopClock,
{
    /// Ends the grasp with the configured [`EndAction`]: sent at once, in the caller's
    /// cycle. A release that cannot be sent (the actuator refuses or is gone), or one that
    /// starts from a hardware fault, falls back to torque off; so does one with nowhere known
    /// to open to. The loop's log is not extended (the hold's figures stay the hold's).
    pub fn end(&mut self) -> EndReport<A::Error> {
        let action = self.config().end_action;
        let mut error = None;
        let state = match action {
            // The servos already hold the last command a read confirmed: nothing to send.
            EndAction::Hold if self.holding_confirmed() => Some(EndState::Holding),
            EndAction::Hold => self.end_with(SafeAction::HoldLastSafeEffort, &mut error),
            EndAction::TorqueOff => self.end_with(SafeAction::TorqueOff, &mut error),
            EndAction::Release => {
                let opened = self.open(&mut error);
                self.end_with(SafeAction::TorqueOff, &mut error)
                    .map(|off| opened.unwrap_or(off))
            }
        };
        EndReport {
            action,
            state,
            error,
        }
    }

    /// The safe action `action`; its state if the actuator took it.
    fn end_with(&mut self, action: SafeAction, error: &mut Option<A::Error>) -> Option<EndState> {
        match self.actuator_mut().safe_stop(action) {
            Ok(()) => Some(match action {
                SafeAction::HoldLastSafeEffort => EndState::Holding,
                SafeAction::TorqueOff => EndState::TorqueOff,
            }),
            Err(e) => {
                error.get_or_insert(e);
                None
            }
        }
    }

    /// The opening part of a release: where it got to, or `None` when it could not start.
    fn open(&mut self, error: &mut Option<A::Error>) -> Option<EndState> {
        let open_rad = self.open_position_rad()?;
        let faulted = self.last_state().is_some_and(|st| !st.faults.is_empty());
        let effort_raw = self.config().band.max_raw();
        if faulted || effort_raw == 0 {
            return None;
        }
        let cmd = GripperCommand {
            position_rad: open_rad,
            effort: Effort::from_torque_limit_raw(effort_raw),
        };
        if let Err(e) = self.actuator_mut().command(&cmd) {
            error.get_or_insert(e);
            return None;
        }
        let (period, timeout) = (self.config().period_us, self.config().release_timeout_us);
        let start = self.clock_mut().now_us();
        let mut rate = FixedRate::new(period, start);
        let mut last = None;
        loop {
            let t = rate.wait(self.clock_mut());
            match self.actuator_mut().state() {
                Ok(st) => {
                    last = Some(st.position_rad);
                    if (st.position_rad - open_rad).abs() <= RELEASE_TOLERANCE_RAD {
                        return Some(EndState::Released {
                            position_rad: st.position_rad,
                        });
                    }
                    if !st.faults.is_empty() {
                        break;
                    }
                }
                Err(e) => {
                    error.get_or_insert(e);
                    break;
                }
            }
            if t.saturating_sub(start) >= timeout {
                break;
            }
        }
        Some(EndState::NotOpened {
            position_rad: last,
            open_rad,
        })
    }
}
