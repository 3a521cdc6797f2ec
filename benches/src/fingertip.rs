//! The barometric fingertip as an in-process device: hand-sim's [`Fingertip`] (three MS5611
//! chip models on one SPI bus, read and compensated by the real `baro-drivers` scheduler) with
//! its frame log off, pressed and released on a fixed schedule counted in cycles.

use crate::CycleError;
use hand_sim::fingertip::{Cell, CellSet, ContactPatch, Fingertip, FingertipConfig};
use hand_traits::{PressureFrame, TactileSource};

/// One press of the schedule: which cells, how hard.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Press {
    /// The pressed cells.
    pub cells: CellSet,
    /// Total force, kgf.
    pub kgf: f64,
}

/// Presses applied in turn: each held `press_cycles` frames, then `release_cycles` untouched.
#[derive(Debug, Clone)]
pub struct PressSchedule {
    /// The presses, in order, repeated for ever.
    pub presses: Vec<Press>,
    /// Untouched frames before the first press (the detectors' resting baseline).
    pub rest_cycles: u64,
    /// Frames each press is held.
    pub press_cycles: u64,
    /// Untouched frames after each press.
    pub release_cycles: u64,
}

impl PressSchedule {
    /// The press in force at frame `n`, if any.
    pub fn at(&self, n: u64) -> Option<Press> {
        let k = n.checked_sub(self.rest_cycles)?;
        let period = self.press_cycles + self.release_cycles;
        if period == 0 || self.presses.is_empty() || k % period >= self.press_cycles {
            return None;
        }
        let i = (k / period) as usize % self.presses.len();
        Some(self.presses[i])
    }
}

/// A rectangle of cells from its top-left corner (row 1…4, column 1…6) and size.
pub fn rect(row: u8, col: u8, rows: u8, cols: u8) -> Result<CellSet, CycleError> {
    CellSet::rect(row, col, rows, cols)
        .ok_or_else(|| CycleError::Config(format!("{rows} × {cols} cells at ({row}, {col})")))
}

/// The whole 4 × 6 pad (Table 1's weights rest on all of it).
pub fn whole_pad() -> CellSet {
    Cell::all().fold(CellSet::EMPTY, CellSet::with)
}

/// The fingertip, its schedule and the frame count.
#[derive(Debug)]
pub struct PressedFingertip {
    tip: Fingertip,
    schedule: PressSchedule,
    frames: u64,
    current: Option<Press>,
}

impl PressedFingertip {
    /// A fingertip read at `osr` (256…4096), noise seeded with `seed`, pressed per `schedule`.
    pub fn new(osr: u16, seed: u64, schedule: PressSchedule) -> Result<Self, CycleError> {
        let config = FingertipConfig {
            osr,
            ..FingertipConfig::default()
        };
        let mut tip = Fingertip::new(&config, seed)?;
        tip.set_frame_log(false);
        Ok(PressedFingertip {
            tip,
            schedule,
            frames: 0,
            current: None,
        })
    }

    /// Applies the schedule's press for this frame, then reads one frame (2 conversions per
    /// sensor, compensated by the driver). The only stage that touches the "device".
    pub fn read(&mut self) -> Result<PressureFrame<3>, CycleError> {
        let want = self.schedule.at(self.frames);
        if want != self.current {
            let patch = want.map_or(ContactPatch::NONE, |p| {
                ContactPatch::from_kgf(p.cells, p.kgf)
            });
            self.tip.set_contact(patch)?;
            self.current = want;
        }
        self.frames += 1;
        Ok(self.tip.read_frame()?)
    }

    /// The press in force during the last frame read.
    pub fn pressed(&self) -> Option<Press> {
        self.current
    }

    /// Frames read so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }
}
