//! Object softness classification.

/// The three softness classes of the underactuated-hand experiment (sponge, silicone rubber,
/// wood for its model objects).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Softness {
    /// Soft, like sponge.
    Soft,
    /// Moderate, like silicone rubber.
    Moderate,
    /// Hard, like wood.
    Hard,
}

impl Softness {
    /// All classes, in index order.
    pub const ALL: [Softness; 3] = [Softness::Soft, Softness::Moderate, Softness::Hard];

    /// The class's index in [`Softness::ALL`] (a network output's position).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The class at `index` in [`Softness::ALL`], if there is one.
    ///
    /// ```
    /// # use hand_traits::Softness;
    /// for s in Softness::ALL { assert_eq!(Softness::from_index(s.index()), Some(s)); }
    /// assert_eq!(Softness::from_index(3), None);
    /// ```
    pub fn from_index(index: usize) -> Option<Self> {
        Self::ALL.get(index).copied()
    }
}

/// Tells how soft a grasped object is from a grasp's time series.
///
/// ```
/// use hand_traits::{Softness, SoftnessClassifier};
///
/// /// Harder objects push back harder: classify by peak force.
/// struct PeakForce;
///
/// impl SoftnessClassifier for PeakForce {
///     type Input = [f32];
///     type Error = core::convert::Infallible;
///     fn classify(&mut self, force_n: &[f32]) -> Result<Softness, Self::Error> {
///         let peak = force_n.iter().copied().fold(0.0, f32::max);
///         Ok(if peak > 10.0 { Softness::Hard } else if peak > 3.0 { Softness::Moderate } else { Softness::Soft })
///     }
/// }
///
/// assert_eq!(PeakForce.classify(&[0.5, 4.0, 12.0])?, Softness::Hard);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait SoftnessClassifier {
    /// What the classifier reads: a feature vector, a time series.
    type Input: ?Sized;
    /// Why no class could be given.
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Classifies one grasp.
    fn classify(&mut self, input: &Self::Input) -> Result<Softness, Self::Error>;
}
