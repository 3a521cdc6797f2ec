//! Weight estimation (seed 000 Table 1): three MS5611 → tared rises → force DNN (frozen).
//!
//! The fingertip is read at OSR 4096 with whole-pad loads of 50…200 gf, as hand-sim's weight
//! series that trained the committed `sim` model; the tare is the mean of the resting frames
//! before the first load, as that model's training tare (`paper_experiments::data::weights`).

use crate::CycleError;
use crate::fingertip::{Press, PressSchedule, PressedFingertip, whole_pad};
use hand_traits::PressureFrame;
use paper_experiments::force_eval::{MODEL_DIR, SIM_FILE};
use tactile_nets::force_dnn::{ForceDnn, LiveTare};

/// Resting frames averaged into the tare.
pub const TARE_FRAMES: u64 = 20;
/// The loads applied in turn, gf.
pub const LOADS_GF: [f64; 4] = [50.0, 100.0, 150.0, 200.0];

/// One cycle's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightOut {
    /// The frame read.
    pub frame: PressureFrame<3>,
    /// Rises over the tare, hPa.
    pub rise_hpa: [f32; 3],
    /// The DNN's weight, gf.
    pub weight_gf: f32,
}

/// The weight-estimation cycle.
pub struct WeightCycle {
    tip: PressedFingertip,
    tare: LiveTare,
    dnn: ForceDnn,
}

impl WeightCycle {
    /// The cycle with the committed simulated-series force DNN.
    pub fn new() -> Result<Self, CycleError> {
        let schedule = PressSchedule {
            presses: LOADS_GF
                .iter()
                .map(|gf| Press {
                    cells: whole_pad(),
                    kgf: gf / 1000.0,
                })
                .collect(),
            rest_cycles: TARE_FRAMES,
            press_cycles: 60,
            release_cycles: 20,
        };
        let dnn = ForceDnn::load(&crate::workspace_root().join(MODEL_DIR).join(SIM_FILE))?;
        Ok(WeightCycle {
            tip: PressedFingertip::new(4096, 11, schedule)?,
            tare: LiveTare::new(TARE_FRAMES as u32),
            dnn,
        })
    }

    /// Decode: one frame from the three chips through the driver.
    pub fn decode(&mut self) -> Result<PressureFrame<3>, CycleError> {
        self.tip.read()
    }

    /// Estimate: the rises over the tare, hPa.
    pub fn estimate(&mut self, frame: &PressureFrame<3>) -> [f32; 3] {
        // Zero while taring.
        self.tare.rise_hpa(frame).unwrap_or([0.0; 3])
    }

    /// Policy: the force DNN's weight for the rises, gf.
    pub fn policy(&self, rise_hpa: &[f32; 3]) -> Result<f32, CycleError> {
        Ok(self.dnn.estimate_gf(rise_hpa)?)
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<WeightOut, CycleError> {
        let frame = self.decode()?;
        let rise_hpa = self.estimate(&frame);
        let weight_gf = self.policy(&rise_hpa)?;
        Ok(WeightOut {
            frame,
            rise_hpa,
            weight_gf,
        })
    }

    /// The load on the pad during the last frame, gf (0 when released).
    pub fn load_gf(&self) -> f64 {
        self.tip.pressed().map_or(0.0, |p| p.kgf * 1000.0)
    }
}
