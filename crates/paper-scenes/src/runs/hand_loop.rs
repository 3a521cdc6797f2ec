//! The full hand as one control loop.
//!
//! Every 10 ms tick of hand-control's [`GraspLoop`] (its [`FixedRate`](hand_control::grasp_loop::FixedRate)
//! grid on the loop clock) the [`HandLoop`]:
//!
//! 1. runs one grasp cycle — read the fingertip's three MS5611s, estimate the contact pressure,
//!    ask the fuzzy policy for an effort, write the Protocol 2.0 goals, read the servos back
//!    (the grasp loop's own safe-state handling covers sensor and servo faults);
//! 2. on the frame that cycle read, estimates the force (the force DNN on the tared rises, hPa)
//!    and the contact (the arrival detector, eq. 3 Arrival-of-Time on 3 × 3, and the contact MLP
//!    on 4 × 6 when one is given);
//! 3. reads the ICM-20789 pad on the cycles where its own 30 Hz tick falls due, feeds its frames
//!    to a streaming tap trigger (pressure over the resting baseline, as handstack's
//!    `TapToMove`), and on a completed window asks the CNN for the region;
//! 4. polls the arm once, without blocking: the moveL in flight (`UrArm::progress`), or starts
//!    the next one (`UrArm::start_move_linear`) to the grid pose of the last region located.
//!
//! The loop never knows whether its devices are simulated: it holds a [`TactileSource`] of
//! pressure frames, a grasp policy, a [`RebootableActuator`], a [`LoopClock`], a
//! [`TactileSource`] of IMU frames and a [`UrArm`].
//!
//! **Safe state.** The first fault of any device ends the loop in the cycle it is seen: a
//! fingertip or servo fault has already sent the hand to its configured safe action inside the
//! grasp cycle; a pad or arm fault sends it there from this loop
//! ([`GripperActuator::safe_stop`](hand_traits::GripperActuator::safe_stop)); any fault stops an arm move in flight (`stopL`, tried;
//! the arm's own loss cannot be stopped from here). The [`LoopFaultReport`] says which device,
//! in which cycle and at what loop time.
//!
//! **Timing figures.** Compute is wall time around a cycle's work with the time spent waiting on
//! the loop clock taken out (on a simulated clock, waiting is where the physics steps); jitter is
//! the loop clock's time when the wait returned minus the tick; overruns are the ticks the grasp
//! loop's scheduler skipped.

use std::time::{Duration, Instant};

use aot_locate::{AotLocator, ArrivalDetector, DetectorConfig};
use hand_control::grasp_loop::{
    ConfigError, GraspLoop, LoopClock, LoopConfig, Mode, RebootableActuator,
};
use hand_sim::fingertip::geometry::aot_geometry;
use hand_traits::{
    ContactLocator, GraspPolicy, ImuFrame, LinearMotion, Pose, PressureFrame, TactileSource,
};
use handstack::tap_to_move::{RegionToGrid, TapTrigger};
use tactile_nets::contact_cnn::ContactCnn;
use tactile_nets::contact_mlp::{ContactMlp, TapReading, features};
use tactile_nets::force_dnn::{ForceDnn, LiveTare};
use ur_bridge::{MoveHandle, UrArm};

/// The loop clock with the wall time spent waiting on it counted, and the loop time at which
/// the last wait returned (the cycle's start).
pub struct TimedClock<C> {
    inner: C,
    waited: Duration,
    woke_us: u64,
}

impl<C: LoopClock> TimedClock<C> {
    /// Wraps `inner`.
    pub fn new(inner: C) -> Self {
        Self {
            inner,
            waited: Duration::ZERO,
            woke_us: 0,
        }
    }

    /// The wrapped clock.
    pub fn inner_mut(&mut self) -> &mut C {
        &mut self.inner
    }
}

impl<C: LoopClock> LoopClock for TimedClock<C> {
    fn now_us(&mut self) -> u64 {
        self.inner.now_us()
    }

    fn wait_until_us(&mut self, t_us: u64) {
        let t0 = Instant::now();
        self.inner.wait_until_us(t_us);
        self.woke_us = self.inner.now_us();
        self.waited += t0.elapsed();
    }
}

/// The fingertip estimators run on the grasp cycle's frame.
pub struct Estimators {
    /// The force DNN (tared rises in hPa → gf).
    pub force: ForceDnn,
    /// The contact MLP on 4 × 6, if the scene names it.
    pub mlp: Option<ContactMlp>,
    detector: ArrivalDetector,
    aot: AotLocator,
    tare: LiveTare,
}

impl Estimators {
    /// The force DNN, tared over the first `tare_frames` frames, and the contact MLP.
    pub fn new(force: ForceDnn, mlp: Option<ContactMlp>, tare_frames: u32) -> Self {
        Self {
            force,
            mlp,
            detector: ArrivalDetector::new(DetectorConfig::DEFAULT),
            aot: AotLocator::new(aot_geometry()),
            tare: LiveTare::new(tare_frames),
        }
    }

    /// One frame: the force (once tared) and a contact location (once a contact arrived).
    fn update(&mut self, frame: &PressureFrame<3>, out: &mut Stats) -> Result<(), String> {
        let p = frame.pressure_pa;
        if let Some(rise) = self.tare.rise_hpa(frame) {
            out.force_gf = Some(self.force.estimate_gf(&rise).map_err(|e| e.to_string())?);
        }
        // A contact is new when none had arrived before this frame (a finished press rearms
        // on a frame at rest, which cannot itself arrive).
        let had_arrived = self.detector.any_arrived();
        let Some(onset) = self.detector.push_streaming(frame.t_us as i64, p) else {
            return Ok(());
        };
        if !had_arrived {
            out.contacts += 1;
        }
        let event = self.detector.event(onset, p);
        out.aot_area = Some(self.aot.locate(&event).map_err(|e| e.to_string())?.region);
        if let Some(mlp) = &self.mlp {
            let reading = TapReading::from_detector(&self.detector, p, onset);
            let pred = mlp
                .predict(&features(&reading))
                .map_err(|e| e.to_string())?;
            out.mlp_area = Some(pred.region);
        }
        Ok(())
    }
}

/// The ICM-20789 pad at its own rate, its trigger and the CNN.
pub struct PadPart<Pad> {
    /// The pad's frames.
    pub pad: Pad,
    /// Frames per second the loop reads (the chip's 30 Hz).
    pub rate_hz: u32,
    /// The tap trigger.
    pub trigger: TapTrigger,
    /// The contact CNN.
    pub cnn: ContactCnn,
    /// The CNN's input from a window (`paper_experiments::tap_run::cnn_window`).
    pub to_input: fn(&[ImuFrame]) -> [f32; 152],
}

/// The arm, its grid and the move in flight.
pub struct ArmPart {
    /// The ur_rtde client.
    pub arm: UrArm,
    /// Region → pose.
    pub grid: RegionToGrid,
    /// Speed and acceleration of the moves.
    pub motion: LinearMotion,
    active: Option<MoveHandle>,
    pending: Option<Pose>,
}

impl ArmPart {
    /// The arm; its first move goes to the grid's home pose.
    pub fn new(arm: UrArm, grid: RegionToGrid, motion: LinearMotion) -> Self {
        let home = *grid.home();
        Self {
            arm,
            grid,
            motion,
            active: None,
            pending: Some(home),
        }
    }

    /// Sends the arm to `target` next: started at once if the arm is free, else when the move
    /// in flight ends (a later request replaces an earlier one still waiting).
    pub fn request(&mut self, target: Pose) {
        self.pending = Some(target);
    }

    /// Whether a move is in flight or waiting to start.
    pub fn busy(&self) -> bool {
        self.active.is_some() || self.pending.is_some()
    }

    /// One non-blocking poll: the move in flight, then the next one if the arm is free.
    fn poll(&mut self, stats: &mut Stats) -> Result<(), ur_bridge::UrError> {
        if let Some(h) = &self.active {
            let p = self.arm.progress(h)?;
            if !p.running {
                stats.moves_completed += 1;
                self.active = None;
            }
        } else if self.pending.is_none() && !self.arm.is_connected()? {
            return Err(ur_bridge::UrError::ConnectionLost);
        }
        if self.active.is_none() {
            if let Some(target) = self.pending.take() {
                self.active = Some(self.arm.start_move_linear(&target, &self.motion)?);
                stats.moves_started += 1;
            }
        }
        Ok(())
    }
}

/// Which device faulted, when, and what it said.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopFaultReport {
    /// The device (`sensors.fingertip`, `hand`, `sensors.imu_pad`, `arm`, `estimators`).
    pub device: &'static str,
    /// The loop cycle it was seen in.
    pub cycle: u64,
    /// That cycle's tick on the loop clock, µs.
    pub t_us: u64,
    /// What happened.
    pub reason: String,
    /// The grasp loop's mode at the end of that cycle (`Safe` / `Halted`: the hand's safe state).
    pub mode: Mode,
}

/// Whole microseconds the histogram resolves: two 10 ms periods; longer cycles share the last
/// bin (their exact value still reaches the max).
const COMPUTE_BINS_US: usize = 20_000;

/// Each cycle's compute time as a histogram of whole microseconds, sized once, so recording a
/// cycle allocates nothing however long the loop runs: exact mean and max, percentiles to the
/// microsecond.
///
/// ```
/// use paper_scenes::runs::hand_loop::ComputeTimes;
///
/// let mut t = ComputeTimes::default();
/// for us in [120.4, 130.0, 125.9, 9_000.0] {
///     t.record(us);
/// }
/// assert_eq!(t.max_us(), 9_000.0);
/// assert_eq!(t.percentile_us(50), 125.0);
/// assert_eq!(t.percentile_us(99), 9_000.0);
/// ```
#[derive(Debug, Clone)]
pub struct ComputeTimes {
    counts: Vec<u32>,
    n: u64,
    sum_us: f64,
    max_us: f64,
}

impl Default for ComputeTimes {
    fn default() -> Self {
        Self {
            counts: vec![0; COMPUTE_BINS_US + 1],
            n: 0,
            sum_us: 0.0,
            max_us: 0.0,
        }
    }
}

impl ComputeTimes {
    /// Adds one cycle of `us` microseconds.
    pub fn record(&mut self, us: f64) {
        let bin = (us.max(0.0) as usize).min(COMPUTE_BINS_US);
        self.counts[bin] += 1;
        self.n += 1;
        self.sum_us += us;
        self.max_us = self.max_us.max(us);
    }

    /// Cycles recorded.
    pub fn len(&self) -> u64 {
        self.n
    }

    /// Whether none was recorded.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Mean, µs (0 when empty).
    pub fn mean_us(&self) -> f64 {
        self.sum_us / self.n.max(1) as f64
    }

    /// Longest, µs (0 when empty).
    pub fn max_us(&self) -> f64 {
        self.max_us
    }

    /// The `pct`-th percentile, µs: the ⌈n·pct/100⌉-th shortest cycle, to the whole
    /// microsecond (the max when it falls past the histogram; 0 when empty).
    pub fn percentile_us(&self, pct: u64) -> f64 {
        let k = (self.n * pct).div_ceil(100).max(1);
        let mut seen = 0;
        for (us, &c) in self.counts.iter().enumerate().take(COMPUTE_BINS_US) {
            seen += u64::from(c);
            if seen >= k {
                return us as f64;
            }
        }
        self.max_us
    }
}

/// What the loop counted and measured.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    /// Cycles run.
    pub cycles: u64,
    /// Wall time of each cycle's work (waiting excluded).
    pub compute: ComputeTimes,
    /// Largest |cycle start − tick|, µs (loop clock).
    pub jitter_max_us: u64,
    /// Pad frames read.
    pub pad_reads: u64,
    /// CNN windows located.
    pub cnn_triggers: u64,
    /// The regions the CNN named, in order.
    pub located: Vec<u16>,
    /// Arm moves started.
    pub moves_started: u64,
    /// Arm moves completed.
    pub moves_completed: u64,
    /// Contacts the arrival detector saw on the fingertip.
    pub contacts: u64,
    /// The last AoT 3 × 3 area.
    pub aot_area: Option<u16>,
    /// The last MLP 4 × 6 area (the cell nearest the contact's centroid).
    pub mlp_area: Option<u16>,
    /// The last force estimate, gf.
    pub force_gf: Option<f32>,
    /// Torque limit last sent (0…1023).
    pub torque_raw: Option<u16>,
}

/// The fused full-hand loop.
pub struct HandLoop<S, P, A, C, Pad>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    P: GraspPolicy,
    A: RebootableActuator,
    C: LoopClock,
{
    grasp: GraspLoop<S, P, A, TimedClock<C>, 3>,
    estimators: Estimators,
    pad: PadPart<Pad>,
    arm: ArmPart,
    first_tick_us: Option<u64>,
    stats: Stats,
    fault: Option<LoopFaultReport>,
}

impl<S, P, A, C, Pad> HandLoop<S, P, A, C, Pad>
where
    S: TactileSource<Frame = PressureFrame<3>>,
    S::Error: core::fmt::Debug + core::fmt::Display,
    P: GraspPolicy,
    P::Error: core::fmt::Display,
    A: RebootableActuator,
    A::Error: core::fmt::Display,
    C: LoopClock,
    Pad: TactileSource<Frame = ImuFrame>,
    Pad::Error: core::fmt::Display,
{
    /// The loop over a fingertip, a policy, a hand and a clock (as [`GraspLoop::new`]), the
    /// estimators, the pad and the arm.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        tip: S,
        policy: P,
        hand: A,
        clock: C,
        config: LoopConfig,
        estimators: Estimators,
        pad: PadPart<Pad>,
        arm: ArmPart,
    ) -> Result<Self, ConfigError> {
        Ok(Self {
            grasp: GraspLoop::new(tip, policy, hand, TimedClock::new(clock), config)?,
            estimators,
            pad,
            arm,
            first_tick_us: None,
            stats: Stats::default(),
            fault: None,
        })
    }

    /// Runs cycles until the next tick is at or after `until_us`, or a fault ended the loop.
    pub fn run_until(&mut self, until_us: u64) {
        while self.fault.is_none() && self.next_tick_us() < until_us {
            self.cycle();
        }
    }

    /// Runs on until the arm has finished its moves (the hand keeps its period meanwhile), for
    /// at most `extra_us` of loop time and the arm's move timeout of wall time: the arm moves
    /// in its controller's time, which a simulated loop clock may outrun many times over.
    pub fn finish_moves(&mut self, extra_us: u64) {
        let until = self.next_tick_us().saturating_add(extra_us);
        let wall = Instant::now();
        let timeout = self.arm.arm.config().move_timeout;
        while self.fault.is_none()
            && self.arm.busy()
            && self.next_tick_us() < until
            && wall.elapsed() < timeout
        {
            self.cycle();
        }
    }

    /// The next cycle's tick (an overrun moves it on to the next grid tick).
    fn next_tick_us(&mut self) -> u64 {
        let period = self.grasp.config().period_us;
        match self.grasp.log().last() {
            Some(s) => s.t_us + period,
            None => self.grasp.clock_mut().now_us(),
        }
    }

    /// One cycle; `false` once a fault has ended the loop.
    pub fn cycle(&mut self) -> bool {
        if self.fault.is_some() {
            return false;
        }
        let wall = Instant::now();
        let waited = self.grasp.clock_mut().waited;
        let s = *self.grasp.cycle();
        let woke = self.grasp.clock_mut().woke_us;
        self.stats.cycles += 1;
        self.stats.jitter_max_us = self.stats.jitter_max_us.max(woke.abs_diff(s.t_us));
        self.stats.torque_raw = s.torque_raw.or(self.stats.torque_raw);
        let first = *self.first_tick_us.get_or_insert(s.t_us);
        if let Some(kind) = s.fault {
            if matches!(s.mode, Mode::Safe | Mode::Halted) {
                let device = handstack::runs::grasp::fault_device(kind);
                let reason = self
                    .grasp
                    .events()
                    .last()
                    .map_or_else(|| device.to_owned(), |e| e.fault.to_string());
                self.end(device, &s, reason, false);
            }
        }
        if self.fault.is_none() {
            if let Some(frame) = &s.frame {
                if let Err(reason) = self.estimators.update(frame, &mut self.stats) {
                    self.end("estimators", &s, reason, true);
                }
            }
        }
        // The pad: every frame whose 30 Hz tick is due by this cycle's tick.
        let rate = u64::from(self.pad.rate_hz.max(1));
        while self.fault.is_none() && self.stats.pad_reads * 1_000_000 <= (s.t_us - first) * rate {
            match self.pad.pad.read_frame() {
                Ok(f) => {
                    self.stats.pad_reads += 1;
                    // The window borrows the trigger: make the CNN's input before locating.
                    let pad = &mut self.pad;
                    if let Some((window, _)) = pad.trigger.push(f) {
                        let input = (pad.to_input)(window);
                        self.locate(&input, &s);
                    }
                }
                Err(e) => self.end("sensors.imu_pad", &s, e.to_string(), true),
            }
        }
        if self.fault.is_none() {
            if let Err(e) = self.arm.poll(&mut self.stats) {
                self.end("arm", &s, e.to_string(), true);
            }
        }
        let waited = self.grasp.clock_mut().waited - waited;
        let compute = wall.elapsed().saturating_sub(waited);
        self.stats.compute.record(compute.as_secs_f64() * 1e6);
        self.fault.is_none()
    }

    fn locate(&mut self, input: &[f32], s: &hand_control::grasp_loop::Sample<3>) {
        match self.pad.cnn.locate(input) {
            Ok(c) => {
                self.stats.cnn_triggers += 1;
                self.stats.located.push(c.region);
                match self.arm.grid.pose(c.region) {
                    Ok(p) => self.arm.request(*p),
                    Err(e) => self.end("arm", s, e.to_string(), true),
                }
            }
            Err(e) => self.end("estimators", s, e.to_string(), true),
        }
    }

    /// The safe state: the hand to its safe action (unless the grasp loop already sent it
    /// there this cycle), any arm move stopped; the fault recorded.
    fn end(
        &mut self,
        device: &'static str,
        s: &hand_control::grasp_loop::Sample<3>,
        reason: String,
        hand_still_running: bool,
    ) {
        if self.fault.is_some() {
            return;
        }
        let mut mode = s.mode;
        if hand_still_running {
            let action = self.grasp.config().safe_action;
            if self.grasp.actuator_mut().safe_stop(action).is_ok() {
                mode = Mode::Safe;
            }
        }
        if device != "arm" && self.arm.active.take().is_some() {
            let _ = self
                .arm
                .arm
                .stop_linear(self.arm.motion.accel_m_per_s2.max(1.0));
        }
        self.arm.active = None;
        self.arm.pending = None;
        self.fault = Some(LoopFaultReport {
            device,
            cycle: s.cycle,
            t_us: s.t_us,
            reason,
            mode,
        });
    }

    /// What the loop counted.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Ticks the scheduler skipped because a cycle overran.
    pub fn overruns(&self) -> u64 {
        self.grasp.missed_ticks()
    }

    /// The fault that ended the loop, if any.
    pub fn fault(&self) -> Option<&LoopFaultReport> {
        self.fault.as_ref()
    }

    /// The grasp loop inside.
    pub fn grasp(&self) -> &GraspLoop<S, P, A, TimedClock<C>, 3> {
        &self.grasp
    }

    /// The arm part.
    pub fn arm_mut(&mut self) -> &mut ArmPart {
        &mut self.arm
    }
}

/// The full-hand scene's loop: composed from the scene's parts and run.
pub mod scene;
