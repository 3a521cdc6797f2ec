//! Seed 002 §IV-B as a loop over the `hand-traits` traits: the arm goes home and waits; when
//! the pad's pressure rises above a threshold, the accelerometer / gyroscope window around that
//! instant goes to a [`ContactLocator`]; the region it names picks a grid pose; the arm moves
//! there in a straight line. Any fault stops the arm (`Arm::stop`) before it is returned.

use std::borrow::Borrow;
use std::collections::VecDeque;
use std::time::Instant;

use hand_traits::{Arm, ContactLocator, ImuFrame, LinearMotion, TactileSource};

use crate::grid::{GridError, RegionToGrid};

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

/// What one cycle did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleReport {
    /// The region the locator named.
    pub region: u16,
    /// Its confidence.
    pub confidence: f32,
    /// Source time of the frame whose pressure crossed the threshold, µs.
    pub trigger_t_us: u64,
    /// Source time from the trigger to the last frame of the window, µs.
    pub window_wait_us: u64,
    /// Wall time the locator took, s.
    pub locate_s: f64,
    /// Wall time of the move to the grid pose, s.
    pub move_s: f64,
}

/// Why a cycle ended early. The arm was told to stop first.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError<S: core::fmt::Debug, L: core::fmt::Debug, A: core::fmt::Debug> {
    /// The tactile source failed.
    #[error("tactile source: {0:?}")]
    Source(S),
    /// The locator failed.
    #[error("contact locator: {0:?}")]
    Locator(L),
    /// The arm failed.
    #[error("arm: {0:?}")]
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

/// A contact window (the frames around the trigger) and the trigger frame's time, µs.
type Window = (VecDeque<ImuFrame>, u64);

/// The tap-to-move experiment over a grid.
#[derive(Debug, Clone)]
pub struct TapToMove<'g> {
    grid: &'g RegionToGrid,
    config: TapToMoveConfig,
    /// The resting pressure of the last wait: the next wait first lets the last press end.
    rest_pa: Option<f32>,
}

impl<'g> TapToMove<'g> {
    /// The experiment on `grid`.
    pub fn new(grid: &'g RegionToGrid, config: TapToMoveConfig) -> Self {
        Self {
            grid,
            config,
            rest_pa: None,
        }
    }

    /// One cycle: home, wait for a contact, locate it, move to its grid pose.
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
        let (mut window, trigger_t_us) = self.wait_for_contact(source).map_err(|e| halt(arm, e))?;
        let window_wait_us = window
            .back()
            .map_or(0, |f| f.t_us.saturating_sub(trigger_t_us));
        let input = to_input(window.make_contiguous());
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
        arm.move_linear(&target, &self.config.motion)
            .map_err(|e| halt(arm, ExperimentError::Arm(e)))?;
        Ok(CycleReport {
            region: contact.region,
            confidence: contact.confidence,
            trigger_t_us,
            window_wait_us,
            locate_s,
            move_s: t1.elapsed().as_secs_f64(),
        })
    }

    /// Reads frames until the pressure rises `threshold_pa` over the resting baseline, then the
    /// rest of the window. Returns the window and the trigger frame's time.
    fn wait_for_contact<S, LE, AE>(
        &mut self,
        source: &mut S,
    ) -> Result<Window, ExperimentError<S::Error, LE, AE>>
    where
        S: TactileSource<Frame = ImuFrame>,
        LE: core::fmt::Debug,
        AE: core::fmt::Debug,
    {
        let c = &self.config;
        let mut recent: VecDeque<ImuFrame> =
            VecDeque::with_capacity(c.frames_before + c.frames_after);
        let (mut sum, mut n) = (0.0_f64, 0_usize);
        // Until the previous press is released (half the threshold above the old rest), no new
        // baseline: a baseline taken mid-press would hide the next tap.
        let mut released = self.rest_pa.is_none();
        for _ in 0..c.max_wait_frames {
            let f = source.read_frame().map_err(ExperimentError::Source)?;
            if let Some(p) = f.pressure_pa.filter(|p| p.is_finite()) {
                if !released {
                    released = self
                        .rest_pa
                        .is_none_or(|rest| p - rest < 0.5 * c.threshold_pa);
                } else if n < c.baseline_samples {
                    sum += f64::from(p);
                    n += 1;
                    if n == c.baseline_samples {
                        self.rest_pa = Some((sum / n as f64) as f32);
                    }
                } else if p - (sum / n as f64) as f32 > c.threshold_pa
                    && recent.len() == c.frames_before
                {
                    // The trigger frame is the first of the `frames_after`.
                    recent.push_back(f);
                    while recent.len() < c.frames_before + c.frames_after {
                        recent.push_back(source.read_frame().map_err(ExperimentError::Source)?);
                    }
                    return Ok((recent, f.t_us));
                }
            }
            if recent.len() == c.frames_before {
                recent.pop_front();
            }
            recent.push_back(f);
        }
        Err(ExperimentError::NoContact(c.max_wait_frames))
    }
}
