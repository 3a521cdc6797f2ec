//! [`GraspLoop`]: tactile source → contact estimate → grasp policy → actuator, once per tick.

use hand_traits::{
    Effort, GraspPolicy, GripperActuator, GripperCommand, GripperState, PressureFrame, SafeAction,
    TactileSource,
};

use super::clock::{FixedRate, LoopClock};
use super::config::{ConfigError, LoopConfig, Recovery, check_goal};
use super::estimate::{ContactEstimate, PressureEstimator};
use super::fault::{FaultEvent, LoopFault, RebootableActuator};
use super::log::{Mode, Sample};

/// The fault type of a loop over these parts.
pub type FaultOf<S, P, A> = LoopFault<
    <S as TactileSource>::Error,
    <P as GraspPolicy>::Error,
    <A as GripperActuator>::Error,
>;

/// The closed grasp loop of the grasping paper (§5), generic over the `hand-traits` parts.
///
/// Each cycle, on the fixed-rate grid: read a frame, estimate the contact pressure and its
/// filtered rate, ask the policy for an effort, clamp it into the torque band, send it with the
/// closing goal, read the actuator back. Any fault (source, estimate, policy, a command or
/// state read the actuator fails, a hardware-error bit) sends the actuator to the configured
/// safe state in the same cycle; it is reported as a [`FaultEvent`] and every cycle is logged.
pub struct GraspLoop<S, P, A, C, const N: usize>
where
    S: TactileSource<Frame = PressureFrame<N>>,
    P: GraspPolicy,
    A: RebootableActuator,
    C: LoopClock,
{
    source: S,
    policy: P,
    actuator: A,
    clock: C,
    config: LoopConfig,
    rate: FixedRate,
    estimator: PressureEstimator<N>,
    mode: Mode,
    cycle: u64,
    tared: u32,
    goal_rad: f32,
    /// The last command that was followed by a fault-free state read.
    last_safe: Option<GripperCommand>,
    last_sent: Option<GripperCommand>,
    last_state: Option<GripperState>,
    /// Where the hand was at its first state read: where a release opens it to.
    open_rad: Option<f32>,
    safe_since_us: u64,
    safe_confirmed: bool,
    safe_stop_failing: bool,
    rebooted_since_safe: bool,
    reboots: u32,
    log: Vec<Sample<N>>,
    events: Vec<FaultEvent<S::Error, P::Error, A::Error>>,
    events_dropped: u64,
}

/// Pushes `item`, first dropping the older half of `v` when it holds `capacity` (amortised
/// O(1), the slice stays contiguous); returns how many were dropped.
fn push_bounded<T>(v: &mut Vec<T>, item: T, capacity: usize) -> u64 {
    let mut dropped = 0;
    if v.len() >= capacity {
        let n = v.len() - capacity / 2;
        v.drain(..n);
        dropped = n as u64;
    }
    v.push(item);
    dropped
}

impl<S, P, A, C, const N: usize> GraspLoop<S, P, A, C, N>
where
    S: TactileSource<Frame = PressureFrame<N>>,
    P: GraspPolicy,
    A: RebootableActuator,
    C: LoopClock,
{
    /// A loop over the four parts; the first tick is the clock's present time.
    pub fn new(
        source: S,
        policy: P,
        actuator: A,
        mut clock: C,
        config: LoopConfig,
    ) -> Result<Self, ConfigError> {
        config.validate()?;
        let start = clock.now_us();
        Ok(GraspLoop {
            source,
            policy,
            actuator,
            rate: FixedRate::new(config.period_us, start),
            estimator: PressureEstimator::new(config.contact_threshold_pa, config.rate_cutoff_hz),
            clock,
            goal_rad: config.goal_rad,
            config,
            mode: Mode::Tare,
            cycle: 0,
            tared: 0,
            last_safe: None,
            last_sent: None,
            last_state: None,
            open_rad: None,
            safe_since_us: 0,
            safe_confirmed: false,
            safe_stop_failing: false,
            rebooted_since_safe: false,
            reboots: 0,
            log: Vec::new(),
            events: Vec::new(),
            events_dropped: 0,
        })
    }

    /// Runs every cycle whose tick is before `until_us`.
    pub fn run_until(&mut self, until_us: u64) {
        while self.rate.peek(self.clock.now_us()).0 < until_us {
            self.cycle();
        }
    }

    /// Runs one cycle and returns its log entry.
    pub fn cycle(&mut self) -> &Sample<N> {
        let t_us = self.rate.wait(&mut self.clock);
        let mut s = Sample::new(self.cycle, t_us, self.mode);
        let mut faults: Vec<FaultOf<S, P, A>> = Vec::new();

        let frame = match self.source.read_frame() {
            Ok(f) => Some(f),
            Err(e) => {
                faults.push(LoopFault::Source(e));
                None
            }
        };
        s.frame = frame;
        if let Some(frame) = &frame {
            if self.mode == Mode::Tare {
                match self.estimator.tare(frame) {
                    Ok(()) => self.tared += 1,
                    Err(e) => faults.push(LoopFault::Estimate(e)),
                }
            } else {
                match self.estimator.update(frame) {
                    Ok(e) => s.estimate = Some(e),
                    Err(e) => faults.push(LoopFault::Estimate(e)),
                }
            }
        }
        if self.mode == Mode::Grasp && faults.is_empty() {
            if let Some(estimate) = s.estimate {
                if let Err(f) = self.command(&estimate, &mut s) {
                    faults.push(f);
                }
            }
        }
        match self.actuator.state() {
            Ok(st) => {
                s.state = Some(st);
                self.last_state = Some(st);
                self.open_rad.get_or_insert(st.position_rad);
                if !st.faults.is_empty() {
                    faults.push(LoopFault::Hardware(st.faults));
                }
            }
            Err(e) => faults.push(LoopFault::State(e)),
        }

        if faults.is_empty() && self.mode == Mode::Grasp {
            self.last_safe = self.last_sent.or(self.last_safe);
        }
        if self.mode == Mode::Tare && faults.is_empty() && self.tared >= self.config.tare_cycles {
            match self.estimator.finish_tare() {
                Ok(()) => self.mode = Mode::Grasp,
                Err(e) => faults.push(LoopFault::Estimate(e)),
            }
        }
        s.fault = faults.first().map(LoopFault::kind);
        let clean = faults.is_empty();
        self.report(t_us, faults);
        match self.mode {
            Mode::Tare | Mode::Grasp if !clean => self.enter_safe(t_us, &mut s),
            Mode::Safe | Mode::Halted => self.stay_safe(t_us, clean, &mut s),
            _ => {}
        }
        s.mode = self.mode;
        self.cycle += 1;
        push_bounded(&mut self.log, s, self.config.log_capacity);
        // Just pushed, so the log is not empty.
        &self.log[self.log.len() - 1]
    }

    fn command(
        &mut self,
        estimate: &ContactEstimate,
        s: &mut Sample<N>,
    ) -> Result<(), FaultOf<S, P, A>> {
        let obs = estimate.observation(self.config.target_pressure_pa);
        let effort = self.policy.effort(&obs).map_err(LoopFault::Policy)?;
        let (banded, _) = self.config.band.clamp(effort);
        let cmd = GripperCommand {
            position_rad: self.goal_rad,
            effort: banded,
        };
        s.policy_raw = Some(effort.to_torque_limit_raw());
        self.actuator.command(&cmd).map_err(LoopFault::Command)?;
        s.torque_raw = Some(banded.to_torque_limit_raw());
        s.goal_rad = Some(cmd.position_rad);
        self.last_sent = Some(cmd);
        Ok(())
    }

    /// The fault's cycle: hold the last command known safe (if this cycle sent another), then
    /// the safe stop. Both are tried even if the first fails; failures are reported.
    fn enter_safe(&mut self, t_us: u64, s: &mut Sample<N>) {
        self.mode = Mode::Safe;
        self.rebooted_since_safe = false;
        self.safe_since_us = t_us;
        if self.config.safe_action == SafeAction::HoldLastSafeEffort {
            if let Some(safe) = self.last_safe {
                if self.last_sent != Some(safe) {
                    if let Err(e) = self.actuator.command(&safe) {
                        self.push_event(t_us, LoopFault::Command(e));
                    } else {
                        self.last_sent = Some(safe);
                    }
                }
            }
        }
        self.safe_stop(t_us, s);
    }

    fn safe_stop(&mut self, t_us: u64, s: &mut Sample<N>) {
        s.safe_action = Some(self.config.safe_action);
        match self.actuator.safe_stop(self.config.safe_action) {
            Ok(()) => {
                self.safe_confirmed = true;
                self.safe_stop_failing = false;
            }
            Err(e) => {
                self.safe_confirmed = false;
                // Retried every cycle; reported when it starts failing.
                if !self.safe_stop_failing {
                    self.safe_stop_failing = true;
                    self.push_event(t_us, LoopFault::SafeStop(e));
                }
            }
        }
    }

    /// In the safe state: retry an unconfirmed safe stop; recover as configured.
    fn stay_safe(&mut self, t_us: u64, clean: bool, s: &mut Sample<N>) {
        if !self.safe_confirmed {
            self.safe_stop(t_us, s);
        }
        let Recovery::Automatic {
            cooldown_us,
            max_reboots,
        } = self.config.recovery
        else {
            return;
        };
        if self.mode == Mode::Halted || !self.safe_confirmed {
            return;
        }
        let Some(state) = s.state else { return };
        if clean {
            if let Err(e) = self.resume_mode() {
                self.push_event(t_us, LoopFault::Reboot(e));
            }
            return;
        }
        if state.faults.is_empty() {
            return; // a fault of another part: wait for a clean cycle
        }
        if self.reboots >= max_reboots {
            self.mode = Mode::Halted;
            return;
        }
        let cooled = t_us.saturating_sub(self.safe_since_us) >= cooldown_us;
        if cooled && state.load_fraction.abs() <= self.config.clear_load_fraction {
            self.reboots += 1;
            s.rebooted = true;
            match self.actuator.reboot() {
                Ok(()) => self.rebooted_since_safe = true,
                Err(e) => self.push_event(t_us, LoopFault::Reboot(e)),
            }
        }
    }

    /// Back to grasping (or taring): torque on again after a torque-off safe stop.
    fn resume_mode(&mut self) -> Result<(), A::Error> {
        if self.config.safe_action == SafeAction::TorqueOff && !self.rebooted_since_safe {
            self.actuator.enable_torque()?;
        }
        self.mode = if self.estimator.is_tared() {
            Mode::Grasp
        } else {
            Mode::Tare
        };
        self.safe_confirmed = false;
        self.rebooted_since_safe = false;
        self.last_sent = None;
        Ok(())
    }

    /// Leaves the safe state by hand: reboots the actuator first if it last reported a
    /// hardware error, then grasps again from the next cycle.
    pub fn resume(&mut self) -> Result<(), A::Error> {
        if matches!(self.mode, Mode::Safe | Mode::Halted) {
            if self.last_state.is_some_and(|st| !st.faults.is_empty()) {
                self.actuator.reboot()?;
                self.reboots += 1;
                self.rebooted_since_safe = true;
            }
            self.resume_mode()?;
        }
        Ok(())
    }

    fn report(&mut self, t_us: u64, faults: Vec<FaultOf<S, P, A>>) {
        for f in faults {
            // A fault that persists cycle after cycle is reported once, when it starts.
            let repeat = self
                .log
                .last()
                .is_some_and(|prev| prev.fault == Some(f.kind()) && prev.cycle + 1 == self.cycle);
            if !repeat {
                self.push_event(t_us, f);
            }
        }
    }

    fn push_event(&mut self, t_us: u64, fault: FaultOf<S, P, A>) {
        let event = FaultEvent {
            cycle: self.cycle,
            t_us,
            fault,
        };
        self.events_dropped += push_bounded(&mut self.events, event, self.config.log_capacity);
    }

    /// Changes the closing goal; one outside the configured limits is refused (an out-of-range
    /// command is never sent).
    pub fn set_goal_rad(&mut self, goal_rad: f32) -> Result<(), ConfigError> {
        self.goal_rad = check_goal(goal_rad, self.config.goal_limits_rad)?;
        Ok(())
    }

    /// The torque band in force.
    pub fn config(&self) -> &LoopConfig {
        &self.config
    }

    /// Each sensor's zero from the loop's tare, Pa (`None` while taring): what a per-sensor
    /// estimator beside the loop (the grasping paper's force DNN) reads its rises against.
    pub fn zero_pa(&self) -> Option<[f64; N]> {
        self.estimator.zero_pa()
    }

    /// The mode after the last cycle.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The cycles kept: every cycle so far, or, once more than
    /// [`LoopConfig::log_capacity`] have run, the newest ones (see [`GraspLoop::log_dropped`]).
    pub fn log(&self) -> &[Sample<N>] {
        &self.log
    }

    /// Cycles dropped from the front of the log to keep it within its capacity.
    pub fn log_dropped(&self) -> u64 {
        // Every cycle run is either kept or dropped.
        self.cycle - self.log.len() as u64
    }

    /// The faults reported so far (the newest, bounded as the log).
    pub fn events(&self) -> &[FaultEvent<S::Error, P::Error, A::Error>] {
        &self.events
    }

    /// Fault events dropped to keep them within [`LoopConfig::log_capacity`].
    pub fn events_dropped(&self) -> u64 {
        self.events_dropped
    }

    /// Reboots sent so far.
    pub fn reboots(&self) -> u32 {
        self.reboots
    }

    /// Ticks skipped because a cycle overran.
    pub fn missed_ticks(&self) -> u64 {
        self.rate.missed_ticks()
    }

    /// Where the hand was when the loop first read it, rad: where
    /// [`EndAction::Release`](super::EndAction::Release) opens it to (`None` before a read).
    pub fn open_position_rad(&self) -> Option<f32> {
        self.open_rad
    }

    /// Whether the actuator holds the loop's last command and a fault-free read confirmed it:
    /// grasping, no fault since (an end that keeps the grip has nothing to send).
    pub(super) fn holding_confirmed(&self) -> bool {
        self.mode == Mode::Grasp && self.last_sent.is_some() && self.last_sent == self.last_safe
    }

    /// The actuator's state at its last fault-free read of a cycle.
    pub fn last_state(&self) -> Option<GripperState> {
        self.last_state
    }

    /// The effort last sent, if any.
    pub fn last_effort(&self) -> Option<Effort> {
        self.last_sent.map(|c| c.effort)
    }

    /// The tactile source.
    pub fn source_mut(&mut self) -> &mut S {
        &mut self.source
    }

    /// The actuator.
    pub fn actuator_mut(&mut self) -> &mut A {
        &mut self.actuator
    }

    /// The clock.
    pub fn clock_mut(&mut self) -> &mut C {
        &mut self.clock
    }

    /// The parts back, with the log (the cycles kept).
    pub fn into_parts(self) -> (S, P, A, C, Vec<Sample<N>>) {
        (
            self.source,
            self.policy,
            self.actuator,
            self.clock,
            self.log,
        )
    }
}
