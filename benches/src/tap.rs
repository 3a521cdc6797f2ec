//! Tap to UR3 (seed 002 §IV): ICM-20789 frames (hand-sim's pad: the chip model read by the
//! real `imu-icm20789` driver at 30 Hz, Low Noise pressure) → the 4 × 38 accelerometer /
//! gyroscope window (hand-sim's cutter) → the committed contact CNN (frozen path) → region →
//! its UR3 grid pose (handstack's `RegionToGrid`; the arm's I/O is not part of the cycle).
//!
//! Every cycle classifies the latest 38 frames: the cost of the cycle in which a tap's
//! window completes, which the tap-to-move loop (`handstack::tap_to_move`) pays once per tap.

use crate::CycleError;
use hand_sim::imu_pad::{ImuPad, ImuPadConfig, TapSpec, TapWindow, WINDOW_SAMPLES};
use hand_traits::{ImuFrame, Pose, TactileSource};
use handstack::tap_to_move::RegionToGrid;
use paper_experiments::cnn_eval::{MODEL_DIR, model_file};
use paper_experiments::data::imu_pad::WINDOW_VALUES;
use tactile_nets::contact_cnn::{ContactCnn, Prediction, Variant};

/// The window as the CNN reads it: channel-major, acc in mm/s², gyro in mrad/s (the units of
/// hand-sim's tap dataset it was trained on, as in paper-experiments' tap-to-move example).
pub type CnnWindow = [f32; WINDOW_VALUES];

/// One cycle's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapOut {
    /// The frame read.
    pub frame: ImuFrame,
    /// The CNN's region and confidence (`None` until 38 frames have been read).
    pub prediction: Option<Prediction>,
    /// The grid pose of that region.
    pub pose: Option<Pose>,
}

/// The tap-to-UR3 cycle.
pub struct TapCycle {
    pad: ImuPad,
    /// The last frames, oldest first; twice a window long so sliding is a rare `copy_within`.
    recent: Vec<ImuFrame>,
    cnn: ContactCnn,
    grid: RegionToGrid,
}

impl TapCycle {
    /// A pad tapped 1.2 mm deep at the centre of each of the nine regions in turn, the
    /// committed paper-size CNN, and the default UR3 grid.
    pub fn new() -> Result<Self, CycleError> {
        let taps = [1, 2, 3]
            .into_iter()
            .flat_map(|column| {
                [4, 12, 20].map(|row| TapSpec {
                    column,
                    row,
                    depth_mm: 1.2,
                })
            })
            .collect();
        let config = ImuPadConfig {
            taps,
            ..ImuPadConfig::default()
        };
        let root = crate::workspace_root();
        Ok(TapCycle {
            pad: ImuPad::new(&config, 14)?,
            recent: Vec::with_capacity(2 * WINDOW_SAMPLES),
            cnn: ContactCnn::load(&root.join(MODEL_DIR).join(model_file(Variant::Paper)))?,
            grid: RegionToGrid::ur3_default()?,
        })
    }

    /// Decode: one frame (IMU burst + pressure) through the driver.
    pub fn decode(&mut self) -> Result<ImuFrame, CycleError> {
        Ok(self.pad.read_frame()?)
    }

    /// Estimate: the frame added to the recent ones; the window of the last 38, once full.
    pub fn estimate(&mut self, frame: ImuFrame) -> Result<Option<CnnWindow>, CycleError> {
        if self.recent.len() == 2 * WINDOW_SAMPLES {
            self.recent.copy_within(WINDOW_SAMPLES.., 0);
            self.recent.truncate(self.recent.len() - WINDOW_SAMPLES);
        }
        self.recent.push(frame);
        let Some(start) = self.recent.len().checked_sub(WINDOW_SAMPLES) else {
            return Ok(None);
        };
        Ok(Some(cnn_window(&self.recent[start..])?))
    }

    /// Policy: the CNN's region for the window.
    pub fn policy(&self, window: &CnnWindow) -> Result<Prediction, CycleError> {
        Ok(self.cnn.predict(window)?)
    }

    /// Encode: the arm's target, the region's grid pose.
    pub fn encode(&self, region: u8) -> Result<Pose, CycleError> {
        Ok(*self.grid.pose(u16::from(region))?)
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<TapOut, CycleError> {
        let frame = self.decode()?;
        let Some(window) = self.estimate(frame)? else {
            return Ok(TapOut {
                frame,
                prediction: None,
                pose: None,
            });
        };
        let prediction = self.policy(&window)?;
        let pose = self.encode(prediction.region)?;
        Ok(TapOut {
            frame,
            prediction: Some(prediction),
            pose: Some(pose),
        })
    }

    /// The grid the poses come from.
    pub fn grid(&self) -> &RegionToGrid {
        &self.grid
    }

    /// The CNN the cycle runs.
    pub fn cnn(&self) -> &ContactCnn {
        &self.cnn
    }
}

/// The CNN's input for 38 frames: hand-sim's window cut around the 20th frame, scaled.
pub fn cnn_window(frames: &[ImuFrame]) -> Result<CnnWindow, CycleError> {
    let centre = frames.get(WINDOW_SAMPLES / 2).map_or(0, |f| f.t_us);
    let w = TapWindow::extract(frames, centre)?.signals;
    Ok(core::array::from_fn(|i| {
        w[i / WINDOW_SAMPLES][i % WINDOW_SAMPLES] * 1e3
    }))
}
