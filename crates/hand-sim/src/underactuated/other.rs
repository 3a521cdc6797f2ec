//! Another hand: the same design, built by someone else.
//!
//! An FSR's sensitivity depends on how its actuator presses on it (the puck, the pad over it,
//! the finger's curvature), so force sensors glued into another build read the same force
//! higher than the nominal law says — by more than the unit-to-unit spread of one batch. A
//! potentiometer mounted again reads each distal angle a few degrees off. The softness net
//! learns forces against angles, so the built-in one misclassifies objects in such a hand and a
//! user trains their own ([`UnderactuatedConfig::other_hand`] draws one from a seed for the
//! tests that show both).

use super::UnderactuatedConfig;
use rand::Rng;

/// The range of each FSR's sensitivity in another build, relative to the nominal law.
pub const FSR_GAIN: core::ops::RangeInclusive<f64> = 1.6..=2.2;
/// The range of each potentiometer's mounting error in another build, degrees (either sign).
pub const POT_OFFSET_DEG: core::ops::RangeInclusive<f64> = 6.0..=12.0;

impl UnderactuatedConfig {
    /// This hand built again, drawn from `seed`: each finger's FSR reads [`FSR_GAIN`] times the
    /// nominal sensitivity, each distal potentiometer is mounted [`POT_OFFSET_DEG`] degrees off
    /// (up or down). The mechanics, the object and the ADC are kept.
    ///
    /// ```
    /// use hand_sim::underactuated::UnderactuatedConfig;
    /// let base = UnderactuatedConfig::default();
    /// let a = base.other_hand(1);
    /// assert_eq!(a, base.other_hand(1)); // a seed is one hand
    /// assert_ne!(a, base.other_hand(2));
    /// assert!(a.sensors.fsr_gain.iter().all(|g| (1.6..=2.2).contains(g)));
    /// assert!(a.sensors.pot_offset_deg.iter().all(|o| (6.0..=12.0).contains(&o.abs())));
    /// a.validate()?;
    /// # Ok::<(), hand_sim::SimError>(())
    /// ```
    pub fn other_hand(&self, seed: u64) -> UnderactuatedConfig {
        let mut rng = crate::seed::stream(seed, "underactuated-build");
        let mut hand = self.clone();
        for i in 0..4 {
            hand.sensors.fsr_gain[i] = rng.random_range(FSR_GAIN);
            let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
            hand.sensors.pot_offset_deg[i] = sign * rng.random_range(POT_OFFSET_DEG);
        }
        hand
    }
}
