//! One fingertip's cycle: read → tare / estimate → force → contact → grasp torque.

use aot_locate::{AotError, AotLocator, AreaGrid, DetectorConfig, Geometry};
use baro_drivers::{Measurement, Ms5611, Osr, Ready, SampleError, Scheduler, Transport, Uninit};
use embedded_hal::delay::DelayNs;
use fuzzy_mamdani::{EvalError, GraspController};
use hand_traits::{ContactLocator, EstimateError, GraspPolicy, PressureEstimator, PressureFrame};
use tactile_nets::RunError;
use tactile_nets::contact_mlp::{LiveTap, features};
#[cfg(not(feature = "fixed-point"))]
use tactile_nets::pretrained::{CONTACT_MLP_OSR1024, FORCE_DNN_SIM};
#[cfg(feature = "fixed-point")]
use tactile_nets::pretrained::{FIXED_CONTACT_MLP_OSR1024, FIXED_FORCE_DNN_SIM};

/// MS5611s per fingertip (seed 000 §2).
pub const SENSORS: usize = 3;

/// The board's pad: 4 × 6 cells of 3 mm, 18 × 12 mm. The paper gives no dimensions; this is
/// the simulated fingertip's pad (`hand_sim::fingertip::geometry::PAD`), the one the built-in
/// contact MLP was trained on, so a fingertip is built to it. The host harness
/// (`examples/host_cycles.rs`) fails if the two differ.
pub const PAD: AreaGrid = AreaGrid {
    width_mm: 18.0,
    height_mm: 12.0,
};

/// Where the board's three MS5611 sit under [`PAD`], mm from its centre (x right, y up):
/// sensor 1 top right, sensor 2 bottom centre, sensor 3 top left, an inverted triangle; the
/// simulated fingertip's (`hand_sim::fingertip::geometry::AOT_SENSORS_MM`), checked by the
/// host harness like [`PAD`].
pub const SENSORS_MM: [[f32; 2]; SENSORS] = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];

/// The oversampling ratio: two conversions of 2.28 ms per cycle for all three sensors, and the
/// OSR of the contact MLP built in below.
pub const OSR: Osr = Osr::Osr1024;

/// The contact MLP trained on taps read at [`OSR`]: naming its static links its weights alone
/// (13.6 KiB) rather than all five OSRs'. With `fixed-point` (the Cortex-M3 boards: no FPU),
/// its fixed-point form, as is the force DNN's.
#[cfg(not(feature = "fixed-point"))]
static CONTACT_MLP: &ContactModel = &CONTACT_MLP_OSR1024;
#[cfg(feature = "fixed-point")]
static CONTACT_MLP: &ContactModel = &FIXED_CONTACT_MLP_OSR1024;

/// The force DNN trained on hand-sim's weight series (in fixed point with `fixed-point`).
#[cfg(not(feature = "fixed-point"))]
static FORCE_DNN: &ForceModel = &FORCE_DNN_SIM;
#[cfg(feature = "fixed-point")]
static FORCE_DNN: &ForceModel = &FIXED_FORCE_DNN_SIM;

#[cfg(not(feature = "fixed-point"))]
type ContactModel = tactile_nets::contact_mlp::StaticContactMlp;
#[cfg(feature = "fixed-point")]
type ContactModel = tactile_nets::fixed::FixedContactMlp;
#[cfg(not(feature = "fixed-point"))]
type ForceModel = tactile_nets::force_dnn::StaticForceDnn;
#[cfg(feature = "fixed-point")]
type ForceModel = tactile_nets::fixed::FixedForceDnn;

/// What a fingertip is set up with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// Untouched cycles averaged into the zero before anything is estimated.
    pub tare_frames: u32,
    /// The contact pressure the grasp holds, Pa over the zero.
    pub target_pa: f32,
    /// Mean rise above which the pad counts as touched, Pa.
    pub contact_threshold_pa: f32,
    /// Cut-off of the pressure rate's low-pass, Hz.
    pub rate_cutoff_hz: f32,
}

impl Config {
    /// The host grasp loop's defaults (`hand_control::grasp_loop::LoopConfig::new`) for
    /// target, threshold and rate filter.
    pub const DEFAULT: Config = Config {
        tare_frames: 30,
        target_pa: 500.0,
        contact_threshold_pa: 50.0,
        rate_cutoff_hz: 2.0,
    };
}

impl Default for Config {
    fn default() -> Self {
        Config::DEFAULT
    }
}

/// Why a cycle (or the start-up) failed. The board sends a fault frame with the safe torque 0.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Error<E> {
    /// A sensor failed on the bus, its PROM or its conversion (which sensor is inside).
    Sensor(SampleError<E>),
    /// A frame could not be estimated (a non-finite pressure, a stale time stamp).
    Estimate(EstimateError),
    /// The force DNN or the contact MLP refused its input.
    Net(RunError),
    /// Arrival-of-Time refused its event.
    Locate(AotError),
    /// The fuzzy controller failed.
    Grasp(EvalError),
}

impl<E> From<EstimateError> for Error<E> {
    fn from(e: EstimateError) -> Self {
        Error::Estimate(e)
    }
}

impl<E> From<RunError> for Error<E> {
    fn from(e: RunError) -> Self {
        Error::Net(e)
    }
}

/// One cycle's results (what [`crate::frame::encode`] sends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The cycle's time stamp, µs.
    pub t_us: u64,
    /// The three compensated pressures, Pa.
    pub pressure_pa: [i32; SENSORS],
    /// Whether the zero is tared; until then nothing below is estimated and the torque is 0.
    pub tared: bool,
    /// Whether the mean rise is above the contact threshold.
    pub in_contact: bool,
    /// The force DNN's estimate, gf.
    pub force_gf: Option<f32>,
    /// Arrival-of-Time's cell on the 3 × 3 grid, once a contact has arrived.
    pub grid_cell: Option<u8>,
    /// The contact MLP's cell on the 4 × 6 pad, once a contact has arrived.
    pub pad_cell: Option<u8>,
    /// The grasp torque limit, MX-28 counts.
    pub torque_raw: u16,
}

/// The pipeline over three MS5611 on transport `DI` (I2C behind a TCA9548A, or SPI).
pub struct Fingertip<DI> {
    sensors: [Ms5611<DI, Ready>; SENSORS],
    scheduler: Scheduler,
    read: [Measurement; SENSORS],
    config: Config,
    tare_left: u32,
    estimator: PressureEstimator<SENSORS>,
    live: LiveTap,
    aot: AotLocator,
    force: &'static ForceModel,
    mlp: &'static ContactModel,
    grasp: GraspController,
}

impl<DI, E> Fingertip<DI>
where
    DI: Transport<Error = E>,
{
    /// Resets each sensor and checks its PROM, then builds the estimators (allocating nothing);
    /// Arrival-of-Time locates on `pad` (the
    /// board's: [`SENSORS_MM`] over [`PAD`]).
    pub fn new<D: DelayNs>(
        sensors: [Ms5611<DI, Uninit>; SENSORS],
        delay: &mut D,
        config: Config,
        pad: Geometry,
    ) -> Result<Self, Error<E>> {
        let [a, b, c] = sensors;
        let init = |s: Ms5611<DI, Uninit>, sensor, delay: &mut D| {
            s.init(delay).map_err(|e| {
                Error::Sensor(SampleError {
                    sensor,
                    error: e.error,
                })
            })
        };
        let sensors = [init(a, 0, delay)?, init(b, 1, delay)?, init(c, 2, delay)?];
        Ok(Fingertip {
            sensors,
            scheduler: Scheduler::new(OSR),
            read: [Measurement {
                temperature_centi_celsius: 0,
                pressure_pa: 0,
            }; SENSORS],
            config,
            tare_left: config.tare_frames.max(1),
            estimator: PressureEstimator::new(config.contact_threshold_pa, config.rate_cutoff_hz),
            live: LiveTap::new(DetectorConfig::DEFAULT),
            aot: AotLocator::new(pad),
            force: FORCE_DNN,
            mlp: CONTACT_MLP,
            grasp: fuzzy_mamdani::grasp_controller(),
        })
    }

    /// The shortest cycle the conversions allow, ns (two conversion times at the OSR).
    pub fn cycle_bound_ns(&self) -> u64 {
        self.scheduler.cycle_bound_ns()
    }

    /// One cycle stamped `t_us` (strictly increasing): [`sample`](Self::sample) the three
    /// sensors, then [`estimate`](Self::estimate). On an error the caller sends
    /// [`crate::frame::fault`], the safe torque 0.
    pub fn cycle<D: DelayNs>(&mut self, delay: &mut D, t_us: u64) -> Result<Estimate, Error<E>> {
        let pressure_pa = self.sample(delay)?;
        self.estimate(t_us, pressure_pa)
    }

    /// The bus half of a cycle: the three compensated pressures, Pa (two conversion times).
    pub fn sample<D: DelayNs>(&mut self, delay: &mut D) -> Result<[i32; SENSORS], Error<E>> {
        self.scheduler
            .sample_all(&mut self.sensors, delay, &mut self.read)
            .map_err(Error::Sensor)?;
        Ok(self.read.map(|m| m.pressure_pa))
    }

    /// The compute half of a cycle, on pressures read at `t_us`: tare, force, contact, torque.
    /// Not inlined, so that an instruction counter can collect exactly this work.
    #[inline(never)]
    pub fn estimate(
        &mut self,
        t_us: u64,
        pressure_pa: [i32; SENSORS],
    ) -> Result<Estimate, Error<E>> {
        // Exact: pressures up to 120 000 Pa are integers below f32's 2^24.
        let frame = PressureFrame {
            t_us,
            pressure_pa: pressure_pa.map(|p| p as f32),
        };
        // Every frame, tared or not: a host given the frames rebuilds the same inputs.
        let contact = self.live.push(t_us as i64, frame.pressure_pa);
        let mut out = Estimate {
            t_us,
            pressure_pa,
            tared: false,
            in_contact: false,
            force_gf: None,
            grid_cell: None,
            pad_cell: None,
            torque_raw: 0,
        };
        if self.tare_left > 0 {
            self.estimator.tare(&frame)?;
            self.tare_left -= 1;
            if self.tare_left == 0 {
                self.estimator.finish_tare()?;
            }
            return Ok(out);
        }
        let pressure = self.estimator.update(&frame)?;
        let zero = self.estimator.zero_pa().ok_or(EstimateError::NotTared)?;
        let rise_hpa: [f32; SENSORS] =
            core::array::from_fn(|k| ((f64::from(frame.pressure_pa[k]) - zero[k]) / 100.0) as f32);
        out.tared = true;
        out.in_contact = pressure.in_contact;
        out.force_gf = Some(self.force.estimate_gf(&rise_hpa)?);
        if let Some((onset, reading)) = contact {
            let event = self.live.detector().event(onset, frame.pressure_pa);
            let grid = self.aot.locate(&event).map_err(Error::Locate)?;
            let pad = self.mlp.predict(&features(&reading))?;
            out.grid_cell = u8::try_from(grid.region).ok();
            out.pad_cell = u8::try_from(pad.region).ok();
        }
        let effort = self
            .grasp
            .effort(&pressure.observation(self.config.target_pa))
            .map_err(Error::Grasp)?;
        out.torque_raw = effort.to_torque_limit_raw();
        Ok(out)
    }

    /// Hands the three sensors (and their buses) back.
    pub fn destroy(self) -> [Ms5611<DI, Ready>; SENSORS] {
        self.sensors
    }
}
