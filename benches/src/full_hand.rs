//! The whole hand in one cycle: one barometric fingertip feeding contact location (AoT and
//! MLP), the force DNN and the fuzzy grasp with its MX-28 sync writes; the ICM-20789 pad's
//! CNN and UR3 grid pose alongside; the underactuated hand's softness net. Each part is the
//! scene cycle of its module, fed the shared frame where the parts share a sensor.
//!
//! The shared fingertip is read at OSR 1024 (the grasp loop's rate/noise choice); the contact
//! MLP and force DNN are the ones their scenes use (trained at OSR 256 and 4096): this cycle
//! measures the composed cost, the accuracy of each part is its scene's.

use crate::CycleError;
use crate::contact::{ContactCycle, ContactEstimate};
use crate::fingertip::{Press, PressSchedule, PressedFingertip, rect};
use crate::grasp::{GraspCycle, TARE_FRAMES};
use crate::softness::{Read, SoftnessCycle};
use crate::tap::{CnnWindow, TapCycle};
use crate::weight::{TARE_FRAMES as WEIGHT_TARE_FRAMES, WeightCycle};
use hand_control::grasp_loop::ContactEstimate as GraspEstimate;
use hand_traits::{Contact, FingerFrame, GripperCommand, ImuFrame, Pose, PressureFrame, Softness};
use paper_experiments::data::underactuated::N_VARIABLES;
use tactile_nets::contact_cnn::Prediction as CnnPrediction;
use tactile_nets::contact_mlp::Prediction as MlpPrediction;
use tactile_nets::force_dnn::LiveTare;

/// What the devices gave this cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frames {
    /// The fingertip's three pressures.
    pub tip: PressureFrame<3>,
    /// The ICM-20789 pad's frame.
    pub imu: ImuFrame,
    /// The underactuated hand's read and its decoded frame.
    pub hand: (Read, FingerFrame<4>),
}

/// What the estimators made of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimates {
    /// Arrival detection.
    pub contact: ContactEstimate,
    /// Tared rises for the force DNN, hPa.
    pub rise_hpa: [f32; 3],
    /// The grasp estimate (`None` while taring).
    pub grasp: Option<GraspEstimate>,
    /// The CNN's window (`None` until full).
    pub window: Option<CnnWindow>,
    /// The softness sample.
    pub sample: [f32; N_VARIABLES],
}

/// What the policies decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decisions {
    /// Eq. 3 and ranging, once a contact has arrived.
    pub aot: Option<(Contact, Contact)>,
    /// The contact MLP, once a contact has arrived.
    pub mlp: Option<MlpPrediction>,
    /// The force DNN's weight, gf.
    pub weight_gf: f32,
    /// The grasp command (`None` while taring).
    pub command: Option<GripperCommand>,
    /// The CNN's region.
    pub region: Option<CnnPrediction>,
    /// The softness class so far.
    pub softness: Softness,
}

/// What went out: the servo bytes (length) and the arm's target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Commands {
    /// Bytes of this cycle's sync writes.
    pub servo_bytes: usize,
    /// The arm's grid pose.
    pub pose: Option<Pose>,
}

/// The full-hand cycle.
pub struct FullHandCycle {
    tip: PressedFingertip,
    tare: LiveTare,
    contact: ContactCycle,
    weight: WeightCycle,
    grasp: GraspCycle,
    tap: TapCycle,
    softness: SoftnessCycle,
}

impl FullHandCycle {
    /// Every scene's parts, one shared fingertip.
    pub fn new() -> Result<Self, CycleError> {
        let cells = rect(2, 3, 2, 2)?;
        let presses = [0.5, 1.0, 2.0, 5.0]
            .map(|kgf| Press { cells, kgf })
            .to_vec();
        // At OSR 1024 (≈ 4.6 ms a frame): 280 ms holds, 320 ms releases, long enough for the
        // contact detector to see every sensor back at rest and re-arm.
        let schedule = PressSchedule {
            presses,
            rest_cycles: TARE_FRAMES,
            press_cycles: 60,
            release_cycles: 70,
        };
        Ok(FullHandCycle {
            tip: PressedFingertip::new(1024, 15, schedule)?,
            tare: LiveTare::new(WEIGHT_TARE_FRAMES as u32),
            contact: ContactCycle::new()?,
            weight: WeightCycle::new()?,
            grasp: GraspCycle::new()?,
            tap: TapCycle::new()?,
            softness: SoftnessCycle::new()?,
        })
    }

    /// Decode: every device once.
    pub fn decode(&mut self) -> Result<Frames, CycleError> {
        Ok(Frames {
            tip: self.tip.read()?,
            imu: self.tap.decode()?,
            hand: self.softness.decode(),
        })
    }

    /// Estimate: every estimator on its frame.
    pub fn estimate(&mut self, f: &Frames) -> Result<Estimates, CycleError> {
        Ok(Estimates {
            contact: self.contact.estimate(&f.tip),
            rise_hpa: self.tare.rise_hpa(&f.tip).unwrap_or([0.0; 3]),
            grasp: self.grasp.estimate(&f.tip)?,
            window: self.tap.estimate(f.imu)?,
            sample: SoftnessCycle::estimate(&f.hand.1),
        })
    }

    /// Policy: every model and controller on its estimate (`grasp` is the hand read's index).
    pub fn policy(&mut self, e: &Estimates, grasp: usize) -> Result<Decisions, CycleError> {
        let (mut aot, mut mlp) = (None, None);
        if let (Some(event), Some(reading)) = (e.contact.event, e.contact.reading) {
            aot = Some(self.contact.aot(&event)?);
            mlp = Some(self.contact.mlp(&reading)?);
        }
        Ok(Decisions {
            aot,
            mlp,
            weight_gf: self.weight.policy(&e.rise_hpa)?,
            command: e.grasp.map(|g| self.grasp.policy(&g)).transpose()?,
            region: e.window.map(|w| self.tap.policy(&w)).transpose()?,
            softness: self.softness.policy(grasp, &e.sample)?,
        })
    }

    /// Encode: the servo sync writes and the arm's grid pose.
    pub fn encode(&mut self, d: &Decisions) -> Result<Commands, CycleError> {
        let servo_bytes = match &d.command {
            Some(cmd) => self.grasp.encode(cmd)?.1.len(),
            None => 0,
        };
        let pose = d.region.map(|p| self.tap.encode(p.region)).transpose()?;
        Ok(Commands { servo_bytes, pose })
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<(Decisions, Commands), CycleError> {
        let frames = self.decode()?;
        let estimates = self.estimate(&frames)?;
        let decisions = self.policy(&estimates, frames.hand.0.grasp)?;
        let commands = self.encode(&decisions)?;
        Ok((decisions, commands))
    }
}
