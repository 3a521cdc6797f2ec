//! The fuzzy grasp of the MX-28 hand (seed 000 §5–7, Table 5): three MS5611 → tared mean
//! pressure and its filtered rate (hand-control's estimator) → the paper's fuzzy controller
//! in the cube's Table 5 torque band → the goal sync writes to both servos.
//!
//! These are the compute steps of `hand_control::grasp_loop::GraspLoop::cycle`, called one by
//! one so each can be timed; the loop itself adds its fault bookkeeping and a log entry per
//! cycle (see `tests/alloc/zero_alloc.rs` for what that log costs) and talks to a real port.

use crate::CycleError;
use crate::fingertip::{Press, PressSchedule, PressedFingertip, rect};
use fuzzy_mamdani::GraspController;
use hand_control::control_table::MX_28;
use hand_control::grasp_loop::{ContactEstimate, LoopConfig, PressureEstimator, TorqueBand};
use hand_control::{GoalPackets, RawGoals, encode_goals};
use hand_traits::{GraspPolicy, GripperCommand, PressureFrame};

/// Resting frames averaged into the estimator's zero.
pub const TARE_FRAMES: u64 = 20;
/// The hand's servo IDs (two fingers).
pub const SERVO_IDS: [u8; 2] = [1, 2];
/// The Table 5 object whose band the controller uses.
pub const OBJECT: &str = "cube";

/// One cycle's result.
#[derive(Debug, Clone, PartialEq)]
pub struct GraspOut<'a> {
    /// The frame read.
    pub frame: PressureFrame<3>,
    /// The estimate (`None` while taring).
    pub estimate: Option<ContactEstimate>,
    /// The command sent (`None` while taring).
    pub command: Option<GripperCommand>,
    /// Its raw goals.
    pub goals: Option<RawGoals>,
    /// The bytes on the wire this cycle (both sync writes; empty while taring).
    pub packets: &'a [u8],
}

/// The grasp cycle.
pub struct GraspCycle {
    tip: PressedFingertip,
    estimator: PressureEstimator<3>,
    config: LoopConfig,
    band: TorqueBand,
    policy: GraspController,
    packets: GoalPackets,
    tared: u64,
}

impl GraspCycle {
    /// Bytes on the wire per cycle for two MX-28s: the Goal PWM sync write (header, ID, LEN,
    /// instruction, CRC = 10, address + length 4, 2 × (ID + 2 bytes)) = 20, and the Goal
    /// Position one (4-byte register) = 24; no byte stuffing at these values.
    pub const WIRE_LEN: usize = 44;

    /// The cycle with hand-control's default loop settings and the cube's Table 5 band.
    pub fn new() -> Result<Self, CycleError> {
        let row = paper_fixtures::seed000::table5_grasp_torque()
            .map_err(|e| CycleError::Config(e.to_string()))?
            .into_iter()
            .find(|r| r.object == OBJECT)
            .ok_or_else(|| CycleError::Config(format!("Table 5 has no {OBJECT}")))?;
        let raw = |v: u32| u16::try_from(v).map_err(|_| CycleError::Config(format!("torque {v}")));
        let (lo, hi) = (raw(row.torque_min)?, raw(row.torque_max)?);
        let band = TorqueBand::new(lo, hi).map_err(|e| CycleError::Config(e.to_string()))?;
        let config = LoopConfig {
            band,
            ..LoopConfig::new()
        };
        // A contact squeezed harder and harder, released, again: the rules that fire vary.
        let cells = rect(2, 3, 2, 2)?;
        let presses = [0.2, 0.5, 1.0, 2.0]
            .map(|kgf| Press { cells, kgf })
            .to_vec();
        let schedule = PressSchedule {
            presses,
            rest_cycles: TARE_FRAMES,
            press_cycles: 40,
            release_cycles: 10,
        };
        Ok(GraspCycle {
            tip: PressedFingertip::new(1024, 13, schedule)?,
            estimator: PressureEstimator::new(config.contact_threshold_pa, config.rate_cutoff_hz),
            policy: fuzzy_mamdani::grasp_controller().with_torque_band(lo, hi),
            band,
            config,
            packets: GoalPackets::new(&MX_28, &SERVO_IDS),
            tared: 0,
        })
    }

    /// Decode: one frame from the three chips through the driver.
    pub fn decode(&mut self) -> Result<PressureFrame<3>, CycleError> {
        self.tip.read()
    }

    /// Estimate: tare while the first frames come in, then the contact estimate.
    pub fn estimate(
        &mut self,
        frame: &PressureFrame<3>,
    ) -> Result<Option<ContactEstimate>, CycleError> {
        if self.estimator.is_tared() {
            return Ok(Some(self.estimator.update(frame)?));
        }
        self.estimator.tare(frame)?;
        self.tared += 1;
        if self.tared >= TARE_FRAMES {
            self.estimator.finish_tare()?;
        }
        Ok(None)
    }

    /// Policy: the fuzzy effort for the estimate, clamped into the band, closing to the goal.
    pub fn policy(&mut self, estimate: &ContactEstimate) -> Result<GripperCommand, CycleError> {
        let obs = estimate.observation(self.config.target_pressure_pa);
        let (effort, _) = self.band.clamp(self.policy.effort(&obs)?);
        Ok(GripperCommand {
            position_rad: self.config.goal_rad,
            effort,
        })
    }

    /// Encode: the command's raw goals and both sync writes, framed by hand-control's
    /// [`GoalPackets`], the encoder `ServoHand::write_goals` sends (only its port write is
    /// left out, so the bench times compute, not the tty).
    pub fn encode(&mut self, cmd: &GripperCommand) -> Result<(RawGoals, &[u8]), CycleError> {
        let goals = encode_goals(&MX_28, cmd).map_err(|e| CycleError::Config(e.to_string()))?;
        let wire = self.packets.encode(&goals);
        Ok((goals, wire))
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<GraspOut<'_>, CycleError> {
        let frame = self.decode()?;
        let Some(estimate) = self.estimate(&frame)? else {
            return Ok(GraspOut {
                frame,
                estimate: None,
                command: None,
                goals: None,
                packets: &[],
            });
        };
        let command = self.policy(&estimate)?;
        let (goals, packets) = self.encode(&command)?;
        Ok(GraspOut {
            frame,
            estimate: Some(estimate),
            command: Some(command),
            goals: Some(goals),
            packets,
        })
    }

    /// The loop settings (target pressure, goal, band).
    pub fn config(&self) -> &LoopConfig {
        &self.config
    }

    /// A fresh copy of the paper's controller in this cycle's band (to check a cycle against).
    pub fn reference_policy(&self) -> GraspController {
        fuzzy_mamdani::grasp_controller().with_torque_band(self.band.min_raw(), self.band.max_raw())
    }
}
