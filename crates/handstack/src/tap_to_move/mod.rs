//! Tap-to-move as a loop over the `hand-traits` traits, after Al and Martinez-Hernandez,
//! "Multimodal barometric and inertial measurement unit based tactile sensor for robot control"
//! (§IV-B): the arm goes home and waits; when the pad's pressure rises above a threshold, the
//! accelerometer / gyroscope window around that instant goes to a [`ContactLocator`]; the region
//! it names picks a grid pose ([`RegionToGrid`]); the arm moves there in a straight line. Any
//! fault stops the arm (`Arm::stop`) before it is returned.
//!
//! The cell runs it across processes ([`crate::cell`], feature `cell`): the pad node triggers
//! with [`TapTrigger`], the coordinator picks the grid pose.

use std::borrow::Borrow;
use std::collections::VecDeque;
use std::time::Instant;

use hand_traits::{Arm, ContactLocator, ImuFrame, LinearMotion, TactileSource};

mod grid;
mod resample;

pub use grid::{GridError, REGIONS, RegionToGrid};
pub use resample::at_rate;

/// When a contact counts, and which frames the locator sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapToMoveConfig {
    /// Pressure rise over the resting baseline that counts as a contact, Pa.
    pub threshold_pa: f32,
    /// Pressure samples averaged for the resting baseline at the start of each wait.
    pub baseline_samples: usize,
    /// Frames before the trigger frame in the window (§IV-A: 19 of 38).
    pub frames_before: usize,
    /// Frames from the trigger frame on (§IV-A: 19 of 38).
    pub frames_after: usize,
    /// Most frames read while waiting for a contact before giving up.
    pub max_wait_frames: usize,
    /// Speed and acceleration of the moves.
    pub motion: LinearMotion,
}

impl Default for TapToMoveConfig {
    fn default() -> Self {
        Self {
            threshold_pa: 20.0,
            baseline_samples: 10,
            frames_before: 19,
            frames_after: 19,
            max_wait_frames: 10_000,
            motion: LinearMotion::default(),
        }
    }
}

impl TapToMoveConfig {
    /// The default trigger with its window of `frames_before + frames_after` frames centred
    /// `frames` after the trigger frame (at most half the window: it starts at the trigger at
    /// the latest), where a locator's training windows sat
    /// (`tactile_nets::contact_cnn::ContactCnn::trigger_offset`).
    ///
    /// ```
    /// use handstack::tap_to_move::TapToMoveConfig;
    /// let c = TapToMoveConfig::centred_after_trigger(16);
    /// assert_eq!((c.frames_before, c.frames_after), (3, 35));
    /// let c = TapToMoveConfig::centred_after_trigger(40);
    /// assert_eq!((c.frames_before, c.frames_after), (0, 38));
    /// ```
    pub fn centred_after_trigger(frames: usize) -> TapToMoveConfig {
        let d = TapToMoveConfig::default();
        let shift = frames.min(d.frames_before);
        TapToMoveConfig {
            frames_before: d.frames_before - shift,
            frames_after: d.frames_after + shift,
            ..d
        }
    }
}

/// What one cycle did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleReport {
    /// The region the locator named.
    pub region: u16,
    /// Its confidence.
    pub confidence: f32,
    /// Whether the window lay within the locator's range ([`hand_traits::Contact::in_range`]). When it
    /// did not, the region is an extrapolation and the arm was not moved: it stays at home.
    pub in_range: bool,
    /// Source time of the frame whose pressure crossed the threshold, µs.
    pub trigger_t_us: u64,
    /// Source time from the trigger to the last frame of the window, µs.
    pub window_wait_us: u64,
    /// Wall time the locator took, s.
    pub locate_s: f64,
    /// Wall time of the move to the grid pose, s (0 when the arm was not moved).
    pub move_s: f64,
}

/// Why a cycle ended early. The arm was told to stop first.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExperimentError<S, L, A>
where
    S: core::fmt::Debug + core::fmt::Display,
    L: core::fmt::Debug + core::fmt::Display,
    A: core::fmt::Debug + core::fmt::Display,
{
    /// The tactile source failed.
    #[error("tactile source: {0}")]
    Source(S),
    /// The locator failed.
    #[error("contact locator: {0}")]
    Locator(L),
    /// The arm failed.
    #[error("arm: {0}")]
    Arm(A),
    /// The region has no grid pose.
    #[error(transparent)]
    Grid(GridError),
    /// No contact within the configured number of frames.
    #[error("no contact in {0} frames")]
    NoContact(usize),
}

/// The error of a cycle over source `S`, locator `L` and arm `A`.
pub type CycleError<S, L, A> =
    ExperimentError<<S as TactileSource>::Error, <L as ContactLocator>::Error, <A as Arm>::Error>;

/// A contact window (the frames around the trigger, oldest first) and the trigger frame's
/// time, µs.
pub type Window<'a> = (&'a [ImuFrame], u64);

/// Finds taps in a stream of pad frames, one frame at a time: the pressure rising
/// `threshold_pa` over a resting baseline (the mean of the first `baseline_samples` readings of
/// each wait) triggers, and the `frames_before` frames before the trigger frame plus the
/// `frames_after` from it on make the window. After a window the next wait first lets the press
/// end (half the threshold above the old rest) before it takes a new baseline: a baseline taken
/// mid-press would hide the next tap. [`TapToMove`] waits with it; a loop that must keep its own
/// period pushes each frame as it reads it. Allocates nothing after [`TapTrigger::new`].
///
/// ```
/// use hand_traits::ImuFrame;
/// use handstack::tap_to_move::{TapToMoveConfig, TapTrigger};
///
/// let config = TapToMoveConfig { frames_before: 2, frames_after: 2, ..Default::default() };
/// let mut trigger = TapTrigger::new(config);
/// let frame = |t_us, pa| ImuFrame {
///     t_us,
///     accel_mps2: [0.0; 3],
///     gyro_rps: [0.0; 3],
///     pressure_pa: Some(pa),
/// };
/// let mut windows = Vec::new();
/// for t in 0..20u64 {
///     let pa = if (14..17).contains(&t) { 100_050.0 } else { 100_000.0 };
///     if let Some((window, trigger_t_us)) = trigger.push(frame(t, pa)) {
///         windows.push((window.iter().map(|f| f.t_us).collect::<Vec<_>>(), trigger_t_us));
///     }
/// }
/// assert_eq!(windows, [(vec![12, 13, 14, 15], 14)]);
/// ```
#[derive(Debug, Clone)]
pub struct TapTrigger {
    config: TapToMoveConfig,
    recent: VecDeque<ImuFrame>,
    sum: f64,
    n: usize,
    /// The resting pressure of the last wait.
    rest_pa: Option<f32>,
    released: bool,
    trigger_t_us: Option<u64>,
    /// The last push returned a window: the next one starts a new wait.
    done: bool,
}

impl TapTrigger {
    /// A trigger with `config`'s threshold, baseline and window.
    pub fn new(config: TapToMoveConfig) -> TapTrigger {
        TapTrigger {
            recent: VecDeque::with_capacity(config.frames_before + config.frames_after),
            config,
            sum: 0.0,
            n: 0,
            rest_pa: None,
            released: true,
            trigger_t_us: None,
            done: false,
        }
    }

    /// Starts a new wait (the frames so far dropped, the last rest kept for the release).
    pub fn restart(&mut self) {
        self.recent.clear();
        self.sum = 0.0;
        self.n = 0;
        self.released = self.rest_pa.is_none();
        self.trigger_t_us = None;
        self.done = false;
    }

    /// The window the last [`push`](Self::push) returned (contiguous since it did).
    fn window(&self) -> Window<'_> {
        (self.recent.as_slices().0, self.trigger_t_us.unwrap_or(0))
    }

    /// Whether a contact has triggered and the window is filling.
    pub fn is_triggered(&self) -> bool {
        self.trigger_t_us.is_some()
    }

    /// Adds a frame. Once the window is complete returns it, oldest frame first, with the
    /// trigger frame's time (µs).
    pub fn push(&mut self, f: ImuFrame) -> Option<Window<'_>> {
        if self.done {
            self.restart();
        }
        let c = self.config;
        if let Some(t) = self.trigger_t_us {
            self.recent.push_back(f);
            if self.recent.len() < c.frames_before + c.frames_after {
                return None;
            }
            self.done = true;
            return Some((self.recent.make_contiguous(), t));
        }
        if let Some(p) = f.pressure_pa.filter(|p| p.is_finite()) {
            if !self.released {
                self.released = self
                    .rest_pa
                    .is_none_or(|rest| p - rest < 0.5 * c.threshold_pa);
            } else if self.n < c.baseline_samples {
                self.sum += f64::from(p);
                self.n += 1;
                if self.n == c.baseline_samples {
                    self.rest_pa = Some((self.sum / self.n as f64) as f32);
                }
            } else if p - (self.sum / self.n as f64) as f32 > c.threshold_pa
                && self.recent.len() == c.frames_before
            {
                // The trigger frame is the first of the `frames_after`.
                self.trigger_t_us = Some(f.t_us);
                return self.push(f);
            }
        }
        if self.recent.len() == c.frames_before {
            self.recent.pop_front();
        }
        self.recent.push_back(f);
        None
    }
}

/// The tap-to-move experiment over a grid.
#[derive(Debug, Clone)]
pub struct TapToMove<'g> {
    grid: &'g RegionToGrid,
    config: TapToMoveConfig,
    /// The contact detector; it keeps the last wait's rest so the next first lets that press
    /// end.
    trigger: TapTrigger,
}

impl<'g> TapToMove<'g> {
    /// The experiment on `grid`.
    pub fn new(grid: &'g RegionToGrid, config: TapToMoveConfig) -> Self {
        Self {
            grid,
            config,
            trigger: TapTrigger::new(config),
        }
    }

    /// One cycle: home, wait for a contact, locate it, move to its grid pose — unless the
    /// window lay outside the locator's range ([`CycleReport::in_range`]): then the arm stays
    /// at home.
    ///
    /// `to_input` turns the `frames_before + frames_after` frames around the trigger into the
    /// locator's input, owned or as anything that borrows as it (for a CNN taking `[f32]`: the
    /// 4 × 38 acc x / y, gyro x / y window as a `[f32; 152]`).
    pub fn cycle<S, L, A, F, B>(
        &mut self,
        source: &mut S,
        locator: &mut L,
        arm: &mut A,
        mut to_input: F,
    ) -> Result<CycleReport, CycleError<S, L, A>>
    where
        S: TactileSource<Frame = ImuFrame>,
        L: ContactLocator,
        A: Arm,
        F: FnMut(&[ImuFrame]) -> B,
        B: Borrow<L::Input>,
    {
        // Any fault: stop the arm (safe state), then report the fault.
        fn halt<A: Arm, E>(arm: &mut A, e: E) -> E {
            let _ = arm.stop();
            e
        }
        arm.move_linear(self.grid.home(), &self.config.motion)
            .map_err(|e| halt(arm, ExperimentError::Arm(e)))?;
        let (window, trigger_t_us) = self.wait_for_contact(source).map_err(|e| halt(arm, e))?;
        let window_wait_us = window
            .last()
            .map_or(0, |f| f.t_us.saturating_sub(trigger_t_us));
        let input = to_input(window);
        let t0 = Instant::now();
        let contact = locator
            .locate(input.borrow())
            .map_err(|e| halt(arm, ExperimentError::Locator(e)))?;
        let locate_s = t0.elapsed().as_secs_f64();
        let target = *self
            .grid
            .pose(contact.region)
            .map_err(|e| halt(arm, ExperimentError::Grid(e)))?;
        let t1 = Instant::now();
        if contact.in_range {
            arm.move_linear(&target, &self.config.motion)
                .map_err(|e| halt(arm, ExperimentError::Arm(e)))?;
        }
        Ok(CycleReport {
            region: contact.region,
            confidence: contact.confidence,
            in_range: contact.in_range,
            trigger_t_us,
            window_wait_us,
            locate_s,
            move_s: if contact.in_range {
                t1.elapsed().as_secs_f64()
            } else {
                0.0
            },
        })
    }

    /// Reads frames until the pressure rises `threshold_pa` over the resting baseline (at most
    /// `max_wait_frames`), then the rest of the window ([`TapTrigger`]). Returns the window and
    /// the trigger frame's time.
    fn wait_for_contact<S, LE, AE>(
        &mut self,
        source: &mut S,
    ) -> Result<Window<'_>, ExperimentError<S::Error, LE, AE>>
    where
        S: TactileSource<Frame = ImuFrame>,
        LE: core::fmt::Debug + core::fmt::Display,
        AE: core::fmt::Debug + core::fmt::Display,
    {
        self.trigger.restart();
        let mut waited = 0;
        loop {
            if !self.trigger.is_triggered() {
                if waited == self.config.max_wait_frames {
                    return Err(ExperimentError::NoContact(waited));
                }
                waited += 1;
            }
            let f = source.read_frame().map_err(ExperimentError::Source)?;
            // Ends the borrow before the loop reads again (a window borrows the trigger).
            if self.trigger.push(f).is_some() {
                break;
            }
        }
        Ok(self.trigger.window())
    }
}
