//! Robot arms that move a tool to a pose.

/// A tool pose in the robot's base frame, as Universal Robots controllers express it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// Tool centre point position, in metres.
    pub position_m: [f64; 3],
    /// Tool orientation as a rotation vector (axis × angle), in radians.
    pub rotation_vec_rad: [f64; 3],
}

impl Pose {
    /// The straight-line distance between two poses' positions, in metres.
    ///
    /// ```
    /// # use hand_traits::Pose;
    /// let a = Pose { position_m: [0.0, 0.0, 0.0], ..Pose::default() };
    /// let b = Pose { position_m: [0.3, 0.4, 0.0], ..Pose::default() };
    /// assert!((a.distance_m(&b) - 0.5).abs() < 1e-12);
    /// let far = Pose { position_m: [1e-3, 0.0, 0.0], ..Pose::default() };
    /// assert!((a.distance_m(&far) - 1e-3).abs() < 1e-15);
    /// let nan = Pose { position_m: [f64::NAN, 0.0, 0.0], ..Pose::default() };
    /// assert!(a.distance_m(&nan).is_nan());
    /// ```
    pub fn distance_m(&self, other: &Pose) -> f64 {
        let d: [f64; 3] = core::array::from_fn(|i| self.position_m[i] - other.position_m[i]);
        // no_std: no f64::sqrt in core before it is stabilised there, so Newton's method.
        sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    }
}

fn sqrt(x: f64) -> f64 {
    // Only sums of squares reach here: 0, positive, +inf or NaN (from a NaN coordinate).
    if x == 0.0 || x.is_nan() || x.is_infinite() {
        return x;
    }
    let mut r = if x > 1.0 { x } else { 1.0 };
    // Converges quadratically from above; 64 steps is far beyond what any f64 needs.
    for _ in 0..64 {
        let next = 0.5 * (r + x / r);
        if next >= r {
            break;
        }
        r = next;
    }
    r
}

/// Speed and acceleration of a straight-line tool move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearMotion {
    /// Tool speed, in metres per second.
    pub speed_m_per_s: f64,
    /// Tool acceleration, in metres per second squared.
    pub accel_m_per_s2: f64,
}

impl Default for LinearMotion {
    /// Universal Robots' `moveL` defaults: 0.25 m/s, 1.2 m/s².
    fn default() -> Self {
        Self {
            speed_m_per_s: 0.25,
            accel_m_per_s2: 1.2,
        }
    }
}

/// An arm that moves its tool in straight lines and reports where it is.
///
/// ```
/// use hand_traits::{Arm, LinearMotion, Pose};
///
/// /// An arm that teleports: enough to test a region-to-grid loop.
/// #[derive(Default)]
/// struct Teleport { at: Pose }
///
/// impl Arm for Teleport {
///     type Error = core::convert::Infallible;
///     fn move_linear(&mut self, target: &Pose, _: &LinearMotion) -> Result<(), Self::Error> {
///         self.at = *target;
///         Ok(())
///     }
///     fn tcp_pose(&mut self) -> Result<Pose, Self::Error> { Ok(self.at) }
///     fn stop(&mut self) -> Result<(), Self::Error> { Ok(()) }
/// }
///
/// let mut arm = Teleport::default();
/// let target = Pose { position_m: [0.2, -0.1, 0.3], rotation_vec_rad: [0.0, 3.14, 0.0] };
/// arm.move_linear(&target, &LinearMotion::default())?;
/// assert_eq!(arm.tcp_pose()?, target);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait Arm {
    /// What can go wrong (a protective stop, a lost connection, an unreachable pose…).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Moves the tool in a straight line to `target` and returns when it is there.
    fn move_linear(&mut self, target: &Pose, motion: &LinearMotion) -> Result<(), Self::Error>;
    /// The present tool pose.
    fn tcp_pose(&mut self) -> Result<Pose, Self::Error>;
    /// Decelerates to a stop.
    fn stop(&mut self) -> Result<(), Self::Error>;
}
