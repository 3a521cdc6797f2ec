//! Contact localisation: which region of a pad was touched.

/// Where a pad was touched: one region of a fixed partition of the pad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// The touched region, `0..regions`, in the locator's documented order.
    pub region: u16,
    /// How many regions the locator tells apart (9 for a 3 × 3 grid, 24 for 4 × 6).
    pub regions: u16,
    /// How sure the locator is, in `0.0..=1.0` (a softmax probability, a normalised score).
    pub confidence: f32,
    /// Whether the input lay within the range the locator is valid for (a learned model's
    /// training range). `false`: the region is an extrapolation — its confidence says nothing
    /// of a reading unlike any the model saw — to be reported, not acted on.
    pub in_range: bool,
}

/// Finds where a pad was touched.
///
/// Arrival-of-Time on a 3 × 3 grid, an MLP on 4 × 6 and a CNN on an IMU pad all implement it,
/// so a scene can swap one for another.
///
/// ```
/// use hand_traits::{Contact, ContactLocator, PressureFrame};
///
/// /// The region of the sensor that rose the most.
/// struct Loudest;
///
/// impl ContactLocator for Loudest {
///     type Input = PressureFrame<3>;
///     type Error = core::convert::Infallible;
///     fn locate(&mut self, frame: &Self::Input) -> Result<Contact, Self::Error> {
///         let (i, _) = frame.pressure_pa.iter().enumerate()
///             .fold((0, f32::MIN), |best, (i, &p)| if p > best.1 { (i, p) } else { best });
///         Ok(Contact { region: i as u16, regions: 3, confidence: 1.0, in_range: true })
///     }
/// }
///
/// let c = Loudest.locate(&PressureFrame { t_us: 0, pressure_pa: [1.0, 3.0, 2.0] })?;
/// assert_eq!(c.region, 1);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait ContactLocator {
    /// What the locator reads: pressures with arrival times, a feature vector, an IMU window.
    type Input: ?Sized;
    /// Why no location could be given (no sensor arrived, a non-finite input…).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Locates one contact.
    fn locate(&mut self, input: &Self::Input) -> Result<Contact, Self::Error>;
}
