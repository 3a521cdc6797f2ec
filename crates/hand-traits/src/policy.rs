//! Grasp policies: from tactile feedback to actuator effort.

/// What a grasp policy sees each cycle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GraspObservation {
    /// Target contact pressure minus measured contact pressure, in pascal.
    pub pressure_error_pa: f32,
    /// Time derivative of the measured contact pressure, in pascal per second.
    pub pressure_rate_pa_per_s: f32,
}

/// Actuator effort as a fraction of the actuator's maximum, always in `0.0..=1.0`.
///
/// The barometric-fingertip paper sets an MX-28's torque limit on a 0…1023 scale; an effort of
/// 1.0 is 1023 there. Each actuator maps the fraction to its own unit (PWM, current, torque limit).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct Effort(f32);

impl Effort {
    /// No effort.
    pub const ZERO: Effort = Effort(0.0);
    /// Full effort.
    pub const FULL: Effort = Effort(1.0);
    /// The top of the paper's torque-limit scale (MX-28, 0…1023).
    pub const TORQUE_LIMIT_RAW_MAX: u16 = 1023;

    /// An effort, or `None` if `fraction` is outside `0.0..=1.0` or not finite.
    ///
    /// ```
    /// # use hand_traits::Effort;
    /// assert!(Effort::new(0.5).is_some());
    /// assert!(Effort::new(1.5).is_none());
    /// assert!(Effort::new(f32::NAN).is_none());
    /// ```
    pub fn new(fraction: f32) -> Option<Self> {
        (0.0..=1.0).contains(&fraction).then_some(Effort(fraction))
    }

    /// An effort clamped into `0.0..=1.0`; NaN becomes zero effort, the safe side.
    ///
    /// ```
    /// # use hand_traits::Effort;
    /// assert_eq!(Effort::saturating(2.0), Effort::FULL);
    /// assert_eq!(Effort::saturating(f32::NAN), Effort::ZERO);
    /// ```
    pub fn saturating(fraction: f32) -> Self {
        if fraction.is_nan() {
            Effort::ZERO
        } else {
            Effort(fraction.clamp(0.0, 1.0))
        }
    }

    /// The fraction in `0.0..=1.0`.
    pub fn fraction(self) -> f32 {
        self.0
    }

    /// An effort from the paper's 0…1023 torque-limit scale (values above 1023 saturate).
    ///
    /// ```
    /// # use hand_traits::Effort;
    /// assert_eq!(Effort::from_torque_limit_raw(1023), Effort::FULL);
    /// assert_eq!(Effort::from_torque_limit_raw(400).to_torque_limit_raw(), 400);
    /// ```
    pub fn from_torque_limit_raw(raw: u16) -> Self {
        Effort::saturating(f32::from(raw) / f32::from(Self::TORQUE_LIMIT_RAW_MAX))
    }

    /// The effort on the paper's 0…1023 torque-limit scale, rounded to nearest.
    pub fn to_torque_limit_raw(self) -> u16 {
        // In 0..=1 by construction, so the product is in 0..=1023 and the cast is exact.
        (self.0 * f32::from(Self::TORQUE_LIMIT_RAW_MAX) + 0.5) as u16
    }
}

/// Chooses the grasp effort from tactile feedback, once per control cycle.
///
/// See the crate-level example for an implementation.
pub trait GraspPolicy {
    /// Why no effort could be chosen (a non-finite observation…).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// The effort for this cycle's observation.
    fn effort(&mut self, obs: &GraspObservation) -> Result<Effort, Self::Error>;
}
