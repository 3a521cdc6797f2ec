//! The grasp stack a paper scene names for one Table 5 object: the fingertip, the Dynamixel
//! hand, the clock the loop runs on and the loop's configuration — real (the scene's
//! `i2c_buses` and `serial_port`, opened through the run's platform, on its clock) or the
//! Table 5 world (`paper_experiments::grasp_rig`: the fingertip's chip models behind the real
//! driver, `ServoHand` speaking Protocol 2.0 to the servo-bus simulator whose MX-28 drives
//! hand-sim's grasp physics with the object between the fingers, in simulated time). The runner
//! gets the same kinds of handle either way; only [`Environment`] says what the world did,
//! where there is one to observe.

use super::fingertip::Fingertip;
use crate::Error;
use crate::error::device;
use crate::runs::RunContext;
use crate::scene::PaperScene;
use hand_control::ServoHand;
use hand_control::grasp_loop::{LoopClock, LoopConfig, TorqueBand};
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use handstack::RunError;
use paper_experiments::grasp_rig::{self, Shared};

/// A grasp stack, opened.
pub struct GraspStack {
    /// The fingertip the loop reads.
    pub tip: Fingertip,
    /// The hand the loop drives.
    pub hand: ServoHand,
    /// The loop's clock.
    pub clock: Box<dyn LoopClock>,
    /// The loop's configuration in the object's torque band.
    pub config: LoopConfig,
    /// The simulated world, when the stack is one.
    pub environment: Option<Environment>,
}

/// Opens the stack for `object` in `band`: the scene's real devices when its hand names a
/// `serial_port` (sensors first, so a bus that cannot be opened fails before any servo
/// command), else a fresh Table 5 world for `object` with the fingertip seeded `seed`.
pub fn open(
    scene: &PaperScene,
    cx: &RunContext<'_>,
    object: &str,
    band: TorqueBand,
    seed: u64,
) -> Result<GraspStack, Error> {
    let config = grasp_rig::config(band);
    let hand = scene.file.hand.as_ref().map(|h| h.get_ref());
    if let Some((hand, port)) = hand.and_then(|h| Some((h, h.serial_port.as_ref()?.get_ref()))) {
        let tip = handstack::stack::fingertip::open(&scene.scene, &*cx.platform)?;
        let hand = handstack::stack::hand::open(hand, port)?;
        return Ok(GraspStack {
            tip: Fingertip::new(tip),
            hand,
            clock: Box::new(cx.platform.clock()),
            config,
            environment: None,
        });
    }
    let kind = ObjectKind::from_name(object)
        .ok_or_else(|| device("grasp", format!("no simulated object {object}")))?;
    let params =
        ObjectParams::calibrated(kind, band.min_raw(), band.max_raw(), &RigParams::default())?;
    let (world, hand) =
        grasp_rig::world(params, seed).map_err(|e| device("grasp", format!("{object}: {e}")))?;
    Ok(GraspStack {
        tip: Fingertip::new(RigTip(grasp_rig::Source(world.clone()))),
        hand,
        clock: Box::new(grasp_rig::Clock(world.clone())),
        config,
        environment: Some(Environment(world)),
    })
}

/// The Table 5 world's fingertip, its errors as run errors.
struct RigTip(grasp_rig::Source);

impl hand_traits::TactileSource for RigTip {
    type Frame = hand_traits::PressureFrame<3>;
    type Error = RunError;
    fn read_frame(&mut self) -> Result<Self::Frame, RunError> {
        self.0.read_frame().map_err(|e| RunError::Device {
            device: "sensors.fingertip",
            reason: e.to_string(),
        })
    }
}

/// What the simulated world did during a hold (the ground truth no hardware stack has).
pub struct Environment(Shared);

/// The object's fate in one hold.
#[derive(Debug, Clone, Copy)]
pub struct Fate {
    /// The greatest pad force, N.
    pub peak_force_n: f64,
    /// Slipped, crushed or dropped.
    pub lost: bool,
}

impl Environment {
    /// Schedules a fault in the world (a silent servo, a tactile bus error, …): the fault
    /// campaigns of the tests and the soak.
    pub fn inject(&self, injection: grasp_rig::Injection) {
        self.0.borrow_mut().injections.push(injection);
    }

    /// The world's first failure during the hold (it stops the world where it happens), or
    /// the object's fate.
    pub fn fate(&self) -> Result<Fate, Error> {
        let mut w = self.0.borrow_mut();
        if let Some(e) = w.world_error.take() {
            return Err(device("grasp world", e.to_string()));
        }
        let s = w.state();
        Ok(Fate {
            peak_force_n: w.plant.body().peak_force_n(),
            lost: s.slip_m > hand_sim::grasp::rig::SLIP_TOLERANCE_M || s.damaged || s.dropped,
        })
    }
}
