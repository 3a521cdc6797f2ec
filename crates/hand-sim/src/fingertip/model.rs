//! The fingertip as a scene model: three MS5611 chip models on one SPI bus (a chip select
//! each), read by the real `baro-drivers` scheduler, their true pressures from
//! [`FingertipPhysics`].

use super::contact::ContactPatch;
use super::geometry::{Cell, CellSet, SENSORS};
use super::law::LawParams;
use super::physics::FingertipPhysics;
use crate::SimError;
use crate::scene::Model;
use baro_drivers::sim::{Conditions, Environment, Ms5611Sim};
use baro_drivers::{Measurement, Ms5611, Osr, Ready, Scheduler, SpiInterface};
use hand_traits::{PressureFrame, TactileSource};
use rand::Rng;
use serde::Deserialize;
use sim_clock::SimClock;
use std::cell::{RefCell, RefMut};
use std::rc::Rc;

/// The `[fingertip]` table of a scene file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingertipConfig {
    /// MS5611 oversampling ratio: 256, 512, 1024, 2048 or 4096 (the speed / noise knob).
    #[serde(default = "default_osr")]
    pub osr: u16,
    /// Resting pressure, hPa; each sensor adds its own random decimals (seed 000 §4: "1010.xx").
    #[serde(default = "default_baseline")]
    pub baseline_hpa: f64,
    /// Slow upward drift of the bias, hPa per minute (§4 reports drift, not its rate: assumed).
    #[serde(default = "default_drift")]
    pub drift_hpa_per_min: f64,
    /// Pad temperature, °C.
    #[serde(default = "default_temperature")]
    pub temperature_c: f64,
    /// Taps to apply, in any order; they must not overlap.
    #[serde(default)]
    pub taps: Vec<TapConfig>,
}

/// One press of a rectangle of cells.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TapConfig {
    /// When the press starts, s.
    pub at_s: f64,
    /// How long it is held, s.
    pub hold_s: f64,
    /// Top-left cell's row, 1…4.
    pub row: u8,
    /// Top-left cell's column, 1…6.
    pub col: u8,
    /// Rectangle height in cells.
    #[serde(default = "one")]
    pub rows: u8,
    /// Rectangle width in cells.
    #[serde(default = "one")]
    pub cols: u8,
    /// Total force, kgf (Table 2 uses 5, 7, 9).
    pub force_kgf: f64,
    /// Shift of the whole press off its cells (x right, y up), mm: at most half a cell
    /// (1.5 mm) each way; default none.
    #[serde(default)]
    pub offset_mm: [f64; 2],
}

fn default_osr() -> u16 {
    4096
}
fn default_baseline() -> f64 {
    1010.0
}
fn default_drift() -> f64 {
    0.1
}
fn default_temperature() -> f64 {
    25.0
}
fn one() -> u8 {
    1
}

impl Default for FingertipConfig {
    fn default() -> Self {
        Self {
            osr: default_osr(),
            baseline_hpa: default_baseline(),
            drift_hpa_per_min: default_drift(),
            temperature_c: default_temperature(),
            taps: Vec::new(),
        }
    }
}

impl TapConfig {
    /// The tap's cells, or a config error naming what is off the pad.
    pub fn cells(&self) -> Result<CellSet, SimError> {
        if Cell::new(self.row, self.col).is_none() {
            return Err(SimError::config("taps.row/col", "row 1…4, col 1…6"));
        }
        // `None` for an empty rectangle too.
        CellSet::rect(self.row, self.col, self.rows, self.cols).ok_or_else(|| {
            SimError::config(
                "taps.rows/cols",
                "a rectangle of at least one cell inside the 4 × 6 pad",
            )
        })
    }
}

/// The OSR of a ratio, or a config error listing the allowed ones.
pub fn osr_from_ratio(ratio: u16) -> Result<Osr, SimError> {
    Osr::from_ratio(ratio)
        .ok_or_else(|| SimError::config("osr", "one of 256, 512, 1024, 2048, 4096"))
}

/// What one chip model measures: its sensor's true pressure from the shared physics.
#[derive(Debug)]
pub struct SensorEnv {
    physics: Rc<RefCell<FingertipPhysics>>,
    sensor: usize,
    temperature_c: f64,
}

impl Environment for SensorEnv {
    fn conditions(&mut self, now_ns: u64) -> Conditions {
        Conditions {
            pressure_mbar: self.physics.borrow_mut().pressure_hpa(self.sensor, now_ns),
            temperature_celsius: self.temperature_c,
        }
    }
}

type Sensor = Ms5611<SpiInterface<Ms5611Sim<SensorEnv>>, Ready>;

/// The simulated fingertip: physics, three chips, the driver's scheduler and a frame log.
#[derive(Debug)]
pub struct Fingertip {
    physics: Rc<RefCell<FingertipPhysics>>,
    sensors: Vec<Sensor>,
    clock: SimClock,
    scheduler: Scheduler,
    frames: Vec<PressureFrame<SENSORS>>,
    /// Whether `read_frame` appends to `frames` (off for endless control loops).
    keep_frames: bool,
    steps: u64,
}

impl Fingertip {
    /// Builds the fingertip `config` describes, its randomness from `seed`.
    pub fn new(config: &FingertipConfig, seed: u64) -> Result<Fingertip, SimError> {
        Self::with_law(config, LawParams::CALIBRATED, seed)
    }

    /// As [`new`](Self::new) with another law (for sensitivity studies).
    pub fn with_law(
        config: &FingertipConfig,
        law: LawParams,
        seed: u64,
    ) -> Result<Fingertip, SimError> {
        let osr = osr_from_ratio(config.osr)?;
        if !(-40.0..=85.0).contains(&config.temperature_c) {
            return Err(SimError::config(
                "temperature_c",
                "within the MS5611's −40…85 °C",
            ));
        }
        let mut rng = crate::seed::stream(seed, "fingertip");
        let baseline: [f64; SENSORS] =
            core::array::from_fn(|_| config.baseline_hpa + rng.random::<f64>());
        let mut physics = FingertipPhysics::new(law, baseline, config.drift_hpa_per_min)?;
        for (t_ns, patch) in tap_timeline(&config.taps)? {
            physics.set_contact(t_ns, patch)?;
        }
        let physics = Rc::new(RefCell::new(physics));
        let clock = SimClock::new();
        let mut sensors = Vec::with_capacity(SENSORS);
        for sensor in 0..SENSORS {
            let env = SensorEnv {
                physics: Rc::clone(&physics),
                sensor,
                temperature_c: config.temperature_c,
            };
            // Nothing reads the chips' command logs here: off, so the heap stays flat.
            let chip = Ms5611Sim::new(env, clock.clone())
                .with_seed(crate::seed::derive(
                    seed,
                    &format!("fingertip/ms5611/{sensor}"),
                ))
                .with_command_log(false);
            let ready = Ms5611::new_with_spi(chip)
                .init(&mut clock.delay())
                .map_err(|e| driver_error(e.error))?;
            sensors.push(ready);
        }
        Ok(Fingertip {
            physics,
            sensors,
            clock,
            scheduler: Scheduler::new(osr),
            frames: Vec::new(),
            keep_frames: true,
            steps: 0,
        })
    }

    /// The physics behind the chips: to press or release the pad from a control loop.
    pub fn physics(&self) -> RefMut<'_, FingertipPhysics> {
        self.physics.borrow_mut()
    }

    /// Presses the pad with `patch` from now on (or releases it with [`ContactPatch::NONE`]).
    pub fn set_contact(&mut self, patch: ContactPatch) -> Result<(), SimError> {
        let now = self.clock.now_ns();
        self.physics.borrow_mut().set_contact(now, patch)
    }

    /// The clock the chips run on (a clone sharing its counter): a loop that waits on it, or
    /// steps other simulated devices to it, keeps one time with the fingertip.
    pub fn clock(&self) -> SimClock {
        self.clock.clone()
    }

    /// The bus clock, ns of simulated time.
    pub fn now_ns(&self) -> u64 {
        self.clock.now_ns()
    }

    /// Lets the bus idle until `t_ns` (no conversion, no frame): a control loop waiting for its
    /// next tick. An earlier time changes nothing.
    pub fn idle_until_ns(&mut self, t_ns: u64) {
        self.clock.advance_to_ns(t_ns);
    }

    /// Keeps every frame read for [`frames`](Self::frames) (the default), or not: a control
    /// loop that runs indefinitely turns the log off so reading a frame never allocates.
    pub fn set_frame_log(&mut self, keep: bool) {
        self.keep_frames = keep;
    }

    /// Every frame read so far (while the frame log was on).
    pub fn frames(&self) -> &[PressureFrame<SENSORS>] {
        &self.frames
    }

    /// The configured oversampling ratio.
    pub fn osr(&self) -> Osr {
        self.scheduler.osr()
    }
}

impl TactileSource for Fingertip {
    type Frame = PressureFrame<SENSORS>;
    type Error = SimError;

    /// One scheduler cycle over the three sensors (2 × the OSR's conversion time), decoded by
    /// the real driver; the frame is stamped when the cycle ends and also kept in the log.
    fn read_frame(&mut self) -> Result<PressureFrame<SENSORS>, SimError> {
        let mut out = [Measurement {
            temperature_centi_celsius: 0,
            pressure_pa: 0,
        }; SENSORS];
        let mut delay = self.clock.delay();
        self.scheduler
            .sample_all(&mut self.sensors, &mut delay, &mut out)
            .map_err(|e| driver_error(e.error))?;
        self.steps += 1;
        let frame = PressureFrame {
            t_us: self.clock.now_ns() / 1000,
            pressure_pa: out.map(|m| m.pressure_pa as f32),
        };
        if self.keep_frames {
            self.frames.push(frame);
        }
        Ok(frame)
    }
}

impl Model for Fingertip {
    const NAME: &'static str = "fingertip";

    fn step_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        while self.clock.now_ns() < t_ns {
            self.read_frame()?;
        }
        Ok(())
    }

    fn steps(&self) -> u64 {
        self.steps
    }
}

fn driver_error(e: impl core::fmt::Debug) -> SimError {
    SimError::Driver {
        model: "fingertip",
        detail: format!("{e:?}"),
    }
}

/// Taps as a time-ordered list of contact changes; overlapping taps are a config error.
fn tap_timeline(taps: &[TapConfig]) -> Result<Vec<(u64, ContactPatch)>, SimError> {
    let mut spans = Vec::with_capacity(taps.len());
    for tap in taps {
        let ok = |v: f64| (0.0..1e6).contains(&v);
        if !ok(tap.at_s) || !ok(tap.hold_s) || !ok(tap.force_kgf) {
            return Err(SimError::config(
                "taps",
                "at_s, hold_s and force_kgf finite, ≥ 0",
            ));
        }
        if !super::contact::offset_in_range(tap.offset_mm) {
            return Err(SimError::config(
                "taps.offset_mm",
                "at most half a cell (1.5 mm) each way",
            ));
        }
        let start = (tap.at_s * 1e9) as u64;
        let end = start + (tap.hold_s * 1e9) as u64;
        spans.push((
            start,
            end,
            ContactPatch::from_kgf(tap.cells()?, tap.force_kgf).shifted(tap.offset_mm),
        ));
    }
    spans.sort_by_key(|s| s.0);
    let mut timeline = Vec::with_capacity(2 * spans.len());
    for (i, &(start, end, patch)) in spans.iter().enumerate() {
        if i > 0 && start < spans[i - 1].1 {
            return Err(SimError::config("taps", "taps overlap in time"));
        }
        timeline.push((start, patch));
        timeline.push((end, ContactPatch::NONE));
    }
    Ok(timeline)
}
