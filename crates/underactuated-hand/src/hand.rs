//! The hand on a Firmata board: the stepper (AccelStepperFirmata) and the eight analog inputs.

use std::time::{Duration, Instant};

use firmata_host::{Board, ErrorKind, Options, StepperConfig};
use hand_traits::FingerFrame;

use crate::calibration::Calibration;
use crate::error::HandError;
use crate::wiring::{Drive, Wiring};

/// How far ahead of where it should be a closing stepper's target is kept, in time at the
/// closing speed: the move is leased, renewed as readings are taken, so a host that dies or a
/// link that drops leaves the stepper running for at most this long, never to its end stop.
pub const LEASE: Duration = Duration::from_millis(500);
/// How often a closing move's lease is renewed.
const RENEW_EVERY: Duration = Duration::from_millis(100);

/// A close under way: from where, since when, how fast.
#[derive(Debug, Clone, Copy)]
struct Closing {
    from_steps: i32,
    since: Instant,
    steps_per_s: f64,
    renewed: Instant,
}

impl Closing {
    /// The target that keeps the stepper at speed for [`LEASE`] from now.
    fn target(&self, now: Instant) -> i32 {
        let ahead = (now.saturating_duration_since(self.since) + LEASE).as_secs_f64();
        let steps = f64::from(self.from_steps) + self.steps_per_s * ahead;
        steps.clamp(-268_435_455.0, 268_435_455.0) as i32
    }
}

/// Everything the hand needs to open.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HandConfig {
    /// Which pin is which part.
    pub wiring: Wiring,
    /// Counts to newtons and degrees.
    pub calibration: Calibration,
    /// Steps to tendon.
    pub drive: Drive,
    /// The board's analog sampling interval, ms (0: leave the firmware's, 19 ms).
    pub sampling_ms: u16,
    /// The serial link: baud rate (57 600 by default), the wait for the reset, reply timeout.
    pub board: Options,
}

impl HandConfig {
    /// What is wrong with it, if anything.
    pub fn check(&self) -> Result<(), HandError> {
        let setup = |e: &str| HandError::Setup(e.to_owned());
        self.wiring.check().map_err(|e| setup(&e))?;
        self.calibration.check().map_err(setup)?;
        self.drive.check().map_err(setup)?;
        Ok(())
    }
}

/// One reading of the eight inputs, calibrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// When the newest of the eight reports arrived, µs since the hand was opened.
    pub t_us: u64,
    /// The raw codes: FSRs 1–4, then potentiometers 1–4.
    pub codes: [u16; 8],
    /// Forces, N, then distal angles, degrees (the softness classifier's order).
    pub sample: [f32; 8],
}

impl Reading {
    /// As hand-traits' finger frame (angles in radians).
    pub fn frame(&self) -> FingerFrame<4> {
        FingerFrame {
            t_us: self.t_us,
            force_n: core::array::from_fn(|i| self.sample[i]),
            distal_angle_rad: core::array::from_fn(|i| self.sample[4 + i].to_radians()),
        }
    }
}

/// The hand on its board: opened, the stepper configured and zeroed where the hand is, the
/// eight inputs reporting.
///
/// Dropping it stops the stepper where it is (its outputs stay as they were: a program chooses
/// to release or disable through [`open_fully`](Self::open_fully) and
/// [`disable`](Self::disable) before). A close is leased ([`LEASE`]), so even a host that dies
/// without dropping it leaves the stepper running for at most half a second.
///
/// ```no_run
/// use underactuated_hand::{HandConfig, UnderactuatedHand};
/// use std::time::Duration;
///
/// let mut hand = UnderactuatedHand::open("/dev/ttyACM0", &HandConfig::default())?;
/// hand.close_at(1.5)?; // mm/s of tendon, open loop
/// while let Some(r) = hand.next_reading(Duration::from_millis(100))? {
///     if r.sample[..4].iter().any(|f| *f > 0.1) {
///         break; // first contact
///     }
/// }
/// hand.stop()?;
/// hand.open_fully(Duration::from_secs(30))?;
/// hand.disable()?;
/// # Ok::<(), underactuated_hand::HandError>(())
/// ```
#[derive(Debug)]
pub struct UnderactuatedHand {
    board: Board,
    config: HandConfig,
    epoch: Instant,
    version_reports: u64,
    last: Option<Instant>,
    stopped: bool,
    closing: Option<Closing>,
}

impl UnderactuatedHand {
    /// Opens the board on `port` (through its reset), configures the stepper on the wiring's
    /// pins at constant speed (no acceleration ramp: the paper's open-loop close), takes the
    /// hand's present position as zero (open), and enables the eight analog reports.
    ///
    /// # Errors
    /// [`HandError::Setup`] for a bad configuration (before the port is opened); the board's
    /// errors; [`HandError::NoSteppers`] when the firmware has no AccelStepperFirmata.
    pub fn open(port: &str, config: &HandConfig) -> Result<UnderactuatedHand, HandError> {
        config.check()?;
        let mut board = Board::open(port, &config.board)?;
        let w = config.wiring;
        let device = w.stepper_device;
        board.stepper_config(device, &StepperConfig::driver(w.step_pin, w.dir_pin))?;
        // A firmware without steppers ignores the messages: the position query tells.
        match board.stepper_position(device) {
            Ok(_) => {}
            Err(e)
                if matches!(
                    e.kind,
                    ErrorKind::Timeout { .. } | ErrorKind::Refused { .. }
                ) =>
            {
                return Err(HandError::NoSteppers {
                    port: port.to_owned(),
                    firmware: board.firmware().map_or_else(
                        || "unnamed".to_owned(),
                        |f| format!("{} {}.{}", f.name, f.major, f.minor),
                    ),
                });
            }
            Err(e) => return Err(e.into()),
        }
        board.stepper_set_acceleration(device, 0.0)?;
        board.stepper_zero(device)?;
        if config.sampling_ms > 0 {
            board.set_sampling_interval(config.sampling_ms)?;
        }
        for ch in w.channels() {
            board.enable_analog(ch)?;
        }
        Ok(UnderactuatedHand {
            version_reports: board.version_reports(),
            board,
            config: config.clone(),
            epoch: Instant::now(),
            last: None,
            stopped: true,
            closing: None,
        })
    }

    /// Starts closing at `mm_s` of tendon, constant speed, until [`stop`](Self::stop). The
    /// move is leased ([`LEASE`]): [`next_reading`](Self::next_reading) renews it, so the
    /// stepper stops on its own within half a second of the host's last reading.
    pub fn close_at(&mut self, mm_s: f64) -> Result<(), HandError> {
        let device = self.config.wiring.stepper_device;
        let steps_per_s = self.config.drive.steps_per_s(mm_s);
        let from_steps = self.board.stepper_position(device)?;
        self.board.stepper_set_speed(device, steps_per_s as f32)?;
        let now = Instant::now();
        let closing = Closing {
            from_steps,
            since: now,
            steps_per_s,
            renewed: now,
        };
        self.board.stepper_to(device, closing.target(now))?;
        self.closing = Some(closing);
        self.stopped = false;
        Ok(())
    }

    /// Renews a close's lease when it is due.
    fn renew(&mut self) -> Result<(), HandError> {
        let now = Instant::now();
        if let Some(c) = self.closing.as_mut() {
            if now.saturating_duration_since(c.renewed) >= RENEW_EVERY {
                c.renewed = now;
                let target = c.target(now);
                self.board
                    .stepper_to(self.config.wiring.stepper_device, target)?;
            }
        }
        Ok(())
    }

    /// Stops the stepper where it is (its outputs stay enabled: the hand holds); the position,
    /// steps from open.
    pub fn stop(&mut self) -> Result<i32, HandError> {
        self.closing = None;
        let at = self.board.stepper_stop(self.config.wiring.stepper_device)?;
        self.stopped = true;
        Ok(at)
    }

    /// Microseconds since the hand was opened: the clock of its readings.
    pub fn now_us(&self) -> u64 {
        self.epoch.elapsed().as_micros() as u64
    }

    /// Runs the stepper back to open (position 0) at the speed last set and waits, up to
    /// `timeout`, until it is there.
    pub fn open_fully(&mut self, timeout: Duration) -> Result<i32, HandError> {
        self.closing = None;
        let device = self.config.wiring.stepper_device;
        let mark = self.board.mark();
        self.board.stepper_to(device, 0)?;
        self.stopped = false;
        let at = self.board.wait_stepper_complete(device, mark, timeout)?;
        self.stopped = true;
        Ok(at)
    }

    /// Sets the opening speed used by [`open_fully`](Self::open_fully), mm/s.
    pub fn set_speed(&mut self, mm_s: f64) -> Result<(), HandError> {
        let steps_per_s = self.config.drive.steps_per_s(mm_s) as f32;
        self.board
            .stepper_set_speed(self.config.wiring.stepper_device, steps_per_s)?;
        Ok(())
    }

    /// Disables the driver's outputs: the motor no longer holds the tendon.
    pub fn disable(&mut self) -> Result<(), HandError> {
        self.board
            .stepper_enable(self.config.wiring.stepper_device, false)?;
        Ok(())
    }

    /// The stepper's position as the board last reported it, steps from open.
    pub fn position(&self) -> Option<i32> {
        self.board
            .stepper_last_position(self.config.wiring.stepper_device)
    }

    /// Waits up to `timeout` for reports, then gives the eight inputs' newest values when any
    /// is newer than the last reading given (`None`: nothing new in time). A close's lease is
    /// renewed meanwhile.
    ///
    /// # Errors
    /// The board's errors (a hang-up, an I/O error); [`HandError::Restarted`] when the board
    /// restarted; [`HandError::Silent`] when an input has not reported for 50 sampling
    /// intervals (at least 1 s).
    pub fn next_reading(&mut self, timeout: Duration) -> Result<Option<Reading>, HandError> {
        let deadline = Instant::now() + timeout;
        loop {
            self.renew()?;
            let left = deadline.saturating_duration_since(Instant::now());
            self.board.poll(left.min(Duration::from_millis(20)))?;
            if self.board.version_reports() != self.version_reports {
                return Err(HandError::Restarted {
                    port: self.board.port_name().to_owned(),
                });
            }
            if let Some(r) = self.reading()? {
                return Ok(Some(r));
            }
            if left.is_zero() {
                return Ok(None);
            }
        }
    }

    fn reading(&mut self) -> Result<Option<Reading>, HandError> {
        let interval_ms = match self.config.sampling_ms {
            0 => 19,
            ms => u64::from(ms),
        };
        let stale = Duration::from_millis((interval_ms * 50).max(1000));
        let now = Instant::now();
        let mut codes = [0u16; 8];
        let mut newest = self.epoch;
        for (k, ch) in self.config.wiring.channels().into_iter().enumerate() {
            let r = self.board.analog(ch);
            let at = r.map_or(self.epoch, |r| r.at);
            let silent = now.saturating_duration_since(at);
            if silent > stale {
                return Err(HandError::Silent {
                    port: self.board.port_name().to_owned(),
                    channel: ch,
                    silent_ms: silent.as_millis() as u64,
                });
            }
            codes[k] = r.map_or(0, |r| r.counts);
            newest = newest.max(at);
        }
        if self.last.is_some_and(|l| newest <= l) {
            return Ok(None);
        }
        self.last = Some(newest);
        Ok(Some(Reading {
            t_us: newest.saturating_duration_since(self.epoch).as_micros() as u64,
            codes,
            sample: self.config.calibration.sample(&codes),
        }))
    }

    /// The configuration it was opened with.
    pub fn config(&self) -> &HandConfig {
        &self.config
    }

    /// The board's port.
    pub fn port(&self) -> &str {
        self.board.port_name()
    }
}

impl Drop for UnderactuatedHand {
    fn drop(&mut self) {
        if !self.stopped {
            let _ = self.board.stepper_stop(self.config.wiring.stepper_device);
        }
    }
}
