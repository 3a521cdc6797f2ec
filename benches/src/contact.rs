//! Contact location on the barometric fingertip (seed 000 §3–4): three MS5611 → arrival
//! detection → Arrival-of-Time (eq. 3, and the ranging scorer) on the 3 × 3 grid, and the
//! contact MLP on the 4 × 6 pad.
//!
//! The pad is read at OSR 256 (the committed MLP's selection OSR) and pressed in turn on a
//! single corner cell, a 2 × 2 block and a 1 × 3 bar at 5 / 7 / 9 kgf (Table 2's forces).
//! Both locators run on every cycle in which a contact has arrived — a loop publishing its
//! contact estimate each tick; the detector re-arms once every sensor is back at rest.
//!
//! The ranging scorer's constants are the OSR-256-sized ones of `crates/aot-locate/benches`
//! (its cost does not depend on their values; its accuracy is fitted and reported in
//! `docs/contact-location.md`, not here).

use crate::CycleError;
use crate::fingertip::{Press, PressSchedule, PressedFingertip, rect};
use aot_locate::{AotLocator, ArrivalDetector, ArrivalEvent, DetectorConfig, Ranging, Scorer};
use hand_sim::fingertip::geometry::aot_geometry;
use hand_traits::{Contact, ContactLocator, PressureFrame};
use paper_experiments::contact_eval::{MODEL_DIR, SELECTION_OSR, chosen_file};
use paper_experiments::data::fingertip::TapReading;
use tactile_nets::contact_mlp::{ContactMlp, Prediction, features};

/// Untouched frames before the first press (the detectors' resting baseline).
pub const REST_FRAMES: u64 = 30;
/// Frames each press is held: 400 ms at OSR 256 (as hand-sim's tap dataset).
pub const PRESS_FRAMES: u64 = 330;
/// Frames between presses: ~300 ms, 15 of the pad's 20 ms time constants (hand-sim's
/// calibrated law) after the release reaches the farthest sensor, so every sensor is back
/// within the re-arm margin before the next press.
pub const RELEASE_FRAMES: u64 = 250;

/// One cycle's estimate: the detector's event, or `None` while nothing has arrived.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEstimate {
    /// The frame read.
    pub frame: PressureFrame<3>,
    /// The eq. 3 input (rises over the frozen baselines, arrivals from the first one).
    pub event: Option<ArrivalEvent>,
    /// The MLP's reading (baselines, held pressures, arrivals in ms from the first one).
    pub reading: Option<TapReading>,
}

/// One cycle's locations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOut {
    /// The estimate they were made from.
    pub estimate: ContactEstimate,
    /// Eq. 3 on the 3 × 3 grid.
    pub eq3: Option<Contact>,
    /// The ranging scorer on the 3 × 3 grid.
    pub ranging: Option<Contact>,
    /// The MLP on the 4 × 6 pad.
    pub mlp: Option<Prediction>,
}

/// The contact-location cycle.
pub struct ContactCycle {
    tip: PressedFingertip,
    detector: ArrivalDetector,
    eq3: AotLocator,
    ranging: AotLocator,
    mlp: ContactMlp,
}

impl ContactCycle {
    /// The cycle with the committed validation-chosen MLP.
    pub fn new() -> Result<Self, CycleError> {
        let shapes = [rect(1, 1, 1, 1)?, rect(2, 3, 2, 2)?, rect(4, 2, 1, 3)?];
        let presses = shapes
            .iter()
            .flat_map(|&cells| [5.0, 7.0, 9.0].map(|kgf| Press { cells, kgf }))
            .collect();
        let schedule = PressSchedule {
            presses,
            rest_cycles: REST_FRAMES,
            press_cycles: PRESS_FRAMES,
            release_cycles: RELEASE_FRAMES,
        };
        let model = Ranging::new(3_000.0, 2_500.0, 25_000.0, 30.0).map_err(CycleError::Ranging)?;
        let root = crate::workspace_root();
        Ok(ContactCycle {
            tip: PressedFingertip::new(SELECTION_OSR, 12, schedule)?,
            detector: ArrivalDetector::new(DetectorConfig::DEFAULT),
            eq3: AotLocator::new(aot_geometry()),
            ranging: AotLocator::with_scorer(aot_geometry(), Scorer::Ranging(model)),
            mlp: ContactMlp::load(&root.join(MODEL_DIR).join(chosen_file(SELECTION_OSR)))?,
        })
    }

    /// Decode: one frame from the three chips through the driver.
    pub fn decode(&mut self) -> Result<PressureFrame<3>, CycleError> {
        self.tip.read()
    }

    /// Estimate: arrival detection, and the locators' inputs once a contact has arrived.
    pub fn estimate(&mut self, frame: &PressureFrame<3>) -> ContactEstimate {
        let t_us = frame.t_us as i64;
        let p = frame.pressure_pa;
        let Some(onset) = self.detector.push_streaming(t_us, p) else {
            return ContactEstimate {
                frame: *frame,
                event: None,
                reading: None,
            };
        };
        let reading = TapReading::from_detector(&self.detector, p, onset);
        ContactEstimate {
            frame: *frame,
            event: Some(self.detector.event(onset, p)),
            reading: Some(reading),
        }
    }

    /// Policy, AoT: eq. 3 and the ranging scorer on the event.
    pub fn aot(&mut self, event: &ArrivalEvent) -> Result<(Contact, Contact), CycleError> {
        Ok((self.eq3.locate(event)?, self.ranging.locate(event)?))
    }

    /// Policy, MLP: the contact on the 4 × 6 pad from the reading's features.
    pub fn mlp(&self, reading: &TapReading) -> Result<Prediction, CycleError> {
        Ok(self.mlp.predict(&features(reading))?)
    }

    /// Contacts the MLP's decoder chooses from.
    pub fn catalogue_len(&self) -> usize {
        self.mlp.catalogue().len()
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<ContactOut, CycleError> {
        let frame = self.decode()?;
        let estimate = self.estimate(&frame);
        let (mut eq3, mut ranging, mut mlp) = (None, None, None);
        if let (Some(event), Some(reading)) = (estimate.event, estimate.reading) {
            let (a, b) = self.aot(&event)?;
            (eq3, ranging) = (Some(a), Some(b));
            mlp = Some(self.mlp(&reading)?);
        }
        Ok(ContactOut {
            estimate,
            eq3,
            ranging,
            mlp,
        })
    }

    /// The press in force during the last frame.
    pub fn pressed(&self) -> Option<Press> {
        self.tip.pressed()
    }
}
