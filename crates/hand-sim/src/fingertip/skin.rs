//! Another fingertip: the same sensors under a silicone of its own.
//!
//! No two moulded fingertips respond alike: the silicone's thickness and stiffness set how much
//! of a load reaches each sensor, and each sensor sits a little deeper or shallower in it. That
//! is why seed 000 trained its force DNN and contact MLP on its own fingertip, and why a user of
//! the built-in models calibrates their own. [`LawParams::other_skin`] draws such a fingertip
//! from a seed: the calibrated law with its response and per-sensor gains scaled, so tests can
//! show what the built-in models miss on it and what a model trained on its own data recovers.

use super::law::LawParams;
use rand::Rng;

/// How far another skin's overall response differs from the calibrated one: a factor drawn
/// uniformly in 1 ± this (a thinner or softer silicone passes more of a load).
pub const RESPONSE_SPREAD: f64 = 0.25;
/// How far each sensor's gain differs from the calibrated one: a factor in 1 ± this (a sensor
/// seated deeper or shallower).
pub const GAIN_SPREAD: f64 = 0.15;

impl LawParams {
    /// This law under another skin drawn from `seed`: the linear and saturating responses
    /// scaled by one factor in 1 ± [`RESPONSE_SPREAD`], the force scale of the non-linear
    /// term by another, each sensor's gain by its own in 1 ± [`GAIN_SPREAD`]. Geometry and
    /// timing are kept (the sensors do not move).
    ///
    /// ```
    /// use hand_sim::fingertip::LawParams;
    /// let a = LawParams::CALIBRATED.other_skin(3);
    /// assert_eq!(a, LawParams::CALIBRATED.other_skin(3)); // a seed is one fingertip
    /// assert_ne!(a, LawParams::CALIBRATED.other_skin(4));
    /// assert_eq!(a.sensors_mm, LawParams::CALIBRATED.sensors_mm);
    /// ```
    pub fn other_skin(&self, seed: u64) -> LawParams {
        let mut rng = crate::seed::stream(seed, "fingertip-skin");
        let mut factor = |spread: f64| 1.0 + spread * (2.0 * rng.random::<f64>() - 1.0);
        let response = factor(RESPONSE_SPREAD);
        let scale = factor(RESPONSE_SPREAD);
        let gains = self.gains.map(|g| g * factor(GAIN_SPREAD));
        LawParams {
            linear_hpa_per_n: self.linear_hpa_per_n * response,
            saturation_hpa: self.saturation_hpa * response,
            scale_n: self.scale_n * scale,
            gains,
            ..*self
        }
    }
}
