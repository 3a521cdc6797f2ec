//! Sources of tactile frames.

/// Anything that yields tactile frames: a fingertip of barometers, an IMU pad, a finger array.
///
/// A source is polled by the control loop once per cycle; it does its own bus work.
///
/// ```
/// use hand_traits::{PressureFrame, TactileSource};
///
/// /// Replays recorded frames, then reports that it ran dry.
/// struct Replay<'a> { frames: &'a [PressureFrame<3>], next: usize }
///
/// #[derive(Debug, PartialEq)]
/// struct Exhausted;
///
/// impl core::fmt::Display for Exhausted {
///     fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
///         f.write_str("the recording ran out of frames")
///     }
/// }
///
/// impl TactileSource for Replay<'_> {
///     type Frame = PressureFrame<3>;
///     type Error = Exhausted;
///     fn read_frame(&mut self) -> Result<Self::Frame, Self::Error> {
///         let frame = *self.frames.get(self.next).ok_or(Exhausted)?;
///         self.next += 1;
///         Ok(frame)
///     }
/// }
///
/// let frames = [PressureFrame { t_us: 0, pressure_pa: [101_000.0; 3] }];
/// let mut source = Replay { frames: &frames, next: 0 };
/// assert_eq!(source.read_frame()?.pressure_pa[0], 101_000.0);
/// assert_eq!(source.read_frame(), Err(Exhausted));
/// # Ok::<(), Exhausted>(())
/// ```
pub trait TactileSource {
    /// The frame type, e.g. [`PressureFrame`](crate::PressureFrame) or [`ImuFrame`](crate::ImuFrame).
    type Frame;
    /// What can go wrong reading one frame (a bus NACK, a CRC mismatch, a timeout…), in
    /// words for the user (`Display`) and for a developer (`Debug`).
    type Error: core::fmt::Debug + core::fmt::Display;

    /// Reads the next frame.
    fn read_frame(&mut self) -> Result<Self::Frame, Self::Error>;
}
