//! [`ImuPad`]: the pad's truth fed to the ICM-20789 chip model and read back, 30 times a
//! second, by the real `imu-icm20789` driver over the model's I2C bus.

use std::collections::VecDeque;

use crate::SimError;
use crate::imu_pad::config::{ImuPadConfig, TapTiming};
use crate::imu_pad::tap::{PadTruth, RealisedTap};
use crate::scene::Model;
use crate::seed;
use hand_traits::{ImuFrame, TactileSource};
use imu_icm20789::sim::ChipModel;
use imu_icm20789::{AccelScale, BaroMode, GyroDlpf, GyroScale, Icm20789, ImuSettings};
use rand::Rng;
use sim_clock::SimDelay;

/// The IMU settings the simulated pad's chip is read with (seed 002 names none; ours): ±2 g
/// and ±250 °/s, the finest scales, since a 0.2–1.6 mm tap moves the pad by far less than
/// either; a 41 Hz gyro low-pass, above the 30 Hz frame rate's 15 Hz Nyquist band and well
/// below the 1 kHz output rate. Every pad dataset was recorded with them; `handstack` reads a
/// real pad with its own (`handstack::stack::pad::IMU_SETTINGS`), which paper-scenes' tests
/// hold equal to these.
pub const IMU_SETTINGS: ImuSettings = ImuSettings {
    accel_scale: AccelScale::G2,
    gyro_scale: GyroScale::Dps250,
    gyro_dlpf: GyroDlpf::Hz41,
};

/// The ICM-20789 pad of seed 002: taps on a 3 × 24 grid, read through the chip model.
///
/// ```
/// use hand_sim::imu_pad::{ImuPad, ImuPadConfig};
/// use hand_sim::scene::Model;
/// let mut pad = ImuPad::new(&ImuPadConfig::default(), 7)?;
/// pad.step_to(4_000_000_000)?; // the default 1.2 mm tap on the chip, start to end
/// let frames = pad.drain_frames();
/// assert!(frames.len() >= 115); // 30 Hz
/// let peak = frames.iter().filter_map(|f| f.pressure_pa).fold(f32::MIN, f32::max);
/// assert!(peak > 101_325.0 + 300.0); // hundreds of counts at 1.2 mm on the chip
/// # Ok::<(), hand_sim::SimError>(())
/// ```
#[derive(Debug)]
pub struct ImuPad {
    driver: Icm20789<ChipModel>,
    delay: SimDelay,
    truth: PadTruth,
    mode: BaroMode,
    period_ns: u64,
    next_sample: u64,
    max_samples_per_step: u64,
    buffer_frames: usize,
    frames: VecDeque<ImuFrame>,
    dropped: u64,
    steps: u64,
    timing: TapTiming,
}

fn driver_error(e: impl core::fmt::Debug) -> SimError {
    SimError::Driver {
        model: ImuPad::NAME,
        detail: format!("{e:?}"),
    }
}

impl ImuPad {
    /// Builds the pad of `config` in a scene seeded with `scene_seed`: realises every tap
    /// (stream `"imu_pad"`), makes the chip model, and initialises it through the driver
    /// (IMU reset, [`IMU_SETTINGS`]; barometer ID and OTP).
    pub fn new(config: &ImuPadConfig, scene_seed: u64) -> Result<ImuPad, SimError> {
        config.validate()?;
        let curve = config.mechanics.curve()?;
        let mut rng = seed::stream(scene_seed, Self::NAME);
        let chip_seed: u64 = rng.random();
        let taps = config
            .taps
            .iter()
            .enumerate()
            .map(|(i, spec)| RealisedTap::realise(spec, i, config, &curve, &mut rng))
            .collect::<Result<Vec<_>, _>>()?;
        let truth = PadTruth::new(taps, config);
        let env = truth.clone();
        let chip = ChipModel::new(move |t_us| env.state(t_us), chip_seed);
        let mut delay = chip.delay();
        let mut driver = Icm20789::new_with_i2c(chip);
        driver.init(&mut delay).map_err(driver_error)?;
        driver.configure_imu(&IMU_SETTINGS).map_err(driver_error)?;
        driver.init_barometer(&mut delay).map_err(driver_error)?;
        let period_ns = (1e9 / config.sample_rate_hz).round() as u64;
        let now = delay.clock().now_ns();
        Ok(ImuPad {
            driver,
            delay,
            truth,
            mode: config.baro_mode,
            period_ns,
            next_sample: now.div_ceil(period_ns),
            max_samples_per_step: config.max_samples_per_step,
            buffer_frames: config.buffer_frames,
            frames: VecDeque::new(),
            dropped: 0,
            steps: 0,
            timing: config.timing,
        })
    }

    /// The taps' timing (lead, press, hold, release), as configured.
    pub fn timing(&self) -> TapTiming {
        self.timing
    }

    /// The realised taps (nominal and actual depth, position, force, counts, IMU amplitudes).
    pub fn taps(&self) -> &[RealisedTap] {
        self.truth.taps()
    }

    /// Time between frames, ns.
    pub fn period_ns(&self) -> u64 {
        self.period_ns
    }

    /// When the next frame will be read, ns.
    pub fn next_sample_ns(&self) -> u64 {
        self.next_sample.saturating_mul(self.period_ns)
    }

    /// Takes the frames read so far.
    pub fn drain_frames(&mut self) -> Vec<ImuFrame> {
        self.frames.drain(..).collect()
    }

    /// Frames dropped because nobody read them before the buffer filled.
    pub fn dropped_frames(&self) -> u64 {
        self.dropped
    }

    /// Lets the chip's clock run until `t_ns` (the host idles between frames).
    fn wait_until(&self, t_ns: u64) {
        self.delay.clock().advance_to_ns(t_ns);
    }

    /// One frame at sample time `t_ns`, read as the driver reads a pad
    /// ([`Icm20789::read_frame`]: the IMU burst during a Low Noise conversion, as the paper's
    /// Arduino read it).
    fn sample(&mut self, t_ns: u64) -> Result<ImuFrame, SimError> {
        self.wait_until(t_ns);
        let f = self
            .driver
            .read_frame(self.mode, &mut self.delay)
            .map_err(driver_error)?;
        Ok(ImuFrame {
            t_us: t_ns / 1_000,
            accel_mps2: f.imu.accel_mps2,
            gyro_rps: f.imu.gyro_rps,
            pressure_pa: Some(f.baro.pressure_pa),
        })
    }

    fn push(&mut self, frame: ImuFrame) {
        if self.frames.len() >= self.buffer_frames {
            self.frames.pop_front();
            self.dropped += 1;
        }
        self.frames.push_back(frame);
    }
}

impl Model for ImuPad {
    const NAME: &'static str = "imu_pad";

    /// Reads every frame due up to `t_ns`; a step needing more than `max_samples_per_step`
    /// frames is refused (nothing read) with a [`SimError::Config`].
    fn step_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        let due = (t_ns / self.period_ns + 1).saturating_sub(self.next_sample);
        if due > self.max_samples_per_step {
            return Err(SimError::config(
                "max_samples_per_step",
                format!("a step to {t_ns} ns needs {due} frames"),
            ));
        }
        for _ in 0..due {
            let t = self.next_sample_ns();
            let frame = self.sample(t)?;
            self.push(frame);
            self.next_sample += 1;
            self.steps += 1;
        }
        Ok(())
    }

    fn steps(&self) -> u64 {
        self.steps
    }
}

impl TactileSource for ImuPad {
    type Frame = ImuFrame;
    type Error = SimError;

    /// The oldest unread frame, reading the next one from the chip if none is waiting.
    fn read_frame(&mut self) -> Result<ImuFrame, SimError> {
        if self.frames.is_empty() {
            let t = self.next_sample_ns();
            self.step_to(t)?;
        }
        self.frames
            .pop_front()
            .ok_or_else(|| SimError::config("imu_pad", "no frame due"))
    }
}
