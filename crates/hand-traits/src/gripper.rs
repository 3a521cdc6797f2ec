//! Gripper actuators: a hand closed by one or more servos.

use crate::Effort;

/// Hardware faults an actuator reports, as a set of flags.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Faults(u8);

impl Faults {
    /// No fault.
    pub const NONE: Faults = Faults(0);
    /// The load exceeded the actuator's limit for too long (Dynamixel: overload error bit).
    pub const OVERLOAD: Faults = Faults(1 << 0);
    /// The actuator is too hot.
    pub const OVERHEAT: Faults = Faults(1 << 1);
    /// The supply voltage is out of range.
    pub const VOLTAGE: Faults = Faults(1 << 2);
    /// The position sensor failed.
    pub const ENCODER: Faults = Faults(1 << 3);
    /// An electrical shock or driver fault.
    pub const ELECTRICAL: Faults = Faults(1 << 4);

    /// The raw flag bits.
    pub fn bits(self) -> u8 {
        self.0
    }

    /// Whether no flag is set.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether every flag of `other` is set in `self`.
    ///
    /// ```
    /// # use hand_traits::Faults;
    /// let f = Faults::OVERLOAD.union(Faults::OVERHEAT);
    /// assert!(f.contains(Faults::OVERLOAD) && !f.contains(Faults::VOLTAGE));
    /// ```
    pub fn contains(self, other: Faults) -> bool {
        self.0 & other.0 == other.0
    }

    /// The flags of both sets.
    pub fn union(self, other: Faults) -> Faults {
        Faults(self.0 | other.0)
    }

    /// Each flag with the words a person reads for it.
    const NAMES: [(Faults, &'static str); 5] = [
        (Faults::OVERLOAD, "overload"),
        (Faults::OVERHEAT, "overheating"),
        (Faults::VOLTAGE, "input voltage out of range"),
        (Faults::ENCODER, "position sensor failure"),
        (Faults::ELECTRICAL, "electrical shock"),
    ];
}

/// The flags in words, joined by commas (`no fault` when empty).
///
/// ```
/// # use hand_traits::Faults;
/// assert_eq!(Faults::OVERLOAD.union(Faults::OVERHEAT).to_string(), "overload, overheating");
/// assert_eq!(Faults::NONE.to_string(), "no fault");
/// ```
impl core::fmt::Display for Faults {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.is_empty() {
            return f.write_str("no fault");
        }
        let mut first = true;
        for (flag, name) in Faults::NAMES {
            if self.contains(flag) {
                if !first {
                    f.write_str(", ")?;
                }
                f.write_str(name)?;
                first = false;
            }
        }
        Ok(())
    }
}

/// One command to a gripper: where to close to, and with how much effort at most.
///
/// The barometric-fingertip paper grasps by position control under a torque limit: the fingers
/// head for `position_rad` but never push harder than `effort`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GripperCommand {
    /// Goal closure position, in radians of the actuator's output.
    pub position_rad: f32,
    /// The most effort the actuator may use on the way.
    pub effort: Effort,
}

/// What a gripper reports back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GripperState {
    /// Present closure position, in radians.
    pub position_rad: f32,
    /// Present closure velocity, in radians per second.
    pub velocity_rad_per_s: f32,
    /// Present load as a signed fraction of the actuator's maximum (positive when closing).
    pub load_fraction: f32,
    /// Hardware faults the actuator reports.
    pub faults: Faults,
}

/// What an actuator does when the control loop goes to its safe state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SafeAction {
    /// Keep holding with the last effort known to be safe: the object is not dropped.
    #[default]
    HoldLastSafeEffort,
    /// Disable torque: nothing is crushed, but the object may fall.
    TorqueOff,
}

/// A gripper that closes under an effort limit and reports its state.
///
/// ```
/// use hand_traits::{Effort, Faults, GripperActuator, GripperCommand, GripperState, SafeAction};
///
/// /// A gripper that moves instantly: enough to test a control loop.
/// #[derive(Default)]
/// struct Ideal { state: Option<GripperState> }
///
/// impl GripperActuator for Ideal {
///     type Error = core::convert::Infallible;
///     fn command(&mut self, cmd: &GripperCommand) -> Result<(), Self::Error> {
///         self.state = Some(GripperState {
///             position_rad: cmd.position_rad, velocity_rad_per_s: 0.0,
///             load_fraction: cmd.effort.fraction(), faults: Faults::NONE,
///         });
///         Ok(())
///     }
///     fn state(&mut self) -> Result<GripperState, Self::Error> {
///         Ok(self.state.unwrap_or(GripperState {
///             position_rad: 0.0, velocity_rad_per_s: 0.0, load_fraction: 0.0, faults: Faults::NONE,
///         }))
///     }
///     fn safe_stop(&mut self, action: SafeAction) -> Result<(), Self::Error> {
///         if action == SafeAction::TorqueOff { self.state = None; }
///         Ok(())
///     }
/// }
///
/// let mut g = Ideal::default();
/// g.command(&GripperCommand { position_rad: 1.0, effort: Effort::from_torque_limit_raw(400) })?;
/// assert_eq!(g.state()?.position_rad, 1.0);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait GripperActuator {
    /// What can go wrong (a lost status packet, a CRC mismatch, a hardware-error bit…).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Sends one command.
    fn command(&mut self, cmd: &GripperCommand) -> Result<(), Self::Error>;
    /// Reads the present state.
    fn state(&mut self) -> Result<GripperState, Self::Error>;
    /// Goes to the safe state `action` describes.
    fn safe_stop(&mut self, action: SafeAction) -> Result<(), Self::Error>;
}
